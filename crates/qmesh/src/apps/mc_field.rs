//! Marching cubes of a sampled field (2022 §7.2 on a grid), slab by slab: only the cells
//! the surface crosses are built, a few layers at a time, and each slab's map is marched
//! on its own core and dropped. Memory follows a slab per core, not the grid, and the
//! surface is the one the map of every crossed cell gives (see [`FieldOptions`]).

use std::time::Instant;

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::marching_cubes::{Layers, McFlags, McReport, march};
use super::mc_grid::Grid;
use crate::build::{BuildOptions, CellKind, IndexedMesh, build_map};
use crate::pattern::{PatternKind, PatternSet};

/// How [`marching_cubes_field_with`] marches the grid.
#[derive(Clone, Copy, Debug)]
pub struct FieldOptions {
    /// Each case of cell query-replaced once and its surface laid on every cell of the
    /// case (the same surface; see `mc_compiled`), rather than every crossed cell
    /// query-replaced on the maps of slabs. Sets that place vertices inside cubes or
    /// leave a case unmatched are marched on maps whatever this says.
    pub compiled: bool,
    /// Crossed cells per slab (a slab is at least one layer of cells). The surface does
    /// not depend on it: each slab's map also holds the crossed cells of the layer on
    /// each side, so every face it shares with them is matched as in the whole map.
    pub slab_cells: usize,
}

impl Default for FieldOptions {
    fn default() -> Self {
        FieldOptions { compiled: true, slab_cells: 8192 }
    }
}

/// Marching cubes of a scalar field sampled on a grid of `dims` points (unit spacing,
/// value of point (i, j, k) at `(i·ny + j)·nz + k`): inside where value ≤ `iso`, new
/// vertices at the linear interpolation of the crossing (kept off the grid points).
/// Only the cells the surface crosses are built (the others hold no part of it: their
/// faces with the crossed cells have no crossing edge), slab by slab.
///
/// ```
/// use qmesh::apps::{McFlags, marching_cubes_field, mc_pattern_set};
/// // A 3×3×3 grid whose centre point alone is inside: one closed surface around it.
/// let mut values = vec![1.0f32; 27];
/// values[13] = -1.0;
/// let (surface, report) = marching_cubes_field(&values, [3, 3, 3], 0.0, &mc_pattern_set(), McFlags::Inside)?;
/// assert_eq!((report.volumes_replaced, report.unmatched_volumes), (8, 0));
/// assert_eq!(surface.points.len(), 6);
/// # Ok::<(), String>(())
/// ```
///
/// # Errors
/// A value count that does not match `dims`, or dims below 2.
pub fn marching_cubes_field(
    values: &[f32],
    dims: [usize; 3],
    iso: f64,
    set: &PatternSet,
    flags: McFlags,
) -> Result<(IndexedMesh, McReport), String> {
    marching_cubes_field_with(values, dims, iso, set, flags, &FieldOptions::default())
}

/// [`marching_cubes_field`] with the slab size chosen.
///
/// # Errors
/// A value count that does not match `dims`, dims below 2, or a slab size of 0.
pub fn marching_cubes_field_with(
    values: &[f32],
    dims: [usize; 3],
    iso: f64,
    set: &PatternSet,
    flags: McFlags,
    opts: &FieldOptions,
) -> Result<(IndexedMesh, McReport), String> {
    let t = Instant::now();
    let [nx, ny, nz] = dims;
    if dims.iter().any(|&n| n < 2) {
        return Err(format!("grid dimensions {nx}×{ny}×{nz}: at least 2 points per axis"));
    }
    if values.len() != nx * ny * nz {
        return Err(format!("{} values for a {nx}×{ny}×{nz} grid ({} expected)", values.len(), nx * ny * nz));
    }
    if opts.slab_cells == 0 {
        return Err("a slab needs at least one cell".into());
    }
    let grid = Grid::new(values, dims, iso);
    let layers = grid.crossed_layers();
    let classify = t.elapsed().as_secs_f64();
    if opts.compiled
        && let Some((surface, mut r)) = super::mc_compiled::march_compiled(&grid, &layers, set, flags)
    {
        r.seconds = t.elapsed().as_secs_f64();
        r.phases.classify = classify;
        return Ok((surface, r));
    }
    let slabs = slab_ranges(&layers, opts.slab_cells);
    let marched: Vec<SlabSurface> =
        slabs.par_iter().map(|&(lo, hi)| march_slab(&grid, &layers, lo, hi, set, flags)).collect::<Result<_, _>>()?;
    let mut r = McReport {
        f_patterns: set.count(PatternKind::Face),
        v_patterns: set.count(PatternKind::Volume),
        ..Default::default()
    };
    let mut surface = IndexedMesh::new();
    let mut on_planes: FxHashMap<u64, u32> = FxHashMap::default();
    for (s, &(lo, hi)) in marched.iter().zip(&slabs) {
        let ids: Vec<u32> = s
            .mesh
            .points
            .iter()
            .zip(&s.edges)
            .map(|(&p, &e)| {
                let fresh = |surface: &mut IndexedMesh| {
                    surface.points.push(p);
                    surface.points.len() as u32 - 1
                };
                // Only points on the planes between slabs are met twice.
                match e.and_then(|e| grid.plane_of(e).map(|k| (e, k))) {
                    Some((e, k)) if (k == lo && lo > 0) || (k == hi && hi < nz - 1) => {
                        *on_planes.entry(e).or_insert_with(|| fresh(&mut surface))
                    }
                    _ => fresh(&mut surface),
                }
            })
            .collect();
        for i in 0..s.mesh.nb_polygons() {
            let poly: Vec<u32> = s.mesh.polygon(i).iter().map(|&v| ids[v as usize]).collect();
            surface.push_polygon(&poly);
        }
        let q = &s.report;
        r.edges_split += q.edges_split;
        r.faces_replaced += q.faces_replaced;
        r.volumes_replaced += q.volumes_replaced;
        r.unmatched_faces += q.unmatched_faces;
        r.unmatched_volumes += q.unmatched_volumes;
        r.cells_built += s.cells;
    }
    r.polygons = surface.nb_polygons();
    r.seconds = t.elapsed().as_secs_f64();
    r.phases.classify = classify;
    r.phases.slabs = r.seconds - classify;
    Ok((surface, r))
}

