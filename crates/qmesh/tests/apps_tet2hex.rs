//! Tetrahedra to hexahedra (2022 §7.4) through the library entry point.

mod common;

use qmesh::apps::tet_to_hex;
use qmesh::build::{BuildOptions, extract, quality_by_kind};
use qmesh::io::load_map;

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn every_tetrahedron_becomes_four_positive_hexahedra() {
    let Some(dir) = common::data_dir() else { return };
    for name in ["tet/gmsh_sphere_tet.msh", "tet/gmsh_torus_tet_v22.msh", "tet/CAD0.mesh"] {
        let mut loaded = load_map(&dir.join(name), None, &BuildOptions::default()).expect(name);
        let before = loaded.map.count_cells();
        let r = tet_to_hex(&mut loaded.map, None, true).expect("tet2hex");
        assert!(loaded.map.is_valid().is_empty(), "{name}");
        assert_eq!(r.volumes_replaced, before.volumes, "{name}");
        let after = loaded.map.count_cells();
        assert_eq!(after.euler_characteristic(3), before.euler_characteristic(3), "{name}");
        let (cells, kinds) = extract(&loaded.map);
        assert_eq!((kinds.hex, kinds.tet + kinds.other), (4 * before.volumes, 0), "{name}");
        let q = quality_by_kind(&cells);
        assert!(q.kinds.iter().all(|(_, s)| s.min > 0.0), "{name}: all hexahedra positive");
    }
}

/// 2022 Theorem 2 on one tetrahedron with the generated tet2hex set: every face
/// replacement adds the darts it says it adds and leaves the map valid.
#[test]
fn each_face_replacement_adds_the_darts_it_reports() {
    use qmesh::apps::{GeneratedKind, generated_pattern_set};
    use qmesh::cmap::{CMap3, Orbit};
    use qmesh::pattern::FlagRule;
    use qmesh::replace::{find_face, replace_face};
    use qmesh::signature::Flags;
    let set = generated_pattern_set(GeneratedKind::Tet2Hex, FlagRule::Corners).unwrap();
    let mut m = CMap3::new();
    let p: Vec<u32> =
        [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]].iter().map(|&x| m.add_vertex(x)).collect();
    m.make_tetrahedron([p[0], p[1], p[2], p[3]]);
    let flag = m.reserve_mark().unwrap();
    for d in m.darts().collect::<Vec<_>>() {
        m.mark(d, flag);
    }
    m.split_all_edges(2).unwrap();
    let mut replaced = 0;
    for d in m.cells(Orbit::Face).collect::<Vec<_>>() {
        let (i, aligned) = find_face(&m, &set, Flags::Mark(flag), d, true).expect("every face matches");
        let before = m.nb_darts();
        let added = replace_face(&mut m, &set.patterns[i], &aligned);
        assert!(added > 0 && m.nb_darts() == before + added, "{added} darts said added");
        assert!(m.is_valid().is_empty());
        replaced += 1;
    }
    assert_eq!(replaced, 4);
}
