//! Transparent huge pages for the map's large per-dart arrays.
//!
//! A 3-map of a few million darts fills tens of megabytes in one go, and with 4 KiB
//! pages the kernel takes one fault (and one page clearing) per 4 KiB: about a tenth of
//! `qmesh info`'s time on the paper meshes. Linux systems commonly run transparent huge
//! pages in `madvise` mode, where a program has to ask for them; this asks for the
//! 2 MiB-aligned part of a large buffer. Pages are still only backed when first
//! written, so a buffer filled to its capacity costs no more memory.

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
        madvise_huge(start, end - start);
    }
}

#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn madvise_huge(start: usize, len: usize) {
    // SAFETY: [start, start + len) lies inside one live allocation owned by the caller's
    // Vec; MADV_HUGEPAGE only changes how the kernel backs those pages, never their
    // contents, and a failure (EINVAL when THP is off) is harmless.
    unsafe {
        libc::madvise(start as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn madvise_huge(_start: usize, _len: usize) {}
