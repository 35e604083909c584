//! Choosing non-overlapping matches (2025 §5.2.2): order the candidates, then take
//! them one by one, dropping any that shares a dart with one already taken.
//!
//! `Greedy` takes them in start-dart order, which gives exactly the matches of the
//! paper's greedy search (annotating the darts of each selected match with ∅ before
//! the next start dart): a candidate found without that constraint is rejected by it
//! exactly when it shares a dart with a selected match.

use super::matcher::{Match, QuerySet};
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
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    match strategy {
        Strategy::Greedy => {}
        Strategy::Best => order.sort_by(|&a, &b| candidates[b].score.total_cmp(&candidates[a].score)),
        Strategy::Random(seed) => shuffle(&mut order, seed),
    }
    let mut used = BitSet::with_len(map.dart_capacity());
    let mut touched = BitSet::with_len(if separation == Separation::Vertices { map.positions().len() } else { 0 });
    let mut annot = set.annotator();
    let mut out = Vec::new();
    for i in order {
        if max.is_some_and(|m| out.len() >= m) {
            break;
        }
        let m = candidates[i];
        if used.get(m.start.idx()) {
            continue;
        }
        let darts = set.darts_of(map, &m, &mut annot);
        if darts.iter().any(|d| used.get(d.idx())) {
            continue;
        }
        if separation == Separation::Vertices {
            if darts.iter().any(|&d| touched.get(map.vertex_of(d) as usize)) {
                continue;
            }
            for &d in &darts {
                touched.insert(map.vertex_of(d) as usize);
            }
        }
        for d in &darts {
            used.insert(d.idx());
        }
        out.push(Selected { m, darts });
    }
    out
}

/// Fisher–Yates with SplitMix64: the same order for the same seed on every platform.
fn shuffle(v: &mut [usize], seed: u64) {
    let mut rng = crate::random::SplitMix64(seed);
    for i in (1..v.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        v.swap(i, j);
    }
}
