//! Which cells of an octree lie outside the surface (2022 §7.1, "remove the volumes
//! outside the object"): the untouched cells are grouped into face-connected regions,
//! and one winding number per region decides.

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::octree::{OctCell, RootBox};
use crate::disjoint_sets::SharedDisjointSets;
use crate::geom::TriangleBvh;

/// No cell in a sibling slot.
const NONE: u32 = u32::MAX;

/// The indices of the `cells` (distinct leaves of one octree) outside the surface and
/// untouched by it (`touched[i]`: the surface meets cell i). The untouched cells are
/// grouped into face-connected regions (the surface cannot separate two face
/// neighbours it touches neither of); one winding number per region decides, at the
/// centre of its first cell in the order of `cells`. A neighbour is looked for at its
/// own size and then coarser, down to the coarsest level among `cells`.
pub fn outside_among(root: &RootBox, cells: &[OctCell], touched: &[bool], surface: &TriangleBvh) -> Vec<usize> {
    let regions = untouched_regions(root, cells, touched);
    // One winding number per region (at its root, its first cell), on all cores.
    let roots: Vec<u32> =
        (0..cells.len() as u32).filter(|&k| !touched[k as usize] && regions[k as usize] == k).collect();
    let root_inside: Vec<bool> =
        roots.par_iter().map(|&r| surface.contains(root.cell_box(cells[r as usize]).centre())).collect();
    let mut inside = vec![true; cells.len()];
    roots.iter().zip(root_inside).for_each(|(&r, i)| inside[r as usize] = i);
    (0..cells.len()).filter(|&k| !touched[k] && !inside[regions[k] as usize]).collect()
}

/// For each of the `cells`, the first cell (in their order) of its face-connected
/// region of untouched cells (a touched cell is its own).
fn untouched_regions(root: &RootBox, cells: &[OctCell], touched: &[bool]) -> Vec<u32> {
    let siblings = Siblings::of(cells);
    let coarsest = cells.iter().map(|c| c.level).min().unwrap_or(0);
    // The untouched face neighbour (as large or larger) of cell c towards d, if any;
    // `family`: the indices of c and its siblings.
    let neighbour = |c: OctCell, family: Option<&[u32; 8]>, d: [i64; 3]| {
        let p = [0, 1, 2].map(|k| i64::from(c.ijk[k]) + d[k]);
        if let Some(f) = family.filter(|_| p.iter().zip(c.ijk).all(|(&a, b)| a >> 1 == i64::from(b >> 1))) {
            // A sibling: the same parent.
            let j = f[(0..3).map(|k| ((p[k] & 1) as usize) << k).sum::<usize>()];
            return if j != NONE && !touched[j as usize] { j } else { NONE };
        }
        if !root.contains(c.level, p) {
            return NONE;
        }
        let same = OctCell { level: c.level, ijk: p.map(|x| x as u32) };
        // Leaves do not overlap: the first leaf met is the only one.
        match (coarsest..=c.level).rev().find_map(|l| siblings.index(same.ancestor(l))) {
            Some(j) if !touched[j as usize] => j,
            _ => NONE,
        }
    };
    const FACES: [[i64; 3]; 6] = [[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]];
    // Face neighbours are joined on all cores: a region is named by its first cell
    // whatever the order of the unions.
    let regions = SharedDisjointSets::new(cells.len());
    (0..cells.len()).into_par_iter().with_min_len(1 << 10).filter(|&k| !touched[k]).for_each(|k| {
        let c = cells[k];
        let family = siblings.family(c);
        for d in FACES {
            let j = neighbour(c, family, d);
            if j != NONE {
                regions.union(k as u32, j);
            }
        }
    });
    (0..cells.len() as u32).into_par_iter().with_min_len(1 << 12).map(|k| regions.find(k)).collect()
}

/// Cells by their parent: each parent's children's indices, by octant. A refinement
/// lists the eight children of a cell one after the other, so the table holds one
/// entry per parent, and most entries are made without hashing.
struct Siblings {
    by_parent: FxHashMap<OctCell, u32>,
    /// Per parent, the index of each child (bit k of the octant: the upper half along axis k).
    children: Vec<[u32; 8]>,
    /// The level-0 cells (which have no parent).
    top: FxHashMap<[u32; 3], u32>,
}

impl Siblings {
    fn of(cells: &[OctCell]) -> Siblings {
        let mut s = Siblings { by_parent: FxHashMap::default(), children: Vec::new(), top: FxHashMap::default() };
        let mut last: Option<(OctCell, usize)> = None;
        for (i, &c) in cells.iter().enumerate() {
            if c.level == 0 {
                s.top.insert(c.ijk, i as u32);
                continue;
            }
            let p = c.ancestor(c.level - 1);
            let group = match last {
                Some((q, g)) if q == p => g,
                _ => {
                    let next = s.children.len() as u32;
                    let g = *s.by_parent.entry(p).or_insert(next) as usize;
                    if g == s.children.len() {
                        s.children.push([NONE; 8]);
                    }
                    last = Some((p, g));
                    g
                }
            };
            s.children[group][octant(c)] = i as u32;
        }
        s
    }

    /// The index of `c` among the cells, if it is one of them.
    fn index(&self, c: OctCell) -> Option<u32> {
        if c.level == 0 {
            return self.top.get(&c.ijk).copied();
        }
        Some(self.family(c)?[octant(c)]).filter(|&i| i != NONE)
    }

