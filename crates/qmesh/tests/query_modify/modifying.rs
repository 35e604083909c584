//! The 2025 modify operations: extend/delete round trips, replace keeping the match's
//! boundary, created vertices placed by mean value coordinates, rule files and their
//! errors.

use crate::common;

use qmesh::build::{BuildOptions, build_volume_map, extract};
use qmesh::cmap::{CMap3, Orbit};
use qmesh::generate::hex_grid;
use qmesh::modify::{Action, Operation, Plan, Rule, load_rules, parse_rules, run_rules};
use qmesh::query::{Condition, MatchOptions, Query, QuerySet, find_matches};

fn grid(x: usize, y: usize, z: usize) -> CMap3 {
    build_volume_map(&hex_grid(x, y, z), &BuildOptions::default()).unwrap().0
}

fn rule(op: Operation, q: CMap3, t: &CMap3) -> Rule {
    let mut q = Query::new("q", q, |_| Condition::Any).unwrap();
    let plan = Plan::new(op, &mut q, t).unwrap();
    let mut r = Rule::find(q);
    r.action = Action::Plan(plan);
    r
}

/// Whether `whole` is isomorphic to `m` (a query of it with ε everywhere matches).
fn isomorphic(m: &CMap3, whole: &CMap3) -> bool {
    let q = Query::new("whole", whole.clone(), |_| Condition::Boundary).unwrap();
    find_matches(m, &QuerySet::new(vec![q]), &MatchOptions::default()).per_query[0] == 1
}

/// The 2×1×1 pair merged into one polyhedron with the pair's 10 boundary quads.
fn merged_pair() -> CMap3 {
    let mesh = hex_grid(2, 1, 1);
    let pair = grid(2, 1, 1);
    let faces: Vec<Vec<u32>> = pair
        .cells(Orbit::Face)
        .filter(|&d| pair.is_free(d, 3))
        .map(|d| pair.orbit(d, Orbit::HalfFace).iter().map(|&e| pair.vertex_of(e)).collect())
        .collect();
    let mut m = CMap3::with_positions(mesh.points.clone(), 0);
    m.make_polyhedron(&faces).unwrap();
    assert!(m.is_valid().is_empty());
    m
}

#[test]
fn extend_then_delete_gives_the_map_back() {
    let mut m = grid(1, 3, 1);
    let one = grid(1, 1, 1);
    let two = grid(2, 1, 1);
    let before = m.count_cells();
    let r = run_rules(&mut m, &[rule(Operation::Extend, one.clone(), &two)]);
    assert!(r[0].valid, "{:?}", r[0].problem);
    // Each of the 3 cells gets a neighbour glued on a free face: 6 volumes, χ kept.
    assert_eq!((r[0].selected, r[0].volumes_after, r[0].darts_added), (3, 6, 72));
    assert_eq!(m.count_cells().euler_characteristic(3), before.euler_characteristic(3));
    let r = run_rules(&mut m, &[rule(Operation::Delete, two, &one)]);
    assert!(r[0].valid, "{:?}", r[0].problem);
    assert_eq!(r[0].volumes_after, 3);
    m.compact();
    assert!(isomorphic(&m, &grid(1, 3, 1)));
}

#[test]
fn extend_glues_on_boundary_darts_only() {
    // The query's darts the target glues to get ε: in a 3×3×3 grid the centre cell has
    // no free face, so only the 26 cells with a free face are extended.
    let mut m = grid(3, 3, 3);
    let r = run_rules(&mut m, &[rule(Operation::Extend, grid(1, 1, 1), &grid(2, 1, 1))]);
    assert!(r[0].valid);
    assert_eq!(r[0].selected, 26);
    assert_eq!(r[0].volumes_after, 27 + 26);
}

#[test]
fn replace_keeps_the_boundary_of_each_match() {
    let mut m = grid(4, 2, 1);
    let before = m.count_cells();
    let free_before = m.boundary_faces();
    let r = run_rules(&mut m, &[rule(Operation::Replace, grid(2, 1, 1), &merged_pair())]);
    assert!(r[0].valid, "{:?}", r[0].problem);
    assert_eq!((r[0].selected, r[0].volumes_after), (4, 4));
    assert_eq!(m.boundary_faces(), free_before);
    let after = m.count_cells();
    assert_eq!(after.vertices, before.vertices);
    // One inner quad (4 edges… kept, the face removed) per pair: faces −4, χ kept.
    assert_eq!(after.faces, before.faces - 4);
    assert_eq!(after.euler_characteristic(3), before.euler_characteristic(3));
    // Replacing back gives the grid again.
    let r = run_rules(&mut m, &[rule(Operation::Replace, merged_pair(), &grid(2, 1, 1))]);
    assert!(r[0].valid);
    m.compact();
    assert!(isomorphic(&m, &grid(4, 2, 1)));
}

