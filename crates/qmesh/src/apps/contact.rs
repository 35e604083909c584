//! Which of the cells a refinement made the surface touches (2022 §7.1: the cells to
//! split at the next level). A touched cell keeps the leaves of the surface's hierarchy
//! near it, and its children look only at those instead of walking the hierarchy from
//! its root: the same answers, with a fraction of the box tests.

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::box_cells::cell_of;
use super::octree::{OctCell, RootBox};
use crate::cmap::Dart;
use crate::geom::{Aabb, TriangleBvh};

/// A volume made by the last refinement: one dart, its octree cell, and whether the
/// surface meets the cell's box.
pub(super) struct FreshCell {
    pub dart: Dart,
    pub cell: OctCell,
    pub touches: bool,
}

/// The hierarchy's leaves near each cell that will be refined next
/// ([`TriangleBvh::leaves_near`]), one list after the other.
#[derive(Default)]
pub(super) struct NearLeaves {
    lists: FxHashMap<OctCell, (u32, u32)>,
    leaves: Vec<u32>,
}

impl NearLeaves {
    /// The leaves near the parent of `c`, if it kept them.
    fn of_parent(&self, c: OctCell) -> Option<&[u32]> {
        let parent = c.ancestor(c.level.checked_sub(1)?);
        self.lists.get(&parent).map(|&(start, len)| &self.leaves[start as usize..(start + len) as usize])
    }

    /// Adds the lists of `other` (for other cells) after its own.
    pub fn append(&mut self, other: NearLeaves) {
        if self.lists.is_empty() && self.leaves.is_empty() {
            *self = other;
            return;
        }
        let shift = self.leaves.len() as u32;
        self.lists.reserve(other.lists.len());
        self.lists.extend(other.lists.into_iter().map(|(c, (start, len))| (c, (start + shift, len))));
        self.leaves.extend(other.leaves);
    }
}

/// Longer lists are not kept: the walk from the hierarchy's root prunes whole subtrees,
/// where a long list is tested leaf by leaf (the first levels' cells are near most of
/// the surface), and the children of a cell without a list walk from the root.
const LONGEST_LIST_USED: usize = 256;

/// What one core found for its run of cells: whether the surface touches each, the
/// touched cells that keep leaves (with how many) and those leaves, one list after the
/// other.
struct Run {
    touches: Vec<bool>,
    kept: Vec<(OctCell, u32)>,
    leaves: Vec<u32>,
}

/// Whether the surface meets each of `cells` (in order), on all cores, testing the
/// surface only near each cell's parent (`near`); with the leaves near the touched
/// cells of level `next_parents`, which the next refinement splits (`None` after the
/// last one).
pub(super) fn contacts(
    root: RootBox,
    surface: &TriangleBvh,
    cells: &[OctCell],
    near: &NearLeaves,
    next_parents: Option<u8>,
) -> (Vec<bool>, NearLeaves) {
    // Small runs, each a job of its own: the first levels have few cells, each tested
    // against much of the surface, and the tests run beside a refinement's own steps
    // (see `refine`), so the core that finishes those takes the runs not yet started
    // (rayon cuts a range further only when another core steals it, and otherwise runs
    // the rest of its half on the core that holds it). Armadillo L6, 20 alternating runs
    // on 2 threads, when the tests ran beside the reads and edge splits only:
    // `split_edges` 14.0 -> 11.7 ms against 4 runs per thread, each not a job.
    let chunk = cells.len().div_ceil(16 * rayon::current_num_threads()).max(1);
    let runs: Vec<Run> = cells
        .par_chunks(chunk)
        .with_max_len(1)
        .map(|run| {
            let (mut touches, mut kept, mut leaves) = (Vec::with_capacity(run.len()), Vec::new(), Vec::new());
            for &cell in run {
                let parent_near = near.of_parent(cell);
                let cell_box = root.cell_box(cell);
                let touched = surface.intersects_box_near(&cell_box, parent_near);
                if touched && next_parents == Some(cell.level) {
                    let before = leaves.len();
                    if surface.leaves_near(&cell_box, parent_near, &mut leaves, LONGEST_LIST_USED) {
                        kept.push((cell, (leaves.len() - before) as u32));
                    }
                }
                touches.push(touched);
            }
            Run { touches, kept, leaves }
        })
        .collect();
    let mut next = NearLeaves::default();
    next.lists.reserve(runs.iter().map(|r| r.kept.len()).sum());
    let mut touches = Vec::with_capacity(cells.len());
    for Run { touches: run_touches, kept, leaves } in runs {
        let mut start = next.leaves.len() as u32;
        for (c, len) in kept {
            next.lists.insert(c, (start, len));
            start += len;
        }
        next.leaves.extend(leaves);
        touches.extend(run_touches);
    }
    (touches, next)
}

/// Each of `volumes` (with its box) as a [`FreshCell`], tested by [`contacts`].
pub(super) fn fresh_cells(
    root: RootBox,
    surface: &TriangleBvh,
    volumes: &[(Dart, Aabb)],
    near: &NearLeaves,
    next_parents: Option<u8>,
) -> (Vec<FreshCell>, NearLeaves) {
    let octs: Vec<OctCell> = volumes.par_iter().map(|(_, b)| cell_of(root, b)).collect();
    let (touches, next) = contacts(root, surface, &octs, near, next_parents);
    let cells =
        volumes.iter().zip(octs).zip(touches).map(|((&(dart, _), cell), touches)| FreshCell { dart, cell, touches });
    (cells.collect(), next)
}
