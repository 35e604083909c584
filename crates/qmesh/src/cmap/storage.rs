//! The dart store behind every algorithm: betas, origin vertices, marks, positions.
//!
//! All other modules read and write darts through the handful of functions here
//! (`beta`, `link`, `unlink`, `create_dart`, `delete_dart`, `vertex_of`, marks), so the
//! layout can change without touching the algorithms above it (GUIDE §2).

use super::bitset::BitSet;
use super::constructors::Layout;
use super::dart::Dart;
use super::error::MapError;
use super::orbit::LocalScratch;
use super::page_backing::{advise_huge_pages, extend_backed};
use rayon::prelude::*;

/// A 3D combinatorial map (2022 §2.2, 2025 §3.2) with one position per vertex.
///
/// Storage is struct-of-arrays: per dart `[β0, β1, β2, β3]` (16 B) and the origin vertex
/// id (4 B; `u32::MAX` marks a deleted slot), plus 32 mark bits (4 B) once a mark is first
/// used — 20 or 24 bytes per dart; positions live in their own table indexed by vertex
/// id. Raw index 0 is the null dart ε.
///
/// **Orientation convention.** In a volume (dimension 3), β1 turns *clockwise* around a
/// face seen from outside its volume, i.e. the right-hand normal of a β1 cycle points
/// into the volume (as in the papers, 2022 §2.2). Cell constructors take nodes in VTK
/// order and produce this orientation. In a surface map (dimension 2), β1 follows the
/// face cycles as given by the file.
#[derive(Clone, Debug)]
pub struct CMap3 {
    pub(super) betas: Vec<[u32; 4]>,
    /// Origin vertex id per dart; [`DEAD`] for ε and deleted slots.
    pub(super) vertex: Vec<u32>,
    /// Mark bits per dart, or empty while no mark was ever used (all bits clear): a
    /// map that is only read (`qmesh info`) never pays for them.
    pub(super) marks: Vec<u32>,
    pub(super) positions: Vec<[f64; 3]>,
    pub(super) free_darts: Vec<u32>,
    pub(super) used_marks: u32,
    pub(super) live: usize,
    pub(super) dimension: u8,
    pub(super) scratch: LocalScratch,
    /// Optional per-dart volume label (Medit reference, gmsh entity): only allocated
    /// when a mesh carries labels.
    pub(super) labels: Option<Vec<i32>>,
    /// The label of every volume when the input had one label for all (no per-dart
    /// table then).
    pub(super) uniform_label: Option<i32>,
}

/// Vertex id stored for ε and for deleted dart slots.
pub(crate) const DEAD: u32 = u32::MAX;

impl Default for CMap3 {
    fn default() -> Self {
        Self::new()
    }
}

impl CMap3 {
    /// An empty volume map (dimension 3).
    pub fn new() -> Self {
        Self::with_capacity(0, 0)
    }

    /// An empty volume map with room for `darts` darts and `vertices` vertices.
    pub fn with_capacity(darts: usize, vertices: usize) -> Self {
        let mut betas = Vec::with_capacity(darts + 1);
        advise_huge_pages(&betas);
        betas.push([0; 4]);
        let mut vertex = Vec::with_capacity(darts + 1);
        advise_huge_pages(&vertex);
        vertex.push(DEAD);
        CMap3 {
            betas,
            vertex,
            marks: Vec::new(),
            positions: Vec::with_capacity(vertices),
            free_darts: Vec::new(),
            used_marks: 0,
            live: 0,
            dimension: 3,
            scratch: LocalScratch::default(),
            labels: None,
            uniform_label: None,
        }
    }

    /// An empty volume map owning `positions` (vertex id i at `positions[i]`), with room
    /// for `darts` darts.
    pub fn with_positions(positions: Vec<[f64; 3]>, darts: usize) -> Self {
        let mut m = Self::with_capacity(darts, 0);
        m.positions = positions;
        m
    }

    /// 3 for a volume map (β3 may be free, β1 and β2 never), 2 for a surface map
    /// (β3 unused, β2 free on the boundary).
    pub fn dimension(&self) -> u8 {
        self.dimension
    }

    /// Declares the map a surface (2) or volume (3) map; `is_valid` checks accordingly.
    pub fn set_dimension(&mut self, dim: u8) {
        assert!(dim == 2 || dim == 3, "dimension must be 2 or 3");
        self.dimension = dim;
    }

    /// Number of live darts.
    pub fn nb_darts(&self) -> usize {
        self.live
    }

    /// One past the largest raw dart index (the size of per-dart side tables).
    pub fn dart_capacity(&self) -> usize {
        self.betas.len()
    }

