//! Many query words at once (2025 §5.2.1): a prefix tree over the words, walked
//! together with the input map from a start dart. The walk is depth-first with an
//! explicit stack; before each child is tried the annotation is undone to the state of
//! its parent, so every word is checked exactly as Algorithm 1 alone would.

use super::annotate::Annotator;
use super::guard::{CornerGuards, is_alive};
use super::word::QueryWord;
use crate::cmap::{BitSet, CMap3};

/// A node of the compressed tree: the run of symbols read on the way into it, `len`
/// symbols of word `word` from position `depth` (every word through the node has
/// them), its children `children[first..first + count]` (their runs start with
/// distinct symbols), and the words it ends, `terminals[t_first..t_first + t_count]`
/// (query indices).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Node {
    word: u32,
    len: u32,
    depth: u32,
    first: u32,
    count: u32,
    t_first: u32,
    t_count: u32,
    /// The only query whose words pass through this node, or `MIXED`.
    owner: u32,
}

const MIXED: u32 = u32::MAX;

/// A prefix tree of query words, with chains of single-child nodes merged into runs so
/// that the symbols of one word are checked in a tight loop. The runs are read from
/// the words themselves (the tree keeps no copy of them): whatever reads the tree is
/// given the words it was built from, in the same order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PrefixTree {
    nodes: Vec<Node>,
    children: Vec<u32>,
    terminals: Vec<u32>,
    max_darts: usize,
}

