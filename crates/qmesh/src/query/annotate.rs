//! Algorithm 1 of the 2025 paper with the constraint table of §5.1.2: replaying a query
//! word on an input map from a start dart.
//!
//! The input is traversed in the same breadth-first order as the query was labelled,
//! so the dart processed k-th is the one annotated k, and a label symbol met while
//! processing dart k is either an earlier label (the input dart must be the one
//! already annotated with it: case (b)) or exactly the next label (a new dart: case
//! (a)). The queue of Algorithm 1 is therefore the match array itself, and nothing is
//! allocated per start dart.

use super::annotation::{Annotation, RESERVED};
use super::word::{ANY, BOUNDARY, FIRST_CONDITION, INTERIOR, NEW, NO_CONNECTION, QueryWord};
use crate::cmap::{BitSet, CMap3, Dart};

/// Reusable state of one annotation (one per thread).
#[derive(Clone, Debug)]
pub struct Annotator {
    /// `matched[k]` = raw input dart annotated k (`matched[0]` unused).
    pub(crate) matched: Vec<u32>,
    pub(crate) table: Annotation,
    /// Symbols checked so far (a throughput counter).
    pub(crate) steps: u64,
    /// The prefix-tree walk's stack, kept between start darts (no allocation per start).
    pub(crate) stack: Vec<(u32, u32, (usize, usize))>,
    /// The walk's per-level sets of queries still alive (corner guards).
    pub(crate) alive: Vec<u64>,
}

impl Annotator {
    /// State for queries of up to `max_darts` darts.
    pub fn new(max_darts: usize) -> Annotator {
        // ↔ may reserve one outside dart per query dart besides the labelled ones.
        let mut matched = Vec::with_capacity(max_darts + 1);
        matched.push(0);
        Annotator {
            matched,
            table: Annotation::with_capacity(2 * max_darts + 2),
            steps: 0,
            stack: Vec::new(),
            alive: Vec::new(),
        }
    }

    /// Makes room for queries of up to `max_darts` darts (kept if already large enough).
    pub(crate) fn reserve(&mut self, max_darts: usize) {
        if self.table.capacity() < 2 * max_darts + 2 {
            *self = Annotator::new(max_darts);
        }
    }

    /// Starts a new annotation at input dart `start` (label 1).
    #[inline]
    pub(crate) fn begin(&mut self, start: u32) {
        self.table.clear();
        self.matched.truncate(1);
        self.matched.push(start);
        self.table.insert_new(start, 1);
    }

    /// The state to come back to with [`undo_to`](Self::undo_to).
    #[inline]
    pub(crate) fn save(&self) -> (usize, usize) {
        (self.matched.len(), self.table.len())
    }

    #[inline]
    pub(crate) fn undo_to(&mut self, (m, t): (usize, usize)) {
        self.matched.truncate(m);
        self.table.undo_to(t);
    }

