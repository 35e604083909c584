//! The subdivisions of a hexahedron into tetrahedra without new points (Pellerin,
//! Verhetsel & Remacle 2018, "There are 174 subdivisions of the hexahedron into
//! tetrahedra"), which 2025 §7.1 turns into recombination rules. qmesh enumerates them
//! itself ([`enumerate`]), groups them up to the 48 symmetries and up to the 24
//! rotations of the cube (a combinatorial map sees orientation, so a mirror image is
//! another query), and searches a positive realisation of each ([`realize`]).
//!
//! Corners are numbered in VTK hexahedron order everywhere in this module's API.
//!
//! ```
//! let s = qmesh::apps::HexSplits::get();
//! assert_eq!(s.classes.len(), 174);
//! assert_eq!(s.classes.iter().filter(|c| c.realization.is_some()).count(), 171);
//! ```

mod enumerate;
mod realize;
mod rules;

use std::collections::BTreeMap;
use std::sync::OnceLock;

use rustc_hash::FxHashMap;

use crate::apps::cube;
use crate::build::HEX_CORNER_BITS;
pub use rules::{HexRule, HexRuleError, hex_rules, split_query_mesh, split_target_mesh};

/// One subdivision of the hexahedron with labelled corners.
#[derive(Clone, Debug)]
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
#[derive(Clone, Debug)]
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
#[derive(Clone, Debug)]
pub struct OrientedClass {
    /// A representative (VTK node numbers, positive order).
    pub tets: Vec<[u8; 4]>,
    pub class: usize,
    /// Node positions (VTK order) where every tetrahedron is positive, if found.
    pub realization: Option<[[f64; 3]; 8]>,
}

/// The faces of the hexahedron as VTK node quads, outward (right-hand normals), in the
/// order x = 0, x = 1, y = 0, y = 1, z = 0, z = 1 of the unit hexahedron (the cube's
/// faces through [`HEX_CORNER_BITS`]; checked by a test).
pub const HEX_FACES: [[u8; 4]; 6] =
    [[0, 4, 7, 3], [1, 2, 6, 5], [0, 1, 5, 4], [3, 7, 6, 2], [0, 3, 2, 1], [4, 5, 6, 7]];

/// Positions of the 8 corners.
type Corners = [[f64; 3]; 8];
/// A labelled subdivision keyed for sorting into classes.
type Keyed = (usize, Vec<u8>, Vec<u8>, u8, Vec<u8>);

/// Every subdivision, its classes and their realisations.
#[derive(Debug)]
pub struct HexSplits {
    pub splits: Vec<HexSplit>,
    pub classes: Vec<SplitClass>,
    pub oriented: Vec<OrientedClass>,
    /// Indices into `splits` by diagonal choice.
    by_diagonals: Vec<Vec<u32>>,
}

fn to_vtk(t: [u8; 4]) -> [u8; 4] {
    t.map(|c| HEX_CORNER_BITS[c as usize] as u8)
}

/// The subdivision `tets` relabelled by the corner permutation `p`, sorted.
fn image(tets: &[u8], p: &[u8; 8]) -> Vec<u8> {
    let mut v: Vec<u8> =
        tets.iter().map(|&m| (0..8).filter(|&c| m >> c & 1 == 1).fold(0u8, |r, c| r | 1 << p[c])).collect();
    v.sort_unstable();
    v
}

/// A realisation of `tets` moved by the cube isometry of corner permutation `s`: a
/// realisation of `image(tets, s)` (corner-bit order). An improper isometry reverses
/// both the geometry and the combinatorial orientation, so tetrahedra stay positive.
fn carry(p: &[[f64; 3]; 8], s: &[u8; 8]) -> [[f64; 3]; 8] {
    let origin = cube::corner(s[0]);
    let axes: [[f64; 3]; 3] = std::array::from_fn(|k| crate::geom::sub(cube::corner(s[1 << k]), origin));
    let map = |x: [f64; 3]| -> [f64; 3] {
        std::array::from_fn(|j| origin[j] + (0..3).map(|k| x[k] * axes[k][j]).sum::<f64>())
    };
    let mut out = [[0.0; 3]; 8];
    for c in 0..8 {
        out[s[c] as usize] = map(p[c]);
    }
    out
}

fn canonical(tets: &[u8], perms: &[[u8; 8]]) -> Vec<u8> {
    perms.iter().map(|p| image(tets, p)).min().expect("the group is not empty")
}

