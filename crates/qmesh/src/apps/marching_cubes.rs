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
    /// Where a field's time went (seconds).
    pub phases: McPhases,
}

/// The phases of marching a field: the crossed cells found, then either the cases
/// compiled, the crossing points placed and the cells' polygons laid, or the slabs'
/// maps built and marched.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct McPhases {
    pub classify: f64,
    pub compile: f64,
    pub points: f64,
    pub lay: f64,
    pub slabs: f64,
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
/// ids of `map`) with the patterns of `set` (usually [`super::mc_pattern_set`]);
/// `crossing(a, b)` places the new vertex on an edge from inside vertex `a` to outside
/// vertex `b`. The map keeps the replaced cells; the surface's polygons are returned
/// oriented with normals pointing outside.
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
    march(map, inside, crossing, set, flags, None).map(|m| (m.surface, m.report))
}

/// What one march gives: the surface, the two original vertices (inside end first) of
/// the edge each of its points was placed on (None for a point a v-pattern placed inside
/// a cube), and the report.
pub(super) struct March {
    pub surface: IndexedMesh,
    pub edge_ends: Vec<Option<[u32; 2]>>,
    pub report: McReport,
}

/// The part of a map that one march replaces and counts, by layer: a slab of a grid
/// whose map also holds one layer of cells on each side (see `super::mc_field`).
pub(super) struct Layers<'a> {
    /// The layer (grid coordinate along the slab axis) of an original vertex.
    pub of_vertex: &'a dyn Fn(u32) -> usize,
    /// Cells whose lowest vertex is in `lo..hi` are this slab's.
    pub lo: usize,
    pub hi: usize,
    /// Whether `hi` is the grid's last plane (its cells are then this slab's too).
    pub top: bool,
}

impl Layers<'_> {
    /// Whether a cell (edge, face or volume) with these original vertices is this
    /// slab's: each cell of the grid is one slab's.
    pub fn owns(&self, vertices: &mut dyn Iterator<Item = u32>) -> bool {
        let low = vertices.map(self.of_vertex).min().unwrap_or(usize::MAX);
        (self.lo..self.hi).contains(&low) || (self.top && low == self.hi)
    }
}

/// Whether a cell (edge, face or volume) with these original vertices is replaced and
/// counted by a march (see [`Layers::owns`]).
pub(super) type Owns<'a> = &'a dyn Fn(&mut dyn Iterator<Item = u32>) -> bool;

