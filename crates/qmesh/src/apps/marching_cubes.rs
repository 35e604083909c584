//! Marching cubes by query-replace (2022 Algorithm 6, §7.2): split the edges that cross
//! the surface, query-replace the faces then the cubes with the generated patterns, and
//! keep the faces made only of new vertices — the surface.

use std::time::Instant;

use crate::build::IndexedMesh;
use crate::cmap::{CMap3, Dart, MapError, Orbit, OrbitWalker};
use crate::pattern::{PatternKind, PatternSet};
use crate::replace::replace_cells;
use crate::signature::Flags;

/// What [`marching_cubes`] did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct McReport {
    pub f_patterns: usize,
    pub v_patterns: usize,
    pub edges_split: usize,
    pub faces_replaced: usize,
    pub volumes_replaced: usize,
    pub unmatched_faces: usize,
    pub unmatched_volumes: usize,
    pub polygons: usize,
    /// Hexahedra of the map marched: for a field, only the cells the surface crosses.
    pub cells_built: usize,
    pub seconds: f64,
}

/// Which input darts carry the flags that matching respects (2022 §7.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum McFlags {
    /// Darts at inside corners: inside/outside is part of the query, as in qmesh's
    /// generated set ([`super::mc_pattern_set`], flags in the files' marks).
    #[default]
    Inside,
    /// Darts at the cube's corners, inside or not: only the topology of the split
    /// boundary is queried, as in the authors' set (`patterns/cgal/marching-cubes`,
    /// flags by the geometric corner rule).
    Corners,
}

/// Extracts the surface between the vertices with `inside[v]` and the others (vertex
/// ids of `map`) with the patterns of `set` (usually [`super::mc_pattern_set`]); `crossing(a, b)` places the new vertex on an edge from inside vertex
/// `a` to outside vertex `b`. The map keeps the replaced cells; the surface's polygons
/// are returned oriented with normals pointing outside.
///
/// # Errors
/// Only if the map has no free mark.
pub fn marching_cubes(
    map: &mut CMap3,
    inside: &[bool],
    crossing: &dyn Fn(u32, u32) -> [f64; 3],
    set: &PatternSet,
    flags: McFlags,
) -> Result<(IndexedMesh, McReport), MapError> {
    let t = Instant::now();
    let mut r = McReport {
        f_patterns: set.count(PatternKind::Face),
        v_patterns: set.count(PatternKind::Volume),
        ..Default::default()
    };
    let original = map.nb_vertex_ids();
    let is_in = |v: u32| inside.get(v as usize).copied().unwrap_or(false);
    let flag = map.reserve_mark()?;
    for d in map.darts().collect::<Vec<_>>() {
        if flags == McFlags::Corners || is_in(map.vertex_of(d)) {
            map.mark(d, flag);
        }
    }
    // Crossing edges: one inside and one outside end.
    let edges: Vec<Dart> =
        map.cells(Orbit::Edge).filter(|&d| is_in(map.vertex_of(d)) != is_in(map.vertex_of(map.next(d)))).collect();
    for &d in &edges {
        let (a, b) = (map.vertex_of(d), map.vertex_of(map.next(d)));
        let p = if is_in(a) { crossing(a, b) } else { crossing(b, a) };
        map.insert_vertex_in_edge(d, p);
    }
    r.edges_split = edges.len();
    let is_new = |v: u32| v as usize >= original;
    let mut w = OrbitWalker::new();
    let faces: Vec<Dart> = map
        .cells(Orbit::Face)
        .filter(|&d| w.collect(map, d, Orbit::HalfFace).iter().any(|&x| is_new(map.vertex_of(x))))
        .collect();
    let volumes: Vec<Dart> = map
        .cells(Orbit::Volume)
        .filter(|&d| w.collect(map, d, Orbit::Volume).iter().any(|&x| is_new(map.vertex_of(x))))
        .collect();
    let rep = replace_cells(map, set, Flags::Mark(flag), &faces, &volumes, true);
    map.free_mark(flag);
    r.faces_replaced = rep.faces_replaced;
    r.volumes_replaced = rep.volumes_replaced;
    r.unmatched_faces = rep.unmatched_faces;
    r.unmatched_volumes = rep.unmatched_volumes;
    let surface = surface_polygons(map, original, inside);
    r.polygons = surface.nb_polygons();
    r.seconds = t.elapsed().as_secs_f64();
    Ok((surface, r))
}

