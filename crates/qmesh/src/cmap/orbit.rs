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
    /// Whether `i` is there.
    fn has(&self, i: u32) -> bool;
}

impl Visited for BitSet {
    #[inline]
    fn visit(&mut self, i: u32) -> bool {
        self.insert(i as usize)
    }

    #[inline]
    fn has(&self, i: u32) -> bool {
        self.get(i as usize)
    }
}

impl Visited for FxHashSet<u32> {
    #[inline]
    fn has(&self, i: u32) -> bool {
        self.contains(&i)
    }

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
    // ε (index 0) has all betas ε, so compositions through it need no test.
    let b = |x: u32, i: usize| map.beta_raw(x, i);
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

/// The permutation whose cycles an orbit is made of, when it has one: β1 for orbits
/// with β1 among their generators, β1∘β2 for the vertex orbits. The traversal walks
/// such a cycle in one go and only stacks the darts the other generators lead to.
#[derive(Clone, Copy)]
enum Cycle {
    Beta1,
    Beta1Beta2,
}

impl Cycle {
    fn of(orbit: Orbit) -> Option<Cycle> {
        match orbit {
            Orbit::Face | Orbit::HalfFace | Orbit::Volume | Orbit::Component => Some(Cycle::Beta1),
            Orbit::Betas(mask) if mask & 0b11 != 0 => Some(Cycle::Beta1),
            Orbit::Vertex | Orbit::VolumeVertex => Some(Cycle::Beta1Beta2),
            Orbit::Edge | Orbit::Betas(_) => None,
        }
    }

    #[inline]
    fn forward(self, map: &CMap3, d: u32) -> u32 {
        match self {
            Cycle::Beta1 => map.beta_raw(d, 1),
            Cycle::Beta1Beta2 => map.beta_raw(map.beta_raw(d, 2), 1),
        }
    }

    #[inline]
    fn backward(self, map: &CMap3, d: u32) -> u32 {
        match self {
            Cycle::Beta1 => map.beta_raw(d, 0),
            Cycle::Beta1Beta2 => map.beta_raw(map.beta_raw(d, 0), 2),
        }
    }
}

/// Calls `push` with the neighbours of `d` under the generators of `orbit` other than
/// its cycle permutation (and that permutation's inverse).
#[inline]
fn other_neighbours(map: &CMap3, d: u32, orbit: Orbit, mut push: impl FnMut(u32)) {
    let b = |x: u32, i: usize| map.beta_raw(x, i);
    match orbit {
        Orbit::Vertex => {
            push(b(b(d, 3), 1));
            push(b(b(d, 0), 3));
        }
        Orbit::Face => push(b(d, 3)),
        Orbit::Volume => push(b(d, 2)),
        Orbit::Component => {
            push(b(d, 3));
            push(b(d, 2));
        }
        Orbit::Betas(mask) => {
            for i in [3, 2] {
                if mask & (1 << i) != 0 {
                    push(b(d, i));
                }
            }
        }
        Orbit::HalfFace | Orbit::VolumeVertex | Orbit::Edge => {}
    }
}

/// Stacks `n` unless it is ε or already seen (marking it seen).
#[inline]
fn push_unseen<V: Visited>(seen: &mut V, stack: &mut Vec<u32>, n: u32) {
    if n != 0 && seen.visit(n) {
        stack.push(n);
    }
}

/// The traversal: from `start`, calling `visit` once per dart of the orbit. `seen`
/// keeps the visited darts (callers decide when to clear it); `stack` is reused.
///
/// Cycles of the orbit's permutation (β1, or β1∘β2 around a vertex) are walked both
/// ways from each dart that enters them until a visited dart or ε; the other
/// generators' neighbours are stacked. Each dart is visited once and `start` first.
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
    let Some(cycle) = Cycle::of(orbit) else {
        stack.push(start.raw());
        while let Some(d) = stack.pop() {
            visit(Dart::from_raw(d).expect("stack holds no ε"));
            neighbours(map, d, orbit, |n| push_unseen(seen, stack, n));
        }
        return;
    };
    // Entries are marked when popped, not when stacked: the other generators often map
    // a whole cycle onto another (β3 between the two sides of a face), and marking
    // them all on the way in would cut that cycle into one-dart walks.
    let mut entry = start.raw();
    loop {
        let mut x = entry;
        loop {
            visit(Dart::from_raw(x).expect("walks hold no ε"));
            other_neighbours(map, x, orbit, |n| stack_if_new(seen, stack, n));
            x = cycle.forward(map, x);
            if x == 0 || !seen.visit(x) {
                break;
            }
        }
        let mut y = cycle.backward(map, entry);
        while y != 0 && seen.visit(y) {
            visit(Dart::from_raw(y).expect("walks hold no ε"));
            other_neighbours(map, y, orbit, |n| stack_if_new(seen, stack, n));
            y = cycle.backward(map, y);
        }
        entry = loop {
            match stack.pop() {
                Some(e) if seen.visit(e) => break e,
                Some(_) => {}
                None => return,
            }
        };
    }
}

/// Stacks `n` unless it is ε or already seen (without marking it).
#[inline]
fn stack_if_new<V: Visited>(seen: &V, stack: &mut Vec<u32>, n: u32) {
    if n != 0 && !seen.has(n) {
        stack.push(n);
    }
}

