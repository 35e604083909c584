//! Octree hexahedral subdivision of a surface (2022 Algorithm 5, §7.1): one cube around
//! the surface; at each level the hexahedra the surface touches, then those breaking
//! 2:1 balance, get their edges split in two, their faces replaced by the 2×2 f-pattern
//! and their volume by the 2×2×2 v-pattern. `direct` does the same with plain boxes.

use std::time::Instant;

use rayon::prelude::*;

use super::box_cells::{cell_of, flag_box_corners, is_corner, map_cells, volume_box};
use super::generated_patterns::{GeneratedKind, given_or_generated};
use super::octree::{Octree, RootBox};
use crate::build::{BuildOptions, IndexedMesh, build_map};
use crate::cmap::{CMap3, Dart, MapError, Mark, Orbit, OrbitWalker};
use crate::geom::{Aabb, TriangleBvh};
use crate::pattern::PatternSet;
use crate::replace::replace_cells;
use crate::signature::Flags;

/// Options of [`subdivide`].
#[derive(Clone, Copy, Debug)]
pub struct SubdivideOptions {
    /// Maximal level l_max (the root cube is level 0).
    pub levels: u8,
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
        SubdivideOptions { levels: 4, margin: 0.01, direct: false, remove_outside: false, use_signatures: true }
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
    pub removed_outside: usize,
    pub seconds: f64,
}

/// The subdivision: the hexahedra (VTK order, with a `level` array) and, unless
/// `direct`, the 3-map the query-replaces produced.
#[derive(Debug)]
pub struct Subdivision {
    pub mesh: IndexedMesh,
    pub map: Option<CMap3>,
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
    progress: &dyn Fn(u8),
) -> Result<Subdivision, MapError> {
    let t = Instant::now();
    let root = RootBox::around(&surface.bounds(), opts.margin);
    let (mut tree, map, mut report) = if opts.direct {
        let (tree, r) = subdivide_direct(root, surface, opts.levels, progress);
        (tree, None, r)
    } else {
        let (map, r) = subdivide_qr(root, surface, opts, patterns, progress)?;
        let tree = Octree { root, leaves: map_cells(&map, root).into_iter().collect() };
        (tree, Some(map), r)
    };
    let mut map = map;
    if opts.remove_outside {
        let outside = tree.outside_leaves(surface);
        report.removed_outside = outside.len();
        outside.iter().for_each(|c| {
            tree.leaves.remove(c);
        });
        if let Some(m) = map.as_mut() {
            remove_outside_volumes(m, root, &tree)?;
        }
    }
    let mesh = tree.to_mesh();
    report.volumes = tree.leaves.len();
    report.per_level = vec![0; usize::from(opts.levels) + 1];
    tree.leaves.iter().for_each(|c| report.per_level[usize::from(c.level)] += 1);
    report.seconds = t.elapsed().as_secs_f64();
    Ok(Subdivision { mesh, map, report })
}

/// The octree of [`subdivide`] with `direct` (no map): for pipelines that only need
/// the cells, such as marching cubes of a surface.
pub fn octree_around(surface: &TriangleBvh, levels: u8, margin: f64) -> Octree {
    subdivide_direct(RootBox::around(&surface.bounds(), margin), surface, levels, &|_| {}).0
}

fn subdivide_direct(
    root: RootBox,
    surface: &TriangleBvh,
    levels: u8,
    progress: &dyn Fn(u8),
) -> (Octree, SubdivideReport) {
    let mut tree = Octree::new(root);
    let mut r = SubdivideReport::default();
    for level in 1..=levels {
        progress(level);
        let touched = tree.touched(surface, level);
        let created = tree.split(&touched);
        r.balance_splits += tree.balance(created);
    }
    (tree, r)
}

fn subdivide_qr(
    root: RootBox,
    surface: &TriangleBvh,
    opts: &SubdivideOptions,
    patterns: Option<&PatternSet>,
    progress: &dyn Fn(u8),
) -> Result<(CMap3, SubdivideReport), MapError> {
    let mut generated = None;
    let set = given_or_generated(patterns, GeneratedKind::HexSubdivision, &mut generated);
    let mut map = build_map(Octree::new(root).to_mesh(), &BuildOptions::default()).expect("one hexahedron builds").0;
    // Each dart's label is the level of its volume (replacements copy labels to the
    // darts they create; children are relabelled after each refinement).
    map.enable_labels();
    let mut r = SubdivideReport::default();
    for level in 1..=opts.levels {
        progress(level);
        let mut w = OrbitWalker::new();
        let candidates: Vec<(Dart, Aabb)> = map
            .cells(Orbit::Volume)
            .filter(|&d| map.label_of(d) == i32::from(level) - 1)
            .map(|d| (d, volume_box(&map, d, &mut w)))
            .collect();
        let touched: Vec<Dart> =
            candidates.par_iter().filter(|(_, b)| surface.intersects_box(b)).map(|&(d, _)| d).collect();
        let mut plan = balance_closure(&mut map, &touched, i32::from(level) - 1)?;
        r.balance_splits += plan.len() - touched.len();
        plan.sort_unstable();
        for batch in plan.chunk_by(|a, b| a.0 == b.0) {
            let cells: Vec<Dart> = batch.iter().map(|&(_, d)| d).collect();
            refine(&mut map, set, &cells, batch[0].0 + 1, opts.use_signatures, &mut r)?;
        }
    }
    Ok((map, r))
}

