//! Indexed cells → map → indexed cells: every standard kind is recognised with its VTK
//! node order (positive volume), other volumes become polyhedra, inverted cells are
//! counted and flipped on request, and the map costs 24 bytes per dart.

mod common;

use qmesh::build::{BuildOptions, CellKind, IndexedMesh, build_volume_map, extract};
use qmesh::cmap::CMap3;
use qmesh::geom::signed_volume_of_table;

/// One cell of each kind in VTK order, side by side, plus an octagonal prism polyhedron.
fn zoo() -> IndexedMesh {
    let mut m = IndexedMesh::new();
    let add = |m: &mut IndexedMesh, kind: CellKind, pts: &[[f64; 3]], x: f64| {
        let base = m.points.len() as u32;
        m.points.extend(pts.iter().map(|p| [p[0] + x, p[1], p[2]]));
        let nodes: Vec<u32> = (0..pts.len() as u32).map(|k| base + k).collect();
        m.push_cell(kind, &nodes, None);
    };
    add(&mut m, CellKind::Tet, &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], 0.0);
    add(&mut m, CellKind::Pyramid, &[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0.5, 0.5, 1.]], 2.0);
    add(
        &mut m,
        CellKind::Prism,
        &[[0., 0., 0.], [0., 1., 0.], [1., 0., 0.], [0., 0., 1.], [0., 1., 1.], [1., 0., 1.]],
        4.0,
    );
    add(&mut m, CellKind::Hex, &common::UNIT_CUBE, 6.0);
    // An octagonal prism as a VTK polyhedron (outward faces).
    let base = m.points.len() as u32;
    for z in [0.0, 1.0] {
        for k in 0..8 {
            let a = k as f64 * std::f64::consts::TAU / 8.0;
            m.points.push([10.0 + a.cos(), a.sin(), z]);
        }
    }
    let mut stream = vec![10u32, 8];
    stream.extend((0..8).rev().map(|k| base + k));
    stream.push(8);
    stream.extend((0..8).map(|k| base + 8 + k));
    for k in 0..8 {
        stream.extend([4, base + k, base + (k + 1) % 8, base + 8 + (k + 1) % 8, base + 8 + k]);
    }
    m.push_cell(CellKind::Polyhedron, &stream, None);
    m
}

#[test]
fn every_kind_is_recognised_with_positive_vtk_order() {
    let mesh = zoo();
    let (map, report) = build_volume_map(&mesh, &BuildOptions::default()).unwrap();
    assert!(map.is_valid().is_empty());
    assert_eq!(report.inverted_cells, 0);
    let (back, kinds) = extract(&map);
    assert_eq!((kinds.tet, kinds.pyramid, kinds.prism, kinds.hex, kinds.other), (1, 1, 1, 1, 1));
    for i in 0..back.nb_cells() {
        let (k, nodes) = back.cell(i);
        if k != CellKind::Polyhedron {
            let v = signed_volume_of_table(k.face_table(), nodes, &back.points);
            assert!(v > 0.0, "{k:?} extracted with volume {v}");
        }
    }
    let (again, _) = build_volume_map(&back, &BuildOptions::default()).unwrap();
    assert_eq!(again.count_cells(), map.count_cells());
}

#[test]
fn inverted_cells_are_counted_and_flipped_on_request() {
    let mut mesh = zoo();
    // Mirror every cell by swapping two nodes of the tet and top/bottom of the hex.
    let (_, tet) = mesh.cell(0);
    let t = [tet[0], tet[2], tet[1], tet[3]];
    mesh.conn[0..4].copy_from_slice(&t);
    let h0 = mesh.offsets[3];
    let hex: Vec<u32> = mesh.conn[h0..h0 + 8].to_vec();
    mesh.conn[h0..h0 + 8].copy_from_slice(&[hex[4], hex[5], hex[6], hex[7], hex[0], hex[1], hex[2], hex[3]]);
    let (_, r) = build_volume_map(&mesh, &BuildOptions::default()).unwrap();
    assert_eq!((r.inverted_cells, r.flipped_cells), (2, 0));
    let (map, r) = build_volume_map(&mesh, &BuildOptions { fix_orientation: true }).unwrap();
    assert_eq!((r.inverted_cells, r.flipped_cells), (2, 2));
    let (back, _) = extract(&map);
    let (again, r) = build_volume_map(&back, &BuildOptions::default()).unwrap();
    assert_eq!(r.inverted_cells, 0);
    assert!(again.is_valid().is_empty());
}

#[test]
fn the_map_costs_20_bytes_per_dart_plus_positions_and_24_with_marks() {
    let (mut map, _) = build_volume_map(&qmesh::generate::hex_grid(10, 10, 10), &BuildOptions::default()).unwrap();
    assert_eq!(map.nb_darts(), 24_000);
    // Capacity is exact after building: one slot for ε, 20 B per dart, 24 B per position.
    assert_eq!(map.bytes_per_dart(), 20);
    assert_eq!(map.heap_bytes(), (map.nb_darts() + 1) * 20 + map.nb_vertex_ids() * 24);
    // The first mark allocates the 4-byte mark word of every dart.
    let m = map.reserve_mark().unwrap();
    assert_eq!(map.bytes_per_dart(), CMap3::BYTES_PER_DART);
    assert_eq!(map.heap_bytes(), (map.nb_darts() + 1) * 24 + map.nb_vertex_ids() * 24);
    map.free_mark(m);
}

#[test]
fn shared_faces_and_orientation_errors_name_the_cells() {
    let mut mesh = zoo();
    let (_, hex) = mesh.cell(3);
    let hex = hex.to_vec();
    mesh.push_cell(CellKind::Hex, &hex, None); // a duplicate of cell 3
    let e = build_volume_map(&mesh, &BuildOptions::default()).unwrap_err().to_string();
    assert!(e.contains("cells 3 and 5") && e.contains("inconsistent orientation"), "{e}");
}

#[test]
fn a_polyhedron_with_more_faces_than_points_reads_back() {
    // The legacy VTK cell list of a polyhedron holds face counts and sizes beside point
    // indices: a tetrahedron written as one (4 faces, 4 points) must not be read as
    // "point index 4 out of range".
    let dir = common::temp_dir("poly-tet");
    let path = dir.join("tet.vtk");
    let text = "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n\
        0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 18\n17 4 3 0 2 1 3 0 1 3 3 1 2 3 3 0 3 2\nCELL_TYPES 1\n42\n";
    std::fs::write(&path, text).unwrap();
    let qmesh::io::Loaded::Indexed(mesh) = qmesh::io::read(&path, None).unwrap() else {
        panic!("a cell file reads as cells")
    };
    assert_eq!((mesh.nb_cells(), mesh.kinds[0]), (1, CellKind::Polyhedron));
    let (m, _) = build_volume_map(&mesh, &BuildOptions::default()).unwrap();
    assert_eq!((m.count_cells().volumes, m.nb_darts()), (1, 12));
    // And a point index beyond the points is still refused, at the cell's line.
    std::fs::write(&path, text.replace("3 0 3 2\n", "3 0 3 7\n")).unwrap();
    let e = qmesh::io::read(&path, None).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("line 8") && e.contains("point index 7 is out of range"), "{e}");
}
