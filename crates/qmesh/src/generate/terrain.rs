//! A voxel terrain (2025 §7.4, step 1): a height map made by diamond-square, one layer
//! of voxels whose top corners follow it, each voxel's bottom face split in two
//! triangles along the same diagonal (which tells a query the bottom from the top and
//! fixes its orientation up to a half turn).

use crate::build::{CellKind, IndexedMesh};
use crate::random::SplitMix64;

/// What [`terrain`] makes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerrainOptions {
    /// Voxels along x.
    pub nx: usize,
    /// Voxels along y.
    pub ny: usize,
    /// Seed of the height map.
    pub seed: u64,
    /// How much of the random displacement is kept at each halving of the
    /// diamond-square step (0 < r ≤ 1; 0.5 gives the classic fractal terrain,
    /// smaller is smoother).
    pub roughness: f64,
    /// Height difference between the lowest and the highest top corner (0: every top
    /// at the same height).
    pub relief: f64,
    /// Height of the lowest top corner (the voxels' bottoms are at 0).
    pub base: f64,
}

impl Default for TerrainOptions {
    fn default() -> Self {
        TerrainOptions { nx: 128, ny: 128, seed: 1, roughness: 0.5, relief: 8.0, base: 1.0 }
    }
}

/// The voxels of a terrain over `[0, nx] × [0, ny]`: unit squares, bottoms at z = 0,
/// top corner (i, j) at `base + h(i, j)` with `h` the height map scaled to
/// `[0, relief]`. Each voxel is a polyhedron with 7 faces (4 sides, the top
/// quadrilateral, 2 bottom triangles along the (i, j)–(i+1, j+1) diagonal), faces
/// outward, so the map has 26 darts per voxel.
///
/// ```
/// use qmesh::generate::{TerrainOptions, terrain};
/// let t = terrain(&TerrainOptions { nx: 4, ny: 3, ..Default::default() });
/// assert_eq!((t.nb_cells(), t.points.len()), (12, 2 * 5 * 4));
/// ```
pub fn terrain(o: &TerrainOptions) -> IndexedMesh {
    let (nx, ny) = (o.nx, o.ny);
    let heights = height_map(nx + 1, ny + 1, o.seed, o.roughness);
    let (lo, hi) = heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| (a.min(h), b.max(h)));
    let scale = if hi > lo { o.relief / (hi - lo) } else { 0.0 };
    let mut m = IndexedMesh::new();
    let corners = (nx + 1) * (ny + 1);
    m.points.reserve(2 * corners);
    for j in 0..=ny {
        for i in 0..=nx {
            m.points.push([i as f64, j as f64, 0.0]);
        }
    }
    for j in 0..=ny {
        for i in 0..=nx {
            let h = heights[j * (nx + 1) + i];
            m.points.push([i as f64, j as f64, o.base + (h - lo) * scale]);
        }
    }
    let bottom = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let top = |i: usize, j: usize| (corners + j * (nx + 1) + i) as u32;
    for j in 0..ny {
        for i in 0..nx {
            let [b00, b10, b11, b01] = [bottom(i, j), bottom(i + 1, j), bottom(i + 1, j + 1), bottom(i, j + 1)];
            let [t00, t10, t11, t01] = [top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1)];
            let faces: [&[u32]; 7] = [
                &[b00, b01, b11],
                &[b00, b11, b10],
                &[t00, t10, t11, t01],
                &[b00, b10, t10, t00],
                &[b10, b11, t11, t10],
                &[b11, b01, t01, t11],
                &[b01, b00, t00, t01],
            ];
            let mut stream = vec![faces.len() as u32];
            for f in faces {
                stream.push(f.len() as u32);
                stream.extend_from_slice(f);
            }
            m.push_cell(CellKind::Polyhedron, &stream, None);
        }
    }
    m
}

