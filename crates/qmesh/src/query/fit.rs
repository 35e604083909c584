//! Affine fits from a query's vertex positions to a match's (beyond the paper, its §8
//! future work): among the automorphic images of a match, the one whose fit has the
//! smallest residual — ties broken by the fit closest to the query's own orientation —
//! so every copy of a part is edited the same way.

/// The query side of the fit, computed once: one label per query vertex, and the
/// inverse of Σ [q 1][q 1]ᵀ over their positions.
#[derive(Clone, Debug)]
pub(crate) struct AffineFit {
    labels: Vec<u32>,
    points: Vec<[f64; 3]>,
    inverse: [[f64; 4]; 4],
}

impl AffineFit {
    /// None when the points do not span 3D (no unique affine map).
    pub(crate) fn new(labels: Vec<u32>, points: Vec<[f64; 3]>) -> Option<AffineFit> {
        let mut m = [[0.0; 4]; 4];
        for q in &points {
            let h = [q[0], q[1], q[2], 1.0];
            for (i, row) in m.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x += h[i] * h[j];
                }
            }
        }
        invert(m).map(|inverse| AffineFit { labels, points, inverse })
    }

    /// (relative residual, ‖A − I‖²) of the least-squares affine map A·q + t sending
    /// the query points to the positions `position(label)`. The relative residual is
    /// the root-mean-square distance of the positions from the fit over their
    /// root-mean-square distance from their centroid: 0 for an affine copy of the
    /// query, 0.01 for one 1 % off, at most 1, whatever the units.
    #[allow(clippy::needless_range_loop)] // matrix products read best with indices
    pub(crate) fn score(&self, position: impl Fn(u32) -> [f64; 3]) -> (f64, f64) {
        let p: Vec<[f64; 3]> = self.labels.iter().map(|&l| position(l)).collect();
        let mut b = [[0.0; 4]; 3];
        for (q, p) in self.points.iter().zip(&p) {
            let h = [q[0], q[1], q[2], 1.0];
            for i in 0..3 {
                for j in 0..4 {
                    b[i][j] += p[i] * h[j];
                }
            }
        }
        let mut m = [[0.0; 4]; 3];
        for i in 0..3 {
            for j in 0..4 {
                m[i][j] = (0..4).map(|k| b[i][k] * self.inverse[k][j]).sum();
            }
        }
        let residual: f64 = self
            .points
            .iter()
            .zip(&p)
            .map(|(q, p)| {
                (0..3).map(|i| (m[i][0] * q[0] + m[i][1] * q[1] + m[i][2] * q[2] + m[i][3] - p[i]).powi(2)).sum::<f64>()
            })
            .sum();
        let turn =
            (0..3).map(|i| (0..3).map(|j| (m[i][j] - if i == j { 1.0 } else { 0.0 }).powi(2)).sum::<f64>()).sum();
        // The constant map to the centroid leaves exactly the spread as its residual,
        // so the least-squares residual is at most the spread.
        let spread = spread_around_centroid(&p);
        (if spread > 0.0 { (residual / spread).sqrt() } else { 0.0 }, turn)
    }
}

/// Σ ‖p − c‖² over the points, c their centroid.
fn spread_around_centroid(points: &[[f64; 3]]) -> f64 {
    use crate::geom::{centroid, dot, sub};
    let c = centroid(points.iter().copied());
    points.iter().map(|&p| dot(sub(p, c), sub(p, c))).sum()
}

/// Gauss–Jordan inverse with partial pivoting; None when singular.
#[allow(clippy::needless_range_loop)]
fn invert(mut a: [[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let mut inv = [[0.0; 4]; 4];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let scale = a.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs())).max(1e-300);
    for c in 0..4 {
        let p = (c..4).max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))?;
        if a[p][c].abs() < 1e-12 * scale {
            return None;
        }
        a.swap(c, p);
        inv.swap(c, p);
        let d = a[c][c];
        for j in 0..4 {
            a[c][j] /= d;
            inv[c][j] /= d;
        }
        for r in 0..4 {
            if r != c {
                let f = a[r][c];
                for j in 0..4 {
                    a[r][j] -= f * a[c][j];
                    inv[r][j] -= f * inv[c][j];
                }
            }
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fits_a_rotation_exactly_and_measures_the_turn() {
        let q: Vec<[f64; 3]> = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [1., 1., 1.]];
        let fit = AffineFit::new((1..=5).collect(), q.clone()).unwrap();
        let (r, t) = fit.score(|l| {
            let p = q[l as usize - 1];
            [p[0] + 3.0, p[1], p[2]]
        });
        assert!(r < 1e-18 && t < 1e-18, "{r} {t}");
        let (r, t) = fit.score(|l| {
            let p = q[l as usize - 1];
            [-p[1], p[0], p[2]] // a quarter turn about z
        });
        assert!(r < 1e-18 && (t - 4.0).abs() < 1e-9, "{r} {t}");
        assert!(AffineFit::new(vec![1, 2, 3], vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]]).is_none());
    }

    /// Flatness is judged relative to the points' size: a square 1000 wide and 10⁻⁹
    /// high is flat (no affine fit), one 100 high is not.
    #[test]
    fn flat_point_sets_have_no_fit_whatever_their_size() {
        let slab = |h: f64| {
            let pts = vec![[0., 0., 0.], [1000., 0., 0.], [0., 1000., 0.], [1000., 1000., h], [500., 500., 0.]];
            AffineFit::new((1..=5).collect(), pts)
        };
        assert!(slab(1e-9).is_none());
        assert!(slab(100.0).is_some());
    }

    /// The residual is relative to the spread of the matched positions: a distorted
    /// copy scores the same in millimetres as in metres, above 0 and at most 1.
    #[test]
    fn the_residual_is_relative_whatever_the_units() {
        let q: Vec<[f64; 3]> = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [1., 1., 1.]];
        let fit = AffineFit::new((1..=5).collect(), q.clone()).unwrap();
        let raised = |scale: f64| {
            let q = &q;
            move |l: u32| {
                let p = q[l as usize - 1];
                let lift = if l == 5 { 0.5 } else { 0.0 };
                [scale * p[0], scale * p[1], scale * (p[2] + lift)]
            }
        };
        let (r1, _) = fit.score(raised(1.0));
        let (r1000, _) = fit.score(raised(1000.0));
        assert!(r1 > 1e-3 && r1 < 1.0, "{r1}");
        assert!((r1000 - r1).abs() < 1e-12, "{r1} in metres, {r1000} in millimetres");
        // All five positions at one point: nothing to fit against, no residual.
        assert_eq!(fit.score(|_| [2.0, 3.0, 4.0]).0, 0.0);
        // Positions that no affine map of the query explains better than their
        // centroid: weights (2, −1, −1, −1, 1) are orthogonal to x, y, z and 1 over
        // the query's points, so the fit is the constant map and the residual is 1.
        let w = [2.0, -1.0, -1.0, -1.0, 1.0];
        let (r, _) = fit.score(|l| [3.0 * w[l as usize - 1] + 7.0, 4.0, -2.0]);
        assert!((r - 1.0).abs() < 1e-9, "{r}");
        // Scattered positions with no affine relation to the query stay at most 1.
        let far = [[0., 0., 0.], [0., 0., 9.], [5., 0., 0.], [0., 7., 0.], [-3., -3., -3.]];
        let (r, _) = fit.score(|l| far[l as usize - 1]);
        assert!(r > 0.0 && r <= 1.0, "{r}");
    }
}
