//! The query-replace pipeline (2022 §4, §5): split every edge (e-pattern), then replace
//! every face matching an f-pattern, then every volume matching a v-pattern. Each cell
//! is replaced at most once, so the result does not depend on the order.

use std::time::Instant;

use super::face::align_face;
use super::lookup_memo;
use super::plans::Plans;
use crate::cmap::{CMap3, Dart, MapError, Orbit};
use crate::modify::{DisjointExecutor, FacePattern};
use crate::pattern::{FlagRule, PatternKind, PatternSet, flag_corners_on};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use crate::geom::centroid;
use crate::signature::{
    Flags, Signature, Surface, VolumeWord, face_signature, match_direct, start_with_signature, volume_signature_from,
    word_from,
};

/// Cells looked up in parallel before their replacements are applied (bounds the
/// memory of the pending matches).
pub const LOOKUP_CHUNK: usize = 4096;

/// Options of [`query_replace`].
#[derive(Clone, Copy, Debug)]
pub struct ReplaceOptions {
    /// Split every edge into this many segments first (the e-pattern).
    pub split_edges: Option<usize>,
    /// Flags on the input: `Corners` flags every original dart (edge splits add unflagged darts).
    pub flags: FlagRule,
    /// Look patterns up by signature (hash map) rather than testing each one directly.
    pub use_signatures: bool,
}

impl Default for ReplaceOptions {
    fn default() -> Self {
        ReplaceOptions { split_edges: None, flags: FlagRule::Corners, use_signatures: true }
    }
}

/// What [`query_replace`] did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct ReplaceReport {
    pub edges_split: usize,
    /// Matches per pattern (indices of the set).
    pub matches: Vec<usize>,
    pub faces_replaced: usize,
    pub volumes_replaced: usize,
    pub unmatched_faces: usize,
    pub unmatched_volumes: usize,
    pub query_seconds: f64,
    /// Replacing, edge splits included.
    pub replace_seconds: f64,
    /// Of `replace_seconds`, splitting the edges (the e-pattern).
    pub split_seconds: f64,
    /// Configurations no pattern matched (2022 §6.4 coverage), most frequent first.
    #[serde(skip)]
    pub uncovered: Vec<Uncovered>,
    /// One dart of each volume a v-pattern created, with the pattern's index (for a
    /// `pattern_id` cell array; see [`crate::build::volume_values`]).
    #[serde(skip)]
    pub created_volumes: Vec<(Dart, u32)>,
    /// For each of `created_volumes`, the index in the replaced `volumes` of the volume
    /// it came from.
    #[serde(skip)]
    pub created_from: Vec<u32>,
}

/// A configuration (face or volume boundary) that no pattern matched.
#[derive(Clone, Debug)]
pub struct Uncovered {
    pub kind: PatternKind,
    pub signature: Signature,
    /// How many cells have it.
    pub count: usize,
    /// The centroid of one such cell.
    pub sample: [f64; 3],
}

/// Collects unmatched configurations by signature.
#[derive(Default)]
struct Coverage(FxHashMap<(PatternKind, Signature), (usize, [f64; 3])>);

impl Coverage {
    fn add(&mut self, map: &CMap3, kind: PatternKind, signature: Signature, d: Dart) {
        let orbit = if kind == PatternKind::Face { Orbit::HalfFace } else { Orbit::Volume };
        let e = self
            .0
            .entry((kind, signature))
            .or_insert_with(|| (0, centroid(map.orbit(d, orbit).iter().map(|&x| map.point(x)))));
        e.0 += 1;
    }

    fn into_list(self) -> Vec<Uncovered> {
        let mut v: Vec<Uncovered> = self
            .0
            .into_iter()
            .map(|((kind, signature), (count, sample))| Uncovered { kind, signature, count, sample })
            .collect();
        v.sort_by(|a, b| b.count.cmp(&a.count).then_with(|| a.signature.cmp(&b.signature)));
        v
    }
}

/// Runs the e, f and v query-replace passes on `map` with the patterns of `set`.
///
/// # Errors
/// Only from the edge split (k = 0).
pub fn query_replace(map: &mut CMap3, set: &PatternSet, opts: &ReplaceOptions) -> Result<ReplaceReport, MapError> {
    let mark = map.reserve_mark()?;
    match opts.flags {
        FlagRule::Corners | FlagRule::File => {
            for d in map.darts().collect::<Vec<_>>() {
                map.mark(d, mark);
            }
        }
        FlagRule::Geometric => {
            for v in map.cells(Orbit::Volume).collect::<Vec<_>>() {
                let darts = map.orbit(v, Orbit::Volume);
                flag_corners_on(map, mark, &darts, false, Surface::Cell);
            }
        }
        FlagRule::None => {}
    }
    let t = Instant::now();
    let edges_split = match opts.split_edges {
        Some(k) => map.split_all_edges(k)?,
        None => 0,
    };
    let split_seconds = t.elapsed().as_secs_f64();
    let faces: Vec<Dart> = map.cells(Orbit::Face).collect();
    let volumes: Vec<Dart> = map.cells(Orbit::Volume).collect();
    let mut r = replace_cells(map, set, Flags::Mark(mark), &faces, &volumes, opts.use_signatures);
    r.edges_split = edges_split;
    r.replace_seconds += split_seconds;
    r.split_seconds = split_seconds;
    map.free_mark(mark);
    Ok(r)
}

