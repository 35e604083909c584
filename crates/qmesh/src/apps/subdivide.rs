//! Octree hexahedral subdivision of a surface (2022 Algorithm 5, §7.1): one cube around
//! the surface; at each level the hexahedra the surface touches, then those breaking
//! 2:1 balance, get their edges split in two, their faces replaced by the 2×2 f-pattern
//! and their volume by the 2×2×2 v-pattern. `direct` does the same with plain boxes.

use std::time::Instant;

use super::box_cells::volume_box;
use super::contact::{FreshCell, NearLeaves, fresh_cells};
use super::generated_patterns::{GeneratedKind, given_or_generated};
use super::octree::{OctCell, Octree, RootBox, coarser_neighbours};
use super::outside::{outside_among, outside_in_regions};
use super::refine::{ContactTest, refine};
use crate::build::{BuildOptions, IndexedMesh, build_map};
use crate::cmap::{CMap3, Dart, MapError, Orbit, OrbitWalker};
use crate::geom::{Aabb, TriangleBvh};
use crate::pattern::PatternSet;
use rustc_hash::{FxHashMap, FxHashSet};

/// The level-0 cells of [`subdivide`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RootShape {
    /// One cube centred on the surface's bounding box (qmesh's default; see `margin`).
    #[default]
    Cube,
    /// The authors' program's set-up (2022 §7.1, `hexa-subdivision -init X`): the
    /// bounding box itself in `init` cells along its longest axis (see
    /// [`RootBox::bounding_grid`]); the level-0 cells the surface neither meets nor
    /// holds are left out from the start, as that program does.
    BoundingBox { init: u32 },
}

/// Options of [`subdivide`]. With `remove_outside`, each level first drops the cells
/// outside the surface that it does not touch, so they are neither refined nor split
/// for balance (the authors' program does the same: with [`RootShape::BoundingBox`]
/// the cell and replacement counts are its own).
#[derive(Clone, Copy, Debug)]
pub struct SubdivideOptions {
    /// Maximal level l_max (the root cells are level 0).
    pub levels: u8,
    /// The level-0 cells.
    pub root: RootShape,
    /// Growth of the root cube beyond the surface's longest extent (0.01 = 1 %).
    pub margin: f64,
    /// Refine with plain boxes instead of query-replace (the paper's time-direct).
    pub direct: bool,
    /// Drop the hexahedra outside the surface that it does not touch (the authors' set-up).
    pub remove_outside: bool,
    /// Look patterns up by signature (otherwise by direct isomorphism tests).
    pub use_signatures: bool,
}

impl Default for SubdivideOptions {
    fn default() -> Self {
        SubdivideOptions {
            levels: 4,
            root: RootShape::Cube,
            margin: 0.01,
            direct: false,
            remove_outside: false,
            use_signatures: true,
        }
    }
}

/// What [`subdivide`] did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct SubdivideReport {
    pub volumes: usize,
    /// Cells per level, index = level.
    pub per_level: Vec<usize>,
    /// Face and volume query-replaces (the paper's #fqr and #vqr; 0 with `direct`).
    pub faces_replaced: usize,
    pub volumes_replaced: usize,
    /// Cells split to restore 2:1 balance.
    pub balance_splits: usize,
    /// Cells dropped as outside the surface (each level drops its own before refining).
    pub removed_outside: usize,
    /// Volumes with hanging vertices (more than 8 vertices: a finer neighbour split a
    /// face or an edge; the authors' "generic" cells), counted on the octree.
    pub with_hanging_vertices: usize,
    /// Where the query-replace subdivision spent its time (all zero with `direct`).
    pub phases: SubdividePhases,
    pub seconds: f64,
}

/// Seconds per phase of the query-replace subdivision, summed over the levels.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct SubdividePhases {
    /// Building the level-0 map.
    pub start: f64,
    /// The level-0 cells' contact with the surface, which octant of its parent each new
    /// cell is, and the children's contact tests beyond the time of the edge splits and
    /// replacements they run beside (all of it on one thread).
    pub contact: f64,
    /// Finding the cells outside the surface and removing them (the last level's are
    /// removed during `finish`; the face-connected regions of a level's untouched
    /// cells are found beside the replacements that made them, in `contact` if longer).
    pub remove_outside: f64,
    /// Registering a level's cells as leaves and finding the 2:1 balance closure, beyond
    /// the time of the removal they run beside.
    pub balance: f64,
    /// Splitting the cells' edges, flagging their corners, listing their faces, while
    /// the other cores test the surface's contact with the children-to-be (as they do
    /// during `lookup` and `apply`).
    pub split_edges: f64,
    /// Looking the faces' and volumes' patterns up (on all cores).
    pub lookup: f64,
    /// Applying the replacements and relabelling the children.
    pub apply: f64,
    /// The final leaves, their mesh and the count of cells with hanging vertices, made
    /// while the last level's outside cells leave the map.
    pub finish: f64,
}

