//! The 2025 query engine: the §5.1.2 constraint table cell by cell, the Fig. 3
//! situations, whole-map queries, prefix tree = one word at a time, parallel =
//! sequential, and agreement with the 2022 signatures.

use crate::common;

use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::{BitSet, CMap3, Dart, Orbit};
use qmesh::generate::{hex_grid, tet_grid};
use qmesh::query::{
    Annotator, Condition, MatchOptions, Query, QueryError, QuerySet, Strategy, find_matches, select, select_by_volumes,
};
use qmesh::signature::{Flags, Surface, volume_signature};

fn grid(x: usize, y: usize, z: usize) -> CMap3 {
    build_volume_map(&hex_grid(x, y, z), &BuildOptions::default()).unwrap().0
}

fn query(map: CMap3, c: Condition) -> Query {
    Query::new("q", map, |_| c).unwrap()
}

/// Matches of `q` (one per set of darts) in `m` from every dart, one word at a time.
fn count(m: &CMap3, q: &Query, consumed: Option<&BitSet>) -> usize {
    let mut a = Annotator::new(q.nb_darts());
    m.darts().filter(|&s| a.annotate(m, &q.word, s, consumed)).count()
}

/// The 2×1×1 grid with hexahedron 0's x = 0 face 3-sewn to hexahedron 1's x = 2 face:
/// a ring of two cells, so a query pair lands on darts that are sewn to each other.
fn ring() -> CMap3 {
    let mut m = grid(2, 1, 1);
    let free_face_at = |m: &CMap3, x: f64| {
        m.darts()
            .filter(|&d| m.is_free(d, 3))
            .find(|&d| m.orbit(d, Orbit::HalfFace).iter().all(|&e| (m.point(e)[0] - x).abs() < 1e-9))
            .unwrap()
    };
    let d1 = free_face_at(&m, 0.0);
    let (a, b) = (m.point(d1), m.point(m.next(d1)));
    // β3(d1) runs from b + 2x to a + 2x.
    let d2 = m
        .orbit(free_face_at(&m, 2.0), Orbit::HalfFace)
        .into_iter()
        .find(|&e| m.point(e) == [b[0] + 2.0, b[1], b[2]] && m.point(m.next(e)) == [a[0] + 2.0, a[1], a[2]])
        .unwrap();
    m.sew3(d1, d2).unwrap();
    assert!(m.is_valid().is_empty());
    m
}

/// Whether `q` matches `m` from dart 1 (the builder lays out the first cell of every
/// grid alike, so query dart k lands on input dart k).
fn from_first_dart(m: &CMap3, q: &Query, consumed: Option<&BitSet>) -> bool {
    let mut a = Annotator::new(q.nb_darts());
    a.annotate(m, &q.word, Dart::from_raw(1).unwrap(), consumed)
}

/// One hexahedron with condition `c` on its x = 1 face and `*` elsewhere.
fn hex_with_condition_on_x1(c: Condition) -> Query {
    let hex = grid(1, 1, 1);
    let map = hex.clone();
    Query::new("hex", hex, |d| {
        if map.orbit(d, Orbit::HalfFace).iter().all(|&e| map.point(e)[0] == 1.0) { c } else { Condition::Any }
    })
    .unwrap()
}

/// One hexahedron whose face at coordinate `axis` = 1 is 3-sewn to its face at 0.
fn periodic_cube(axis: usize) -> CMap3 {
    let mut m = grid(1, 1, 1);
    let shift = |p: [f64; 3]| {
        let mut q = p;
        q[axis] -= 1.0;
        q
    };
    let f1 = m.darts().find(|&d| m.orbit(d, Orbit::HalfFace).iter().all(|&e| m.point(e)[axis] == 1.0)).unwrap();
    let (a, b) = (m.point(f1), m.point(m.next(f1)));
    let f0 = m.darts().find(|&e| m.point(e) == shift(b) && m.point(m.next(e)) == shift(a)).unwrap();
    m.sew3(f1, f0).unwrap();
    assert!(m.is_valid().is_empty());
    m
}

