//! Orbits: the one traversal every algorithm uses (2022 §2.2, 2025 §3.2).
//!
//! An orbit is the set of darts reachable from a dart through a set of generators.
//! Cells are orbits: vertex ⟨β1∘β2, β1∘β3⟩, edge ⟨β2, β3⟩, face ⟨β1, β3⟩, volume
//! ⟨β1, β2⟩, connected component ⟨β1, β2, β3⟩. Inverses are always followed, so orbits
//! are complete in open maps (free β3 on the boundary, free β2 on surface borders).

use rustc_hash::FxHashSet;

use super::bitset::BitSet;
use super::dart::Dart;
use super::storage::CMap3;

/// Which orbit to traverse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orbit {
    /// Darts whose origin is the same vertex: ⟨β1∘β2, β1∘β3⟩ and inverses.
    Vertex,
    /// Darts of one edge, both directions: ⟨β2, β3⟩.
    Edge,
    /// Darts of a face, both sides: ⟨β1, β3⟩.
    Face,
    /// Darts of one side of a face: ⟨β1⟩.
    HalfFace,
    /// Darts of a volume: ⟨β1, β2⟩.
    Volume,
    /// Darts of a connected component: ⟨β1, β2, β3⟩.
    Component,
    /// Darts of a vertex seen from inside one volume: ⟨β1∘β2⟩.
    VolumeVertex,
    /// Any set of betas: bit i set = βi is a generator (β1 implies β0).
    Betas(u8),
}

/// A set that remembers visited raw dart indices.
pub trait Visited {
    /// Inserts `i`; returns true when it was not there before.
    fn visit(&mut self, i: u32) -> bool;
}

impl Visited for BitSet {
    #[inline]
    fn visit(&mut self, i: u32) -> bool {
        self.insert(i as usize)
    }
}

impl Visited for FxHashSet<u32> {
    #[inline]
    fn visit(&mut self, i: u32) -> bool {
        self.insert(i)
    }
}

/// Calls `push` with every neighbour of `d` under the generators of `orbit`.
/// Higher betas are pushed first so that the depth-first walk (last in, first out)
/// finishes a face, then a volume, before crossing to the next one: the darts of a
/// cell are stored together, so this keeps the walk in cache.
#[inline]
fn neighbours(map: &CMap3, d: u32, orbit: Orbit, mut push: impl FnMut(u32)) {
    let b = |x: u32, i: usize| if x == 0 { 0 } else { map.beta_raw(x, i) };
    match orbit {
        Orbit::Vertex => {
            push(b(b(d, 0), 3));
            push(b(b(d, 3), 1));
            push(b(b(d, 0), 2));
            push(b(b(d, 2), 1));
        }
        Orbit::VolumeVertex => {
            push(b(b(d, 0), 2));
            push(b(b(d, 2), 1));
        }
        Orbit::Edge => {
            push(b(d, 3));
            push(b(d, 2));
        }
        Orbit::Face => {
            push(b(d, 3));
            push(b(d, 0));
            push(b(d, 1));
        }
        Orbit::HalfFace => {
            push(b(d, 0));
            push(b(d, 1));
        }
        Orbit::Volume => {
            push(b(d, 2));
            push(b(d, 0));
            push(b(d, 1));
        }
        Orbit::Component => {
            for i in (0..4).rev() {
                push(b(d, i));
            }
        }
        Orbit::Betas(mask) => {
            let mask = if mask & 0b11 != 0 { mask | 0b11 } else { mask };
            for i in (0..4).rev() {
                if mask & (1 << i) != 0 {
                    push(b(d, i));
                }
            }
        }
    }
}