/// Diamond-square heights on a `w × h` grid of corners (row-major, x fastest): made on
/// the smallest (2ᵏ + 1)² square holding it, then cropped. Corners start uniform in
/// [0, 1); each diamond and square step adds a uniform displacement in ±a/2, `a`
/// shrinking by `roughness` at each halving of the step.
pub fn height_map(w: usize, h: usize, seed: u64, roughness: f64) -> Vec<f64> {
    let mut side = 1;
    while side + 1 < w.max(h) {
        side *= 2;
    }
    let n = side + 1;
    let mut z = vec![0.0; n * n];
    let mut rng = SplitMix64(seed);
    for (i, j) in [(0, 0), (side, 0), (0, side), (side, side)] {
        z[j * n + i] = rng.unit();
    }
    let mut amplitude = 1.0;
    let mut step = side;
    while step > 1 {
        let half = step / 2;
        // Diamond: the centre of each square gets the mean of its 4 corners.
        for j in (half..n).step_by(step) {
            for i in (half..n).step_by(step) {
                let mean = (z[(j - half) * n + i - half]
                    + z[(j - half) * n + i + half]
                    + z[(j + half) * n + i - half]
                    + z[(j + half) * n + i + half])
                    / 4.0;
                z[j * n + i] = mean + amplitude * (rng.unit() - 0.5);
            }
        }
        // Square: each edge midpoint gets the mean of its 2 to 4 diamond neighbours.
        for j in (0..n).step_by(half) {
            let first = if (j / half) % 2 == 0 { half } else { 0 };
            for i in (first..n).step_by(step) {
                let mut sum = 0.0;
                let mut count = 0.0;
                for (di, dj) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                    let (x, y) = (i as i64 + di * half as i64, j as i64 + dj * half as i64);
                    if (0..n as i64).contains(&x) && (0..n as i64).contains(&y) {
                        sum += z[y as usize * n + x as usize];
                        count += 1.0;
                    }
                }
                z[j * n + i] = sum / count + amplitude * (rng.unit() - 0.5);
            }
        }
        amplitude *= roughness;
        step = half;
    }
    (0..h).flat_map(|j| z[j * n..j * n + w].to_vec()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{BuildOptions, build_volume_map};

    #[test]
    fn every_voxel_is_one_volume_of_26_darts_sewn_to_its_neighbours() {
        let t = terrain(&TerrainOptions { nx: 5, ny: 4, seed: 7, ..Default::default() });
        let (map, _) = build_volume_map(&t, &BuildOptions::default()).unwrap();
        let c = map.count_cells();
        assert_eq!((c.volumes, c.darts), (20, 20 * 26));
        assert!(map.is_valid().is_empty());
        // Boundary: 20 tops + 40 bottom triangles + 2·(5 + 4) sides.
        assert_eq!(map.boundary_faces(), 20 + 40 + 18);
    }

    #[test]
    fn heights_span_the_relief_and_depend_on_the_seed() {
        let o = TerrainOptions { nx: 9, ny: 6, seed: 3, roughness: 0.6, relief: 5.0, base: 1.0 };
        let tops =
            |o: &TerrainOptions| terrain(o).points[(o.nx + 1) * (o.ny + 1)..].iter().map(|p| p[2]).collect::<Vec<_>>();
        let z = tops(&o);
        let (lo, hi) = z.iter().fold((f64::MAX, f64::MIN), |(a, b), &h| (a.min(h), b.max(h)));
        assert!((lo - 1.0).abs() < 1e-12 && (hi - 6.0).abs() < 1e-12, "{lo} {hi}");
        assert_eq!(z, tops(&o), "same seed, same terrain");
        assert_ne!(z, tops(&TerrainOptions { seed: 4, ..o }));
        let flat = tops(&TerrainOptions { relief: 0.0, ..o });
        assert!(flat.iter().all(|&h| h == 1.0));
    }

    #[test]
    fn diamond_square_fills_every_corner() {
        for (w, h) in [(2, 2), (3, 3), (5, 5), (6, 9), (129, 129)] {
            let z = height_map(w, h, 11, 0.5);
            assert_eq!(z.len(), w * h);
            assert!(z.iter().all(|v| v.is_finite()));
            // A filled corner is almost never exactly 0 (the grid starts at 0).
            assert!(z.iter().filter(|&&v| v == 0.0).count() <= 1, "{w}×{h}");
        }
    }
}
