//! Octree subdivision (2022 Algorithm 5): query-replace and direct give the same
//! leaves, the map stays valid, 2:1 balance holds, counts follow the refinement.

mod common;

use qmesh::apps::{RootShape, SubdivideOptions, subdivide};
use qmesh::build::{CellValues, IndexedMesh};
use qmesh::cmap::Orbit;
use qmesh::geom::TriangleBvh;
use qmesh::io::read_surface;
use rustc_hash::FxHashMap;

/// A tilted triangle and a small box-shaped surface: touches cells at every level.
fn test_surface() -> TriangleBvh {
    let s = [0.1, 0.2, 0.15];
    let box_corner = |i: u32| [0, 1, 2].map(|k| s[k] + 0.3 * f64::from(i >> k & 1));
    let quads = [[0u32, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let mut tris = vec![[[0.0, 0.0, 0.9], [1.0, 0.1, 1.0], [0.3, 1.0, 0.8]]];
    for q in quads {
        tris.push([box_corner(q[0]), box_corner(q[1]), box_corner(q[2])]);
        tris.push([box_corner(q[0]), box_corner(q[2]), box_corner(q[3])]);
    }
    TriangleBvh::new(tris)
}

/// Largest number of mesh points strictly inside one hexahedron edge (2:1 balance
/// allows one: the midpoint), checked by position, independently of the octree.
fn max_points_inside_an_edge(m: &IndexedMesh) -> usize {
    let key = |p: [f64; 3]| p.map(|c| (c * 1e9).round() as i64);
    let at: FxHashMap<[i64; 3], u32> = m.points.iter().enumerate().map(|(i, &p)| (key(p), i as u32)).collect();
    let mut worst = 0;
    for c in 0..m.nb_cells() {
        let n = m.cell(c).1;
        let edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)];
        for (a, b) in edges {
            let (p, q) = (m.points[n[a] as usize], m.points[n[b] as usize]);
            // Points at 1/8 steps along the edge (a level three deeper would show there).
            let inside = (1..8)
                .filter(|&k| {
                    let t = f64::from(k) / 8.0;
                    at.contains_key(&key([0, 1, 2].map(|i| p[i] + t * (q[i] - p[i]))))
                })
                .count();
            worst = worst.max(inside);
        }
    }
    worst
}

/// The boxes of the map's volumes and of the mesh's hexahedra, sorted, in quarters of
/// the finest cell's side: equal when the map's volumes are the octree's leaves (a
/// leaf's dart naming the wrong volume refines or removes the wrong cell, which the
/// mesh does not show).
fn map_and_mesh_boxes(map: &qmesh::cmap::CMap3, mesh: &IndexedMesh) -> (Vec<[i64; 6]>, Vec<[i64; 6]>) {
    let bounds = |points: &mut dyn Iterator<Item = [f64; 3]>| {
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for p in points {
            (0..3).for_each(|k| (lo[k], hi[k]) = (lo[k].min(p[k]), hi[k].max(p[k])));
        }
        (lo, hi)
    };
    let of_mesh: Vec<_> =
        (0..mesh.nb_cells()).map(|c| bounds(&mut mesh.cell(c).1.iter().map(|&i| mesh.points[i as usize]))).collect();
    let of_map: Vec<_> = map
        .cells(Orbit::Volume)
        .map(|v| bounds(&mut map.orbit(v, Orbit::Volume).iter().map(|&x| map.point(x))))
        .collect();
    let origin = bounds(&mut mesh.points.iter().copied()).0;
    let quarter = of_mesh.iter().flat_map(|(lo, hi)| (0..3).map(|k| hi[k] - lo[k])).fold(f64::MAX, f64::min) / 4.0;
    let key = |boxes: &[([f64; 3], [f64; 3])]| {
        let r = |x: f64, k: usize| ((x - origin[k]) / quarter).round() as i64;
        let mut keys: Vec<[i64; 6]> = boxes
            .iter()
            .map(|(lo, hi)| [r(lo[0], 0), r(lo[1], 1), r(lo[2], 2), r(hi[0], 0), r(hi[1], 1), r(hi[2], 2)])
            .collect();
        keys.sort_unstable();
        keys
    };
    (key(&of_map), key(&of_mesh))
}

fn run(surface: &TriangleBvh, levels: u8, direct: bool) -> qmesh::apps::Subdivision {
    let opts = SubdivideOptions { levels, direct, ..Default::default() };
    subdivide(surface, &opts, None, &|_| {}).expect("subdivide")
}

