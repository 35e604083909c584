//! Choosing non-overlapping matches (2025 §5.2.2): order the candidates, then take
//! them one by one, dropping any that shares a dart with one already taken.
//!
//! `Greedy` takes them in start-dart order, which gives exactly the matches of the
//! paper's greedy search (annotating the darts of each selected match with ∅ before
//! the next start dart): a candidate found without that constraint is rejected by it
//! exactly when it shares a dart with a selected match.

use super::annotate::Annotator;
use super::matcher::{Found, Match, MatchOptions, MatchVolumes, QuerySet, matches_at};
use crate::cmap::{BitSet, CMap3, Dart};

/// In which order candidates are taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// Start-dart order (then prefix-tree order).
    Greedy,
    /// Decreasing score (ties in start-dart order).
    Best,
    /// A shuffled order, reproducible from the seed.
    Random(u64),
}

impl Strategy {
    /// Reads `greedy`, `best` or `random` (seeded with `seed`).
    pub fn parse(s: &str, seed: u64) -> Option<Strategy> {
        match s {
            "greedy" => Some(Strategy::Greedy),
            "best" => Some(Strategy::Best),
            "random" => Some(Strategy::Random(seed)),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Strategy::Greedy => "greedy",
            Strategy::Best => "best",
            Strategy::Random(_) => "random",
        }
    }
}

/// What two selected matches may not share.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Separation {
    /// A dart (2025 §5.2.2: matches do not overlap).
    #[default]
    Darts,
    /// A vertex: no two selected matches touch, so an edit that moves a match's
    /// vertices (flatten-top) cannot undo another's.
    Vertices,
}

impl Separation {
    /// Reads `darts` or `vertices`.
    pub fn parse(s: &str) -> Option<Separation> {
        match s {
            "darts" => Some(Separation::Darts),
            "vertices" => Some(Separation::Vertices),
            _ => None,
        }
    }
}

/// A selected match with its input darts in query label order.
#[derive(Clone, Debug)]
pub struct Selected {
    pub m: Match,
    pub darts: Vec<Dart>,
}

/// Selects non-overlapping matches among `candidates` (all from [`find_matches`]
/// on this `map`), at most `max` of them.
///
/// [`find_matches`]: super::find_matches
pub fn select(
    map: &CMap3,
    set: &QuerySet,
    candidates: &[Match],
    strategy: Strategy,
    max: Option<usize>,
) -> Vec<Selected> {
    select_separated(map, set, candidates, strategy, max, Separation::Darts)
}

/// As [`select`], with matches kept apart by `separation`.
pub fn select_separated(
    map: &CMap3,
    set: &QuerySet,
    candidates: &[Match],
    strategy: Strategy,
    max: Option<usize>,
    separation: Separation,
) -> Vec<Selected> {
    let mut taken = Taken::new(map, separation);
    let mut annot = set.annotator();
    let mut out = Vec::new();
    for i in order(candidates, strategy) {
        if max.is_some_and(|m| out.len() >= m) {
            break;
        }
        out.extend(taken.take(map, set, candidates[i], &mut annot));
    }
    out
}

/// As [`select`], with the input volumes of every candidate known (`volumes`, from
/// [`MatchOptions::volume_of`] over `nb_volumes` volumes), returning the indices of
/// the selected candidates: a match covers whole volumes, so two matches share a dart
/// exactly when they share a volume, and no match is annotated again (the caller
/// gets the darts of the few it keeps with [`QuerySet::darts_of`]).
pub fn select_by_volumes(
    candidates: &[Match],
    volumes: &MatchVolumes,
    nb_volumes: usize,
    strategy: Strategy,
) -> Vec<usize> {
    assert_eq!(volumes.len(), candidates.len(), "the volumes of every candidate");
    let mut used = BitSet::with_len(nb_volumes);
    let mut out = Vec::new();
    for i in order(candidates, strategy) {
        let vs = volumes.of(i);
        if vs.iter().any(|&v| used.get(v as usize)) {
            continue;
        }
        vs.iter().for_each(|&v| {
            used.insert(v as usize);
        });
        out.push(i);
    }
    out
}

/// The candidates' indices in the order `strategy` takes them.
fn order(candidates: &[Match], strategy: Strategy) -> Vec<usize> {
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    match strategy {
        Strategy::Greedy => {}
        Strategy::Best => order.sort_by(|&a, &b| candidates[b].score.total_cmp(&candidates[a].score)),
        Strategy::Random(seed) => shuffle(&mut order, seed),
    }
    order
}

/// What [`select_random_lazily`] looked at.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LazySearch {
    /// Start darts matched.
    pub starts_tested: usize,
    /// Matches found from them (one per set of darts).
    pub matches: usize,
    /// The same counting automorphic copies.
    pub with_automorphisms: usize,
}

