//! One refinement step of the query-replace subdivision (2022 Algorithm 5, §7.1): the
//! cells' whole edges are split in two, the darts at their corners flagged, then their
//! faces and volumes query-replaced. What each cell needs is read on all cores; the
//! edges are split on one thread in the cells' order, so the map is the same whatever
//! the number of threads. From the reads to the last replacement, the other cores test
//! the surface's contact with the children-to-be (their octree cells are known before
//! they exist).

use std::time::Instant;

use rayon::prelude::*;
use smallvec::SmallVec;

use super::box_cells::{along_box_edge, child_box, is_corner};
use super::contact::{FreshCell, NearLeaves, contacts};
use super::octree::{OctCell, RootBox};
use super::outside::untouched_regions;
use super::subdivide::SubdivideReport;
use crate::cmap::{BitSet, CMap3, Dart, MapError, Mark, Orbit, OrbitWalker};
use crate::geom::{Aabb, TriangleBvh};
use crate::pattern::PatternSet;
use crate::replace::replace_cells;
use crate::signature::Flags;

/// What refining a cell needs, read before its edges are split: its darts, its box,
/// its whole edges (both ends at corners of the box; split ones end at a midpoint), its
/// darts at a box corner along a box edge (the flags of the patterns, the same darts
/// once the edges are split) and one dart of each of its half-faces (the first in the
/// order of `darts`). Edges come with the dart after theirs: while it is still after
/// it, the edge is whole (splitting an edge gives each of its darts a new next).
/// Faces come with the smallest dart of their two sides, which names them.
struct Cell {
    darts: Vec<Dart>,
    bbox: Aabb,
    whole_edges: SmallVec<[(Dart, Dart); 12]>,
    corners: SmallVec<[Dart; 24]>,
    faces: SmallVec<[(Dart, Dart); 8]>,
}

/// Room made in the map per refined cell (see [`refine`]).
const DARTS_PER_CELL: usize = 200;
const VERTICES_PER_CELL: usize = 12;

/// What reading one cell uses, kept from cell to cell.
#[derive(Default)]
struct Scratch {
    walker: OrbitWalker,
    /// The darts of the cell being read that lie on a half-face already listed.
    on_listed_face: BitSet,
}

/// Where the children's contact with the surface is tested (see [`contacts`]).
#[derive(Clone, Copy)]
pub(super) struct ContactTest<'a> {
    pub root: RootBox,
    pub surface: &'a TriangleBvh,
    /// The leaves of the surface's hierarchy near the cells being refined.
    pub near: &'a NearLeaves,
    /// The level whose touched cells the next refinement splits (`None` after the last).
    pub next_parents: Option<u8>,
    /// When the children are the last of their level to be made and the next level
    /// drops the cells outside the surface: the level's earlier children, in order.
    /// The untouched regions of those and these children are then found beside the
    /// replacements (see [`outside_in_regions`](super::outside::outside_in_regions)).
    pub regions_after: Option<&'a [FreshCell]>,
}

/// What [`refine`] made.
pub(super) struct Refined {
    /// The children, in the order the replacements made them.
    pub children: Vec<FreshCell>,
    /// The leaves near the children the next refinement splits.
    pub near: NearLeaves,
    /// With [`ContactTest::regions_after`]: the untouched regions of those cells then
    /// `children`, in that order, named as
    /// [`outside_in_regions`](super::outside::outside_in_regions) takes them (`None` if a
    /// cell was left unreplaced, which leaves the regions to be found again).
    pub regions: Option<Vec<u32>>,
}

/// Refines the volumes of `cells` (one dart and the octree cell of each, all of one
/// level) into their children: splits their whole edges, flags their corner darts,
/// query-replaces their faces, then themselves; and tests the children's contact with
/// the surface.
pub(super) fn refine(
    map: &mut CMap3,
    set: &PatternSet,
    cells: &[(Dart, OctCell)],
    contact: &ContactTest,
    use_signatures: bool,
    r: &mut SubdivideReport,
) -> Result<Refined, MapError> {
    let t = Instant::now();
    // The tables grow once for the whole step, not table by table as the edge splits
    // and each batch of replacements outgrow them (on bunny and fertility they grew by
    // at most 182 darts and 10 vertices per refined cell; unused room is never touched).
    map.reserve(DARTS_PER_CELL * cells.len(), VERTICES_PER_CELL * cells.len());
    let flag = map.reserve_mark()?;
    let mut octants: Vec<OctCell> = Vec::with_capacity(8 * cells.len());
    octants.extend(cells.iter().flat_map(|&(_, c)| c.children()));
    let child_level = i32::from(octants.first().map_or(0, |c| c.level));
    // The children's contact needs their octree cells only: it is tested while the
    // cells are read, their edges split and their faces and volumes replaced, so that
    // the steps of these with little to share out (the edge splits, each batch's
    // bookkeeping, the few cells of the first levels) leave the other cores to it.
    let ((before, rep, split_at, replaced_at), (touches, near, regions)) = rayon::join(
        || {
            let before = on_cores(cells, |w, &(d, _)| read_cell(map, w, d));
            let faces = split_edges(map, &before, flag, child_level);
            let split_at = t.elapsed().as_secs_f64();
            // Each volume named by a flagged corner dart: in a cube's configuration every
            // one is a start of its signature, so the lookup's traversal is also the
            // replacement's.
            let volumes: Vec<Dart> = before.iter().map(|c| c.corners.first().copied().unwrap_or(c.darts[0])).collect();
            let rep = replace_cells(map, set, Flags::Mark(flag), &faces, &volumes, use_signatures);
            (before, rep, split_at, t.elapsed().as_secs_f64())
        },
        || {
            let (touches, near) = contacts(contact.root, contact.surface, &octants, contact.near, contact.next_parents);
            // The children in the order of their octants, which the replacements' order
            // (known later) permutes: the regions are the same, only their names differ.
            let regions = contact.regions_after.map(|earlier| {
                let cells: Vec<OctCell> = earlier.iter().map(|c| c.cell).chain(octants.iter().copied()).collect();
                let touched: Vec<bool> = earlier.iter().map(|c| c.touches).chain(touches.iter().copied()).collect();
                untouched_regions(&contact.root, &cells, &touched)
            });
            (touches, near, regions)
        },
    );
    map.free_mark(flag);
    r.faces_replaced += rep.faces_replaced;
    r.volumes_replaced += rep.volumes_replaced;
    r.phases.split_edges += split_at;
    r.phases.lookup += rep.query_seconds;
    r.phases.apply += replaced_at - split_at - rep.query_seconds;
    // The contact tests' time beyond the replacements.
    r.phases.contact += t.elapsed().as_secs_f64() - replaced_at;
    // Each child's octant of its parent's box names its octree cell and contact.
    let t = Instant::now();
    let from = &rep.created_from;
    let (children, octant_of): (Vec<FreshCell>, Vec<usize>) = rep
        .created_volumes
        .par_iter()
        .zip(from)
        .with_min_len(1 << 9)
        .map_init(OrbitWalker::new, |w, (&(dart, _), &i)| {
            let parent = &before[i as usize].bbox;
            let k = 8 * i as usize + octant(parent, &child_box(map, dart, parent, w));
            (FreshCell { dart, cell: octants[k], touches: touches[k] }, k)
        })
        .unzip();
    // The cells' reads go on another core when one is free (thousands of small lists).
    rayon::spawn(move || drop(before));
    let regions = regions.filter(|_| children.len() == octants.len()).map(|mut found| {
        let earlier = found.len() - octants.len();
        let of_children: Vec<u32> = octant_of.iter().map(|&k| found[earlier + k]).collect();
        found.truncate(earlier);
        found.extend(of_children);
        found
    });
    r.phases.contact += t.elapsed().as_secs_f64();
    Ok(Refined { children, near, regions })
}

