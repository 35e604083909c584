//! Signatures (2022 §2.4, §4): invariant under dart renumbering and start dart,
//! collision-free on every pattern in `../shared/data`, and equal exactly when the
//! direct isomorphism test (§2.3) finds a match.

mod common;

use proptest::prelude::*;
use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::{CMap3, Dart, Orbit};
use qmesh::pattern::{FlagRule, PatternKind, load_pattern, load_pattern_dir};
use qmesh::signature::{
    Flags, Signature, Surface, match_direct, signature_shape, start_with_signature, volume_shape, volume_signature,
    volume_signature_from,
};

/// The same map with its darts created in the order given by `perm` (a permutation of
/// the live darts), marks and vertex ids carried over.
fn renumbered(m: &CMap3, perm: &[usize]) -> (CMap3, Vec<Dart>) {
    let old: Vec<Dart> = m.darts().collect();
    let mut r = CMap3::new();
    r.set_dimension(m.dimension());
    for &p in m.positions() {
        r.add_vertex(p);
    }
    let mut new_of = vec![None; m.dart_capacity()];
    let order: Vec<Dart> = perm.iter().map(|&i| old[i]).collect();
    for &d in &order {
        let n = r.create_dart(m.vertex_of(d));
        r.set_mark_bits(n, m.mark_bits(d));
        new_of[d.idx()] = Some(n);
    }
    let map_of = |d: Dart| new_of[d.idx()].unwrap();
    for &d in &order {
        for i in 1..4 {
            if let Some(t) = m.beta(d, i) {
                r.link(map_of(d), i, map_of(t));
            }
        }
    }
    (r, old.iter().map(|&d| map_of(d)).collect())
}

fn shuffled(n: usize, seed: u64) -> Vec<usize> {
    let mut v: Vec<usize> = (0..n).collect();
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    for i in (1..n).rev() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        v.swap(i, (s % (i as u64 + 1)) as usize);
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Any numbering of a cell's darts and any start dart give the same signature.
    #[test]
    fn cell_signature_is_invariant(seed in any::<u64>(), split in 0usize..24, k in 1usize..4, flag_every in 1usize..5) {
        let mut m = CMap3::new();
        let v = common::unit_cube_vertices(&mut m, 0.0);
        let h = m.make_hexahedron(v);
        let mark = m.reserve_mark().unwrap();
        for (i, d) in m.orbit(h, Orbit::Volume).into_iter().enumerate() {
            if i % flag_every == 0 {
                m.mark(d, mark);
            }
        }
        let d = m.orbit(h, Orbit::Volume)[split];
        m.split_edge(d, k).unwrap();
        let flags = Flags::Mark(mark);
        let (s0, a0) = volume_signature(&m, Surface::Cell, flags, h).unwrap();
        let (r, image) = renumbered(&m, &shuffled(m.nb_darts(), seed));
        for &start in &image {
            let (s1, a1) = volume_signature(&r, Surface::Cell, flags, start).unwrap();
            prop_assert_eq!(&s1, &s0);
            prop_assert_eq!(a1, a0);
        }
        // The direct test maps h to its image.
        let found = match_direct((&m, Surface::Cell, flags, h), (&r, Surface::Cell, flags, image[0]));
        prop_assert!(found.is_some());
    }
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn the_325_transition_patterns_have_325_distinct_signatures() {
    let Some(d) = common::data_dir() else { return };
    let set = load_pattern_dir(&d.join("patterns/cgal/hexa-325-patterns"), FlagRule::Corners);
    assert!(set.skipped.is_empty(), "{:?}", set.skipped);
    assert_eq!(set.count(PatternKind::Volume), 325);
    assert!(set.duplicates().is_empty());
    let mut sigs: Vec<_> = set.patterns.iter().map(|p| p.signature.clone()).collect();
    sigs.sort();
    sigs.dedup();
    assert_eq!(sigs.len(), 325);
    // Every boundary is a subdivided cube: 8 corners × 3 flagged darts.
    for p in &set.patterns {
        let flagged = p.map.darts().filter(|&x| p.map.is_marked(x, p.flags) && p.map.is_free(x, 3)).count();
        assert_eq!(flagged, 24, "{}", p.file.display());
    }
}

#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn papers_pattern_sets_load_with_the_expected_kinds() {
    let Some(d) = common::data_dir() else { return };
    let cgal = d.join("patterns/cgal");
    for (dir, f, v) in [
        ("hexa-8-subdivision", 1, 1),
        ("tetra-to-hexa", 1, 1),
        ("hexa-to-truncated-cube", 1, 1),
        ("square-5-patterns", 5, 0),
    ] {
        let set = load_pattern_dir(&cgal.join(dir), FlagRule::Corners);
        assert_eq!((set.count(PatternKind::Face), set.count(PatternKind::Volume)), (f, v), "{dir}");
        assert!(set.duplicates().is_empty(), "{dir}");
    }
    let split = load_pattern(&cgal.join("hexa-8-subdivision/vpattern/split-hexa.moka"), FlagRule::Corners).unwrap();
    assert_eq!(split.automorphisms, 24, "the cube's rotations");
    assert_eq!(split.map.count_cells().volumes, 8);
}