/// The unit cube as 6 pyramids around its centre: same boundary, one inner vertex.
fn six_pyramids() -> CMap3 {
    let mut mesh = qmesh::build::IndexedMesh::new();
    mesh.points = hex_grid(1, 1, 1).points;
    mesh.points.push([0.5, 0.5, 0.5]);
    for f in [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]] {
        mesh.push_cell(qmesh::build::CellKind::Pyramid, &[f[0], f[1], f[2], f[3], 8], None);
    }
    build_volume_map(&mesh, &BuildOptions { fix_orientation: true }).unwrap().0
}

#[test]
fn replace_places_created_vertices_by_mean_value_coordinates() {
    // Each cell of a stretched 2×2×1 grid becomes 6 pyramids; the created apex lands
    // at the cell's centre.
    let mut mesh = hex_grid(2, 2, 1);
    mesh.points.iter_mut().for_each(|p| p[2] *= 3.0);
    let mut m = build_volume_map(&mesh, &BuildOptions::default()).unwrap().0;
    let r = run_rules(&mut m, &[rule(Operation::Replace, grid(1, 1, 1), &six_pyramids())]);
    assert!(r[0].valid, "{:?}", r[0].problem);
    assert_eq!((r[0].selected, r[0].volumes_after, r[0].vertices_created), (4, 24, 4));
    let cells = extract(&m).0;
    assert!(cells.kinds.iter().all(|&k| k == qmesh::build::CellKind::Pyramid));
    let q = qmesh::build::quality_by_kind(&cells);
    assert!(q.kinds[0].1.min > 0.0, "{:?}", q.kinds);
    let centres = cells.points.iter().filter(|p| (p[2] - 1.5).abs() < 1e-9).count();
    assert_eq!(centres, 4);
    for p in cells.points.iter().filter(|p| (p[2] - 1.5).abs() < 1e-9) {
        assert!([p[0], p[1]].iter().all(|c| (c - 0.5).abs() < 1e-9 || (c - 1.5).abs() < 1e-9), "{p:?}");
    }
}

#[test]
fn rule_files_run_without_code() {
    let dir = common::temp_dir("rules");
    let write = |name: &str, m: &qmesh::build::IndexedMesh| {
        qmesh::io::write_indexed(&dir.join(name), m, qmesh::io::Format::Vtk, &Default::default()).unwrap()
    };
    write("pair.vtk", &hex_grid(2, 1, 1));
    write("one.vtk", &hex_grid(1, 1, 1));
    std::fs::write(
        dir.join("rules.toml"),
        "[[rule]]\nname = \"halve\"\nop = \"delete\"\nquery = \"pair.vtk\"\ntarget = \"one.vtk\"\nstrategy = \"random\"\nseed = 3\nmax = 2\n",
    )
    .unwrap();
    let rules = load_rules(&dir.join("rules.toml")).unwrap();
    let mut m = grid(6, 1, 1);
    let r = run_rules(&mut m, &rules);
    assert_eq!((r[0].rule.as_str(), r[0].selected, r[0].volumes_after), ("halve", 2, 4));
    // Random with a max tries start darts until it has 2 (of the 5 pairs).
    assert!((2..=5).contains(&r[0].matches) && r[0].starts_tested.is_some(), "{:?}", r[0]);
    assert!(r[0].valid);
}

/// The path of a rule file `r.toml` in a fresh folder holding the unit cube `one.vtk`.
fn rule_file_beside_a_cube(name: &str) -> std::path::PathBuf {
    let dir = common::temp_dir(name);
    qmesh::io::write_indexed(&dir.join("one.vtk"), &hex_grid(1, 1, 1), qmesh::io::Format::Vtk, &Default::default())
        .unwrap();
    dir.join("r.toml")
}