/// Consecutive layers `lo..hi`, each run holding at most `cells` crossed cells (or one
/// layer): a function of the field only, so the result does not depend on the cores.
fn slab_ranges(layers: &[Vec<(u32, u8)>], cells: usize) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let (mut lo, mut held) = (0, 0);
    for (k, layer) in layers.iter().enumerate() {
        if k > lo && held + layer.len() > cells {
            out.push((lo, k));
            (lo, held) = (k, 0);
        }
        held += layer.len();
    }
    out.push((lo, layers.len()));
    out
}

/// One slab's surface on its own points, the grid edge of each point (None inside a
/// cube).
struct SlabSurface {
    mesh: IndexedMesh,
    edges: Vec<Option<u64>>,
    report: McReport,
    /// Crossed cells of the slab (without the layers on either side).
    cells: usize,
}

/// Builds the crossed cells of layers `lo..hi` and of the layer on each side, and
/// marches the slab's own.
fn march_slab(
    grid: &Grid,
    layers: &[Vec<(u32, u8)>],
    lo: usize,
    hi: usize,
    set: &PatternSet,
    flags: McFlags,
) -> Result<SlabSurface, String> {
    let [nx, ny, nz] = grid.dims;
    let (first, last) = (lo.saturating_sub(1), hi.min(nz - 2));
    let mut cells = IndexedMesh::new();
    // Local point of each grid point of planes first..=last + 1.
    let window = |g: usize| {
        let [i, j, k] = grid.coordinates(g);
        ((k - first) * nx + i) * ny + j
    };
    let mut point_of = vec![u32::MAX; (last + 2 - first) * nx * ny];
    for (k, layer) in layers.iter().enumerate().take(last + 1).skip(first) {
        for &(c, _) in layer {
            let (i, j) = (c as usize % (nx - 1), c as usize / (nx - 1));
            let nodes = grid.corners([i, j, k]).map(|g| {
                let slot = &mut point_of[window(g)];
                if *slot == u32::MAX {
                    *slot = cells.points.len() as u32;
                    cells.points.push(grid.coordinates(g).map(|x| x as f64));
                }
                *slot
            });
            cells.push_cell(CellKind::Hex, &nodes, None);
        }
    }
    drop(point_of);
    let own = layers[lo..hi].iter().map(Vec::len).sum();
    if own == 0 {
        return Ok(SlabSurface { mesh: IndexedMesh::new(), edges: Vec::new(), report: McReport::default(), cells: 0 });
    }
    let (mut map, _) = build_map(cells, &BuildOptions::default()).map_err(|e| e.to_string())?;
    // The grid point of every vertex, from its (integer) position: the builder gives a
    // vertex where crossed cells meet only at a corner or an edge one id per side.
    let grid_point: Vec<usize> =
        (0..map.nb_vertex_ids() as u32).map(|v| grid.index(map.position(v).map(|x| x as usize))).collect();
    let inside: Vec<bool> = grid_point.iter().map(|&g| grid.is_inside(g)).collect();
    let crossing = |a: u32, b: u32| grid.crossing(grid_point[a as usize], grid_point[b as usize]);
    let of_vertex = |v: u32| grid.coordinates(grid_point[v as usize])[2];
    let layers = Layers { of_vertex: &of_vertex, lo, hi, top: hi == nz - 1 };
    let owns = |v: &mut dyn Iterator<Item = u32>| layers.owns(v);
    let m = march(&mut map, &inside, &crossing, set, flags, Some(&owns)).map_err(|e| e.to_string())?;
    let edges = m
        .edge_ends
        .iter()
        .map(|e| e.map(|[a, b]| grid.edge_key(grid_point[a as usize], grid_point[b as usize])))
        .collect();
    Ok(SlabSurface { mesh: m.surface, edges, report: m.report, cells: own })
}
