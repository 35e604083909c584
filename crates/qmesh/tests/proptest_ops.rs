//! Property tests: random sequences of constructions, sews, unsews, edge splits, face
//! and volume removals keep the map valid after every step, with cell counts changing
//! exactly as each operation dictates.

mod common;

use proptest::prelude::*;
use qmesh::cmap::{CMap3, Dart, Orbit};

#[derive(Clone, Debug)]
enum Op {
    AddHex(u8),
    AddTet(u8),
    Sew3(u16, u16),
    Unsew3(u16),
    Split(u16, u8),
    RemoveFace(u16),
    RemoveVolume(u16),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        2 => any::<u8>().prop_map(Op::AddHex),
        2 => any::<u8>().prop_map(Op::AddTet),
        4 => (any::<u16>(), any::<u16>()).prop_map(|(a, b)| Op::Sew3(a, b)),
        1 => any::<u16>().prop_map(Op::Unsew3),
        3 => (any::<u16>(), 1u8..5).prop_map(|(a, k)| Op::Split(a, k)),
        1 => any::<u16>().prop_map(Op::RemoveFace),
        1 => any::<u16>().prop_map(Op::RemoveVolume),
    ]
}

fn pick(m: &CMap3, i: u16, keep: impl Fn(Dart) -> bool) -> Option<Dart> {
    let v: Vec<Dart> = m.darts().filter(|&d| keep(d)).collect();
    (!v.is_empty()).then(|| v[i as usize % v.len()])
}

fn apply(m: &mut CMap3, op: &Op) {
    let before = m.count_cells();
    match *op {
        Op::AddHex(o) => {
            let v = common::unit_cube_vertices(m, o as f64 * 2.0);
            m.make_hexahedron(v);
            let a = m.count_cells();
            assert_eq!(
                (a.darts, a.volumes, a.faces, a.vertices),
                (before.darts + 24, before.volumes + 1, before.faces + 6, before.vertices + 8)
            );
        }
        Op::AddTet(o) => {
            let x = o as f64 * 2.0;
            let v = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]
                .map(|p| m.add_vertex([p[0] + x, p[1], p[2] + 5.0]));
            m.make_tetrahedron(v);
            assert_eq!(m.count_cells().volumes, before.volumes + 1);
        }
        Op::Sew3(a, b) => {
            let (Some(d1), Some(d2)) = (pick(m, a, |d| m.is_free(d, 3)), pick(m, b, |d| m.is_free(d, 3))) else {
                return;
            };
            if m.is_sewable3(d1, d2) {
                m.sew3(d1, d2).unwrap();
                let a = m.count_cells();
                assert_eq!((a.darts, a.faces, a.volumes), (before.darts, before.faces - 1, before.volumes));
            } else {
                assert!(m.sew3(d1, d2).is_err());
            }
        }
        Op::Unsew3(a) => {
            let Some(d) = pick(m, a, |d| !m.is_free(d, 3)) else { return };
            m.unsew3(d).unwrap();
            let a = m.count_cells();
            assert_eq!((a.darts, a.faces, a.volumes), (before.darts, before.faces + 1, before.volumes));
        }
        Op::Split(a, k) => {
            let Some(d) = pick(m, a, |_| true) else { return };
            let around = m.orbit(d, Orbit::Edge).len();
            m.split_edge(d, k as usize).unwrap();
            let a = m.count_cells();
            let k = k as usize;
            assert_eq!(a.darts, before.darts + (k - 1) * around);
            assert_eq!(
                (a.vertices, a.edges, a.faces, a.volumes),
                (before.vertices + k - 1, before.edges + k - 1, before.faces, before.volumes)
            );
        }
        Op::RemoveFace(a) => {
            let Some(d) = pick(m, a, |d| !m.is_free(d, 3)) else { return };
            let len = m.orbit(d, Orbit::HalfFace).len();
            let other = m.beta(d, 3).unwrap();
            let same_volume = m.orbit(d, Orbit::Volume).contains(&other);
            if m.remove_face(d).is_ok() {
                let a = m.count_cells();
                assert_eq!(a.darts, before.darts - 2 * len);
                if !same_volume {
                    // Two volumes merge into one. (A face a volume shares with itself
                    // can instead cut that volume apart: no fixed count there.)
                    assert_eq!(a.volumes, before.volumes - 1);
                }
            } else {
                assert_eq!(m.count_cells(), before, "a refused removal must leave the map unchanged");
            }
        }
        Op::RemoveVolume(a) => {
            let Some(d) = pick(m, a, |_| true) else { return };
            let n = m.orbit(d, Orbit::Volume).len();
            assert_eq!(m.remove_volume(d).unwrap(), n);
            let a = m.count_cells();
            assert_eq!((a.darts, a.volumes), (before.darts - n, before.volumes - 1));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn random_operation_sequences_keep_the_map_valid(ops in prop::collection::vec(op(), 1..40)) {
        let mut m = CMap3::new();
        for op in &ops {
            apply(&mut m, op);
            let v = m.is_valid();
            prop_assert!(v.is_empty(), "after {:?}: {}", op, v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join("; "));
            // The parallel census agrees with the census by definition.
            let (fast, reference) = (m.census(), m.census_reference());
            prop_assert_eq!(fast.counts, reference.counts, "after {:?}", op);
            prop_assert_eq!(fast.volume_reps.len(), reference.volume_reps.len());
        }
        let before = m.count_cells();
        m.compact();
        prop_assert!(m.is_valid().is_empty());
        prop_assert_eq!(m.count_cells(), before);
        prop_assert_eq!(m.dart_capacity(), m.nb_darts() + 1, "compact leaves no orphan dart");
    }
}
