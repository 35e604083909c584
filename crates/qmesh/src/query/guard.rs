//! Corner guards: a geometric filter inside the prefix-tree walk (the "aborting early
//! when the matched geometry becomes overly distorted" of 2025 §7.1.1).
//!
//! A query with hexahedral corners is scored by the scaled Jacobian of its hexahedron,
//! which is at most the Jacobian at each corner. As soon as a corner and its three
//! neighbours are matched, that corner's Jacobian is known, and a match below the
//! threshold can be dropped right there, together with everything below it in the tree.
//! Queries sharing a prefix are checked together: a node is left when every query
//! through it has failed a corner; the checks are grouped by the labels they read, so
//! one evaluation serves all queries with the same corner labels.

use super::query_map::Query;
use super::trie::PrefixTree;
use super::word::{FIRST_CONDITION, NEW};
use crate::cmap::{CMap3, Dart};
use crate::geom::{HEX_CORNER_FRAMES, corner_jacobian};

/// One corner check at a tree node: the labels of the corner and its ξ, η, ζ
/// neighbours, and the queries (`killed[first..first + count]`) dropped if it fails.
#[derive(Clone, Copy, Debug)]
struct Check {
    labels: [u32; 4],
    first: u32,
    count: u32,
}

/// The corner checks of every node of a prefix tree, and per node the set of queries
/// ending below it.
#[derive(Clone, Debug, Default)]
pub(crate) struct CornerGuards {
    /// Bitset words per query set.
    pub(crate) words: usize,
    /// Per node: its checks, `checks[a..b]`.
    node_checks: Vec<(u32, u32)>,
    checks: Vec<Check>,
    killed: Vec<u32>,
    /// Per node, `words` bitset words: the queries ending in its subtree.
    subtree: Vec<u64>,
}

impl CornerGuards {
    /// Guards for the queries of `tree` that have hexahedral corners.
    pub(crate) fn new(tree: &PrefixTree, queries: &[Query]) -> CornerGuards {
        let words = queries.len().div_ceil(64).max(1);
        let n = tree.nb_nodes();
        let mut per_node: Vec<Vec<([u32; 4], u32)>> = vec![Vec::new(); n];
        let mut subtree = vec![0u64; n * words];
        // Depth-first over the tree with the path and the label count at each node's end.
        let mut path: Vec<(usize, u32)> = Vec::new();
        let mut stack = vec![(0usize, 0usize, 1u32)];
        while let Some((node, depth, labels_before)) = stack.pop() {
            path.truncate(depth);
            let labels = labels_before
                + tree.run_of(node).iter().filter(|&&s| (NEW..FIRST_CONDITION).contains(&s)).count() as u32;
            path.push((node, labels));
            for &q in tree.terminals_of(node) {
                for &(p, _) in &path {
                    subtree[p * words + q as usize / 64] |= 1 << (q % 64);
                }
                let Some(c) = queries[q as usize].corners else { continue };
                for frame in HEX_CORNER_FRAMES {
                    let l = frame.map(|i| c[i]);
                    let ready = *l.iter().max().expect("four labels");
                    let at = path.iter().find(|&&(_, have)| have >= ready).map_or(node, |&(p, _)| p);
                    per_node[at].push((l, q));
                }
            }
            for &child in tree.children_of(node) {
                stack.push((child as usize, depth + 1, labels));
            }
        }
        let mut g = CornerGuards { words, subtree, ..Default::default() };
        for mut list in per_node {
            list.sort_unstable();
            let start = g.checks.len() as u32;
            for chunk in list.chunk_by(|a, b| a.0 == b.0) {
                g.checks.push(Check { labels: chunk[0].0, first: g.killed.len() as u32, count: chunk.len() as u32 });
                g.killed.extend(chunk.iter().map(|x| x.1));
            }
            g.node_checks.push((start, g.checks.len() as u32));
        }
        g
    }

    /// Applies the checks of `node` to the current match (`matched[k]` = raw dart of
    /// label k): clears in `alive` the queries whose corner Jacobian is at or below
    /// `threshold`. Returns whether some query ending below `node` is still alive.
    #[inline]
    pub(crate) fn apply(&self, node: usize, map: &CMap3, matched: &[u32], threshold: f64, alive: &mut [u64]) -> bool {
        let (a, b) = self.node_checks[node];
        for c in &self.checks[a as usize..b as usize] {
            let killed = &self.killed[c.first as usize..(c.first + c.count) as usize];
            if killed.iter().all(|&q| alive[q as usize / 64] >> (q % 64) & 1 == 0) {
                continue;
            }
            let p = c.labels.map(|l| map.point(Dart::from_raw(matched[l as usize]).expect("matched darts are not ε")));
            if corner_jacobian(p[0], p[1], p[2], p[3]) <= threshold {
                killed.iter().for_each(|&q| alive[q as usize / 64] &= !(1 << (q % 64)));
            }
        }
        let sub = &self.subtree[node * self.words..(node + 1) * self.words];
        sub.iter().zip(alive.iter()).any(|(s, a)| s & a != 0)
    }
}