/// Signatures of all pattern boundaries collide exactly when the direct test says the
/// boundaries are isomorphic.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn pattern_signatures_collide_only_for_isomorphic_boundaries() {
    let Some(d) = common::data_dir() else { return };
    let mut all = Vec::new();
    for dir in ["hexa-325-patterns", "hexa-8-subdivision", "tetra-to-hexa", "hexa-to-truncated-cube"] {
        all.extend(load_pattern_dir(&d.join("patterns/cgal").join(dir), FlagRule::Corners).patterns);
    }
    let vols: Vec<_> = all.iter().filter(|p| p.kind == PatternKind::Volume).collect();
    let mut pairs = 0;
    for (i, a) in vols.iter().enumerate() {
        for b in &vols[i + 1..] {
            if a.boundary_darts != b.boundary_darts {
                continue;
            }
            pairs += 1;
            let iso = match_direct(
                (&a.map, Surface::PatternBoundary, Flags::Mark(a.flags), a.boundary),
                (&b.map, Surface::PatternBoundary, Flags::Mark(b.flags), b.boundary),
            )
            .is_some();
            assert_eq!(iso, a.signature == b.signature, "{} vs {}", a.file.display(), b.file.display());
        }
    }
    assert!(pairs > 100, "only {pairs} comparable pairs");
}

/// Cells of a real mesh with random edge splits, flags on the original darts.
fn randomly_split_cells(d: &std::path::Path) -> (CMap3, Vec<Dart>, Flags) {
    let mesh = qmesh::io::read(&d.join("hex/gmsh_box_hex_4x4x4.vtk"), None).unwrap();
    let qmesh::io::Loaded::Indexed(mesh) = mesh else { panic!() };
    let (mut m, _) = build_volume_map(&mesh, &BuildOptions::default()).unwrap();
    let flag = m.reserve_mark().unwrap();
    for x in m.darts().collect::<Vec<_>>() {
        m.mark(x, flag);
    }
    let darts: Vec<Dart> = m.darts().collect();
    for (i, &x) in darts.iter().enumerate().filter(|(i, _)| i % 37 == 0) {
        m.split_edge(x, 1 + i % 3).unwrap();
    }
    assert!(m.is_valid().is_empty());
    let cells: Vec<Dart> = m.cells(Orbit::Volume).collect();
    (m, cells, Flags::Mark(flag))
}

/// On random cells of a real mesh with random edge splits (flags on original darts),
/// equal signatures ⇔ the direct isomorphism test matches.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn signature_equality_matches_direct_isomorphism_on_random_cells() {
    let Some(d) = common::data_dir() else { return };
    let (m, cells, flags) = randomly_split_cells(&d);
    let sig: Vec<_> = cells.iter().map(|&c| volume_signature(&m, Surface::Cell, flags, c).unwrap().0).collect();
    let (mut same, mut different) = (0, 0);
    for i in 0..cells.len() {
        for j in (i + 1)..cells.len() {
            let iso =
                match_direct((&m, Surface::Cell, flags, cells[i]), (&m, Surface::Cell, flags, cells[j])).is_some();
            assert_eq!(iso, sig[i] == sig[j]);
            if iso { same += 1 } else { different += 1 }
        }
    }
    assert!(same > 0 && different > 0, "{same} isomorphic pairs, {different} not");
}

/// The direct search for a known signature's start finds a start exactly when the
/// cell has that signature, and then the one that minimising over every start finds.
#[cfg_attr(not(qmesh_data), ignore = "needs the shared data folder ($QMESH_DATA)")]
#[test]
fn start_with_signature_is_the_minimising_start() {
    let Some(d) = common::data_dir() else { return };
    let (m, cells, flags) = randomly_split_cells(&d);
    let found: Vec<_> = cells.iter().map(|&c| volume_signature_from(&m, Surface::Cell, flags, c).unwrap()).collect();
    let (mut hits, mut misses) = (0, 0);
    for (i, (s, _, _)) in found.iter().enumerate().step_by(3) {
        let Signature::Volume(w) = s else { panic!("a v-signature") };
        for (j, &c) in cells.iter().enumerate() {
            let start = start_with_signature(&m, Surface::Cell, flags, c, w);
            assert_eq!(start.is_some(), found[j].0 == *s, "cells {i}, {j}");
            if found[j].0 == *s {
                assert_eq!(volume_shape(&m, Surface::Cell, flags, c), Some(signature_shape(w)), "an invariant");
            }
            if let Some(t) = start {
                assert_eq!(t, found[j].2, "cells {i}, {j}");
                hits += 1;
            } else {
                misses += 1;
            }
        }
    }
    assert!(hits > 10 && misses > 10, "{hits} hits, {misses} misses");
}

