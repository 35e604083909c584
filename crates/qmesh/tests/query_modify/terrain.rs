//! 2025 §7.4, terrain generation (Table 2): query-apply with the built-in flatten-top,
//! then query-extend with a house, from the rule files of `examples/terrain`; and the
//! merge and rule-file errors of query-apply.

use std::path::{Path, PathBuf};

use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::{CMap3, Orbit};
use qmesh::generate::{TerrainOptions, hex_grid, terrain};
use qmesh::modify::{Action, Rule, builtin_apply, load_rules, parse_rules, run_rules};
use qmesh::query::{Condition, Query};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/terrain").join(name)
}

/// The 12-sided boundary faces (flattened spot tops), each with its vertices' heights.
fn spot_tops(m: &CMap3) -> Vec<Vec<f64>> {
    m.cells(Orbit::Face)
        .filter(|&d| m.is_free(d, 3) && m.face_degree(d) == 12)
        .map(|d| m.orbit(d, Orbit::HalfFace).iter().map(|&e| m.point(e)[2]).collect())
        .collect()
}

#[test]
fn table_2_counts_from_the_example_rule_files() {
    let o = TerrainOptions { base: 12.0, ..TerrainOptions::default() };
    let (mut m, _) = build_volume_map(&terrain(&o), &BuildOptions::default()).unwrap();
    let c = m.count_cells();
    assert_eq!((c.volumes, c.darts), (16_384, 425_984), "step 1");
    let spots = load_rules(&example("flatten.toml")).unwrap();
    let r = &run_rules(&mut m, &spots)[0];
    assert!(r.valid, "{:?}", r.problem);
    // A random selection with a max stops early: a few hundred start darts, not all.
    assert_eq!((r.selected, r.modified), (50, 50));
    assert!(r.matches >= 50 && r.starts_tested.is_some_and(|n| n < 10_000), "{:?}", (r.matches, r.starts_tested));
    assert_eq!((r.volumes_after, r.darts_after), (15_984, 419_984), "step 2");
    let tops = spot_tops(&m);
    assert_eq!(tops.len(), 50);
    for z in &tops {
        assert!(z.iter().all(|&h| (h - z[0]).abs() < 1e-12), "a spot is not flat: {z:?}");
        assert!(z[0] >= 12.0 && z[0] <= 20.0, "spot height {} outside the relief", z[0]);
    }
    let houses = load_rules(&example("houses.toml")).unwrap();
    let r = &run_rules(&mut m, &houses)[0];
    assert!(r.valid, "{:?}", r.problem);
    assert_eq!((r.matches, r.selected, r.modified), (50, 50, 50));
    assert_eq!((r.volumes_after, r.darts_after), (16_134, 431_684), "step 3");
    assert!(spot_tops(&m).is_empty(), "every spot top is under a house");
    // Same seed, same spots: the run is deterministic.
    let (mut again, _) = build_volume_map(&terrain(&o), &BuildOptions::default()).unwrap();
    run_rules(&mut again, &spots);
    let mut a = spot_tops(&again);
    let mut b = tops;
    a.sort_by(|x, y| x.partial_cmp(y).unwrap());
    b.sort_by(|x, y| x.partial_cmp(y).unwrap());
    assert_eq!(a, b);
}

#[test]
fn merge_makes_one_volume_of_a_block_through_its_inner_edges() {
    // 2×2×2 hexahedra: 12 inner faces around 6 inner edges and a centre vertex; the
    // last face around each inner edge takes the edge with it.
    let grid = |n| build_volume_map(&hex_grid(n, n, n), &BuildOptions::default()).unwrap().0;
    let mut m = grid(3);
    let rule = Rule {
        action: Action::Apply(builtin_apply("merge").unwrap()),
        max: Some(1),
        ..Rule::find(Query::new("block", grid(2), |_| Condition::Any).unwrap())
    };
    let r = &run_rules(&mut m, &[rule])[0];
    assert!(r.valid, "{:?}", r.problem);
    assert_eq!((r.modified, r.volumes_after), (1, 27 - 7));
    // The merged volume: the block's 24 boundary quads.
    let merged = m.cells(Orbit::Volume).find(|&d| m.orbit(d, Orbit::Volume).len() == 96);
    assert!(merged.is_some(), "no volume of 24 quadrilaterals");
}

