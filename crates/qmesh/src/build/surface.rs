//! Polygons → surface map (dimension 2): β2 from opposite half-edges.

use rustc_hash::FxHashMap;

use super::error::BuildError;
use super::indexed::IndexedMesh;
use super::volume::BuildReport;
use crate::cmap::{CMap3, Dart, Orbit};

/// Builds a surface map: each polygon is a face, half-edges u→v and v→u are 2-sewn,
/// half-edges without an opposite stay 2-free (the boundary). Degenerate polygons
/// (fewer than 3 distinct consecutive vertices) are skipped with a warning count.
///
/// # Errors
/// A node index out of range, or a half-edge used twice in the same direction
/// (a non-manifold edge or inconsistent orientation).
pub fn build_surface_map(mesh: &IndexedMesh) -> Result<(CMap3, BuildReport), BuildError> {
    if mesh.nb_polygons() == 0 {
        return Err(BuildError::Empty);
    }
    let mut map = CMap3::with_capacity(mesh.poly_conn.len(), mesh.points.len());
    map.set_dimension(2);
    for &p in &mesh.points {
        map.add_vertex(p);
    }
    let mut report = BuildReport::default();
    let mut used = vec![false; mesh.points.len()];
    let mut half: FxHashMap<(u32, u32), (Dart, u32)> = FxHashMap::default();
    half.reserve(mesh.poly_conn.len());
    for pi in 0..mesh.nb_polygons() {
        let poly = mesh.polygon(pi);
        if let Some(&bad) = poly.iter().find(|&&v| v as usize >= mesh.points.len()) {
            return Err(BuildError::BadPolygon {
                polygon: pi,
                reason: format!("node index {bad} is out of range (the mesh has {} points)", mesh.points.len()),
            });
        }
        let n = poly.len();
        if n < 3 || (0..n).any(|k| poly[k] == poly[(k + 1) % n]) {
            report.degenerate_cells += 1;
            continue;
        }
        let d0 = map.make_polygon(poly);
        let mut d = d0;
        for k in 0..n {
            let (u, v) = (poly[k], poly[(k + 1) % n]);
            used[u as usize] = true;
            if let Some(&(_, other)) = half.get(&(u, v)) {
                return Err(BuildError::NonManifoldEdge { u, v, a: other as usize, b: pi });
            }
            half.insert((u, v), (d, pi as u32));
            d = map.next(d);
        }
    }
    for (&(u, v), &(d, _)) in &half {
        if u < v
            && let Some(&(o, _)) = half.get(&(v, u))
        {
            map.link(d, 2, o);
        }
    }
    report.unreferenced_points = used.iter().filter(|u| !**u).count();
    // Fans meeting only at a vertex are distinct vertices of the map.
    let reps: Vec<Dart> = map.cells(Orbit::Vertex).collect();
    let mut seen = vec![false; map.nb_vertex_ids()];
    for d in reps {
        let v = map.vertex_of(d);
        if std::mem::replace(&mut seen[v as usize], true) {
            let fresh = map.add_vertex(map.position(v));
            for x in map.orbit(d, Orbit::Vertex) {
                map.set_vertex_of(x, fresh);
            }
            report.split_vertices += 1;
        }
    }
    Ok((map, report))
}