/// The faces whose vertices are all new, each taken once from its outside volume (a
/// half-face's β1 order turns inward, toward its volume: the outside volume's copy
/// points out of the object).
fn surface_polygons(map: &CMap3, original: usize, inside: &[bool]) -> IndexedMesh {
    let mut out = IndexedMesh::new();
    let mut id = vec![u32::MAX; map.nb_vertex_ids()];
    let mut w = OrbitWalker::new();
    for d in map.cells(Orbit::HalfFace) {
        let cycle: Vec<Dart> = w.collect(map, d, Orbit::HalfFace).to_vec();
        if cycle.iter().any(|&x| (map.vertex_of(x) as usize) < original) {
            continue;
        }
        let is_outside = |v: usize| v < original && !inside.get(v).copied().unwrap_or(false);
        // The face across an edge of a cut, in the same volume, is the part of a cube
        // face on that side of the cut: its original corners tell the side (no walk of
        // the whole volume); the volume is walked only when that face has none.
        let across = map.beta(d, 2).and_then(|e| {
            let mut x = e;
            loop {
                let v = map.vertex_of(x) as usize;
                if v < original {
                    return Some(v);
                }
                x = map.next(x);
                if x == e {
                    return None;
                }
            }
        });
        let outside_volume = match across {
            Some(v) => is_outside(v),
            None => w.collect(map, d, Orbit::Volume).iter().any(|&x| is_outside(map.vertex_of(x) as usize)),
        };
        if !outside_volume {
            continue;
        }
        let poly: Vec<u32> = cycle
            .iter()
            .map(|&x| {
                let v = map.vertex_of(x) as usize;
                if id[v] == u32::MAX {
                    id[v] = out.points.len() as u32;
                    out.points.push(map.position(v as u32));
                }
                id[v]
            })
            .collect();
        out.push_polygon(&poly);
    }
    out
}

/// Splits every polygon into a fan of triangles, from the first vertex whose
/// diagonals are not already edges of the surface (two polygons sharing two vertices
/// would otherwise get the same diagonal, a non-manifold edge).
pub fn triangulate(mesh: &IndexedMesh) -> IndexedMesh {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut edges: rustc_hash::FxHashSet<(u32, u32)> = rustc_hash::FxHashSet::default();
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        for k in 0..p.len() {
            edges.insert(key(p[k], p[(k + 1) % p.len()]));
        }
    }
    let mut out = IndexedMesh { points: mesh.points.clone(), ..IndexedMesh::new() };
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        let n = p.len();
        let diagonals = |apex: usize| (2..n.saturating_sub(1)).map(move |j| (p[apex], p[(apex + j) % n]));
        let apex = (0..n).find(|&a| diagonals(a).all(|(u, v)| !edges.contains(&key(u, v)))).unwrap_or(0);
        for (u, v) in diagonals(apex) {
            edges.insert(key(u, v));
        }
        for k in 1..n.saturating_sub(1) {
            out.push_polygon(&[p[apex], p[(apex + k) % n], p[(apex + k + 1) % n]]);
        }
    }
    out
}

/// Marching cubes of a scalar field sampled on a grid of `dims` points (unit spacing,
/// value of point (i, j, k) at `(i·ny + j)·nz + k`): inside where value ≤ `iso`, new
/// vertices at the linear interpolation of the crossing (kept off the grid points).
/// Only the cells the surface crosses are built (the others hold no part of it: their
/// faces with the crossed cells have no crossing edge), so time and memory follow the
/// surface, not the grid.
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
    let [nx, ny, nz] = dims;
    if dims.iter().any(|&n| n < 2) {
        return Err(format!("grid dimensions {nx}×{ny}×{nz}: at least 2 points per axis"));
    }
    if values.len() != nx * ny * nz {
        return Err(format!("{} values for a {nx}×{ny}×{nz} grid ({} expected)", values.len(), nx * ny * nz));
    }
    let value = |g: usize| f64::from(values[g]);
    let band = crossed_cells(values, dims, iso);
    if band.nb_cells() == 0 {
        let r = McReport {
            f_patterns: set.count(PatternKind::Face),
            v_patterns: set.count(PatternKind::Volume),
            ..Default::default()
        };
        return Ok((IndexedMesh::new(), r));
    }
    let cells_built = band.nb_cells();
    let (mut map, _) =
        crate::build::build_map(band, &crate::build::BuildOptions::default()).map_err(|e| e.to_string())?;
    // The grid point of every vertex, from its (integer) position: the builder gives a
    // vertex where crossed cells meet only at a corner or an edge one id per side.
    let grid_point: Vec<usize> = (0..map.nb_vertex_ids() as u32)
        .map(|v| {
            let [a, b, c] = map.position(v).map(|x| x as usize);
            (a * ny + b) * nz + c
        })
        .collect();
    let inside: Vec<bool> = grid_point.iter().map(|&g| value(g) - iso <= 0.0).collect();
    let crossing = |a: u32, b: u32| {
        let (ga, gb) = (grid_point[a as usize], grid_point[b as usize]);
        let (va, vb) = (value(ga), value(gb));
        let t = if vb != va { ((iso - va) / (vb - va)).clamp(1e-6, 1.0 - 1e-6) } else { 0.5 };
        let (p, q) = (grid_position(ga, ny, nz), grid_position(gb, ny, nz));
        [0, 1, 2].map(|k| p[k] + t * (q[k] - p[k]))
    };
    let (surface, mut r) = marching_cubes(&mut map, &inside, &crossing, set, flags).map_err(|e| e.to_string())?;
    r.cells_built = cells_built;
    Ok((surface, r))
}

