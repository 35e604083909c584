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
    outside_in_regions(root, cells, touched, &untouched_regions(root, cells, touched), surface)
}

/// [`outside_among`] with the regions found beforehand: `regions[i]` names the region
/// of cell i, by any number below `cells.len()` that no other region has (such as
/// [`untouched_regions`] of the same cells in another order).
pub(super) fn outside_in_regions(
    root: &RootBox,
    cells: &[OctCell],
    touched: &[bool],
    regions: &[u32],
    surface: &TriangleBvh,
) -> Vec<usize> {
    // Each region's first cell, where its winding number is taken (on all cores).
    let mut first = vec![NONE; cells.len()];
    let mut roots: Vec<u32> = Vec::new();
    for k in (0..cells.len()).filter(|&k| !touched[k]) {
        let f = &mut first[regions[k] as usize];
        if *f == NONE {
            *f = k as u32;
            roots.push(k as u32);
        }
    }
    let root_inside: Vec<bool> =
        roots.par_iter().map(|&r| surface.contains(root.cell_box(cells[r as usize]).centre())).collect();
    let mut inside = vec![true; cells.len()];
    roots.iter().zip(root_inside).for_each(|(&r, i)| inside[r as usize] = i);
    (0..cells.len()).filter(|&k| !touched[k] && !inside[first[regions[k] as usize] as usize]).collect()
}

