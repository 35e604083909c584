//! Every mesh in `../shared/data/{hex,tet,surface}` loads, is valid, and keeps its
//! counts through read → write → read in every writable format.

mod common;

use qmesh::build::{BuildOptions, count_cell_kinds};
use qmesh::cmap::CMap3;
use qmesh::io::{Format, Loaded, WriteOptions, load_map, read, write_indexed, write_map};

fn signature(m: &CMap3) -> (usize, usize, usize, usize, usize, i64, [usize; 5]) {
    let c = m.count_cells();
    assert_eq!(c, m.census_reference().counts, "the parallel census agrees with the census by definition");
    let k = count_cell_kinds(m);
    (
        c.darts,
        c.vertices,
        c.edges,
        c.faces,
        c.volumes,
        c.euler_characteristic(m.dimension()),
        [k.tet, k.pyramid, k.prism, k.hex, k.other],
    )
}

fn roundtrip_all(sub: &str, volume_formats: bool) {
    let files = common::data_files(sub);
    let out = common::temp_dir(&format!("rt-{sub}"));
    let mut checked = 0;
    for f in &files {
        let loaded = match load_map(f, None, &BuildOptions::default()) {
            Ok(l) => l,
            Err(e) => {
                // Surfaces with non-manifold edges cannot become maps: round-trip the
                // indexed polygons instead, and check the error names the file.
                assert!(!volume_formats, "{}: {e}", f.display());
                assert!(e.to_string().contains(&*f.file_name().unwrap().to_string_lossy()), "{e}");
                let Loaded::Indexed(mesh) = read(f, None).unwrap() else { panic!() };
                let p = out.join("indexed.off");
                write_indexed(&p, &mesh, Format::Off, &WriteOptions::default()).unwrap();
                let Loaded::Indexed(back) = read(&p, None).unwrap() else { panic!() };
                assert_eq!((back.points.len(), back.nb_polygons()), (mesh.points.len(), mesh.nb_polygons()));
                continue;
            }
        };
        let v = loaded.map.is_valid();
        assert!(v.is_empty(), "{}: {} violations, first: {}", f.display(), v.len(), v[0]);
        let expect = signature(&loaded.map);
        let formats: &[(&str, bool)] = if volume_formats {
            &[("vtk", false), ("vtk", true), ("vtu", false), ("mesh", false), ("msh", false), ("moka", false)]
        } else {
            &[("off", false), ("obj", false), ("vtk", false), ("vtk", true), ("vtu", false), ("moka", false)]
        };
        for &(ext, binary) in formats {
            let p = out.join(format!("rt.{ext}"));
            write_map(&p, &loaded.map, None, &WriteOptions { binary })
                .unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            let mut back = load_map(&p, None, &BuildOptions::default())
                .unwrap_or_else(|e| panic!("{} via {ext}: {e}", f.display()));
            if ext == "moka" {
                // A closed surface and a closed volume are the same g-map: .moka cannot
                // tell them apart, so the caller restores the dimension.
                back.map.set_dimension(loaded.map.dimension());
            }
            assert!(back.map.is_valid().is_empty(), "{} via {ext}", f.display());
            assert_eq!(signature(&back.map), expect, "{} via {ext} (binary {binary})", f.display());
        }
        checked += 1;
    }
    eprintln!("{sub}: {checked} of {} files round-tripped", files.len());
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn hex_files_roundtrip() {
    roundtrip_all("hex", true);
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn tet_files_roundtrip() {
    roundtrip_all("tet", true);
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn surface_files_roundtrip() {
    roundtrip_all("surface", false);
}

/// 2025 Table 1 column #d: 24 darts per hexahedron.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn paper_hex_meshes_have_expected_counts() {
    let Some(d) = common::data_dir() else { return };
    for (file, vols, darts, verts, chi) in [
        ("armadillo_out.mesh", 29_935, 718_440, Some(34_726), Some(1)),
        ("dragon_out.mesh", 14_009, 336_216, None, None),
        ("rockerarm.mesh", 10_600, 254_400, None, None),
    ] {
        let l = load_map(&d.join("hex").join(file), None, &BuildOptions::default()).unwrap();
        let c = l.map.count_cells();
        assert_eq!((c.volumes, c.darts), (vols, darts), "{file}");
        if let Some(v) = verts {
            assert_eq!(c.vertices, v, "{file}");
        }
        if let Some(x) = chi {
            assert_eq!(c.euler_characteristic(3), x, "{file}");
        }
        assert!(l.map.is_valid().is_empty());
        assert_eq!(l.report.inverted_cells, 0, "{file}");
        // 24 bytes per dart plus positions.
        assert_eq!(CMap3::BYTES_PER_DART, 24);
    }
}

/// HexaLab files declaring VTK type 10 with 8 indices are read as hexahedra.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn type10_with_eight_indices_reads_as_hex() {
    let Some(d) = common::data_dir() else { return };
    let l = load_map(&d.join("hex/hex_cube_coarse.vtk"), None, &BuildOptions::default()).unwrap();
    assert!(l.warnings.iter().any(|w| w.contains("read as hexahedra")), "{:?}", l.warnings);
    assert_eq!(count_cell_kinds(&l.map).hex, 68);
}

/// The same mesh in four formats gives the same map.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn formats_agree_on_gmsh_sphere() {
    let Some(d) = common::data_dir() else { return };
    let sigs: Vec<_> =
        ["gmsh_sphere_tet.mesh", "gmsh_sphere_tet.msh", "gmsh_sphere_tet.vtk", "gmsh_sphere_tet_v22.msh"]
            .iter()
            .map(|f| signature(&load_map(&d.join("tet").join(f), None, &BuildOptions::default()).unwrap().map))
            .collect();
    assert!(sigs.windows(2).all(|w| w[0] == w[1]), "{sigs:?}");
}