/// The hexahedra of the grid cells with corners on both sides of `iso` (corner order
/// and cell order as [`crate::generate::hex_grid`]), on their own points placed at
/// their grid coordinates.
fn crossed_cells(values: &[f32], [nx, ny, nz]: [usize; 3], iso: f64) -> IndexedMesh {
    let g = |i: usize, j: usize, k: usize| (i * ny + j) * nz + k;
    let inside = |i: usize, j: usize, k: usize| f64::from(values[g(i, j, k)]) - iso <= 0.0;
    let mut mesh = IndexedMesh::new();
    let mut point_of = vec![u32::MAX; values.len()];
    for k in 0..nz - 1 {
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let corners = [
                    (i, j, k),
                    (i + 1, j, k),
                    (i + 1, j + 1, k),
                    (i, j + 1, k),
                    (i, j, k + 1),
                    (i + 1, j, k + 1),
                    (i + 1, j + 1, k + 1),
                    (i, j + 1, k + 1),
                ];
                let first = inside(i, j, k);
                if corners.iter().all(|&(a, b, c)| inside(a, b, c) == first) {
                    continue;
                }
                let nodes = corners.map(|(a, b, c)| {
                    let p = g(a, b, c);
                    if point_of[p] == u32::MAX {
                        point_of[p] = mesh.points.len() as u32;
                        mesh.points.push([a as f64, b as f64, c as f64]);
                    }
                    point_of[p]
                });
                mesh.push_cell(crate::build::CellKind::Hex, &nodes, None);
            }
        }
    }
    mesh
}

/// The position of grid point `g` (index `(i·ny + j)·nz + k`).
fn grid_position(g: usize, ny: usize, nz: usize) -> [f64; 3] {
    [(g / (ny * nz)) as f64, (g / nz % ny) as f64, (g % nz) as f64]
}

/// Marching cubes of a surface (2022 §7.2 on the hexahedra of §7.1): the 2:1 octree of
/// `levels` around it, each vertex inside or outside by winding number, crossing edges
/// split at their middle. Returns the surface, the report and the number of hexahedra.
///
/// # Errors
/// An octree that does not build (cannot happen for a valid surface).
pub fn marching_cubes_surface(
    surface: &crate::geom::TriangleBvh,
    levels: u8,
    margin: f64,
    set: &PatternSet,
    flags: McFlags,
) -> Result<(IndexedMesh, McReport, usize), String> {
    let tree = super::subdivide::octree_around(surface, levels, margin);
    let hexes = tree.to_mesh();
    let inside = tree.point_sides(surface);
    let (cells, _) = super::hanging::insert_hanging_vertices(&hexes).map_err(|e| e.to_string())?;
    let (mut map, _) =
        crate::build::build_map(cells, &crate::build::BuildOptions::default()).map_err(|e| e.to_string())?;
    let points = hexes.points;
    let crossing = |a: u32, b: u32| {
        let (p, q) = (points[a as usize], points[b as usize]);
        [0, 1, 2].map(|k| 0.5 * (p[k] + q[k]))
    };
    let (s, mut r) = marching_cubes(&mut map, &inside, &crossing, set, flags).map_err(|e| e.to_string())?;
    r.cells_built = tree.leaves.len();
    Ok((s, r, tree.leaves.len()))
}
