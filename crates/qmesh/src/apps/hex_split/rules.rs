//! Recombination rules (2025 §7.1): per oriented class of subdivision with a positive
//! realisation, the query is its tetrahedra sewn together with `↔` on every 3-free
//! dart (no folded match with fewer than 8 vertices), and the target one volume, the
//! hexahedron with its six faces triangulated as the query's boundary.

#[cfg(test)]
use super::HEX_FACES;
use super::HexSplits;
use crate::build::{BuildError, BuildOptions, CellKind, IndexedMesh, build_volume_map};
use crate::cmap::{CMap3, Dart, Standard};
use crate::modify::{ModifyError, Plan};
use crate::query::{Automorphisms, Condition, Labelling, Query, QueryError, QueryWord};

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
    /// Per face of [`HEX_FACES`](super::HEX_FACES), the labels of the two boundary darts along its
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

/// The query map of a subdivision: the map [`build_volume_map`] makes of
/// [`split_query_mesh`] (the same darts, 12 per tetrahedron in order, so the stored
/// start darts hold), sewn directly: two tetrahedra of a subdivision share a face
/// exactly when they share its three corners, and a ball has no other contact.
pub(super) fn split_query_map(tets: &[[u8; 4]], points: &[[f64; 3]; 8]) -> CMap3 {
    let mut map = CMap3::with_positions(points.to_vec(), 12 * tets.len());
    let mut out = [0u32; 24];
    // Per corner mask of a triangle, the first dart of the face seen with it.
    let mut seen: [Option<Dart>; 256] = [None; 256];
    for t in tets {
        map.make_standard_cell(Standard::Tet, &t.map(u32::from), &mut out);
        for first in [out[0], out[3], out[6], out[9]] {
            let d = Dart::from_raw(first).expect("created darts are not ε");
            let face = [d, map.next(d), map.prev(d)];
            let mask = face.iter().fold(0u8, |m, &x| m | 1 << map.vertex_of(x));
            let Some(other) = seen[mask as usize].replace(d) else { continue };
            // The dart of the other face along d's edge, the other way.
            let (a, b) = (map.vertex_of(d), map.vertex_of(map.next(d)));
            let mut y = other;
            while (map.vertex_of(y), map.vertex_of(map.next(y))) != (b, a) {
                y = map.next(y);
            }
            map.link_faces3(d, y);
        }
    }
    map
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
/// Also returns the labels that the query's automorphisms take label 1 to
/// ([`super::OrientedClass::query_automorphisms`]).
pub(super) fn rule_start(tets: &[[u8; 4]], points: &[[f64; 3]; 8]) -> (u32, Vec<u32>) {
    let map = split_query_map(tets, points);
    let word = |l: &Labelling| QueryWord::new(&map, l, |_| Condition::NoConnection);
    let labelling = |d: Dart| Labelling::new(&map, d).expect("query maps are connected");
    let start = map.darts().min_by_key(|&d| word(&labelling(d)).symbols().collect::<Vec<_>>()).expect("not empty");
    let l = labelling(start);
    (start.raw(), Automorphisms::of(&map, &l, &word(&l)).start_labels())
}

/// One rule per oriented class that has a positive realisation (2025 §7.1: 171 classes
/// up to symmetry, each chiral one in both mirror images), read from the stored table
/// (`rule_table.rs`; each is what the test-only `compile_rule` makes of its class).
///
/// # Errors
/// None today: the stored rules are checked by a test. The `Result` stays for the
/// plans and target maps built from them later.
pub fn hex_rules() -> Result<Vec<HexRule>, HexRuleError> {
    Ok(super::rule_table::stored_rules())
}

/// The rule of oriented class `o` (which has a realisation), compiled from its query
/// map: what the stored table holds.
#[cfg(test)]
pub(super) fn compile_rule(splits: &HexSplits, o: usize) -> Result<HexRule, HexRuleError> {
    let class = &splits.oriented[o];
    {
        let points = class.realization.expect("only realised classes get rules");
        let err_class = class.class;
        let qmap = split_query_map(&class.tets, &points);
        let start = class.query_start.and_then(Dart::from_raw).expect("realised classes have a start");
        // Every node is a vertex id of the query map: its corner is the first label there.
        let corners = |map: &CMap3, labelling: &Labelling| -> [u32; 8] {
            let mut corners = [0u32; 8];
            for (k, &d) in labelling.darts.iter().enumerate().rev() {
                corners[map.vertex_of(d) as usize] = k as u32 + 1;
            }
            corners
        };
        let query = Query::from_valid_start_with_corners(
            &format!("hex-split-{o}"),
            qmap,
            start,
            |_| Condition::NoConnection,
            corners,
            Some(&class.query_automorphisms),
        )
        .map_err(|source| HexRuleError::Query { class: err_class, source })?;
        let corners = query.corners.expect("given");
        let (map, labelling) = (query.map(), query.labelling());
        // Per pair of nodes, the face of [`HEX_FACES`] it is a diagonal of; each boundary
        // dart along one goes to its face, in label order (one pass over the free darts).
        let mut face_of = [[u8::MAX; 8]; 8];
        for (f, q) in HEX_FACES.iter().enumerate() {
            for (a, b) in [(q[0], q[2]), (q[1], q[3])] {
                (face_of[a as usize][b as usize], face_of[b as usize][a as usize]) = (f as u8, f as u8);
            }
        }
        let mut diagonals = [[0u32; 2]; 6];
        let mut found = [0usize; 6];
        for &d in labelling.darts.iter().filter(|&&d| map.is_free(d, 3)) {
            let f = face_of[map.vertex_of(d) as usize][map.vertex_of(map.next(d)) as usize];
            if let Some(slot) = diagonals.get_mut(f as usize) {
                slot[found[f as usize]] = labelling.of(d);
                found[f as usize] += 1;
            }
        }
        debug_assert_eq!(found, [2; 6], "each face of a subdivision has one diagonal, two boundary darts along it");
        let on_diagonal = |l: u32| diagonals.iter().flatten().any(|&x| x == l);
        let keep = query.word.free_labels().map(|k| k as u32).find(|&k| !on_diagonal(k)).expect("hexahedron edges");
        Ok(HexRule { query, target: HexTarget { oriented: o, corners, diagonals, keep } })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct sewing gives the general builder's map dart for dart, on every
    /// realised class.
    #[test]
    fn direct_query_maps_equal_the_general_builder() {
        for o in &HexSplits::get().oriented {
            let Some(points) = o.realization else { continue };
            let direct = split_query_map(&o.tets, &points);
            let (built, report) =
                build_volume_map(&split_query_mesh(&o.tets, &points), &BuildOptions::default()).unwrap();
            assert_eq!(report.split_vertices, 0);
            assert_eq!(direct.dart_capacity(), built.dart_capacity());
            for d in built.darts() {
                for i in 0..=3 {
                    assert_eq!(direct.beta(d, i), built.beta(d, i), "class {}: β{i} of dart {}", o.class, d.raw());
                }
                assert_eq!(direct.vertex_of(d), built.vertex_of(d));
            }
            assert!(direct.is_valid().is_empty());
        }
    }

    #[test]
    fn one_valid_rule_per_realisable_oriented_class_with_distinct_words() {
        let splits = HexSplits::get();
        let rules = hex_rules().unwrap();
        assert_eq!(rules.len(), splits.oriented.iter().filter(|o| o.realization.is_some()).count());
        let plans: Vec<Plan> = rules.iter().map(|r| r.target.plan(&r.query).unwrap()).collect();
        // Canonical words are a complete invariant of connected maps: two rules share a
        // word only when one complex of tetrahedra is a hexahedron in two ways (other
        // corners), and then both readings must stay (they score differently).
        let mut by_word: rustc_hash::FxHashMap<Vec<u32>, Vec<&HexRule>> = Default::default();
        rules.iter().for_each(|r| by_word.entry(r.query.word.symbols().collect()).or_default().push(r));
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
            // The stored automorphisms are those a search finds.
            let searched = Automorphisms::of(r.query.map(), r.query.labelling(), &r.query.word);
            assert_eq!(searched.start_labels(), r.query.automorphisms.start_labels(), "{}", r.query.name);
            assert_eq!(searched.count(), r.query.automorphisms.count());
            assert!(r.query.map().is_valid().is_empty());
            // The 36 boundary darts stay (the hexahedron's), the others go.
            assert_eq!(plan.darts_removed(), 12 * tets - 36, "{}", r.query.name);
            assert_eq!(plan.darts_added(), 0);
            for (f, d) in r.target.diagonals.iter().enumerate() {
                let q = HEX_FACES[f];
                let v = |l: u32| r.query.map().vertex_of(r.query.labelling().darts[l as usize - 1]);
                for &l in d {
                    let mut e =
                        [v(l), r.query.map().vertex_of(r.query.map().next(r.query.labelling().darts[l as usize - 1]))];
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
