//! Conformal transitions (2022 Algorithm 7): every 2:1 configuration is covered by the
//! generated set and by the papers' 325 patterns; octree meshes become conformal.

mod common;

use qmesh::apps::{
    GeneratedKind, SubdivideOptions, configuration_cell, conformal, generated_pattern_set, subdivide,
    transition_configurations,
};
use qmesh::build::{extract, non_conformal_faces, quality_by_kind};
use qmesh::geom::TriangleBvh;
use qmesh::io::read_surface;
use qmesh::pattern::{FlagRule, PatternKind, PatternSet, load_pattern_dir};

/// Runs the pipeline on a single cube of every configuration; returns how many fail.
fn uncovered(set: &PatternSet) -> Vec<String> {
    let mut missing = Vec::new();
    for c in transition_configurations().0 {
        let (map, r) = conformal(&configuration_cell(c), set, true).expect("one cell builds");
        assert!(map.is_valid().is_empty(), "{c:?}");
        if r.replace.unmatched_volumes + r.replace.unmatched_faces > 0 {
            missing.push(format!("{c:?}"));
        }
    }
    missing
}

#[test]
fn configurations_and_classes() {
    let (all, classes) = transition_configurations();
    // 2:1 configurations of a cube other than the plain one, and their rotation classes
    // (the figures of Jaillet and Lobos' set, 2022 §7.3).
    assert_eq!(all.len(), 6209);
    assert_eq!(classes.len(), 325);
}

#[test]
fn generated_set_covers_every_configuration() {
    let set = generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners).expect("generated");
    assert_eq!(set.count(PatternKind::Face), 5);
    assert_eq!(set.count(PatternKind::Volume), 325);
    assert!(set.duplicates().is_empty());
    assert_eq!(uncovered(&set), Vec::<String>::new());
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn papers_325_patterns_cover_every_configuration() {
    let Some(dir) = common::data_dir() else { return };
    let mut set = PatternSet::default();
    for sub in ["patterns/cgal/hexa-325-patterns", "patterns/cgal/square-5-patterns"] {
        load_pattern_dir(&dir.join(sub), FlagRule::Corners).patterns.into_iter().for_each(|p| {
            set.insert(p);
        });
    }
    assert_eq!((set.count(PatternKind::Face), set.count(PatternKind::Volume)), (5, 325));
    assert_eq!(uncovered(&set), Vec::<String>::new());
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn octree_of_the_bunny_becomes_conformal() {
    let Some(dir) = common::data_dir() else { return };
    let s = read_surface(&dir.join("surface/bunny.off"), None).expect("bunny");
    let bvh = TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
    let octree = subdivide(&bvh, &SubdivideOptions { levels: 4, direct: true, ..Default::default() }, None, &|_| {})
        .expect("subdivide")
        .mesh;
    let mut papers = PatternSet::default();
    for sub in ["patterns/cgal/hexa-325-patterns", "patterns/cgal/square-5-patterns"] {
        load_pattern_dir(&dir.join(sub), FlagRule::Corners).patterns.into_iter().for_each(|p| {
            papers.insert(p);
        });
    }
    let generated = generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners).expect("generated");
    for set in [&generated, &papers] {
        let (map, r) = conformal(&octree, set, true).expect("conformal");
        assert!(map.is_valid().is_empty());
        assert_eq!((r.replace.unmatched_faces, r.replace.unmatched_volumes), (0, 0));
        assert!(r.hanging.cells_with_hanging > 100, "{:?}", r.hanging);
        assert_eq!(non_conformal_faces(&map), 0);
        let (cells, kinds) = extract(&map);
        assert_eq!(kinds.other, 0, "only hex, prism, pyramid, tet");
        for (kind, q) in quality_by_kind(&cells).kinds {
            assert!(q.min > 0.0, "{kind:?}: every cell has positive volume");
        }
    }
    // Without the transitions, the octree is not conformal.
    let (plain, _) = qmesh::build::build_map(octree, &Default::default()).expect("octree");
    assert!(non_conformal_faces(&plain) > 100);
}

#[test]
fn a_mesh_that_is_not_an_octree_is_refused_with_the_cell() {
    let mut grid = qmesh::generate::hex_grid(2, 2, 2);
    grid.points[13][0] += 0.2; // the centre point: all 8 cells stop being boxes
    let set = generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners).expect("generated");
    let err = conformal(&grid, &set, true).expect_err("sheared cells");
    assert!(err.to_string().contains("cell 0 is not an axis-aligned box"), "{err}");
    let tets = qmesh::generate::tet_grid(1, 1, 1);
    assert!(conformal(&tets, &set, true).is_err());
}
