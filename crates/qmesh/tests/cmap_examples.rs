//! The papers' hand-built examples and one test per operation, CGAL style:
//! precondition, operation, `is_valid()` after each step.

mod common;

use common::unit_cube_vertices;
use qmesh::cmap::{CMap3, Dart, MapError, Orbit};

fn assert_valid(m: &CMap3) {
    let v = m.is_valid();
    assert!(v.is_empty(), "invalid map: {}", v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join("; "));
}

/// Two unit cubes sharing the face x = 1 (vertex ids shared, not yet 3-sewn): the map,
/// the first cube's vertex ids and one dart of each cube.
fn two_cubes() -> (CMap3, [u32; 8], Dart, Dart) {
    let mut m = CMap3::new();
    let a = unit_cube_vertices(&mut m, 0.0);
    let far = unit_cube_vertices(&mut m, 1.0);
    let b = [a[1], far[1], far[2], a[2], a[5], far[5], far[6], a[6]];
    let c1 = m.make_hexahedron(a);
    let c2 = m.make_hexahedron(b);
    (m, a, c1, c2)
}

/// Finds the dart of `face_of` whose origin is `from` and target `to`.
fn dart_from_to(m: &CMap3, vol: Dart, from: u32, to: u32) -> Dart {
    m.orbit(vol, Orbit::Volume)
        .into_iter()
        .find(|&d| m.vertex_of(d) == from && m.vertex_of(m.next(d)) == to)
        .expect("no such dart")
}

/// 2022 Fig. 1: two cubes sharing a face, 48 darts; β0(a)=d, β1(a)=b, β2(a)=e, β3(a)=1.
#[test]
fn paper_2022_fig1_two_cubes() {
    let mut m = CMap3::new();
    let a = unit_cube_vertices(&mut m, 0.0);
    let mut b = [0u32; 8];
    // Second cube shares the face x = 1 (vertices 1, 2, 6, 5 of the first).
    let far = unit_cube_vertices(&mut m, 1.0);
    b[0] = a[1];
    b[3] = a[2];
    b[7] = a[6];
    b[4] = a[5];
    b[1] = far[1];
    b[2] = far[2];
    b[6] = far[6];
    b[5] = far[5];
    // Cells built on shared vertex ids are valid only once sewn (one orbit per id).
    let c1 = m.make_hexahedron(a);
    let c2 = m.make_hexahedron(b);
    assert_eq!(m.nb_darts(), 48);
    // a: the dart of cube 1 on the shared face (x = 1) running 2→1 (β1 turns clockwise
    // seen from outside); its β3 partner runs 1→2 in cube 2.
    let da = dart_from_to(&m, c1, a[2], a[1]);
    let partner = dart_from_to(&m, c2, a[1], a[2]);
    assert!(m.is_sewable3(da, partner));
    m.sew3(da, partner).unwrap();
    assert_valid(&m);
    assert_eq!(m.beta(da, 3), Some(partner)); // β3(a) = 1
    let (bb, dd, ee) = (m.beta(da, 1).unwrap(), m.beta(da, 0).unwrap(), m.beta(da, 2).unwrap());
    assert_eq!(m.vertex_of(bb), a[1]); // β1(a) = b continues the face
    assert_eq!(m.vertex_of(m.next(dd)), a[2]); // β0(a) = d ends where a starts
    assert_eq!((m.vertex_of(ee), m.vertex_of(m.next(ee))), (a[1], a[2])); // β2(a) = e: same edge, other face
    assert!(m.orbit(c1, Orbit::Volume).contains(&ee));
    let c = m.count_cells();
    assert_eq!((c.darts, c.vertices, c.edges, c.faces, c.volumes, c.components), (48, 12, 20, 11, 2, 1));
    assert_eq!(m.euler_characteristic(), 1);
    assert_eq!(m.boundary_faces(), 10);
    // Removing the shared face merges the cubes into one volume of 40 darts.
    m.remove_face(da).unwrap();
    assert_valid(&m);
    assert_eq!(m.count_cells().volumes, 1);
    assert_eq!(m.nb_darts(), 40);
}

