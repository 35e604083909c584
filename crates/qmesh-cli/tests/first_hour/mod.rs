//! What a new user's first hour found (issue 15): outputs that lie or lose data, and
//! arguments that depend on their order. Each test failed before its fix.

use super::{json_of, qmesh, temp};

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

/// Polygon count and vertex count of a surface file, read back by `qmesh info`.
fn surface_counts(path: &std::path::Path) -> (u64, u64) {
    let j = json_of(&["info", s(path), "--json"]);
    (j["faces"].as_u64().unwrap(), j["vertices"].as_u64().unwrap())
}

/// Item 1: a volume mesh written to a surface format is its boundary surface, in every
/// surface format and from every command that writes cells (here `tetrahedralize`,
/// `tet2hex`, `recombine` and `convert`).
#[test]
fn volume_meshes_written_to_surface_formats_keep_their_boundary() {
    let grid = temp("fh-grid.vtk");
    assert_eq!(qmesh(&["generate", "grid", "--size", "2", "-o", s(&grid)]).0, 0);
    // 2×2×2 hexahedra: 24 boundary quads on 26 boundary vertices.
    for ext in ["off", "obj", "stl", "ply"] {
        let out = temp(&format!("fh-grid.{ext}"));
        let (code, _, err) = qmesh(&["convert", s(&grid), s(&out)]);
        assert_eq!(code, 0, "{err}");
        let (faces, vertices) = surface_counts(&out);
        // STL holds triangles only: each quad is two.
        assert_eq!(faces, if ext == "stl" { 48 } else { 24 }, "{ext}");
        assert_eq!(vertices, 26, "{ext}");
    }
    let tets = temp("fh-tets.off");
    let (code, _, err) = qmesh(&["tetrahedralize", s(&grid), "-o", s(&tets), "--five"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(surface_counts(&tets), (48, 26), "the 24 quads, each split in two");
    let tet_vtk = temp("fh-tets.vtk");
    assert_eq!(qmesh(&["tetrahedralize", s(&grid), "-o", s(&tet_vtk), "--five"]).0, 0);
    for cmd in ["tet2hex", "recombine"] {
        let out = temp(&format!("fh-{cmd}.obj"));
        let (code, _, err) = qmesh(&[cmd, s(&tet_vtk), "-o", s(&out)]);
        assert_eq!(code, 0, "{cmd}: {err}");
        let (faces, _) = surface_counts(&out);
        assert!(faces >= 24, "{cmd} wrote {faces} boundary faces");
    }
}

/// Item 2: no command overwrites its input without `--force`, whatever path names it
/// (`./`, `..`, a symbolic link, a hard link).
#[test]
fn no_command_overwrites_its_input_without_force() {
    let dir = temp("fh-overwrite");
    std::fs::create_dir_all(&dir).unwrap();
    let surface = dir.join("t.off");
    std::fs::write(&surface, "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n").unwrap();
    let before = std::fs::read(&surface).unwrap();
    std::os::unix::fs::symlink(&surface, dir.join("link.off")).unwrap();
    std::fs::hard_link(&surface, dir.join("hard.off")).unwrap();
    let dotted = dir.join(".").join("..").join("fh-overwrite").join("t.off");
    for out in [surface.clone(), dotted, dir.join("link.off"), dir.join("hard.off")] {
        for args in [
            vec!["subdivide", s(&surface), "--levels", "2", "-o", s(&out)],
            vec!["marching-cubes", s(&surface), "--levels", "2", "-o", s(&out)],
            vec!["convert", s(&surface), s(&out)],
        ] {
            let (code, _, err) = qmesh(&args);
            assert_eq!(code, 2, "{args:?}");
            assert!(err.contains("refusing to overwrite"), "{args:?}: {err}");
            assert_eq!(std::fs::read(&surface).unwrap(), before, "{args:?} changed its input");
        }
    }
    // --force is the way to do it on purpose.
    let (code, _, err) = qmesh(&["convert", s(&surface), s(&surface), "--force"]);
    assert_eq!(code, 0, "{err}");
}

/// Item 8: `--patterns` takes one folder per occurrence (or a comma-separated list), so
/// positional arguments after it stay positional.
#[test]
fn patterns_option_does_not_swallow_positional_arguments() {
    let dir = temp("fh-tet2hex-patterns");
    assert_eq!(qmesh(&["patterns", "generate", "tet2hex", "-o", s(&dir)]).0, 0);
    let tets = temp("fh-pt.vtk");
    assert_eq!(qmesh(&["generate", "tet-grid", "--size", "1", "-o", s(&tets)]).0, 0);
    let out = temp("fh-pt-out.vtk");
    let (code, _, err) = qmesh(&["replace", "--split-edges", "2", "--patterns", s(&dir), s(&tets), s(&out)]);
    assert_eq!(code, 0, "{err}");
    let twice = format!("{},{}", s(&dir), s(&dir));
    let (code, _, err) = qmesh(&["replace", "--split-edges", "2", "--patterns", &twice, s(&tets), s(&out)]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) =
        qmesh(&["replace", "--split-edges", "2", "--patterns", s(&dir), "--patterns", s(&dir), s(&tets), s(&out)]);
    assert_eq!(code, 0, "{err}");
}

/// A Medit file with one hexahedron on `points` (VTK order) and `extra` unused points.
fn one_hex(name: &str, points: &[[f64; 3]; 8], extra: usize) -> std::path::PathBuf {
    let mut text = format!("MeshVersionFormatted 2\nDimension 3\nVertices\n{}\n", 8 + extra);
    for p in points {
        text += &format!("{} {} {} 0\n", p[0], p[1], p[2]);
    }
    for k in 0..extra {
        text += &format!("{} 5 5 0\n", 5 + k);
    }
    text += "Hexahedra\n1\n1 2 3 4 5 6 7 8 0\nEnd\n";
    let path = temp(name);
    std::fs::write(&path, text).unwrap();
    path
}

const UNIT: [[f64; 3]; 8] =
    [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]];

/// Item 3: a tangled hexahedron (positive volume, a negative corner) is reported by
/// `info` (text and JSON) and by `validate`, which fails on it with `--strict`.
#[test]
fn tangled_cells_are_reported_and_strict_validation_fails() {
    let mut p = UNIT;
    p[6] = [0.2, 0.2, 0.2];
    let tangled = one_hex("fh-tangled.mesh", &p, 0);
    let j = json_of(&["info", s(&tangled), "--json"]);
    assert_eq!((j["tangled_cells"].as_u64(), j["inverted_cells"].as_u64()), (Some(1), Some(0)));
    let (code, out, _) = qmesh(&["info", s(&tangled)]);
    assert_eq!(code, 0);
    assert!(out.contains("tangled cells 1"), "{out}");
    let (code, out, err) = qmesh(&["validate", s(&tangled)]);
    assert_eq!(code, 0, "combinatorially valid: a warning only");
    assert!(err.contains("warning: 1 cells tangled"), "{err}");
    assert!(out.contains("geometrically defective"), "{out}");
    let (code, _, err) = qmesh(&["validate", s(&tangled), "--strict"]);
    assert_eq!(code, 1, "{err}");
    let fine = one_hex("fh-fine.mesh", &UNIT, 0);
    assert_eq!(qmesh(&["validate", s(&fine), "--strict"]).0, 0);
    assert_eq!(json_of(&["info", s(&fine), "--json"])["tangled_cells"], 0);
}

/// Item 4: `tet2hex` refuses a mesh without tetrahedra instead of rewriting its cells.
#[test]
fn tet2hex_refuses_a_mesh_without_tetrahedra() {
    let hex = one_hex("fh-hex.mesh", &UNIT, 0);
    let out = temp("fh-hex-out.vtk");
    let _ = std::fs::remove_file(&out);
    let (code, _, err) = qmesh(&["tet2hex", s(&hex), "-o", s(&out)]);
    assert_eq!(code, 2);
    assert!(err.contains("no tetrahedra"), "{err}");
    assert!(!out.exists(), "nothing is written");
}

/// Item 5: `convert` keeps the points no cell uses (or says it leaves them out) and
/// reports what it wrote.
#[test]
fn convert_keeps_unreferenced_points_and_reports_what_it_wrote() {
    let hex = one_hex("fh-unused.mesh", &UNIT, 2);
    let out = temp("fh-unused-out.vtk");
    let (code, stdout, err) = qmesh(&["convert", s(&hex), s(&out)]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("10 points, 1 cells") && stdout.contains("kept"), "{stdout}");
    assert_eq!(json_of(&["info", s(&out), "--json"])["unreferenced_points"], 2);
    let (code, stdout, _) = qmesh(&["convert", s(&hex), s(&out), "--drop-unused"]);
    assert_eq!(code, 0);
    assert!(stdout.contains("8 points, 1 cells") && stdout.contains("left out"), "{stdout}");
    let off = temp("fh-unused-out.off");
    let (code, stdout, _) = qmesh(&["convert", s(&hex), s(&off)]);
    assert_eq!(code, 0);
    assert!(stdout.contains("8 points, 6 polygons: the boundary surface of 1 cells"), "{stdout}");
}

/// Item 9: messages say what is wrong in words: a missing patterns folder, a folder
/// given as a mesh, a missing output folder, three cells on one face, a gmsh element
/// with too few nodes; `-q` silences the summary (the demo's χ: `demo_runs_…`).
#[test]
fn messages_name_the_problem() {
    let hex = one_hex("fh-msg.mesh", &UNIT, 0);
    let out = temp("fh-msg-out.vtk");
    let (code, _, err) = qmesh(&["replace", "--patterns", "/nonexistent-patterns", s(&hex), s(&out)]);
    assert_eq!(code, 2);
    assert!(err.contains("/nonexistent-patterns: no such pattern folder"), "{err}");
    let dir = temp("fh-msg-dir");
    std::fs::create_dir_all(&dir).unwrap();
    let (code, _, err) = qmesh(&["info", s(&dir)]);
    assert_eq!(code, 2);
    assert!(err.contains("this is a folder, not a mesh file"), "{err}");
    let (code, _, err) = qmesh(&["convert", s(&hex), "/nonexistent-folder/x.vtk"]);
    assert_eq!(code, 2);
    assert!(err.contains("the folder /nonexistent-folder does not exist"), "{err}");
    let three = temp("fh-three.mesh");
    std::fs::write(
        &three,
        "MeshVersionFormatted 2\nDimension 3\nVertices\n6\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 -1 0\n1 1 1 0\n\
         Tetrahedra\n3\n1 2 3 4 0\n1 3 2 5 0\n1 2 3 6 0\nEnd\n",
    )
    .unwrap();
    let (code, _, err) = qmesh(&["info", s(&three)]);
    assert_eq!(code, 2);
    assert!(err.contains("three cells on one face") && !err.contains("fix-orientation"), "{err}");
    let short = temp("fh-short.msh");
    std::fs::write(
        &short,
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n\
         $Elements\n2\n1 4 2 0 1 1 2 3\n2 4 2 0 1 1 2 3 4\n$EndElements\n",
    )
    .unwrap();
    let (code, _, err) = qmesh(&["info", s(&short)]);
    assert_eq!(code, 2);
    assert!(err.contains("line 13") && err.contains("tetrahedron) needs 4 nodes, this one has 3"), "{err}");
    let tets = temp("fh-msg-tets.vtk");
    let (code, stdout, err) = qmesh(&["tetrahedralize", s(&hex), "-o", s(&tets), "-q"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(stdout, "", "-q prints no summary");
}

/// Item 7: the authors' own marching-cubes set runs as published (CGAL `.mesh` files and
/// their Moka copies, no inside flags: the cube-corner rule is detected) and gives a
/// closed surface.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn the_authors_marching_cubes_patterns_give_a_closed_surface() {
    let data = std::env::var_os("QMESH_DATA")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"));
    let out = temp("fh-mc-authors.off");
    let bunny = data.join("surface/bunny.off");
    let patterns = data.join("patterns/cgal/marching-cubes");
    let (code, stdout, err) =
        qmesh(&["marching-cubes", s(&bunny), "--levels", "5", "-o", s(&out), "--patterns", s(&patterns), "--json"]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!((j["unmatched_faces"].as_u64(), j["unmatched_volumes"].as_u64()), (Some(0), Some(0)));
    assert_eq!((j["open_edges"].as_u64(), j["euler_characteristic"].as_i64()), (Some(0), Some(2)));
    assert_eq!(j["flags"], "corners");
}

/// Item 6: VTU size headers are checked, and vtkio's errors are told in words at the
/// line they are about.
#[test]
fn vtu_size_headers_are_checked_and_errors_are_readable() {
    let grid = temp("fh-vtu-grid.vtk");
    assert_eq!(qmesh(&["generate", "grid", "--size", "1", "-o", s(&grid)]).0, 0);
    let piece = |points: &str| {
        format!(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n\
             <UnstructuredGrid>\n<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n<Points>\n{points}\n</Points>\n<Cells>\n\
             <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>\n\
             <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4</DataArray>\n\
             <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray>\n</Cells>\n</Piece>\n\
             </UnstructuredGrid>\n</VTKFile>\n"
        )
    };
    let short = temp("fh-short.vtu");
    std::fs::write(
        &short,
        piece(
            "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0</DataArray>",
        ),
    )
    .unwrap();
    let (code, _, err) = qmesh(&["info", s(&short)]);
    assert_eq!(code, 2);
    assert!(err.contains("line 5") && err.contains("point coordinates hold 11 values, 12 expected"), "{err}");
    assert!(!err.contains("DataArraySizeMismatch") && !err.contains('{'), "no Rust debug text: {err}");
    // 96 bytes of coordinates behind a header that claims 8 (base64 of 8u32, then of 96 zero bytes).
    let header = "CAAAAA==";
    let zeros = "A".repeat(128);
    let lying = temp("fh-lying.vtu");
    std::fs::write(
        &lying,
        piece(&format!(
            "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"binary\">{header}{zeros}</DataArray>"
        )),
    )
    .unwrap();
    let (code, _, err) = qmesh(&["info", s(&lying)]);
    assert_eq!(code, 2);
    assert!(err.contains("line 6") && err.contains("says 8 bytes, but it holds 96"), "{err}");
}

/// The box of non-white pixels of a PNG below `top`: (x0, y0, x1, y1).
fn ink_box(path: &std::path::Path, top: u32) -> (u32, u32, u32, u32) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let mut b = (u32::MAX, u32::MAX, 0, 0);
    for (i, p) in buf[..info.buffer_size()].chunks(3).enumerate() {
        let (x, y) = (i as u32 % info.width, i as u32 / info.width);
        if y >= top && p != [255, 255, 255] {
            b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
        }
    }
    b
}

/// Item 11: pictures have a title line, the mesh fills most of the frame, and a
/// quality legend on an all-equal mesh says so instead of listing unused colours.
#[test]
fn pictures_have_a_title_fill_the_frame_and_a_useful_legend() {
    let grid = temp("fh-render.vtk");
    assert_eq!(qmesh(&["generate", "grid", "--size", "8,2,1", "-o", s(&grid)]).0, 0);
    let png = temp("fh-render.png");
    let j = json_of(&["render", s(&grid), "-o", s(&png), "--color-by", "quality", "--size", "400,300", "--json"]);
    assert_eq!(j["title"], "fh-render.vtk - 16 cells - coloured by scaled Jacobian");
    assert_eq!(j["legend"], serde_json::json!(["scaled jacobian: all 1.00"]));
    // Below the legend band, a long slab spans most of the width.
    let (x0, _, x1, _) = ink_box(&png, 120);
    assert!(x1 - x0 > 300, "the mesh spans {} of 400 pixels", x1 - x0);
    let j = json_of(&["render", s(&grid), "-o", s(&png), "--json"]);
    assert_eq!(j["legend"], serde_json::json!(["hex 16"]));
}
