//! Matching a set of queries from every start dart of a map, in parallel (rayon over
//! dart ranges; the map is only read). Results are in start-dart order, then prefix
//! tree order, whatever the number of threads.

use std::time::Instant;

use rayon::prelude::*;

use super::annotate::Annotator;
use super::guard::CornerGuards;
use super::metric::Metric;
use super::query_map::Query;
use super::trie::PrefixTree;
use crate::cmap::{BitSet, CMap3, Dart};

/// Several queries and the prefix tree of their words.
#[derive(Debug)]
pub struct QuerySet {
    pub queries: Vec<Query>,
    pub tree: PrefixTree,
    /// Per query, the labels whose placement proves a match not canonical.
    prune: Vec<Vec<bool>>,
    guards: CornerGuards,
}

impl QuerySet {
    /// The set of `queries` (their order is the query index of matches).
    pub fn new(queries: Vec<Query>) -> QuerySet {
        let tree = PrefixTree::new(queries.iter().map(|q| &q.word));
        let prune = queries.iter().map(|q| q.automorphisms.prune_table(q.nb_darts())).collect();
        let guards = CornerGuards::new(&tree, &queries);
        QuerySet { queries, tree, prune, guards }
    }

    /// An annotator large enough for every query of the set.
    pub fn annotator(&self) -> Annotator {
        Annotator::new(self.tree.max_darts())
    }

    /// The input darts of `m` in query label order (Algorithm 1 replayed: a match is
    /// determined by its query and start dart).
    ///
    /// # Panics
    /// If `m` is not a match of this set on `map` (the map changed since).
    pub fn darts_of(&self, map: &CMap3, m: &Match, annot: &mut Annotator) -> Vec<Dart> {
        let q = &self.queries[m.query as usize];
        let ok = annot.annotate(map, &q.word, m.start, None);
        assert!(ok, "match of query {} at dart {} no longer holds", q.name, m.start);
        annot.matched()
    }
}

/// One match: a query and the input dart its label 1 is annotated on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Match {
    pub query: u32,
    pub start: Dart,
    /// The metric's value (0 without a metric).
    pub score: f64,
}

/// Options of [`find_matches`].
#[derive(Clone, Copy, Debug, Default)]
pub struct MatchOptions<'a> {
    /// Keep every automorphic copy of a match instead of one per set of darts.
    pub all_automorphisms: bool,
    /// Score every match with this metric.
    pub metric: Option<&'a Metric>,
    /// Darts that count as annotated ∅ (already used).
    pub consumed: Option<&'a BitSet>,
    /// Only matches whose hexahedron (queries with hexahedral corners) has a scaled
    /// Jacobian above this: each corner is checked as soon as it is matched, and the
    /// walk leaves a branch when every query through it has a corner at or below.
    pub min_hex_quality: Option<f64>,
    /// The volume id of every input dart (by raw index): when given, the report lists
    /// the input volumes of each match ([`MatchReport::volumes`]), so that selecting
    /// among matches needs no second annotation.
    pub volume_of: Option<&'a [u32]>,
}

/// The input volumes of each match, sorted (filled when [`MatchOptions::volume_of`] is
/// given; empty otherwise).
#[derive(Clone, Debug, Default)]
pub struct MatchVolumes {
    at: Vec<u32>,
    ids: Vec<u32>,
}

impl MatchVolumes {
    /// The volumes of match `i`.
    pub fn of(&self, i: usize) -> &[u32] {
        &self.ids[self.at[i] as usize..self.at[i + 1] as usize]
    }

    /// Number of matches listed.
    pub fn len(&self) -> usize {
        self.at.len().saturating_sub(1)
    }

    /// Whether no match is listed.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Appends the volumes of the match annotated in `matched` (0-based by label).
    fn push(&mut self, query: &Query, matched: &[u32], volume_of: &[u32]) {
        if self.at.is_empty() {
            self.at.push(0);
        }
        let from = self.ids.len();
        self.ids.extend(query.volume_labels().iter().map(|&l| volume_of[matched[l as usize - 1] as usize]));
        self.ids[from..].sort_unstable();
        self.at.push(self.ids.len() as u32);
    }

