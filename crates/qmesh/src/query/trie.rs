//! Many query words at once (2025 §5.2.1): a prefix tree over the words, walked
//! together with the input map from a start dart. The walk is depth-first with an
//! explicit stack; before each child is tried the annotation is undone to the state of
//! its parent, so every word is checked exactly as Algorithm 1 alone would.

use super::annotate::Annotator;
use super::guard::{CornerGuards, is_alive};
use super::word::QueryWord;
use crate::cmap::{BitSet, CMap3};

/// A node of the compressed tree: the run of symbols `symbols[run..run + len]` read
/// on the way into it (starting at word position `depth`), its children
/// `children[first..first + count]` (their runs start with distinct symbols), and the
/// words it ends, `terminals[t_first..t_first + t_count]` (query indices).
#[derive(Clone, Copy, Debug, Default)]
struct Node {
    run: u32,
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
/// that the symbols of one word are checked in a tight loop.
#[derive(Clone, Debug, Default)]
pub struct PrefixTree {
    nodes: Vec<Node>,
    children: Vec<u32>,
    symbols: Vec<u32>,
    terminals: Vec<u32>,
    max_darts: usize,
}

impl PrefixTree {
    /// The tree of `words` (word i ends at a terminal naming i), built from the words
    /// sorted: the words through a node are a contiguous range of the sorted list, and
    /// a run ends where the range's first and last words part (or one ends). Children
    /// are in order of their smallest word index, terminals in word order.
    pub fn new<'a>(words: impl IntoIterator<Item = &'a QueryWord>) -> PrefixTree {
        let words: Vec<&[u32]> = words.into_iter().map(|w| w.ops()).collect();
        let max_darts = words.iter().map(|w| w.len() / 3).max().unwrap_or(0);
        let mut sorted: Vec<u32> = (0..words.len() as u32).collect();
        sorted.sort_by(|&a, &b| words[a as usize].cmp(words[b as usize]).then(a.cmp(&b)));
        let word = |i: usize| words[sorted[i] as usize];
        let common = |lo: usize, hi: usize, from: usize| -> usize {
            let (a, b) = (word(lo), word(hi - 1));
            from + a[from..].iter().zip(&b[from..]).take_while(|(x, y)| x == y).count()
        };
        let mut tree = PrefixTree { max_darts, ..Default::default() };
        tree.nodes.push(Node::default());
        // (compressed node, its range of sorted words, depth below it)
        let mut todo = vec![(0usize, 0usize, words.len(), 0usize)];
        while let Some((c, lo, hi, depth)) = todo.pop() {
            // Words ending here sort first in the range.
            let ends = (lo..hi).take_while(|&i| word(i).len() == depth).count();
            tree.nodes[c].t_first = tree.terminals.len() as u32;
            tree.nodes[c].t_count = ends as u32;
            tree.terminals.extend((lo..lo + ends).map(|i| sorted[i]));
            // Groups of words by their symbol at `depth`, by smallest word index.
            let mut groups: Vec<(u32, usize, usize)> = Vec::new();
            let mut i = lo + ends;
            while i < hi {
                let sym = word(i)[depth];
                let j = (i..hi).find(|&j| word(j)[depth] != sym).unwrap_or(hi);
                groups.push(((i..j).map(|k| sorted[k]).min().expect("not empty"), i, j));
                i = j;
            }
            groups.sort_unstable();
            tree.nodes[c].first = tree.children.len() as u32;
            tree.nodes[c].count = groups.len() as u32;
            let first = tree.children.len();
            tree.children.resize(first + groups.len(), 0);
            for (k, &(smallest, a, b)) in groups.iter().enumerate() {
                let end = common(a, b, depth);
                let run = tree.symbols.len() as u32;
                tree.symbols.extend_from_slice(&word(a)[depth..end]);
                let owner = if b - a == 1 { smallest } else { MIXED };
                let id = tree.nodes.len();
                tree.nodes.push(Node {
                    run,
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

    /// The symbols read on the way into `node`.
    pub(crate) fn run_of(&self, node: usize) -> &[u32] {
        let n = self.nodes[node];
        &self.symbols[n.run as usize..(n.run + n.len) as usize]
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

    /// Walks the tree and the map together from input dart `start` (raw), calling
    /// `found(query, annotator)` at every terminal reached: the annotator then holds
    /// that query's match. `consumed` darts count as annotated ∅. With `prune` (one
    /// table per query), a branch owned by one query stops as soon as an automorphic
    /// image of its match starts at a smaller dart (only canonical matches are then
    /// reported). With `guard` (its corner checks and a threshold), queries whose
    /// matched corners have a Jacobian at or below the threshold are dropped as soon as
    /// those corners are matched.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn walk(
        &self,
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
            let syms = &self.symbols[c.run as usize..(c.run + c.len) as usize];
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