/// The subdivision: the hexahedra (VTK order, with a `level` array) and, unless
/// `direct`, the 3-map the query-replaces produced.
#[derive(Debug)]
pub struct Subdivision {
    pub mesh: IndexedMesh,
    pub map: Option<CMap3>,
    /// One dart of each volume of `map`, in increasing order (empty without a map).
    pub volumes: Vec<Dart>,
    pub report: SubdivideReport,
}

/// Subdivides around `surface` with `patterns` (default: the generated
/// `hex-subdivision` set); `progress(level)` is called as each level starts.
///
/// # Errors
/// Only if the map runs out of marks (it cannot: the pipeline uses two).
pub fn subdivide(
    surface: &TriangleBvh,
    opts: &SubdivideOptions,
    patterns: Option<&PatternSet>,
    progress: &(dyn Fn(u8) + Sync),
) -> Result<Subdivision, MapError> {
    // Run on a worker of rayon's pool: each level's dozens of parallel steps (a fraction
    // of a millisecond each at the first levels) are then handed to the other workers
    // directly, instead of each putting the calling thread to sleep until a worker has
    // run it (fertility at level 6, 16 alternating runs: 0.058 -> 0.051 s on 1 thread,
    // 0.037 -> 0.035 s on 2); and the other workers stay awake between the steps
    // (2 threads, alternating runs: fertility L6 0.0331 -> 0.0322 s, armadillo L6
    // 0.0410 -> 0.0402 s, bunny L6 0.0537 -> 0.0521 s, fertility L7 0.150 -> 0.146 s).
    crate::awake_pool::with_workers_awake(|| subdivide_on_pool(surface, opts, patterns, progress))
}

fn subdivide_on_pool(
    surface: &TriangleBvh,
    opts: &SubdivideOptions,
    patterns: Option<&PatternSet>,
    progress: &(dyn Fn(u8) + Sync),
) -> Result<Subdivision, MapError> {
    let t = Instant::now();
    let start = initial_tree(surface, opts.root, opts.margin);
    let root = start.root;
    let (tree, mesh, map, volumes, mut report) = if opts.direct {
        let (mut tree, mut r) = subdivide_direct(start, surface, opts.levels, opts.remove_outside, progress);
        if opts.remove_outside {
            r.removed_outside += prune_outside(&mut tree, surface);
        }
        r.with_hanging_vertices = tree.with_hanging_vertices();
        let mesh = tree.to_mesh();
        (tree, mesh, None, Vec::new(), r)
    } else {
        let QrSubdivision { mut map, report: mut r, leaves, last_level, last_outside } =
            subdivide_qr(start, surface, opts, patterns, progress)?;
        // The octree's mesh needs the leaves only: it is made while the last level's
        // outside cells leave the map.
        let t = Instant::now();
        let (removed, (mesh, hanging, volumes, tree)) = rayon::join(
            || map.remove_volumes(&last_outside),
            || {
                let mut volumes: Vec<Dart> =
                    leaves.values().chain(last_level.iter().map(|c| &c.dart)).copied().collect();
                volumes.sort_unstable();
                let tree =
                    Octree { root, leaves: leaves.into_keys().chain(last_level.iter().map(|c| c.cell)).collect() };
                let (mesh, hanging) = rayon::join(|| tree.to_mesh(), || tree.with_hanging_vertices());
                (mesh, hanging, volumes, tree)
            },
        );
        removed?;
        r.with_hanging_vertices = hanging;
        r.phases.finish = t.elapsed().as_secs_f64();
        (tree, mesh, Some(map), volumes, r)
    };
    report.volumes = tree.leaves.len();
    report.per_level = vec![0; usize::from(opts.levels) + 1];
    tree.leaves.iter().for_each(|c| report.per_level[usize::from(c.level)] += 1);
    report.seconds = t.elapsed().as_secs_f64();
    Ok(Subdivision { mesh, map, volumes, report })
}

/// The octree of [`subdivide`] with `direct` (no map): for pipelines that only need
/// the cells, such as marching cubes of a surface.
pub fn octree_around(surface: &TriangleBvh, levels: u8, root: RootShape, margin: f64) -> Octree {
    subdivide_direct(initial_tree(surface, root, margin), surface, levels, false, &|_| {}).0
}