/// The map of `mesh` after flatten-top with itself as the query, and the rule's report.
fn flatten_top_of_itself(mesh: &qmesh::build::IndexedMesh) -> (CMap3, qmesh::modify::RuleReport) {
    let (q, _) = build_volume_map(mesh, &BuildOptions::default()).unwrap();
    let mut m = q.clone();
    let rule = Rule {
        action: Action::Apply(builtin_apply("flatten-top").unwrap()),
        ..Rule::find(Query::new("itself", q, |_| Condition::Any).unwrap())
    };
    let r = run_rules(&mut m, &[rule]).remove(0);
    (m, r)
}

#[test]
fn flatten_top_without_a_top_face_is_refused_and_leaves_a_valid_map() {
    // A tetrahedron standing on a face: its three other faces lean 70.5° from +z.
    let mut mesh = qmesh::build::IndexedMesh::new();
    let h = (2.0f64 / 3.0).sqrt();
    mesh.points = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.75f64.sqrt(), 0.0], [0.5, 0.75f64.sqrt() / 3.0, h]];
    mesh.push_cell(qmesh::build::CellKind::Tet, &[0, 1, 2, 3], None);
    let (_, r) = flatten_top_of_itself(&mesh);
    assert_eq!((r.selected, r.modified), (1, 0));
    assert!(r.valid);
    assert!(r.problem.as_deref().unwrap_or("").contains("no top face"), "{:?}", r.problem);
}

/// Which faces are tops depends on their direction only: a block of voxels a tenth
/// of a unit wide (faces of area 0.01) is flattened as a unit one is.
#[test]
fn flatten_top_finds_the_top_faces_at_any_scale() {
    for scale in [1.0, 0.1] {
        let mut mesh = hex_grid(2, 2, 1);
        mesh.points.iter_mut().for_each(|p| *p = p.map(|c| c * scale));
        let (m, r) = flatten_top_of_itself(&mesh);
        assert!(r.valid && r.problem.is_none(), "scale {scale}: {:?}", r.problem);
        assert_eq!(r.modified, 1, "scale {scale}");
        // One volume whose top is one octagon (the four top quads merged) at z = scale.
        let top: Vec<_> = m.cells(Orbit::Face).filter(|&d| m.is_free(d, 3) && m.face_degree(d) == 8).collect();
        assert_eq!(top.len(), 1, "scale {scale}");
        assert!(m.orbit(top[0], Orbit::HalfFace).iter().all(|&e| (m.point(e)[2] - scale).abs() < 1e-12));
    }
}

#[test]
fn apply_rule_file_errors_name_the_key() {
    let f = example("flatten.toml");
    let cases = [
        ("[[rule]]\nop = \"apply\"\nquery = \"block.vtk\"\n", "`apply`: op = \"apply\" needs"),
        (
            "[[rule]]\nop = \"apply\"\napply = \"smooth\"\nquery = \"block.vtk\"\n",
            ":3: `apply`: unknown apply operation 'smooth' (merge, flatten-top)",
        ),
        ("[[rule]]\nop = \"query\"\napply = \"merge\"\nquery = \"block.vtk\"\n", ":3: `apply`: only op = \"apply\""),
        (
            "[[rule]]\nop = \"apply\"\napply = \"merge\"\nquery = \"block.vtk\"\nseparation = \"faces\"\n",
            ":5: `separation`: unknown separation 'faces' (darts, vertices)",
        ),
        (
            "[[rule]]\nop = \"apply\"\napply = \"merge\"\nquery = \"block.vtk\"\ntarget = \"spot.vtk\"\n",
            ":5: `target`: op = \"apply\" takes no target",
        ),
    ];
    for (text, want) in cases {
        let e = parse_rules(&f, text).map(|_| ()).expect_err(text).to_string();
        assert!(e.contains(want), "{text:?}: {e}");
    }
    let ok = parse_rules(&f, "[[rule]]\nop = \"apply\"\napply = \"merge\"\nquery = \"block.vtk\"\n").unwrap();
    assert_eq!(ok[0].action.name(), "apply");
}
