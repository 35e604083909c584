//! Volumes that are axis-aligned boxes (octree cells, possibly with vertices inserted
//! on their edges and faces): their box, their octree cell, and the papers' corner
//! flags computed from the box (2022 §7: a dart is flagged when it starts at an
//! original corner of its cell and runs along one of the cell's edges).

use super::octree::{OctCell, RootBox};
use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};
use crate::geom::Aabb;

/// Tolerance for "on the corner lattice", relative to the cell size.
pub(crate) const LATTICE_TOL: f64 = 1e-6;

/// The box of the volume of `d`.
pub(crate) fn volume_box(map: &CMap3, d: Dart, w: &mut OrbitWalker) -> Aabb {
    Aabb::of(w.collect(map, d, Orbit::Volume).iter().map(|&x| map.point(x)))
}

/// The box of the volume of `d`, a child (octant) of the box `parent`, read from one
/// of its vertices off the parent's centre planes: the child's faces on the parent's
/// faces hold the parent's corner, and each face on a centre plane has one of them
/// across an edge. Falls back to [`volume_box`] if none is found so.
pub(crate) fn child_box(map: &CMap3, d: Dart, parent: &Aabb, w: &mut OrbitWalker) -> Aabb {
    let (c, e) = (parent.centre(), parent.extent());
    let off_centre = |p: &[f64; 3]| (0..3).all(|k| (p[k] - c[k]).abs() > LATTICE_TOL * e[k]);
    let across = map.face_cycle(d).filter_map(|x| map.beta(x, 2)).flat_map(|y| map.face_cycle(y));
    let Some(p) = map.face_cycle(d).chain(across).map(|x| map.point(x)).find(off_centre) else {
        return volume_box(map, d, w);
    };
    let mut b = *parent;
    for k in 0..3 {
        if p[k] > c[k] {
            b.lo[k] = c[k];
        } else {
            b.hi[k] = c[k];
        }
    }
    b
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

/// The darts of `volume` (whose box is `b`) that start at a corner of the box and run
/// along a box edge (their end shares two coordinates): the flags of the box patterns.
pub(crate) fn box_corner_darts<'a>(map: &'a CMap3, volume: &'a [Dart], b: &'a Aabb) -> impl Iterator<Item = Dart> + 'a {
    volume.iter().copied().filter(move |&x| {
        let p = map.point(x);
        is_corner(b, p) && along_box_edge(b, p, map.point(map.next(x)))
    })
}

/// Whether the segment p-q of a volume with box `b` runs along one axis (its ends share
/// two coordinates).
pub(crate) fn along_box_edge(b: &Aabb, p: [f64; 3], q: [f64; 3]) -> bool {
    let e = b.extent();
    (0..3).filter(|&k| (p[k] - q[k]).abs() <= LATTICE_TOL * e[k]).count() == 2
}

/// Volumes per walker when `n` volumes are walked on all cores: a few chunks per thread,
/// as each long-lived walker takes a bit set as large as the map.
pub(crate) fn walker_chunk(n: usize) -> usize {
    n.div_ceil(4 * rayon::current_num_threads()).max(1024)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{BuildOptions, build_map};

    /// The eight cells of a 2×2×2 grid are the octants of its box: read from any of
    /// their darts, each child box is the volume's own box.
    #[test]
    fn child_boxes_are_the_volumes_boxes_from_every_dart() {
        let (map, _) = build_map(crate::generate::hex_grid(2, 2, 2), &BuildOptions::default()).unwrap();
        let mut w = OrbitWalker::new();
        let parent = Aabb::of(map.positions().iter().copied());
        let mut octants = std::collections::BTreeSet::new();
        for v in map.cells(Orbit::Volume) {
            let own = volume_box(&map, v, &mut w);
            octants.insert(own.lo.map(|x| x as i64));
            for d in map.orbit(v, Orbit::Volume) {
                let b = child_box(&map, d, &parent, &mut w);
                assert_eq!((b.lo, b.hi), (own.lo, own.hi), "from dart {}", d.raw());
            }
        }
        assert_eq!(octants.len(), 8);
    }
}
