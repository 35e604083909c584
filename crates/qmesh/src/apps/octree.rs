//! The octree of 2022 Algorithm 5 as plain boxes: the root cube around a surface, leaf
//! cells addressed by level and integer position, refinement of the cells the surface
//! touches and 2:1 balance over face and edge neighbours. This is the hand-written
//! ("direct") counterpart of the query-replace subdivision in `subdivide.rs`.

use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};

use crate::build::{CellKind, CellValues, IndexedMesh};
use crate::geom::{Aabb, TriangleBvh};

/// The level-0 cells: a grid of `cells` equal boxes of extent `cell` from `lo`. qmesh's
/// own root is one cube around the surface; the authors' program (2022 §7.1, its
/// `-init X`) divides the surface's bounding box itself into X cells along its longest
/// axis and as many along the others as keep the cells closest to cubes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootBox {
    pub lo: [f64; 3],
    /// Extent of a level-0 cell along each axis.
    pub cell: [f64; 3],
    /// Level-0 cells along each axis.
    pub cells: [u32; 3],
}

impl RootBox {
    /// The cube centred on `b` whose side is `b`'s longest extent grown by `margin`
    /// (a fraction: 0.01 adds 1 %).
    pub fn around(b: &Aabb, margin: f64) -> RootBox {
        let e = b.extent();
        let size = e[0].max(e[1]).max(e[2]).max(f64::MIN_POSITIVE) * (1.0 + margin);
        let c = b.centre();
        RootBox { lo: c.map(|x| x - size / 2.0), cell: [size; 3], cells: [1; 3] }
    }

    /// The authors' root: `b` itself cut into `init` cells along its longest axis and
    /// ⌈init · extent / longest⌉ along each other one, each axis in equal parts (so with
    /// `init` = 1 the one root cell is the bounding box, not a cube).
    pub fn bounding_grid(b: &Aabb, init: u32) -> RootBox {
        let e = b.extent().map(|x| x.max(f64::MIN_POSITIVE));
        let longest = e[0].max(e[1]).max(e[2]);
        let init = init.max(1);
        let cells = e.map(|x| ((f64::from(init) * x / longest).ceil() as u32).clamp(1, init));
        RootBox { lo: b.lo, cell: [0, 1, 2].map(|k| e[k] / f64::from(cells[k])), cells }
    }

    /// The box of a cell.
    pub fn cell_box(&self, c: OctCell) -> Aabb {
        let s = self.step(c.level);
        let lo = [0, 1, 2].map(|k| self.lo[k] + s[k] * f64::from(c.ijk[k]));
        Aabb { lo, hi: [0, 1, 2].map(|k| lo[k] + s[k]) }
    }

    /// Cell extents at `level`.
    pub fn step(&self, level: u8) -> [f64; 3] {
        self.cell.map(|x| x / f64::from(1u32 << level))
    }

    /// Cells along each axis at `level`.
    pub fn cells_at(&self, level: u8) -> [i64; 3] {
        self.cells.map(|n| i64::from(n) << level)
    }

    /// The level of a box whose extent along x is `side` (the nearest integer of
    /// log2(level-0 extent / side)).
    pub fn level_of(&self, side: f64) -> u8 {
        (self.cell[0] / side).log2().round().clamp(0.0, 30.0) as u8
    }

    /// The level-0 cells.
    pub fn level_zero(&self) -> impl Iterator<Item = OctCell> + '_ {
        let [nx, ny, nz] = self.cells;
        (0..nz).flat_map(move |k| (0..ny).flat_map(move |j| (0..nx).map(move |i| OctCell { level: 0, ijk: [i, j, k] })))
    }

    /// Whether the same-level position `p` of a cell at `level` is inside the grid.
    pub(super) fn contains(&self, level: u8, p: [i64; 3]) -> bool {
        let n = self.cells_at(level);
        (0..3).all(|k| (0..n[k]).contains(&p[k]))
    }
}

