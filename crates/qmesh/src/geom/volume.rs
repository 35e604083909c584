//! Signed volumes of cells given by face cycles in map orientation (normals inward).

use super::{centroid, cross, dot, sub};
use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};

/// Signed volume of a closed cell whose faces are vertex cycles with inward normals
/// (the map's orientation convention): positive for a correctly oriented cell.
/// Non-planar faces are fan-triangulated around their centroid.
pub fn signed_volume_of_faces<F: AsRef<[u32]>>(faces: &[F], points: &[[f64; 3]]) -> f64 {
    let all = faces.iter().flat_map(|f| f.as_ref().iter().map(|&v| points[v as usize]));
    let o = centroid(all);
    let six_v: f64 = faces.iter().map(|f| six_volume_of_face(f.as_ref().iter().map(|&v| points[v as usize]), o)).sum();
    -six_v / 6.0
}

/// As [`signed_volume_of_faces`] for a cell given by a face table over its nodes
/// (no allocation: the builder's hot path).
pub fn signed_volume_of_table(table: &[&[usize]], nodes: &[u32], points: &[[f64; 3]]) -> f64 {
    let mut p = [[0.0; 3]; 8];
    for (k, &v) in nodes.iter().enumerate().take(8) {
        p[k] = points[v as usize];
    }
    let o = centroid(p[..nodes.len()].iter().copied());
    let mut six_v = 0.0;
    for f in table {
        let n = f.len() as f64;
        let mut c = [0.0; 3];
        for &k in *f {
            c = [c[0] + p[k][0], c[1] + p[k][1], c[2] + p[k][2]];
        }
        let c = sub([c[0] / n, c[1] / n, c[2] / n], o);
        for i in 0..f.len() {
            let a = sub(p[f[i]], o);
            let b = sub(p[f[(i + 1) % f.len()]], o);
            six_v += dot(a, cross(b, c));
        }
    }
    -six_v / 6.0
}

/// Six times the signed volume of the cone from `o` over one face (fan around its
/// centroid), for a face given by its corner positions in cycle order.
fn six_volume_of_face(corners: impl Iterator<Item = [f64; 3]> + Clone, o: [f64; 3]) -> f64 {
    let c = centroid(corners.clone());
    let mut it = corners.clone().chain(corners.take(1)).peekable();
    let mut six_v = 0.0;
    while let Some(p) = it.next() {
        let Some(&q) = it.peek() else { break };
        six_v += dot(sub(p, o), cross(sub(q, o), sub(c, o)));
    }
    six_v
}

/// Signed volume of the volume of `d` in `map` (positive when correctly oriented).
pub fn signed_volume_of_map_volume(map: &CMap3, d: Dart, walker: &mut OrbitWalker) -> f64 {
    let darts: Vec<Dart> = walker.collect(map, d, Orbit::Volume).to_vec();
    let o = centroid(darts.iter().map(|&x| map.point(x)));
    let mut six_v = 0.0;
    for &x in &darts {
        // Each dart contributes the triangle (origin, target, face centroid).
        let face = walker.collect(map, x, Orbit::HalfFace);
        let c = centroid(face.iter().map(|&y| map.point(y)));
        let a = sub(map.point(x), o);
        let b = sub(map.point(map.next(x)), o);
        six_v += dot(a, cross(b, sub(c, o)));
    }
    -six_v / 6.0
}