#[test]
fn rule_file_errors_name_the_file_line_and_key() {
    let f = rule_file_beside_a_cube("rule-errors");
    let cases: [(&str, &str); 7] = [
        ("[[rule]]\nop = \"extend\"\nquery = \n", ":3:"),
        ("[[rule]]\nop = \"grow\"\nquery = \"one.vtk\"\n", ":2: `op`: unknown operation 'grow'"),
        ("[[rule]]\nop = \"query\"\n\nquery = \"missing.vtk\"\n", ":4: `query`: cannot use the query"),
        (
            "[[rule]]\nop = \"query\"\nquery = \"one.vtk\"\nboundary = \"maybe\"\n",
            ":4: `boundary`: unknown boundary condition",
        ),
        ("[[rule]]\nop = \"extend\"\nquery = \"one.vtk\"\n", "`target`: extend needs a target"),
        ("[[rule]]\nop = \"query\"\nquery = \"one.vtk\"\ncolour = 3\n", ":4:"),
        ("[[rule]]\nop = \"extend\"\nquery = \"one.vtk\"\ntarget = \"one.vtk\"\n", "changes nothing"),
    ];
    for (text, want) in cases {
        let e = parse_rules(&f, text).map(|_| ()).expect_err(text).to_string();
        assert!(e.starts_with(&f.display().to_string()) && e.contains(want), "{text:?}: {e}");
        assert!(!e.contains("Spanned") && !e.contains("{ "), "debug text in {e}");
    }
}

#[test]
fn apply_runs_a_function_on_every_selected_match() {
    // Query-apply (2025 §6.4): merge each selected pair of cells through their shared
    // face with the map's own primitive; the map is validated afterwards.
    let mut m = grid(4, 2, 1);
    let q = Query::new("pair", grid(2, 1, 1), |_| Condition::Any).unwrap();
    let shared: Vec<usize> =
        q.labelling().darts.iter().enumerate().filter(|(_, d)| !q.map().is_free(**d, 3)).map(|(k, _)| k).collect();
    let merge = move |map: &mut CMap3, _: &Query, darts: &[qmesh::cmap::Dart]| map.remove_face(darts[shared[0]]);
    let rule = Rule { action: Action::Apply(std::sync::Arc::new(merge)), ..Rule::find(q) };
    let r = run_rules(&mut m, &[rule]);
    assert!(r[0].valid, "{:?}", r[0].problem);
    assert_eq!((r[0].selected, r[0].modified, r[0].volumes_after), (4, 4, 4));
    m.compact();
    assert!(isomorphic(&m, &merged_pair_grid()));
}

/// The 4×2×1 grid after merging pairs along x: what `replace` with the merged pair
/// gives, built by the replace rule itself.
fn merged_pair_grid() -> CMap3 {
    let mut m = grid(4, 2, 1);
    run_rules(&mut m, &[rule(Operation::Replace, grid(2, 1, 1), &merged_pair())]);
    m.compact();
    m
}

/// Every count of a rule's report, on a case worked out by hand: a column of 3 cubes,
/// each extended by a second cube glued on one of its free faces.
#[test]
fn a_rule_report_counts_what_the_rule_did() {
    let mut m = grid(1, 3, 1);
    let r = &run_rules(&mut m, &[rule(Operation::Extend, grid(1, 1, 1), &grid(2, 1, 1))])[0];
    assert_eq!((r.rule.as_str(), r.op), ("q", "extend"));
    // The face the target glues on must be free (ε), so the query keeps the 4 rotations
    // about it. One match per cube (its darts), and one per free face and rotation with
    // the automorphisms: 5 × 4 at each end of the column, 4 × 4 in the middle.
    assert_eq!((r.matches, r.matches_with_automorphisms, r.automorphisms), (3, 56, 4));
    assert_eq!((r.selected, r.modified, r.starts_tested), (3, 3, None));
    // Each glued cube: 24 darts, 4 vertices of its own.
    assert_eq!((r.darts_added, r.darts_removed, r.vertices_created), (72, 0, 12));
    assert_eq!((r.volumes_before, r.volumes_after, r.darts_before, r.darts_after), (3, 6, 72, 144));
    assert!(r.query_seconds > 0.0 && r.modify_seconds > 0.0, "{r:?}");
    assert!(r.valid && r.problem.is_none());
}

