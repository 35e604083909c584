//! Recombination rules (2025 §7.1): per oriented class of subdivision with a positive
//! realisation, the query is its tetrahedra sewn together with `↔` on every 3-free
//! dart (no folded match with fewer than 8 vertices), and the target one volume, the
//! hexahedron with its six faces triangulated as the query's boundary.

use super::{HEX_FACES, HexSplits};
use crate::build::{BuildError, BuildOptions, CellKind, IndexedMesh, build_volume_map};
use crate::cmap::{CMap3, Dart};
use crate::modify::{ModifyError, Plan};
use crate::query::{Condition, Query, QueryError};

/// One recombination rule: its query and what replaces a match.
#[derive(Clone, Debug)]
pub struct HexRule {
    pub query: Query,
    pub target: HexTarget,
}

/// What replaces a match of a [`HexRule`]'s query: one hexahedron.
#[derive(Clone, Debug)]
pub struct HexTarget {
    /// Index in [`HexSplits::oriented`].
    pub oriented: usize,
    /// Per VTK node, the label of a query dart at that node.
    pub corners: [u32; 8],
    /// Per face of [`HEX_FACES`], the labels of the two boundary darts along its
    /// diagonal (one in each triangle).
    pub diagonals: [[u32; 2]; 6],
    /// A boundary dart on an edge of the hexahedron (not a diagonal): it stays in the
    /// hexahedron's volume whatever is merged later.
    pub keep: u32,
}

impl HexTarget {
    /// The target map: one volume bounded by the query's 12 boundary triangles, on the
    /// class's realisation.
    ///
    /// # Errors
    /// Only on a defect of the generated maps (never expected; tested).
    pub fn map(&self) -> Result<CMap3, HexRuleError> {
        let class = &HexSplits::get().oriented[self.oriented];
        let points = class.realization.expect("only realised classes get rules");
        build_volume_map(&split_target_mesh(&class.tets, &points), &BuildOptions::default())
            .map(|(map, _)| map)
            .map_err(|source| HexRuleError::Build { class: class.class, source })
    }

    /// The modify plan replacing a match of `query` (this target's) by the hexahedron.
    /// Built on demand, with the target map: a recombination needs the plans of the
    /// classes it uses only.
    ///
    /// # Errors
    /// Only on a defect of the generated maps (never expected; tested).
    pub fn plan(&self, query: &Query) -> Result<Plan, HexRuleError> {
        Plan::replace(query, &self.map()?)
            .map_err(|source| HexRuleError::Plan { class: HexSplits::get().oriented[self.oriented].class, source })
    }
}

/// Why the rules could not be built (a defect of qmesh, reported rather than hidden).
#[derive(Debug, thiserror::Error)]
pub enum HexRuleError {
    #[error("subdivision class {class}: {source}")]
    Build { class: usize, source: BuildError },
    #[error("subdivision class {class}: {source}")]
    Query { class: usize, source: QueryError },
    #[error("subdivision class {class}: {source}")]
    Plan { class: usize, source: ModifyError },
}

/// The outward boundary triangles of positively oriented tetrahedra (the faces in one
/// tetrahedron only).
fn boundary(tets: &[[u8; 4]]) -> Vec<[u8; 3]> {
    let faces = |t: &[u8; 4]| [[t[0], t[2], t[1]], [t[0], t[1], t[3]], [t[1], t[2], t[3]], [t[0], t[3], t[2]]];
    let key = |f: &[u8; 3]| f.iter().fold(0u8, |m, &c| m | 1 << c);
    let mut count = [0u8; 256];
    tets.iter().flat_map(faces).for_each(|f| count[key(&f) as usize] += 1);
    tets.iter().flat_map(faces).filter(|f| count[key(f) as usize] == 1).collect()
}

/// The query mesh of a subdivision: its tetrahedra on the realisation's points.
pub fn split_query_mesh(tets: &[[u8; 4]], points: &[[f64; 3]; 8]) -> IndexedMesh {
    let mut m = IndexedMesh::new();
    m.points = points.to_vec();
    for t in tets {
        m.push_cell(CellKind::Tet, &t.map(u32::from), None);
    }
    m
}

/// The target mesh: one polyhedron bounded by the subdivision's 12 boundary triangles.
pub fn split_target_mesh(tets: &[[u8; 4]], points: &[[f64; 3]; 8]) -> IndexedMesh {
    let mut m = IndexedMesh::new();
    m.points = points.to_vec();
    let tris = boundary(tets);
    let mut stream = vec![tris.len() as u32];
    for t in &tris {
        stream.push(3);
        stream.extend(t.iter().map(|&c| u32::from(c)));
    }
    m.push_cell(CellKind::Polyhedron, &stream, None);
    m
}

/// The start dart whose word is the smallest (lexicographically, conditions last) in
/// the query map of `tets` on `points`: the same rule for every query, so words share
/// long prefixes in the tree, and closing labels (smaller than new ones) come as early
/// as possible, so a walk fails early. On Armadillo (149,675 tets) this cuts the
/// symbols checked from 3.8 G (first dart) to 0.63 G. Stored in the catalogue
/// ([`super::OrientedClass::query_start`]), as it takes a word per dart.
pub(super) fn smallest_word_start(tets: &[[u8; 4]], points: &[[f64; 3]; 8]) -> u32 {
    let (map, _) = build_volume_map(&split_query_mesh(tets, points), &BuildOptions::default())
        .expect("enumerated subdivisions are valid complexes");
    let word = |d: Dart| -> Vec<u32> {
        let l = crate::query::Labelling::new(&map, d).expect("query maps are connected");
        crate::query::QueryWord::new(&map, &l, |_| Condition::NoConnection).symbols().to_vec()
    };
    map.darts().min_by_key(|&d| word(d)).expect("not empty").raw()
}

