//! Orientation and geometric realisation of a subdivision of the hexahedron.
//!
//! A subdivision found combinatorially is a 3-ball; orienting it (each tetrahedron's
//! corners in positive order, consistent across shared triangles, boundary triangles
//! facing out) is a traversal. Whether some placement of the 8 corners makes every
//! tetrahedron positive is searched for by gradient ascent on a soft minimum of the
//! tetrahedron volumes: Pellerin et al. (2018) report 171 realisable classes out of
//! 174, and this search finds those 171.

use super::enumerate::boundary_triangles;
use crate::apps::cube;
use crate::geom::{cross, dot, sub};

/// Signed volume ×6 of the tetrahedron `t` (corner indices into `p`).
pub(crate) fn det(p: &[[f64; 3]; 8], t: [u8; 4]) -> f64 {
    let a = p[t[0] as usize];
    dot(sub(p[t[3] as usize], a), cross(sub(p[t[1] as usize], a), sub(p[t[2] as usize], a)))
}

/// The tetrahedra of `tets` (masks) as positively ordered corner tuples, consistently
/// with the outward boundary triangles of `diagonals`; None if no consistent
/// orientation exists.
pub(crate) fn orient(tets: &[u8], diagonals: u8) -> Option<Vec<[u8; 4]>> {
    let mut oriented: Vec<Option<[u8; 4]>> = vec![None; tets.len()];
    let mut stack = Vec::new();
    // A boundary triangle (a, b, c) seen from outside counter-clockwise: the
    // tetrahedron on it is positive as (a, c, b, d).
    let outward = boundary_triangles(diagonals);
    let first = outward[0];
    let m0 = first.iter().fold(0u8, |m, &c| m | 1 << c);
    let i0 = tets.iter().position(|&t| t & m0 == m0)?;
    let apex = (tets[i0] & !m0).trailing_zeros() as u8;
    oriented[i0] = Some([first[0], first[2], first[1], apex]);
    stack.push(i0);
    while let Some(i) = stack.pop() {
        let t = oriented[i].expect("stacked tetrahedra are oriented");
        // Outward faces of a positive (0, 1, 2, 3): (0 2 1), (0 1 3), (1 2 3), (0 3 2).
        for f in [[t[0], t[2], t[1]], [t[0], t[1], t[3]], [t[1], t[2], t[3]], [t[0], t[3], t[2]]] {
            let m = f.iter().fold(0u8, |m, &c| m | 1 << c);
            let Some(j) = (0..tets.len()).find(|&j| j != i && tets[j] & m == m) else { continue };
            let w = (tets[j] & !m).trailing_zeros() as u8;
            let want = [f[0], f[1], f[2], w];
            match oriented[j] {
                None => {
                    oriented[j] = Some(want);
                    stack.push(j);
                }
                Some(o) if same_orientation(o, want) => {}
                Some(_) => return None,
            }
        }
    }
    let out: Option<Vec<[u8; 4]>> = oriented.into_iter().collect();
    let out = out?;
    // Every boundary triangle must face out.
    for b in outward {
        let m = b.iter().fold(0u8, |m, &c| m | 1 << c);
        let t = out.iter().find(|t| mask4(t) & m == m)?;
        let apex = (mask4(t) & !m).trailing_zeros() as u8;
        if !same_orientation(*t, [b[0], b[2], b[1], apex]) {
            return None;
        }
    }
    Some(out)
}

fn mask4(t: &[u8; 4]) -> u8 {
    t.iter().fold(0u8, |m, &c| m | 1 << c)
}

/// Whether two orderings of the same 4 corners differ by an even permutation.
fn same_orientation(a: [u8; 4], b: [u8; 4]) -> bool {
    let pos: Vec<usize> = b.iter().map(|x| a.iter().position(|y| y == x).expect("same corners")).collect();
    let mut inversions = 0;
    for i in 0..4 {
        for j in i + 1..4 {
            inversions += usize::from(pos[i] > pos[j]);
        }
    }
    inversions % 2 == 0
}

/// The smallest signed volume ×6 of the oriented tetrahedra on corners `p`.
fn worst(p: &[[f64; 3]; 8], tets: &[[u8; 4]]) -> f64 {
    tets.iter().map(|&t| det(p, t)).fold(f64::INFINITY, f64::min)
}

/// The volume ×6 every tetrahedron of a realisation exceeds.
const TARGET: f64 = 1e-3;

/// Corner positions (index = corner bits) making every oriented tetrahedron positive
/// (volume ×6 above 10⁻³ within the box [−1, 2]³), or None when the search fails
/// (which does not prove that none exists).
///
/// Gradient ascent on a soft minimum of the volumes, from the unit cube and then from
/// reproducibly perturbed cubes (deterministic: the same answer on every run).
pub(crate) fn realize(tets: &[[u8; 4]]) -> Option<[[f64; 3]; 8]> {
    const TEMPERATURE: f64 = 0.02;
    let mut rng = crate::random::SplitMix64(0x5EED_0000 + tets.len() as u64);
    // Starts ever farther from the cube (past 2 or so, random points of the box): two
    // of the 15-tetrahedron classes are only found from far away.
    for restart in 0..64 {
        let noise = 0.4 * f64::from(restart % 24);
        let mut p: [[f64; 3]; 8] =
            std::array::from_fn(|c| cube::corner(c as u8).map(|x| x + noise * (2.0 * rng.unit() - 1.0)));
        for _ in 0..1_500 {
            let dets: Vec<f64> = tets.iter().map(|&t| det(&p, t)).collect();
            let low = dets.iter().copied().fold(f64::INFINITY, f64::min);
            if low > TARGET {
                return Some(p);
            }
            let mut g = [[0.0; 3]; 8];
            for (&t, &v) in tets.iter().zip(&dets) {
                let w = (-(v - low) / TEMPERATURE).exp();
                let [a, b, c, d] = t.map(usize::from);
                let (ab, ac, ad) = (sub(p[b], p[a]), sub(p[c], p[a]), sub(p[d], p[a]));
                let (gb, gc, gd) = (cross(ac, ad), cross(ad, ab), cross(ab, ac));
                for k in 0..3 {
                    g[b][k] += w * gb[k];
                    g[c][k] += w * gc[k];
                    g[d][k] += w * gd[k];
                    g[a][k] -= w * (gb[k] + gc[k] + gd[k]);
                }
            }
            let norm = g.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
            if norm < 1e-12 {
                break;
            }
            for (q, gq) in p.iter_mut().zip(&g) {
                for k in 0..3 {
                    q[k] = (q[k] + 0.01 * gq[k] / norm).clamp(-1.0, 2.0);
                }
            }
        }
        if worst(&p, tets) > TARGET {
            return Some(p);
        }
    }
    None
}

/// The realisation `p` of `tets` rounded to the fewest decimals (up to 9) that keep
/// every tetrahedron clearly positive (volume ×6 above half the search's target), so
/// that the stored catalogue reads as short numbers; `p` itself if none does.
pub(crate) fn tidy(p: [[f64; 3]; 8], tets: &[[u8; 4]]) -> [[f64; 3]; 8] {
    (2..=9)
        .map(|decimals| {
            let scale = 10f64.powi(decimals);
            p.map(|q| q.map(|x| (x * scale).round() / scale))
        })
        .find(|r| worst(r, tets) > 0.5 * TARGET)
        .unwrap_or(p)
}
