//! Signed volumes of cells given by face cycles in map orientation (normals inward).

use super::{centroid, cross, dot, sub};
use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};

/// Signed volume of a closed cell whose faces are vertex cycles with inward normals
/// (the map's orientation convention): positive for a correctly oriented cell.
/// Non-planar faces are fan-triangulated around their centroid.
pub fn signed_volume_of_faces<F: AsRef<[u32]>>(faces: &[F], points: &[[f64; 3]]) -> f64 {
    let all = faces.iter().flat_map(|f| f.as_ref().iter().map(|&v| points[v as usize]));
    let o = centroid(all);
    let mut six_v = 0.0;
    for f in faces {
        let f = f.as_ref();
        let c = centroid(f.iter().map(|&v| points[v as usize]));
        for k in 0..f.len() {
            let a = sub(points[f[k] as usize], o);
            let b = sub(points[f[(k + 1) % f.len()] as usize], o);
            six_v += dot(a, cross(b, sub(c, o)));
        }
    }
    -six_v / 6.0
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