/// Labels the darts of the cells `before` with the children's level (the darts the
/// edge splits and the replacements create copy it), marks their corner darts with
/// `flag`, splits their whole edges; returns one dart of each of their faces.
fn split_edges(map: &mut CMap3, before: &[Cell], flag: Mark, child_level: i32) -> Vec<Dart> {
    for c in before {
        c.darts.iter().for_each(|&x| map.set_label_of(x, child_level));
        c.corners.iter().for_each(|&x| map.mark(x, flag));
    }
    // Each face once, by its name, in the cells' order.
    let mut named = BitSet::with_len(map.dart_capacity());
    let faces: Vec<Dart> =
        before.iter().flat_map(|c| &c.faces).filter(|&&(_, face)| named.insert(face.idx())).map(|&(x, _)| x).collect();
    // Each edge once, in the cells' order: a cell's edge that an earlier cell split is
    // no longer whole.
    for &(x, after) in before.iter().flat_map(|c| &c.whole_edges) {
        if map.next(x) == after {
            map.insert_vertex_in_edge(x, midpoint(map.point(x), map.point(after)));
        }
    }
    faces
}

/// The octant of `parent` that `child` is, numbered as [`OctCell::children`] does (bit
/// k: the upper half along axis k).
fn octant(parent: &Aabb, child: &Aabb) -> usize {
    let (p, c) = (parent.centre(), child.centre());
    (0..3).filter(|&k| c[k] > p[k]).map(|k| 1 << k).sum()
}

fn read_cell(map: &CMap3, s: &mut Scratch, d: Dart) -> Cell {
    let darts = s.walker.collect(map, d, Orbit::Volume).to_vec();
    let points: SmallVec<[[f64; 3]; 64]> = darts.iter().map(|&x| map.point(x)).collect();
    let bbox = Aabb::of(points.iter().copied());
    let (mut whole_edges, mut corners) = (SmallVec::new(), SmallVec::new());
    for (&x, &p) in darts.iter().zip(&points).filter(|&(_, &p)| is_corner(&bbox, p)) {
        let after = map.next(x);
        let q = map.point(after);
        // Each whole edge has two darts in the cell (β2 of each other): the first met is
        // kept (splitting the edge from it splits the other's).
        if is_corner(&bbox, q) && map.beta(x, 2).is_none_or(|y| whole_edges.iter().all(|&(z, _)| z != y)) {
            whole_edges.push((x, after));
        }
        if along_box_edge(&bbox, p, q) {
            corners.push(x);
        }
    }
    // Each half-face once, from its first dart in the order of `darts`.
    let listed = &mut s.on_listed_face;
    listed.grow(map.dart_capacity());
    let mut faces = SmallVec::new();
    for &x in &darts {
        if !listed.get(x.idx()) {
            let mut name = x;
            for y in map.face_cycle(x) {
                listed.insert(y.idx());
                name = name.min(y).min(map.beta(y, 3).unwrap_or(y));
            }
            faces.push((x, name));
        }
    }
    darts.iter().for_each(|x| listed.remove(x.idx()));
    Cell { darts, bbox, whole_edges, corners, faces }
}

/// `f` of every cell, in order, on all cores (the cells of one of rayon's pieces share
/// a [`Scratch`]: a few per thread, as a scratch grows bit sets as large as the map).
fn on_cores<C: Sync, T: Send>(cells: &[C], f: impl Fn(&mut Scratch, &C) -> T + Sync) -> Vec<T> {
    cells.par_iter().with_min_len(64).map_init(Scratch::default, |s, c| f(s, c)).collect()
}

fn midpoint(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]))
}