#[test]
fn query_replace_and_direct_agree_and_stay_balanced() {
    let surface = test_surface();
    for levels in 1..=5 {
        let qr = run(&surface, levels, false);
        let direct = run(&surface, levels, true);
        assert_eq!(qr.mesh, direct.mesh, "levels {levels}: same hexahedra and levels");
        let map = qr.map.as_ref().expect("query-replace keeps its map");
        assert!(map.is_valid().is_empty(), "levels {levels}");
        let (of_map, of_mesh) = map_and_mesh_boxes(map, &qr.mesh);
        assert!(of_map == of_mesh, "levels {levels}: the map's volumes are not the octree's leaves");
        assert_eq!(map.count_cells().volumes, qr.report.volumes);
        // Each volume query-replace turns one cell into 8.
        assert_eq!(qr.report.volumes, 1 + 7 * qr.report.volumes_replaced);
        assert_eq!(max_points_inside_an_edge(&qr.mesh), if levels == 1 { 0 } else { 1 }, "levels {levels}");
        let Some(CellValues::Int(level)) = qr.mesh.cell_array("level") else { panic!("level array") };
        assert_eq!(level.iter().copied().max(), Some(i32::from(levels)));
    }
}

#[test]
fn balance_is_needed_and_applied() {
    let surface = test_surface();
    let r = run(&surface, 5, true).report;
    assert!(r.balance_splits > 0, "this surface forces balance splits: {r:?}");
    assert_eq!(r.per_level.iter().sum::<usize>(), r.volumes);
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn bunny_at_level_four_both_ways() {
    let Some(dir) = common::data_dir() else { return };
    let s = read_surface(&dir.join("surface/bunny.off"), None).expect("bunny");
    let bvh = TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
    let qr = run(&bvh, 4, false);
    let direct = run(&bvh, 4, true);
    assert_eq!(qr.mesh, direct.mesh);
    assert_eq!(qr.report.volumes, 1842);
    // The papers' own hexa-8-subdivision patterns (drawn in Moka) give the same cells.
    let papers = qmesh::pattern::load_pattern_dir(
        &dir.join("patterns/cgal/hexa-8-subdivision"),
        qmesh::pattern::FlagRule::Corners,
    );
    let opts = SubdivideOptions { levels: 4, ..Default::default() };
    let with_papers = subdivide(&bvh, &opts, Some(&papers), &|_| {}).expect("subdivide");
    assert_eq!(with_papers.mesh, qr.mesh);
    assert!(qr.map.expect("map").is_valid().is_empty());
    assert_eq!(max_points_inside_an_edge(&qr.mesh), 1);
    // Removing the outside level by level keeps the cells the surface touches and those
    // inside: the same cells as removing it from the whole octree at the end.
    let opts = SubdivideOptions { levels: 4, direct: true, remove_outside: true, ..Default::default() };
    let kept = subdivide(&bvh, &opts, None, &|_| {}).expect("subdivide");
    let mut whole = qmesh::apps::octree_around(&bvh, 4, opts.root, opts.margin);
    assert_eq!(whole.leaves.len(), 1842);
    for c in whole.outside_leaves(&bvh) {
        whole.leaves.remove(&c);
    }
    assert_eq!(kept.mesh, whole.to_mesh());
    assert!(kept.report.removed_outside > 100 && kept.report.volumes > 1000, "{:?}", kept.report);
    let qr = subdivide(&bvh, &SubdivideOptions { direct: false, ..opts }, None, &|_| {}).expect("subdivide");
    assert_eq!(qr.mesh, kept.mesh);
    assert_eq!(qr.report.removed_outside, kept.report.removed_outside);
    let map = qr.map.expect("map");
    assert!(map.is_valid().is_empty());
    let (of_map, of_mesh) = map_and_mesh_boxes(&map, &qr.mesh);
    assert!(of_map == of_mesh, "the map's volumes are not the octree's leaves");
}

/// The authors' set-up (root cells on the bounding box, `-init X`): the figures of their
/// program (`cgal_hexa_subdivision`, 2022) on the bunny, measured with it.
#[test]
fn bounding_box_root_gives_the_authors_counts() {
    let Some(dir) = common::data_dir() else { return };
    let s = read_surface(&dir.join("surface/bunny.off"), None).expect("bunny");
    let bvh = TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
    let run = |levels, init, remove_outside, direct| {
        let root = RootShape::BoundingBox { init };
        let opts = SubdivideOptions { levels, root, remove_outside, direct, ..Default::default() };
        subdivide(&bvh, &opts, None, &|_| {}).expect("subdivide")
    };
    // -lmax 0 -init X: the grid cells the bunny meets or holds.
    for (init, cells) in [(1, 1), (2, 8), (3, 23), (4, 49), (8, 238), (12, 644)] {
        assert_eq!(run(0, init, false, true).report.volumes, cells, "init {init}");
    }
    // -lmax 3 and 5, with and without removing the outside: volumes, generic cells
    // (hanging vertices), face and volume replacements.
    for (levels, remove, figures) in
        [(3, true, [254, 2, 234, 56]), (3, false, [393, 17, 234, 56]), (5, true, [6045, 434, 5020, 1282])]
    {
        let qr = run(levels, 1, remove, false);
        let r = &qr.report;
        let hanging = r.with_hanging_vertices;
        assert_eq!([r.volumes, hanging, r.faces_replaced, r.volumes_replaced], figures, "l_max {levels}");
        let direct = run(levels, 1, remove, true);
        assert_eq!(qr.mesh, direct.mesh);
        assert_eq!(direct.report.with_hanging_vertices, hanging);
        let map = qr.map.as_ref().expect("map");
        assert!(map.is_valid().is_empty());
        // Counted on the tree, as the volumes of the map with more than 8 vertices.
        let on_map = map.cells(Orbit::Volume).filter(|&d| map.orbit(d, Orbit::Volume).len() > 24).count();
        assert_eq!(on_map, hanging, "l_max {levels}");
        // The phases account for the query-replace run (none with `direct`).
        let p = r.phases;
        let phases = [p.start, p.contact, p.remove_outside, p.balance, p.split_edges, p.lookup, p.apply, p.finish];
        assert!(p.lookup > 0.0 && p.apply > 0.0 && p.split_edges > 0.0 && p.contact > 0.0, "{p:?}");
        assert_eq!(remove, p.remove_outside > 0.0);
        assert!(phases.iter().sum::<f64>() <= r.seconds, "{p:?} in {} s", r.seconds);
        assert_eq!(direct.report.phases.apply + direct.report.phases.lookup, 0.0);
    }
}

/// The patterns are looked up on all cores: one thread or several give the same map.
#[test]
fn same_map_on_one_thread_and_on_four() {
    let Some(dir) = common::data_dir() else { return };
    let s = read_surface(&dir.join("surface/bunny.off"), None).expect("bunny");
    let bvh = TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
    let root = RootShape::BoundingBox { init: 1 };
    let opts = SubdivideOptions { levels: 6, root, remove_outside: true, ..Default::default() };
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool");
        pool.install(|| subdivide(&bvh, &opts, None, &|_| {}).expect("subdivide"))
    };
    let (one, four) = (on(1), on(4));
    assert_eq!(one.mesh, four.mesh);
    // The authors' figures; the last level alone looks up several chunks of faces.
    assert_eq!((four.report.faces_replaced, four.report.volumes_replaced), (22018, 5671));
    assert!(four.report.faces_replaced > 4 * qmesh::replace::LOOKUP_CHUNK);
    let (a, b) = (one.map.expect("map"), four.map.expect("map"));
    assert_eq!(a.nb_darts(), b.nb_darts());
    assert!(a.darts().all(|d| (0..=3).all(|i| a.beta(d, i) == b.beta(d, i))), "dart for dart");
}