/// The f and v passes of query-replace restricted to the given faces and volumes (one
/// dart each), with the caller's flags: what the applications use (2022 §7), which
/// split edges and set flags themselves. List each face once (either side): a face
/// shared by two volumes is replaced on both sides at once; and each volume once.
///
/// Replacing a face leaves every other face's cycle and flags as they were, and
/// replacing a volume every other volume's boundary, so the patterns are looked up on
/// all cores, [`LOOKUP_CHUNK`] cells at a time, then applied in the order given: the
/// same map as one cell at a time, whatever the number of threads.
pub fn replace_cells(
    map: &mut CMap3,
    set: &PatternSet,
    flags: Flags,
    faces: &[Dart],
    volumes: &[Dart],
    use_signatures: bool,
) -> ReplaceReport {
    let mut r = ReplaceReport { matches: vec![0; set.patterns.len()], ..Default::default() };
    let mut coverage = Coverage::default();
    let has = |k: PatternKind| set.count(k) > 0;
    if has(PatternKind::Face) {
        // Each pattern's plans are made once, when it first matches (on any core).
        let plans = Plans::of(set);
        let plan = |i: usize| plans.face(set, i);
        let mut executor = DisjointExecutor::reuse();
        for chunk in faces.chunks(LOOKUP_CHUNK) {
            let t = Instant::now();
            // The match and its job (the darts across read too), on all cores.
            let found = on_cores(chunk, |d| {
                find_face(map, set, flags, d, use_signatures)
                    .map(|(i, aligned)| (i, plan(i).map(|p| p.job_on(FacePattern::both_sides(map, aligned)))))
            });
            r.query_seconds += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let mut jobs = Vec::with_capacity(chunk.len());
            for (&d, found) in chunk.iter().zip(found) {
                match found {
                    Some((i, job)) => {
                        jobs.extend(job);
                        r.matches[i] += 1;
                        r.faces_replaced += 1;
                    }
                    None => {
                        r.unmatched_faces += 1;
                        coverage.add(map, PatternKind::Face, face_signature(map, flags, d), d);
                    }
                }
            }
            executor.execute(map, &jobs);
            r.replace_seconds += t.elapsed().as_secs_f64();
        }
        executor.recycle();
    }
    if has(PatternKind::Volume) {
        let plans = Plans::of(set);
        let plan = |i: usize| plans.volume(set, i);
        let mut executor = DisjointExecutor::reuse();
        for (c, chunk) in volumes.chunks(LOOKUP_CHUNK).enumerate() {
            let t = Instant::now();
            // The match and its job, which follows the traversal from the match's start.
            let found = on_cores(chunk, |d| {
                find_volume_then(map, set, flags, d, use_signatures, |from_d, i, start| match from_d {
                    Some(w) if w.darts.first() == Some(&start) => Some((i, plan(i)?.job_following(w)?)),
                    _ => Some((i, plan(i)?.job(word_from(map, Surface::Cell, flags, start, None)?)?)),
                })
            });
            r.query_seconds += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let (mut jobs, mut used) = (Vec::with_capacity(chunk.len()), Vec::with_capacity(chunk.len()));
            for (k, (&d, found)) in chunk.iter().zip(found).enumerate() {
                match found {
                    Some((i, job)) => {
                        r.matches[i] += 1;
                        r.volumes_replaced += 1;
                        jobs.push(job);
                        used.push((i, (c * LOOKUP_CHUNK + k) as u32));
                    }
                    None => {
                        r.unmatched_volumes += 1;
                        if let Some((s, _, _)) = volume_signature_from(map, Surface::Cell, flags, d) {
                            coverage.add(map, PatternKind::Volume, s, d);
                        }
                    }
                }
            }
            let created = executor.execute(map, &jobs);
            let made: usize = used.iter().map(|&(i, _)| plan(i).map_or(0, |p| p.volume_starts.len())).sum();
            r.created_volumes.reserve(made);
            r.created_from.reserve(made);
            let mut first = 0;
            for (&(i, from), job) in used.iter().zip(&jobs) {
                let starts = &plan(i).expect("a job has a plan").volume_starts;
                r.created_volumes.extend(starts.iter().map(|&k| (created[first + k as usize], i as u32)));
                r.created_from.extend(starts.iter().map(|_| from));
                first += job.plan.new_darts.len();
            }
            r.replace_seconds += t.elapsed().as_secs_f64();
        }
        executor.recycle();
    }
    r.uncovered = coverage.into_list();
    r
}

/// `f` of every dart of `cells`, in order, on all cores (on this one for a few cells,
/// where handing them out costs more than looking them up), 32 cells a piece, so that
/// no core is left alone with a large piece at the end.
fn on_cores<T: Send>(cells: &[Dart], f: impl Fn(Dart) -> T + Sync) -> Vec<T> {
    if cells.len() < 64 {
        cells.iter().map(|&d| f(d)).collect()
    } else {
        cells.par_iter().with_max_len(32).map(|&d| f(d)).collect()
    }
}

