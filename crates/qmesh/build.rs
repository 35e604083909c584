// Tells the tests whether the shared data folder (`$QMESH_DATA`, default
// `../shared/data` beside the repository) is there. Tests that read it carry
// `#[cfg_attr(not(qmesh_data), ignore = "…")]`, so that without it cargo's summary
// counts them as ignored, with the reason, never as passed. With
// `QMESH_REQUIRE_DATA=1` (CI) a missing folder stops the build.
//
// The folder is looked for when the build script runs (a change of either variable
// reruns it); a folder that appears later is seen after `touch crates/qmesh/build.rs`.

use std::path::PathBuf;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(qmesh_data)");
    println!("cargo::rerun-if-env-changed=QMESH_DATA");
    println!("cargo::rerun-if-env-changed=QMESH_REQUIRE_DATA");
    println!("cargo::rerun-if-changed=build.rs");
    let dir = std::env::var_os("QMESH_DATA").map(PathBuf::from).unwrap_or_else(|| {
        PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it")).join("../../../shared/data")
    });
    if dir.is_dir() {
        println!("cargo::rustc-cfg=qmesh_data");
    } else if std::env::var("QMESH_REQUIRE_DATA").as_deref() == Ok("1") {
        panic!("QMESH_REQUIRE_DATA=1 but the data folder {} is missing", dir.display());
    }
}