/// [`marching_cubes`] on the volumes `region` owns (all when None); the faces those
/// volumes share with the others are replaced too (their match must be the one the
/// whole map would make), and only owned cells are counted.
pub(super) fn march(
    map: &mut CMap3,
    inside: &[bool],
    crossing: &dyn Fn(u32, u32) -> [f64; 3],
    set: &PatternSet,
    flags: McFlags,
    region: Option<Owns>,
) -> Result<March, MapError> {
    let t = Instant::now();
    let mut r = McReport {
        f_patterns: set.count(PatternKind::Face),
        v_patterns: set.count(PatternKind::Volume),
        ..Default::default()
    };
    let original = map.nb_vertex_ids();
    let is_in = |v: u32| inside.get(v as usize).copied().unwrap_or(false);
    let owns = |vertices: &mut dyn Iterator<Item = u32>| region.is_none_or(|owns| owns(vertices));
    let flag = map.reserve_mark()?;
    let darts: Vec<Dart> = map.darts().collect();
    for &d in &darts {
        if flags == McFlags::Corners || is_in(map.vertex_of(d)) {
            map.mark(d, flag);
        }
    }
    // Crossing edges (one inside and one outside end, inside end first), in the order
    // of their first darts; only the crossing darts' orbits are walked.
    let mut w = OrbitWalker::new();
    let mut seen = crate::cmap::BitSet::with_len(map.dart_capacity());
    let (mut split, mut edges) = (Vec::new(), Vec::new());
    for &d in &darts {
        let [a, b] = [map.vertex_of(d), map.vertex_of(map.next(d))];
        if is_in(a) != is_in(b) && !seen.get(d.idx()) {
            for &x in w.collect(map, d, Orbit::Edge) {
                seen.insert(x.idx());
            }
            split.push(d);
            edges.push(if is_in(a) { [a, b] } else { [b, a] });
        }
    }
    drop((darts, seen));
    // (splitting the edges and replacing the faces and cubes about doubles the darts)
    map.reserve(map.nb_darts(), edges.len());
    for (k, (&d, &[a, b])) in split.iter().zip(&edges).enumerate() {
        // (new vertex ids follow the edges' order: a surface point's edge is found back)
        let n = map.insert_vertex_in_edge(d, crossing(a, b));
        debug_assert_eq!(map.vertex_of(n) as usize, original + k);
    }
    r.edges_split = edges.iter().filter(|e| owns(&mut e.iter().copied())).count();
    let is_new = |v: u32| v as usize >= original;
    // The volumes to replace, their darts marked so that the faces they hold are found.
    let owned = map.reserve_mark()?;
    let mut volumes = Vec::new();
    for d in map.cells(Orbit::Volume).collect::<Vec<_>>() {
        let darts = w.collect(map, d, Orbit::Volume);
        let old = darts.iter().map(|&x| map.vertex_of(x)).filter(|&v| !is_new(v));
        if darts.iter().any(|&x| is_new(map.vertex_of(x))) && owns(&mut old.into_iter()) {
            for &x in darts {
                map.mark(x, owned);
            }
            volumes.push(d);
        }
    }
    let (mut faces, mut shared) = (Vec::new(), Vec::new());
    for d in map.cells(Orbit::Face) {
        let cycle = w.collect(map, d, Orbit::HalfFace);
        let held = map.is_marked(d, owned) || map.beta(d, 3).is_some_and(|o| map.is_marked(o, owned));
        if held && cycle.iter().any(|&x| is_new(map.vertex_of(x))) {
            let mut old = cycle.iter().map(|&x| map.vertex_of(x)).filter(|&v| !is_new(v));
            if owns(&mut old) { faces.push(d) } else { shared.push(d) }
        }
    }
    map.free_mark(owned);
    replace_cells(map, set, Flags::Mark(flag), &shared, &[], true);
    let rep = replace_cells(map, set, Flags::Mark(flag), &faces, &volumes, true);
    map.free_mark(flag);
    r.faces_replaced = rep.faces_replaced;
    r.volumes_replaced = rep.volumes_replaced;
    // (a shared face that nothing matches is counted by the slab that owns it)
    r.unmatched_faces = rep.unmatched_faces;
    r.unmatched_volumes = rep.unmatched_volumes;
    let created: Vec<Dart> = rep.created_volumes.iter().map(|&(d, _)| d).collect();
    let (surface, points) = surface_polygons(map, original, inside, &created);
    r.polygons = surface.nb_polygons();
    r.seconds = t.elapsed().as_secs_f64();
    let edge_ends = points.iter().map(|&v| edges.get(v as usize - original).copied()).collect();
    Ok(March { surface, edge_ends, report: r })
}

