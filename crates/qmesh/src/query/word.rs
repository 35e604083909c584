//! Query words (2025 Def. 3–5, §5.1.2): a breadth-first labelling of a query map and,
//! for every dart in label order, the labels of its β1, β2 and β3 neighbours, with a
//! boundary condition in place of the label of a free β3.

use super::error::QueryError;
use crate::cmap::{CMap3, Dart};

/// What a 3-free query dart may be matched to (2025 §5.1.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Condition {
    /// `*`: any input dart, sewn or not.
    Any,
    /// `ε`: an input dart that is 3-free (on the mesh boundary).
    Boundary,
    /// `ε̄`: an input dart that is 3-sewn.
    Interior,
    /// `↔`: an input dart not 3-sewn to another dart of the same match.
    NoConnection,
}

/// Symbol codes of the conditions in a word; labels are 1..=n, far below these.
pub(crate) const ANY: u32 = u32::MAX;
pub(crate) const BOUNDARY: u32 = u32::MAX - 1;
pub(crate) const INTERIOR: u32 = u32::MAX - 2;
pub(crate) const NO_CONNECTION: u32 = u32::MAX - 3;
/// Symbols at or above this are conditions.
pub(crate) const FIRST_CONDITION: u32 = NO_CONNECTION;
/// In compiled words (`ops`), set on a label that is new at its position (the next
/// label of the breadth-first order), so matching knows without comparing.
pub(crate) const NEW: u32 = 1 << 30;

impl Condition {
    /// Every condition, in the order of the paper's table.
    pub const ALL: [Condition; 4] = [Condition::Any, Condition::Boundary, Condition::Interior, Condition::NoConnection];

    /// Reads a condition as users write it: `*`/`any`, `eps`/`ε`/`boundary`,
    /// `interior`/`ε̄`/`sewn`, `no-connection`/`↔`/`apart`.
    pub fn parse(s: &str) -> Option<Condition> {
        match s.trim() {
            "*" | "any" | "wildcard" => Some(Condition::Any),
            "eps" | "ε" | "epsilon" | "boundary" | "free" => Some(Condition::Boundary),
            "interior" | "ε̄" | "eps-bar" | "not-eps" | "sewn" => Some(Condition::Interior),
            "no-connection" | "↔" | "<->" | "apart" => Some(Condition::NoConnection),
            _ => None,
        }
    }

    /// The paper's symbol.
    pub fn symbol(self) -> &'static str {
        match self {
            Condition::Any => "*",
            Condition::Boundary => "ε",
            Condition::Interior => "ε̄",
            Condition::NoConnection => "↔",
        }
    }

    /// The name [`parse`](Self::parse) accepts in ASCII.
    pub fn name(self) -> &'static str {
        match self {
            Condition::Any => "*",
            Condition::Boundary => "eps",
            Condition::Interior => "interior",
            Condition::NoConnection => "no-connection",
        }
    }

    pub(crate) fn code(self) -> u32 {
        match self {
            Condition::Any => ANY,
            Condition::Boundary => BOUNDARY,
            Condition::Interior => INTERIOR,
            Condition::NoConnection => NO_CONNECTION,
        }
    }

    pub(crate) fn of_code(c: u32) -> Option<Condition> {
        match c {
            ANY => Some(Condition::Any),
            BOUNDARY => Some(Condition::Boundary),
            INTERIOR => Some(Condition::Interior),
            NO_CONNECTION => Some(Condition::NoConnection),
            _ => None,
        }
    }
}

/// A breadth-first labelling of a connected query map (2025 Def. 3): from a start
/// dart, neighbours visited in the order β1, β2, β3, labels given in prefix order.
#[derive(Clone, Debug)]
pub struct Labelling {
    /// `darts[k - 1]` is the dart labelled k.
    pub darts: Vec<Dart>,
    /// Label of each raw dart index (0 = unlabelled, ε, or dead).
    pub label: Vec<u32>,
}

impl Labelling {
    /// Labels the map from `start`.
    ///
    /// # Errors
    /// [`QueryError::Empty`], [`QueryError::Free`] when a dart is 1- or 2-free (the
    /// query must be closed in dimensions 1 and 2, 2025 §5), and
    /// [`QueryError::NotConnected`] when some live dart is not reached.
    pub fn new(map: &CMap3, start: Dart) -> Result<Labelling, QueryError> {
        if map.nb_darts() == 0 || !map.is_live(start) {
            return Err(QueryError::Empty);
        }
        let mut label = vec![0u32; map.dart_capacity()];
        let mut darts = vec![start];
        label[start.idx()] = 1;
        let mut k = 0;
        while k < darts.len() {
            let d = darts[k];
            k += 1;
            for i in 1..=3 {
                let Some(n) = map.beta(d, i) else {
                    if i < 3 {
                        return Err(QueryError::free(map, d, i));
                    }
                    continue;
                };
                if label[n.idx()] == 0 {
                    darts.push(n);
                    label[n.idx()] = darts.len() as u32;
                }
            }
        }
        if darts.len() != map.nb_darts() {
            let missed = map.darts().find(|d| label[d.idx()] == 0).expect("some dart was not reached");
            return Err(QueryError::NotConnected {
                reached: darts.len(),
                total: map.nb_darts(),
                face: super::error::describe_face(map, missed),
            });
        }
        Ok(Labelling { darts, label })
    }

    /// Number of labelled darts.
    pub fn len(&self) -> usize {
        self.darts.len()
    }

    /// Whether no dart is labelled (never true for a built labelling).
    pub fn is_empty(&self) -> bool {
        self.darts.is_empty()
    }

    /// Label of `d` (1-based).
    #[inline]
    pub fn of(&self, d: Dart) -> u32 {
        self.label[d.idx()]
    }
}

