//! The subdivisions of a hexahedron into tetrahedra without new points (Pellerin,
//! Verhetsel & Remacle 2018, "There are 174 subdivisions of the hexahedron into
//! tetrahedra"), which 2025 §7.1 turns into recombination rules. qmesh enumerates them
//! itself ([`enumerate`]), groups them up to the 48 symmetries and up to the 24
//! rotations of the cube (a combinatorial map sees orientation, so a mirror image is
//! another query), and searches a positive realisation of each ([`realize`]).
//!
//! Corners are numbered in VTK hexahedron order everywhere in this module's API.
//!
//! The enumeration and the realisation search take about a second; every run of
//! `recombine` or `tetrahedralize` needs their result, so it is stored in `table.rs`,
//! generated from [`HexSplits::enumerate`] and checked against it by a test
//! (`stored::tests`), which also regenerates it (`QMESH_BLESS=1`). The recombination
//! rules compiled from it are stored the same way, in `rules.bin` (`rule_table`).
//!
//! ```
//! let s = qmesh::apps::HexSplits::get();
//! assert_eq!(s.classes.len(), 174);
//! assert_eq!(s.classes.iter().filter(|c| c.realization.is_some()).count(), 171);
//! assert_eq!(s.splits().len(), 6966);
//! ```

mod classify;
mod enumerate;
mod realize;
mod rule_table;
mod rules;
mod stored;
#[rustfmt::skip]
mod table;

use std::collections::BTreeMap;
use std::sync::OnceLock;

use crate::build::HEX_CORNER_BITS;
pub use rules::{HexRule, HexRuleError, HexTarget, hex_rules, split_query_mesh, split_target_mesh};

/// One subdivision of the hexahedron with labelled corners.
#[derive(Clone, Debug, PartialEq)]
pub struct HexSplit {
    /// Tetrahedra as VTK hexahedron node numbers, each in positive order.
    pub tets: Vec<[u8; 4]>,
    /// Bit f: the diagonal of [`HEX_FACES`]`[f]` joins its nodes 1 and 3 (else 0 and 2).
    pub diagonals: u8,
    /// Index in [`HexSplits::classes`].
    pub class: usize,
    /// Index in [`HexSplits::oriented`].
    pub oriented: usize,
}

impl HexSplit {
    /// Whether every tetrahedron is positive (volume above 10⁻⁹ of the hexahedron's
    /// bounding box) on a hexahedron with these nodes (VTK order) in `points`.
    pub fn is_positive_on(&self, nodes: &[u32; 8], points: &[[f64; 3]]) -> bool {
        let p: [[f64; 3]; 8] = std::array::from_fn(|i| points[nodes[i] as usize]);
        let b = crate::geom::Aabb::of(p.iter().copied()).extent();
        let eps = 1e-9 * b[0].max(b[1]).max(b[2]).powi(3);
        self.tets.iter().all(|&t| realize::det(&p, t) > eps)
    }
}

/// A class up to the 48 symmetries of the cube.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitClass {
    /// A representative (VTK node numbers, positive order).
    pub tets: Vec<[u8; 4]>,
    /// Labelled subdivisions in the class.
    pub members: usize,
    /// Node positions (VTK order) where every tetrahedron is positive, if one was found.
    pub realization: Option<[[f64; 3]; 8]>,
    /// Its classes up to rotation: one if it is its own mirror image, else two.
    pub oriented: Vec<usize>,
}

/// A class up to the 24 rotations.
#[derive(Clone, Debug, PartialEq)]
pub struct OrientedClass {
    /// A representative (VTK node numbers, positive order).
    pub tets: Vec<[u8; 4]>,
    pub class: usize,
    /// Node positions (VTK order) where every tetrahedron is positive, if found.
    pub realization: Option<[[f64; 3]; 8]>,
    /// With a realisation: the dart of the query map built from [`split_query_mesh`]
    /// whose word is the smallest, the start of the class's rule (see `rules`).
    pub query_start: Option<u32>,
    /// With a realisation: the labels that the rule query's automorphisms take label 1
    /// to (identity excluded), stored so that building the rules needs no search.
    pub query_automorphisms: Vec<u32>,
}

/// The faces of the hexahedron as VTK node quads, outward (right-hand normals), in the
/// order x = 0, x = 1, y = 0, y = 1, z = 0, z = 1 of the unit hexahedron (the cube's
/// faces through [`HEX_CORNER_BITS`]; checked by a test).
pub const HEX_FACES: [[u8; 4]; 6] =
    [[0, 4, 7, 3], [1, 2, 6, 5], [0, 1, 5, 4], [3, 7, 6, 2], [0, 3, 2, 1], [4, 5, 6, 7]];

/// A corner-bit tetrahedron in VTK node numbers (the renumbering is an involution).
fn to_vtk(t: [u8; 4]) -> [u8; 4] {
    t.map(|c| HEX_CORNER_BITS[c as usize] as u8)
}

