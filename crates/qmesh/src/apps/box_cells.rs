//! Volumes that are axis-aligned boxes (octree cells, possibly with vertices inserted
//! on their edges and faces): their box, their octree cell, and the papers' corner
//! flags computed from the box (2022 §7: a dart is flagged when it starts at an
//! original corner of its cell and runs along one of the cell's edges).

use super::octree::{OctCell, RootBox};
use crate::cmap::{CMap3, Dart, Mark, Orbit, OrbitWalker};
use crate::geom::Aabb;

/// Tolerance for "on the corner lattice", relative to the cell size.
pub(crate) const LATTICE_TOL: f64 = 1e-6;

/// The box of the volume of `d`.
pub(crate) fn volume_box(map: &CMap3, d: Dart, w: &mut OrbitWalker) -> Aabb {
    Aabb::of(w.collect(map, d, Orbit::Volume).iter().map(|&x| map.point(x)))
}

fn on_side(b: &Aabb, k: usize, x: f64) -> bool {
    let tol = LATTICE_TOL * b.extent()[k];
    (x - b.lo[k]).abs() <= tol || (x - b.hi[k]).abs() <= tol
}

/// Whether `p` is a corner of box `b`.
pub(crate) fn is_corner(b: &Aabb, p: [f64; 3]) -> bool {
    (0..3).all(|k| on_side(b, k, p[k]))
}

/// The octree cell a box is.
pub(crate) fn cell_of(root: RootBox, b: &Aabb) -> OctCell {
    let level = root.level_of(b.extent()[0]);
    let s = root.step(level);
    OctCell { level, ijk: [0, 1, 2].map(|k| ((b.lo[k] - root.lo[k]) / s[k]).round().max(0.0) as u32) }
}

/// Flags with `mark` the darts of the volume of `d` (whose box is `b`) that start at a
/// corner of the box and run along a box edge (their end shares two coordinates).
pub(crate) fn flag_box_corners(map: &mut CMap3, mark: Mark, d: Dart, b: &Aabb, w: &mut OrbitWalker) {
    let volume = w.collect(map, d, Orbit::Volume).to_vec();
    flag_box_corners_of(map, mark, &volume, b);
}

/// [`flag_box_corners`] on the darts of a volume already collected.
pub(crate) fn flag_box_corners_of(map: &mut CMap3, mark: Mark, volume: &[Dart], b: &Aabb) {
    let e = b.extent();
    for &x in volume {
        let (p, q) = (map.point(x), map.point(map.next(x)));
        let along_edge = (0..3).filter(|&k| (p[k] - q[k]).abs() <= LATTICE_TOL * e[k]).count() == 2;
        if along_edge && is_corner(b, p) {
            map.mark(x, mark);
        }
    }
}