#[test]
fn constraint_table_cell_by_cell() {
    use Condition::*;
    let lone = grid(1, 1, 1); // the x = 1 face is 3-free: row "d_i = ε"
    let pair = grid(2, 1, 1); // sewn to a dart outside the match: row "not annotated"
    let periodic = periodic_cube(0); // sewn to the x = 0 face of the match: row "labelled"
    let mut consumed = BitSet::with_len(pair.dart_capacity());
    for d in pair.darts().skip(24) {
        consumed.insert(d.idx()); // row ∅: the second hexahedron belongs to a selected match
    }
    // Columns *, ε, ε̄, ↔ of the §5.1.2 table.
    let rows: [(&str, &CMap3, Option<&BitSet>, [bool; 4]); 4] = [
        ("ε", &lone, None, [true, true, false, true]),
        ("not annotated", &pair, None, [true, false, true, true]),
        ("labelled", &periodic, None, [true, false, true, false]),
        ("∅", &pair, Some(&consumed), [true, false, true, true]),
    ];
    for (row, m, c, cells) in rows {
        for (cond, want) in [Any, Boundary, Interior, NoConnection].into_iter().zip(cells) {
            let q = hex_with_condition_on_x1(cond);
            assert_eq!(from_first_dart(m, &q, c), want, "row {row}, column {}", cond.symbol());
        }
    }
    // Column "label": ε → ×, not annotated → (a), labelled → (b) (the pair's shared
    // face: one new dart, then the others closing on labels), ∅ → ×.
    let q = query(pair.clone(), Any);
    assert!(!from_first_dart(&lone, &q, None));
    assert!(from_first_dart(&pair, &q, None));
    assert!(!from_first_dart(&pair, &q, Some(&consumed)));
    assert_eq!(count(&pair, &q, None), 8); // the 8 automorphisms of a 2×1×1 box
    assert!(!from_first_dart(&periodic, &q, None));
}

#[test]
fn no_connection_blocks_faces_glued_that_were_apart_in_the_query() {
    // Fig. 3 (b) in 3D: the pair matches the ring with *, not with ↔.
    let r = ring();
    let pair = grid(2, 1, 1);
    assert!(count(&r, &query(pair.clone(), Condition::Any), None) > 0);
    assert!(count(&r, &query(pair.clone(), Condition::Interior), None) == 0); // y, z sides are free
    assert_eq!(count(&r, &query(pair.clone(), Condition::NoConnection), None), 0);
    assert!(count(&grid(4, 1, 1), &query(pair, Condition::NoConnection), None) > 0);
}

