//! `PatternSet`: signature → pattern, built once (2022 §4); lookups in amortised O(1).

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::flags::FlagRule;
use super::load::load_pattern;
use super::{Pattern, PatternKind};
use crate::io::Format;
#[cfg(doc)]
use crate::signature::volume_shape;
use crate::signature::{Signature, signature_shape};

/// A file of a patterns folder that was not loaded, and why.
#[derive(Debug, Clone)]
pub struct Skipped {
    pub file: PathBuf,
    pub reason: String,
}

/// Patterns indexed by signature. Patterns with equal signatures are duplicates: the
/// first one (in file order) is used, the audit lists the others.
#[derive(Debug, Default)]
pub struct PatternSet {
    pub patterns: Vec<Pattern>,
    pub skipped: Vec<Skipped>,
    index: FxHashMap<Signature, Vec<usize>>,
    /// Per v-signature shape (darts, flagged darts), the first pattern of each distinct
    /// signature with that shape.
    volume_shapes: FxHashMap<(usize, usize), Vec<usize>>,
    version: SetVersion,
}

/// Names one content of a set: new for every set and after every insert, so that what
/// is remembered about a set's lookups (see `replace::lookup_memo`) is never used for
/// another.
#[derive(Debug)]
struct SetVersion(u64);

impl Default for SetVersion {
    fn default() -> Self {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
        SetVersion(NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
    }
}

impl PatternSet {
    /// Adds a pattern; returns its index.
    pub fn insert(&mut self, p: Pattern) -> usize {
        let i = self.patterns.len();
        let first = !self.index.contains_key(&p.signature);
        if let (true, Signature::Volume(w)) = (first, &p.signature) {
            self.volume_shapes.entry(signature_shape(w)).or_default().push(i);
        }
        self.index.entry(p.signature.clone()).or_default().push(i);
        self.patterns.push(p);
        self.version = SetVersion::default();
        i
    }

    /// This content's version: equal for two calls only if no pattern was added between
    /// them, and never equal for two sets.
    pub fn version(&self) -> u64 {
        self.version.0
    }

    /// The pattern whose boundary has this signature.
    pub fn lookup(&self, s: &Signature) -> Option<&Pattern> {
        self.index.get(s).map(|v| &self.patterns[v[0]])
    }

    /// Index of the pattern whose boundary has this signature.
    pub fn lookup_index(&self, s: &Signature) -> Option<usize> {
        self.index.get(s).map(|v| v[0])
    }

    /// The v-patterns (one per distinct signature) whose boundary has `shape` (darts,
    /// flagged darts; see [`volume_shape`]): the only ones a volume of that shape can
    /// match.
    pub fn volume_candidates(&self, shape: (usize, usize)) -> &[usize] {
        self.volume_shapes.get(&shape).map_or(&[], |v| v.as_slice())
    }

    /// Groups of patterns (indices) sharing one signature.
    pub fn duplicates(&self) -> Vec<Vec<usize>> {
        let mut d: Vec<Vec<usize>> = self.index.values().filter(|v| v.len() > 1).cloned().collect();
        d.sort();
        d
    }

    pub fn count(&self, kind: PatternKind) -> usize {
        self.patterns.iter().filter(|p| p.kind == kind).count()
    }
}

/// Loads every mesh file under `dir` (recursively, in sorted order; the papers'
/// `fpattern/` and `vpattern/` subfolders included) or a single file. Files that are
/// not meshes or not valid patterns are recorded in `skipped` with the reason.
///
/// When `dir` has `fpattern/` or `vpattern/` subfolders (the papers' layout), only
/// those are read and each pattern must be of its folder's kind; other files are
/// reported as skipped.
pub fn load_pattern_dir(dir: &Path, rule: FlagRule) -> PatternSet {
    let mut files = Vec::new();
    collect(dir, &mut files);
    files.sort();
    let layout = ["fpattern", "vpattern"].map(|s| dir.join(s)).into_iter().filter(|p| p.is_dir()).count() > 0;
    // Files are read and their patterns built on all cores, then inserted in file order
    // (the same set whatever the number of threads).
    let loaded: Vec<Result<Pattern, Skipped>> = files
        .into_par_iter()
        .map(|f| {
            let expected = expected_kind(dir, &f);
            let skip = |reason: String| Err(Skipped { file: f.clone(), reason });
            if layout && expected.is_none() {
                return skip("outside the fpattern/ and vpattern/ folders".into());
            }
            if Format::from_path(&f).is_none() {
                return skip("not a mesh file".into());
            }
            match load_pattern(&f, rule) {
                Ok(p) if expected.is_some_and(|k| k != p.kind) => {
                    skip(format!("a {} in a folder of {}s", p.kind.name(), expected.unwrap().name()))
                }
                Ok(p) => Ok(p),
                Err(e) => skip(e.to_string()),
            }
        })
        .collect();
    let mut set = PatternSet::default();
    for p in loaded {
        match p {
            Ok(p) => {
                set.insert(p);
            }
            Err(skipped) => set.skipped.push(skipped),
        }
    }
    set
}

/// The kind implied by the papers' layout (`DIR/fpattern/…`, `DIR/vpattern/…`).
fn expected_kind(dir: &Path, file: &Path) -> Option<PatternKind> {
    match file.strip_prefix(dir).ok()?.components().next()?.as_os_str().to_str()? {
        "fpattern" => Some(PatternKind::Face),
        "vpattern" => Some(PatternKind::Volume),
        _ => None,
    }
}

fn collect(p: &Path, out: &mut Vec<PathBuf>) {
    if p.is_dir() {
        collect_dir(p, out);
    } else if p.is_file() {
        out.push(p.to_path_buf());
    }
}

/// The files under folder `p`, told apart by the folder's own entries (one `stat` per
/// symbolic link only).
fn collect_dir(p: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(p) else { return };
    for e in rd.flatten() {
        match e.file_type() {
            Ok(t) if t.is_dir() => collect_dir(&e.path(), out),
            Ok(t) if t.is_file() => out.push(e.path()),
            _ => collect(&e.path(), out),
        }
    }
}