    /// Makes room for `darts` more darts and `vertices` more vertices (an operation
    /// that knows how much it will add avoids growing the tables step by step).
    pub fn reserve(&mut self, darts: usize, vertices: usize) {
        self.betas.reserve(darts);
        self.vertex.reserve(darts);
        if !self.marks.is_empty() {
            self.marks.reserve(darts);
        }
        if let Some(l) = &mut self.labels {
            l.reserve(darts);
        }
        self.positions.reserve(vertices);
    }

    /// Number of vertex ids (positions), including ids no dart uses any more.
    pub fn nb_vertex_ids(&self) -> usize {
        self.positions.len()
    }

    /// Whether raw index `d` is a live dart of this map.
    #[inline]
    pub fn is_live(&self, d: Dart) -> bool {
        self.vertex.get(d.idx()).is_some_and(|&v| v != DEAD)
    }

    /// All live darts in increasing index order.
    pub fn darts(&self) -> impl Iterator<Item = Dart> + '_ {
        self.vertex
            .iter()
            .enumerate()
            .skip(1)
            .filter(|(_, v)| **v != DEAD)
            .filter_map(|(i, _)| Dart::from_raw(i as u32))
    }

    /// βi(d) for i in 0..=3; `None` when d is i-free.
    #[inline]
    pub fn beta(&self, d: Dart, i: usize) -> Option<Dart> {
        Dart::from_raw(self.betas[d.idx()][i])
    }

    /// Hints the processor to load dart `d`'s links and vertex id into cache (no effect
    /// on results; whole-map passes call it for darts they will reach soon).
    #[inline]
    #[allow(unsafe_code)]
    pub(crate) fn prefetch_dart(&self, d: u32) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            let i = (d as usize).min(self.betas.len().saturating_sub(1));
            // SAFETY: SSE is part of the x86_64 baseline, and a prefetch never reads or
            // faults (the addresses are in bounds anyway).
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(self.betas.as_ptr().wrapping_add(i).cast());
                _mm_prefetch::<_MM_HINT_T0>(self.vertex.as_ptr().wrapping_add(i).cast());
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = d;
    }

    /// Raw βi(d) (0 = ε), for hot loops.
    #[inline]
    pub fn beta_raw(&self, d: u32, i: usize) -> u32 {
        self.betas[d as usize][i]
    }

    /// All four links of raw dart `d` (0 = ε), for hot loops that read several.
    #[inline]
    pub fn betas_raw(&self, d: u32) -> [u32; 4] {
        self.betas[d as usize]
    }

    /// Whether d is i-free.
    #[inline]
    pub fn is_free(&self, d: Dart, i: usize) -> bool {
        self.betas[d.idx()][i] == 0
    }

    /// β1(d): the next dart around d's face.
    ///
    /// # Panics
    /// If d is 1-free, which only happens in the middle of a bulk rewiring with
    /// [`unlink`](Self::unlink).
    #[inline]
    pub fn next(&self, d: Dart) -> Dart {
        self.beta(d, 1).expect("β1 is free: the map is being rewired")
    }

    /// β0(d): the previous dart around d's face. # Panics as [`next`](Self::next).
    #[inline]
    pub fn prev(&self, d: Dart) -> Dart {
        self.beta(d, 0).expect("β0 is free: the map is being rewired")
    }

    /// Low-level link, no checks: for i = 1, β1(d1) = d2 and β0(d2) = d1; for i = 0 the
    /// converse; for i = 2, 3 both directions. Vertex ids and orbits are not updated;
    /// algorithms that rewire in bulk use this and restore validity themselves.
    #[inline]
    pub fn link(&mut self, d1: Dart, i: usize, d2: Dart) {
        match i {
            0 => {
                self.betas[d1.idx()][0] = d2.raw();
                self.betas[d2.idx()][1] = d1.raw();
            }
            1 => {
                self.betas[d1.idx()][1] = d2.raw();
                self.betas[d2.idx()][0] = d1.raw();
            }
            2 | 3 => {
                self.betas[d1.idx()][i] = d2.raw();
                self.betas[d2.idx()][i] = d1.raw();
            }
            _ => panic!("beta index {i} out of 0..=3"),
        }
    }

    /// Sets βi of raw dart `d` to raw dart `to` alone (no reverse link: for code that
    /// stores both directions itself).
    #[inline]
    pub(crate) fn set_beta_raw(&mut self, d: u32, i: usize, to: u32) {
        self.betas[d as usize][i] = to;
    }

    /// Takes `n` dart slots for [`SharedDarts::store_dart`](super::SharedDarts::store_dart), appended to `out`: the
    /// slots `n` calls of [`create_dart`](Self::create_dart) would take, in the same
    /// order (freed slots first, the last freed first). Every slot must be stored before
    /// the map is read again.
    pub(crate) fn reserve_darts(&mut self, n: usize, out: &mut Vec<Dart>) {
        self.live += n;
        let keep = self.free_darts.len() - n.min(self.free_darts.len());
        out.extend(self.free_darts[keep..].iter().rev().map(|&i| Dart::from_raw(i).expect("free list holds no ε")));
        let fresh = n - (self.free_darts.len() - keep);
        self.free_darts.truncate(keep);
        let first = self.betas.len();
        assert!(first + fresh < u32::MAX as usize, "too many darts for u32 indices");
        extend_backed(&mut self.betas, fresh, |_| [0; 4]);
        extend_backed(&mut self.vertex, fresh, |_| DEAD);
        if !self.marks.is_empty() {
            extend_backed(&mut self.marks, fresh, |_| 0);
        }
        if let Some(l) = &mut self.labels {
            extend_backed(l, fresh, |_| 0);
        }
        extend_backed(out, fresh, |k| Dart::from_raw((first + k) as u32).expect("index 0 is never reserved"));
    }

    /// Low-level unlink, no checks: frees βi(d) and the reverse pointer of its partner.
    #[inline]
    pub fn unlink(&mut self, d: Dart, i: usize) {
        let Some(o) = self.beta(d, i) else { return };
        self.betas[d.idx()][i] = 0;
        let back = match i {
            0 => 1,
            1 => 0,
            _ => i,
        };
        if self.betas[o.idx()][back] == d.raw() {
            self.betas[o.idx()][back] = 0;
        }
    }

    /// Adds a vertex at `p` and returns its id.
    pub fn add_vertex(&mut self, p: [f64; 3]) -> u32 {
        self.positions.push(p);
        (self.positions.len() - 1) as u32
    }

    /// Id of the vertex at the origin of d.
    #[inline]
    pub fn vertex_of(&self, d: Dart) -> u32 {
        self.vertex[d.idx()]
    }

    /// Sets the origin vertex id of one dart (low level: keep vertex orbits uniform).
    #[inline]
    pub fn set_vertex_of(&mut self, d: Dart, v: u32) {
        debug_assert!(v != DEAD && self.is_live(d), "vertex id of a deleted dart");
        self.vertex[d.idx()] = v;
    }

    /// Position of vertex id `v`.
    #[inline]
    pub fn position(&self, v: u32) -> [f64; 3] {
        self.positions[v as usize]
    }

    /// Moves vertex id `v`.
    pub fn set_position(&mut self, v: u32, p: [f64; 3]) {
        self.positions[v as usize] = p;
    }

    /// Position of the origin of d.
    #[inline]
    pub fn point(&self, d: Dart) -> [f64; 3] {
        self.positions[self.vertex[d.idx()] as usize]
    }

    /// All positions, indexed by vertex id.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// A new free dart (all betas ε, no marks) whose origin is vertex `v`; reuses
    /// deleted slots first.
    pub fn create_dart(&mut self, v: u32) -> Dart {
        self.live += 1;
        if let Some(i) = self.free_darts.pop() {
            let k = i as usize;
            self.betas[k] = [0; 4];
            self.vertex[k] = v;
            if let Some(m) = self.marks.get_mut(k) {
                *m = 0;
            }
            if let Some(l) = &mut self.labels {
                l[k] = 0;
            }
            return Dart::from_raw(i).expect("free list holds no ε");
        }
        let i = self.betas.len();
        assert!(i < u32::MAX as usize, "too many darts for u32 indices");
        self.betas.push([0; 4]);
        self.vertex.push(v);
        if !self.marks.is_empty() {
            self.marks.push(0);
        }
        if let Some(l) = &mut self.labels {
            l.push(0);
        }
        Dart::from_raw(i as u32).expect("index 0 is never pushed")
    }

    /// Appends the darts of one standard cell laid out as `layout` on `nodes`; returns
    /// the raw index of the first one. β3 is free. The block is assembled on the stack
    /// and copied in one go (this is the builder's inner loop).
    pub(super) fn append_cell(&mut self, layout: &Layout, nodes: &[u32]) -> u32 {
        let base = self.betas.len() as u32;
        let n = layout.origin.len();
        assert!((base as usize) + n < u32::MAX as usize, "too many darts for u32 indices");
        let (mut betas, mut vertex) = ([[0u32; 4]; 24], [0u32; 24]);
        for (k, (b, &o)) in layout.local_betas.iter().zip(&layout.origin).enumerate() {
            betas[k] = [base + b[0] as u32, base + b[1] as u32, base + b[2] as u32, 0];
            vertex[k] = nodes[o as usize];
        }
        self.betas.extend_from_slice(&betas[..n]);
        self.vertex.extend_from_slice(&vertex[..n]);
        if !self.marks.is_empty() {
            self.marks.resize(self.betas.len(), 0);
        }
        if let Some(l) = &mut self.labels {
            l.resize(l.len() + n, 0);
        }
        self.live += n;
        base
    }

    /// Deletes d (low level): its slot goes to the free list. Darts still pointing at
    /// it are the caller's responsibility (`is_valid` reports them).
    pub fn delete_dart(&mut self, d: Dart) {
        debug_assert!(self.is_live(d), "deleting {d:?} twice");
        self.betas[d.idx()] = [0; 4];
        self.vertex[d.idx()] = DEAD;
        if let Some(m) = self.marks.get_mut(d.idx()) {
            *m = 0;
        }
        self.free_darts.push(d.raw());
        self.live -= 1;
    }

    /// Deletes `darts`, whose indices are exactly the bits of `gone`, as
    /// [`delete_dart`](Self::delete_dart) of each in their order would (their slots go
    /// to the free list in that order); the slots are cleared on all cores, a stretch of
    /// the tables each.
    pub(crate) fn delete_darts(&mut self, darts: &[Dart], gone: &BitSet) {
        /// Darts per stretch: a whole number of the set's 64-bit words.
        const STRETCH: usize = 1 << 14;
        let set_bits = |k: usize| gone.ones_in(k * STRETCH, (k + 1) * STRETCH);
        self.betas.par_chunks_mut(STRETCH).zip(self.vertex.par_chunks_mut(STRETCH)).enumerate().for_each(
            |(k, (betas, vertex))| {
                for i in set_bits(k) {
                    betas[i] = [0; 4];
                    vertex[i] = DEAD;
                }
            },
        );
        if !self.marks.is_empty() {
            self.marks.par_chunks_mut(STRETCH).enumerate().for_each(|(k, marks)| {
                set_bits(k).for_each(|i| marks[i] = 0);
            });
        }
        self.free_darts.extend(darts.iter().map(|d| d.raw()));
        self.live -= darts.len();
    }

    /// Starts keeping a volume label per dart (the uniform label, or 0, initially).
    pub fn enable_labels(&mut self) {
        if self.labels.is_none() {
            self.labels = Some(vec![self.uniform_label.unwrap_or(0); self.betas.len()]);
        }
    }

    /// Gives every volume the same label without a per-dart table (a file whose cells
    /// all carry one reference keeps it, at no memory cost).
    pub fn set_uniform_label(&mut self, label: i32) {
        self.uniform_label = Some(label);
    }

    /// Whether volume labels are kept.
    pub fn has_labels(&self) -> bool {
        self.labels.is_some() || self.uniform_label.is_some()
    }

    /// Volume label of d's volume (0 when labels are not kept).
    #[inline]
    pub fn label_of(&self, d: Dart) -> i32 {
        self.labels.as_ref().map_or(self.uniform_label.unwrap_or(0), |l| l[d.idx()])
    }

    /// Sets the label of one dart (callers label whole volumes).
    #[inline]
    pub fn set_label_of(&mut self, d: Dart, label: i32) {
        if let Some(l) = &mut self.labels {
            l[d.idx()] = label;
        }
    }

    /// Heap bytes held by the map (darts, positions, free list).
    pub fn heap_bytes(&self) -> usize {
        self.betas.capacity() * 16
            + self.vertex.capacity() * 4
            + self.marks.capacity() * 4
            + self.positions.capacity() * 24
            + self.free_darts.capacity() * 4
            + self.labels.as_ref().map_or(0, |l| l.capacity() * 4)
    }

    /// Bytes per dart of the per-dart arrays at most (betas + vertex + marks).
    pub const BYTES_PER_DART: usize = 16 + 4 + 4;

    /// Bytes per dart of this map's per-dart arrays: 20, or 24 once marks are in use
    /// (labels, when kept, add 4 more).
    pub fn bytes_per_dart(&self) -> usize {
        16 + 4 + if self.marks.is_empty() { 0 } else { 4 } + if self.labels.is_some() { 4 } else { 0 }
    }

    pub(super) fn err_if_dead(&self, d: Dart) -> Result<(), MapError> {
        if self.is_live(d) { Ok(()) } else { Err(MapError::DeadDart(d)) }
    }
}