impl PrefixTree {
    /// The tree of `words` (word i ends at a terminal naming i). The words through a
    /// node are a contiguous range of one list of word indices; each node orders its
    /// range by the symbol read next (words ending there first), then by index, so
    /// that its children's ranges are contiguous. A run ends where the words of a
    /// child part (or one ends). Children are in order of their smallest word index,
    /// terminals in word order. Only one symbol per word is compared at each node, so
    /// building costs about one pass over the words' shared symbols.
    pub fn new<'a>(words: impl IntoIterator<Item = &'a QueryWord>) -> PrefixTree {
        let words: Vec<&[u32]> = words.into_iter().map(|w| w.ops()).collect();
        let max_darts = words.iter().map(|w| w.len() / 3).max().unwrap_or(0);
        let mut order: Vec<u32> = (0..words.len() as u32).collect();
        let word = |i: u32| words[i as usize];
        let mut tree = PrefixTree { max_darts, ..Default::default() };
        tree.nodes.push(Node::default());
        // (compressed node, its range of `order`, depth below it)
        let mut todo = vec![(0usize, 0usize, words.len(), 0usize)];
        let mut groups: Vec<(u32, usize, usize)> = Vec::new();
        while let Some((c, lo, hi, depth)) = todo.pop() {
            let range = &mut order[lo..hi];
            range.sort_unstable_by_key(|&i| (word(i).get(depth).map_or(0, |&s| u64::from(s) + 1), i));
            let ends = range.iter().take_while(|&&i| word(i).len() == depth).count();
            tree.nodes[c].t_first = tree.terminals.len() as u32;
            tree.nodes[c].t_count = ends as u32;
            tree.terminals.extend_from_slice(&range[..ends]);
            // Groups of words by their symbol at `depth`; each starts with its
            // smallest word index, whose symbols are the run of the group's node.
            groups.clear();
            let mut i = ends;
            while i < range.len() {
                let sym = word(range[i])[depth];
                let j = (i..range.len()).find(|&j| word(range[j])[depth] != sym).unwrap_or(range.len());
                groups.push((range[i], lo + i, lo + j));
                i = j;
            }
            groups.sort_unstable();
            tree.nodes[c].first = tree.children.len() as u32;
            tree.nodes[c].count = groups.len() as u32;
            let first = tree.children.len();
            tree.children.resize(first + groups.len(), 0);
            for (k, &(smallest, a, b)) in groups.iter().enumerate() {
                let lead = word(order[a]);
                let end = order[a + 1..b].iter().fold(lead.len(), |end, &o| {
                    depth + lead[depth..end].iter().zip(&word(o)[depth..]).take_while(|(x, y)| x == y).count()
                });
                let owner = if b - a == 1 { smallest } else { MIXED };
                let id = tree.nodes.len();
                tree.nodes.push(Node {
                    word: smallest,
                    len: (end - depth) as u32,
                    depth: depth as u32,
                    owner,
                    ..Default::default()
                });
                tree.children[first + k] = id as u32;
                todo.push((id, a, b, end));
            }
        }
        tree
    }

    /// Number of nodes (the root included).
    pub fn nb_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// The largest query, in darts.
    pub fn max_darts(&self) -> usize {
        self.max_darts
    }

    /// The symbols read on the way into `node`, from the `words` the tree was built from.
    pub(crate) fn run_of<'w>(&self, node: usize, words: &'w [impl AsRef<QueryWord>]) -> &'w [u32] {
        let n = self.nodes[node];
        &words[n.word as usize].as_ref().ops()[n.depth as usize..(n.depth + n.len) as usize]
    }

    /// The queries whose words end at `node`.
    pub(crate) fn terminals_of(&self, node: usize) -> &[u32] {
        let n = self.nodes[node];
        &self.terminals[n.t_first as usize..(n.t_first + n.t_count) as usize]
    }

    pub(crate) fn children_of(&self, node: usize) -> &[u32] {
        let n = self.nodes[node];
        &self.children[n.first as usize..(n.first + n.count) as usize]
    }

    /// Walks the tree (built from `words`) and the map together from input dart
    /// `start` (raw), calling `found(query, annotator)` at every terminal reached: the
    /// annotator then holds that query's match. `consumed` darts count as annotated ∅.
    /// With `prune` (one table per query), a branch owned by one query stops as soon as
    /// an automorphic image of its match starts at a smaller dart (only canonical
    /// matches are then reported). With `guard` (its corner checks and a threshold),
    /// queries whose matched corners have a Jacobian at or below the threshold are
    /// dropped as soon as those corners are matched.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn walk(
        &self,
        words: &[impl AsRef<QueryWord>],
        map: &CMap3,
        annot: &mut Annotator,
        start: u32,
        consumed: Option<&BitSet>,
        prune: Option<&[Vec<bool>]>,
        guard: Option<(&CornerGuards, f64)>,
        mut found: impl FnMut(u32, &Annotator),
    ) {
        if self.nodes[0].count == 0 || consumed.is_some_and(|c| c.get(start as usize)) {
            return;
        }
        annot.begin(start);
        // (node, next child to try, annotation state on entering the node)
        let mut stack = std::mem::take(&mut annot.stack);
        stack.clear();
        stack.push((0, 0, annot.save()));
        // Queries still alive at each stack level (guards only), `w` words per level.
        let w = guard.map_or(0, |g| g.0.words);
        let mut alive = std::mem::take(&mut annot.alive);
        if w > 0 {
            alive.clear();
            alive.resize(w, u64::MAX);
        }
        while let Some(top) = stack.last_mut() {
            let node = self.nodes[top.0 as usize];
            if top.1 == node.count {
                stack.pop();
                continue;
            }
            let child = self.children[(node.first + top.1) as usize];
            top.1 += 1;
            if node.count > 1 {
                annot.undo_to(top.2);
            }
            let c = self.nodes[child as usize];
            let syms = &words[c.word as usize].as_ref().ops()[c.depth as usize..(c.depth + c.len) as usize];
            let table = match prune {
                Some(t) if c.owner != MIXED => Some(t[c.owner as usize].as_slice()),
                _ => None,
            };
            if !annot.run(map, consumed, c.depth as usize, syms, table) {
                continue;
            }
            let level = stack.len();
            if let Some((g, threshold)) = guard {
                alive.resize((level + 1) * w, 0);
                alive.copy_within((level - 1) * w..level * w, level * w);
                let (matched, mine) = (&annot.matched, &mut alive[level * w..(level + 1) * w]);
                if !g.apply(child as usize, map, matched, threshold, mine) {
                    continue;
                }
            }
            for &q in &self.terminals[c.t_first as usize..(c.t_first + c.t_count) as usize] {
                if w == 0 || is_alive(&alive[level * w..], q) {
                    found(q, annot);
                }
            }
            if c.count > 0 {
                stack.push((child, 0, annot.save()));
            }
        }
        annot.stack = stack;
        annot.alive = alive;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The tree as the words sorted lexicographically give it (the first definition:
    /// a node's words are a range of the sorted list, a run ends where that range's
    /// first and last words part; its symbols are read from the range's smallest word
    /// index), for comparison.
    fn from_sorted(words: &[QueryWord]) -> PrefixTree {
        let ops: Vec<&[u32]> = words.iter().map(|w| w.ops()).collect();
        let mut sorted: Vec<u32> = (0..ops.len() as u32).collect();
        sorted.sort_by(|&a, &b| ops[a as usize].cmp(ops[b as usize]).then(a.cmp(&b)));
        let word = |i: usize| ops[sorted[i] as usize];
        let mut tree =
            PrefixTree { max_darts: ops.iter().map(|w| w.len() / 3).max().unwrap_or(0), ..Default::default() };
        tree.nodes.push(Node::default());
        let mut todo = vec![(0usize, 0usize, ops.len(), 0usize)];
        while let Some((c, lo, hi, depth)) = todo.pop() {
            let ends = (lo..hi).take_while(|&i| word(i).len() == depth).count();
            (tree.nodes[c].t_first, tree.nodes[c].t_count) = (tree.terminals.len() as u32, ends as u32);
            tree.terminals.extend((lo..lo + ends).map(|i| sorted[i]));
            let mut groups = Vec::new();
            let mut i = lo + ends;
            while i < hi {
                let j = (i..hi).find(|&j| word(j)[depth] != word(i)[depth]).unwrap_or(hi);
                groups.push(((i..j).map(|k| sorted[k]).min().unwrap(), i, j));
                i = j;
            }
            groups.sort_unstable();
            (tree.nodes[c].first, tree.nodes[c].count) = (tree.children.len() as u32, groups.len() as u32);
            for &(smallest, a, b) in &groups {
                let (x, y) = (word(a), word(b - 1));
                let end = depth + x[depth..].iter().zip(&y[depth..]).take_while(|(p, q)| p == q).count();
                let node = Node {
                    word: smallest,
                    len: (end - depth) as u32,
                    depth: depth as u32,
                    owner: if b - a == 1 { smallest } else { MIXED },
                    ..Default::default()
                };
                tree.children.push(tree.nodes.len() as u32);
                todo.push((tree.nodes.len(), a, b, end));
                tree.nodes.push(node);
            }
        }
        tree
    }

    /// Each word, read from the root along the runs, ends at a terminal naming it.
    fn reads_every_word(tree: &PrefixTree, words: &[QueryWord]) {
        for (q, w) in words.iter().enumerate() {
            let (mut node, mut at) = (0, 0);
            while at < w.ops().len() {
                let child = tree.children_of(node).iter().map(|&c| c as usize).find(|&c| {
                    let run = tree.run_of(c, words);
                    w.ops()[at..].starts_with(run)
                });
                node = child.unwrap_or_else(|| panic!("word {q} leaves the tree at symbol {at}"));
                at += tree.run_of(node, words).len();
            }
            assert!(tree.terminals_of(node).contains(&(q as u32)), "word {q} does not end at its terminal");
        }
    }

    #[test]
    fn the_rule_book_tree_is_the_sorted_words_tree() {
        let words: Vec<QueryWord> =
            crate::apps::hex_rules().unwrap().into_iter().map(|r| r.query.word.clone()).collect();
        let tree = PrefixTree::new(&words);
        assert_eq!(tree, from_sorted(&words));
        reads_every_word(&tree, &words);
    }

    proptest! {
        /// Random words on three labels (so that prefixes are shared, words repeat and
        /// some words are prefixes of others): the same tree as the sorted words give.
        #[test]
        fn same_tree_as_the_sorted_words(raw in prop::collection::vec(prop::collection::vec(0u32..4, 0..5), 0..24)) {
            let words: Vec<QueryWord> = raw
                .iter()
                .map(|w| QueryWord::from_symbols(w.iter().flat_map(|&s| [s.min(1), s, 1 + s % 2]).collect()))
                .collect();
            let tree = PrefixTree::new(&words);
            prop_assert_eq!(&tree, &from_sorted(&words));
            reads_every_word(&tree, &words);
        }
    }
}