/// The subdivision `tets` (corner masks) relabelled by the corner permutation `p`,
/// sorted.
fn image(tets: &[u8], p: &[u8; 8]) -> Vec<u8> {
    let mut v: Vec<u8> =
        tets.iter().map(|&m| (0..8).filter(|&c| m >> c & 1 == 1).fold(0u8, |r, c| r | 1 << p[c])).collect();
    v.sort_unstable();
    v
}

/// Every subdivision, its classes and their realisations.
#[derive(Debug)]
pub struct HexSplits {
    pub classes: Vec<SplitClass>,
    pub oriented: Vec<OrientedClass>,
    /// The labelled subdivisions, derived from `oriented` when first asked for.
    labelled: OnceLock<Labelled>,
}

/// The labelled subdivisions, ordered by oriented class, then diagonal choice, then
/// corner masks.
#[derive(Debug, PartialEq)]
struct Labelled {
    splits: Vec<HexSplit>,
    /// Indices into `splits` by diagonal choice.
    by_diagonals: Vec<Vec<u32>>,
}

impl Labelled {
    fn new(splits: Vec<HexSplit>) -> Labelled {
        let mut by_diagonals = vec![Vec::new(); 64];
        for (i, s) in splits.iter().enumerate() {
            by_diagonals[s.diagonals as usize].push(i as u32);
        }
        Labelled { splits, by_diagonals }
    }
}

impl HexSplits {
    /// The catalogue, read once per process from the stored table (the enumeration's
    /// result, checked by a test).
    pub fn get() -> &'static HexSplits {
        static CATALOGUE: OnceLock<HexSplits> = OnceLock::new();
        CATALOGUE.get_or_init(stored::from_table)
    }

    /// The catalogue computed from scratch: every subdivision enumerated, classified and
    /// realised (about a second on 2 cores). [`HexSplits::get`] returns the same,
    /// stored.
    pub fn enumerate() -> HexSplits {
        classify::from_enumeration()
    }

    /// Every labelled subdivision (6,966).
    pub fn splits(&self) -> &[HexSplit] {
        &self.labelled().splits
    }

    fn labelled(&self) -> &Labelled {
        self.labelled.get_or_init(|| stored::labelled(&self.oriented))
    }

    /// The subdivisions whose face diagonals are `diagonals` (bits as in [`HexSplit`]).
    pub fn with_diagonals(&self, diagonals: u8) -> impl Iterator<Item = &HexSplit> + '_ {
        let l = self.labelled();
        l.by_diagonals[diagonals as usize & 63].iter().map(|&i| &l.splits[i as usize])
    }

    /// Number of classes per tetrahedron count (up to the 48 symmetries).
    pub fn histogram(&self) -> BTreeMap<usize, usize> {
        let mut h = BTreeMap::new();
        for c in &self.classes {
            *h.entry(c.tets.len()).or_insert(0) += 1;
        }
        h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_match_pellerin_et_al() {
        let s = HexSplits::get();
        assert_eq!(s.classes.len(), 174);
        assert_eq!(s.classes.iter().filter(|c| c.realization.is_some()).count(), 171);
        let h = s.histogram();
        assert_eq!((h.keys().next(), h.keys().last()), (Some(&5), Some(&15)));
        assert_eq!(h[&5], 1);
        assert_eq!(s.classes.iter().map(|c| c.members).sum::<usize>(), s.splits().len());
        // Up to rotation a class is one or two (a chiral pair) oriented classes.
        assert_eq!(s.classes.iter().map(|c| c.oriented.len()).sum::<usize>(), s.oriented.len());
        assert!(s.classes.iter().all(|c| matches!(c.oriented.len(), 1 | 2)));
        assert_eq!(s.oriented.len(), 336);
        // Every labelled subdivision is listed under its own diagonals.
        for d in 0..64u8 {
            assert!(s.with_diagonals(d).all(|x| x.diagonals == d));
        }
        assert_eq!((0..64u8).map(|d| s.with_diagonals(d).count()).sum::<usize>(), s.splits().len());
    }

    #[test]
    fn every_realisation_is_positive() {
        let s = HexSplits::get();
        for (i, o) in s.oriented.iter().enumerate() {
            if let Some(p) = o.realization {
                for t in &o.tets {
                    assert!(realize::det(&p, *t) > 0.0, "oriented class {i}, tet {t:?}");
                }
            }
            assert_eq!(o.realization.is_some(), s.classes[o.class].realization.is_some());
        }
    }

    #[test]
    fn hex_faces_are_the_cube_faces_in_vtk_numbers() {
        for (f, quad) in crate::apps::cube::faces().iter().enumerate() {
            assert_eq!(HEX_FACES[f], quad.map(|c| HEX_CORNER_BITS[c as usize] as u8), "face {f}");
        }
    }
}
