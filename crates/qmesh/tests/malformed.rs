//! A catalogue of malformed inputs across the formats: each must give an error naming
//! the file, the line (or byte offset) and what was expected — never a panic, and
//! never an allocation out of proportion with the file size (measured with a counting
//! global allocator).

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use qmesh::build::BuildOptions;
use qmesh::io::load_map;

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// Tests measuring the allocator run one at a time.
static SERIAL: Mutex<()> = Mutex::new(());

#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(l.size(), Ordering::Relaxed) + l.size();
        PEAK.fetch_max(now, Ordering::Relaxed);
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size(), Ordering::Relaxed);
        unsafe { System.dealloc(p, l) }
    }
}

#[global_allocator]
static A: Counting = Counting;

/// (file name, contents, substrings the message must contain).
type Case = (&'static str, &'static [u8], &'static [&'static str]);

const CASES: &[Case] = &[
    // --- VTK legacy ---
    ("empty.vtk", b"", &["line 1", "# vtk DataFile"]),
    ("header.vtk", b"# not vtk\n", &["line 1", "expected '# vtk DataFile"]),
    ("mode.vtk", b"# vtk DataFile Version 3.0\nt\nTEXT\n", &["line 3", "ASCII or BINARY"]),
    ("dataset.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n", &["STRUCTURED_POINTS", "not supported"]),
    ("huge_points.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1000000000000 float\n0 0 0\n", &["line 5", "1000000000000 points"]),
    ("neg_points.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS -5 float\n", &["line 5", "non-negative"]),
    ("trunc_points.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0\n", &["line 6", "point coordinates", "end of file"]),
    ("nan.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 float\n0 nan 0\n", &["line 6", "finite"]),
    ("inf.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 float\n0 inf 0\n", &["line 6", "finite"]),
    ("badtype.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 quaternion\n", &["line 5", "data type"]),
    ("oob.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 9\nCELL_TYPES 1\n10\n", &["line 8", "point index 9", "out of range"]),
    ("negidx.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 -2 3\nCELL_TYPES 1\n10\n", &["point index -2", "out of range"]),
    ("cellsize.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n7 0 1 2 3\nCELL_TYPES 1\n10\n", &["line 8", "declares 7 nodes"]),
    ("types_count.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n", &["CELL_TYPES lists 2 types for 1 cells"]),
    ("nodes_for_type.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n12\n", &["type 12 needs 8 points"]),
    ("binary_trunc.vtk", b"# vtk DataFile Version 3.0\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 2 double\n\x00\x00", &["line 5", "48 more bytes"]),
    ("degenerate_repeat.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 2 10\n4 0 1 2 3\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n", &["line 9", "cells 0 and 1", "inconsistent orientation", "lines 8, 9"]),
    ("degenerate_tet.vtk", b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 0 2 3\nCELL_TYPES 1\n10\n", &["line 8", "cell 0", "repeated"]),
    // --- Medit ---
    ("nohead.mesh", b"Vertices\n1\n0 0 0 0\n", &["MeshVersionFormatted"]),
    ("version.mesh", b"MeshVersionFormatted 9\n", &["line 1", "version 1 or 2"]),
    ("dim.mesh", b"MeshVersionFormatted 1\nDimension 7\n", &["line 2", "dimension 2 or 3"]),
    ("huge.mesh", b"MeshVersionFormatted 1\nDimension 3\nVertices\n1000000000000\n0 0 0 0\n", &["line 4", "1000000000000 vertices"]),
    ("trunc.mesh", b"MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0.0 0.0 0.0 0\n1.0 1.0\n", &["line 6", "z coordinate"]),
    ("lies.mesh", b"MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0 0 0\n1 1\n", &["line 4", "2 vertices"]),
    ("zeroidx.mesh", b"MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra\n1\n0 1 2 3 0\n", &["line 11", "vertex index 0", "1..=4"]),
    ("badref.mesh", b"MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra\n1\n1 2 3 4 x\n", &["line 11", "element reference"]),
    ("nanvert.mesh", b"MeshVersionFormatted 1\nDimension 3\nVertices\n1\nNaN 0 0 0\n", &["line 5", "finite"]),
    // --- gmsh ---
    ("nofmt.msh", b"$Nodes\n", &["line 1", "$MeshFormat"]),
    ("ver.msh", b"$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", &["version 3.0", "not supported"]),
    ("binary.msh", b"$MeshFormat\n4.1 1 8\n$EndMeshFormat\n", &["binary"]),
    ("huge22.msh", b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n999999999999\n1 0 0 0\n$EndNodes\n", &["line 5", "999999999999 nodes"]),
    ("undef_tag.msh", b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 4 2 0 1 1 7 8 9\n$EndElements\n", &["line 10", "node tag 7"]),
    ("unterminated.msh", b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n", &["$EndEntities", "end of file"]),
    ("eltype.msh", b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 99 0 1\n$EndElements\n", &["line 10", "element type 99"]),
    ("v4count.msh", b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 5 1 5\n3 1 0 1\n1\n0 0 0\n$EndNodes\n", &["declares 5 nodes"]),
    // --- OFF / OBJ / STL / PLY ---
    ("head.off", b"FOO\n", &["line 1", "'OFF' header"]),
    ("huge.off", b"OFF\n1000000000000 1 0\n", &["line 2", "1000000000000 vertices"]),
    ("oob.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", &["line 6", "vertex index 5"]),
    ("small.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", &["line 6", "at least 3"]),
    ("nmanifold.off", b"OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 1 0 2\n", &["line 8", "edge 0-1", "polygons 0 and 1", "lines 7, 8"]),
    ("idx.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", &["line 4", "index 4"]),
    ("zero.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", &["line 4", "index 0"]),
    ("word.obj", b"v 0 0 0\nv 1 0 zz\n", &["line 2", "z coordinate", "zz"]),
    ("noface.obj", b"v 0 0 0\n", &["no faces"]),
    ("short.stl", b"\x00\x01", &["byte", "84 bytes"]),
    ("count.stl", b"binary header padded to eighty bytes with dots..................................\xff\xff\xff\x00", &["byte 84", "16777215 triangles"]),
    ("ascii.stl", b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n", &["line 6", "'vertex'"]),
    ("notxml.vtu", b"hello", &["line 1", "VTKFile"]),
    ("unclosed.vtu", b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"2\" NumberOfCells=\"1\">\n<Points></Points>\n", &["line 4", "DataArray"]),
    ("polydata.vtu", b"<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\"><PolyData></PolyData></VTKFile>\n", &["line 2", "UnstructuredGrid"]),
    ("oob.vtu", b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 7</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">5</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n", &["line 6", "point index 7"]),
    ("magic.ply", b"plx\n", &["line 1", "'ply'"]),
    ("hdr.ply", b"ply\nformat ascii 1.0\nelement vertex 1000000000000\nend_header\n", &["line 3", "1000000000000"]),
    ("ply_oob.ply", b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 8\n", &["line 13", "vertex index 8"]),
    ("ply_type.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\nend_header\n", &["line 4", "scalar type"]),
    // --- moka ---
    ("head.moka", b"Not moka\n", &["line 1", "Moka file"]),
    ("alpha.moka", b"Moka file [ascii]\n0 0 0 0 0 0 0 0\n5 0 0 0 0 0 0 0 0\n", &["out of range"]),
    ("flag.moka", b"Moka file [ascii]\n0 0 0 0 0 0 0 0\n1 0 0 0 0 0 0 0 7\n", &["line 3", "point flag"]),
];

fn check(name: &str, data: &[u8], must: &[&str], dir: &std::path::Path) -> Result<(), String> {
    let p = dir.join(name);
    std::fs::write(&p, data).unwrap();
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let r = std::panic::catch_unwind(|| load_map(&p, None, &BuildOptions::default()));
    let peak = PEAK.load(Ordering::Relaxed) - before;
    let msg = match r {
        Err(_) => return Err(format!("{name}: the reader panicked")),
        Ok(Ok(_)) => return Err(format!("{name}: expected an error, the file was accepted")),
        Ok(Err(e)) => e.to_string(),
    };
    if !msg.contains(name) {
        return Err(format!("{name}: message does not name the file: {msg}"));
    }
    if let Some(m) = must.iter().find(|m| !msg.contains(*m)) {
        return Err(format!("{name}: message lacks '{m}': {msg}"));
    }
    // Whole-file buffer + parse structures: a small multiple of the size plus slack.
    let budget = 64 * data.len() + (256 << 10);
    if peak > budget {
        return Err(format!("{name}: peak allocation {peak} B for a {} B file", data.len()));
    }
    Ok(())
}

#[test]
fn catalogue_of_malformed_inputs() {
    let _g = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    assert!(CASES.len() >= 30);
    let dir = common::temp_dir("malformed");
    let failures: Vec<String> = CASES.iter().filter_map(|(n, d, m)| check(n, d, m, &dir).err()).collect();
    assert!(failures.is_empty(), "{} of {} cases failed:\n{}", failures.len(), CASES.len(), failures.join("\n"));
    eprintln!("{} malformed inputs rejected with located messages", CASES.len());
}

/// The case: a 100-byte file declaring 10^12 points, in every text format.
#[test]
fn hundred_byte_files_declaring_a_trillion_points() {
    let _g = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::temp_dir("trillion");
    let pad = |s: &str| {
        let mut v = s.as_bytes().to_vec();
        v.resize(100, b' ');
        v
    };
    for (name, text) in [
        ("t.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1000000000000 double\n"),
        ("t.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n1000000000000\n"),
        ("t.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1000000000000\n"),
        ("t.off", "OFF\n1000000000000 1 0\n"),
        ("t.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000000\n"),
    ] {
        let data = pad(text);
        assert_eq!(data.len(), 100);
        check(name, &data, &["1000000000000"], &dir).unwrap();
    }
}

/// Truncating a real file anywhere gives an error (or a smaller valid mesh), never a panic.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn truncated_real_files_never_panic() {
    let _g = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let Some(d) = common::data_dir() else { return };
    let dir = common::temp_dir("trunc");
    for f in [
        "hex/gmsh_box_hex_4x4x4.vtk",
        "hex/gmsh_box_hex_4x4x4.msh",
        "hex/gmsh_box_hex_4x4x4_v22.msh",
        "hex/gmsh_box_hex_4x4x4.mesh",
        "surface/cube.off",
        "patterns/cgal/hexa-8-subdivision/vpattern/split-hexa.moka",
    ] {
        let data = std::fs::read(d.join(f)).unwrap();
        let name = std::path::Path::new(f).file_name().unwrap().to_string_lossy().into_owned();
        for cut in (1..data.len()).step_by(data.len() / 40 + 1) {
            let p = dir.join(&name);
            std::fs::write(&p, &data[..cut]).unwrap();
            let r = std::panic::catch_unwind(|| load_map(&p, None, &BuildOptions::default()));
            assert!(r.is_ok(), "{f} cut at {cut}: panic");
        }
    }
}