/// The faces of the `created` volumes (one dart each) whose vertices are all new, each
/// taken from its outside volume (a half-face's β1 order turns inward, toward its
/// volume: the outside volume's copy points out of the object); with the map vertex of
/// each point.
fn surface_polygons(map: &CMap3, original: usize, inside: &[bool], created: &[Dart]) -> (IndexedMesh, Vec<u32>) {
    let mut out = IndexedMesh::new();
    let mut vertex_of_point = Vec::new();
    let mut id = vec![u32::MAX; map.nb_vertex_ids()];
    let mut w = OrbitWalker::new();
    let mut faces = OrbitWalker::new();
    let is_outside = |v: usize| v < original && !inside.get(v).copied().unwrap_or(false);
    let mut seen = crate::cmap::BitSet::with_len(map.dart_capacity());
    let mut poly = Vec::new();
    for &c in created {
        let darts = w.collect(map, c, Orbit::Volume);
        if !darts.iter().any(|&x| is_outside(map.vertex_of(x) as usize)) {
            continue;
        }
        for &d in darts {
            if seen.get(d.idx()) {
                continue;
            }
            let cycle = faces.collect(map, d, Orbit::HalfFace);
            for x in cycle {
                seen.insert(x.idx());
            }
            if cycle.iter().any(|&x| (map.vertex_of(x) as usize) < original) {
                continue;
            }
            poly.clear();
            for &x in cycle {
                let v = map.vertex_of(x) as usize;
                if id[v] == u32::MAX {
                    id[v] = out.points.len() as u32;
                    out.points.push(map.position(v as u32));
                    vertex_of_point.push(v as u32);
                }
                poly.push(id[v]);
            }
            out.push_polygon(&poly);
        }
    }
    (out, vertex_of_point)
}

/// Splits every polygon into a fan of triangles, from the first vertex whose
/// diagonals are not already edges of the surface (two polygons sharing two vertices
/// would otherwise get the same diagonal, a non-manifold edge).
pub fn triangulate(mesh: &IndexedMesh) -> IndexedMesh {
    let mut out = IndexedMesh { points: mesh.points.clone(), ..IndexedMesh::new() };
    fan_into(mesh, &mut out);
    out
}

/// [`triangulate`], taking the mesh (its points move to the result).
pub fn triangulate_owned(mut mesh: IndexedMesh) -> IndexedMesh {
    let mut out = IndexedMesh { points: std::mem::take(&mut mesh.points), ..IndexedMesh::new() };
    fan_into(&mesh, &mut out);
    out
}

/// Appends the fans of `mesh`'s polygons to `out`, whose points they index.
fn fan_into(mesh: &IndexedMesh, out: &mut IndexedMesh) {
    let conn = &mesh.poly_conn;
    // The edges of the polygons by vertex; the diagonals drawn, in a set of their own.
    let Some(half) = crate::build::HalfEdges::of_polygons(&mesh.poly_offsets, conn, out.points.len(), |_| true) else {
        return;
    };
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut diagonals: rustc_hash::FxHashSet<(u32, u32)> = rustc_hash::FxHashSet::default();
    diagonals.reserve((0..mesh.nb_polygons()).map(|i| mesh.polygon(i).len().saturating_sub(3)).sum());
    let is_edge = |d: &rustc_hash::FxHashSet<(u32, u32)>, u: u32, v: u32| {
        half.find(conn, u, v).is_some() || half.find(conn, v, u).is_some() || d.contains(&key(u, v))
    };
    let triangles: usize = (0..mesh.nb_polygons()).map(|i| mesh.polygon(i).len().saturating_sub(2)).sum();
    out.poly_conn.reserve(3 * triangles);
    out.poly_offsets.reserve(triangles);
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        let n = p.len();
        let diagonal_ends = |apex: usize| (2..n.saturating_sub(1)).map(move |j| (p[apex], p[(apex + j) % n]));
        let apex = (0..n).find(|&a| diagonal_ends(a).all(|(u, v)| !is_edge(&diagonals, u, v))).unwrap_or(0);
        for (u, v) in diagonal_ends(apex) {
            diagonals.insert(key(u, v));
        }
        for k in 1..n.saturating_sub(1) {
            out.push_polygon(&[p[apex], p[(apex + k) % n], p[(apex + k + 1) % n]]);
        }
    }
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
    root: super::RootShape,
    margin: f64,
    set: &PatternSet,
    flags: McFlags,
) -> Result<(IndexedMesh, McReport, usize), String> {
    let tree = super::subdivide::octree_around(surface, levels, root, margin);
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
