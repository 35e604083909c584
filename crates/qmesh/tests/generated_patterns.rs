//! The pattern sets qmesh generates are the papers' sets: same signatures as the
//! authors' `.moka` files, same result on a real mesh.

mod common;

use qmesh::apps::{GeneratedKind, generated_pattern_set};
use qmesh::build::BuildOptions;
use qmesh::io::load_map;
use qmesh::pattern::{FlagRule, PatternKind, PatternSet, load_pattern_dir};
use qmesh::replace::{ReplaceOptions, query_replace};

fn signatures(set: &PatternSet, kind: PatternKind) -> Vec<String> {
    let mut v: Vec<String> = set.patterns.iter().filter(|p| p.kind == kind).map(|p| p.signature.digest()).collect();
    v.sort();
    v
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn generated_sets_match_the_papers_pattern_files() {
    let Some(d) = common::data_dir() else { return };
    for (kind, dir, mesh, factor) in [
        (GeneratedKind::HexSubdivision, "hexa-8-subdivision", "hex/gmsh_box_hex_4x4x4.vtk", 8),
        (GeneratedKind::Tet2Hex, "tetra-to-hexa", "tet/CAD0.mesh", 4),
    ] {
        let ours = generated_pattern_set(kind, FlagRule::Corners).unwrap();
        let theirs = load_pattern_dir(&d.join("patterns/cgal").join(dir), FlagRule::Corners);
        for k in [PatternKind::Face, PatternKind::Volume] {
            assert_eq!(signatures(&ours, k), signatures(&theirs, k), "{dir} {k:?}");
        }
        let path = d.join(mesh);
        let mut a = load_map(&path, None, &BuildOptions::default()).unwrap().map;
        let mut b = load_map(&path, None, &BuildOptions::default()).unwrap().map;
        let before = a.count_cells().volumes;
        let opts = ReplaceOptions { split_edges: Some(2), ..Default::default() };
        query_replace(&mut a, &ours, &opts).unwrap();
        query_replace(&mut b, &theirs, &opts).unwrap();
        assert_eq!(a.count_cells(), b.count_cells(), "{dir}");
        assert_eq!(a.count_cells().volumes, factor * before);
        assert!(a.is_valid().is_empty());
        if kind != GeneratedKind::HexSubdivision {
            // The authors drew tetra-to-hexa by hand: its inner points are not exact
            // barycentres, so only the topology is compared.
            continue;
        }
        // Same geometry too: every vertex position of one output is in the other.
        let key = |p: [f64; 3]| p.map(|c| (c * 1e9).round() as i64);
        let pa: std::collections::BTreeSet<_> = a.positions().iter().map(|&p| key(p)).collect();
        let used_b: std::collections::BTreeSet<_> = b.darts().map(|x| key(b.point(x))).collect();
        assert!(used_b.is_subset(&pa), "{dir}: vertex positions differ");
    }
}