/// 2025 Fig. 1: a prism sharing a triangle with a tetrahedron, 30 darts.
#[test]
fn paper_2025_fig1_prism_and_tet() {
    let mut m = CMap3::new();
    // VTK wedge: 0-1-2 normal points away from 3-4-5.
    let p =
        [[0., 0., 0.], [0., 1., 0.], [1., 0., 0.], [0., 0., 1.], [0., 1., 1.], [1., 0., 1.]].map(|q| m.add_vertex(q));
    let apex = m.add_vertex([0.3, 0.3, 2.0]);
    let prism = m.make_prism(p);
    // The tet sits on the top triangle 3-4-5; VTK tet 0-1-2 normal toward 3 (the apex, +z).
    let tet = m.make_tetrahedron([p[3], p[5], p[4], apex]);
    assert_eq!(m.nb_darts(), 30);
    assert_eq!(m.orbit(tet, Orbit::Volume).len(), 12);
    assert_eq!(m.orbit(prism, Orbit::Volume).len(), 18);
    let d1 = dart_from_to(&m, prism, p[3], p[4]);
    let d5 = dart_from_to(&m, tet, p[4], p[3]);
    m.sew3(d1, d5).unwrap();
    assert_valid(&m);
    // β1(1) = 2, β0(1) = 3, β2(3) = 4, β3(3) = 5 as in the figure.
    let d3 = m.prev(d1);
    assert_eq!(m.next(m.next(d1)), d3);
    let d4 = m.beta(d3, 2).unwrap();
    assert!(m.orbit(prism, Orbit::Volume).contains(&d4));
    let d5b = m.beta(d3, 3).unwrap();
    assert!(m.orbit(tet, Orbit::Volume).contains(&d5b));
    let c = m.count_cells();
    assert_eq!((c.vertices, c.edges, c.faces, c.volumes), (7, 12, 8, 2));
    assert_eq!(m.euler_characteristic(), 1);
}

#[test]
fn split_edge_across_two_cubes_keeps_marks_on_original_half() {
    let (mut m, a, c1, c2) = two_cubes();
    let da = dart_from_to(&m, c1, a[2], a[1]);
    m.sew3(da, dart_from_to(&m, c2, a[1], a[2])).unwrap();
    let flag = m.reserve_mark().unwrap();
    for d in m.darts().collect::<Vec<_>>() {
        m.mark(d, flag);
    }
    let edge = m.orbit(da, Orbit::Edge).len();
    assert_eq!(edge, 4); // two faces of each cube around the shared boundary edge
    let new = m.split_edge(da, 3).unwrap();
    assert_valid(&m);
    assert_eq!(new.len(), 2);
    assert_eq!(m.nb_darts(), 48 + 2 * edge);
    let p = m.point(new[0]);
    assert!((p[0] - 1.0).abs() + (p[1] - 2.0 / 3.0).abs() + p[2].abs() < 1e-12, "{p:?}");
    assert!(m.is_marked(da, flag));
    assert!(!m.is_marked(new[0], flag) && !m.is_marked(new[1], flag));
    let c = m.count_cells();
    assert_eq!((c.vertices, c.edges), (14, 22));
    assert_eq!(m.euler_characteristic(), 1);
    m.free_mark(flag);
}

