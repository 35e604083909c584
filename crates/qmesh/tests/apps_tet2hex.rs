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
