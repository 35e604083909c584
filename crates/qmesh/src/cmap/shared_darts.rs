//! The map's per-dart tables seen as relaxed atomics, for passes that rewrite many darts
//! on all cores at once: each job of such a pass reads and writes only darts no other job
//! touches (the distinct edges of a batch of splits, the disjoint matches of a
//! replacement pass), so the result is the one of running the jobs one after another.
//!
//! Relaxed loads and stores compile to the plain moves the tables would get: the view
//! costs nothing, and a caller that broke the disjointness would get a wrong map, never
//! undefined behaviour.

use std::sync::atomic::{AtomicI32, AtomicU32, Ordering::Relaxed};

use super::dart::Dart;
use super::storage::CMap3;

/// Per-dart links, vertex ids, marks and labels of a map, writable from many threads.
pub(crate) struct SharedDarts<'a> {
    /// β0..β3 of dart `d` at `4 d .. 4 d + 4`.
    betas: &'a [AtomicU32],
    vertex: &'a [AtomicU32],
    /// Empty while the map has never used a mark.
    marks: &'a [AtomicU32],
    labels: Option<&'a [AtomicI32]>,
    uniform_label: i32,
}

/// `v` as atomics, for as long as it is borrowed.
#[allow(unsafe_code)]
fn atomic_u32(v: &mut [u32]) -> &[AtomicU32] {
    const { assert!(size_of::<AtomicU32>() == size_of::<u32>() && align_of::<AtomicU32>() == align_of::<u32>()) };
    // SAFETY: AtomicU32 has the size, alignment (checked above) and bit validity of u32,
    // and the exclusive borrow keeps every other access out while the view lives (what
    // the standard library's unstable `AtomicU32::from_mut_slice` does).
    unsafe { &*(std::ptr::from_mut(v) as *const [AtomicU32]) }
}

/// [`atomic_u32`] for i32.
#[allow(unsafe_code)]
fn atomic_i32(v: &mut [i32]) -> &[AtomicI32] {
    const { assert!(size_of::<AtomicI32>() == size_of::<i32>() && align_of::<AtomicI32>() == align_of::<i32>()) };
    // SAFETY: as in `atomic_u32`.
    unsafe { &*(std::ptr::from_mut(v) as *const [AtomicI32]) }
}

impl CMap3 {
    /// The per-dart tables as [`SharedDarts`], and the positions of `new_vertices` vertices
    /// added at the end (at the origin, to be written by the pass), with the positions of
    /// the vertices before them.
    pub(crate) fn shared_darts(&mut self, new_vertices: usize) -> (SharedDarts<'_>, &[[f64; 3]], &mut [[f64; 3]]) {
        let before = self.positions.len();
        self.positions.resize(before + new_vertices, [0.0; 3]);
        let (old, new) = self.positions.split_at_mut(before);
        let shared = SharedDarts {
            betas: atomic_u32(self.betas.as_flattened_mut()),
            vertex: atomic_u32(&mut self.vertex),
            marks: atomic_u32(&mut self.marks),
            labels: self.labels.as_deref_mut().map(atomic_i32),
            uniform_label: self.uniform_label.unwrap_or(0),
        };
        (shared, old, new)
    }
}

impl SharedDarts<'_> {
    /// Sets raw βi of raw dart `d` (one side of a link only).
    #[inline]
    pub fn set_beta(&self, d: u32, i: usize, to: u32) {
        self.betas[4 * d as usize + i].store(to, Relaxed);
    }

    #[inline]
    pub fn vertex_of(&self, d: Dart) -> u32 {
        self.vertex[d.idx()].load(Relaxed)
    }

    /// The volume label of `d` (as [`CMap3::label_of`]).
    #[inline]
    pub fn label_of(&self, d: Dart) -> i32 {
        self.labels.map_or(self.uniform_label, |l| l[d.idx()].load(Relaxed))
    }

    /// Writes a new dart (a slot of [`CMap3::reserve_darts`]): its links (raw), vertex id
    /// and label, and no mark.
    #[inline]
    pub fn store_dart(&self, d: Dart, betas: [u32; 4], vertex: u32, label: i32) {
        let k = d.idx();
        betas.iter().enumerate().for_each(|(i, &b)| self.betas[4 * k + i].store(b, Relaxed));
        self.vertex[k].store(vertex, Relaxed);
        if let Some(m) = self.marks.get(k) {
            m.store(0, Relaxed);
        }
        if let Some(l) = self.labels {
            l[k].store(label, Relaxed);
        }
    }
}