/// The level-0 leaves of `shape` around `surface`.
fn initial_tree(surface: &TriangleBvh, shape: RootShape, margin: f64) -> Octree {
    match shape {
        RootShape::Cube => Octree::new(RootBox::around(&surface.bounds(), margin)),
        RootShape::BoundingBox { init } => {
            let mut tree = Octree::new(RootBox::bounding_grid(&surface.bounds(), init));
            prune_outside(&mut tree, surface);
            tree
        }
    }
}

/// Removes the leaves outside `surface` that it does not touch; returns how many.
fn prune_outside(tree: &mut Octree, surface: &TriangleBvh) -> usize {
    let outside = tree.outside_leaves(surface);
    outside.iter().for_each(|c| {
        tree.leaves.remove(c);
    });
    outside.len()
}

fn subdivide_direct(
    mut tree: Octree,
    surface: &TriangleBvh,
    levels: u8,
    remove_outside: bool,
    progress: &dyn Fn(u8),
) -> (Octree, SubdivideReport) {
    let mut r = SubdivideReport::default();
    for level in 1..=levels {
        progress(level);
        if remove_outside {
            r.removed_outside += prune_outside(&mut tree, surface);
        }
        let touched = tree.touched(surface, level);
        let created = tree.split(&touched);
        r.balance_splits += tree.balance(created);
    }
    (tree, r)
}

/// What [`subdivide_qr`] made.
struct QrSubdivision {
    map: CMap3,
    report: SubdivideReport,
    /// The leaves before the last level, with one dart of their volume.
    leaves: FxHashMap<OctCell, Dart>,
    /// The last level's cells that are not outside the surface: leaves too, not yet in
    /// `leaves`.
    last_level: Vec<FreshCell>,
    /// One dart of each of the last level's cells outside the surface, still in the map.
    last_outside: Vec<Dart>,
}

/// The query-replace subdivision.
fn subdivide_qr(
    start: Octree,
    surface: &TriangleBvh,
    opts: &SubdivideOptions,
    patterns: Option<&PatternSet>,
    progress: &dyn Fn(u8),
) -> Result<QrSubdivision, MapError> {
    let root = start.root;
    let mut r = SubdivideReport::default();
    // The level whose touched cells the refinement of `level` splits.
    let parents_of = |level: u8| (level <= opts.levels).then(|| level - 1);
    // The pattern set (when generated) is made while the level-0 map is built and its
    // cells tested.
    let mut generated = None;
    let slot = &mut generated;
    let (set, (mut map, (mut fresh, mut fresh_near), (start_seconds, contact_seconds))) = rayon::join(
        move || given_or_generated(patterns, GeneratedKind::HexSubdivision, slot),
        || {
            let t = Instant::now();
            let mut map = build_map(start.to_mesh(), &BuildOptions::default()).expect("a grid of boxes builds").0;
            // Each dart's label is the level of its volume (replacements copy labels to
            // the darts they create; children are relabelled after each refinement).
            map.enable_labels();
            let mut w = OrbitWalker::new();
            let boxes: Vec<(Dart, Aabb)> = map.cells(Orbit::Volume).map(|d| (d, volume_box(&map, d, &mut w))).collect();
            let start_seconds = t.elapsed().as_secs_f64();
            // The volumes made by the last level: the only ones the surface may touch, or
            // that may be outside and untouched, among the cells of their level (the
            // older leaves were refined, removed or found inside; balance refines inside
            // cells only); and the leaves of the surface's hierarchy near those the next
            // level refines.
            let t = Instant::now();
            let fresh = fresh_cells(root, surface, &boxes, &NearLeaves::default(), parents_of(1));
            (map, fresh, (start_seconds, t.elapsed().as_secs_f64()))
        },
    );
    r.phases.start = start_seconds;
    r.phases.contact += contact_seconds;
    // Each leaf's dart stays a dart of its volume: edge splits and face replacements
    // add darts and relink the old ones, and only refined or removed cells lose theirs.
    let mut leaves: FxHashMap<OctCell, Dart> = FxHashMap::default();
    // The untouched regions among `fresh`, when the last refinement found them.
    let mut fresh_regions: Option<Vec<u32>> = None;
    let mut level = 0;
    loop {
        level += 1;
        let (mut cells, near) = (std::mem::take(&mut fresh), std::mem::take(&mut fresh_near));
        let mut outside = Vec::new();
        if opts.remove_outside {
            let t = Instant::now();
            outside = take_outside(root, surface, &mut cells, fresh_regions.take());
            r.removed_outside += outside.len();
            r.phases.remove_outside += t.elapsed().as_secs_f64();
        }
        if level > opts.levels {
            // The last level's cells are not refined: the outside ones leave the map in
            // `subdivide`, while the others join the leaves there, beside the mesh. No
            // replacement follows: the buffers the passes kept would only add to the peak.
            crate::modify::DisjointExecutor::release_recycled();
            return Ok(QrSubdivision { map, report: r, leaves, last_level: cells, last_outside: outside });
        }
        progress(level);
        let parent_level = i32::from(level) - 1;
        let touched: Vec<(OctCell, Dart)> = cells
            .iter()
            .filter(|c| c.touches && i32::from(c.cell.level) == parent_level)
            .map(|c| (c.cell, c.dart))
            .collect();
        // The outside cells leave the map while the balance closure is found on the
        // octree's leaves (which never name them).
        let t = Instant::now();
        let (removing, mut plan) = rayon::join(
            || {
                let t = Instant::now();
                if outside.is_empty() {
                    return Ok(0.0);
                }
                map.remove_volumes(&outside).map(|_| t.elapsed().as_secs_f64())
            },
            || {
                leaves.reserve(cells.len());
                leaves.extend(cells.iter().map(|c| (c.cell, c.dart)));
                balance_closure(&root, &leaves, &touched)
            },
        );
        let removing = removing?;
        r.phases.remove_outside += removing;
        r.phases.balance += t.elapsed().as_secs_f64() - removing;
        r.balance_splits += plan.len() - touched.len();
        plan.sort_unstable();
        let contact =
            ContactTest { root, surface, near: &near, next_parents: parents_of(level + 1), regions_after: None };
        let batches: Vec<&[(i32, Dart, OctCell)]> = plan.chunk_by(|a, b| a.0 == b.0).collect();
        for (b, batch) in batches.iter().enumerate() {
            let cells: Vec<(Dart, OctCell)> = batch.iter().map(|&(_, d, c)| (d, c)).collect();
            // The last batch finds the next level's untouched regions beside its
            // replacements.
            let last = b + 1 == batches.len() && opts.remove_outside;
            let contact = ContactTest { regions_after: last.then_some(&fresh[..]), ..contact };
            let refined = refine(&mut map, set, &cells, &contact, opts.use_signatures, &mut r)?;
            cells.iter().for_each(|(_, c)| {
                leaves.remove(c);
            });
            // The longer list is kept and the shorter copied into it.
            if fresh.len() < refined.children.len() {
                let mut children = refined.children;
                children.splice(0..0, fresh);
                fresh = children;
            } else {
                fresh.extend(refined.children);
            }
            fresh_near.append(refined.near);
            fresh_regions = refined.regions;
        }
    }
}