/// The f-pattern matching the face of `d` (either side when it is 3-sewn) and the
/// target darts aligned with its boundary.
pub fn find_face(
    map: &CMap3,
    set: &PatternSet,
    flags: Flags,
    d: Dart,
    by_signature: bool,
) -> Option<(usize, Vec<Dart>)> {
    let sides = [Some(d), map.beta(d, 3)];
    if by_signature {
        return sides.into_iter().flatten().find_map(|side| find_face_by_memo(map, set, flags, side));
    }
    for side in sides.into_iter().flatten() {
        let candidates: Vec<usize> = if by_signature {
            set.lookup_index(&face_signature(map, flags, side)).into_iter().collect()
        } else {
            (0..set.patterns.len()).filter(|&i| set.patterns[i].kind == PatternKind::Face).collect()
        };
        for i in candidates {
            if let Some(aligned) = align_face(map, flags, side, &set.patterns[i]) {
                return Some((i, aligned));
            }
        }
    }
    None
}

/// The f-pattern of the half-face of `side` by its signature, and its darts aligned
/// with the pattern's boundary cycle: remembered per thread by the flags around it.
fn find_face_by_memo(map: &CMap3, set: &PatternSet, flags: Flags, side: Dart) -> Option<(usize, Vec<Dart>)> {
    let mut darts: smallvec::SmallVec<[Dart; 16]> = smallvec::smallvec![side];
    let mut x = map.next(side);
    while x != side {
        darts.push(x);
        x = map.next(x);
    }
    let look_up = || {
        let i = set.lookup_index(&face_signature(map, flags, side))?;
        let aligned = align_face(map, flags, side, &set.patterns[i])?;
        let s = darts.iter().position(|&x| x == aligned[0]).expect("aligned darts are the face's");
        Some((i as u32, s as u32))
    };
    let found = if darts.len() <= 64 {
        let bits = darts.iter().enumerate().fold(0u64, |b, (k, &x)| b | (u64::from(flags.get(map, x)) << k));
        lookup_memo::face(set, (darts.len() as u32, bits), look_up)
    } else {
        look_up()
    };
    let (i, s) = found?;
    let k = darts.len();
    Some((i as usize, (0..k).map(|j| darts[(s as usize + j) % k]).collect()))
}

/// The v-pattern matching the volume of `d`, and the target dart corresponding to the
/// pattern's canonical start.
pub fn find_volume(map: &CMap3, set: &PatternSet, flags: Flags, d: Dart, by_signature: bool) -> Option<(usize, Dart)> {
    find_volume_then(map, set, flags, d, by_signature, |_, i, start| Some((i, start)))
}

/// [`find_volume`], then `then(from_d, pattern, start)`, where `from_d` is the traversal
/// from `d` that named the configuration when patterns are looked up by signature (the
/// traversal from the start itself when the start is `d`: a replacement that follows it
/// need not walk the volume again).
fn find_volume_then<R>(
    map: &CMap3,
    set: &PatternSet,
    flags: Flags,
    d: Dart,
    by_signature: bool,
    then: impl FnOnce(Option<&VolumeWord>, usize, Dart) -> Option<R>,
) -> Option<R> {
    if by_signature {
        // One traversal from d names the configuration (see `lookup_memo`).
        return lookup_memo::with_word(map, flags, d, |from_d, word| {
            let darts = &from_d.darts;
            if let Some(found) = lookup_memo::recall(set, word) {
                return found.and_then(|(i, at)| then(Some(from_d), i as usize, darts[at as usize]));
            }
            // Only patterns of the volume's shape can match; when one signature has it,
            // its start is found directly (the same start as by minimising, see
            // `start_with_signature`).
            let n = darts.len();
            let shape = (n, word[2 * n..].iter().filter(|&&b| b == 1).count());
            let found = match set.volume_candidates(shape) {
                [] => None,
                &[i] => match &set.patterns[i].signature {
                    Signature::Volume(s) => start_with_signature(map, Surface::Cell, flags, d, s).map(|s| (i, s)),
                    Signature::Face(_) => None,
                },
                _ => volume_signature_from(map, Surface::Cell, flags, d)
                    .and_then(|(sig, _, start)| set.lookup_index(&sig).map(|i| (i, start))),
            };
            let label = |s: Dart| darts.iter().position(|&x| x == s).expect("the start is a dart of the volume");
            lookup_memo::remember(set, word, found.map(|(i, s)| (i as u32, label(s) as u32)));
            found.and_then(|(i, s)| then(Some(from_d), i, s))
        })
        .flatten();
    }
    let (i, start) =
        set.patterns.iter().enumerate().filter(|(_, p)| p.kind == PatternKind::Volume).find_map(|(i, p)| {
            match_direct(
                (&p.map, Surface::PatternBoundary, Flags::Mark(p.flags), p.start),
                (map, Surface::Cell, flags, d),
            )
            .map(|t| (i, t))
        })?;
    then(None, i, start)
}