    /// Checks the consecutive compiled symbols `ops` of a word, the first being number
    /// `t` (0-based: dart t / 3 + 1, β t % 3 + 1), annotating as it goes (the cells of
    /// the §5.1.2 table). `consumed` darts count as annotated ∅ (greedy selection,
    /// §5.2.2). Returns false at the first violated constraint; the annotation is then
    /// left partial (callers undo or restart).
    ///
    /// Checks of earlier labels (case (b)) are accumulated without branching and
    /// tested once per dart: a failed one only means the darts read afterwards are
    /// meaningless, and nothing they annotate survives a failure.
    ///
    /// With `prune` (a query's [`prune_table`](super::Automorphisms)), a new label that
    /// an automorphism maps the start to, landing on a dart smaller than the start,
    /// also ends the run: that match is found again, canonically, from that dart.
    ///
    /// [`steps`](Self::steps) grows by the symbols checked: all of `ops` when they
    /// hold, up to the failing one otherwise.
    #[inline]
    pub(crate) fn run(
        &mut self,
        map: &CMap3,
        consumed: Option<&BitSet>,
        t: usize,
        ops: &[u32],
        prune: Option<&[bool]>,
    ) -> bool {
        let (mut k, mut i) = (t / 3 + 1, t % 3 + 1);
        if k >= self.matched.len() {
            return false; // not a word of a connected query
        }
        let mut row = map.betas_raw(self.matched[k]);
        let mut ok = true;
        // The index of the symbol at which the word fails, if it does.
        let failed_at = 'walk: {
            for (n, &op) in ops.iter().enumerate() {
                let di = row[i];
                if op < NEW {
                    // (b): the dart already annotated with this label, and no other.
                    ok &= di == self.matched[op as usize];
                } else if op < FIRST_CONDITION {
                    // (a): a new dart, not ε, not annotated (nor ∅).
                    let label = op - NEW;
                    if !ok
                        || di == 0
                        || consumed.is_some_and(|c| c.get(di as usize))
                        || prune.is_some_and(|p| p[label as usize] && di < self.matched[1])
                        || !self.table.insert_new(di, label)
                    {
                        break 'walk n;
                    }
                    self.matched.push(di);
                } else if !self.condition(consumed, di, op) {
                    break 'walk n;
                }
                i += 1;
                if i == 4 && n + 1 < ops.len() {
                    if !ok {
                        break 'walk n;
                    }
                    i = 1;
                    k += 1;
                    // Breadth-first labels: dart k was reached from an earlier one.
                    row = map.betas_raw(self.matched[k]);
                }
            }
            self.steps += ops.len() as u64;
            return ok;
        };
        self.steps += failed_at as u64 + 1;
        false
    }

    /// A boundary condition of a 3-free query dart against its input dart βi(d_k).
    #[inline]
    fn condition(&mut self, consumed: Option<&BitSet>, di: u32, op: u32) -> bool {
        match op {
            ANY => true,
            BOUNDARY => di == 0,
            INTERIOR => di != 0,
            NO_CONNECTION => {
                if di == 0 || consumed.is_some_and(|c| c.get(di as usize)) {
                    return true;
                }
                // (c): reserve an unannotated dart so that no later label lands on it;
                // a labelled one fails. No dart is reserved twice: distinct query darts
                // match distinct input darts, and β3 is one-to-one.
                self.table.insert_new(di, RESERVED)
            }
            _ => unreachable!("unknown condition code {op}"),
        }
    }

    /// Algorithm 1: annotates `map` with `word` from `start`. On success the match is
    /// [`matched`](Self::matched) (query label k → input dart).
    ///
    /// ```
    /// use qmesh::build::{BuildOptions, build_volume_map};
    /// use qmesh::query::{Annotator, Condition, Query};
    /// let (grid, _) = build_volume_map(&qmesh::generate::hex_grid(2, 1, 1), &BuildOptions::default()).unwrap();
    /// let (one, _) = build_volume_map(&qmesh::generate::hex_grid(1, 1, 1), &BuildOptions::default()).unwrap();
    /// // One hexahedron whose faces must all be on the boundary matches nothing in a 2×1×1 grid …
    /// let q = Query::new("hex", one.clone(), |_| Condition::Boundary).unwrap();
    /// let mut a = Annotator::new(q.nb_darts());
    /// assert!(grid.darts().all(|s| !a.annotate(&grid, &q.word, s, None)));
    /// // … and any hexahedron matches from every dart (24 automorphisms × 2 cells).
    /// let q = Query::new("hex", one, |_| Condition::Any).unwrap();
    /// assert_eq!(grid.darts().filter(|&s| a.annotate(&grid, &q.word, s, None)).count(), 48);
    /// assert_eq!(a.matched().len(), 24);
    /// ```
    pub fn annotate(&mut self, map: &CMap3, word: &QueryWord, start: Dart, consumed: Option<&BitSet>) -> bool {
        if consumed.is_some_and(|c| c.get(start.idx())) {
            return false;
        }
        self.begin(start.raw());
        self.run(map, consumed, 0, word.ops(), None)
    }

    /// The input darts of the last successful annotation, in query label order.
    pub fn matched(&self) -> Vec<Dart> {
        self.matched[1..].iter().map(|&d| Dart::from_raw(d).expect("matched darts are not ε")).collect()
    }

    /// Raw input darts of the current annotation, label 1 first.
    #[inline]
    pub fn matched_raw(&self) -> &[u32] {
        &self.matched[1..]
    }

    /// Whether input dart `d` (raw) is annotated with a label in the current annotation.
    #[inline]
    pub(crate) fn is_labelled(&self, d: u32) -> bool {
        self.table.get(d).is_some_and(|v| v != RESERVED)
    }

    /// Symbols checked since this annotator was made.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}
