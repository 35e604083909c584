//! Mean value coordinates (2022 §5.2): 2D for polygons (Hormann & Floater, arbitrary
//! polygons) and 3D for closed triangle meshes (Ju, Schaefer & Warren).

use super::{cross, dot, sub};

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Mean value coordinates of `x` with respect to the planar polygon `poly` (in 3D,
/// measured in the polygon's plane). The weights sum to 1 and reproduce `x`.
pub fn mvc_polygon(poly: &[[f64; 3]], x: [f64; 3]) -> Vec<f64> {
    let n = poly.len();
    // Plane normal (Newell) to sign the angles.
    let mut nrm = [0.0; 3];
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
        nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
        nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let r: Vec<[f64; 3]> = poly.iter().map(|&p| sub(p, x)).collect();
    let len: Vec<f64> = r.iter().map(|&v| norm(v)).collect();
    let scale = len.iter().cloned().fold(0.0, f64::max).max(1e-300);
    if let Some(i) = len.iter().position(|&l| l <= 1e-12 * scale) {
        let mut w = vec![0.0; n];
        w[i] = 1.0;
        return w;
    }
    let nn = norm(nrm).max(1e-300);
    // tan(α_i / 2) for the angle between r_i and r_{i+1}.
    let tan_half: Vec<f64> = (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            let a2 = dot(cross(r[i], r[j]), nrm) / nn; // 2 × signed area
            let d = dot(r[i], r[j]);
            if a2.abs() <= 1e-14 * len[i] * len[j] { 0.0 } else { (len[i] * len[j] - d) / a2 }
        })
        .collect();
    let mut w: Vec<f64> = (0..n).map(|i| (tan_half[(i + n - 1) % n] + tan_half[i]) / len[i]).collect();
    let s: f64 = w.iter().sum();
    if s.abs() < 1e-300 {
        return vec![1.0 / n as f64; n];
    }
    w.iter_mut().for_each(|x| *x /= s);
    w
}

/// |u0 · (u1 × u2)| of the unit directions to a triangle's corners under which `x` is
/// taken to be in the triangle's plane: a point 1e-13 (relative) off it is.
const COPLANAR: f64 = 1e-10;

