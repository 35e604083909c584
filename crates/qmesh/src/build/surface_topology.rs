//! The topology of a polygon surface without building its map: the open edges and
//! Euler characteristic that [`build_surface_map`] and counting its cells would give,
//! from a sorted array of half-edges and a union-find over corners (a third of the map's
//! memory, for checking a large output before it is written).

use rayon::prelude::*;

use super::indexed::IndexedMesh;
#[cfg(doc)]
use super::surface::build_surface_map;

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
    let n_points = mesh.points.len() as u32;
    // Corners of the polygons kept, as (first corner, size) runs.
    let mut polygons: Vec<(u32, u32)> = Vec::with_capacity(mesh.nb_polygons());
    let mut corners: Vec<u32> = Vec::with_capacity(mesh.poly_conn.len());
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        if p.iter().any(|&v| v >= n_points) {
            return None;
        }
        let n = p.len();
        if n < 3 || (0..n).any(|k| p[k] == p[(k + 1) % n]) {
            continue;
        }
        polygons.push((corners.len() as u32, n as u32));
        corners.extend_from_slice(p);
    }
    let next = |(s, n): (u32, u32), k: u32| s + (k + 1) % n;
    // Half-edge of corner h: corners[h] → the next corner's vertex.
    let mut half: Vec<(u64, u32)> = Vec::with_capacity(corners.len());
    for &(s, n) in &polygons {
        for k in 0..n {
            let (u, v) = (corners[(s + k) as usize], corners[next((s, n), k) as usize]);
            half.push(((u64::from(u) << 32) | u64::from(v), s + k));
        }
    }
    half.par_sort_unstable();
    if half.windows(2).any(|w| w[0].0 == w[1].0) {
        return None;
    }
    let twin = |key: u64| {
        let reversed = key.rotate_left(32);
        half.binary_search_by_key(&reversed, |h| h.0).ok().map(|i| half[i].1)
    };
    // Around the target v of half-edge h (u → v), the corner after h in its polygon and
    // the corner of its opposite (v → u) are consecutive in v's fan.
    let mut parent: Vec<u32> = (0..corners.len() as u32).collect();
    let (mut paired, mut joined) = (0usize, 0usize);
    for &(s, n) in &polygons {
        for k in 0..n {
            let h = (s + k) as usize;
            let key = (u64::from(corners[h]) << 32) | u64::from(corners[next((s, n), k) as usize]);
            if let Some(t) = twin(key) {
                paired += 1;
                if union(&mut parent, next((s, n), k), t) {
                    joined += 1;
                }
            }
        }
    }
    let open = corners.len() - paired;
    let (v, e, f) = (corners.len() - joined, paired / 2 + open, polygons.len());
    Some(SurfaceTopology { open_edges: open, euler_characteristic: v as i64 - e as i64 + f as i64 })
}

/// Joins the sets of `a` and `b`; whether they were apart.
fn union(parent: &mut [u32], a: u32, b: u32) -> bool {
    let (ra, rb) = (root(parent, a), root(parent, b));
    if ra == rb {
        return false;
    }
    parent[ra.max(rb) as usize] = ra.min(rb);
    true
}

fn root(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let up = parent[parent[x as usize] as usize];
        parent[x as usize] = up;
        x = up;
    }
    x
}
