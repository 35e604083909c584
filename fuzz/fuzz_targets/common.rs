//! Shared body of the reader fuzz targets: parse bytes as a file of one format, then
//! build its map. Errors are expected; panics, hangs and huge allocations are bugs.

pub fn read_and_build(extension: &str, data: &[u8]) {
    let name = format!("fuzz.{extension}");
    let path = std::path::Path::new(&name);
    let format = qmesh::io::Format::from_path(path).expect("known extension");
    if let Ok(qmesh::io::Loaded::Indexed(mesh)) = qmesh::io::parse(path, data, format) {
        let _ = qmesh::build::build_map(mesh, &qmesh::build::BuildOptions { fix_orientation: true });
    }
}
