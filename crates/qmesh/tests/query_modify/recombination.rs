//! Tetrahedra → hexahedra (2025 §7.1): the synthetic tetrahedralization and the
//! recombination that must give back exactly the hexahedra it came from.

use qmesh::apps::{
    HexSplits, RecombineOptions, SplitChoice, TetrahedralizeOptions, recombine, recombined_mesh, split_query_mesh,
    tetrahedralize,
};
use qmesh::build::{BuildOptions, CellKind, CellValues, IndexedMesh, build_volume_map, non_conformal_faces};
use qmesh::geom::signed_volume_of_table;

/// Vertex sets of the hexahedra of a mesh.
fn hex_sets(m: &IndexedMesh) -> Vec<[u32; 8]> {
    let mut v: Vec<[u32; 8]> = (0..m.nb_cells())
        .filter(|&c| m.kinds[c] == CellKind::Hex)
        .map(|c| {
            let mut h: [u32; 8] = m.cell(c).1.try_into().unwrap();
            h.sort_unstable();
            h
        })
        .collect();
    v.sort_unstable();
    v
}

/// A hex grid whose interior vertices are moved (reproducibly) so hexahedra differ.
fn jittered_grid(n: usize, amount: f64) -> IndexedMesh {
    let mut g = qmesh::generate::hex_grid(n, n, n);
    for (i, p) in g.points.iter_mut().enumerate() {
        if p.iter().all(|&x| x > 0.0 && x < n as f64) {
            let h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            for (k, x) in p.iter_mut().enumerate() {
                *x += amount * (((h >> (8 * k)) & 0xff) as f64 / 255.0 - 0.5);
            }
        }
    }
    g
}

fn check_round_trip(hexes: &IndexedMesh, choice: SplitChoice, seed: u64) {
    let (tets, t) = tetrahedralize(hexes, &TetrahedralizeOptions { choice, seed }).unwrap();
    assert_eq!(t.hexes, hexes.nb_cells());
    assert_eq!(t.by_tet_count.iter().map(|(n, c)| n * c).sum::<usize>(), tets.nb_cells());
    // Conformal and positive.
    let (mut map, built) = build_volume_map(&tets, &BuildOptions::default()).unwrap();
    assert_eq!((built.inverted_cells, built.degenerate_cells), (0, 0));
    assert_eq!(non_conformal_faces(&map), 0);
    for c in 0..tets.nb_cells() {
        let v = signed_volume_of_table(CellKind::Tet.face_table(), tets.cell(c).1, &tets.points);
        assert!(v > 0.0, "tet {c}");
    }
    let Some(CellValues::Int(source)) = tets.cell_array("source_cell") else { panic!("source_cell") };
    assert_eq!(source.len(), tets.nb_cells());
    let chi = map.count_cells().euler_characteristic(3);
    let (r, made) = recombine(&mut map, &RecombineOptions::default()).unwrap();
    assert!(map.is_valid().is_empty());
    assert_eq!(map.count_cells().euler_characteristic(3), chi);
    assert_eq!(r.tets_in, tets.nb_cells());
    assert_eq!(r.by_tet_count.iter().map(|(n, c)| n * c).sum::<usize>() + r.tets_left, r.tets_in);
    assert_eq!((r.hexes, r.tets_left, r.hex_tet_interfaces), (hexes.nb_cells(), 0, 0), "{choice:?} seed {seed}");
    let (out, kinds) = recombined_mesh(&map, &made, false);
    assert_eq!((kinds.hex, kinds.tet, kinds.other), (hexes.nb_cells(), 0, 0));
    assert_eq!(hex_sets(&out), hex_sets(hexes), "the original hexahedra, vertex set for vertex set");
}

#[test]
fn recombination_gives_back_the_original_hexahedra() {
    check_round_trip(&jittered_grid(4, 0.3), SplitChoice::Five, 1);
    for seed in 1..=3 {
        check_round_trip(&jittered_grid(3, 0.0), SplitChoice::Any, seed);
    }
}

/// On an unstructured hex mesh split with any subdivision, best-first selection takes
/// well-shaped hexahedra made of parts of two others; the repair gives every original
/// back, where the selection alone leaves tetrahedra.
#[test]
fn any_split_of_an_unstructured_hex_mesh_is_fully_recovered() {
    let Some(dir) = crate::common::data_dir() else { return };
    let path = dir.join("hex/gmsh_torus_hex_subdiv.mesh");
    let qmesh::io::Loaded::Indexed(hexes) = qmesh::io::read(&path, None).unwrap() else { panic!("a cell mesh") };
    for seed in 1..=2 {
        let (tets, _) = tetrahedralize(&hexes, &TetrahedralizeOptions { choice: SplitChoice::Any, seed }).unwrap();
        let (mut map, _) = build_volume_map(&tets, &BuildOptions::default()).unwrap();
        let mut plain = map.clone();
        let (r, made) = recombine(&mut map, &RecombineOptions::default()).unwrap();
        let (out, _) = recombined_mesh(&map, &made, false);
        assert_eq!(hex_sets(&out), hex_sets(&hexes), "seed {seed}: {r:?}");
        assert!(map.is_valid().is_empty());
        let (p, _) = recombine(&mut plain, &RecombineOptions { repair_effort: 0.0, ..Default::default() }).unwrap();
        assert_eq!(p.repairs, 0);
        assert!(p.tets_left > 0, "seed {seed}: the selection alone recovers all: the test no longer shows the repair");
        assert_eq!(p.tets_left, r.repaired_tets, "seed {seed}: what the repair recovered was left over");
    }
}

