//! Automorphisms of a query (2025 §5.2.2, "matches once per automorphism"): the start
//! darts from which the query matches itself. A match and its compositions with the
//! automorphisms cover the same input darts; [`Automorphisms::is_canonical`] keeps the
//! one starting at the smallest input dart.

use super::annotate::Annotator;
use super::fit::AffineFit;
use super::word::{Condition, Labelling, QueryWord};
use crate::cmap::{CMap3, Dart};

/// One non-identity automorphism, as a permutation of labels.
#[derive(Clone, Debug)]
struct Permutation {
    /// `image[k - 1]` = label of a(d_k).
    image: Vec<u32>,
    /// Whether it maps every 3-free dart to one with the same condition.
    keeps_conditions: bool,
}

/// The automorphisms of a query map with boundary (free β3 mapped to free β3).
#[derive(Clone, Debug, Default)]
pub struct Automorphisms {
    others: Vec<Permutation>,
}

impl Automorphisms {
    /// All automorphisms of the query `map` labelled by `labelling` with word `word`.
    pub fn of(map: &CMap3, labelling: &Labelling, word: &QueryWord) -> Automorphisms {
        let strict = word.with_all_conditions(Condition::Boundary);
        let mut a = Annotator::new(word.nb_darts());
        let start = labelling.darts[0];
        let mut others = Vec::new();
        for &s in &labelling.darts {
            if s == start || !a.annotate(map, &strict, s, None) {
                continue;
            }
            let image: Vec<u32> = a.matched_raw().iter().map(|&d| labelling.label[d as usize]).collect();
            let keeps_conditions =
                word.free_labels().all(|k| word.condition(k) == word.condition(image[k - 1] as usize));
            others.push(Permutation { image, keeps_conditions });
        }
        Automorphisms { others }
    }

    /// Automorphisms that keep the boundary conditions, identity included: how many
    /// times the query matches the same input darts.
    pub fn count(&self) -> usize {
        1 + self.others.iter().filter(|p| p.keeps_conditions).count()
    }

    /// Automorphisms of the bare map (conditions ignored), identity included.
    pub fn topological_count(&self) -> usize {
        1 + self.others.len()
    }

    /// For each label, whether it is the image of label 1 under an automorphism that
    /// keeps the conditions: once such a label lands on a dart smaller than the start,
    /// the match will be found from that dart and this start can stop.
    pub(crate) fn prune_table(&self, nb_darts: usize) -> Vec<bool> {
        let mut t = vec![false; nb_darts + 1];
        for p in self.others.iter().filter(|p| p.keeps_conditions) {
            t[p.image[0] as usize] = true;
        }
        t
    }

    /// How many automorphic images of the current match (itself included) fulfil the
    /// conditions: its copies when every copy is kept.
    pub(crate) fn valid_images(&self, map: &CMap3, word: &QueryWord, annot: &Annotator) -> usize {
        1 + self.others.iter().filter(|p| p.keeps_conditions || Self::fulfils(p, map, word, annot)).count()
    }

    /// Whether the current match of `annot` is the representative of its class: no
    /// automorphic image that also fulfils the conditions starts at a smaller dart.
    #[inline]
    pub(crate) fn is_canonical(&self, map: &CMap3, word: &QueryWord, annot: &Annotator) -> bool {
        let m = &annot.matched;
        let s = m[1];
        self.others.iter().all(|p| {
            let j = p.image[0] as usize;
            m[j] > s || (!p.keeps_conditions && !Self::fulfils(p, map, word, annot))
        })
    }

    /// The start dart of the automorphic image of the current match (itself included)
    /// that fulfils the conditions and whose affine fit from the query's positions is
    /// best: smallest residual, then closest to the query's orientation.
    /// Also returns that image's relative fit residual.
    pub(crate) fn best_image(&self, map: &CMap3, word: &QueryWord, fit: &AffineFit, annot: &Annotator) -> (u32, f64) {
        let m = &annot.matched;
        let pos = |d: u32| map.point(Dart::from_raw(d).expect("matched darts are not ε"));
        let mut best = (fit.score(|l| pos(m[l as usize])), m[1]);
        for p in &self.others {
            if !p.keeps_conditions && !Self::fulfils(p, map, word, annot) {
                continue;
            }
            let s = fit.score(|l| pos(m[p.image[l as usize - 1] as usize]));
            let tol = 1e-9 * (1.0 + best.0.0);
            if s.0 < best.0.0 - tol || (s.0 <= best.0.0 + tol && s.1 < best.0.1 - 1e-9) {
                best = (s, m[p.image[0] as usize]);
            }
        }
        (best.1, best.0.0)
    }

    /// Whether the match composed with `p` fulfils the query's conditions.
    fn fulfils(p: &Permutation, map: &CMap3, word: &QueryWord, annot: &Annotator) -> bool {
        word.free_labels().all(|k| {
            let x = annot.matched[p.image[k - 1] as usize];
            let y = map.beta_raw(x, 3);
            match word.condition(k).expect("free labels have conditions") {
                Condition::Any => true,
                Condition::Boundary => y == 0,
                Condition::Interior => y != 0,
                Condition::NoConnection => y == 0 || !annot.is_labelled(y),
            }
        })
    }
}
