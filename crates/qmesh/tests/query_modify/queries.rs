//! What a compiled query knows about itself: its size limit, its reach, its corners,
//! whether it has an affine fit, and the metrics that score its matches.

use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::{CMap3, Dart};
use qmesh::generate::hex_grid;
use qmesh::query::{
    Annotator, Condition, MAX_QUERY_DARTS, MatchOptions, Metric, Query, QueryError, QuerySet, Separation, Strategy,
    find_matches,
};

fn grid(x: usize, y: usize, z: usize) -> CMap3 {
    build_volume_map(&hex_grid(x, y, z), &BuildOptions::default()).unwrap().0
}

fn query(map: CMap3) -> Query {
    Query::new("q", map, |_| Condition::Any).unwrap()
}

/// An open polygon of `n` darts (1-sewn only): not a query, but sized to the dart.
fn polygon(n: usize) -> CMap3 {
    let mut m = CMap3::new();
    m.set_dimension(2);
    let v: Vec<u32> = (0..n).map(|i| m.add_vertex([(i as f64).cos(), (i as f64).sin(), 0.0])).collect();
    m.make_polygon(&v);
    m
}

#[test]
fn the_size_limit_is_exactly_max_query_darts() {
    let at_limit = Query::new("big", polygon(MAX_QUERY_DARTS), |_| Condition::Any).unwrap_err();
    assert!(matches!(at_limit, QueryError::Free { beta: 2, .. }), "{at_limit}");
    let over = Query::new("big", polygon(MAX_QUERY_DARTS + 1), |_| Condition::Any).unwrap_err();
    assert_eq!(over, QueryError::TooLarge(MAX_QUERY_DARTS + 1));
    assert!(over.to_string().contains(&format!("at most {MAX_QUERY_DARTS}")), "{over}");
}

#[test]
fn reach_counts_faces_crossed_from_the_start_volume() {
    // A row of three cells: from an end cell the far end is two faces away, from the
    // middle one face.
    let row = grid(3, 1, 1);
    let end = row.darts().find(|&d| row.point(d)[0] == 0.0).unwrap();
    let middle = row.darts().find(|&d| row.point(d)[0] == 1.0 && row.point(row.next(d))[0] == 2.0).unwrap();
    let from = |d: Dart| Query::from_start("row", row.clone(), d, |_| Condition::Any).unwrap().reach();
    assert_eq!((from(end), from(middle)), (2, 1));
    assert_eq!(query(grid(1, 1, 1)).reach(), 0);
    let block = query(grid(2, 2, 2));
    assert_eq!((block.nb_volumes(), block.labelling().len(), block.labelling().is_empty()), (8, 8 * 24, false));
}

/// A hexahedron squashed flat (every z = 0): its vertices span a plane only.
fn flat_hex() -> CMap3 {
    let mut mesh = hex_grid(1, 1, 1);
    mesh.points.iter_mut().for_each(|p| p[2] = 0.0);
    build_volume_map(&mesh, &BuildOptions::default()).unwrap().0
}

#[test]
fn flat_queries_have_no_corners_nor_affine_fit_until_corners_are_given() {
    let cube = query(grid(1, 1, 1));
    assert!(cube.has_affine_fit());
    let corners = cube.corners.expect("a unit cube spans a hexahedron");
    let mut flat = query(flat_hex());
    assert!(!flat.has_affine_fit());
    assert_eq!(flat.corners, None);
    // Without corners the hex quality of a match is unknown, and the metric says −1.
    let input = grid(1, 1, 1);
    let mut a = Annotator::new(24);
    assert!(a.annotate(&input, &flat.word, input.darts().next().unwrap(), None));
    assert_eq!(flat.matched_hex_quality(&input, a.matched_raw()), None);
    assert_eq!(Metric::HexQuality.evaluate(&input, &flat, a.matched_raw()), -1.0);
    // Corners given (the cube's labels: both are labelled alike from their first
    // dart) read the input's hexahedron, a perfect one.
    flat.set_corners(corners);
    assert_eq!(flat.corners, Some(corners));
    let q = flat.matched_hex_quality(&input, a.matched_raw()).expect("corners set");
    assert!((q - 1.0).abs() < 1e-12, "{q}");
    assert!((Metric::HexQuality.evaluate(&input, &flat, a.matched_raw()) - 1.0).abs() < 1e-12);
}

#[test]
fn strategies_and_separations_parse_by_name() {
    for (name, strategy) in [("greedy", Strategy::Greedy), ("best", Strategy::Best), ("random", Strategy::Random(7))] {
        assert_eq!(Strategy::parse(name, 7), Some(strategy));
        assert_eq!(strategy.name(), name);
    }
    assert_eq!(Strategy::parse("first", 7), None);
    assert_eq!(Separation::parse("darts"), Some(Separation::Darts));
    assert_eq!(Separation::parse("vertices"), Some(Separation::Vertices));
    assert_eq!(Separation::parse("faces"), None);
    for c in Condition::ALL {
        assert_eq!(Condition::parse(c.symbol()), Some(c), "{}", c.symbol());
        assert_eq!(Condition::parse(c.name()), Some(c), "{}", c.name());
        assert!(c.name().is_ascii());
    }
    assert_eq!(Condition::parse(" any "), Some(Condition::Any));
    assert_eq!(Condition::parse("all"), None);
    // A word reads dart by dart, β1, β2, β3 each: a lone cube with `ε` everywhere has
    // 24 darts and 24 `ε`.
    let lone = Query::new("lone", grid(1, 1, 1), |_| Condition::Boundary).unwrap();
    let text = lone.word.display();
    assert!(text.starts_with("⟨2,") && text.ends_with(",ε⟩"), "{text}");
    assert_eq!((text.matches(" | ").count(), text.matches('ε').count()), (23, 24), "{text}");
}