#[test]
fn every_realisable_class_is_found_in_its_own_geometry() {
    use qmesh::query::Annotator;
    let s = HexSplits::get();
    let rules = qmesh::apps::hex_rules().unwrap();
    assert_eq!(rules.len(), s.oriented.iter().filter(|o| o.realization.is_some()).count());
    let opts = BuildOptions::default();
    for rule in &rules {
        let o = &s.oriented[rule.target.oriented];
        let p = o.realization.unwrap();
        let (map, _) = build_volume_map(&split_query_mesh(&o.tets, &p), &opts).unwrap();
        let mut a = Annotator::new(rule.query.nb_darts());
        // Some start dart matches the whole subdivision (its own query, ↔ everywhere).
        let whole = map.darts().any(|d| a.annotate(&map, &rule.query.word, d, None));
        assert!(whole, "class {} ({} tets) not found in its own tetrahedra", o.class, o.tets.len());
        // The recombination takes a hexahedron there and leaves a valid map.
        let (mut m2, _) = build_volume_map(&split_query_mesh(&o.tets, &p), &opts).unwrap();
        let (r, _) = recombine(&mut m2, &RecombineOptions { min_quality: -1.0, ..Default::default() }).unwrap();
        assert!(r.hexes >= 1 && m2.is_valid().is_empty());
    }
}

#[test]
fn five_tet_splits_need_bipartite_hex_edges() {
    let grid = qmesh::generate::hex_grid(2, 2, 1);
    let (_, r) = tetrahedralize(&grid, &TetrahedralizeOptions { choice: SplitChoice::Five, seed: 1 }).unwrap();
    assert!(r.bipartite);
    assert_eq!(r.by_tet_count.get(&5), Some(&4));
    // A closed ring of 5 hexahedra around the z axis: its edges along the ring form
    // cycles of length 5, so no 2-colouring exists.
    let mut odd = IndexedMesh::new();
    let n = 5u32;
    for k in 0..n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        for (r, z) in [(1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0)] {
            odd.points.push([r * a.cos(), r * a.sin(), z]);
        }
    }
    for k in 0..n {
        let (p, q) = (4 * k, 4 * ((k + 1) % n));
        // Bottom (inner, outer at k; outer, inner at k + 1), then the top above it.
        odd.push_cell(CellKind::Hex, &[p, p + 1, q + 1, q, p + 3, p + 2, q + 2, q + 3], None);
    }
    let (tets, r) = tetrahedralize(&odd, &TetrahedralizeOptions { choice: SplitChoice::Five, seed: 1 }).unwrap();
    assert!(!r.bipartite);
    assert!(r.by_tet_count.get(&5).copied().unwrap_or(0) < 5, "{:?}", r.by_tet_count);
    let (mut map, _) = build_volume_map(&tets, &BuildOptions::default()).unwrap();
    let (rr, _) = recombine(&mut map, &RecombineOptions::default()).unwrap();
    assert_eq!((rr.hexes, rr.tets_left), (5, 0));
}

#[test]
fn hexahedra_meeting_tetrahedra_keep_their_split_faces() {
    // Two hexahedra side by side; the second one stays as tetrahedra because the
    // recombination is limited to a quality it cannot reach.
    let grid = qmesh::generate::hex_grid(2, 1, 1);
    let (tets, _) = tetrahedralize(&grid, &TetrahedralizeOptions { choice: SplitChoice::Five, seed: 3 }).unwrap();
    let (mut map, _) = build_volume_map(&tets, &BuildOptions::default()).unwrap();
    let (r, _) = recombine(&mut map, &RecombineOptions { min_quality: 0.999, ..Default::default() }).unwrap();
    assert_eq!(r.hexes, 2, "unit cubes have quality 1");
    let mut mixed = tets.clone();
    // Shear the second hexahedron (its far top edge moves sideways): its scaled
    // Jacobian drops below 0.95 while the first stays a unit cube.
    for p in mixed.points.iter_mut().filter(|p| p[0] > 1.5 && p[2] > 0.5) {
        p[1] += 0.6;
    }
    let (mut map, built) = build_volume_map(&mixed, &BuildOptions::default()).unwrap();
    assert_eq!(built.inverted_cells, 0);
    let (r, made) = recombine(&mut map, &RecombineOptions { min_quality: 0.95, ..Default::default() }).unwrap();
    assert_eq!((r.hexes, r.tets_left, r.hex_tet_interfaces, r.hexes_with_tet_faces), (1, 5, 1, 1));
    assert!(map.is_valid().is_empty());
    let (plain, k) = recombined_mesh(&map, &made, false);
    assert_eq!((k.hex, k.tet, k.other), (1, 5, 0));
    assert_eq!(plain.nb_cells(), 6);
    let (_, k) = recombined_mesh(&map, &made, true);
    assert_eq!((k.hex, k.tet, k.other), (0, 5, 1), "conformal: the hexahedron as a polyhedron");
}