    /// Gives back the capacity the lists do not use.
    fn shrink_to_fit(&mut self) {
        self.at.shrink_to_fit();
        self.ids.shrink_to_fit();
    }

    /// Appends every match of `other`.
    fn append(&mut self, other: MatchVolumes) {
        if other.at.is_empty() {
            return;
        }
        if self.at.is_empty() {
            self.at.push(0);
        }
        let base = self.ids.len() as u32;
        self.at.extend(other.at[1..].iter().map(|&a| a + base));
        self.ids.extend(other.ids);
    }
}

/// What [`find_matches`] found.
#[derive(Clone, Debug, Default)]
pub struct MatchReport {
    pub matches: Vec<Match>,
    /// Matches per query (after removing automorphic copies unless asked for all).
    pub per_query: Vec<usize>,
    /// Matches counting automorphic copies.
    pub with_automorphisms: Vec<usize>,
    /// The input volumes of each match, in the order of `matches` (with
    /// [`MatchOptions::volume_of`] only).
    pub volumes: MatchVolumes,
    /// Symbols checked (darts visited × 3, roughly): the annotation throughput.
    pub steps: u64,
    pub seconds: f64,
}

/// Relative fit residuals up to this much above `max_residual` are rounding: an exact
/// copy of the query passes a limit of 0.
const RESIDUAL_ROUNDING: f64 = 1e-12;

/// Start darts per parallel task at most: large enough to amortise scheduling, small
/// enough to balance two to dozens of threads.
const CHUNK: usize = 4096;

/// Start darts per parallel task on a map of `n` dart slots: [`CHUNK`], or less on small
/// maps so that every thread gets some (a start dart can cost a microsecond: a map of
/// a few thousand darts is milliseconds of work).
fn chunk_for(n: usize) -> usize {
    n.div_ceil(4 * rayon::current_num_threads()).clamp(64, CHUNK)
}

/// Matches every query of `set` from every live dart of `map`.
///
/// ```
/// use qmesh::build::{BuildOptions, build_volume_map};
/// use qmesh::query::{Condition, MatchOptions, Query, QuerySet, find_matches};
/// let opts = BuildOptions::default();
/// let (grid, _) = build_volume_map(&qmesh::generate::hex_grid(3, 3, 3), &opts).unwrap();
/// let (block, _) = build_volume_map(&qmesh::generate::hex_grid(2, 2, 2), &opts).unwrap();
/// let set = QuerySet::new(vec![Query::new("block", block, |_| Condition::Any).unwrap()]);
/// let r = find_matches(&grid, &set, &MatchOptions::default());
/// assert_eq!(set.queries[0].automorphisms.count(), 24);
/// assert_eq!((r.per_query[0], r.with_automorphisms[0]), (8, 8 * 24));
/// ```
pub fn find_matches(map: &CMap3, set: &QuerySet, opts: &MatchOptions<'_>) -> MatchReport {
    let t = Instant::now();
    let n = map.dart_capacity();
    // Fold then reduce (in start-dart order): one growing list per task instead of
    // one per chunk, so the lists merge in place (large ones are remapped, not
    // copied) and the peak memory stays near the matches' own size.
    let chunk = chunk_for(n);
    let found = (0..n.div_ceil(chunk))
        .into_par_iter()
        .fold(
            || (set.annotator(), Found::new(set.queries.len())),
            |(mut annot, mut found), c| {
                let before = annot.steps;
                for s in (c * chunk).max(1)..((c + 1) * chunk).min(n) {
                    let Some(start) = Dart::from_raw(s as u32).filter(|&d| map.is_live(d)) else { continue };
                    matches_at(map, set, opts, &mut annot, start, &mut found);
                }
                found.steps += annot.steps - before;
                (annot, found)
            },
        )
        .map(|(_, found)| found)
        .reduce(|| Found::new(set.queries.len()), Found::merge);
    // The lists grew by doubling: what follows (selection, replacement) keeps them,
    // so they give back the capacity they do not use.
    let (mut matches, mut volumes) = (found.matches, found.volumes);
    matches.shrink_to_fit();
    volumes.shrink_to_fit();
    let mut r = MatchReport {
        per_query: vec![0; set.queries.len()],
        with_automorphisms: found.all,
        steps: found.steps,
        volumes,
        ..Default::default()
    };
    for m in &matches {
        r.per_query[m.query as usize] += 1;
    }
    r.matches = matches;
    r.seconds = t.elapsed().as_secs_f64();
    r
}