#[test]
fn sew_unsew_and_errors() {
    let (mut m, a, c1, c2) = two_cubes();
    let da = dart_from_to(&m, c1, a[2], a[1]);
    let db = dart_from_to(&m, c2, a[1], a[2]);
    m.sew3(da, db).unwrap();
    assert!(matches!(m.sew3(da, db), Err(MapError::NotSewable { i: 3, .. })));
    m.unsew3(da).unwrap();
    assert_valid(&m);
    assert_eq!(m.count_cells().components, 2);
    assert_eq!(m.count_cells().vertices, 16);
    assert!(matches!(m.unsew3(da), Err(MapError::AlreadyFree(_, 3))));
    // The shared vertex ids were split: both cubes keep their own 8 vertices.
    m.sew3(da, db).unwrap();
    assert_valid(&m);
    assert_eq!(m.count_cells().vertices, 12);
    // unsew2/sew2 inside a volume.
    let o = m.beta(da, 2).unwrap();
    m.unsew2(da).unwrap();
    m.set_dimension(2); // temporarily an open structure; β3 sewn so validity reports it
    assert!(!m.is_valid().is_empty());
    m.set_dimension(3);
    m.sew2(da, o).unwrap();
    assert_valid(&m);
    // Removing a volume leaves the other one with a boundary face.
    let removed = m.remove_volume(c2).unwrap();
    assert_eq!(removed, 24);
    assert_valid(&m);
    assert_eq!(m.boundary_faces(), 6);
    assert!(matches!(m.remove_face(c1), Err(MapError::FaceOnBoundary(_))));
    let before = m.nb_darts();
    let map = m.compact();
    assert_valid(&m);
    assert_eq!(m.nb_darts(), before);
    assert_eq!(m.dart_capacity(), before + 1);
    assert_eq!(m.nb_vertex_ids(), 8);
    assert!(map.darts.iter().filter(|&&x| x != 0).count() == before);
}

#[test]
fn polyhedron_errors() {
    let mut m = CMap3::new();
    let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, 0., 0.])).collect();
    let open = [vec![v[0], v[1], v[2]], vec![v[1], v[0], v[3]]];
    assert!(matches!(m.make_polyhedron(&open), Err(MapError::OpenPolyhedron(..))));
    let flipped = [vec![v[0], v[1], v[2]], vec![v[0], v[1], v[3]], vec![v[2], v[1], v[3]], vec![v[0], v[2], v[3]]];
    assert!(matches!(m.make_polyhedron(&flipped), Err(MapError::NonManifoldPolyhedron(..))));
    assert_eq!(m.nb_darts(), 0);
}

#[test]
fn one_sew_keeps_beta13_involution() {
    // Build two triangles 3-sewn, 1-unsew an edge on one side and sew it back.
    let mut m = CMap3::new();
    let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i % 2) as f64, 0.])).collect();
    let t1 = m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    let w = m.add_vertex([0., 0., -1.]);
    let t2 = m.make_tetrahedron([v[0], v[2], v[1], w]);
    let p = dart_from_to(&m, t2, v[1], v[0]);
    m.sew3(t1, p).unwrap();
    assert_valid(&m);
    let n = m.next(t1);
    m.unsew1(t1).unwrap();
    m.sew1(t1, n).unwrap();
    assert_valid(&m);
    assert_eq!(m.count_cells().vertices, 5);
}

