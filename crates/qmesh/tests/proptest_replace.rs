//! Property tests of the replacements on random valid maps: hex and tet grids with
//! random edges split and random faces removed, then query-replace (hex subdivision,
//! tet→hex) or marching cubes with random inside vertices. Valid in, valid out; the
//! Euler characteristic is kept; cell counts follow the matches; no dart leaks.

use std::sync::OnceLock;

use proptest::prelude::*;
use qmesh::apps::{GeneratedKind, McFlags, generated_pattern_set, marching_cubes, mc_pattern_set};
use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::{CMap3, Dart, Orbit};
use qmesh::generate::{hex_grid, tet_grid};
use qmesh::modify::{FacePattern, VolumePattern};
use qmesh::pattern::{FlagRule, PatternSet};
use qmesh::replace::{find_face, find_volume, replace_cells};
use qmesh::signature::Flags;

fn sets() -> &'static [PatternSet; 3] {
    static SETS: OnceLock<[PatternSet; 3]> = OnceLock::new();
    SETS.get_or_init(|| {
        [
            generated_pattern_set(GeneratedKind::HexSubdivision, FlagRule::Corners).expect("hex"),
            generated_pattern_set(GeneratedKind::Tet2Hex, FlagRule::Corners).expect("tet"),
            mc_pattern_set(),
        ]
    })
}

/// A grid with some edges split in their middle and some inner faces removed; the
/// original darts carry `flag` (the papers' corner rule).
fn random_map(tets: bool, n: [usize; 3], splits: &[u16], removals: &[u16]) -> (CMap3, qmesh::cmap::Mark) {
    let mesh = if tets { tet_grid(n[0], n[1], n[2]) } else { hex_grid(n[0], n[1], n[2]) };
    let (mut m, _) = build_volume_map(&mesh, &BuildOptions::default()).expect("grid");
    let flag = m.reserve_mark().expect("a mark");
    for d in m.darts().collect::<Vec<_>>() {
        m.mark(d, flag);
    }
    for &r in removals {
        let inner: Vec<Dart> = m.cells(Orbit::Face).filter(|&d| !m.is_free(d, 3)).collect();
        if let Some(&d) = inner.get(r as usize % inner.len().max(1)) {
            m.remove_face(d).expect("an inner face can be removed");
        }
    }
    split_edges_at(&mut m, splits);
    assert!(m.is_valid().is_empty());
    (m, flag)
}

/// Splits, for each of `splits`, the edge of that index (modulo the count) in its middle.
fn split_edges_at(m: &mut CMap3, splits: &[u16]) {
    for &s in splits {
        let edges: Vec<Dart> = m.cells(Orbit::Edge).collect();
        let d = edges[s as usize % edges.len()];
        let (p, q) = (m.point(d), m.point(m.next(d)));
        m.insert_vertex_in_edge(d, [0, 1, 2].map(|k| 0.5 * (p[k] + q[k])));
    }
}

/// The f and v passes one cell at a time, each looked up after the previous
/// replacements (what `replace_cells` must equal, dart for dart).
fn replace_one_by_one(m: &mut CMap3, set: &PatternSet, flags: Flags, faces: &[Dart], volumes: &[Dart]) {
    for &d in faces {
        if let Some((i, aligned)) = find_face(m, set, flags, d, true)
            && let Some(p) = FacePattern::new(&set.patterns[i])
        {
            p.replace(m, &aligned);
        }
    }
    for &d in volumes {
        if let Some((i, start)) = find_volume(m, set, flags, d, true)
            && let Some(p) = VolumePattern::new(&set.patterns[i])
        {
            p.replace(m, start, flags);
        }
    }
}

/// Every dart slot (liveness, betas, vertex id, label) and every position of two maps.
fn same_storage(a: &CMap3, b: &CMap3) -> Result<(), String> {
    if a.dart_capacity() != b.dart_capacity() || a.positions() != b.positions() {
        return Err(format!(
            "{} / {} dart slots, {} / {} vertices",
            a.dart_capacity(),
            b.dart_capacity(),
            a.nb_vertex_ids(),
            b.nb_vertex_ids()
        ));
    }
    for raw in 1..a.dart_capacity() as u32 {
        let d = Dart::from_raw(raw).expect("non-zero");
        let slot = |m: &CMap3| (m.is_live(d), m.is_live(d).then(|| (m.betas_raw(raw), m.vertex_of(d), m.label_of(d))));
        if slot(a) != slot(b) {
            return Err(format!("dart {raw}: {:?} / {:?}", slot(a), slot(b)));
        }
    }
    Ok(())
}