/// The matches found over a range of start darts.
pub(crate) struct Found {
    pub(crate) matches: Vec<Match>,
    /// Per query, matches with their automorphic copies.
    pub(crate) all: Vec<usize>,
    steps: u64,
    volumes: MatchVolumes,
}

impl Found {
    pub(crate) fn new(queries: usize) -> Found {
        Found { matches: Vec::new(), all: vec![0; queries], steps: 0, volumes: MatchVolumes::default() }
    }

    /// `self` then `next` (the start darts after).
    fn merge(mut self, next: Found) -> Found {
        self.matches.extend(next.matches);
        self.all.iter_mut().zip(next.all).for_each(|(a, b)| *a += b);
        self.steps += next.steps;
        self.volumes.append(next.volumes);
        self
    }
}

/// The matches of every query of `set` whose label 1 is at `start` (after the filters
/// of `opts`: automorphic copies, hexahedron quality, geometric fit), appended to
/// `found.matches`; `found.all[q]` counts query q's matches with their automorphic
/// copies. With [`MatchOptions::volume_of`], the volumes of each match go to
/// `found.volumes`.
pub(crate) fn matches_at(
    map: &CMap3,
    set: &QuerySet,
    opts: &MatchOptions<'_>,
    annot: &mut Annotator,
    start: Dart,
    found: &mut Found,
) {
    let Found { matches: out, all, volumes, .. } = found;
    let prune = (!opts.all_automorphisms).then_some(set.prune.as_slice());
    let guard = opts.min_hex_quality.map(|t| (&set.guards, t));
    set.tree.walk(&set.queries, map, annot, start.raw(), opts.consumed, prune, guard, |q, a| {
        let query = &set.queries[q as usize];
        if let Some(t) = opts.min_hex_quality
            && query.matched_hex_quality(map, a.matched_raw()).is_some_and(|j| j <= t)
        {
            return;
        }
        if opts.all_automorphisms || query.automorphisms.is_canonical(map, &query.word, a) {
            let mut start = start;
            if let Some(fit) = (query.orient_by_geometry || query.max_residual.is_some()).then(|| query.fit()).flatten()
            {
                let (s, residual) = query.automorphisms.best_image(map, &query.word, fit, a);
                if query.max_residual.is_some_and(|limit| residual > limit + RESIDUAL_ROUNDING) {
                    return;
                }
                if query.orient_by_geometry && !opts.all_automorphisms {
                    start = Dart::from_raw(s).expect("matched darts are not ε");
                }
            }
            all[q as usize] +=
                if opts.all_automorphisms { 1 } else { query.automorphisms.valid_images(map, &query.word, a) };
            let score = opts.metric.map_or(0.0, |m| m.evaluate(map, query, a.matched_raw()));
            out.push(Match { query: q, start, score });
            if let Some(volume_of) = opts.volume_of {
                volumes.push(query, a.matched_raw(), volume_of);
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small map is shared among the threads (hexbeam's 2,880 darts were one task of
    /// 4,096 on one thread); a large one keeps tasks of [`CHUNK`].
    #[test]
    fn small_maps_give_every_thread_tasks() {
        let two = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        two.install(|| {
            assert_eq!(chunk_for(2_881), 361);
            assert!(2_881usize.div_ceil(chunk_for(2_881)) >= 2 * 2);
            assert_eq!(chunk_for(10), 64);
            assert_eq!(chunk_for(5_000_000), CHUNK);
        });
    }
}