/// An automorphism that moves a `↔` dart onto a `*` one need not give a match: here
/// the query's `↔` face may lie on the x or z faces of a cube sewn to itself in y, not
/// on its y faces (sewn to darts of the match). One set of darts, 16 of its 24 images.
#[test]
fn automorphic_images_are_counted_only_where_they_fulfil_the_conditions() {
    let q = hex_with_condition_on_x1(Condition::NoConnection);
    // The bare cube has 24 automorphisms; 4 of them (about the x axis) keep `↔` on x = 1.
    assert_eq!((q.automorphisms.topological_count(), q.automorphisms.count()), (24, 4));
    let r = find_matches(&periodic_cube(1), &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
    assert_eq!((r.per_query[0], r.with_automorphisms[0]), (1, 16));
    // Oriented by geometry on a cube sewn to itself in x, the image that fits best
    // (the identity, `↔` on the sewn x = 1 face) is not a match: the one kept is.
    let mut oriented = q;
    oriented.orient_by_geometry = true;
    let m = periodic_cube(0);
    let r = find_matches(&m, &QuerySet::new(vec![oriented.clone()]), &MatchOptions::default());
    assert_eq!(r.matches.len(), 1);
    let mut a = Annotator::new(24);
    assert!(a.annotate(&m, &oriented.word, r.matches[0].start, None), "the kept image is not a match");
}

#[test]
fn boundary_condition_blocks_matches_away_from_the_boundary() {
    // Fig. 3 (a): a hexahedron whose faces must all be free matches only a lone one.
    let q = query(grid(1, 1, 1), Condition::Boundary);
    assert_eq!(count(&grid(3, 3, 3), &q, None), 0);
    assert_eq!(count(&grid(1, 1, 1), &q, None), 24);
    // Two hexahedra with free sides match only the ends of a 1×1×n bar… none: the
    // bar's interior faces are sewn on both ends. A 2×1×1 bar matches whole.
    let q = query(grid(2, 1, 1), Condition::Boundary);
    assert_eq!(count(&grid(3, 1, 1), &q, None), 0);
    assert_eq!(count(&grid(2, 1, 1), &q, None), 8);
}

/// The throughput counter: a whole match checks every symbol of the word (three per
/// query dart), and a failure stops at the symbol that fails.
#[test]
fn annotation_counts_the_symbols_it_checks() {
    let pair = grid(2, 1, 1);
    let mut a = Annotator::new(24);
    let any = query(grid(1, 1, 1), Condition::Any);
    let lone = |m: &CMap3| m.darts().find(|&d| m.is_free(d, 3)).unwrap();
    assert!(a.annotate(&pair, &any.word, lone(&pair), None));
    assert_eq!(a.steps(), 3 * 24);
    // From a dart of the shared face, an all-boundary hexahedron fails at the first
    // dart's β3 (its β1 and β2 are new labels 2 and 3): three symbols.
    let boundary = query(grid(1, 1, 1), Condition::Boundary);
    let shared = pair.darts().find(|&d| !pair.is_free(d, 3)).unwrap();
    assert!(!a.annotate(&pair, &boundary.word, shared, None));
    assert_eq!(a.steps(), 3 * 24 + 3);
    // A pair labelled from a dart of its shared face fails on a lone hexahedron at
    // that dart's β3, a new label 4 where the input is 3-free: three symbols again.
    let two = Query::from_start("pair", pair.clone(), shared, |_| Condition::Any).unwrap();
    assert!(!a.annotate(&grid(1, 1, 1), &two.word, Dart::from_raw(1).unwrap(), None));
    assert_eq!(a.steps(), 3 * 24 + 6);
    // The prefix tree's walk counts alike: one lone hexahedron matched from each of
    // its 24 darts, automorphic copies included.
    let set = QuerySet::new(vec![any]);
    let all = MatchOptions { all_automorphisms: true, ..Default::default() };
    let r = find_matches(&grid(1, 1, 1), &set, &all);
    assert_eq!(r.with_automorphisms[0], 24);
    assert_eq!(r.steps, 24 * 3 * 24);
    // Over many chunks of start darts taken by one thread, each chunk adds its own.
    let big = grid(10, 10, 10);
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    assert_eq!(one_thread.install(|| find_matches(&big, &set, &all)).steps, 24_000 * 3 * 24);
    // Keeping one match per set of darts, a walk stops as soon as a new label lands
    // where an automorphic image would start from a smaller dart: fewer symbols.
    let one = find_matches(&grid(1, 1, 1), &set, &MatchOptions::default());
    assert_eq!(one.per_query[0], 1);
    assert!(one.steps < r.steps, "{} symbols with pruning, {} without", one.steps, r.steps);
}

#[test]
fn the_whole_input_matches_and_a_larger_query_never_does() {
    let input = grid(3, 2, 1);
    let q = query(input.clone(), Condition::Boundary);
    let r = find_matches(&input, &QuerySet::new(vec![q]), &MatchOptions::default());
    assert_eq!(r.per_query[0], 1);
    assert_eq!(r.with_automorphisms[0], 4); // a 3×2×1 box: rotations by π about its axes
    let bigger = query(grid(4, 2, 1), Condition::Any);
    assert_eq!(count(&input, &bigger, None), 0);
}

#[test]
fn queries_must_be_connected_and_closed() {
    let mut two = grid(1, 1, 1);
    let v: Vec<u32> =
        (0..8).map(|i| two.add_vertex([5.0 + (i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64])).collect();
    two.make_hexahedron([v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]]);
    let e = Query::new("two", two, |_| Condition::Any).unwrap_err();
    assert!(matches!(e, QueryError::NotConnected { reached: 24, total: 48, .. }), "{e}");
    assert!(e.to_string().contains("not connected"), "{e}");
    let mut open = CMap3::new();
    open.set_dimension(2);
    let v: Vec<u32> = (0..3).map(|i| open.add_vertex([i as f64, (i % 2) as f64, 0.0])).collect();
    open.make_polygon(&v);
    let e = Query::new("open", open, |_| Condition::Any).unwrap_err();
    assert!(matches!(e, QueryError::Free { beta: 2, .. }), "{e}");
    assert!(e.to_string().contains("2-free") && e.to_string().contains("face with vertices"), "{e}");
    assert!(e.to_string().contains("(the face with vertices 0-1-2 (first at 0.000, 0.000, 0.000))"), "{e}");
    // A long face is listed up to its 64th vertex, then "…".
    for (n, head, tail) in [(64, "vertices 0-1-2-3-", "-62-63 (first"), (70, "vertices 0-1-2-3-", "-62-63-… (first")]
    {
        let mut open = CMap3::new();
        open.set_dimension(2);
        let v: Vec<u32> = (0..n).map(|i| open.add_vertex([(i as f64).cos(), (i as f64).sin(), 0.0])).collect();
        open.make_polygon(&v);
        let e = Query::new("open", open, |_| Condition::Any).unwrap_err().to_string();
        assert!(e.contains(head) && e.contains(tail), "{n}-gon: {e}");
    }
}

#[test]
fn block_of_eight_in_a_grid_and_its_corner_variant() {
    let g = grid(6, 5, 4);
    let block = grid(2, 2, 2);
    let r = find_matches(&g, &QuerySet::new(vec![query(block.clone(), Condition::Any)]), &MatchOptions::default());
    assert_eq!(r.per_query[0], 5 * 4 * 3);
    assert_eq!(r.with_automorphisms[0], 5 * 4 * 3 * 24);
    // ε on the three sides through the corner at the origin: only the grid's 8 corners.
    let mut q = query(block, Condition::Any);
    let map = q.map().clone();
    q.set_conditions(|d| {
        let f = map.orbit(d, Orbit::HalfFace);
        let on = |k: usize| f.iter().all(|&e| map.point(e)[k] == 0.0);
        if on(0) || on(1) || on(2) { Condition::Boundary } else { Condition::Any }
    });
    assert_eq!(q.automorphisms.count(), 3);
    let r = find_matches(&g, &QuerySet::new(vec![q]), &MatchOptions::default());
    assert_eq!((r.per_query[0], r.with_automorphisms[0]), (8, 24));
}

#[test]
fn prefix_tree_gives_the_matches_of_each_word_alone() {
    let g = build_volume_map(&tet_grid(3, 2, 2), &BuildOptions::default()).unwrap().0;
    let hexes = build_volume_map(&tet_grid(1, 1, 1), &BuildOptions::default()).unwrap().0;
    // Queries cut from the tet grid: one tet, two tets of a cube, a whole cube, with
    // different conditions (shared prefixes, different ends).
    let mut queries = Vec::new();
    for c in Condition::ALL {
        queries.push(Query::new("cube", hexes.clone(), |_| c).unwrap());
    }
    let one =
        build_volume_map(&qmesh::generate::tet_grid(1, 1, 1).cell_subset(&[0]), &BuildOptions::default()).unwrap().0;
    let two =
        build_volume_map(&qmesh::generate::tet_grid(1, 1, 1).cell_subset(&[0, 1]), &BuildOptions::default()).unwrap().0;
    for c in [Condition::Any, Condition::NoConnection] {
        queries.push(Query::new("one", one.clone(), |_| c).unwrap());
        queries.push(Query::new("two", two.clone(), |_| c).unwrap());
    }
    let set = QuerySet::new(queries);
    let opts = MatchOptions { all_automorphisms: true, ..Default::default() };
    let together = find_matches(&g, &set, &opts);
    for (i, q) in set.queries.iter().enumerate() {
        let alone: Vec<Dart> = {
            let mut a = Annotator::new(q.nb_darts());
            g.darts().filter(|&s| a.annotate(&g, &q.word, s, None)).collect()
        };
        let from_tree: Vec<Dart> = together.matches.iter().filter(|m| m.query == i as u32).map(|m| m.start).collect();
        assert_eq!(from_tree, alone, "query {i} ({})", q.name);
    }
    assert!(together.matches.len() > 100);
}

#[test]
fn parallel_matching_equals_sequential() {
    let g = grid(9, 7, 5);
    let set = QuerySet::new(vec![query(grid(2, 1, 1), Condition::Any), query(grid(2, 2, 1), Condition::Interior)]);
    let par = find_matches(&g, &set, &MatchOptions::default());
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let seq = pool.install(|| find_matches(&g, &set, &MatchOptions::default()));
    assert_eq!(par.matches, seq.matches);
    assert_eq!(par.per_query, seq.per_query);
    let chosen = select(&g, &set, &par.matches, Strategy::Greedy, None);
    let again = pool.install(|| select(&g, &set, &seq.matches, Strategy::Greedy, None));
    assert_eq!(chosen.iter().map(|s| s.m).collect::<Vec<_>>(), again.iter().map(|s| s.m).collect::<Vec<_>>());
}

#[test]
fn selection_never_overlaps_and_respects_max_and_seed() {
    let g = grid(6, 6, 1);
    let set = QuerySet::new(vec![query(grid(2, 1, 1), Condition::Any)]);
    let found = find_matches(&g, &set, &MatchOptions::default());
    for strategy in [Strategy::Greedy, Strategy::Random(7), Strategy::Random(8)] {
        let s = select(&g, &set, &found.matches, strategy, None);
        let mut used = std::collections::HashSet::new();
        for m in &s {
            assert_eq!(m.darts.len(), 48);
            assert!(m.darts.iter().all(|d| used.insert(*d)), "{strategy:?} overlaps");
        }
        assert!(s.len() >= 12 && s.len() <= 18, "{strategy:?}: {}", s.len());
    }
    let a = select(&g, &set, &found.matches, Strategy::Random(7), Some(5));
    let b = select(&g, &set, &found.matches, Strategy::Random(7), Some(5));
    assert_eq!(a.len(), 5);
    assert_eq!(a.iter().map(|s| s.m.start).collect::<Vec<_>>(), b.iter().map(|s| s.m.start).collect::<Vec<_>>());
}

#[test]
fn match_volumes_are_those_of_the_darts_and_select_by_volumes_equals_select() {
    // Two queries (a pair and an L of three cells) over a grid: matches overlap a lot.
    let g = grid(5, 4, 2);
    let square = hex_grid(2, 2, 1);
    let mut l = qmesh::build::IndexedMesh::new();
    l.points.clone_from(&square.points);
    for c in 0..3 {
        let (kind, nodes) = square.cell(c);
        l.push_cell(kind, nodes, None);
    }
    let l = build_volume_map(&l, &BuildOptions::default()).unwrap().0;
    let set = QuerySet::new(vec![query(grid(2, 1, 1), Condition::Any), query(l, Condition::Any)]);
    let mut volume_of = vec![u32::MAX; g.dart_capacity()];
    let firsts: Vec<Dart> = g.cells(Orbit::Volume).collect();
    for (v, &d) in firsts.iter().enumerate() {
        g.orbit(d, Orbit::Volume).iter().for_each(|x| volume_of[x.idx()] = v as u32);
    }
    let metric = qmesh::query::Metric::Volume;
    let opts = MatchOptions { metric: Some(&metric), volume_of: Some(&volume_of), ..Default::default() };
    let found = find_matches(&g, &set, &opts);
    assert_eq!(found.volumes.len(), found.matches.len());
    assert!(!found.volumes.is_empty());
    assert!(found.per_query.iter().all(|&n| n > 10), "{:?}", found.per_query);
    let mut a = set.annotator();
    for (i, m) in found.matches.iter().enumerate() {
        let mut vs: Vec<u32> = set.darts_of(&g, m, &mut a).iter().map(|d| volume_of[d.idx()]).collect();
        vs.sort_unstable();
        vs.dedup();
        assert_eq!(found.volumes.of(i), vs, "match {i}");
    }
    // Without volumes asked for, none are listed.
    assert!(find_matches(&g, &set, &MatchOptions::default()).volumes.is_empty());
    for strategy in [Strategy::Greedy, Strategy::Best, Strategy::Random(3)] {
        let by_darts: Vec<_> = select(&g, &set, &found.matches, strategy, None).iter().map(|s| s.m).collect();
        let by_volumes: Vec<_> = select_by_volumes(&found.matches, &found.volumes, firsts.len(), strategy)
            .iter()
            .map(|&i| found.matches[i])
            .collect();
        assert_eq!(by_darts, by_volumes, "{strategy:?}");
        assert!(by_darts.len() >= 10, "{strategy:?}: {}", by_darts.len());
    }
}

#[test]
fn best_selection_takes_the_highest_metric_first() {
    // A grid with one column of cells stretched: volume ranks those pairs first.
    let mut mesh = hex_grid(4, 1, 1);
    for p in &mut mesh.points {
        if p[0] > 3.5 {
            p[0] = 7.0;
        }
    }
    let g = build_volume_map(&mesh, &BuildOptions::default()).unwrap().0;
    let set = QuerySet::new(vec![query(grid(2, 1, 1), Condition::Any)]);
    let metric = qmesh::query::Metric::Volume;
    let found = find_matches(&g, &set, &MatchOptions { metric: Some(&metric), ..Default::default() });
    let best = select(&g, &set, &found.matches, Strategy::Best, Some(1));
    assert!((best[0].m.score - 5.0).abs() < 1e-9, "{}", best[0].m.score);
    let quality = qmesh::query::Metric::HexQuality;
    let cube = query(grid(1, 1, 1), Condition::Any);
    let mut a = Annotator::new(24);
    assert!(a.annotate(&g, &cube.word, Dart::from_raw(1).unwrap(), None));
    assert!((quality.evaluate(&g, &cube, a.matched_raw()) - 1.0).abs() < 1e-12);
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn single_volume_queries_agree_with_2022_signatures() {
    let Some(dir) = common::data_dir() else { return };
    for file in ["tet/gmsh_torus_tet.mesh", "hex/rockarm.vtk"] {
        let m = qmesh::io::load_map(&dir.join(file), None, &BuildOptions::default()).unwrap().map;
        // The query: the input's first volume as its own map, all `*`.
        let first = m.darts().next().unwrap();
        let cell = qmesh::build::extract(&m).0.cell_subset(&[0]);
        let q = Query::new("cell", build_volume_map(&cell, &BuildOptions::default()).unwrap().0, |_| Condition::Any)
            .unwrap();
        let sig = volume_signature(&m, Surface::Cell, Flags::None, first).unwrap().0;
        let by_signature = m
            .cells(Orbit::Volume)
            .filter(|&v| volume_signature(&m, Surface::Cell, Flags::None, v).unwrap().0 == sig)
            .count();
        let r = find_matches(&m, &QuerySet::new(vec![q]), &MatchOptions::default());
        assert_eq!(r.per_query[0], by_signature, "{file}");
        assert!(by_signature > 100, "{file}: {by_signature}");
    }
}

#[test]
fn residual_threshold_rejects_distorted_copies_and_orientation_follows_the_query() {
    // Shear one cell of a 3×1×1 row: its pair matches stop being affine copies.
    let mut mesh = hex_grid(3, 1, 1);
    for p in &mut mesh.points {
        if p[0] == 3.0 && p[2] == 1.0 {
            p[1] += 0.8;
        }
    }
    let g = build_volume_map(&mesh, &BuildOptions::default()).unwrap().0;
    let mut q = query(grid(2, 1, 1), Condition::Any);
    let all = find_matches(&g, &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
    assert_eq!(all.per_query[0], 2);
    q.max_residual = Some(1e-6);
    let set = QuerySet::new(vec![q.clone()]);
    let strict = find_matches(&g, &set, &MatchOptions::default());
    assert_eq!(strict.per_query[0], 1);
    // The copy kept is the undistorted pair (x from 0 to 2), found from the same dart
    // as without the threshold: `max_residual` alone does not reorient matches.
    let darts = set.darts_of(&g, &strict.matches[0], &mut set.annotator());
    assert!(darts.iter().all(|&d| g.point(d)[0] <= 2.0), "the sheared pair was kept");
    assert!(all.matches.iter().any(|m| m.start == strict.matches[0].start));
    // A limit of 0 keeps exact copies: their residual is rounding only.
    q.max_residual = Some(0.0);
    let exact = find_matches(&grid(3, 1, 1), &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
    assert_eq!(exact.per_query[0], 2);
    // Geometric orientation: the kept copy's first dart is where the query's is.
    q.max_residual = None;
    q.orient_by_geometry = true;
    let r = find_matches(&grid(4, 1, 1), &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
    let first = q.map().point(q.labelling().darts[0]);
    let gm = grid(4, 1, 1);
    for m in &r.matches {
        let p = gm.point(m.start);
        assert!((p[1] - first[1]).abs() < 1e-12 && (p[2] - first[2]).abs() < 1e-12, "{p:?} vs {first:?}");
    }
}

/// The map of the one hexahedron of `mesh`, its nodes listed from bottom corner
/// `first` (the same cell, darts numbered from elsewhere), its points moved by `f`.
fn hex_listed_from(mesh: &qmesh::build::IndexedMesh, first: usize, f: impl Fn([f64; 3]) -> [f64; 3]) -> CMap3 {
    let nodes: Vec<u32> = mesh.cell(0).1.to_vec();
    let turned: Vec<u32> = (0..8).map(|i| nodes[(i + first) % 4 + if i < 4 { 0 } else { 4 }]).collect();
    let mut input = qmesh::build::IndexedMesh::new();
    input.points = mesh.points.iter().map(|&p| f(p)).collect();
    input.push_cell(qmesh::build::CellKind::Hex, &turned, None);
    build_volume_map(&input, &BuildOptions::default()).unwrap().0
}

/// Oriented by geometry, a match is kept as the automorphic image that fits the query
/// best: on a cube with one raised corner, only one image is an affine copy. The
/// input is the same cube (moved, stretched) with its nodes listed from another
/// corner, so its smallest dart, where the match is found, is elsewhere.
#[test]
fn geometric_orientation_keeps_the_image_that_fits_best() {
    let mut mesh = hex_grid(1, 1, 1);
    mesh.points.iter_mut().filter(|p| **p == [1.0, 1.0, 1.0]).for_each(|p| p[2] = 1.5);
    let q_map = build_volume_map(&mesh, &BuildOptions::default()).unwrap().0;
    let mut q = query(q_map.clone(), Condition::Any);
    q.orient_by_geometry = true;
    // Stretched, then turned by 90° about z: the copy that fits exactly is then not
    // the one closest to the query's orientation.
    let stretch = |p: [f64; 3]| [2.0 * p[0] + 5.0, p[1] - 1.0, 3.0 * p[2]];
    let turn = |p: [f64; 3]| [-p[1], p[0], p[2]];
    let affines: [&dyn Fn([f64; 3]) -> [f64; 3]; 2] = [&stretch, &turn];
    // With `ε` on the x = 1 face, the quarter turns about z do not keep the query's
    // conditions, yet on a lone cube (every face free) their images are matches too,
    // and one of them is the exact copy.
    let on_x1 = |d: Dart| q_map.orbit(d, Orbit::HalfFace).iter().all(|&e| q_map.point(e)[0] == 1.0);
    let mut q_eps =
        Query::new("raised", q_map.clone(), |d| if on_x1(d) { Condition::Boundary } else { Condition::Any }).unwrap();
    q_eps.orient_by_geometry = true;
    assert_eq!((q_eps.automorphisms.topological_count(), q_eps.automorphisms.count()), (24, 4));
    for (first, affine) in (0..4).flat_map(|f| affines.iter().map(move |a| (f, a))) {
        let m = hex_listed_from(&mesh, first, affine);
        for q in [&q, &q_eps] {
            let r = find_matches(&m, &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
            assert_eq!(r.matches.len(), 1);
            let (s, d1) = (r.matches[0].start, q.labelling().darts[0]);
            assert_eq!(m.point(s), affine(q_map.point(d1)), "{}: listed from corner {first}", q.name);
            assert_eq!(m.point(m.next(s)), affine(q_map.point(q_map.next(d1))), "{}: corner {first}", q.name);
        }
    }
    // A plain cube: all 24 images fit exactly, and the tie goes to the orientation
    // closest to the query's (here the identity).
    let plain = grid(1, 1, 1);
    let mut q = query(plain.clone(), Condition::Any);
    q.orient_by_geometry = true;
    // `max_residual` alone keeps the match where it was found (the smallest dart).
    let mut unoriented = q.clone();
    unoriented.orient_by_geometry = false;
    let mut residual_only = unoriented.clone();
    residual_only.max_residual = Some(1.0);
    let mut moved = 0;
    for first in 0..4 {
        let m = hex_listed_from(&hex_grid(1, 1, 1), first, |p| p);
        let start_with = |q: &Query| find_matches(&m, &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
        let (s, d1) = (start_with(&q).matches[0].start, q.labelling().darts[0]);
        assert_eq!((m.point(s), m.point(m.next(s))), (plain.point(d1), plain.point(plain.next(d1))), "corner {first}");
        let found_at = start_with(&unoriented).matches[0].start;
        assert_eq!(start_with(&residual_only).matches[0].start, found_at, "corner {first}");
        moved += usize::from(s != found_at);
    }
    assert!(moved > 0, "orienting by geometry never moved a match: the check above is vacuous");
    // Turned by 30° about z and moved far away: every image fits up to rounding (not
    // exactly 0), and the one kept is still the closest to the query's orientation.
    let (c, s30) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let far_turn = |p: [f64; 3]| [c * p[0] - s30 * p[1] + 1000.1, s30 * p[0] + c * p[1] - 3.7, p[2] + 0.3];
    for first in 0..4 {
        let m = hex_listed_from(&hex_grid(1, 1, 1), first, far_turn);
        let r = find_matches(&m, &QuerySet::new(vec![q.clone()]), &MatchOptions::default());
        let (s, d1) = (r.matches[0].start, q.labelling().darts[0]);
        for (got, want) in [(m.point(s), plain.point(d1)), (m.point(m.next(s)), plain.point(plain.next(d1)))] {
            let want = far_turn(want);
            assert!((0..3).all(|i| (got[i] - want[i]).abs() < 1e-9), "corner {first}: {got:?} vs {want:?}");
        }
    }
}

#[test]
fn lazy_random_selection_is_seeded_separated_and_stops_at_max() {
    use qmesh::query::{Separation, select_random_lazily};
    let g = build_volume_map(&qmesh::generate::hex_grid(8, 8, 1), &BuildOptions::default()).unwrap().0;
    let pair = build_volume_map(&qmesh::generate::hex_grid(2, 1, 1), &BuildOptions::default()).unwrap().0;
    let set = QuerySet::new(vec![Query::new("pair", pair, |_| Condition::Any).unwrap()]);
    let opts = MatchOptions::default();
    let starts = |s: &[qmesh::query::Selected]| s.iter().map(|x| x.m.start).collect::<Vec<_>>();
    let (a, seen) = select_random_lazily(&g, &set, &opts, 5, 6, Separation::Darts);
    let (b, _) = select_random_lazily(&g, &set, &opts, 5, 6, Separation::Darts);
    let (c, _) = select_random_lazily(&g, &set, &opts, 6, 6, Separation::Darts);
    assert_eq!((a.len(), starts(&a)), (6, starts(&b)), "same seed, same choice");
    assert_ne!(starts(&a), starts(&c), "another seed, another choice");
    assert!(seen.starts_tested < g.nb_darts() && seen.matches >= 6, "{seen:?}");
    // No two share a dart; with vertex separation no two share a vertex either, and
    // asking for more than fit takes what fits (every dart is tried).
    let (all, seen) = select_random_lazily(&g, &set, &opts, 5, 1000, Separation::Vertices);
    assert!(seen.starts_tested > g.nb_darts() / 2, "{seen:?}");
    assert!(seen.starts_tested < g.nb_darts(), "darts already taken are not tried: {seen:?}");
    let mut vertices = std::collections::HashSet::new();
    for s in &all {
        let mine: std::collections::HashSet<u32> = s.darts.iter().map(|&d| g.vertex_of(d)).collect();
        assert!(mine.iter().all(|v| !vertices.contains(v)), "two selected pairs touch");
        vertices.extend(mine);
    }
    // 8×8 cells: pairs that do not touch fit at most ⌈8/3⌉ per row of every other row.
    assert!(!all.is_empty() && all.len() <= 12, "{}", all.len());
    let (dense, seen) = select_random_lazily(&g, &set, &opts, 5, 1000, Separation::Darts);
    assert!(dense.len() > all.len() && dense.len() <= 32);
    // Taken darts count as ∅: every match found is free to take.
    assert_eq!(seen.matches, dense.len(), "{seen:?}");
}