#[test]
fn metrics_parse_by_name_and_print_it() {
    for (text, name) in [("hex-quality", "hex-quality"), ("scaled-jacobian", "hex-quality"), ("volume", "volume")] {
        let m = Metric::parse(text).unwrap_or_else(|| panic!("{text} is a metric"));
        assert_eq!((m.name(), format!("{m:?}")), (name, name.to_string()));
    }
    assert!(Metric::parse("quality").is_none());
    let custom = Metric::Custom(std::sync::Arc::new(|_: &CMap3, q: &Query, _: &[u32]| q.nb_darts() as f64));
    assert_eq!(custom.name(), "custom");
    let (input, cube) = (grid(2, 1, 1), query(grid(1, 1, 1)));
    let mut a = Annotator::new(24);
    assert!(a.annotate(&input, &cube.word, input.darts().next().unwrap(), None));
    assert_eq!(custom.evaluate(&input, &cube, a.matched_raw()), 24.0);
    let v = Metric::Volume.evaluate(&input, &cube, a.matched_raw());
    assert!((v - 1.0).abs() < 1e-12, "{v}");
}

/// `min_hex_quality` checks corners during the walk (corner guards) and each match at
/// its end: the matches are those of a plain search whose hexahedron is above the
/// threshold. 140 queries (three bitset words): cubes with their corners (even
/// indices) and cubes with `ε` on their last dart and mirrored corners (odd), an
/// inverted hexahedron that no match may keep.
#[test]
fn min_hex_quality_keeps_the_matches_above_it_among_many_queries() {
    let mut mesh = hex_grid(3, 3, 1);
    mesh.points.iter_mut().filter(|p| **p == [1.0, 1.0, 1.0]).for_each(|p| *p = [1.6, 1.6, 1.4]);
    let g = build_volume_map(&mesh, &BuildOptions::default()).unwrap().0;
    let cube = query(grid(1, 1, 1));
    let c = cube.corners.unwrap();
    let mut mirrored = cube.clone();
    let last = mirrored.labelling().darts[23];
    mirrored.set_conditions(|d| if d == last { Condition::Boundary } else { Condition::Any });
    mirrored.set_corners([c[4], c[5], c[6], c[7], c[0], c[1], c[2], c[3]]);
    let set = QuerySet::new((0..140).map(|i| if i % 2 == 0 { cube.clone() } else { mirrored.clone() }).collect());
    let t = 0.5;
    let guarded = find_matches(&g, &set, &MatchOptions { min_hex_quality: Some(t), ..Default::default() });
    let plain = find_matches(&g, &set, &MatchOptions::default());
    let mut a = set.annotator();
    let quality = |m: &qmesh::query::Match, a: &mut Annotator| {
        let raw: Vec<u32> = set.darts_of(&g, m, a).iter().map(|d| d.raw()).collect();
        set.queries[m.query as usize].matched_hex_quality(&g, &raw).unwrap()
    };
    let above: Vec<(u32, Dart)> =
        plain.matches.iter().filter(|m| quality(m, &mut a) > t).map(|m| (m.query, m.start)).collect();
    let kept: Vec<(u32, Dart)> = guarded.matches.iter().map(|m| (m.query, m.start)).collect();
    assert_eq!(kept, above);
    // Three of the four cells around the moved vertex fall to 0.5 or below, the other
    // six cells do not; no mirrored cube is kept.
    let per_query = &guarded.per_query;
    assert!((0..140).all(|q| per_query[q] == if q % 2 == 0 { 6 } else { 0 }), "{per_query:?}");
    assert!(guarded.steps <= plain.steps);
}

/// A consumed dart counts as ∅ (2025 §5.2.2) even as the start: a lone cube with one
/// dart consumed has no match, from that dart or from any other.
#[test]
fn a_consumed_start_dart_starts_no_match() {
    let cube = grid(1, 1, 1);
    let set = QuerySet::new(vec![query(grid(1, 1, 1))]);
    assert_eq!(find_matches(&cube, &set, &MatchOptions::default()).matches.len(), 1);
    let mut consumed = qmesh::cmap::BitSet::with_len(cube.dart_capacity());
    consumed.insert(cube.darts().next().unwrap().idx());
    let r = find_matches(&cube, &set, &MatchOptions { consumed: Some(&consumed), ..Default::default() });
    assert!(r.matches.is_empty(), "{:?}", r.matches);
}