/// `Strategy::Random` with a `max`, without finding every match first: start darts
/// are drawn in a seeded random order (a lazily drawn Fisher–Yates permutation of the
/// darts) and matched one by one, the darts already taken counting as ∅, until `max`
/// matches are taken or every dart was tried. On a large map where a few matches are
/// wanted (the 50 spots of 2025 §7.4) it looks at a few hundred darts instead of all.
pub fn select_random_lazily(
    map: &CMap3,
    set: &QuerySet,
    opts: &MatchOptions<'_>,
    seed: u64,
    max: usize,
    separation: Separation,
) -> (Vec<Selected>, LazySearch) {
    let mut taken = Taken::new(map, separation);
    let mut annot = set.annotator();
    let mut order = LazyPermutation::new(map.dart_capacity(), seed);
    let mut found = Found::new(set.queries.len());
    let mut out = Vec::new();
    let mut stats = LazySearch::default();
    while out.len() < max {
        let Some(raw) = order.next() else { break };
        let Some(start) = Dart::from_raw(raw as u32).filter(|&d| map.is_live(d) && !taken.used.get(d.idx())) else {
            continue;
        };
        stats.starts_tested += 1;
        found.matches.clear();
        let consumed = MatchOptions { consumed: Some(&taken.used), ..*opts };
        matches_at(map, set, &consumed, &mut annot, start, &mut found);
        stats.matches += found.matches.len();
        // The matches from one start all hold that dart: at most one of them is taken.
        for &m in &found.matches {
            out.extend(taken.take(map, set, m, &mut annot));
        }
    }
    stats.with_automorphisms = found.all.iter().sum();
    (out, stats)
}

/// The darts (and vertices) of the matches selected so far.
struct Taken {
    used: BitSet,
    touched: BitSet,
    separation: Separation,
}

impl Taken {
    fn new(map: &CMap3, separation: Separation) -> Taken {
        let vertices = if separation == Separation::Vertices { map.positions().len() } else { 0 };
        Taken { used: BitSet::with_len(map.dart_capacity()), touched: BitSet::with_len(vertices), separation }
    }

    /// Takes `m` unless it shares a dart (or a vertex) with a match taken before.
    fn take(&mut self, map: &CMap3, set: &QuerySet, m: Match, annot: &mut Annotator) -> Option<Selected> {
        if self.used.get(m.start.idx()) {
            return None;
        }
        let darts = set.darts_of(map, &m, annot);
        if darts.iter().any(|d| self.used.get(d.idx())) {
            return None;
        }
        if self.separation == Separation::Vertices {
            if darts.iter().any(|&d| self.touched.get(map.vertex_of(d) as usize)) {
                return None;
            }
            for &d in &darts {
                self.touched.insert(map.vertex_of(d) as usize);
            }
        }
        for d in &darts {
            self.used.insert(d.idx());
        }
        Some(Selected { m, darts })
    }
}

/// 0..n in a uniformly random order drawn as it is read: Fisher–Yates on a virtual
/// array whose swapped entries alone are stored.
struct LazyPermutation {
    n: usize,
    i: usize,
    swapped: rustc_hash::FxHashMap<usize, usize>,
    rng: crate::random::SplitMix64,
}

impl LazyPermutation {
    fn new(n: usize, seed: u64) -> LazyPermutation {
        LazyPermutation { n, i: 0, swapped: Default::default(), rng: crate::random::SplitMix64(seed) }
    }
}

impl Iterator for LazyPermutation {
    type Item = usize;

    fn next(&mut self) -> Option<usize> {
        if self.i >= self.n {
            return None;
        }
        let (i, j) = (self.i, self.i + self.rng.below(self.n - self.i));
        let at = |k: usize, m: &rustc_hash::FxHashMap<usize, usize>| m.get(&k).copied().unwrap_or(k);
        let (a, b) = (at(j, &self.swapped), at(i, &self.swapped));
        self.swapped.insert(j, b);
        self.swapped.remove(&i);
        self.i += 1;
        Some(a)
    }
}

/// Fisher–Yates with SplitMix64: the same order for the same seed on every platform.
fn shuffle(v: &mut [usize], seed: u64) {
    let mut rng = crate::random::SplitMix64(seed);
    for i in (1..v.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        v.swap(i, j);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lazy_permutation_draws_every_index_once() {
        for (n, seed) in [(1, 0), (2, 5), (10, 1), (1000, 42)] {
            let mut drawn: Vec<usize> = LazyPermutation::new(n, seed).collect();
            assert!(n < 10 || drawn.windows(2).any(|w| w[0] > w[1]), "n = {n}: drawn in order");
            drawn.sort_unstable();
            assert_eq!(drawn, (0..n).collect::<Vec<_>>(), "n = {n}");
        }
    }

    /// Every permutation is reachable, those with fixed points included (a variant
    /// that always swaps with a smaller index, Sattolo's, only draws cycles).
    #[test]
    fn shuffle_draws_permutations_with_and_without_fixed_points() {
        let shuffled = |seed: u64| {
            let mut v: Vec<usize> = (0..10).collect();
            shuffle(&mut v, seed);
            v
        };
        let fixed_points = |v: &[usize]| v.iter().enumerate().filter(|&(i, &x)| i == x).count();
        let all: Vec<Vec<usize>> = (0..30).map(shuffled).collect();
        for v in &all {
            let mut sorted = v.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..10).collect::<Vec<_>>());
        }
        assert!(all.iter().any(|v| fixed_points(v) > 0) && all.iter().any(|v| fixed_points(v) < 10));
        assert_eq!(shuffled(3), shuffled(3));
    }
}
