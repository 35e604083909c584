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
//! per range, which backs them in a fraction of the time one fault per page takes.

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

/// Asks the kernel to back the first `n` elements of the spare capacity of `v` (those
/// the next `n` pushes write) with memory now, in one call, instead of one page fault
/// per page as they are written (a hint: contents never change, and nothing happens
/// where the kernel declines or on other systems). The next pushes still have to write
/// the elements.
pub(super) fn populate_spare<T>(v: &Vec<T>, n: usize) {
    let size = std::mem::size_of::<T>();
    let bytes = n.min(v.capacity() - v.len()) * size;
    if bytes < MIN_POPULATE_BYTES {
        return;
    }
    let first = v.as_ptr() as usize + v.len() * size;
    let start = first.next_multiple_of(PAGE);
    let end = (first + bytes) / PAGE * PAGE;
    if end > start {
        advise(start, end - start, Advice::Populate);
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