/// A rule ranked by a metric takes its best match first: of the pairs of a row whose
/// last cell is stretched, the one holding that cell.
#[test]
fn a_ranked_rule_selects_by_its_metric() {
    let mut mesh = hex_grid(4, 1, 1);
    mesh.points.iter_mut().filter(|p| p[0] > 3.5).for_each(|p| p[0] = 7.0);
    let mut m = build_volume_map(&mesh, &BuildOptions::default()).unwrap().0;
    let mut r = rule(Operation::Delete, grid(2, 1, 1), &grid(1, 1, 1));
    r.strategy = qmesh::query::Strategy::Best;
    r.metric = Some(qmesh::query::Metric::Volume);
    r.max = Some(1);
    let report = &run_rules(&mut m, &[r])[0];
    assert_eq!((report.selected, report.volumes_after), (1, 3));
    // The best pair holds the stretched cell (x from 3 to 7, volume 4 against 1): the
    // first two cells, which a selection in dart order would have taken, are left whole.
    let mut spans: Vec<(f64, f64)> = m
        .cells(Orbit::Volume)
        .map(|d| {
            let xs = m.orbit(d, Orbit::Volume).iter().map(|&x| m.point(x)[0]).collect::<Vec<_>>();
            (xs.iter().copied().fold(f64::MAX, f64::min), xs.iter().copied().fold(f64::MIN, f64::max))
        })
        .collect();
    spans.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(&spans[..2], &[(0.0, 1.0), (1.0, 2.0)], "{spans:?}");
}

/// A unit cube's map, its nodes listed from corner `first` of the bottom face (the same
/// geometry, its darts numbered from another corner), moved by `dx` along x.
fn cube_from(first: usize, dx: f64) -> CMap3 {
    let mut mesh = hex_grid(1, 1, 1);
    mesh.points.iter_mut().for_each(|p| p[0] += dx);
    let (bottom, top) = ([0, 1, 2, 3], [4, 5, 6, 7]);
    let nodes: Vec<u32> = mesh.cell(0).1.to_vec();
    let turned: Vec<u32> =
        bottom.iter().chain(&top).map(|&i| nodes[(i + first) % 4 + if i < 4 { 0 } else { 4 }]).collect();
    let mut turned_mesh = qmesh::build::IndexedMesh::new();
    turned_mesh.points = mesh.points.clone();
    turned_mesh.push_cell(qmesh::build::CellKind::Hex, &turned, None);
    build_volume_map(&turned_mesh, &BuildOptions::default()).unwrap().0
}

/// m_QT (2025 §6): of a query's placements in a target, the one whose positions
/// coincide is taken, not the first met; and ties (all positions equal) go to the first
/// start dart, so a plan does not depend on anything but the maps.
#[test]
fn a_query_is_placed_where_its_geometry_fits() {
    use qmesh::modify::correspondence::embed;
    let q = Query::new("cube", cube_from(0, 1.0), |_| Condition::Any).unwrap();
    let pair = grid(2, 1, 1);
    let m = embed(&q, &pair).expect("a cube is in a pair");
    for (&x, &y) in q.labelling().darts.iter().zip(&m) {
        assert_eq!(q.map().point(x), pair.point(y), "label of {}", x.raw());
    }
    let mut flat = hex_grid(2, 1, 1);
    flat.points.iter_mut().for_each(|p| *p = [0.0; 3]);
    let flat = build_volume_map(&flat, &BuildOptions::default()).unwrap().0;
    assert_eq!(embed(&q, &flat).expect("placements")[0], flat.darts().next().unwrap());
}

/// The same for the boundaries of a replacement: the cube's boundary paired with the
/// same cube numbered from another corner goes dart to dart by position.
#[test]
fn boundaries_are_paired_where_their_geometry_fits() {
    use qmesh::modify::correspondence::boundary_correspondence;
    for first in 1..4 {
        let (q, t) = (cube_from(0, 0.0), cube_from(first, 0.0));
        let pairs = boundary_correspondence(&q, &t).expect("isomorphic boundaries");
        assert_eq!(pairs.len(), 24);
        assert!(pairs.iter().all(|&(x, y)| q.point(x) == t.point(y)), "from corner {first}");
    }
    let mut flat = hex_grid(1, 1, 1);
    flat.points.iter_mut().for_each(|p| *p = [0.0; 3]);
    let flat = build_volume_map(&flat, &BuildOptions::default()).unwrap().0;
    let pairs = boundary_correspondence(&cube_from(0, 0.0), &flat).expect("isomorphic boundaries");
    assert_eq!(pairs[0].1, flat.darts().find(|&d| flat.is_free(d, 3)).unwrap());
}