/// Mean value coordinates of `x` with respect to a closed triangle mesh given by its
/// vertex positions and consistently oriented triangles. Weights sum to 1.
pub fn mvc_triangles(verts: &[[f64; 3]], tris: &[[usize; 3]], x: [f64; 3]) -> Vec<f64> {
    let n = verts.len();
    let mut w = vec![0.0; n];
    let d: Vec<f64> = verts.iter().map(|&p| norm(sub(p, x))).collect();
    let scale = d.iter().cloned().fold(0.0, f64::max).max(1e-300);
    if let Some(i) = d.iter().position(|&l| l <= 1e-12 * scale) {
        w[i] = 1.0;
        return w;
    }
    let u: Vec<[f64; 3]> = verts.iter().zip(&d).map(|(&p, &l)| sub(p, x).map(|c| c / l)).collect();
    for t in tris {
        // The angle between two unit vectors a, b as 2·atan2(|a − b|, |a + b|): exact to
        // rounding near π too (2·asin(|a − b| / 2) loses half the digits there).
        let theta: [f64; 3] = std::array::from_fn(|i| {
            let (a, b) = (u[t[(i + 1) % 3]], u[t[(i + 2) % 3]]);
            2.0 * norm(sub(a, b)).atan2(norm([a[0] + b[0], a[1] + b[1], a[2] + b[2]]))
        });
        let h = (theta[0] + theta[1] + theta[2]) / 2.0;
        if std::f64::consts::PI - h < 1e-9 {
            // x lies on this triangle: barycentric weights.
            let b: [f64; 3] = std::array::from_fn(|i| theta[i].sin() * d[t[(i + 2) % 3]] * d[t[(i + 1) % 3]]);
            let s: f64 = b.iter().sum();
            let mut out = vec![0.0; n];
            for i in 0..3 {
                out[t[i]] = b[i] / s;
            }
            return out;
        }
        let det = dot(u[t[0]], cross(u[t[1]], u[t[2]]));
        if det.abs() <= COPLANAR {
            // x is (to rounding) in the plane of this triangle, outside it: the
            // triangle's weights tend to 0 there, but 1/s below would amplify rounding.
            continue;
        }
        let sign = if det < 0.0 { -1.0 } else { 1.0 };
        let c: [f64; 3] = std::array::from_fn(|i| {
            2.0 * h.sin() * (h - theta[i]).sin() / (theta[(i + 1) % 3].sin() * theta[(i + 2) % 3].sin()) - 1.0
        });
        let s: [f64; 3] = c.map(|ci| sign * (1.0 - ci * ci).max(0.0).sqrt());
        if s.iter().any(|si| si.abs() <= 1e-12) {
            continue; // x is in the plane of this triangle, outside it
        }
        for i in 0..3 {
            let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
            w[t[i]] += (theta[i] - c[i1] * theta[i2] - c[i2] * theta[i1]) / (d[t[i]] * theta[i1].sin() * s[i2]);
        }
    }
    let total: f64 = w.iter().sum();
    if total.abs() > 1e-300 {
        w.iter_mut().for_each(|x| *x /= total);
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(w: &[f64], pts: &[[f64; 3]]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for (wi, q) in w.iter().zip(pts) {
            for k in 0..3 {
                p[k] += wi * q[k];
            }
        }
        p
    }

    #[test]
    fn polygon_coordinates_reproduce_points() {
        let sq = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
        let w = mvc_polygon(&sq, [0.5, 0.5, 0.0]);
        assert!(w.iter().all(|x| (x - 0.25).abs() < 1e-12), "{w:?}");
        let x = [0.2, 0.7, 0.0];
        let p = apply(&mvc_polygon(&sq, x), &sq);
        assert!((0..3).all(|k| (p[k] - x[k]).abs() < 1e-12), "{p:?}");
        // A concave L-shaped polygon.
        let l = [[0., 0., 0.], [2., 0., 0.], [2., 1., 0.], [1., 1., 0.], [1., 2., 0.], [0., 2., 0.]];
        let x = [0.5, 1.5, 0.0];
        let p = apply(&mvc_polygon(&l, x), &l);
        assert!((0..3).all(|k| (p[k] - x[k]).abs() < 1e-12), "{p:?}");
    }

    #[test]
    fn triangle_mesh_coordinates_reproduce_points() {
        let v = super::super::UNIT_CUBE;
        let quads = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
        let tris: Vec<[usize; 3]> = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        for x in [[0.5, 0.5, 0.5], [0.2, 0.3, 0.9], [0.5, 0.5, 0.0]] {
            let w = mvc_triangles(&v, &tris, x);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let p = apply(&w, &v);
            assert!((0..3).all(|k| (p[k] - x[k]).abs() < 1e-6), "{x:?} -> {p:?}");
        }
        // Outside the cage, in (or a rounding error off) the plane of a face: linear
        // precision holds there too, to rounding, not to 1e-3.
        let off = [1e-14, -3e-14, 1e-13, -1e-12, 7e-13];
        let mut points = vec![[1.5, 0.5, 1.0 + 1e-13], [2.0, 0.5, 1.0], [0.5, -0.5, 1.0 - 1e-12], [1.25, 1.25, 0.0]];
        // … and along the side planes beyond the cage's corners and edges.
        for (k, &e) in off.iter().enumerate() {
            let t = 0.1 + 0.37 * k as f64;
            points.extend([[1.0 + e, 1.0, 1.0 + t], [1.0, 0.3 + e, 1.0 + t], [e, 0.7, -t], [1.0 + t, 1.0 - e, 0.4]]);
        }
        for x in points {
            let p = apply(&mvc_triangles(&v, &tris, x), &v);
            assert!((0..3).all(|k| (p[k] - x[k]).abs() < 1e-9), "{x:?} -> {p:?}");
        }
    }
}
