//! m_QT (2025 §6): how the query sits in the target (extend), the target in the query
//! (delete), or the query's boundary on the target's (replace). Found by matching one
//! map in the other; among several placements (automorphisms) the one whose darts'
//! positions coincide best is taken, since users build the target from the query in a
//! modeler (2025 §6, §8).

use crate::cmap::{CMap3, Dart};
use crate::query::{Annotator, Condition, Query};
use crate::signature::{Flags, Surface, word_from};

/// Sum of squared distances between the origins of corresponding darts.
fn residual(a: &CMap3, b: &CMap3, pairs: impl Iterator<Item = (Dart, Dart)>) -> f64 {
    pairs
        .map(|(x, y)| {
            let (p, q) = (a.point(x), b.point(y));
            (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
        })
        .sum()
}

/// The placement of `small` inside `big` (label k of `small` → dart of `big`) whose
/// geometry fits best, ignoring boundary conditions (of equally good ones, the one
/// from the first start dart); None if `small` does not occur.
pub fn embed(small: &Query, big: &CMap3) -> Option<Vec<Dart>> {
    let word = small.word.with_all_conditions(Condition::Any);
    let mut a = Annotator::new(small.nb_darts());
    let mut best: Option<(f64, Vec<Dart>)> = None;
    for s in big.darts() {
        if !a.annotate(big, &word, s, None) {
            continue;
        }
        let m = a.matched();
        let r = residual(small.map(), big, small.labelling().darts.iter().copied().zip(m.iter().copied()));
        if best.as_ref().is_none_or(|b| r < b.0) {
            best = Some((r, m));
        }
    }
    best.map(|b| b.1)
}

/// A correspondence between the boundary surfaces (3-free darts) of `q` and `t`, as
/// pairs (dart of q, dart of t): of the isomorphisms, the one whose positions coincide
/// best (of equally good ones, the one from t's first start dart); None when the
/// boundaries are not isomorphic.
pub fn boundary_correspondence(q: &CMap3, t: &CMap3) -> Option<Vec<(Dart, Dart)>> {
    let q0 = q.darts().find(|&d| q.is_free(d, 3))?;
    let qw = word_from(q, Surface::PatternBoundary, Flags::None, q0, None)?;
    let nq = q.darts().filter(|&d| q.is_free(d, 3)).count();
    let nt = t.darts().filter(|&d| t.is_free(d, 3)).count();
    if qw.darts.len() != nq || nq != nt {
        return None; // several boundary components, or boundaries of different sizes
    }
    let mut best: Option<(f64, Vec<(Dart, Dart)>)> = None;
    for s in t.darts().filter(|&d| t.is_free(d, 3)) {
        let Some(tw) = word_from(t, Surface::PatternBoundary, Flags::None, s, Some(&qw.word)) else { continue };
        if tw.word != qw.word {
            continue;
        }
        let pairs: Vec<(Dart, Dart)> = qw.darts.iter().copied().zip(tw.darts.iter().copied()).collect();
        let r = residual(q, t, pairs.iter().copied());
        if best.as_ref().is_none_or(|b| r < b.0) {
            best = Some((r, pairs));
        }
    }
    best.map(|b| b.1)
}