impl HexSplits {
    /// The catalogue, computed once per process (a few tens of milliseconds).
    pub fn get() -> &'static HexSplits {
        static CATALOGUE: OnceLock<HexSplits> = OnceLock::new();
        CATALOGUE.get_or_init(HexSplits::compute)
    }

    fn compute() -> HexSplits {
        let all = enumerate::all_subdivisions();
        let symmetries = cube::symmetries();
        let rotations = cube::rotations();
        let mut class_of: FxHashMap<Vec<u8>, usize> = FxHashMap::default();
        let mut oriented_of: FxHashMap<Vec<u8>, usize> = FxHashMap::default();
        let mut classes: Vec<SplitClass> = Vec::new();
        let mut oriented: Vec<OrientedClass> = Vec::new();
        let mut splits = Vec::with_capacity(all.len());
        // Per class: its representative's masks and realisation (corner-bit order).
        let mut found: Vec<(Vec<u8>, Option<Corners>)> = Vec::new();
        let mut by_diagonals = vec![Vec::new(); 64];
        // Classes are numbered by (tetrahedron count, canonical form).
        // (tets, canonical up to 48, canonical up to 24, diagonals, tets)
        let mut keyed: Vec<Keyed> = all
            .into_iter()
            .map(|(d, t)| (t.len(), canonical(&t, &symmetries), canonical(&t, &rotations), d, t))
            .collect();
        keyed.sort();
        // The first member of each class is its representative: realise those in parallel.
        let realizations: FxHashMap<Vec<u8>, Option<Corners>> = {
            use rayon::prelude::*;
            let mut seen = rustc_hash::FxHashSet::default();
            let reps: Vec<(&Vec<u8>, u8)> =
                keyed.iter().filter(|k| seen.insert(k.1.clone())).map(|k| (&k.4, k.3)).collect();
            reps.into_par_iter()
                .map(|(t, d)| {
                    let oriented = realize::orient(t, d).expect("enumerated subdivisions are balls");
                    (t.clone(), realize::realize(&oriented))
                })
                .collect()
        };
        for (_, c48, c24, diagonals, tets) in keyed {
            let oriented_tets = realize::orient(&tets, diagonals).expect("enumerated subdivisions are balls");
            let class = *class_of.entry(c48).or_insert_with(|| {
                let realization = realizations[&tets];
                found.push((tets.clone(), realization));
                classes.push(SplitClass {
                    tets: oriented_tets.iter().map(|&t| to_vtk(t)).collect(),
                    members: 0,
                    realization: realization.map(|p| std::array::from_fn(|i| p[HEX_CORNER_BITS[i] as usize])),
                    oriented: Vec::new(),
                });
                classes.len() - 1
            });
            classes[class].members += 1;
            let o = *oriented_of.entry(c24).or_insert_with(|| {
                classes[class].oriented.push(oriented.len());
                // The class's realisation carried by the symmetry onto this member.
                let (rep, p) = &found[class];
                let realization = p.map(|p| {
                    let s = symmetries
                        .iter()
                        .find(|s| image(rep, s) == tets)
                        .expect("members of a class are images of its representative");
                    carry(&p, s)
                });
                oriented.push(OrientedClass {
                    tets: oriented_tets.iter().map(|&t| to_vtk(t)).collect(),
                    class,
                    realization: realization.map(|p| std::array::from_fn(|i| p[HEX_CORNER_BITS[i] as usize])),
                });
                oriented.len() - 1
            });
            by_diagonals[diagonals as usize].push(splits.len() as u32);
            splits.push(HexSplit {
                tets: oriented_tets.iter().map(|&t| to_vtk(t)).collect(),
                diagonals,
                class,
                oriented: o,
            });
        }
        HexSplits { splits, classes, oriented, by_diagonals }
    }

    /// The subdivisions whose face diagonals are `diagonals` (bits as in [`HexSplit`]).
    pub fn with_diagonals(&self, diagonals: u8) -> impl Iterator<Item = &HexSplit> + '_ {
        self.by_diagonals[diagonals as usize & 63].iter().map(|&i| &self.splits[i as usize])
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
        assert_eq!(s.classes.iter().map(|c| c.members).sum::<usize>(), s.splits.len());
        // Up to rotation a class is one or two (a chiral pair) oriented classes.
        assert_eq!(s.classes.iter().map(|c| c.oriented.len()).sum::<usize>(), s.oriented.len());
        assert!(s.classes.iter().all(|c| matches!(c.oriented.len(), 1 | 2)));
        assert_eq!(s.oriented.len(), 336);
        // Every labelled subdivision is listed under its own diagonals.
        for d in 0..64u8 {
            assert!(s.with_diagonals(d).all(|x| x.diagonals == d));
        }
        assert_eq!((0..64u8).map(|d| s.with_diagonals(d).count()).sum::<usize>(), s.splits.len());
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
        for (f, quad) in cube::faces().iter().enumerate() {
            assert_eq!(HEX_FACES[f], quad.map(|c| HEX_CORNER_BITS[c as usize] as u8), "face {f}");
        }
    }
}