/// Mutation testing (scripts/mutants.sh core) found these rejection paths untested.
#[test]
fn sew1_and_sew2_refuse_exactly_what_they_document() {
    use qmesh::cmap::MapError;
    let mut m = CMap3::new();
    let v = m.add_vertex([0.0; 3]);
    let d: Vec<qmesh::cmap::Dart> = (0..6).map(|_| m.create_dart(v)).collect();
    // Both 3-free: sewn, and β0 is its inverse.
    m.sew1(d[0], d[1]).unwrap();
    assert_eq!((m.beta(d[0], 1), m.beta(d[1], 0)), (Some(d[1]), Some(d[0])));
    // β1(d1) taken, β0(d2) free — and the other way round: each alone refuses.
    assert!(matches!(m.sew1(d[0], d[2]), Err(MapError::NotSewable { i: 1, .. })));
    assert!(matches!(m.sew1(d[2], d[1]), Err(MapError::NotSewable { i: 1, .. })));
    // One of the two 3-sewn, the other not: refused.
    m.link(d[2], 3, d[3]);
    assert!(matches!(m.sew1(d[2], d[4]), Err(MapError::NotSewable { i: 1, .. })));
    assert!(matches!(m.sew1(d[4], d[2]), Err(MapError::NotSewable { i: 1, .. })));
    // Both 3-sewn but β3(d2) already 1-sewn: refused; when both images are free the
    // images are 1-sewn the other way.
    m.link(d[4], 3, d[5]);
    m.link(d[5], 1, d[1]);
    assert!(m.sew1(d[2], d[4]).is_err());
    m.unlink(d[5], 1);
    m.sew1(d[2], d[4]).unwrap();
    assert_eq!(m.beta(d[5], 1), Some(d[3]));
    // sew2: distinct and both 2-free, each condition on its own.
    let mut m = CMap3::new();
    let v = m.add_vertex([0.0; 3]);
    let e: Vec<qmesh::cmap::Dart> = (0..3).map(|_| m.create_dart(v)).collect();
    assert!(matches!(m.sew2(e[0], e[0]), Err(MapError::NotSewable { i: 2, .. })));
    m.sew2(e[0], e[1]).unwrap();
    assert!(matches!(m.sew2(e[0], e[2]), Err(MapError::NotSewable { i: 2, .. })));
    assert!(matches!(m.sew2(e[2], e[1]), Err(MapError::NotSewable { i: 2, .. })));
}

#[test]
fn is_sewable3_refuses_a_face_sewn_on_either_side() {
    let mut m = CMap3::new();
    let p: Vec<u32> = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [0., 0., -1.], [0., 0., 2.]]
        .iter()
        .map(|&x| m.add_vertex(x))
        .collect();
    let a = m.make_tetrahedron([p[0], p[1], p[2], p[3]]);
    let b = m.make_tetrahedron([p[0], p[2], p[1], p[4]]);
    let c = m.make_tetrahedron([p[0], p[2], p[1], p[5]]);
    let (b, c) = (m.prev(b), m.prev(c));
    assert!(m.is_sewable3(a, b));
    m.sew3(a, b).unwrap();
    // a is sewn, c is free: refused; c free and a sewn the other way round: refused.
    assert!(!m.is_sewable3(a, c));
    assert!(!m.is_sewable3(c, a));
}

#[test]
fn cycle_automorphisms_count_the_rotations_keeping_the_flags() {
    use qmesh::signature::cycle_automorphisms;
    let (t, f) = (true, false);
    assert_eq!(cycle_automorphisms(&[f, f, f, f]), 4);
    assert_eq!(cycle_automorphisms(&[t, t, t]), 3);
    assert_eq!(cycle_automorphisms(&[t, f, t, f]), 2);
    assert_eq!(cycle_automorphisms(&[t, f, f, f]), 1);
    assert_eq!(cycle_automorphisms(&[t, f, f, t, f, f]), 2);
    assert_eq!(cycle_automorphisms(&[t, t, f, t, f, f]), 1);
}

#[test]
fn validity_names_the_violation_and_its_darts_in_maps_over_65536_darts() {
    use qmesh::build::{BuildOptions, build_volume_map};
    use qmesh::cmap::Violation;
    // 30×30×4 hexahedra: 86,400 darts, two parallel chunks of local checks.
    let (mut m, _) = build_volume_map(&qmesh::generate::hex_grid(30, 30, 4), &BuildOptions::default()).unwrap();
    assert!(m.dart_capacity() > 70_000 && m.is_valid().is_empty());
    // One open edge in each chunk: each violation once, in dart order.
    let mut expected = Vec::new();
    let picked = [m.darts().find(|d| d.raw() > 70_000).unwrap(), m.darts().find(|d| d.raw() > 100).unwrap()];
    for d in picked {
        let e = m.beta(d, 2).unwrap();
        m.unlink(d, 2);
        expected.extend([d.raw(), e.raw()]);
    }
    expected.sort_unstable();
    let lo = expected[2];
    assert!(expected[1] < 65_536 && lo > 65_536, "{expected:?}");
    assert_eq!(m.is_valid(), expected.iter().map(|&dart| Violation::Beta2Free { dart }).collect::<Vec<_>>());
    assert_eq!(
        Violation::Beta2Free { dart: lo }.to_string(),
        format!("dart {lo}: β2 is free in a volume map (open volume)")
    );
}

