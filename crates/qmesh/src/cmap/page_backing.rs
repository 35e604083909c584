//! How the kernel backs the map's large per-dart arrays with memory.
//!
//! A 3-map of a few million darts fills tens of megabytes in one go, and with 4 KiB
//! pages the kernel takes one fault (and one page clearing) per 4 KiB: about a tenth of
//! `qmesh info`'s time on the paper meshes. Linux systems commonly run transparent huge
//! pages in `madvise` mode, where a program has to ask for them; this asks for the
//! 2 MiB-aligned part of a large buffer. Pages are still only backed when first
//! written, so a buffer filled to its capacity costs no more memory.
//!
//! A map that grows step by step (a subdivision's levels) writes each step's new darts
//! into spare capacity, where huge pages cost more than they save (the kernel compacts
//! memory to find them). There, the pages about to be written are asked for in one call
//! per piece of 64 KiB, on all cores, which backs them in a fraction of the time one
//! fault per page takes.

use rayon::prelude::*;

/// Buffers smaller than this keep ordinary pages.
const MIN_BYTES: usize = 4 << 20;
const HUGE_PAGE: usize = 2 << 20;

/// Asks the kernel to back the spare and used capacity of `v` with huge pages (a hint:
/// nothing changes where the kernel declines or on other systems).
pub(super) fn advise_huge_pages<T>(v: &Vec<T>) {
    let bytes = v.capacity() * std::mem::size_of::<T>();
    if bytes < MIN_BYTES {
        return;
    }
    let first = v.as_ptr() as usize;
    let start = first.next_multiple_of(HUGE_PAGE);
    let end = (first + bytes) / HUGE_PAGE * HUGE_PAGE;
    if end > start {
        advise(start, end - start, Advice::HugePages);
    }
}

/// Ranges smaller than this are left to ordinary faults.
const MIN_POPULATE_BYTES: usize = 64 << 10;
const PAGE: usize = 4 << 10;
/// Bytes of one piece of [`extend_backed`]: small enough for the pieces of a table of
/// a megabyte to be shared out evenly between cores and to be written while the
/// kernel's clearing of their pages is still in cache, large enough for one call per
/// piece to cost little.
const PIECE: usize = 64 << 10;

/// Appends `item(k)` for k in `0..n` to `v`. When they fill many pages, it goes on all
/// cores a piece at a time: the kernel is first asked to back the piece's pages with
/// memory in one call (`MADV_POPULATE_WRITE`, a hint: contents never change, and
/// nothing happens where the kernel declines or on other systems), which takes a
/// fraction of the time of one fault per page as they are written; then the piece is
/// written.
pub(super) fn extend_backed<T: Send>(v: &mut Vec<T>, n: usize, item: impl Fn(usize) -> T + Sync) {
    let size = std::mem::size_of::<T>().max(1);
    if n * size < MIN_POPULATE_BYTES {
        v.extend((0..n).map(item));
        return;
    }
    v.reserve(n);
    let per_piece = PIECE / size;
    v.spare_capacity_mut()[..n].par_chunks_mut(per_piece).with_max_len(1).enumerate().for_each(|(k, piece)| {
        let first = piece.as_ptr() as usize;
        let (start, end) = (first.next_multiple_of(PAGE), (first + std::mem::size_of_val(piece)) / PAGE * PAGE);
        if end > start {
            advise(start, end - start, Advice::Populate);
        }
        for (j, x) in piece.iter_mut().enumerate() {
            x.write(item(k * per_piece + j));
        }
    });
    let len = v.len() + n;
    // SAFETY: the capacity holds `len` elements (reserved above) and the `n` after the
    // old length were all written by the pieces above.
    #[allow(unsafe_code)]
    unsafe {
        v.set_len(len);
    }
}

/// What the kernel is asked for a range of pages.
#[derive(Clone, Copy)]
enum Advice {
    HugePages,
    Populate,
}

#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn advise(start: usize, len: usize, advice: Advice) {
    let advice = match advice {
        Advice::HugePages => libc::MADV_HUGEPAGE,
        Advice::Populate => libc::MADV_POPULATE_WRITE,
    };
    // SAFETY: [start, start + len) lies inside one live allocation owned by the caller's
    // Vec; MADV_HUGEPAGE only changes how the kernel backs those pages and
    // MADV_POPULATE_WRITE backs them as a write fault would, never changing their
    // contents; a failure (EINVAL when THP is off or before Linux 5.14) is harmless.
    unsafe {
        libc::madvise(start as *mut libc::c_void, len, advice);
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_start: usize, _len: usize, _advice: Advice) {}

#[cfg(test)]
mod tests {
    use super::extend_backed;

    #[test]
    fn extend_backed_appends_the_items_in_order_after_what_was_there() {
        // Below and above the size that goes to the kernel and to all cores, into a
        // buffer with and without room already made.
        for (n, room) in [(0, 0), (10, 0), (100_000, 0), (100_000, 150_000), (70_001, 3)] {
            let mut v = Vec::with_capacity(room);
            v.extend([[1u32, 2, 3, 4]; 3]);
            extend_backed(&mut v, n, |k| [9, k as u32, 9, 0]);
            assert_eq!(v.len(), 3 + n);
            assert!(v[..3].iter().all(|&x| x == [1, 2, 3, 4]));
            assert!(v[3..].iter().enumerate().all(|(k, &x)| x == [9, k as u32, 9, 0]));
        }
    }
}