    /// The indices of the children of the parent of `c`, if any of them is a cell.
    fn family(&self, c: OctCell) -> Option<&[u32; 8]> {
        let g = *self.by_parent.get(&c.ancestor(c.level.checked_sub(1)?))?;
        Some(&self.children[g as usize])
    }
}

/// Which child of its parent `c` is.
fn octant(c: OctCell) -> usize {
    (0..3).map(|k| ((c.ijk[k] & 1) as usize) << k).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An outward-oriented octahedron: the points at L1 distance `r` from `c`.
    fn octahedron(c: [f64; 3], r: f64) -> TriangleBvh {
        let at = |k: usize, s: f64| {
            let mut p = c;
            p[k] += s * r;
            p
        };
        let (x, y, z, nx, ny, nz) = (at(0, 1.0), at(1, 1.0), at(2, 1.0), at(0, -1.0), at(1, -1.0), at(2, -1.0));
        TriangleBvh::new(vec![
            [x, y, z],
            [y, nx, z],
            [nx, ny, z],
            [ny, x, z],
            [y, x, nz],
            [nx, y, nz],
            [ny, nx, nz],
            [x, ny, nz],
        ])
    }

    #[test]
    fn regions_decide_like_a_winding_number_per_cell_in_any_order() {
        let root = RootBox { lo: [0.0; 3], cell: [1.0; 3], cells: [1; 3] };
        let surface = octahedron([0.5; 3], 0.45);
        // The level-3 cells, one of them (at a corner, outside) split into level 4.
        let split = OctCell { level: 3, ijk: [0, 0, 0] };
        let mut cells: Vec<OctCell> = (0..512u32)
            .map(|i| OctCell { level: 3, ijk: [i % 8, i / 8 % 8, i / 64] })
            .filter(|&c| c != split)
            .collect();
        cells.extend(split.children());
        for order in [false, true] {
            if order {
                cells.reverse();
            }
            let touched: Vec<bool> = cells.iter().map(|&c| surface.intersects_box(&root.cell_box(c))).collect();
            let found = outside_among(&root, &cells, &touched, &surface);
            let expected: Vec<usize> = (0..cells.len())
                .filter(|&i| !touched[i] && !surface.contains(root.cell_box(cells[i]).centre()))
                .collect();
            assert_eq!(found, expected);
            let inside = (0..cells.len()).filter(|&i| !touched[i]).count() - found.len();
            assert!(found.len() > 8 && inside > 0, "{} outside, {inside} inside", found.len());
        }
    }

    /// Whether two boxes share a piece of face.
    fn share_a_face(a: &crate::geom::Aabb, b: &crate::geom::Aabb) -> bool {
        let touching = (0..3).filter(|&k| a.hi[k] == b.lo[k] || b.hi[k] == a.lo[k]).count();
        let overlapping = (0..3).filter(|&k| a.lo[k] < b.hi[k] && b.lo[k] < a.hi[k]).count();
        touching == 1 && overlapping == 2
    }

    #[test]
    fn regions_are_the_face_connected_untouched_cells() {
        let root = RootBox { lo: [0.0; 3], cell: [1.0; 3], cells: [2, 1, 1] };
        let surface = octahedron([1.0, 0.5, 0.5], 0.8);
        // Level-2 cells of two level-0 cells, some split into level 3, in a scrambled order.
        let mut cells: Vec<OctCell> = Vec::new();
        for i in 0..128u32 {
            let c = OctCell { level: 2, ijk: [i % 8, i / 8 % 4, i / 32] };
            if i % 5 == 0 { cells.extend(c.children()) } else { cells.push(c) }
        }
        cells.sort_by_key(|c| (c.ijk[1] * 7 + c.ijk[0] * 3 + c.ijk[2]) % 11);
        let boxes: Vec<_> = cells.iter().map(|&c| root.cell_box(c)).collect();
        let touched: Vec<bool> = boxes.iter().map(|b| surface.intersects_box(b)).collect();
        let regions = untouched_regions(&root, &cells, &touched);
        // Brute force: the smallest index reachable through untouched face neighbours.
        let mut expected: Vec<u32> = (0..cells.len() as u32).collect();
        loop {
            let mut changed = false;
            for i in (0..cells.len()).filter(|&i| !touched[i]) {
                for j in (0..cells.len()).filter(|&j| !touched[j] && share_a_face(&boxes[i], &boxes[j])) {
                    if expected[j] < expected[i] {
                        expected[i] = expected[j];
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        assert_eq!(regions, expected);
        let mut distinct: Vec<u32> = (0..cells.len()).filter(|&i| !touched[i]).map(|i| regions[i]).collect();
        distinct.sort_unstable();
        distinct.dedup();
        assert!(distinct.len() >= 2 && (0..cells.len()).any(|i| touched[i]), "{} regions", distinct.len());
    }

    #[test]
    fn siblings_name_every_cell_and_no_other() {
        let mut cells: Vec<OctCell> = OctCell::ROOT.children().collect();
        let first = cells.remove(0);
        cells.extend(first.children());
        let s = Siblings::of(&cells);
        for (i, &c) in cells.iter().enumerate() {
            assert_eq!(s.index(c), Some(i as u32));
        }
        assert_eq!(s.index(first), None);
        assert_eq!(s.index(OctCell::ROOT), None);
        assert_eq!(s.index(OctCell { level: 2, ijk: [3, 3, 3] }), None);
    }
}
