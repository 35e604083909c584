//! A voxel terrain (2025 §7.4, step 1): a height map made by diamond-square, one layer
//! of voxels whose top corners follow it, each voxel's bottom face split in two
//! triangles along the same diagonal (which tells a query the bottom from the top and
//! fixes its orientation up to a half turn).

use crate::build::{CellKind, IndexedMesh};
use crate::cmap::{CMap3, Dart};
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
    let mut m = IndexedMesh { points: voxel_points(o), ..IndexedMesh::new() };
    for j in 0..ny {
        for i in 0..nx {
            let corner = voxel_corners(nx, ny, i, j);
            let mut stream = vec![VOXEL_FACES.len() as u32];
            for f in VOXEL_FACES {
                stream.push(f.len() as u32);
                stream.extend(f.iter().map(|&k| corner[k]));
            }
            m.push_cell(CellKind::Polyhedron, &stream, None);
        }
    }
    m
}

/// The corners of [`terrain`]: the bottoms (z = 0) row by row, then the tops.
fn voxel_points(o: &TerrainOptions) -> Vec<[f64; 3]> {
    let (nx, ny) = (o.nx, o.ny);
    let heights = height_map(nx + 1, ny + 1, o.seed, o.roughness);
    let (lo, hi) = heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| (a.min(h), b.max(h)));
    let scale = if hi > lo { o.relief / (hi - lo) } else { 0.0 };
    let mut points = Vec::with_capacity(2 * (nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            points.push([i as f64, j as f64, 0.0]);
        }
    }
    for &h in &heights {
        let k = points.len() - (nx + 1) * (ny + 1);
        points.push([(k % (nx + 1)) as f64, (k / (nx + 1)) as f64, o.base + (h - lo) * scale]);
    }
    points
}

