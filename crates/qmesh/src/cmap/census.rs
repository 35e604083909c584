//! The census: cell counts, components, validity and one dart per volume, in two
//! parallel passes that share nothing but read-only arrays.
//!
//! Pass A runs over a few ranges of darts: the local validity checks, half-faces (a
//! dart counts one when it is the smallest of its β1 cycle) and volumes. A volume is
//! walked from each dart of the range that could be its smallest and that this range's
//! walks have not reached yet; it is counted by the range holding its smallest dart.
//! A volume straddling ranges may be walked once per range, so the ranges are few.
//!
//! Pass B runs over vertex ids. Once the local checks pass, every vertex orbit carries
//! one id, so the orbit walked from any dart of id v holds all darts of id v exactly
//! when v names a single vertex. The same walk counts the edges at v: an edge is counted
//! at the endpoint holding its smallest dart. Components follow from the edges (every
//! β step moves along an edge or stays at a vertex).
//!
//! A map that fails the local checks or reuses a vertex id is counted by the sequential
//! reference walk instead ([`CMap3::census_reference`]), which is defined on any map.

use rayon::prelude::*;

use super::bitset::BitSet;
use super::counts::{CellCounts, Census};
use super::dart::Dart;
use super::orbit::{Orbit, walk_orbit};
use super::storage::{CMap3, DEAD};
use crate::disjoint_sets::DisjointSets;

/// Dart ranges of pass A per thread.
const RANGES_PER_THREAD: usize = 4;
/// Vertex ids per task of pass B.
const VERTEX_CHUNK: usize = 1 << 10;

/// What pass A finds in one range of darts.
#[derive(Default)]
struct DartTally {
    half_faces: usize,
    sewn_half_faces: usize,
    volume_reps: Vec<Dart>,
    boundary_reps: Vec<Dart>,
}

/// What pass B finds for a range of vertex ids.
#[derive(Default)]
struct VertexTally {
    vertices: usize,
    edges: usize,
    /// Both ends of every counted edge (by vertex id), for the components.
    links: Vec<(u32, u32)>,
    /// Some id is used by darts of more than one orbit.
    shared_id: bool,
}

/// Per-task traversal scratch.
struct Scratch {
    seen: BitSet,
    stack: Vec<u32>,
    darts: Vec<Dart>,
}

impl Scratch {
    fn new(map: &CMap3) -> Self {
        Scratch { seen: BitSet::with_len(map.dart_capacity()), stack: Vec::new(), darts: Vec::new() }
    }

    /// The darts of the orbit of `d` (left in `self.darts`), with `seen` left clear.
    fn collect(&mut self, map: &CMap3, d: Dart, orbit: Orbit) -> &[Dart] {
        self.darts.clear();
        let darts = &mut self.darts;
        walk_orbit(map, d, orbit, &mut self.seen, &mut self.stack, |x| darts.push(x));
        for x in &self.darts {
            self.seen.remove(x.idx());
        }
        &self.darts
    }
}

impl CMap3 {
    /// Counts, validity and one dart per volume (the smallest of each, in increasing
    /// order), computed in parallel. The violations are those of
    /// [`is_valid`](Self::is_valid); the counts equal [`count_cells`](Self::count_cells)'s.
    pub fn census(&self) -> Census {
        let ((violations, tally), (count, first)) = rayon::join(|| self.dart_pass(), || self.vertex_histogram());
        if !violations.is_empty() {
            return Census { violations, ..self.census_reference() };
        }
        let vertices = self.vertex_pass(&count, &first, true);
        if vertices.shared_id {
            return self.census_reference();
        }
        let counts = CellCounts {
            darts: self.nb_darts(),
            vertices: vertices.vertices,
            edges: vertices.edges,
            faces: tally.half_faces - tally.sewn_half_faces / 2,
            volumes: tally.volume_reps.len(),
            components: components(self.nb_vertex_ids(), &vertices.links),
            boundary_faces: tally.half_faces - tally.sewn_half_faces,
        };
        Census { counts, violations, volume_reps: tally.volume_reps, boundary_reps: tally.boundary_reps }
    }

    /// Whether some vertex id is used by more than one vertex orbit, checked in
    /// parallel (meaningful once the local checks pass, or on a freshly built map).
    pub fn has_shared_vertex_id(&self) -> bool {
        let (count, first) = self.vertex_histogram();
        self.vertex_pass(&count, &first, false).shared_id
    }

    /// Pass A over ranges of darts, merged in dart order.
    fn dart_pass(&self) -> (Vec<super::validity::Violation>, DartTally) {
        let n = self.dart_capacity();
        let size = n.div_ceil(rayon::current_num_threads() * RANGES_PER_THREAD).max(1 << 12);
        let chunks: Vec<_> = (0..n.div_ceil(size))
            .into_par_iter()
            .map(|k| {
                let range = k * size..((k + 1) * size).min(n);
                let violations = self.local_violations(range.clone());
                let tally = if violations.is_empty() { self.tally_darts(range) } else { Default::default() };
                (violations, tally)
            })
            .collect();
        let mut violations = Vec::new();
        let mut total = DartTally::default();
        for (v, t) in chunks {
            violations.extend(v);
            total.half_faces += t.half_faces;
            total.sewn_half_faces += t.sewn_half_faces;
            total.volume_reps.extend(t.volume_reps);
            total.boundary_reps.extend(t.boundary_reps);
        }
        (violations, total)
    }