/// The map the query-replace subdivision makes is the map of its boxes with their
/// hanging vertices inserted into the coarse faces (what `conformal` builds from a
/// written octree): the same darts, cells and boundary, which makes that build the
/// "direct + the same map" baseline of `bench/subdivision.py`.
#[test]
fn query_replace_map_is_the_boxes_map_with_hanging_vertices() {
    let Some(dir) = common::data_dir() else { return };
    let s = read_surface(&dir.join("surface/bunny.off"), None).expect("bunny");
    let bvh = TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
    let opts = SubdivideOptions { levels: 5, remove_outside: true, ..Default::default() };
    let qr = subdivide(&bvh, &opts, None, &|_| {}).expect("subdivide");
    let map = qr.map.as_ref().expect("a map");
    let (with_hanging, report) = qmesh::apps::insert_hanging_vertices(&qr.mesh).expect("a 2:1 octree");
    assert!(report.cells_with_hanging > 100, "{report:?}");
    let (built, _) = qmesh::build::build_map(with_hanging, &qmesh::build::BuildOptions::default()).expect("builds");
    assert_eq!(built.nb_darts(), map.nb_darts());
    assert_eq!(built.count_cells(), map.count_cells());
    assert_eq!(built.boundary_faces(), map.boundary_faces());
}
