//! The catalogue from scratch: the enumerated subdivisions sorted into classes up to
//! the 48 symmetries and the 24 rotations of the cube, each class realised.

use rustc_hash::FxHashMap;

use super::{HexSplit, HexSplits, Labelled, OrientedClass, SplitClass, enumerate, image, realize, rules, to_vtk};
use crate::apps::cube;
use crate::build::HEX_CORNER_BITS;

/// Positions of the 8 corners.
type Corners = [[f64; 3]; 8];
/// A labelled subdivision keyed for sorting into classes:
/// (tetrahedra, canonical form up to 48, up to 24, diagonals, corner masks).
type Keyed = (usize, Vec<u8>, Vec<u8>, u8, Vec<u8>);

/// A realisation of `tets` moved by the cube isometry of corner permutation `s`: a
/// realisation of `image(tets, s)` (corner-bit order). An improper isometry reverses
/// both the geometry and the combinatorial orientation, so tetrahedra stay positive.
fn carry(p: &Corners, s: &[u8; 8]) -> Corners {
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

/// Corner-bit order to VTK node order.
fn vtk_corners(p: &Corners) -> Corners {
    std::array::from_fn(|i| p[HEX_CORNER_BITS[i] as usize])
}

/// Classes numbered by (tetrahedron count, canonical form up to the 48 symmetries);
/// oriented classes by first appearance in that order; the first member of a class is
/// its representative, realised, and its realisation is carried onto the other
/// oriented class of a chiral pair.
pub(super) fn from_enumeration() -> HexSplits {
    use rayon::prelude::*;
    let symmetries = cube::symmetries();
    let rotations = cube::rotations();
    let mut keyed: Vec<Keyed> = enumerate::all_subdivisions()
        .into_par_iter()
        .map(|(d, t)| (t.len(), canonical(&t, &symmetries), canonical(&t, &rotations), d, t))
        .collect();
    keyed.sort();
    let realizations: FxHashMap<Vec<u8>, Option<Corners>> = {
        let mut seen = rustc_hash::FxHashSet::default();
        let reps: Vec<(&Vec<u8>, u8)> =
            keyed.iter().filter(|k| seen.insert(k.1.clone())).map(|k| (&k.4, k.3)).collect();
        reps.into_par_iter()
            .map(|(t, d)| {
                let oriented = realize::orient(t, d).expect("enumerated subdivisions are balls");
                (t.clone(), realize::realize(&oriented).map(|p| realize::tidy(p, &oriented)))
            })
            .collect()
    };
    let mut class_of: FxHashMap<Vec<u8>, usize> = FxHashMap::default();
    let mut oriented_of: FxHashMap<Vec<u8>, usize> = FxHashMap::default();
    let mut classes: Vec<SplitClass> = Vec::new();
    let mut oriented: Vec<OrientedClass> = Vec::new();
    let mut splits = Vec::with_capacity(keyed.len());
    // Per class: its representative's masks and realisation (corner-bit order).
    let mut found: Vec<(Vec<u8>, Option<Corners>)> = Vec::new();
    for (_, c48, c24, diagonals, tets) in keyed {
        let oriented_tets = realize::orient(&tets, diagonals).expect("enumerated subdivisions are balls");
        let vtk_tets: Vec<[u8; 4]> = oriented_tets.iter().map(|&t| to_vtk(t)).collect();
        let class = *class_of.entry(c48).or_insert_with(|| {
            let realization = realizations[&tets];
            found.push((tets.clone(), realization));
            classes.push(SplitClass { tets: vtk_tets.clone(), members: 0, realization: None, oriented: Vec::new() });
            classes.len() - 1
        });
        classes[class].members += 1;
        let o = *oriented_of.entry(c24).or_insert_with(|| {
            classes[class].oriented.push(oriented.len());
            let (rep, p) = &found[class];
            let realization = p.map(|p| {
                let s = symmetries
                    .iter()
                    .find(|s| image(rep, s) == tets)
                    .expect("members of a class are images of its representative");
                realize::tidy(carry(&p, s), &oriented_tets)
            });
            oriented.push(OrientedClass {
                tets: vtk_tets.clone(),
                class,
                realization: realization.map(|p| vtk_corners(&p)),
                query_start: None,
                query_automorphisms: Vec::new(),
            });
            oriented.len() - 1
        });
        splits.push(HexSplit { tets: vtk_tets, diagonals, class, oriented: o });
    }
    let starts: Vec<Option<(u32, Vec<u32>)>> =
        oriented.par_iter().map(|o| o.realization.map(|p| rules::rule_start(&o.tets, &p))).collect();
    for (o, start) in oriented.iter_mut().zip(starts) {
        if let Some((start, automorphisms)) = start {
            o.query_start = Some(start);
            o.query_automorphisms = automorphisms;
        }
    }
    // A class is realised as its first oriented class (the representative carried by
    // the identity, rounded as stored).
    for c in &mut classes {
        c.realization = oriented[c.oriented[0]].realization;
    }
    HexSplits { classes, oriented, labelled: Labelled::new(splits).into() }
}