/// A cell of the octree: its level and its integer position among the 2^level cells
/// of each axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct OctCell {
    pub level: u8,
    pub ijk: [u32; 3],
}

impl OctCell {
    /// The first level-0 cell (the only one of a cubic root).
    pub const ROOT: OctCell = OctCell { level: 0, ijk: [0; 3] };

    pub fn children(self) -> impl Iterator<Item = OctCell> {
        (0..8u32)
            .map(move |c| OctCell { level: self.level + 1, ijk: [0, 1, 2].map(|k| 2 * self.ijk[k] + (c >> k & 1)) })
    }

    /// The cell of level `level` ≤ self.level containing this one.
    pub fn ancestor(self, level: u8) -> OctCell {
        let s = self.level - level;
        OctCell { level, ijk: self.ijk.map(|x| x >> s) }
    }
}

/// Offsets to the 6 face and 12 edge neighbours.
fn face_and_edge_offsets() -> impl Iterator<Item = [i64; 3]> {
    (0..27).map(|i| [i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1]).filter(|d: &[i64; 3]| {
        let nz = d.iter().filter(|&&x| x != 0).count();
        nz == 1 || nz == 2
    })
}

/// The leaves coarser than level `below` that share a face or an edge with `cell`
/// (`is_leaf` says which cells are leaves; at most one per neighbour position).
pub(crate) fn coarser_neighbours(
    root: &RootBox,
    cell: OctCell,
    below: u8,
    is_leaf: impl Fn(&OctCell) -> bool,
) -> impl Iterator<Item = OctCell> {
    face_and_edge_offsets().filter_map(move |d| {
        let p = [0, 1, 2].map(|k| i64::from(cell.ijk[k]) + d[k]);
        if !root.contains(cell.level, p) {
            return None;
        }
        let same = OctCell { level: cell.level, ijk: p.map(|x| x as u32) };
        // Leaves do not overlap: when the neighbour at the same level is one, none of
        // its ancestors is (most positions, in a balanced octree: one lookup, not one
        // per level).
        if is_leaf(&same) {
            return None;
        }
        (0..below).rev().map(|l| same.ancestor(l)).find(|c| is_leaf(c))
    })
}

/// The leaves of an octree.
#[derive(Clone, Debug)]
pub struct Octree {
    pub root: RootBox,
    pub leaves: FxHashSet<OctCell>,
}

impl Octree {
    /// Every level-0 cell of `root` as a leaf.
    pub fn new(root: RootBox) -> Octree {
        Octree { root, leaves: root.level_zero().collect() }
    }

    /// Replaces each given leaf by its 8 children; returns the children.
    pub fn split(&mut self, cells: &[OctCell]) -> Vec<OctCell> {
        let mut new = Vec::with_capacity(8 * cells.len());
        for &c in cells {
            if self.leaves.remove(&c) {
                new.extend(c.children());
            }
        }
        self.leaves.extend(new.iter().copied());
        new
    }

    /// Leaves with a face or edge neighbour leaf at least two levels finer, found from
    /// the fine side: for each of `fine`, the coarse leaf holding each neighbour position.
    fn unbalanced_by(&self, fine: &[OctCell]) -> Vec<OctCell> {
        let mut out: FxHashSet<OctCell> = FxHashSet::default();
        for &f in fine.iter().filter(|f| f.level >= 2) {
            out.extend(coarser_neighbours(&self.root, f, f.level - 1, |c| self.leaves.contains(c)));
        }
        let mut v: Vec<OctCell> = out.into_iter().collect();
        v.sort_unstable();
        v
    }

    /// Refines until no leaf has a face or edge neighbour two levels finer, starting
    /// from the leaves just created; returns how many leaves were split.
    pub fn balance(&mut self, mut created: Vec<OctCell>) -> usize {
        let mut split = 0;
        loop {
            let todo = self.unbalanced_by(&created);
            if todo.is_empty() {
                return split;
            }
            split += todo.len();
            created = self.split(&todo);
        }
    }

