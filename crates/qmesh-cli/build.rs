// The same data-folder check as the library's (cfg `qmesh_data` for the CLI tests).
include!("../qmesh/build.rs");