/// The symbol of a compiled symbol (`NEW` cleared on labels; conditions, which have
/// that bit too, as they are).
#[inline]
fn symbol_of_op(s: u32) -> u32 {
    if s < FIRST_CONDITION { s & !NEW } else { s }
}

/// A query word (2025 Def. 5): `3n` symbols, symbol 3(k-1) + (i-1) = l(βi(d_k)), or
/// the condition code of d_k when i = 3 and d_k is 3-free.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct QueryWord {
    /// The symbols as matching reads them: [`NEW`] set on labels met for the first
    /// time (the symbols themselves are these without it).
    ops: Vec<u32>,
}

impl AsRef<QueryWord> for QueryWord {
    fn as_ref(&self) -> &QueryWord {
        self
    }
}

impl QueryWord {
    /// The word of `map` under `labelling`, with `condition(d)` for each 3-free dart d.
    pub fn new(map: &CMap3, labelling: &Labelling, mut condition: impl FnMut(Dart) -> Condition) -> QueryWord {
        let mut symbols = Vec::with_capacity(3 * labelling.len());
        for &d in &labelling.darts {
            for i in 1..=3 {
                symbols.push(match map.beta(d, i) {
                    Some(n) => labelling.of(n),
                    None => condition(d).code(),
                });
            }
        }
        QueryWord::from_symbols(symbols)
    }

    /// The word of these symbols (labels, and condition codes on free β3), as
    /// [`symbols`](Self::symbols) gives them back: for words stored compiled.
    pub(crate) fn from_symbols(symbols: Vec<u32>) -> QueryWord {
        let mut seen = 1; // label 1 is the start dart
        let ops = symbols
            .into_iter()
            .map(|s| {
                if s < FIRST_CONDITION && s > seen {
                    seen = s;
                    s | NEW
                } else {
                    s
                }
            })
            .collect();
        QueryWord { ops }
    }

    /// The compiled symbols matching reads.
    #[inline]
    pub(crate) fn ops(&self) -> &[u32] {
        &self.ops
    }

    /// Number of darts of the query.
    #[inline]
    pub fn nb_darts(&self) -> usize {
        self.ops.len() / 3
    }

    /// All symbols, in order.
    pub fn symbols(&self) -> impl ExactSizeIterator<Item = u32> + '_ {
        self.ops.iter().map(|&s| symbol_of_op(s))
    }

    /// The symbol of βi (i in 1..=3) of the dart labelled k (k in 1..=n).
    #[inline]
    pub fn symbol(&self, k: usize, i: usize) -> u32 {
        symbol_of_op(self.ops[3 * (k - 1) + (i - 1)])
    }

    /// The condition of the dart labelled k, when it is 3-free in the query.
    pub fn condition(&self, k: usize) -> Option<Condition> {
        Condition::of_code(self.symbol(k, 3))
    }

    /// The volume of each label (`volumes[k]` for label k; index 0 unused), volumes
    /// numbered in the order of their smallest label: labels joined by β1 or β2 are in
    /// one volume (a query is closed under both). Also returns the number of volumes.
    pub(crate) fn volumes_of_labels(&self) -> (Vec<u32>, usize) {
        let n = self.nb_darts();
        let mut volume = vec![u32::MAX; n + 1];
        let (mut count, mut stack) = (0, Vec::new());
        for k in 1..=n {
            if volume[k] != u32::MAX {
                continue;
            }
            volume[k] = count;
            stack.push(k);
            while let Some(x) = stack.pop() {
                for i in 1..=2 {
                    let y = self.symbol(x, i) as usize;
                    if volume[y] == u32::MAX {
                        volume[y] = count;
                        stack.push(y);
                    }
                }
            }
            count += 1;
        }
        (volume, count as usize)
    }

    /// The smallest label of each volume of the query, ascending.
    pub(crate) fn volume_firsts(&self) -> Vec<u32> {
        let (volume, count) = self.volumes_of_labels();
        let mut firsts = Vec::with_capacity(count);
        for (k, &v) in volume.iter().enumerate().skip(1) {
            if v as usize == firsts.len() {
                firsts.push(k as u32);
            }
        }
        firsts
    }

    /// Labels of the 3-free darts.
    pub fn free_labels(&self) -> impl Iterator<Item = usize> + '_ {
        (1..=self.nb_darts()).filter(|&k| self.symbol(k, 3) >= FIRST_CONDITION)
    }

    /// Sets the condition of the 3-free dart labelled k.
    ///
    /// # Panics
    /// If that dart is 3-sewn in the query.
    pub fn set_condition(&mut self, k: usize, c: Condition) {
        let s = &mut self.ops[3 * (k - 1) + 2];
        assert!(*s >= FIRST_CONDITION, "dart {k} of the query is 3-sewn");
        *s = c.code();
    }

    /// The same word with every condition replaced by `c`.
    pub fn with_all_conditions(&self, c: Condition) -> QueryWord {
        QueryWord { ops: self.ops.iter().map(|&s| if s >= FIRST_CONDITION { c.code() } else { s }).collect() }
    }

    /// Human-readable form, `⟨2,5,ε | 3,…⟩`-like, for tests and audits.
    pub fn display(&self) -> String {
        let symbols: Vec<u32> = self.symbols().collect();
        let parts: Vec<String> = symbols
            .chunks(3)
            .map(|c| {
                c.iter()
                    .map(|&s| Condition::of_code(s).map_or_else(|| s.to_string(), |c| c.symbol().to_string()))
                    .collect::<Vec<_>>()
                    .join(",")
            })
            .collect();
        format!("⟨{}⟩", parts.join(" | "))
    }
}