    /// Leaves with hanging vertices: a face or edge neighbour of the same size was
    /// refined, which split the shared face or edge (more than 8 vertices; the
    /// authors' "generic" cells). Only a same-size neighbour shares a whole face or
    /// edge of a leaf, so no other refinement splits one. Counted on the tree, so the
    /// direct and the query-replace subdivisions give the same figure.
    pub fn with_hanging_vertices(&self) -> usize {
        let mut refined: FxHashSet<OctCell> = FxHashSet::default();
        for &c in &self.leaves {
            for l in (0..c.level).rev() {
                if !refined.insert(c.ancestor(l)) {
                    break;
                }
            }
        }
        // A leaf has one exactly when a cell of its level sharing a face or an edge with it
        // is refined: the leaves around each refined cell, each counted once.
        let leaves_around = |r: &OctCell| {
            let r = *r;
            face_and_edge_offsets().filter_map(move |d| {
                let p = [0, 1, 2].map(|k| i64::from(r.ijk[k]) + d[k]);
                let c = OctCell { level: r.level, ijk: p.map(|x| x as u32) };
                (self.root.contains(r.level, p) && self.leaves.contains(&c)).then_some(c)
            })
        };
        let mut found: Vec<OctCell> = refined.par_iter().flat_map_iter(leaves_around).collect();
        found.par_sort_unstable();
        found.dedup();
        found.len()
    }

    /// Leaves the surface touches, in a stable order.
    pub fn touched(&self, surface: &TriangleBvh, below_level: u8) -> Vec<OctCell> {
        let mut v: Vec<OctCell> = self
            .leaves
            .par_iter()
            .filter(|c| c.level < below_level && surface.intersects_box(&self.root.cell_box(**c)))
            .copied()
            .collect();
        v.sort_unstable();
        v
    }

    /// Leaves outside the surface that it does not touch (see `outside_among`, which decides them).
    pub fn outside_leaves(&self, surface: &TriangleBvh) -> Vec<OctCell> {
        let leaves = self.sorted_leaves();
        let touched: Vec<bool> = leaves.par_iter().map(|&c| surface.intersects_box(&self.root.cell_box(c))).collect();
        super::outside::outside_among(&self.root, &leaves, &touched, surface).into_iter().map(|i| leaves[i]).collect()
    }

    /// Leaves sorted by (level, position): a deterministic order for output.
    pub fn sorted_leaves(&self) -> Vec<OctCell> {
        let mut v: Vec<OctCell> = self.leaves.iter().copied().collect();
        v.sort_unstable();
        v
    }

    /// The leaves in output order, the finest-lattice position of each point, and each
    /// leaf's 8 points (VTK hexahedron order).
    fn numbering(&self) -> (Vec<OctCell>, Vec<[u32; 3]>, Vec<[u32; 8]>) {
        let leaves = self.sorted_leaves();
        let fine = leaves.iter().map(|c| c.level).max().unwrap_or(0);
        let mut ids: FxHashMap<[u32; 3], u32> = FxHashMap::default();
        let mut lattice = Vec::new();
        let hexes = leaves
            .iter()
            .map(|c| {
                let s = 1u32 << (fine - c.level);
                std::array::from_fn(|i| {
                    let b = crate::build::HEX_CORNER_BITS[i];
                    let q = [0, 1, 2].map(|k| (c.ijk[k] + (b >> k & 1)) * s);
                    *ids.entry(q).or_insert_with(|| {
                        lattice.push(q);
                        (lattice.len() - 1) as u32
                    })
                })
            })
            .collect();
        (leaves, lattice, hexes)
    }