/// The cells to split with `seeds` (leaves of one level, with a dart of their volume)
/// so that 2:1 balance survives: every leaf sharing a face or an edge with a
/// cell to split and coarser than it is split first, transitively (2022 §7.1, "those
/// having more than one subdivision level of difference with a neighbour"). Found on
/// the octree's leaves, which name the map's volumes. Returns (level, volume dart, cell)
/// triples.
fn balance_closure(
    root: &RootBox,
    leaves: &FxHashMap<OctCell, Dart>,
    seeds: &[(OctCell, Dart)],
) -> Vec<(i32, Dart, OctCell)> {
    let mut in_plan: FxHashSet<OctCell> = seeds.iter().map(|s| s.0).collect();
    let mut queue: Vec<OctCell> = seeds.iter().map(|s| s.0).collect();
    let mut next = 0;
    while next < queue.len() {
        let c = queue[next];
        next += 1;
        for n in coarser_neighbours(root, c, c.level, |x| leaves.contains_key(x)) {
            if in_plan.insert(n) {
                queue.push(n);
            }
        }
    }
    queue.iter().map(|&c| (i32::from(c.level), leaves[&c], c)).collect()
}

/// Removes from `cells` those outside `surface` that it does not touch; returns one dart
/// of each, in the order of `cells`, for the caller to remove them from the map.
/// `regions`: their untouched regions, if found already (see [`outside_in_regions`]).
fn take_outside(
    root: RootBox,
    surface: &TriangleBvh,
    cells: &mut Vec<FreshCell>,
    regions: Option<Vec<u32>>,
) -> Vec<Dart> {
    let octs: Vec<OctCell> = cells.iter().map(|c| c.cell).collect();
    let touches: Vec<bool> = cells.iter().map(|c| c.touches).collect();
    let mut outside = match regions {
        Some(regions) if regions.len() == cells.len() => outside_in_regions(&root, &octs, &touches, &regions, surface),
        _ => outside_among(&root, &octs, &touches, surface),
    };
    if outside.is_empty() {
        return Vec::new();
    }
    outside.sort_unstable();
    let darts = outside.iter().map(|&i| cells[i].dart).collect();
    let mut gone = vec![false; cells.len()];
    for &i in &outside {
        gone[i] = true;
    }
    let mut i = 0;
    cells.retain(|_| {
        i += 1;
        !gone[i - 1]
    });
    darts
}
