//! Tetrahedra → hexahedra recombination (2025 §7.1): every subdivision of the
//! hexahedron into tetrahedra is a query ([`hex_rules`]), all matched at once through
//! the prefix tree; matches are ranked by the scaled Jacobian of the hexahedron they
//! span, taken best first without overlap (§5.2.2), and each is replaced by one
//! volume. The shared diagonal of two recombined hexahedra (or of one on the boundary)
//! is then removed, so their common face becomes a quadrilateral.

use std::collections::BTreeMap;
use std::sync::OnceLock;
use std::time::Instant;

use rustc_hash::FxHashMap;

use super::hex_split::{HexRuleError, HexSplits, HexTarget, hex_rules};
use super::recombine_repair::{VolumeIds, repair_leftovers};
use crate::build::{CellKind, ExtractedKinds, IndexedMesh, classify_volume, extract_with, polyhedron_stream};
use crate::cmap::{BitSet, CMap3, Dart, Orbit};
use crate::modify::{Plan, execute};
use crate::query::{Match, MatchOptions, Metric, QuerySet, Selected, Strategy, find_matches, select_by_volumes};

/// The rules' queries and their prefix tree, and their targets, built once per
/// process; a target's modify plan is built the first time a match of it is replaced.
struct RuleBook {
    targets: Vec<HexTarget>,
    set: QuerySet,
    plans: Vec<OnceLock<Result<Plan, HexRuleError>>>,
}

impl RuleBook {
    fn plan(&self, rule: usize) -> Result<&Plan, &HexRuleError> {
        self.plans[rule].get_or_init(|| self.targets[rule].plan(&self.set.queries[rule])).as_ref()
    }
}

fn rule_book() -> Result<&'static RuleBook, &'static HexRuleError> {
    static BOOK: OnceLock<Result<RuleBook, HexRuleError>> = OnceLock::new();
    BOOK.get_or_init(|| {
        let (queries, targets): (Vec<_>, Vec<_>) = hex_rules()?.into_iter().map(|r| (r.query, r.target)).unzip();
        let plans = targets.iter().map(|_| OnceLock::new()).collect();
        Ok(RuleBook { targets, set: QuerySet::new(queries), plans })
    })
    .as_ref()
}

/// Options of [`recombine`].
#[derive(Clone, Copy, Debug)]
pub struct RecombineOptions {
    /// `Best` (the paper's: decreasing scaled Jacobian) or `Greedy` (start-dart order).
    pub strategy: Strategy,
    /// Matches whose hexahedron has a scaled Jacobian at or below this are dropped.
    pub min_quality: f64,
    /// After the selection, repair it where tetrahedra are left: search nodes per
    /// candidate in all (0: keep the best-first selection as it is; default 0.25).
    pub repair_effort: f64,
}

impl Default for RecombineOptions {
    fn default() -> Self {
        RecombineOptions { strategy: Strategy::Best, min_quality: 0.0, repair_effort: 0.25 }
    }
}

/// What [`recombine`] did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct RecombineReport {
    pub tets_in: usize,
    /// Queries in the prefix tree (oriented subdivision classes).
    pub queries: usize,
    /// Matches found above the quality threshold (the paper's #Q), one per set of darts.
    pub matches: usize,
    /// Matches of any quality (before the threshold).
    pub candidates: usize,
    /// Symbols checked while matching (the prefix-tree walk's work).
    pub steps: u64,
    pub hexes: usize,
    pub tets_left: usize,
    /// Hexahedron faces still split in two triangles because tetrahedra are on the other side.
    pub hex_tet_interfaces: usize,
    /// Hexahedra with at least one such face.
    pub hexes_with_tet_faces: usize,
    /// Enumerating the subdivisions and realising them (once per process).
    pub catalogue_seconds: f64,
    /// Compiling the rules and their prefix tree (once per process).
    pub rules_seconds: f64,
    pub query_seconds: f64,
    pub select_seconds: f64,
    /// Repairs of the selection where it left tetrahedra over (each drops some
    /// hexahedra and takes more tetrahedra in others).
    pub repairs: usize,
    /// Tetrahedra left over by the selection that the repairs put in hexahedra.
    pub repaired_tets: usize,
    pub replace_seconds: f64,
    pub quality_min: Option<f64>,
    pub quality_mean: Option<f64>,
    /// Matches used per subdivision class (index up to the cube's 48 symmetries).
    pub by_class: BTreeMap<usize, usize>,
    /// Matches used per number of tetrahedra.
    pub by_tet_count: BTreeMap<usize, usize>,
}

/// The hexahedra made by [`recombine`]: corners (vertex ids, VTK order) and a dart of
/// each one's volume.
#[derive(Clone, Debug, Default)]
pub struct Recombined {
    pub corners: Vec<[u32; 8]>,
    pub darts: Vec<Dart>,
}

