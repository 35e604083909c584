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
                + tree.run_of(node, queries).iter().filter(|&&s| (NEW..FIRST_CONDITION).contains(&s)).count() as u32;
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
            if !killed.iter().any(|&q| is_alive(alive, q)) {
                continue;
            }
            let p = c.labels.map(|l| map.point(Dart::from_raw(matched[l as usize]).expect("matched darts are not ε")));
            if corner_jacobian(p[0], p[1], p[2], p[3]) <= threshold {
                killed.iter().for_each(|&q| kill(alive, q));
            }
        }
        let sub = &self.subtree[node * self.words..(node + 1) * self.words];
        sub.iter().zip(alive.iter()).any(|(s, a)| s & a != 0)
    }
}

/// Whether query `q` is still alive in the bitset `alive` (one bit per query).
#[inline]
pub(crate) fn is_alive(alive: &[u64], q: u32) -> bool {
    alive[q as usize / 64] >> (q % 64) & 1 == 1
}

/// Clears query `q`'s bit in `alive`.
#[inline]
fn kill(alive: &mut [u64], q: u32) {
    alive[q as usize / 64] &= !(1 << (q % 64));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{BuildOptions, build_volume_map};
    use crate::query::{Annotator, Condition};

    #[test]
    fn one_bit_per_query_across_words() {
        for q in 0..192 {
            let mut only = [0u64; 3];
            only[q as usize / 64] = 1 << (q % 64);
            assert!((0..192).all(|r| is_alive(&only, r) == (r == q)), "query {q}");
            let mut all = [u64::MAX; 3];
            kill(&mut all, q);
            assert!((0..192).all(|r| is_alive(&all, r) != (r == q)), "query {q}");
        }
    }

    /// 70 cube queries with `*` conditions (0..70) and 70 with `ε` on their last dart
    /// (70..140): the same labels and corners, words that part at their last symbol
    /// (a tree of a long shared run and two one-symbol leaves), three bitset words.
    fn two_groups() -> (Vec<Query>, PrefixTree, CornerGuards) {
        let cube = build_volume_map(&crate::generate::hex_grid(1, 1, 1), &BuildOptions::default()).unwrap().0;
        let any = Query::new("any", cube, |_| Condition::Any).unwrap();
        let mut late = any.clone();
        let last = late.labelling().darts[23];
        late.set_conditions(|d| if d == last { Condition::Boundary } else { Condition::Any });
        let queries: Vec<Query> = (0..140).map(|i| if i < 70 { any.clone() } else { late.clone() }).collect();
        let tree = PrefixTree::new(queries.iter().map(|q| &q.word));
        let guards = CornerGuards::new(&tree, &queries);
        (queries, tree, guards)
    }

    /// The nodes from the root to the one where query `q` ends.
    fn path_to(tree: &PrefixTree, q: u32) -> Vec<usize> {
        let mut path = vec![0];
        while !tree.terminals_of(*path.last().unwrap()).contains(&q) {
            let below = |n: u32| {
                let mut stack = vec![n as usize];
                std::iter::from_fn(|| {
                    let n = stack.pop()?;
                    stack.extend(tree.children_of(n).iter().map(|&c| c as usize));
                    Some(n)
                })
                .any(|n| tree.terminals_of(n).contains(&q))
            };
            let next = tree.children_of(*path.last().unwrap()).iter().find(|&&c| below(c)).expect("q ends below");
            path.push(*next as usize);
        }
        path
    }

    #[test]
    fn corners_at_or_below_the_threshold_drop_their_queries_and_stop_the_walk() {
        let (queries, tree, g) = two_groups();
        assert_eq!(g.words, 3);
        let map = build_volume_map(&crate::generate::hex_grid(1, 1, 1), &BuildOptions::default()).unwrap().0;
        let mut a = Annotator::new(24);
        assert!(a.annotate(&map, &queries[0].word, map.darts().next().unwrap(), None));
        let path = path_to(&tree, 0);
        assert_eq!(path.len(), 3, "root, shared run, leaf: {path:?}");
        // A perfect cube's corners have a Jacobian of exactly 1: at a threshold of 1
        // every corner fails. Its corners are all matched on the shared run, which
        // drops every query and says that nothing is left below it.
        let mut alive = [u64::MAX; 3];
        let stop = path.iter().position(|&n| !g.apply(n, &map, &a.matched, 1.0, &mut alive));
        assert_eq!(stop, Some(1), "dropped where the corners are matched");
        assert!((0..140).all(|q| !is_alive(&alive, q)));
        // Below the Jacobian of every corner, nothing is dropped.
        let mut alive = [u64::MAX; 3];
        assert!(path.iter().all(|&n| g.apply(n, &map, &a.matched, 0.5, &mut alive)));
        assert_eq!(alive, [u64::MAX; 3]);
        // Where only the `ε` queries are alive, the `*` queries' own leaf has nothing
        // left below it, whatever the geometry.
        let mut boundary_only = [0u64; 3];
        (70..140).for_each(|q| boundary_only[q as usize / 64] |= 1 << (q % 64));
        let end = *path.last().unwrap();
        assert!(!g.apply(end, &map, &a.matched, 0.5, &mut boundary_only.clone()));
        let mut first_only = [1u64, 0, 0];
        assert!(g.apply(end, &map, &a.matched, 0.5, &mut first_only));
    }
}
