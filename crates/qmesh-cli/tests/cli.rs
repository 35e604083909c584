//! The `qmesh` binary as users call it: exit statuses, JSON keys, messages.

use std::path::PathBuf;
use std::process::Command;

use qmesh::cmap::CMap3;
use qmesh::io::{WriteOptions, write_map};

mod compiled_sets;
mod examples;
mod first_hour;

fn qmesh(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qmesh")).args(args).output().expect("run qmesh");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("qmesh-cli-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

#[test]
fn info_json_has_the_documented_keys() {
    let grid = temp("g.vtk");
    let (code, _, err) = qmesh(&["generate", "grid", "--size", "3,2,1", "-o", grid.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (code, out, err) = qmesh(&["info", grid.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in [
        "darts",
        "vertices",
        "edges",
        "faces",
        "volumes",
        "boundary_faces",
        "euler_characteristic",
        "components",
        "cell_types",
        "inverted_cells",
        "valid",
        "read_seconds",
        "build_seconds",
        "peak_memory_bytes",
    ] {
        assert!(j.get(k).is_some(), "missing key {k}");
    }
    assert_eq!(j["darts"], 6 * 24);
    assert_eq!(j["volumes"], 6);
    assert_eq!(j["cell_types"]["hex"], 6);
    assert_eq!(j["euler_characteristic"], 1);
    assert_eq!(j["valid"], true);
    assert!(j["peak_memory_bytes"].as_u64().unwrap() > 0);
    let v = json_of(&["validate", grid.to_str().unwrap(), "--json"]);
    assert_eq!((v["valid"].as_bool(), v["geometrically_valid"].as_bool()), (Some(true), Some(true)), "{v}");
    assert_eq!((v["darts"].as_u64(), v["violations"].as_u64()), (Some(6 * 24), Some(0)));
}

#[test]
fn surface_info_reports_boundary_edges() {
    let off = temp("open.off");
    std::fs::write(&off, "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n").unwrap();
    let (code, out, _) = qmesh(&["info", off.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["boundary_edges"], 4);
    assert_eq!(j["euler_characteristic"], 1);
}

#[test]
fn validate_exits_1_with_violations_on_an_invalid_map() {
    // A map with a dangling β3 (written as .moka, which stores maps as they are).
    let mut m = CMap3::new();
    let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, 0.5 * i as f64])).collect();
    let a = m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    let b = m.next(m.next(a));
    m.link(a, 3, b); // the rest of the face stays 3-free: β1∘β3 is not an involution
    let bad = temp("bad.moka");
    write_map(&bad, &m, None, &WriteOptions::default()).unwrap();
    let (code, out, _) = qmesh(&["validate", bad.to_str().unwrap()]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("INVALID") && out.contains("β1∘β3"), "{out}");
    let good = temp("good.vtk");
    qmesh(&["generate", "tet-grid", "--size", "2", "-o", good.to_str().unwrap()]);
    let (code, out, _) = qmesh(&["validate", good.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
}

#[test]
fn convert_refuses_to_overwrite_its_input_and_reports_errors() {
    let grid = temp("c.mesh");
    qmesh(&["generate", "grid", "--size", "2", "-o", grid.to_str().unwrap()]);
    let before = std::fs::read(&grid).unwrap();
    let (code, _, err) = qmesh(&["convert", grid.to_str().unwrap(), grid.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("refusing to overwrite"), "{err}");
    assert_eq!(std::fs::read(&grid).unwrap(), before);
    let out = temp("c.msh");
    let (code, said, err) = qmesh(&["convert", grid.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(said.starts_with("wrote "), "{said}");
    // -q as with every other command: the file, and nothing on stdout.
    let quiet = temp("c_quiet.msh");
    let (code, said, err) = qmesh(&["convert", "-q", grid.to_str().unwrap(), quiet.to_str().unwrap()]);
    assert_eq!((code, said.as_str()), (0, ""), "{err}");
    assert_eq!(std::fs::read(&quiet).unwrap(), std::fs::read(&out).unwrap());
    // --json as with the other commands: what was written, and the same file.
    let json = temp("c_json.msh");
    let j = json_of(&["convert", grid.to_str().unwrap(), json.to_str().unwrap(), "--json"]);
    assert_eq!((j["format"].as_str(), j["points"].as_u64(), j["cells"].as_u64()), (Some("msh"), Some(27), Some(8)));
    assert_eq!(std::fs::read(&json).unwrap(), std::fs::read(&out).unwrap());
    let j = json_of(&["convert", grid.to_str().unwrap(), temp("c_json.off").to_str().unwrap(), "--json"]);
    assert_eq!((j["polygons"].as_u64(), j["boundary_of_volumes"].as_u64()), (Some(24), Some(8)));
    // -o OUT, as with every other command; one output only.
    let flagged = temp("c_flag.msh");
    let (code, _, err) = qmesh(&["convert", grid.to_str().unwrap(), "-o", flagged.to_str().unwrap(), "-q"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read(&flagged).unwrap(), std::fs::read(&out).unwrap());
    let (code, _, err) =
        qmesh(&["convert", grid.to_str().unwrap(), out.to_str().unwrap(), "-o", flagged.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = qmesh(&["convert", grid.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("OUTPUT"), "{err}");
    let (code, _, err) = qmesh(&["info", "/nonexistent/x.vtk"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: /nonexistent/x.vtk"), "{err}");
    let broken = temp("broken.mesh");
    std::fs::write(&broken, "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n").unwrap();
    let (code, _, err) = qmesh(&["info", broken.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("broken.mesh:line 4"), "{err}");
    // No temporary file is left next to a failed output.
    let leftovers = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().contains("qmesh-tmp"));
    assert_eq!(leftovers.count(), 0);
}

#[test]
fn demo_runs_and_writes_its_files() {
    let dir = temp("demo");
    let (code, out, err) = qmesh(&["demo", "-o", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("valid true") && !out.contains("valid false"), "{out}");
    assert!(out.contains("χ 0,"), "the torus's marching-cubes surface has genus 1: {out}");
    assert!(!out.contains("Some("), "no Rust debug text: {out}");
    for f in [
        "torus.off",
        "torus_octree.vtk",
        "torus_conformal.vtk",
        "torus_marching_cubes.off",
        "gyroid.off",
        "hex_grid_subdivided.vtk",
        "tet_grid_to_hex.vtk",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
        let (w, h, ink) = png_stats(&dir.join(f).with_extension("png"));
        assert!(w == 1200 && h == 900 && ink > 10_000, "{f}: a picture with something on it");
        let (code, _, err) = qmesh(&["validate", dir.join(f).to_str().unwrap()]);
        assert_eq!(code, 0, "{f}: {err}");
    }
    let info = json_of(&["info", dir.join("torus_conformal.vtk").to_str().unwrap(), "--json"]);
    assert_eq!(info["non_conformal_faces"], 0);
}

#[test]
fn generated_patterns_are_written_and_usable() {
    let dir = temp("gen");
    let (code, out, err) = qmesh(&["patterns", "generate", "tet2hex", "-o", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("1 f-patterns, 1 v-patterns, 0 duplicates"), "{out}");
    let tets = temp("t.vtk");
    qmesh(&["generate", "tet-grid", "--size", "2", "-o", tets.to_str().unwrap()]);
    let hexes = temp("h.vtk");
    let (code, out, err) = qmesh(&[
        "replace",
        tets.to_str().unwrap(),
        hexes.to_str().unwrap(),
        "--split-edges",
        "2",
        "--patterns",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["volumes"], 4 * 48);
    assert_eq!(j["cell_types"]["hex"], 4 * 48);
    assert_eq!(j["valid"], true);
    assert_eq!(j["unmatched_volumes"], 0);
}

#[test]
fn quality_reports_scaled_jacobians() {
    let grid = temp("q.vtk");
    qmesh(&["generate", "grid", "--size", "3", "-o", grid.to_str().unwrap()]);
    let (code, out, err) = qmesh(&["quality", grid.to_str().unwrap(), "--json", "--per-cell"]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let hex = &j["scaled_jacobian"]["hex"];
    assert_eq!(hex["count"], 27);
    assert!((hex["min"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    assert_eq!(hex["histogram"][9], 27);
    assert_eq!(j["per_cell"].as_array().unwrap().len(), 27);
    let tets = temp("qt.vtk");
    qmesh(&["generate", "tet-grid", "--size", "1", "-o", tets.to_str().unwrap()]);
    let (_, out, _) = qmesh(&["quality", tets.to_str().unwrap(), "--json"]);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    // The 6 Kuhn tetrahedra of a cube are congruent: J = 1, and the largest product of
    // edge lengths at a node is 1·√2·√3, so the scaled Jacobian is √2/√6 = 1/√3.
    let tet = &j["scaled_jacobian"]["tet"];
    assert_eq!(tet["count"], 6);
    let expected = 1.0 / 3f64.sqrt();
    assert!((tet["min"].as_f64().unwrap() - expected).abs() < 1e-12, "{tet}");
    assert!((tet["max"].as_f64().unwrap() - expected).abs() < 1e-12, "{tet}");
}

fn json_of(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = qmesh(args);
    assert_eq!(code, 0, "{args:?}: {err}{out}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}: {out}"))
}

/// `subdivide --conformal` runs the transitions on the subdivision's own map: the same
/// cells as `conformal` on the written octree, conformal and valid.
#[test]
fn subdivide_conformal_equals_subdivide_then_conformal() {
    let (tets, box_off, octree) = (temp("sc-t.vtk"), temp("sc-box.off"), temp("sc-oct.vtk"));
    let (fused, apart) = (temp("sc-fused.vtk"), temp("sc-apart.vtk"));
    let s = |p: &PathBuf| p.to_str().unwrap().to_string();
    assert_eq!(qmesh(&["generate", "tet-grid", "--size", "2,2,2", "-o", &s(&tets)]).0, 0);
    assert_eq!(qmesh(&["convert", &s(&tets), &s(&box_off)]).0, 0);
    let base = ["subdivide", &s(&box_off), "--levels", "3", "--json"];
    json_of(&[&base[..], &["-o", &s(&octree)]].concat());
    let c = json_of(&["conformal", &s(&octree), "-o", &s(&apart), "--json"]);
    let f = json_of(&[&base[..], &["-o", &s(&fused), "--conformal"]].concat());
    let t = &f["transitions"];
    assert_eq!(t["cell_types"], c["cell_types"]);
    assert!(c["cell_types"]["pyramid"].as_u64().unwrap() > 0, "{c}");
    assert_eq!(
        (t["volumes_replaced"].clone(), t["faces_replaced"].clone()),
        (c["volumes_replaced"].clone(), c["faces_replaced"].clone())
    );
    assert_eq!(
        (t["non_conformal_faces"].as_u64(), t["unmatched_volumes"].as_u64(), f["valid"].as_bool()),
        (Some(0), Some(0), Some(true))
    );
    let info = json_of(&["info", &s(&fused), "--json"]);
    assert_eq!((info["non_conformal_faces"].as_u64(), info["inverted_cells"].as_u64()), (Some(0), Some(0)));
    assert_eq!(info["cell_types"], c["cell_types"]);
    // The transition folders only go with --conformal, and no transitions on plain boxes.
    let (code, _, err) = qmesh(&[&base[..], &["-o", &s(&fused), "--force", "--transition-patterns", "x"]].concat());
    assert!(code != 0 && err.contains("--conformal"), "{err}");
    let (code, _, err) = qmesh(&[&base[..], &["-o", &s(&fused), "--force", "--conformal", "--direct"]].concat());
    assert!(code != 0 && err.contains("--direct"), "{err}");
}

/// The shared data folder ($QMESH_DATA, default ../shared/data).
fn data_dir() -> PathBuf {
    std::env::var_os("QMESH_DATA")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"))
}

/// With the authors' set-up and patterns, `marching-cubes` replaces the cells the
/// authors' program replaces (`cgal_hexa_subdivision -lmax 5 -init 1 -marching-cubes`,
/// bunny: 8,136 faces and 4,062 volumes).
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn marching_cubes_gives_the_authors_counts() {
    let data = data_dir();
    let s = |p: &PathBuf| p.to_str().unwrap().to_string();
    let (bunny, patterns) = (data.join("surface/bunny.off"), data.join("patterns/cgal/marching-cubes"));
    let out = temp("mc-bunny.off");
    let args = ["marching-cubes", &s(&bunny), "--root", "box", "--levels", "5", "--patterns", &s(&patterns)];
    let j = json_of(&[&args[..], &["-o", &s(&out), "--json"]].concat());
    let counts = [&j["faces_replaced"], &j["volumes_replaced"], &j["open_edges"], &j["unmatched_volumes"]];
    assert_eq!(counts.map(|v| v.as_u64().unwrap()), [8_136, 4_062, 0, 0], "{j}");
    assert_eq!((j["root"].as_str(), j["init"].as_u64()), (Some("box"), Some(1)));
}

/// With the authors' set-up and patterns, `subdivide --conformal` gives the authors'
/// program's figures (`cgal_hexa_subdivision -lmax 6 -create-transitions`, bunny).
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn subdivide_conformal_gives_the_authors_counts() {
    let data = data_dir();
    let s = |p: &PathBuf| p.to_str().unwrap().to_string();
    let patterns = format!(
        "{},{}",
        s(&data.join("patterns/cgal/hexa-325-patterns")),
        s(&data.join("patterns/cgal/square-5-patterns"))
    );
    let out = temp("sc-bunny.vtk");
    let bunny = data.join("surface/bunny.off");
    let j = json_of(&[
        "subdivide",
        &s(&bunny),
        "--root",
        "box",
        "--levels",
        "6",
        "--remove-outside",
        "--conformal",
        "--transition-patterns",
        &patterns,
        "-o",
        &s(&out),
        "--json",
    ]);
    let t = &j["transitions"];
    let k = &t["cell_types"];
    let counts = [&k["hex"], &k["prism"], &k["pyramid"], &k["tet"], &k["other"], &t["volumes_replaced"], &j["darts"]];
    assert_eq!(counts.map(|v| v.as_u64().unwrap()), [25_792, 1_498, 17_002, 12_845, 0, 2_718, 1_072_144], "{j}");
    assert_eq!((t["non_conformal_faces"].as_u64(), j["valid"].as_bool()), (Some(0), Some(true)));
}

#[test]
fn octree_pipeline_subdivide_conformal_info() {
    let (tets, box_off, octree, conf) = (temp("t.vtk"), temp("box.off"), temp("oct.vtk"), temp("conf.vtk"));
    let s = |p: &PathBuf| p.to_str().unwrap().to_string();
    let (code, _, err) = qmesh(&["generate", "tet-grid", "--size", "2,2,2", "-o", &s(&tets)]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = qmesh(&["convert", &s(&tets), &s(&box_off)]);
    assert_eq!(code, 0, "{err}");
    let sub = json_of(&["subdivide", &s(&box_off), "--levels", "3", "-o", &s(&octree), "--json"]);
    assert_eq!(sub["valid"], true);
    assert!(sub["volumes"].as_u64().unwrap() > 8);
    let direct = json_of(&["subdivide", &s(&box_off), "--levels", "3", "-o", &s(&temp("d.vtk")), "--direct", "--json"]);
    assert_eq!(direct["volumes"], sub["volumes"]);
    let info = json_of(&["info", &s(&octree), "--json"]);
    assert!(info["non_conformal_faces"].as_u64().unwrap() > 0, "an octree has hanging vertices");
    let c = json_of(&["conformal", &s(&octree), "-o", &s(&conf), "--json"]);
    assert_eq!((c["unmatched_volumes"].as_u64(), c["valid"].as_bool()), (Some(0), Some(true)));
    assert_eq!(c["v_patterns"], 325);
    let info = json_of(&["info", &s(&conf), "--json"]);
    assert_eq!((info["non_conformal_faces"].as_u64(), info["inverted_cells"].as_u64()), (Some(0), Some(0)));
    // Each cell knows the pattern that made it (-1: a hexahedron left as it was).
    let Ok(qmesh::io::Loaded::Indexed(m)) = qmesh::io::read(&conf, None) else { panic!("conformal output") };
    let Some(qmesh::build::CellValues::Int(ids)) = m.cell_array("pattern_id") else { panic!("pattern_id array") };
    let untouched = ids.iter().filter(|&&i| i == -1).count() as u64;
    let replaced = c["volumes_replaced"].as_u64().unwrap();
    assert_eq!(untouched, sub["volumes"].as_u64().unwrap() - replaced);
    assert!(ids.iter().all(|i| (-1..330).contains(i)));
    // convert keeps the per-cell arrays, cell for cell.
    let converted = temp("conf.vtu");
    let (code, _, err) = qmesh(&["convert", &s(&conf), &s(&converted)]);
    assert_eq!(code, 0, "{err}");
    let Ok(qmesh::io::Loaded::Indexed(back)) = qmesh::io::read(&converted, None) else { panic!("converted") };
    assert_eq!(back.cell_array("pattern_id"), m.cell_array("pattern_id"));
    assert_eq!((back.kinds.clone(), back.conn.clone()), (m.kinds.clone(), m.conn.clone()));
    let t = json_of(&["tet2hex", &s(&tets), "-o", &s(&temp("h.vtk")), "--json"]);
    assert_eq!(t["cell_types"]["hex"], 4 * 48);
    // Each pipeline's phases account for its run (issue 16 item 3).
    let patterns = temp("tet2hex_patterns");
    let (code, _, err) = qmesh(&["patterns", "generate", "tet2hex", "-o", &s(&patterns)]);
    assert_eq!(code, 0, "{err}");
    let r = json_of(&[
        "replace",
        &s(&tets),
        &s(&temp("r.vtk")),
        "--patterns",
        &s(&patterns),
        "--split-edges",
        "2",
        "--json",
    ]);
    for (j, names) in [
        (&c, &["read", "hanging", "build", "select", "lookup", "apply", "count", "validate", "write"][..]),
        (&t, &["read", "split_edges", "lookup", "apply", "select", "validate", "extract", "write"][..]),
        (&r, &["read", "split_edges", "lookup", "apply", "select", "validate", "write"][..]),
    ] {
        let phases = j["phases"].as_object().unwrap_or_else(|| panic!("phases in {j}"));
        for n in names {
            assert!(phases[*n].as_f64().is_some_and(|x| x >= 0.0), "{n} in {phases:?}");
        }
        let sum: f64 = phases.iter().filter(|(k, _)| *k != "total").map(|(_, v)| v.as_f64().unwrap()).sum();
        assert!((sum - phases["total"].as_f64().unwrap()).abs() < 1e-9, "{phases:?}");
    }
    let inner = &c["phases"];
    let replace = inner["lookup"].as_f64().unwrap() + inner["apply"].as_f64().unwrap();
    assert!(replace <= c["seconds"].as_f64().unwrap() + 1e-9, "{inner}");
}

#[test]
fn marching_cubes_of_a_field_file() {
    let n = 12usize;
    let c = (n as f32 - 1.0) / 2.0;
    let mut bytes = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let d = ((i as f32 - c).powi(2) + (j as f32 - c).powi(2) + (k as f32 - c).powi(2)).sqrt() - 3.7;
                bytes.extend_from_slice(&d.to_le_bytes());
            }
        }
    }
    let field = temp("sphere.f32");
    std::fs::write(&field, bytes).unwrap();
    let out = temp("sphere.off");
    let args =
        ["marching-cubes", "--field", field.to_str().unwrap(), "--dims", "12,12,12", "-o", out.to_str().unwrap()];
    let j = json_of(&[&args[..], &["--triangulate", "--json"]].concat());
    assert_eq!((j["open_edges"].as_u64(), j["euler_characteristic"].as_i64()), (Some(0), Some(2)));
    assert_eq!((j["f_patterns"].as_u64(), j["v_patterns"].as_u64()), (Some(4), Some(21)));
    // A wrong size is refused with the file named.
    let (code, _, err) =
        qmesh(&["marching-cubes", "--field", field.to_str().unwrap(), "--dims", "5,5,5", "-o", out.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("sphere.f32") && err.contains("125 expected"), "{err}");
}

#[test]
fn marching_cubes_patterns_round_trip_through_moka() {
    let dir = temp("mc-patterns");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, out, err) = qmesh(&["patterns", "generate", "marching-cubes", "-o", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("4 f-patterns, 21 v-patterns, 0 duplicates, 0 skipped"), "{out}");
    let (code, _, err) =
        qmesh(&["patterns", "generate", "marching-cubes", "-o", dir.to_str().unwrap(), "--format", "vtk"]);
    assert_eq!(code, 2);
    assert!(err.contains("use --format moka"), "{err}");
    // A one-cube field with two inside corners on a face diagonal (an ambiguous face).
    let values: Vec<u8> = (0..8).flat_map(|i| if i == 0 || i == 6 { -1f32 } else { 1f32 }.to_le_bytes()).collect();
    let field = temp("diag.f32");
    std::fs::write(&field, values).unwrap();
    let out = temp("d.off");
    let run = |extra: &[&str]| {
        let args = [
            &[
                "marching-cubes",
                "--field",
                field.to_str().unwrap(),
                "--dims",
                "2,2,2",
                "-o",
                out.to_str().unwrap(),
                "--json",
            ][..],
            extra,
        ]
        .concat();
        json_of(&args)
    };
    let built_in = run(&[]);
    let from_files = run(&["--patterns", dir.to_str().unwrap()]);
    assert_eq!(built_in["polygons"], 2, "two corners cut off separately");
    assert_eq!(from_files["polygons"], built_in["polygons"]);
    assert_eq!(from_files["unmatched_volumes"], 0);
}

/// Width, height and the number of non-white pixels of a PNG.
fn png_stats(path: &std::path::Path) -> (u32, u32, usize) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let ink = buf[..info.buffer_size()].chunks(3).filter(|p| p != &[255, 255, 255]).count();
    (info.width, info.height, ink)
}

#[test]
fn render_draws_shrunk_clipped_cells() {
    let grid = temp("rg.vtk");
    let (code, _, err) = qmesh(&["generate", "grid", "--size", "6,6,6", "-o", grid.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let png = temp("rg.png");
    let all = json_of(&["render", grid.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "320,240", "--json"]);
    assert_eq!((all["cells"].as_u64(), all["cells_drawn"].as_u64()), (Some(216), Some(216)));
    let (w, h, ink) = png_stats(&png);
    assert_eq!((w, h), (320, 240));
    assert!(ink > 320 * 240 / 10, "the mesh covers part of the picture: {ink} pixels");
    let half = json_of(&[
        "render",
        grid.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--clip",
        "x<50%",
        "--view",
        "30,20",
        "--json",
    ]);
    assert_eq!(half["cells_drawn"], 108);
    // Repeated clips keep a box: 2 of 6 columns, 3 of 6 rows, 1 of 6 layers.
    let g = grid.to_str().unwrap();
    let p = png.to_str().unwrap();
    let b =
        json_of(&["render", g, "-o", p, "--clip", "x>3", "--clip", "x<5", "--clip", "y<3", "--clip", "z>5", "--json"]);
    assert_eq!(b["cells_drawn"], 6);
    let (code, _, err) = qmesh(&["render", grid.to_str().unwrap(), "-o", png.to_str().unwrap(), "--clip", "w<3"]);
    assert_eq!(code, 2);
    assert!(err.contains("axis 'w'"), "{err}");
    // A mesh in a file named .png (read with --format) is not drawn over without --force.
    let named_png = temp("rg_mesh.png");
    std::fs::copy(&grid, &named_png).unwrap();
    let mesh_bytes = std::fs::read(&named_png).unwrap();
    let n = named_png.to_str().unwrap();
    let (code, _, err) = qmesh(&["render", n, "--format", "vtk", "-o", n]);
    assert_eq!(code, 2);
    assert!(err.contains("refusing to overwrite it (use --force)"), "{err}");
    assert_eq!(std::fs::read(&named_png).unwrap(), mesh_bytes, "the input is left as it was");
    let (code, _, err) = qmesh(&["render", n, "--format", "vtk", "-o", n, "--size", "64,48", "--force"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(png_stats(&named_png).0, 64);
}

#[test]
fn query_and_modify_report_counts_and_refuse_bad_rules() {
    let (grid, pair, one) = (temp("qm_grid.vtk"), temp("qm_pair.vtk"), temp("qm_one.vtk"));
    for (f, size) in [(&grid, "5,3,2"), (&pair, "2,1,1"), (&one, "1")] {
        assert_eq!(qmesh(&["generate", "grid", "--size", size, "-o", f.to_str().unwrap()]).0, 0);
    }
    let matched = temp("qm_matches.vtk");
    let (code, out, err) =
        qmesh(&["query", pair.to_str().unwrap(), grid.to_str().unwrap(), "--json", "-o", matched.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    // Pairs along x, y and z: 4·3·2 + 5·2·2 + 5·3·1.
    assert_eq!(j["queries"][0]["matches"], 24 + 20 + 15);
    assert_eq!(j["queries"][0]["automorphisms"], 8);
    let text = std::fs::read_to_string(&matched).unwrap();
    assert!(text.contains("match_count") && text.contains("SCALARS match "), "no match arrays written");
    let rules = temp("qm_rules.toml");
    std::fs::write(&rules, "[[rule]]\nop = \"delete\"\nquery = \"qm_pair.vtk\"\ntarget = \"qm_one.vtk\"\n").unwrap();
    let out_mesh = temp("qm_out.vtk");
    let (code, out, err) = qmesh(&[
        "modify",
        grid.to_str().unwrap(),
        out_mesh.to_str().unwrap(),
        "--rules",
        rules.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["valid"], true);
    assert_eq!(j["rules"][0]["selected"], j["rules"][0]["modified"]);
    assert!(j["volumes"].as_u64().unwrap() < 30);
    // A bad key names the file and line; nothing is written, exit status 2.
    std::fs::write(&rules, "[[rule]]\nop = \"delete\"\nquery = \"qm_pair.vtk\"\ntarget = \"nope.vtk\"\n").unwrap();
    let _ = std::fs::remove_file(&out_mesh);
    let (code, _, err) =
        qmesh(&["modify", grid.to_str().unwrap(), out_mesh.to_str().unwrap(), "--rules", rules.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("qm_rules.toml:4: `target`"), "{err}");
    assert!(!out_mesh.exists());
    // The input is never overwritten without --force.
    let (code, _, err) =
        qmesh(&["modify", grid.to_str().unwrap(), grid.to_str().unwrap(), "--rules", rules.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("refusing to overwrite"), "{err}");
}

#[test]
fn tetrahedralize_then_recombine_gives_the_hexahedra_back() {
    let s = |p: &std::path::Path| p.to_str().unwrap().to_string();
    let (grid, tets, back) = (temp("rc_grid.mesh"), temp("rc_tets.mesh"), temp("rc_back.vtk"));
    let (code, _, err) = qmesh(&["generate", "grid", "--size", "3,2,2", "-o", &s(&grid)]);
    assert_eq!(code, 0, "{err}");
    let j = json_of(&["tetrahedralize", &s(&grid), "-o", &s(&tets), "--five", "--json"]);
    assert_eq!(j["report"]["tets"], 60);
    assert_eq!(j["report"]["bipartite"], true);
    let j = json_of(&["recombine", &s(&tets), "-o", &s(&back), "--json"]);
    assert_eq!(j["recombine"]["hexes"], 12);
    assert_eq!(j["recombine"]["tets_left"], 0);
    assert_eq!(j["cell_types"]["hex"], 12);
    assert_eq!(j["valid"], true);
    // The input is never overwritten without --force.
    let (code, _, err) = qmesh(&["recombine", &s(&tets), "-o", &s(&tets)]);
    assert_eq!(code, 2);
    assert!(err.contains("refusing to overwrite"), "{err}");
    let (code, _, err) = qmesh(&["tetrahedralize", &s(&tets), "-o", &s(&back)]);
    assert_eq!(code, 2);
    assert!(err.contains("no hexahedron"), "{err}");
}

/// `--threads` sets the workers of every command, before or after the command's name,
/// and gives the same result on 1 thread as on 3; 0 is refused in words.
#[test]
fn threads_are_set_for_any_command() {
    let s = |p: &std::path::Path| p.to_str().unwrap().to_string();
    let (grid, tets, one, three) = (temp("th_grid.mesh"), temp("th_tets.mesh"), temp("th_1.vtk"), temp("th_3.vtk"));
    let (code, _, err) = qmesh(&["generate", "grid", "--size", "3,2,2", "-o", &s(&grid)]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = qmesh(&["--threads", "2", "tetrahedralize", &s(&grid), "-o", &s(&tets), "--five"]);
    assert_eq!(code, 0, "{err}");
    for (threads, out) in [("1", &one), ("3", &three)] {
        let j = json_of(&["recombine", &s(&tets), "-o", &s(out), "--threads", threads, "--json"]);
        assert_eq!(j["threads"].to_string(), threads);
        assert_eq!(j["recombine"]["hexes"], 12);
    }
    assert_eq!(std::fs::read(&one).unwrap(), std::fs::read(&three).unwrap());
    let (code, _, err) = qmesh(&["subdivide", "--threads", "0", &s(&grid), "-o", &s(&one)]);
    assert_eq!(code, 2);
    assert!(err.contains("invalid value '0' for '--threads"), "{err}");
}