/// For each of the `cells`, the first cell (in their order) of its face-connected
/// region of untouched cells (a touched cell is its own).
pub(super) fn untouched_regions(root: &RootBox, cells: &[OctCell], touched: &[bool]) -> Vec<u32> {
    let siblings = Siblings::of(cells);
    let coarsest = cells.iter().map(|c| c.level).min().unwrap_or(0);
    // The untouched face neighbour (as large or larger) of a level-0 cell c towards d,
    // if any.
    let neighbour = |c: OctCell, d: [i64; 3]| {
        let p = [0, 1, 2].map(|k| i64::from(c.ijk[k]) + d[k]);
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
    let untouched = |j: u32| j != NONE && !touched[j as usize];
    // Face neighbours are joined on all cores: a region is named by its first cell
    // whatever the order of the unions. The level-0 cells look for theirs one by one.
    let regions = SharedDisjointSets::new(cells.len());
    siblings.top.par_iter().filter(|&(_, &k)| untouched(k)).for_each(|(_, &k)| {
        for d in FACES {
            let j = neighbour(cells[k as usize], d);
            if j != NONE {
                regions.union(k, j);
            }
        }
    });
    // The others family by family: a child meets a sibling on one side along each
    // axis, and on the other the child of the neighbouring family facing it (looked up
    // once for the four children on that side); where that family does not exist, a
    // coarser cell, as [`neighbour`] finds it. A finer neighbour finds the cell itself.
    (0..siblings.children.len()).into_par_iter().with_min_len(1 << 7).for_each(|g| {
        let (parent, family) = (siblings.parents[g], &siblings.children[g]);
        for k in 0..3 {
            let bit = 1 << k;
            for side in [0, bit] {
                let facing = |o: usize| untouched(family[o]) && (o & bit) == side;
                if !(0..8).any(facing) {
                    continue;
                }
                let mut across = parent.ijk.map(i64::from);
                across[k] += if side == 0 { -1 } else { 1 };
                let inside = root.contains(parent.level, across);
                let next = OctCell { level: parent.level, ijk: across.map(|x| x as u32) };
                let next_family = inside.then(|| siblings.by_parent.get(&next)).flatten();
                for o in (0..8).filter(|&o| facing(o)) {
                    let i = family[o];
                    if side == 0 && untouched(family[o | bit]) {
                        regions.union(i, family[o | bit]);
                    }
                    let j = match next_family {
                        Some(&h) => siblings.children[h as usize][o ^ bit],
                        None if inside && parent.level >= coarsest => (coarsest..=parent.level)
                            .rev()
                            .find_map(|l| siblings.index(next.ancestor(l)))
                            .unwrap_or(NONE),
                        None => NONE,
                    };
                    if untouched(j) {
                        regions.union(i, j);
                    }
                }
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
    /// The parents, in the order of `children`.
    parents: Vec<OctCell>,
    /// Per parent, the index of each child (bit k of the octant: the upper half along axis k).
    children: Vec<[u32; 8]>,
    /// The level-0 cells (which have no parent).
    top: FxHashMap<[u32; 3], u32>,
}

impl Siblings {
    fn of(cells: &[OctCell]) -> Siblings {
        let mut s = Siblings {
            by_parent: FxHashMap::default(),
            parents: Vec::new(),
            children: Vec::new(),
            top: FxHashMap::default(),
        };
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
                        s.parents.push(p);
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
        TriangleBvh::new(octahedron_triangles(c, r))
    }

    fn octahedron_triangles(c: [f64; 3], r: f64) -> Vec<[[f64; 3]; 3]> {
        let at = |k: usize, s: f64| {
            let mut p = c;
            p[k] += s * r;
            p
        };
        let (x, y, z, nx, ny, nz) = (at(0, 1.0), at(1, 1.0), at(2, 1.0), at(0, -1.0), at(1, -1.0), at(2, -1.0));
        vec![[x, y, z], [y, nx, z], [nx, ny, z], [ny, x, z], [y, x, nz], [nx, y, nz], [ny, nx, nz], [x, ny, nz]]
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

    /// Regions found on the cells in another order (named by that order's first cells)
    /// decide as those found in the cells' own order, on a closed surface and on one
    /// with a hole, where the region inside joins the one outside and its decision
    /// depends on where the winding number is taken: still at the region's first cell
    /// in the cells' order.
    #[test]
    fn regions_found_in_another_order_decide_the_same() {
        let root = RootBox { lo: [0.0; 3], cell: [1.0; 3], cells: [1; 3] };
        let mut open = octahedron_triangles([0.5; 3], 0.45);
        open.truncate(6);
        // The cells from the centre outwards, and the other way.
        let mut cells: Vec<OctCell> =
            (0..4096u32).map(|i| OctCell { level: 4, ijk: [i % 16, i / 16 % 16, i / 256] }).collect();
        let from_centre = |c: &OctCell| c.ijk.iter().map(|&x| (2 * i64::from(x) - 15).pow(2)).sum::<i64>();
        cells.sort_by_key(from_centre);
        let n = cells.len();
        let reversed: Vec<OctCell> = cells.iter().rev().copied().collect();
        for (surface, is_open) in [(octahedron([0.5; 3], 0.45), false), (TriangleBvh::new(open), true)] {
            let touched: Vec<bool> = cells.iter().map(|&c| surface.intersects_box(&root.cell_box(c))).collect();
            let reversed_touched: Vec<bool> = touched.iter().rev().copied().collect();
            let found = untouched_regions(&root, &reversed, &reversed_touched);
            let regions: Vec<u32> = (0..n).map(|i| found[n - 1 - i]).collect();
            let outside = outside_in_regions(&root, &cells, &touched, &regions, &surface);
            assert_eq!(outside, outside_among(&root, &cells, &touched, &surface));
            // Where the winding number is taken decides, with the hole.
            let mut other: Vec<usize> =
                outside_among(&root, &reversed, &reversed_touched, &surface).iter().map(|&i| n - 1 - i).collect();
            other.sort_unstable();
            assert_eq!(outside == other, !is_open, "{} and {} outside", outside.len(), other.len());
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
        // Level-2 cells of two level-0 cells, some split into level 3 and a few of those
        // into level 4 (beside level-2 cells: found two levels up), in a scrambled order.
        let mut cells: Vec<OctCell> = Vec::new();
        for i in 0..128u32 {
            let c = OctCell { level: 2, ijk: [i % 8, i / 8 % 4, i / 32] };
            if i % 5 != 0 {
                cells.push(c);
                continue;
            }
            for (n, child) in c.children().enumerate() {
                if i % 10 == 0 && n % 3 == 0 { cells.extend(child.children()) } else { cells.push(child) }
            }
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