    /// Position of a point of the finest lattice of `leaves`.
    fn lattice_position(&self, leaves: &[OctCell]) -> impl Fn([u32; 3]) -> [f64; 3] + Sync + '_ {
        let fine = leaves.iter().map(|c| c.level).max().unwrap_or(0);
        let step = self.root.step(fine);
        move |q| [0, 1, 2].map(|k| self.root.lo[k] + step[k] * f64::from(q[k]))
    }

    /// Hexahedra of the leaves (VTK order) with their `level` array. Points are shared
    /// through their position on the finest lattice.
    pub fn to_mesh(&self) -> IndexedMesh {
        let (leaves, lattice, hexes) = self.numbering();
        let position = self.lattice_position(&leaves);
        let mut mesh = IndexedMesh::new();
        mesh.points = lattice.iter().map(|&q| position(q)).collect();
        for h in &hexes {
            mesh.push_cell(CellKind::Hex, h, None);
        }
        mesh.set_cell_array("level", CellValues::Int(leaves.iter().map(|c| i32::from(c.level)).collect()));
        mesh
    }

    /// Whether each point of [`Octree::to_mesh`] is inside the surface: the side of an
    /// untouched leaf holding it when there is one (see [`Octree::outside_leaves`]),
    /// else its winding number.
    pub fn point_sides(&self, surface: &TriangleBvh) -> Vec<bool> {
        let (leaves, lattice, hexes) = self.numbering();
        let outside: rustc_hash::FxHashSet<OctCell> = self.outside_leaves(surface).into_iter().collect();
        let touched: Vec<bool> = leaves.par_iter().map(|&c| surface.intersects_box(&self.root.cell_box(c))).collect();
        let mut side: Vec<Option<bool>> = vec![None; hexes.iter().flatten().max().map_or(0, |&m| m as usize + 1)];
        for (i, h) in hexes.iter().enumerate().filter(|(i, _)| !touched[*i]) {
            let inside = !outside.contains(&leaves[i]);
            h.iter().for_each(|&v| side[v as usize] = Some(inside));
        }
        let position = self.lattice_position(&leaves);
        side.par_iter().enumerate().map(|(v, s)| s.unwrap_or_else(|| surface.contains(position(lattice[v])))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounding_grid_cuts_each_axis_in_equal_parts() {
        let b = Aabb { lo: [1.0, 0.0, -1.0], hi: [11.0, 4.0, 1.5] };
        let r = RootBox::bounding_grid(&b, 4);
        // 4 along x (10), ⌈4 · 4 / 10⌉ = 2 along y, ⌈4 · 2.5 / 10⌉ = 1 along z.
        assert_eq!(r.cells, [4, 2, 1]);
        assert_eq!(r.cell, [2.5, 2.0, 2.5]);
        assert_eq!(Octree::new(r).leaves.len(), 8);
        let last = r.cell_box(OctCell { level: 1, ijk: [7, 3, 1] });
        assert_eq!((last.lo, last.hi), ([9.75, 3.0, 0.25], [11.0, 4.0, 1.5]));
        assert_eq!(RootBox::bounding_grid(&b, 1).cell, b.extent());
    }

    #[test]
    fn balance_splits_coarse_neighbours() {
        let mut t = Octree::new(RootBox { lo: [0.0; 3], cell: [1.0; 3], cells: [1; 3] });
        let kids = t.split(&[OctCell::ROOT]);
        // Split the corner child twice more: its face neighbours (level 1) must split.
        let c = kids[0];
        let g = t.split(&[c]);
        let gg = t.split(&[g[0]]);
        assert_eq!(t.leaves.len(), 7 + 7 + 8);
        let n = t.balance(gg);
        assert_eq!(n, 0, "level 3 cells at the corner touch only level ≥ 2 cells");
        let deep = t.split(&[g[7]]); // the level-2 cell at the centre of child 0
        let n = t.balance(deep);
        // g[7] touches the 7 other level-1 children by faces or edges or only a corner:
        // the 3 face and 3 edge neighbours split, the corner-only one stays.
        assert_eq!(n, 6);
    }
}
