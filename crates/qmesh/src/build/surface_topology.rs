//! The topology of a polygon surface without building its map: the open edges and
//! Euler characteristic that [`build_surface_map`] and counting its cells would give,
//! from the half-edges by vertex and a union-find over corners (12 bytes per corner,
//! for checking a large output before it is written).

use super::half_edges::HalfEdges;
use super::indexed::IndexedMesh;
#[cfg(doc)]
use super::surface::build_surface_map;
use crate::disjoint_sets::DisjointSets;

/// Open edges and Euler characteristic of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SurfaceTopology {
    /// Half-edges without an opposite (the map's 2-free darts).
    pub open_edges: usize,
    /// V − E + F, a vertex counted once per fan of polygons around it (as the map does).
    pub euler_characteristic: i64,
}

/// The topology of `mesh`'s polygons, skipping degenerate ones (fewer than 3 distinct
/// consecutive vertices) as [`build_surface_map`] does; None where it fails: a node out of
/// range, or a half-edge used twice in the same direction (a non-manifold edge or an
/// inconsistent orientation).
///
/// ```
/// use qmesh::build::{IndexedMesh, surface_topology};
/// let mut m = IndexedMesh::new();
/// m.points = vec![[0.0; 3]; 4];
/// m.push_polygon(&[0, 1, 2]);
/// m.push_polygon(&[0, 2, 3]);
/// let t = surface_topology(&m).expect("manifold");
/// assert_eq!((t.open_edges, t.euler_characteristic), (4, 1)); // a disk
/// ```
pub fn surface_topology(mesh: &IndexedMesh) -> Option<SurfaceTopology> {
    let degenerate = |p: &[u32]| p.len() < 3 || (0..p.len()).any(|k| p[k] == p[(k + 1) % p.len()]);
    let half = HalfEdges::new(mesh, |p| !degenerate(p))?;
    let conn = &mesh.poly_conn;
    let target = |h: u32| conn[half.next(h) as usize];
    // A vertex is as many vertices of the map as fans of corners around it: corner c
    // (v → w) and the corner after its opposite (w → v) are consecutive in v's fan.
    let (mut corners, mut paired, mut vertices) = (0usize, 0usize, 0usize);
    let mut fans_of = DisjointSets::new(0);
    for v in 0..mesh.points.len() as u32 {
        let at = half.at(v);
        if at.iter().any(|&c| at.iter().filter(|&&x| target(x) == target(c)).count() > 1) {
            return None;
        }
        corners += at.len();
        fans_of.reset(at.len());
        let mut fans = at.len();
        for (i, &c) in at.iter().enumerate() {
            let Some(t) = half.find(conn, target(c), v) else { continue };
            paired += 1;
            let j = at.iter().position(|&x| x == half.next(t)).expect("the corner after an opposite is at v");
            if fans_of.union(i as u32, j as u32) {
                fans -= 1;
            }
        }
        vertices += fans;
    }
    let open = corners - paired;
    let (e, f) = (paired / 2 + open, half.polygons);
    Some(SurfaceTopology { open_edges: open, euler_characteristic: vertices as i64 - e as i64 + f as i64 })
}
