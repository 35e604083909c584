//! Fuzz target: a pattern file (Moka, VTK or OFF by its first bytes) read, built and
//! turned into a pattern (kind, flags, signature, interior coordinates) must never panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    use qmesh::io::{Format, Loaded, parse};
    let format = if data.starts_with(b"Moka") {
        Format::Moka
    } else if data.starts_with(b"# vtk") {
        Format::Vtk
    } else {
        Format::Off
    };
    let path = std::path::Path::new("fuzz.pattern");
    let map = match parse(path, data, format) {
        Ok(Loaded::Map(m)) => m,
        Ok(Loaded::Indexed(mesh)) => match qmesh::build::build_map(mesh, &qmesh::build::BuildOptions { fix_orientation: true }) {
            Ok((m, _)) => m,
            Err(_) => return,
        },
        Err(_) => return,
    };
    let _ = qmesh::pattern::pattern_from_map(path, map, qmesh::pattern::FlagRule::Corners, &[]);
});