/// Every live dart belongs to some volume, and compaction changes no count.
fn assert_no_leak(m: &mut CMap3) {
    let in_volumes: usize = m.cells(Orbit::Volume).map(|d| m.orbit(d, Orbit::Volume).len()).sum();
    assert_eq!(in_volumes, m.nb_darts(), "darts outside every volume");
    let before = m.count_cells();
    m.compact();
    assert!(m.is_valid().is_empty());
    let after = m.count_cells();
    assert_eq!((after.darts, after.vertices, after.volumes), (before.darts, before.vertices, before.volumes));
    assert_eq!(m.nb_vertex_ids(), after.vertices, "no orphan vertex id");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn query_replace_on_random_maps(
        tets in any::<bool>(),
        n in prop::array::uniform3(1usize..3),
        split_all in any::<bool>(),
        splits in prop::collection::vec(any::<u16>(), 0..30),
        removals in prop::collection::vec(any::<u16>(), 0..3),
    ) {
        let (mut m, flag) = random_map(tets, n, &[], &removals);
        if split_all {
            m.split_all_edges(2).expect("split");
        }
        split_edges_at(&mut m, &splits);
        let before = m.count_cells();
        let set = &sets()[usize::from(tets)];
        let faces: Vec<Dart> = m.cells(Orbit::Face).collect();
        let volumes: Vec<Dart> = m.cells(Orbit::Volume).collect();
        let r = replace_cells(&mut m, set, Flags::Mark(flag), &faces, &volumes, true);
        prop_assert!(m.is_valid().is_empty());
        let after = m.count_cells();
        prop_assert_eq!(after.euler_characteristic(3), before.euler_characteristic(3));
        let children = if tets { 4 } else { 8 };
        prop_assert_eq!(after.volumes, before.volumes + (children - 1) * r.volumes_replaced);
        if split_all && splits.is_empty() && removals.is_empty() {
            prop_assert_eq!(r.volumes_replaced, before.volumes, "every cell matches");
        }
        assert_no_leak(&mut m);
    }

    /// The batched replacements (resolved on all cores, stored in order) give the map
    /// of one replacement after another, dart for dart, freed slots reused included.
    #[test]
    fn batched_replacements_equal_one_by_one(
        tets in any::<bool>(),
        n in prop::array::uniform3(1usize..4),
        splits in prop::collection::vec(any::<u16>(), 0..6),
        removals in prop::collection::vec(any::<u16>(), 0..3),
        labelled in any::<bool>(),
    ) {
        let (mut m, flag) = random_map(tets, n, &[], &removals);
        m.split_all_edges(2).expect("split");
        split_edges_at(&mut m, &splits);
        if labelled {
            m.enable_labels();
            for (k, v) in m.cells(Orbit::Volume).collect::<Vec<_>>().into_iter().enumerate() {
                for x in m.orbit(v, Orbit::Volume) {
                    m.set_label_of(x, k as i32);
                }
            }
        }
        let set = &sets()[usize::from(tets)];
        let faces: Vec<Dart> = m.cells(Orbit::Face).collect();
        let volumes: Vec<Dart> = m.cells(Orbit::Volume).collect();
        let mut reference = m.clone();
        replace_one_by_one(&mut reference, set, Flags::Mark(flag), &faces, &volumes);
        let r = replace_cells(&mut m, set, Flags::Mark(flag), &faces, &volumes, true);
        if splits.is_empty() && removals.is_empty() {
            prop_assert_eq!(r.volumes_replaced, volumes.len(), "every cell matches");
        }
        prop_assert!(m.is_valid().is_empty());
        if let Err(e) = same_storage(&m, &reference) {
            prop_assert!(false, "batched and one-by-one maps differ: {}", e);
        }
    }

    /// Face lookups remembered per thread (by the flags around the half-face) answer
    /// what the lookup without them does: the same pattern, the same aligned darts,
    /// also for faces met again on the same map and on a differently flagged one.
    #[test]
    fn remembered_face_lookups_equal_direct_ones(
        tets in any::<bool>(),
        n in prop::array::uniform3(1usize..3),
        splits in prop::collection::vec(any::<u16>(), 0..12),
        unflag in prop::collection::vec(any::<u16>(), 0..6),
    ) {
        let (mut m, flag) = random_map(tets, n, &splits, &[]);
        let darts: Vec<Dart> = m.darts().collect();
        for &u in &unflag {
            m.unmark(darts[u as usize % darts.len()], flag);
        }
        let set = &sets()[usize::from(tets)];
        for _ in 0..2 {
            for d in m.cells(Orbit::Face).collect::<Vec<_>>() {
                let remembered = find_face(&m, set, Flags::Mark(flag), d, true);
                let direct = find_face(&m, set, Flags::Mark(flag), d, false);
                prop_assert_eq!(remembered, direct, "face of dart {}", d.raw());
            }
        }
    }

    #[test]
    fn marching_cubes_on_random_maps(
        n in prop::array::uniform3(1usize..4),
        inside in prop::collection::vec(any::<bool>(), 64),
        removals in prop::collection::vec(any::<u16>(), 0..2),
    ) {
        let (mut m, flag) = random_map(false, n, &[], &removals);
        m.free_mark(flag);
        let before = m.count_cells();
        let ins: Vec<bool> = (0..m.nb_vertex_ids()).map(|v| inside[v % inside.len()]).collect();
        let pos = m.positions().to_vec();
        let mid = |a: u32, b: u32| {
            let (p, q) = (pos[a as usize], pos[b as usize]);
            [0, 1, 2].map(|k| 0.5 * (p[k] + q[k]))
        };
        let (surface, r) = marching_cubes(&mut m, &ins, &mid, &sets()[2], McFlags::Inside).expect("marching cubes");
        prop_assert!(m.is_valid().is_empty());
        prop_assert_eq!(m.count_cells().euler_characteristic(3), before.euler_characteristic(3));
        if removals.is_empty() {
            prop_assert_eq!(r.unmatched_volumes, 0);
            prop_assert_eq!(r.unmatched_faces, 0);
            if surface.nb_polygons() > 0 {
                // Open only where the inside reaches the grid's boundary.
                let (s, _) = qmesh::build::build_surface_map(&surface).expect("manifold surface");
                prop_assert!(s.is_valid().is_empty());
            }
        }
        assert_no_leak(&mut m);
    }
}
