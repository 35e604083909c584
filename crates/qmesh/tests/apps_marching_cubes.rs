//! Marching cubes by query-replace (2022 Algorithm 6): the generated set covers all 256
//! corner configurations; surfaces are closed, manifold, with the expected topology.

mod common;

use qmesh::apps::{marching_cubes_field, mc_face_patterns, mc_pattern_set, mc_volume_patterns, triangulate};
use qmesh::build::{IndexedMesh, build_surface_map};

/// Open and non-manifold edges and the Euler characteristic of a polygon surface.
fn topology(s: &IndexedMesh) -> (usize, i64) {
    let (map, _) = build_surface_map(s).expect("a manifold surface builds");
    assert!(map.is_valid().is_empty());
    let c = map.count_cells();
    (map.boundary_edges(), c.euler_characteristic(2))
}

fn field(n: usize, f: impl Fn(f64, f64, f64) -> f64) -> Vec<f32> {
    let mut v = Vec::with_capacity(n * n * n);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                v.push(f(i as f64, j as f64, k as f64) as f32);
            }
        }
    }
    v
}

#[test]
fn pattern_counts() {
    assert_eq!(mc_face_patterns().len(), 4);
    // 254 non-trivial corner sets fall into 21 classes under the 24 rotations.
    assert_eq!(mc_volume_patterns().len(), 21);
}

#[test]
fn every_corner_configuration_is_covered() {
    // One cube per configuration: 256 fields on a 2×2×2 grid.
    for config in 0..256u32 {
        let values: Vec<f32> = (0..8)
            .map(|idx| {
                let (i, j, k) = (idx >> 2 & 1, idx >> 1 & 1, idx & 1);
                let corner = i | j << 1 | k << 2;
                if config >> corner & 1 == 1 { -1.0 } else { 1.0 }
            })
            .collect();
        let (surface, r) = marching_cubes_field(&values, [2, 2, 2], 0.0, &mc_pattern_set()).expect("field");
        assert_eq!((r.unmatched_faces, r.unmatched_volumes), (0, 0), "configuration {config:08b}");
        let expect_surface = config != 0 && config != 255;
        assert_eq!(surface.nb_polygons() > 0, expect_surface, "configuration {config:08b}");
    }
}

#[test]
fn sphere_and_torus_have_their_topology() {
    let n = 24;
    let c = (n as f64 - 1.0) / 2.0;
    let sphere = field(n, |x, y, z| ((x - c).powi(2) + (y - c).powi(2) + (z - c).powi(2)).sqrt() - 8.3);
    let (s, r) = marching_cubes_field(&sphere, [n, n, n], 0.0, &mc_pattern_set()).expect("sphere");
    assert_eq!((r.unmatched_faces, r.unmatched_volumes), (0, 0));
    assert_eq!(topology(&s), (0, 2));
    assert_eq!(topology(&triangulate(&s)), (0, 2));
    let torus = field(n, |x, y, z| {
        let q = ((x - c).powi(2) + (y - c).powi(2)).sqrt() - 6.5;
        (q * q + (z - c).powi(2)).sqrt() - 2.7
    });
    let (t, _) = marching_cubes_field(&torus, [n, n, n], 0.0, &mc_pattern_set()).expect("torus");
    assert_eq!(topology(&t), (0, 0));
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn shared_fields_give_closed_surfaces() {
    let Some(dir) = common::data_dir() else { return };
    for (name, n) in [("fields/field_noise_32.f32", 32), ("fields/field_gyroid_64.f32", 64)] {
        let bytes = std::fs::read(dir.join(name)).expect(name);
        let values: Vec<f32> = bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
        let (s, r) = marching_cubes_field(&values, [n, n, n], 0.0, &mc_pattern_set()).expect(name);
        assert_eq!((r.unmatched_faces, r.unmatched_volumes), (0, 0), "{name}");
        let (open, chi) = topology(&s);
        assert_eq!(topology(&triangulate(&s)), (open, chi), "{name}: triangulated");
        assert_eq!(open, 0, "{name}: closed");
        eprintln!("{name}: {} polygons, {} triangles, χ {chi}", s.nb_polygons(), triangulate(&s).nb_polygons());
    }
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn bunny_surface_through_its_octree() {
    let Some(dir) = common::data_dir() else { return };
    let s = qmesh::io::read_surface(&dir.join("surface/bunny.off"), None).expect("bunny");
    let bvh = qmesh::geom::TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
    let (surface, r, hexes) = qmesh::apps::marching_cubes_surface(&bvh, 5, 0.01, &mc_pattern_set()).expect("mc");
    assert_eq!(hexes, 8576);
    assert_eq!((r.unmatched_faces, r.unmatched_volumes), (0, 0));
    assert_eq!(topology(&surface), (0, 2), "a closed sphere-like surface");
}
