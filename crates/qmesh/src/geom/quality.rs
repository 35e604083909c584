//! Element quality with Verdict's definitions (GUIDE §3): the scaled Jacobian of
//! hexahedra (minimum over the 8 corners and the centre) and tetrahedra; for prisms
//! and pyramids the minimum corner Jacobian, normalised so the equilateral cell scores 1.

use super::{cross, dot, sub};

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// det[a, b, c] of the three vectors normalised, or None when one has zero length.
fn unit_det(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<f64> {
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    if la <= f64::MIN_POSITIVE || lb <= f64::MIN_POSITIVE || lc <= f64::MIN_POSITIVE {
        return None;
    }
    Some(dot(a, cross(b, c)) / (la * lb * lc))
}

/// The scaled Jacobian at one corner: det of the unit edge vectors from `o` to `a`,
/// `b`, `c` (0 when an edge has zero length). A hexahedron's scaled Jacobian is at most
/// that of each of its corners (their frames are [`HEX_CORNER_FRAMES`]).
pub fn corner_jacobian(o: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    unit_det(sub(a, o), sub(b, o), sub(c, o)).unwrap_or(0.0)
}

/// Corner frames of a VTK hexahedron: (corner, ξ, η, ζ neighbours), right-handed for a cube.
pub const HEX_CORNER_FRAMES: [[usize; 4]; 8] =
    [[0, 1, 3, 4], [1, 2, 0, 5], [2, 3, 1, 6], [3, 0, 2, 7], [4, 7, 5, 0], [5, 4, 6, 1], [6, 5, 7, 2], [7, 6, 4, 3]];

/// Scaled Jacobian of a hexahedron in VTK node order: the minimum, over the 8 corners
/// and the centre (principal axes), of the determinant of unit edge vectors. 1 for a
/// cube, ≤ 0 for an inverted corner; 0 when an edge has zero length.
pub fn hex_scaled_jacobian(p: &[[f64; 3]; 8]) -> f64 {
    let d = |i: usize, j: usize| sub(p[j], p[i]);
    let add4 = |a: [f64; 3], b: [f64; 3], c: [f64; 3], e: [f64; 3]| {
        [a[0] + b[0] + c[0] + e[0], a[1] + b[1] + c[1] + e[1], a[2] + b[2] + c[2] + e[2]]
    };
    // Principal axes at the centre.
    let x1 = add4(d(0, 1), d(3, 2), d(4, 5), d(7, 6));
    let x2 = add4(d(0, 3), d(1, 2), d(4, 7), d(5, 6));
    let x3 = add4(d(0, 4), d(1, 5), d(2, 6), d(3, 7));
    let mut min = match unit_det(x1, x2, x3) {
        Some(j) => j,
        None => return 0.0,
    };
    for [o, a, b, c] in HEX_CORNER_FRAMES {
        match unit_det(d(o, a), d(o, b), d(o, c)) {
            Some(j) => min = min.min(j),
            None => return 0.0,
        }
    }
    min
}

/// Scaled Jacobian of a tetrahedron in VTK node order: √2 · det[p1−p0, p2−p0, p3−p0]
/// divided by the largest product of the three edge lengths at a node. 1 for a regular
/// tetrahedron.
pub fn tet_scaled_jacobian(p: &[[f64; 3]; 4]) -> f64 {
    let e = |i: usize, j: usize| sub(p[j], p[i]);
    let j = dot(e(0, 3), cross(e(2, 0), e(0, 1)));
    let l = |i: usize, k: usize| dot(e(i, k), e(i, k));
    let (l01, l12, l20, l03, l13, l23) = (l(0, 1), l(1, 2), l(2, 0), l(0, 3), l(1, 3), l(2, 3));
    let lengths = (l01 * l20 * l03).max(l01 * l12 * l13).max(l12 * l20 * l23).max(l03 * l13 * l23).sqrt();
    if lengths < f64::MIN_POSITIVE {
        return 0.0;
    }
    std::f64::consts::SQRT_2 * j / lengths
}

/// Scaled Jacobian of a prism (VTK wedge order: 0-1-2 turns away from 3-4-5): the
/// minimum over the 6 corners of the unit-edge determinant, times 2/√3 (the value at
/// an equilateral triangle's corner), capped at 1.
pub fn prism_scaled_jacobian(p: &[[f64; 3]; 6]) -> f64 {
    const CORNERS: [[usize; 4]; 6] =
        [[0, 2, 1, 3], [1, 0, 2, 4], [2, 1, 0, 5], [3, 4, 5, 0], [4, 5, 3, 1], [5, 3, 4, 2]];
    corner_minimum(p, &CORNERS).map_or(0.0, |j| (j * 2.0 / 3f64.sqrt()).min(1.0))
}

/// Scaled Jacobian of a pyramid (VTK order: base 0-1-2-3 turns toward apex 4): the
/// minimum over the 4 base corners of the unit-edge determinant, times √2 (its value
/// in the pyramid with equilateral faces), capped at 1.
pub fn pyramid_scaled_jacobian(p: &[[f64; 3]; 5]) -> f64 {
    const CORNERS: [[usize; 4]; 4] = [[0, 1, 3, 4], [1, 2, 0, 4], [2, 3, 1, 4], [3, 0, 2, 4]];
    corner_minimum(p, &CORNERS).map_or(0.0, |j| (j * std::f64::consts::SQRT_2).min(1.0))
}

/// Minimum of the unit-edge determinants at the given corner frames [origin, a, b, c].
fn corner_minimum(p: &[[f64; 3]], corners: &[[usize; 4]]) -> Option<f64> {
    corners
        .iter()
        .map(|&[o, a, b, c]| unit_det(sub(p[a], p[o]), sub(p[b], p[o]), sub(p[c], p[o])))
        .try_fold(f64::INFINITY, |m, j| j.map(|j| m.min(j)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ideal_cells_score_one_and_inverted_ones_negative() {
        let cube = super::super::UNIT_CUBE;
        assert!((hex_scaled_jacobian(&cube) - 1.0).abs() < 1e-12);
        let mut flipped = cube;
        flipped.swap(1, 3);
        flipped.swap(5, 7);
        assert!(hex_scaled_jacobian(&flipped) < 0.0);
        let s = 8f64.sqrt();
        let regular = [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]].map(|p| p.map(|c| c / s));
        // VTK order has 0-1-2 turning toward 3.
        let j = tet_scaled_jacobian(&[regular[0], regular[2], regular[1], regular[3]]);
        assert!((j.abs() - 1.0).abs() < 1e-12, "{j}");
        let h = 3f64.sqrt() / 2.0;
        let prism = [[0., 0., 0.], [0.5, h, 0.], [1., 0., 0.], [0., 0., 1.], [0.5, h, 1.], [1., 0., 1.]];
        assert!((prism_scaled_jacobian(&prism) - 1.0).abs() < 1e-12);
        let mut inverted = prism;
        inverted.swap(1, 2);
        inverted.swap(4, 5);
        assert!(prism_scaled_jacobian(&inverted) < 0.0);
        let pyramid = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0.5, 0.5, 0.5f64.sqrt()]];
        assert!((pyramid_scaled_jacobian(&pyramid) - 1.0).abs() < 1e-12);
        let mut flat = pyramid;
        flat[4][2] = -0.2;
        assert!(pyramid_scaled_jacobian(&flat) < 0.0);
    }
}