    /// Half-faces, and the volumes whose smallest dart is in `range` (valid map).
    fn tally_darts(&self, range: std::ops::Range<usize>) -> DartTally {
        let mut t = DartTally::default();
        let (mut walked, mut stack) = (BitSet::with_len(self.dart_capacity()), Vec::new());
        for i in range.start.max(1)..range.end {
            let d = i as u32;
            if self.vertex[i] == DEAD || !self.smallest_of_half_face(d) {
                continue;
            }
            t.half_faces += 1;
            if self.beta_raw(d, 3) != 0 {
                t.sewn_half_faces += 1;
            } else {
                t.boundary_reps.push(Dart::from_raw(d).expect("i ≥ 1"));
            }
            if !walked.get(i) && self.may_be_smallest_of_volume(d) {
                let start = Dart::from_raw(d).expect("i ≥ 1");
                let mut smallest = d;
                walk_orbit(self, start, Orbit::Volume, &mut walked, &mut stack, |x| smallest = smallest.min(x.raw()));
                if range.contains(&(smallest as usize)) {
                    t.volume_reps.push(Dart::from_raw(smallest).expect("a dart"));
                }
            }
        }
        t
    }

    /// Whether `d` is the smallest dart of its β1 cycle (valid map: the cycle closes).
    #[inline]
    fn smallest_of_half_face(&self, d: u32) -> bool {
        let mut x = self.beta_raw(d, 1);
        while x != d {
            if x < d {
                return false;
            }
            x = self.beta_raw(x, 1);
        }
        true
    }

    /// A cheap necessary condition for `d` (smallest of its half-face) to be the
    /// smallest dart of its volume: no dart 2-sewn to its face is smaller.
    #[inline]
    fn may_be_smallest_of_volume(&self, d: u32) -> bool {
        let mut x = d;
        loop {
            let o = self.beta_raw(x, 2);
            if o != 0 && o < d {
                return false;
            }
            x = self.beta_raw(x, 1);
            if x == d {
                return true;
            }
        }
    }

    /// How many darts use each vertex id, and one of them (0: none).
    fn vertex_histogram(&self) -> (Vec<u32>, Vec<u32>) {
        let mut count = vec![0u32; self.nb_vertex_ids()];
        let mut first = vec![0u32; self.nb_vertex_ids()];
        for (i, &v) in self.vertex.iter().enumerate().skip(1) {
            if let Some(c) = count.get_mut(v as usize) {
                *c += 1;
                if *c == 1 {
                    first[v as usize] = i as u32;
                }
            }
        }
        (count, first)
    }

    /// Pass B over vertex ids (valid map: the local checks passed); edges are counted
    /// when `edges` is set.
    fn vertex_pass(&self, count: &[u32], first: &[u32], edges: bool) -> VertexTally {
        let ids = count.len();
        let chunk = |scratch: &mut Scratch, k: usize| {
            let mut t = VertexTally::default();
            for v in k * VERTEX_CHUNK..((k + 1) * VERTEX_CHUNK).min(ids) {
                let Some(start) = Dart::from_raw(first[v]) else { continue };
                let orbit = scratch.collect(self, start, Orbit::Vertex);
                if orbit.len() != count[v] as usize {
                    t.shared_id = true;
                    return t;
                }
                t.vertices += 1;
                for &x in orbit.iter().filter(|_| edges) {
                    if let Some(other) = self.edge_counted_at(x.raw()) {
                        t.edges += 1;
                        t.links.push((v as u32, other));
                    }
                }
            }
            t
        };
        let tallies: Vec<VertexTally> = if ids <= VERTEX_CHUNK {
            // One chunk (small maps, e.g. patterns): no hand-over to the thread pool.
            vec![chunk(&mut Scratch::new(self), 0)]
        } else {
            (0..ids.div_ceil(VERTEX_CHUNK)).into_par_iter().map_init(|| Scratch::new(self), chunk).collect()
        };
        let mut total = VertexTally::default();
        for t in tallies {
            total.vertices += t.vertices;
            total.edges += t.edges;
            total.shared_id |= t.shared_id;
            total.links.extend(t.links);
        }
        total
    }

    /// When `x` is the smallest dart of its edge, the vertex id at the edge's other end.
    ///
    /// The darts of an edge leaving x's vertex form the chain of σ = β3∘β2 through x;
    /// their β2 images are the darts leaving the other end. The chain is a cycle, or a
    /// path between two 3-free darts, walked forward and then backward from x.
    fn edge_counted_at(&self, x: u32) -> Option<u32> {
        let below = |y: u32| y != 0 && y < x;
        let mut y = x;
        let closed = loop {
            let across = self.beta_raw(y, 2);
            if below(across) {
                return None;
            }
            let next = if across == 0 { 0 } else { self.beta_raw(across, 3) };
            if next == x {
                break true;
            }
            if next == 0 {
                break false;
            }
            if next < x {
                return None;
            }
            y = next;
        };
        if !closed {
            let mut z = x;
            loop {
                let across = self.beta_raw(z, 3);
                if across == 0 {
                    break;
                }
                let prev = self.beta_raw(across, 2);
                if below(across) || below(prev) {
                    return None;
                }
                if prev == 0 {
                    break;
                }
                z = prev;
            }
        }
        Some(self.vertex[self.beta_raw(x, 1) as usize])
    }
}

/// Connected components of the graph on vertex ids with the given links (ids that no
/// link and no dart touch are not counted: callers pass every vertex through a link or
/// count isolated ones themselves).
fn components(ids: usize, links: &[(u32, u32)]) -> usize {
    let mut sets = DisjointSets::new(ids);
    let mut used = vec![false; ids];
    for &(a, b) in links {
        used[a as usize] = true;
        used[b as usize] = true;
        sets.union(a, b);
    }
    (0..ids as u32).filter(|&v| used[v as usize] && sets.find(v) == v).count()
}