/// The cells to split with `seeds` (all at level `seed_level`) so that 2:1 balance
/// survives: every volume sharing an edge with a cell to split and coarser than it is
/// split first, transitively (2022 §7.1, "those having more than one subdivision
/// level of difference with a neighbour"). Returns (level, volume dart) pairs.
fn balance_closure(map: &mut CMap3, seeds: &[Dart], seed_level: i32) -> Result<Vec<(i32, Dart)>, MapError> {
    let in_plan = map.reserve_mark()?;
    let mut w = OrbitWalker::new();
    let mut plan: Vec<(i32, Dart)> = Vec::with_capacity(seeds.len());
    for &d in seeds {
        add_to_plan(map, &mut w, in_plan, (seed_level, d), &mut plan);
    }
    let mut next = 0;
    while next < plan.len() {
        let (l, d) = plan[next];
        next += 1;
        let darts = w.collect(map, d, Orbit::Volume).to_vec();
        for x in darts {
            for y in map.orbit(x, Orbit::Edge) {
                let ly = map.label_of(y);
                if ly < l && !map.is_marked(y, in_plan) {
                    add_to_plan(map, &mut w, in_plan, (ly, y), &mut plan);
                }
            }
        }
    }
    map.free_mark(in_plan);
    Ok(plan)
}

fn add_to_plan(map: &mut CMap3, w: &mut OrbitWalker, in_plan: Mark, cell: (i32, Dart), plan: &mut Vec<(i32, Dart)>) {
    for &x in w.collect(map, cell.1, Orbit::Volume) {
        map.mark(x, in_plan);
    }
    plan.push(cell);
}

/// One refinement step of Algorithm 5 on the volumes of `cells`: split their whole
/// edges, flag the darts at their corners, query-replace their faces, then themselves.
fn refine(
    map: &mut CMap3,
    set: &PatternSet,
    cells: &[Dart],
    child_level: i32,
    use_signatures: bool,
    r: &mut SubdivideReport,
) -> Result<(), MapError> {
    let mut w = OrbitWalker::new();
    let old_darts: Vec<Dart> = cells.iter().flat_map(|&d| w.collect(map, d, Orbit::Volume).to_vec()).collect();
    let boxes: Vec<Aabb> = cells.iter().map(|&d| volume_box(map, d, &mut w)).collect();
    // Whole edges: both ends at corners of the cell (split ones end at a midpoint).
    let seen = map.reserve_mark()?;
    let mut edges = Vec::new();
    for (&d, b) in cells.iter().zip(&boxes) {
        for &x in w.collect(map, d, Orbit::Volume) {
            if !map.is_marked(x, seen) && is_corner(b, map.point(x)) && is_corner(b, map.point(map.next(x))) {
                edges.push((x, midpoint(map.point(x), map.point(map.next(x)))));
                let around = map.orbit(x, Orbit::Edge);
                around.into_iter().for_each(|e| map.mark(e, seen));
            }
        }
    }
    map.free_mark(seen);
    for (x, p) in edges {
        map.insert_vertex_in_edge(x, p);
    }
    // Flags on corner darts; each face listed once.
    let flag = map.reserve_mark()?;
    let seen = map.reserve_mark()?;
    let mut faces = Vec::new();
    for (&d, b) in cells.iter().zip(&boxes) {
        flag_box_corners(map, flag, d, b, &mut w);
        for &x in w.collect(map, d, Orbit::Volume) {
            if !map.is_marked(x, seen) {
                faces.push(x);
                let face = map.orbit(x, Orbit::Face);
                face.into_iter().for_each(|f| map.mark(f, seen));
            }
        }
    }
    map.free_mark(seen);
    let rep = replace_cells(map, set, Flags::Mark(flag), &faces, cells, use_signatures);
    map.free_mark(flag);
    r.faces_replaced += rep.faces_replaced;
    r.volumes_replaced += rep.volumes_replaced;
    // Every child keeps some of its parent's boundary darts: relabel through them.
    for d in old_darts {
        if map.label_of(d) != child_level {
            for &x in w.collect(map, d, Orbit::Volume) {
                map.set_label_of(x, child_level);
            }
        }
    }
    Ok(())
}

fn midpoint(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]))
}

/// Removes from the map the volumes whose cell is no longer a leaf of `tree`.
fn remove_outside_volumes(map: &mut CMap3, root: RootBox, tree: &Octree) -> Result<(), MapError> {
    let mut w = OrbitWalker::new();
    let gone: Vec<Dart> = map
        .cells(Orbit::Volume)
        .filter(|&d| !tree.leaves.contains(&cell_of(root, &volume_box(map, d, &mut w))))
        .collect();
    for d in gone {
        map.remove_volume(d)?;
    }
    Ok(())
}