/// One rule per oriented class that has a positive realisation (2025 §7.1: 171 classes
/// up to symmetry, each chiral one in both mirror images).
///
/// # Errors
/// Only on a defect of the generated maps (never expected; tested).
pub fn hex_rules() -> Result<Vec<HexRule>, HexRuleError> {
    use rayon::prelude::*;
    let splits = HexSplits::get();
    let realised: Vec<usize> =
        (0..splits.oriented.len()).filter(|&o| splits.oriented[o].realization.is_some()).collect();
    realised.into_par_iter().map(|o| rule_of(splits, o)).collect()
}

/// The rule of oriented class `o` (which has a realisation).
fn rule_of(splits: &HexSplits, o: usize) -> Result<HexRule, HexRuleError> {
    let class = &splits.oriented[o];
    {
        let points = class.realization.expect("only realised classes get rules");
        let err_class = class.class;
        let opts = BuildOptions::default();
        let (qmap, _) = build_volume_map(&split_query_mesh(&class.tets, &points), &opts)
            .map_err(|source| HexRuleError::Build { class: err_class, source })?;
        let start = class.query_start.and_then(Dart::from_raw).expect("realised classes have a start");
        let mut query = Query::from_valid_start(&format!("hex-split-{o}"), qmap, start, |_| Condition::NoConnection)
            .map_err(|source| HexRuleError::Query { class: err_class, source })?;
        let corners: [u32; 8] = std::array::from_fn(|i| {
            query.labelling.darts.iter().position(|&d| query.map.vertex_of(d) == i as u32).expect("every node is used")
                as u32
                + 1
        });
        query.set_corners(corners);
        let diagonals = HEX_FACES.map(|q| {
            let on = |d: Dart, a: u8, b: u8| {
                let (u, v) = (query.map.vertex_of(d), query.map.vertex_of(query.map.next(d)));
                (u, v) == (a.into(), b.into()) || (u, v) == (b.into(), a.into())
            };
            let free: Vec<Dart> = query.labelling.darts.iter().copied().filter(|&d| query.map.is_free(d, 3)).collect();
            let pick = |a: u8, b: u8| -> Vec<u32> {
                free.iter().filter(|&&d| on(d, a, b)).map(|&d| query.labelling.of(d)).collect()
            };
            let (a, b) = (pick(q[0], q[2]), pick(q[1], q[3]));
            let found = if a.len() == 2 { a } else { b };
            [found[0], found[1]]
        });
        let on_diagonal = |l: u32| diagonals.iter().flatten().any(|&x| x == l);
        let keep = query.word.free_labels().map(|k| k as u32).find(|&k| !on_diagonal(k)).expect("hexahedron edges");
        Ok(HexRule { query, target: HexTarget { oriented: o, corners, diagonals, keep } })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_valid_rule_per_realisable_oriented_class_with_distinct_words() {
        let splits = HexSplits::get();
        let rules = hex_rules().unwrap();
        assert_eq!(rules.len(), splits.oriented.iter().filter(|o| o.realization.is_some()).count());
        let plans: Vec<Plan> = rules.iter().map(|r| r.target.plan(&r.query).unwrap()).collect();
        // Canonical words are a complete invariant of connected maps: two rules share a
        // word only when one complex of tetrahedra is a hexahedron in two ways (other
        // corners), and then both readings must stay (they score differently).
        let mut by_word: rustc_hash::FxHashMap<&[u32], Vec<&HexRule>> = Default::default();
        rules.iter().for_each(|r| by_word.entry(r.query.word.symbols()).or_default().push(r));
        for same in by_word.values().filter(|v| v.len() > 1) {
            assert_eq!(same.len(), 2);
            // Same labels, other corners: the same darts read as another hexahedron.
            let (a, b) = (&same[0].target, &same[1].target);
            assert_ne!(a.corners, b.corners, "a duplicate rule");
            assert_eq!(splits.oriented[a.oriented].tets.len(), splits.oriented[b.oriented].tets.len());
        }
        assert_eq!(by_word.len(), rules.len() - 10, "330 rules, 320 distinct words");
        for (r, plan) in rules.iter().zip(&plans) {
            let tets = splits.oriented[r.target.oriented].tets.len();
            assert_eq!(r.query.nb_darts(), 12 * tets);
            assert_eq!(r.query.nb_volumes(), tets);
            assert!(r.query.map.is_valid().is_empty());
            // The 36 boundary darts stay (the hexahedron's), the others go.
            assert_eq!(plan.darts_removed(), 12 * tets - 36, "{}", r.query.name);
            assert_eq!(plan.darts_added(), 0);
            for (f, d) in r.target.diagonals.iter().enumerate() {
                let q = HEX_FACES[f];
                let v = |l: u32| r.query.map.vertex_of(r.query.labelling.darts[l as usize - 1]);
                for &l in d {
                    let mut e =
                        [v(l), r.query.map.vertex_of(r.query.map.next(r.query.labelling.darts[l as usize - 1]))];
                    e.sort_unstable();
                    let mut a = [u32::from(q[0]), u32::from(q[2])];
                    let mut b = [u32::from(q[1]), u32::from(q[3])];
                    a.sort_unstable();
                    b.sort_unstable();
                    assert!(e == a || e == b);
                }
            }
        }
    }
}
