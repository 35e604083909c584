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
    /// For queries with hexahedral corners, whether it maps corners to corners as a
    /// symmetry of the cube (always true otherwise): only then do its images score the
    /// same and may stand for each other (pruning, canonical start).
    cube: bool,
}

/// The automorphisms of a query map with boundary (free β3 mapped to free β3).
#[derive(Clone, Debug, Default)]
pub struct Automorphisms {
    others: Vec<Permutation>,
}

/// A per-dart invariant of every automorphism: the sizes of the ⟨β2, β3⟩ orbits (the
/// edges' incidences) of the dart's face edges, from the dart on, and whether it is
/// 3-free. An automorphism commutes with every β, so it can only map a start dart to
/// one with the same signature; on tetrahedral queries (alike everywhere at first
/// sight) this rejects almost every other start before an annotation.
struct EdgeSignatures {
    /// Per raw dart index: the ⟨β2, β3⟩ orbit size of its edge.
    edge_size: Vec<u32>,
}

impl EdgeSignatures {
    fn of(map: &CMap3, labelling: &Labelling) -> EdgeSignatures {
        let mut edge_size = vec![0u32; map.dart_capacity()];
        for &d in &labelling.darts {
            edge_size[d.idx()] = Self::edge_orbit_size(map, d);
        }
        EdgeSignatures { edge_size }
    }

    /// Darts of the ⟨β2, β3⟩ orbit of `d`: a cycle or a path alternating β2 and β3.
    fn edge_orbit_size(map: &CMap3, d: Dart) -> u32 {
        let mut n = 1;
        for first in [2, 3] {
            let (mut x, mut i) = (d, first);
            while let Some(y) = map.beta(x, i) {
                if y == d {
                    return n; // a cycle: every dart counted once
                }
                (x, i, n) = (y, 5 - i, n + 1);
            }
        }
        n
    }

    /// Whether `a` and `b` have the same signature.
    fn same(&self, a: Dart, b: Dart, map: &CMap3) -> bool {
        let (mut x, mut y) = (a, b);
        loop {
            if self.edge_size[x.idx()] != self.edge_size[y.idx()] {
                return false;
            }
            (x, y) = (map.next(x), map.next(y));
            if x == a || y == b {
                return x == a && y == b && map.is_free(a, 3) == map.is_free(b, 3);
            }
        }
    }
}

impl Automorphisms {
    /// All automorphisms of the query `map` labelled by `labelling` with word `word`.
    pub fn of(map: &CMap3, labelling: &Labelling, word: &QueryWord) -> Automorphisms {
        let start = labelling.darts[0];
        let signature = EdgeSignatures::of(map, labelling);
        let candidates = labelling.darts.iter().copied().filter(|&s| s != start && signature.same(s, start, map));
        Self::from_candidates(map, labelling, word, candidates)
    }

    /// The automorphisms taking label 1 to the labels `starts`, which [`of`](Self::of)
    /// found before ([`start_labels`](Self::start_labels)): for rule books computed
    /// once and stored. A start from which the query does not match itself is skipped.
    pub(crate) fn from_starts(map: &CMap3, labelling: &Labelling, word: &QueryWord, starts: &[u32]) -> Automorphisms {
        let candidates = starts.iter().filter_map(|&l| labelling.darts.get(l as usize - 1).copied());
        Self::from_candidates(map, labelling, word, candidates)
    }

    /// Each automorphism other than the identity: the image of every label (label k
    /// goes to `image[k - 1]`), whether it keeps the boundary conditions, and whether
    /// it moves the hexahedral corners as a cube symmetry (see
    /// [`restrict_to_corner_symmetries`](Self::restrict_to_corner_symmetries)).
    #[cfg(test)]
    pub(crate) fn images(&self) -> impl Iterator<Item = (&[u32], bool, bool)> {
        self.others.iter().map(|p| (p.image.as_slice(), p.keeps_conditions, p.cube))
    }

    /// The automorphisms that `images` (test-only) listed: for queries stored compiled.
    pub(crate) fn from_images(images: impl IntoIterator<Item = (Vec<u32>, bool, bool)>) -> Automorphisms {
        let others =
            images.into_iter().map(|(image, keeps_conditions, cube)| Permutation { image, keeps_conditions, cube });
        Automorphisms { others: others.collect() }
    }

    /// The image of label 1 under each automorphism other than the identity.
    pub(crate) fn start_labels(&self) -> Vec<u32> {
        self.others.iter().map(|p| p.image[0]).collect()
    }

    /// The automorphisms starting at those of `candidates` from which the query
    /// matches itself (boundary conditions strict: free β3 onto free β3).
    fn from_candidates(
        map: &CMap3,
        labelling: &Labelling,
        word: &QueryWord,
        candidates: impl Iterator<Item = Dart>,
    ) -> Automorphisms {
        thread_local! {
            // One annotator per thread for every query compiled on it (rule books
            // compile hundreds of queries).
            static ANNOTATOR: std::cell::RefCell<Annotator> = std::cell::RefCell::new(Annotator::new(0));
        }
        let strict = word.with_all_conditions(Condition::Boundary);
        let mut others = Vec::new();
        ANNOTATOR.with_borrow_mut(|a| {
            a.reserve(word.nb_darts());
            for s in candidates {
                if !a.annotate(map, &strict, s, None) {
                    continue;
                }
                let image: Vec<u32> = a.matched_raw().iter().map(|&d| labelling.label[d as usize]).collect();
                let keeps_conditions =
                    word.free_labels().all(|k| word.condition(k) == word.condition(image[k - 1] as usize));
                others.push(Permutation { image, keeps_conditions, cube: true });
            }
        });
        Automorphisms { others }
    }

    /// Automorphisms that keep the boundary conditions, identity included: how many
    /// times the query matches the same input darts.
    pub fn count(&self) -> usize {
        1 + self.others.iter().filter(|p| p.keeps_conditions).count()
    }

    /// Keeps as equivalent only the automorphisms that move the hexahedral `corners`
    /// (labels at VTK nodes) as a symmetry of the cube would: another automorphism of
    /// the tetrahedra reads a different hexahedron on the same darts, with another
    /// quality, so its images are matches of their own.
    pub(crate) fn restrict_to_corner_symmetries(&mut self, map: &CMap3, labelling: &Labelling, corners: &[u32; 8]) {
        const EDGES: [[usize; 2]; 12] =
            [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]];
        let vertex = |l: u32| map.vertex_of(labelling.darts[l as usize - 1]);
        let node_of = |v: u32| (0..8).find(|&i| vertex(corners[i]) == v);
        for p in &mut self.others {
            let moved: Option<Vec<usize>> = (0..8).map(|i| node_of(vertex(p.image[corners[i] as usize - 1]))).collect();
            let cube = moved.is_some_and(|m| {
                EDGES.iter().all(|&[a, b]| EDGES.iter().any(|&[x, y]| [m[a], m[b]] == [x, y] || [m[a], m[b]] == [y, x]))
            });
            p.cube = cube;
        }
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
        for p in self.others.iter().filter(|p| p.keeps_conditions && p.cube) {
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
            m[j] > s || !p.cube || (!p.keeps_conditions && !Self::fulfils(p, map, word, annot))
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