/// Recombines the tetrahedra of `map` into hexahedra in place.
///
/// ```
/// use qmesh::apps::{RecombineOptions, SplitChoice, TetrahedralizeOptions, recombine, tetrahedralize};
/// use qmesh::build::{BuildOptions, build_volume_map};
/// let grid = qmesh::generate::hex_grid(3, 2, 2);
/// let (tets, _) = tetrahedralize(&grid, &TetrahedralizeOptions { choice: SplitChoice::Any, seed: 7 }).unwrap();
/// let (mut map, _) = build_volume_map(&tets, &BuildOptions::default()).unwrap();
/// let (report, _) = recombine(&mut map, &RecombineOptions::default()).unwrap();
/// assert_eq!((report.hexes, report.tets_left, report.hex_tet_interfaces), (12, 0, 0));
/// assert!(map.is_valid().is_empty());
/// ```
///
/// # Errors
/// Only if the built-in rules cannot be built (a defect of qmesh).
pub fn recombine(
    map: &mut CMap3,
    opts: &RecombineOptions,
) -> Result<(RecombineReport, Recombined), &'static HexRuleError> {
    let t = Instant::now();
    let splits = HexSplits::get();
    let catalogue_seconds = t.elapsed().as_secs_f64();
    let book = rule_book()?;
    let rules_seconds = t.elapsed().as_secs_f64() - catalogue_seconds;
    let t = Instant::now();
    let volumes = VolumeIds::of(map);
    let mut report = RecombineReport {
        tets_in: volumes.first_dart.iter().filter(|&&d| classify_volume(map, d) == CellKind::Tet).count(),
        queries: book.targets.len(),
        catalogue_seconds,
        rules_seconds,
        ..Default::default()
    };
    let metric = Metric::HexQuality;
    let found = find_matches(
        map,
        &book.set,
        &MatchOptions {
            metric: Some(&metric),
            min_hex_quality: Some(opts.min_quality),
            volume_of: Some(&volumes.of_dart),
            ..Default::default()
        },
    );
    report.candidates = found.matches.len();
    report.steps = found.steps;
    // The matching dropped every hexahedron at or below the threshold already.
    debug_assert!(found.matches.iter().all(|m| m.score > opts.min_quality));
    let candidates = found.matches;
    report.matches = candidates.len();
    report.query_seconds = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let nb_volumes = volumes.first_dart.len();
    let mut chosen = select_by_volumes(&candidates, &found.volumes, nb_volumes, opts.strategy);
    if opts.repair_effort > 0.0 {
        let repaired =
            repair_leftovers(map, &book.set, &candidates, &found.volumes, &volumes, &mut chosen, opts.repair_effort);
        (report.repairs, report.repaired_tets) = (repaired.repairs, repaired.tets);
    }
    report.select_seconds = t.elapsed().as_secs_f64();
    // The candidates are not needed any more: free them before the map grows.
    let chosen: Vec<Match> = chosen.into_iter().map(|i| candidates[i]).collect();
    drop((candidates, found.volumes, volumes));
    let mut annot = book.set.annotator();
    let chosen: Vec<Selected> =
        chosen.into_iter().map(|m| Selected { m, darts: book.set.darts_of(map, &m, &mut annot) }).collect();

    let t = Instant::now();
    let mut out = Recombined::default();
    let mut qualities = Vec::with_capacity(chosen.len());
    for s in &chosen {
        let rule = &book.targets[s.m.query as usize];
        out.corners.push(rule.corners.map(|l| map.vertex_of(s.darts[l as usize - 1])));
        out.darts.push(s.darts[rule.keep as usize - 1]);
        qualities.push(s.m.score);
        execute(map, book.plan(s.m.query as usize)?, &s.darts);
        let o = &splits.oriented[rule.oriented];
        *report.by_class.entry(o.class).or_insert(0) += 1;
        *report.by_tet_count.entry(o.tets.len()).or_insert(0) += 1;
    }
    // Faces between two hexahedra (or on the boundary) lose their diagonal; a face
    // against tetrahedra keeps it, and so does a pair of triangles that lie in two
    // faces of the hexahedron on the other side.
    let mut diagonal = BitSet::with_len(map.dart_capacity());
    for s in &chosen {
        for l in book.targets[s.m.query as usize].diagonals.iter().flatten() {
            diagonal.insert(s.darts[*l as usize - 1].idx());
        }
    }
    let mut with_tet_faces = vec![false; chosen.len()];
    for (i, s) in chosen.iter().enumerate() {
        for [a, _] in book.targets[s.m.query as usize].diagonals {
            let d = s.darts[a as usize - 1];
            if !map.is_live(d) {
                continue; // removed from the other side
            }
            let other_side_hex = map.beta(d, 3).is_none_or(|x| diagonal.get(x.idx()));
            if !other_side_hex || map.remove_edge(d).is_err() {
                report.hex_tet_interfaces += 1;
                with_tet_faces[i] = true;
            }
        }
    }
    report.replace_seconds = t.elapsed().as_secs_f64();
    report.hexes = chosen.len();
    report.hexes_with_tet_faces = with_tet_faces.iter().filter(|&&b| b).count();
    report.tets_left = report.tets_in - report.by_tet_count.iter().map(|(n, c)| n * c).sum::<usize>();
    if !qualities.is_empty() {
        report.quality_min = qualities.iter().copied().reduce(f64::min);
        report.quality_mean = Some(qualities.iter().sum::<f64>() / qualities.len() as f64);
    }
    Ok((report, out))
}

/// The cells of a recombined map: tetrahedra, hexahedra whose six faces are
/// quadrilaterals, and the hexahedra that still meet tetrahedra on a split face,
/// written as hexahedra (the tets' triangles then hang on their quads) or, with
/// `conformal`, as VTK polyhedra keeping those triangles (exactly conformal).
pub fn recombined_mesh(map: &CMap3, hexes: &Recombined, conformal: bool) -> (IndexedMesh, ExtractedKinds) {
    let corners_of: FxHashMap<Dart, usize> = hexes.darts.iter().enumerate().map(|(i, &d)| (d, i)).collect();
    extract_with(map, |map, d, walker| {
        if !conformal {
            let found = walker.collect(map, d, Orbit::Volume).iter().find_map(|x| corners_of.get(x).copied());
            if let Some(i) = found {
                return (CellKind::Hex, hexes.corners[i].to_vec());
            }
        }
        polyhedron_stream(map, d, walker)
    })
}