#[test]
fn beta13_and_vertex_id_violations_are_reported_as_such() {
    use qmesh::cmap::Violation;
    let mut m = CMap3::new();
    let p: Vec<u32> = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [0., 0., -1.]]
        .iter()
        .map(|&x| m.add_vertex(x))
        .collect();
    let a = m.make_tetrahedron([p[0], p[1], p[2], p[3]]);
    let b = m.make_tetrahedron([p[0], p[2], p[1], p[4]]);
    let b = m.prev(b);
    m.sew3(a, b).unwrap();
    assert!(m.is_valid().is_empty());
    // β3 still an involution, but rotated by one around the face.
    let (a1, b1) = (a, m.beta(a, 3).unwrap());
    let (a2, b2) = (m.next(a), m.beta(m.next(a), 3).unwrap());
    m.link(a1, 3, b2);
    m.link(a2, 3, b1);
    let v = m.is_valid();
    assert!(v.iter().any(|x| matches!(x, Violation::Beta13NotInvolution { .. })), "{v:?}");
    assert!(v.iter().any(|x| matches!(x, Violation::VertexIdMismatch { .. })), "{v:?}");
    assert!(!v.iter().any(|x| matches!(x, Violation::NotInvolution { .. })), "{v:?}");
}

#[test]
fn local_violations_are_not_hidden_by_a_shared_vertex_id() {
    use qmesh::cmap::Violation;
    // Two separate tetrahedra on the same 4 vertex ids: two orbits per id …
    let mut m = CMap3::new();
    let p: Vec<u32> =
        [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]].iter().map(|&x| m.add_vertex(x)).collect();
    m.make_tetrahedron([p[0], p[1], p[2], p[3]]);
    let d = m.make_tetrahedron([p[0], p[1], p[2], p[3]]);
    let shared = m.is_valid();
    assert!(!shared.is_empty() && shared.iter().all(|x| matches!(x, Violation::VertexIdShared { .. })), "{shared:?}");
    // … and an open volume: the local violations come first, alone.
    m.unlink(d, 2);
    let v = m.is_valid();
    assert!(!v.is_empty() && v.iter().all(|x| matches!(x, Violation::Beta2Free { .. })), "{v:?}");
}

#[test]
fn a_free_beta1_and_a_broken_beta0_are_named_for_the_right_darts() {
    use qmesh::cmap::Violation;
    let mut m = CMap3::new();
    let p: Vec<u32> =
        [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]].iter().map(|&x| m.add_vertex(x)).collect();
    let a = m.make_tetrahedron([p[0], p[1], p[2], p[3]]);
    let (b, c) = (m.next(a), m.next(m.next(a)));
    // β1 of a unlinked: a has β1 free (β0 set), b has β0 free (β1 set).
    m.unlink(a, 1);
    let v = m.is_valid();
    assert!(v.contains(&Violation::Beta1Free { dart: a.raw() }), "{v:?}");
    assert!(v.contains(&Violation::Beta1Free { dart: b.raw() }), "{v:?}");
    m.link(a, 1, b);
    assert!(m.is_valid().is_empty());
    // a made a fixed point of β1: b keeps β0 = a although β1(a) ≠ b, and c keeps
    // β1 = a although β0(a) ≠ c (for each, one of the two inverse checks fails).
    m.link(a, 1, a);
    let v = m.is_valid();
    assert!(v.contains(&Violation::FixedPoint { dart: a.raw(), i: 1 }), "{v:?}");
    assert!(v.contains(&Violation::Beta0NotInverse { dart: b.raw() }), "{v:?}");
    assert!(v.contains(&Violation::Beta0NotInverse { dart: c.raw() }), "{v:?}");
}