/// The traversal: depth-first from `start`, calling `visit` once per dart of the orbit.
/// `seen` keeps the visited darts (callers decide when to clear it); `stack` is reused.
pub fn walk_orbit<V: Visited>(
    map: &CMap3,
    start: Dart,
    orbit: Orbit,
    seen: &mut V,
    stack: &mut Vec<u32>,
    mut visit: impl FnMut(Dart),
) {
    stack.clear();
    if !seen.visit(start.raw()) {
        return;
    }
    stack.push(start.raw());
    while let Some(d) = stack.pop() {
        visit(Dart::from_raw(d).expect("stack holds no ε"));
        neighbours(map, d, orbit, |n| {
            if n != 0 && seen.visit(n) {
                stack.push(n);
            }
        });
    }
}

/// Reusable traversal state for collecting single orbits without allocating per call.
#[derive(Clone, Debug, Default)]
pub struct OrbitWalker {
    seen: FxHashSet<u32>,
    stack: Vec<u32>,
    out: Vec<Dart>,
}

impl OrbitWalker {
    pub fn new() -> Self {
        Self::default()
    }

    /// The darts of the orbit of `start`, in traversal order (start first).
    pub fn collect(&mut self, map: &CMap3, start: Dart, orbit: Orbit) -> &[Dart] {
        self.seen.clear();
        self.out.clear();
        let out = &mut self.out;
        walk_orbit(map, start, orbit, &mut self.seen, &mut self.stack, |d| out.push(d));
        &self.out
    }

    /// Whether `d` was reached by the last [`collect`](Self::collect).
    pub fn contains(&self, d: Dart) -> bool {
        self.seen.contains(&d.raw())
    }
}

/// Scratch walker held by the map for local operations (`mem::take`n while in use).
pub(crate) type LocalScratch = OrbitWalker;

/// Iterator over one dart per cell of the given orbit kind (the first dart in index order).
#[derive(Debug)]
pub struct Cells<'a> {
    map: &'a CMap3,
    orbit: Orbit,
    seen: BitSet,
    stack: Vec<u32>,
    next: u32,
}

impl Iterator for Cells<'_> {
    type Item = Dart;

    fn next(&mut self) -> Option<Dart> {
        let n = self.map.dart_capacity() as u32;
        while self.next < n {
            let i = self.next;
            self.next += 1;
            let d = Dart::from_raw(i)?;
            if !self.map.is_live(d) || self.seen.get(i as usize) {
                continue;
            }
            walk_orbit(self.map, d, self.orbit, &mut self.seen, &mut self.stack, |_| {});
            return Some(d);
        }
        None
    }
}

impl CMap3 {
    /// One representative dart per cell of kind `orbit`, in increasing index order.
    ///
    /// ```
    /// use qmesh::cmap::{CMap3, Orbit};
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..8).map(|i| m.add_vertex([(i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64])).collect();
    /// m.make_hexahedron([v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]]);
    /// assert_eq!(m.cells(Orbit::Vertex).count(), 8);
    /// assert_eq!(m.cells(Orbit::Edge).count(), 12);
    /// assert_eq!(m.cells(Orbit::Face).count(), 6);
    /// assert!(m.is_valid().is_empty());
    /// ```
    pub fn cells(&self, orbit: Orbit) -> Cells<'_> {
        Cells { map: self, orbit, seen: BitSet::with_len(self.dart_capacity()), stack: Vec::new(), next: 1 }
    }

    /// Number of darts (edges) of the half-face of `d`.
    pub fn face_degree(&self, d: Dart) -> usize {
        let mut n = 1;
        let mut x = self.next(d);
        while x != d {
            n += 1;
            x = self.next(x);
        }
        n
    }

    /// The darts of the orbit of `d` (allocates; loops should reuse an [`OrbitWalker`]).
    pub fn orbit(&self, d: Dart, orbit: Orbit) -> Vec<Dart> {
        let mut w = OrbitWalker::new();
        w.collect(self, d, orbit).to_vec()
    }

    /// Runs `f` with the map's scratch walker (for `&mut self` operations).
    pub(crate) fn with_scratch<R>(&mut self, f: impl FnOnce(&mut Self, &mut OrbitWalker) -> R) -> R {
        let mut w = std::mem::take(&mut self.scratch);
        let r = f(self, &mut w);
        self.scratch = w;
        r
    }
}
