//! Property tests of the 2025 engine on random maps (hex grids with random cells
//! removed) and random queries cut from grids: prefix tree = one word at a time,
//! parallel = sequential, selections never overlap, and extend / delete / replace /
//! apply keep the map valid with the expected counts.

use proptest::prelude::*;
use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::{CMap3, Dart, Orbit};
use qmesh::generate::hex_grid;
use qmesh::modify::{Action, Operation, Plan, Rule, run_rules};
use qmesh::query::{Annotator, Condition, MatchOptions, Query, QuerySet, Strategy as Selection, find_matches, select};

fn grid(x: usize, y: usize, z: usize) -> CMap3 {
    build_volume_map(&hex_grid(x, y, z), &BuildOptions::default()).unwrap().0
}

/// A grid with the cells of `holes` (indices modulo the cell count) removed.
fn holey(dims: (usize, usize, usize), holes: &[usize]) -> CMap3 {
    let mut m = grid(dims.0, dims.1, dims.2);
    let vols: Vec<Dart> = m.cells(Orbit::Volume).collect();
    for &h in holes {
        let d = vols[h % vols.len()];
        if m.is_live(d) && m.count_cells().volumes > 1 {
            m.remove_volume(d).unwrap();
        }
    }
    assert!(m.is_valid().is_empty());
    m
}

fn condition(i: u8) -> Condition {
    Condition::ALL[i as usize % 4]
}

fn arb_map() -> impl Strategy<Value = CMap3> {
    ((1usize..5, 1usize..4, 1usize..3), prop::collection::vec(0usize..100, 0..6)).prop_map(|(d, h)| holey(d, &h))
}

fn arb_query() -> impl Strategy<Value = Query> {
    ((1usize..3, 1usize..3, 1usize..3), any::<u8>(), any::<u8>()).prop_map(|((x, y, z), c, top)| {
        let q = grid(x, y, z);
        let map = q.clone();
        let zmax = z as f64;
        // One condition on the top side, another elsewhere.
        Query::new("q", q, |d| {
            let on_top = map.orbit(d, Orbit::HalfFace).iter().all(|&e| map.point(e)[2] == zmax);
            if on_top { condition(top) } else { condition(c) }
        })
        .unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn prefix_tree_and_threads_agree_with_single_words(m in arb_map(), qs in prop::collection::vec(arb_query(), 1..4)) {
        let set = QuerySet::new(qs);
        for all in [true, false] {
            let opts = MatchOptions { all_automorphisms: all, ..Default::default() };
            let par = find_matches(&m, &set, &opts);
            let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
            let seq = pool.install(|| find_matches(&m, &set, &opts));
            prop_assert_eq!(&par.matches, &seq.matches);
            prop_assert_eq!(&par.with_automorphisms, &seq.with_automorphisms);
            for (i, q) in set.queries.iter().enumerate() {
                let mut a = Annotator::new(q.nb_darts());
                let alone: Vec<Dart> = m.darts().filter(|&s| a.annotate(&m, &q.word, s, None)).collect();
                if all {
                    let tree: Vec<Dart> = par.matches.iter().filter(|x| x.query == i as u32).map(|x| x.start).collect();
                    prop_assert_eq!(tree, alone);
                } else {
                    // One per class, and the classes account for every single-word match.
                    prop_assert_eq!(par.with_automorphisms[i], alone.len());
                    prop_assert!(par.per_query[i] <= alone.len());
                }
            }
        }
    }

    #[test]
    fn selections_never_overlap(m in arb_map(), q in arb_query(), seed in any::<u64>(), max in 1usize..5) {
        let set = QuerySet::new(vec![q]);
        let found = find_matches(&m, &set, &MatchOptions::default());
        for s in [Selection::Greedy, Selection::Random(seed)] {
            let chosen = select(&m, &set, &found.matches, s, Some(max));
            prop_assert!(chosen.len() <= max);
            let mut used = std::collections::HashSet::new();
            for c in &chosen {
                prop_assert!(c.darts.iter().all(|d| used.insert(*d)));
            }
        }
    }

    #[test]
    fn modify_operations_keep_the_map_valid(m in arb_map(), op in 0u8..4, seed in any::<u64>()) {
        let mut m = m;
        let before = m.count_cells();
        let (q, t) = match op {
            0 => (grid(1, 1, 1), grid(2, 1, 1)),     // extend by one cell
            1 => (grid(2, 1, 1), grid(1, 1, 1)),     // delete one of two
            _ => (grid(1, 1, 1), grid(1, 1, 1)),     // replace (identity) or apply
        };
        let mut query = Query::new("q", q, |_| Condition::Any).unwrap();
        let action = match op {
            0 => Action::Plan(Plan::new(Operation::Extend, &mut query, &t).unwrap()),
            1 => Action::Plan(Plan::new(Operation::Delete, &mut query, &t).unwrap()),
            2 => Action::Plan(Plan::new(Operation::Replace, &mut query, &t).unwrap()),
            _ => Action::Apply(std::sync::Arc::new(|map: &mut CMap3, _: &Query, darts: &[Dart]| {
                // Move the match's first vertex a little (geometry only).
                let v = map.vertex_of(darts[0]);
                let p = map.position(v);
                map.set_position(v, [p[0] + 0.01, p[1], p[2]]);
                Ok(())
            })),
        };
        let rule = Rule { action, strategy: Selection::Random(seed), ..Rule::find(query) };
        let r = run_rules(&mut m, &[rule]);
        prop_assert!(r[0].valid, "{:?}", r[0].problem);
        prop_assert!(m.is_valid().is_empty());
        let after = m.count_cells();
        let expect = match op {
            0 => before.volumes + r[0].selected,
            1 => before.volumes - r[0].selected,
            _ => before.volumes,
        };
        prop_assert_eq!(after.volumes, expect);
        prop_assert_eq!(r[0].modified, r[0].selected);
        if op >= 2 {
            prop_assert_eq!(after.darts, before.darts);
            prop_assert_eq!(after.euler_characteristic(3), before.euler_characteristic(3));
        }
    }
}