/// A voxel's faces over its corners 0–3 = bottom (i, j), (i+1, j), (i+1, j+1),
/// (i, j+1) and 4–7 the tops above them, counter-clockwise seen from outside: the two
/// bottom triangles, the top, then the sides facing −y, +x, +y, −x.
const VOXEL_FACES: [&[usize]; 7] =
    [&[0, 3, 2], &[0, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];

/// Point indices of voxel (i, j)'s 8 corners in [`terrain`]'s points.
fn voxel_corners(nx: usize, ny: usize, i: usize, j: usize) -> [u32; 8] {
    let at = |i: usize, j: usize, level: usize| (level * (nx + 1) * (ny + 1) + j * (nx + 1) + i) as u32;
    [
        at(i, j, 0),
        at(i + 1, j, 0),
        at(i + 1, j + 1, 0),
        at(i, j + 1, 0),
        at(i, j, 1),
        at(i + 1, j, 1),
        at(i + 1, j + 1, 1),
        at(i, j + 1, 1),
    ]
}

/// The map of [`terrain`]'s mesh, made directly: every voxel's 26 darts from one
/// template (faces and β2 inside the voxel), β3 to the voxel before it along x and along
/// y. The same map as `build_volume_map(&terrain(o))` up to dart numbering, in a
/// fraction of its time (2025 Table 2, step 1).
///
/// ```
/// use qmesh::generate::{TerrainOptions, terrain_map};
/// let m = terrain_map(&TerrainOptions { nx: 4, ny: 3, ..Default::default() });
/// assert_eq!((m.count_cells().volumes, m.nb_darts()), (12, 12 * 26));
/// assert!(m.is_valid().is_empty());
/// ```
pub fn terrain_map(o: &TerrainOptions) -> CMap3 {
    let (nx, ny) = (o.nx, o.ny);
    let t = VoxelTemplate::new();
    let n = t.origin.len();
    let mut m = CMap3::with_positions(voxel_points(o), nx * ny * n);
    let mut darts: Vec<Dart> = Vec::with_capacity(nx * ny * n);
    for j in 0..ny {
        for i in 0..nx {
            let corner = voxel_corners(nx, ny, i, j);
            let base = darts.len();
            darts.extend(t.origin.iter().map(|&k| m.create_dart(corner[k])));
            let dart = |voxel: usize, k: usize| darts[voxel * n + k];
            let v = j * nx + i;
            for k in 0..n {
                m.link(darts[base + k], 1, darts[base + t.next[k]]);
                if t.twin[k] > k {
                    m.link(darts[base + k], 2, darts[base + t.twin[k]]);
                }
            }
            if i > 0 {
                for &(mine, theirs) in &t.minus_x {
                    m.link(dart(v, mine), 3, dart(v - 1, theirs));
                }
            }
            if j > 0 {
                for &(mine, theirs) in &t.minus_y {
                    m.link(dart(v, mine), 3, dart(v - nx, theirs));
                }
            }
        }
    }
    m
}

/// One voxel's darts, numbered face by face in [`VOXEL_FACES`] order, each face run
/// the other way (the map's positive orientation is clockwise seen from outside).
struct VoxelTemplate {
    /// Corner (0–7) each dart starts at.
    origin: Vec<usize>,
    /// β1, as a dart number.
    next: Vec<usize>,
    /// β2 inside the voxel.
    twin: Vec<usize>,
    /// β3 pairs (this voxel's dart, the dart of the voxel before it along x).
    minus_x: Vec<(usize, usize)>,
    /// The same along y.
    minus_y: Vec<(usize, usize)>,
}

impl VoxelTemplate {
    fn new() -> VoxelTemplate {
        let (mut origin, mut next, mut face_of) = (Vec::new(), Vec::new(), Vec::new());
        for (f, corners) in VOXEL_FACES.iter().enumerate() {
            let start = origin.len();
            let reversed: Vec<usize> = std::iter::once(corners[0]).chain(corners[1..].iter().rev().copied()).collect();
            for (k, &c) in reversed.iter().enumerate() {
                origin.push(c);
                next.push(start + (k + 1) % reversed.len());
                face_of.push(f);
            }
        }
        let target = |d: usize| origin[next[d]];
        let twin = (0..origin.len())
            .map(|d| {
                (0..origin.len()).find(|&e| origin[e] == target(d) && target(e) == origin[d]).expect("closed voxel")
            })
            .collect();
        // β3 pairs each dart of face `f` with the neighbour's dart of face `g` on the same
        // edge, running the other way (it starts where the first ends); `same` maps this
        // voxel's corners of the face to the neighbour's.
        let pairs = |f: usize, g: usize, same: [(usize, usize); 4]| {
            let theirs = |c: usize| same.iter().find(|p| p.0 == c).expect("corner of the face").1;
            (0..origin.len())
                .filter(|&d| face_of[d] == f)
                .map(|d| {
                    let (from, to) = (theirs(target(d)), theirs(origin[d]));
                    let e = (0..origin.len()).find(|&e| face_of[e] == g && origin[e] == from && target(e) == to);
                    (d, e.expect("the faces match"))
                })
                .collect()
        };
        // −x face (6) against the +x face (4) of voxel (i−1, j); −y (3) against +y (5).
        let minus_x = pairs(6, 4, [(0, 1), (3, 2), (4, 5), (7, 6)]);
        let minus_y = pairs(3, 5, [(0, 3), (1, 2), (4, 7), (5, 6)]);
        VoxelTemplate { origin, next, twin, minus_x, minus_y }
    }
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
    fn the_direct_map_is_the_built_map() {
        use crate::query::{Condition, MatchOptions, Query, QuerySet, find_matches};
        let o = TerrainOptions { nx: 5, ny: 4, seed: 2, ..Default::default() };
        let direct = terrain_map(&o);
        assert!(direct.is_valid().is_empty(), "{:?}", direct.is_valid().first());
        let (built, _) = build_volume_map(&terrain(&o), &BuildOptions::default()).unwrap();
        assert_eq!(direct.count_cells(), built.count_cells());
        assert_eq!(direct.positions(), built.positions());
        // Isomorphic, vertex for vertex: the whole built map, ε on its boundary, matches
        // the direct one at a dart with the same origin, and every volume is positive.
        let q = Query::new("whole", built.clone(), |_| Condition::Boundary).unwrap();
        let found = find_matches(&direct, &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
        assert_eq!(found.per_query[0], 1);
        let start = found.matches[0].start;
        assert_eq!(direct.vertex_of(start), built.vertex_of(q.labelling().darts[0]));
        let mut w = crate::cmap::OrbitWalker::new();
        for d in direct.cells(crate::cmap::Orbit::Volume) {
            assert!(crate::geom::signed_volume_of_map_volume(&direct, d, &mut w) > 0.0);
        }
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