/// A replacement needs one boundary surface on each side: two separate cubes have two,
/// so they are refused, even against an identical pair (matching one of the two
/// surfaces would leave the other unpaired).
#[test]
fn boundaries_of_several_surfaces_are_not_paired() {
    use qmesh::modify::correspondence::boundary_correspondence;
    let mut two = hex_grid(1, 1, 1);
    let far: Vec<[f64; 3]> = two.points.iter().map(|p| [p[0] + 5.0, p[1], p[2]]).collect();
    let nodes: Vec<u32> = two.cell(0).1.iter().map(|&v| v + 8).collect();
    two.points.extend(far);
    two.push_cell(qmesh::build::CellKind::Hex, &nodes, None);
    let two = build_volume_map(&two, &BuildOptions::default()).unwrap().0;
    assert_eq!(two.count_cells().volumes, 2);
    assert!(boundary_correspondence(&two, &two).is_none());
    assert!(boundary_correspondence(&cube_from(0, 0.0), &cube_from(0, 0.0)).is_some());
}

/// The 2×1×1 pair whose second cube carries label 5.
fn pair_with_labelled_second() -> CMap3 {
    let mut pair = grid(2, 1, 1);
    pair.enable_labels();
    let second: Vec<_> = pair.cells(Orbit::Volume).collect::<Vec<_>>()[1..].to_vec();
    for v in second {
        for x in pair.orbit(v, Orbit::Volume) {
            pair.set_label_of(x, 5);
        }
    }
    pair
}

fn sorted_volume_labels(m: &CMap3) -> Vec<i32> {
    let mut labels: Vec<i32> = m.cells(Orbit::Volume).map(|d| m.label_of(d)).collect();
    labels.sort_unstable();
    labels
}

/// A target that labels its own volume passes the label to what it adds, on a map that
/// had no labels yet; the volumes the match held keep theirs (0). The same through the
/// batch executor.
#[test]
fn a_target_label_marks_the_added_volumes() {
    use qmesh::modify::{DisjointExecutor, Job};
    use qmesh::query::{Strategy, select};
    let mut m = grid(1, 3, 1);
    let r = run_rules(&mut m, &[rule(Operation::Extend, grid(1, 1, 1), &pair_with_labelled_second())]);
    assert_eq!(r[0].volumes_after, 6);
    assert_eq!(sorted_volume_labels(&m), [0, 0, 0, 5, 5, 5]);
    let mut q = Query::new("cube", grid(1, 1, 1), |_| Condition::Any).unwrap();
    let plan = Plan::new(Operation::Extend, &mut q, &pair_with_labelled_second()).unwrap();
    let set = QuerySet::new(vec![q]);
    let mut m = grid(1, 3, 1);
    let found = find_matches(&m, &set, &MatchOptions::default());
    let chosen = select(&m, &set, &found.matches, Strategy::Greedy, None);
    let jobs: Vec<Job> = chosen.iter().map(|s| Job { plan: &plan, matched: s.darts.clone() }).collect();
    DisjointExecutor::default().execute(&mut m, &jobs);
    assert!(m.is_valid().is_empty());
    assert_eq!(sorted_volume_labels(&m), [0, 0, 0, 5, 5, 5]);
}

/// `input` with every match of the one-volume-or-more `query` the greedy selection takes
/// rewritten by `op` into `target`, through the batch executor on two threads and by
/// `execute` match after match; checks that both maps are the same, dart for dart and
/// vertex for vertex, and returns the batched map and the number of matches.
fn batched_equals_one_by_one(op: Operation, query: CMap3, target: &CMap3, input: CMap3) -> (CMap3, usize) {
    use qmesh::modify::{DisjointExecutor, Job, execute};
    use qmesh::query::{Strategy, select};
    let mut q = Query::new("q", query, |_| Condition::Any).unwrap();
    let plan = Plan::new(op, &mut q, target).unwrap();
    let set = QuerySet::new(vec![q]);
    let mut batched = input;
    let found = find_matches(&batched, &set, &MatchOptions::default());
    let chosen = select(&batched, &set, &found.matches, Strategy::Greedy, None);
    let mut one_by_one = batched.clone();
    let jobs: Vec<Job> = chosen.iter().map(|s| Job { plan: &plan, matched: s.darts.clone() }).collect();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    pool.install(|| DisjointExecutor::default().execute(&mut batched, &jobs).len());
    for s in &chosen {
        execute(&mut one_by_one, &plan, &s.darts);
    }
    assert!(batched.is_valid().is_empty());
    assert_eq!(batched.dart_capacity(), one_by_one.dart_capacity());
    assert_eq!(batched.nb_vertex_ids(), one_by_one.nb_vertex_ids());
    for raw in 1..batched.dart_capacity() as u32 {
        let d = qmesh::cmap::Dart::from_raw(raw).unwrap();
        let slot = |m: &CMap3| m.is_live(d).then(|| (m.betas_raw(raw), m.vertex_of(d), m.point(d), m.label_of(d)));
        assert_eq!(slot(&batched), slot(&one_by_one), "dart {raw}");
    }
    (batched, chosen.len())
}