/// Reusable traversal state for collecting single orbits without allocating per call.
/// The first walks record visited darts in a hash set; a walker used more than
/// `HASHED_WALKS` (32) times switches to a bit set as large as the map, cleared dart by
/// dart before each walk (the hash set costs ~10 % of a subdivision; the bit set would
/// cost a map-sized allocation to a walker made for one orbit).
#[derive(Clone, Debug, Default)]
pub struct OrbitWalker {
    hashed: FxHashSet<u32>,
    bits: BitSet,
    walks: u32,
    stack: Vec<u32>,
    out: Vec<Dart>,
}

/// Walks an [`OrbitWalker`] makes with its hash set before it takes a bit set.
const HASHED_WALKS: u32 = 32;

impl OrbitWalker {
    pub fn new() -> Self {
        Self::default()
    }

    /// The darts of the orbit of `start`, in traversal order (start first).
    pub fn collect(&mut self, map: &CMap3, start: Dart, orbit: Orbit) -> &[Dart] {
        if self.walks < HASHED_WALKS {
            self.walks += 1;
            self.hashed.clear();
            self.out.clear();
            let out = &mut self.out;
            walk_orbit(map, start, orbit, &mut self.hashed, &mut self.stack, |d| out.push(d));
        } else {
            if self.walks == HASHED_WALKS {
                self.walks += 1;
                self.out.clear();
            }
            for d in &self.out {
                self.bits.remove(d.raw() as usize);
            }
            self.out.clear();
            self.bits.grow(map.dart_capacity());
            let out = &mut self.out;
            walk_orbit(map, start, orbit, &mut self.bits, &mut self.stack, |d| out.push(d));
        }
        &self.out
    }

    /// Whether `d` was reached by the last [`collect`](Self::collect).
    pub fn contains(&self, d: Dart) -> bool {
        if self.walks <= HASHED_WALKS { self.hashed.contains(&d.raw()) } else { self.bits.get(d.raw() as usize) }
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
        self.face_cycle(d).count()
    }

    /// The darts of the half-face of `d` in β1 order, `d` first (its β1 cycle, without
    /// a visited set).
    pub fn face_cycle(&self, d: Dart) -> impl Iterator<Item = Dart> + '_ {
        std::iter::successors(Some(d), move |&x| Some(self.next(x)).filter(|&n| n != d))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{BuildOptions, build_surface_map, build_volume_map};
    use crate::generate::{hex_grid, tet_grid, torus_surface};

    /// The orbit by its definition: every generator and its inverse, one dart at a time.
    fn by_definition(map: &CMap3, d: Dart, orbit: Orbit) -> Vec<u32> {
        let mut seen = FxHashSet::default();
        let mut stack = vec![d.raw()];
        seen.insert(d.raw());
        while let Some(x) = stack.pop() {
            neighbours(map, x, orbit, |n| {
                if n != 0 && seen.insert(n) {
                    stack.push(n);
                }
            });
        }
        let mut v: Vec<u32> = seen.into_iter().collect();
        v.sort_unstable();
        v
    }

    fn check_every_orbit(map: &CMap3) {
        let kinds = [
            Orbit::Vertex,
            Orbit::Edge,
            Orbit::Face,
            Orbit::HalfFace,
            Orbit::Volume,
            Orbit::Component,
            Orbit::VolumeVertex,
            Orbit::Betas(0b1010),
            Orbit::Betas(0b0110),
        ];
        let mut walker = OrbitWalker::new();
        for d in map.darts() {
            for orbit in kinds {
                let walked = walker.collect(map, d, orbit);
                assert_eq!(walked[0], d, "the start comes first");
                let mut w: Vec<u32> = walked.iter().map(|x| x.raw()).collect();
                w.sort_unstable();
                let n = w.len();
                w.dedup();
                assert_eq!(w.len(), n, "{orbit:?} from {d:?} visits a dart twice");
                assert_eq!(w, by_definition(map, d, orbit), "{orbit:?} from {d:?}");
            }
        }
    }

    #[test]
    fn cycle_walks_equal_the_orbits_by_definition_on_closed_open_and_rewired_maps() {
        let opts = BuildOptions::default();
        let (mut hexes, _) = build_volume_map(&hex_grid(3, 2, 1), &opts).unwrap();
        check_every_orbit(&hexes);
        // Open boundary where a volume was removed, split edges.
        let first = hexes.darts().next().unwrap();
        hexes.remove_volume(first).unwrap();
        let some = hexes.darts().nth(40).unwrap();
        hexes.split_edge(some, 3).unwrap();
        check_every_orbit(&hexes);
        // A face cut open in the middle of a rewiring (β1 free at one dart).
        let d = hexes.darts().nth(7).unwrap();
        hexes.unlink(d, 1);
        check_every_orbit(&hexes);
        let (tets, _) = build_volume_map(&tet_grid(2, 1, 1), &opts).unwrap();
        check_every_orbit(&tets);
        // A surface with a border: β2 free.
        let torus = torus_surface(2.0, 0.5, 6, 4);
        let mut open = crate::build::IndexedMesh::new();
        open.points = torus.points.clone();
        for p in 0..20 {
            open.push_polygon(&torus.poly_conn[torus.poly_offsets[p]..torus.poly_offsets[p + 1]]);
        }
        let (surface, _) = build_surface_map(&open).unwrap();
        check_every_orbit(&surface);
    }
}
