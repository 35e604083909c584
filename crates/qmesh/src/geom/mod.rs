//! Geometry attached to vertices: vector helpers and signed volumes.

mod bvh;
mod mvc;
mod quality;
mod volume;
mod winding;

pub use bvh::{Aabb, TriangleBvh, triangle_overlaps_box};
pub use mvc::{mvc_polygon, mvc_triangles};
pub use quality::{
    HEX_CORNER_FRAMES, corner_jacobian, hex_scaled_jacobian, prism_scaled_jacobian, pyramid_scaled_jacobian,
    tet_scaled_jacobian,
};
pub use volume::{signed_volume_of_faces, signed_volume_of_map_volume, signed_volume_of_table};
pub use winding::solid_angle;

/// a − b.
#[inline]
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a × b.
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// a · b.
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Mean of points.
pub fn centroid(points: impl IntoIterator<Item = [f64; 3]>) -> [f64; 3] {
    let (mut s, mut n) = ([0.0; 3], 0.0);
    for p in points {
        s = [s[0] + p[0], s[1] + p[1], s[2] + p[2]];
        n += 1.0;
    }
    if n == 0.0 { s } else { [s[0] / n, s[1] / n, s[2] / n] }
}

/// The unit cube's corners in VTK hexahedron order (shared by the unit tests).
#[cfg(test)]
pub(crate) const UNIT_CUBE: [[f64; 3]; 8] =
    [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]];

/// Newell's normal of the face of `d` (twice its vector area; it points the way the
/// face runs counter-clockwise).
pub fn face_normal(map: &crate::cmap::CMap3, d: crate::cmap::Dart) -> [f64; 3] {
    let mut n = [0.0; 3];
    let mut x = d;
    loop {
        let (p, q) = (map.point(x), map.point(map.next(x)));
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        x = map.next(x);
        if x == d {
            return n;
        }
    }
}