/// The batch executor takes plans that delete darts one match at a time (its batched
/// path only adds): the same map, dart for dart, as `execute` match after match.
#[test]
fn batched_deletions_equal_one_by_one() {
    let (m, matches) = batched_equals_one_by_one(Operation::Delete, grid(2, 1, 1), &grid(1, 1, 1), grid(4, 1, 1));
    assert_eq!((matches, m.count_cells().volumes), (2, 2));
}

/// The batch executor writes the matches on all cores (each its own darts): the same
/// map as `execute` match after match, here with 216 cubes each replaced by 6 pyramids
/// around a created vertex.
#[test]
fn batched_replacements_on_two_threads_equal_one_by_one() {
    let (m, matches) = batched_equals_one_by_one(Operation::Replace, grid(1, 1, 1), &six_pyramids(), grid(6, 6, 6));
    assert_eq!((matches, m.count_cells().volumes), (216, 6 * 216));
}

/// The operations' names read back (rule files name them), and each plan's size per
/// match: extending a cube into a pair adds one cube (24 darts), deleting one of a pair
/// removes one.
#[test]
fn operations_read_their_names_and_plans_count_their_darts() {
    for op in [Operation::Extend, Operation::Delete, Operation::Replace] {
        assert_eq!(Operation::parse(op.name()), Some(op));
    }
    assert_eq!(Operation::parse("merge"), None);
    // A rule's action prints as what it does (in `Debug` output of rules and reports).
    assert_eq!(format!("{:?}", Action::Find), "query");
    let mut q = Query::new("cube", grid(1, 1, 1), |_| Condition::Any).unwrap();
    let extend = Plan::new(Operation::Extend, &mut q, &grid(2, 1, 1)).unwrap();
    assert_eq!((extend.darts_added(), extend.darts_removed()), (24, 0));
    let mut q = Query::new("pair", grid(2, 1, 1), |_| Condition::Any).unwrap();
    let delete = Plan::new(Operation::Delete, &mut q, &grid(1, 1, 1)).unwrap();
    assert_eq!((delete.darts_added(), delete.darts_removed()), (0, 24));
}

/// A rule file's face references must exist on the query, and `max_residual` must be
/// a relative residual (0..1) of a query that has an affine fit; a query rule ranked by
/// hex quality on a hexahedron parses into a find rule keeping both.
#[test]
fn rule_files_check_face_references_and_residuals() {
    let f = rule_file_beside_a_cube("rule-checks");
    let query = "[[rule]]\nop = \"query\"\nquery = \"one.vtk\"\n";
    let ranked = "max_residual = 0.5\nstrategy = \"best\"\nmetric = \"hex-quality\"\n";
    let rules = parse_rules(&f, &format!("{query}{ranked}")).expect("a ranked query rule with a residual");
    assert_eq!(rules.len(), 1);
    assert!(matches!(rules[0].action, Action::Find));
    assert_eq!(rules[0].query.max_residual, Some(0.5));
    assert!(matches!(rules[0].metric, Some(qmesh::query::Metric::HexQuality)));
    // Unnamed, a rule is named after its query file.
    assert_eq!(rules[0].name, "one");
    for (extra, want) in [
        ("max_residual = 2.0\n", "2 is not a relative residual in 0..1"),
        ("faces = { \"9\" = \"boundary\" }\n", "has reference 9"),
    ] {
        let e = parse_rules(&f, &format!("{query}{extra}")).map(|_| ()).expect_err(extra).to_string();
        assert!(e.contains(want), "{extra:?}: {e}");
    }
}

/// What a delete rule removes is counted per match: two disjoint pairs of a row of
/// four, one cube (24 darts) removed from each.
#[test]
fn a_delete_rule_counts_the_darts_it_removes() {
    let mut m = grid(4, 1, 1);
    let r = &run_rules(&mut m, &[rule(Operation::Delete, grid(2, 1, 1), &grid(1, 1, 1))])[0];
    assert_eq!((r.selected, r.modified, r.darts_removed, r.darts_added), (2, 2, 48, 0));
    assert_eq!((r.volumes_after, r.darts_after), (2, 48));
}