/// User marks: with `FlagRule::File`, the darts whose `.moka` g-dart carries an effective
/// mark of group 0 ((byte XOR mask) & used) are the pattern's flags.
#[test]
fn moka_marks_are_read_as_flags() {
    let mut m = CMap3::new();
    let v = common::unit_cube_vertices(&mut m, 0.0);
    m.make_hexahedron(v);
    let dir = common::temp_dir("mokaflags");
    let plain = dir.join("cube.moka");
    qmesh::io::write_map(&plain, &m, None, &Default::default()).unwrap();
    // Mark (byte 1, mask 0, used 1) the first g-dart of kept darts 0, 5 and 9.
    let text = std::fs::read_to_string(&plain).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[1] = "0 1 0 0 0 0 0 0".into();
    for k in [0usize, 5, 9] {
        let mut f: Vec<String> = lines[2 + 2 * k].split('\t').map(String::from).collect();
        f[4] = "1".into();
        lines[2 + 2 * k] = f.join("\t");
    }
    let marked = dir.join("marked.moka");
    std::fs::write(&marked, lines.join("\n") + "\n").unwrap();
    let p = load_pattern(&marked, FlagRule::File).unwrap();
    let flagged = p.map.darts().filter(|&d| p.map.is_marked(d, p.flags)).count();
    assert_eq!(flagged, 3);
    let q = load_pattern(&plain, FlagRule::File).unwrap();
    assert_ne!(p.signature, q.signature, "flags take part in the signature");
    assert_eq!(q.automorphisms, 24, "an unflagged cube boundary has the 24 rotations");
}

/// A pattern whose boundary is not one cycle (f) or one closed surface (v) is rejected
/// with a message saying so.
#[test]
fn patterns_with_split_boundaries_are_rejected() {
    let dir = common::temp_dir("badpatterns");
    let two_faces = dir.join("two.off");
    std::fs::write(&two_faces, "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n5 0 0\n6 0 0\n5 1 0\n3 0 1 2\n3 3 4 5\n").unwrap();
    let e = load_pattern(&two_faces, FlagRule::Corners).unwrap_err().to_string();
    assert!(e.contains("two.off") && e.contains("one cycle of 2-free darts"), "{e}");
    let two_tets = dir.join("two.vtk");
    std::fs::write(
        &two_tets,
        "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n\
         0 0 0 1 0 0 0 1 0 0 0 1 5 0 0 6 0 0 5 1 0 5 0 1\nCELLS 2 10\n4 0 1 2 3\n4 4 5 6 7\nCELL_TYPES 2\n10 10\n",
    )
    .unwrap();
    let e = load_pattern(&two_tets, FlagRule::Corners).unwrap_err().to_string();
    assert!(e.contains("two.vtk") && e.contains("one closed surface"), "{e}");
    let closed = dir.join("closed.moka");
    let mut m = CMap3::new();
    let v = common::unit_cube_vertices(&mut m, 0.0);
    m.make_hexahedron(v);
    qmesh::io::write_map(&closed, &m, None, &Default::default()).unwrap();
    assert!(load_pattern(&closed, FlagRule::Corners).is_ok(), "a single hexahedron is a valid v-pattern");
}

#[test]
fn word_from_stops_exactly_when_the_word_exceeds_its_bound() {
    use qmesh::build::{BuildOptions, CellKind, IndexedMesh, build_volume_map};
    use qmesh::signature::word_from;
    // A square pyramid: words from base darts and from side darts differ.
    let mut mesh = IndexedMesh::new();
    mesh.points = vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0.5, 0.5, 1.]];
    mesh.push_cell(CellKind::Pyramid, &[0, 1, 2, 3, 4], None);
    let (m, _) = build_volume_map(&mesh, &BuildOptions::default()).unwrap();
    let words: Vec<(qmesh::cmap::Dart, Vec<u32>)> =
        m.darts().map(|d| (d, word_from(&m, Surface::Cell, Flags::None, d, None).unwrap().word)).collect();
    let distinct: std::collections::BTreeSet<&Vec<u32>> = words.iter().map(|(_, w)| w).collect();
    assert!(distinct.len() >= 2, "the pyramid should give several words");
    for bound in &distinct {
        for (d, w) in &words {
            let got = word_from(&m, Surface::Cell, Flags::None, *d, Some(bound));
            assert_eq!(got.is_some(), w <= *bound, "start {d}: word {w:?}, bound {bound:?}");
            if let Some(g) = got {
                assert_eq!(&g.word, w, "a bound never changes the word it lets through");
            }
        }
    }
}
