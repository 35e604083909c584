//! Shared test helpers: locating `../shared/data` (or `$QMESH_DATA`).
#![allow(dead_code)]

use std::path::PathBuf;

/// The data folder, or None (with a printed reason) when absent. With
/// `QMESH_REQUIRE_DATA=1` (set by `.ci/run`) a missing folder fails the test.
pub fn data_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("QMESH_DATA")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"));
    if dir.is_dir() {
        return Some(dir);
    }
    if std::env::var("QMESH_REQUIRE_DATA").as_deref() == Ok("1") {
        panic!("QMESH_REQUIRE_DATA=1 but the data folder {} is missing", dir.display());
    }
    eprintln!("skipped: data folder {} not found (set QMESH_DATA)", dir.display());
    None
}

/// Files of a data subfolder, sorted.
pub fn data_files(sub: &str) -> Vec<PathBuf> {
    let Some(d) = data_dir() else { return Vec::new() };
    let mut v: Vec<PathBuf> = std::fs::read_dir(d.join(sub))
        .unwrap_or_else(|e| panic!("{sub}: {e}"))
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && qmesh::io::Format::from_path(p).is_some())
        .collect();
    v.sort();
    v
}

/// The unit cube's corners in VTK hexahedron order.
pub const UNIT_CUBE: [[f64; 3]; 8] =
    [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]];

/// Adds the 8 corners of the unit cube shifted by `x0` along x, in VTK hex order.
pub fn unit_cube_vertices(m: &mut qmesh::cmap::CMap3, x0: f64) -> [u32; 8] {
    UNIT_CUBE.map(|p| m.add_vertex([p[0] + x0, p[1], p[2]]))
}

/// A fresh temporary folder for one test.
pub fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("qmesh-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
