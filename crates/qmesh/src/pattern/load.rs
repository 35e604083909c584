//! Loading one pattern file: any mesh format qmesh reads, kind recognised from the
//! boundary, signature and automorphisms computed once.

use std::path::Path;

use super::flags::{FlagRule, flag_corners};
use super::geometry::total_volume;
use super::{Pattern, PatternKind};
use crate::build::{BuildOptions, build_map};
use crate::cmap::{CMap3, Dart};
use crate::io::{Format, IoError, Loaded, read, read_moka_with_flags};
use crate::signature::{
    Flags, Surface, cycle_automorphisms, pattern_face_boundary, pattern_face_signature, volume_signature_from,
    word_from,
};

/// Why a file is not a usable pattern.
#[derive(Debug, thiserror::Error)]
pub enum PatternError {
    #[error(transparent)]
    Io(#[from] IoError),
    #[error("{path}: {msg}", path = path.display())]
    Invalid { path: std::path::PathBuf, msg: String },
}

fn invalid(path: &Path, msg: impl Into<String>) -> PatternError {
    PatternError::Invalid { path: path.to_path_buf(), msg: msg.into() }
}

/// Reads a pattern. Cells of volume files are oriented by their signed volume (the
/// papers' VTK patterns store wedges inverted), so the map is consistently oriented.
///
/// # Errors
/// An unreadable file, a map that is not valid, or a boundary that is not a single
/// cycle of 2-free darts (f-pattern) or a single closed surface of 3-free darts
/// (v-pattern).
pub fn load_pattern(path: &Path, rule: FlagRule) -> Result<Pattern, PatternError> {
    let mut file_flags = Vec::new();
    let from_file = rule == FlagRule::File && Format::from_path(path) == Some(Format::Moka);
    let loaded = if from_file {
        let (m, f) = read_moka_with_flags(path)?;
        file_flags = f;
        Loaded::Map(m)
    } else {
        read(path, None)?
    };
    let (map, source) = match loaded {
        Loaded::Map(m) => (m, Source::AsIs),
        Loaded::Indexed(mesh) => {
            let (map, ..) = build_map(mesh, &BuildOptions { fix_orientation: true })
                .map_err(|cause| IoError::Build { path: path.into(), cause })?;
            (map, Source::Built)
        }
    };
    pattern_of(path, map, rule, &file_flags, source)
}

/// Where a pattern's map comes from, which tells what is left to check.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Source {
    /// `build_map` with `fix_orientation`: every cell has a non-negative volume and
    /// each vertex orbit its own id.
    Built,
    /// A map read or made as is: all checks, and its total signed volume decides the
    /// orientation.
    AsIs,
}

/// Makes a pattern of a map already in memory (generated sets); `name` is what audits
/// and reports call it. Same checks as [`load_pattern`].
///
/// # Errors
/// As [`load_pattern`], without the I/O part.
pub fn pattern_from_map(name: &Path, map: CMap3, rule: FlagRule, file_flags: &[Dart]) -> Result<Pattern, PatternError> {
    pattern_of(name, map, rule, file_flags, Source::AsIs)
}

fn pattern_of(
    path: &Path,
    mut map: CMap3,
    rule: FlagRule,
    file_flags: &[Dart],
    source: Source,
) -> Result<Pattern, PatternError> {
    let violations = match source {
        Source::Built => map.local_violations_all(),
        Source::AsIs => map.is_valid(),
    };
    if let Some(v) = violations.first() {
        return Err(invalid(path, format!("the pattern is not a valid map: {v}")));
    }
    let two_free: Vec<Dart> = map.darts().filter(|&d| map.is_free(d, 2)).collect();
    let three_free: Vec<Dart> = map.darts().filter(|&d| map.is_free(d, 3)).collect();
    let (kind, boundary) = if !two_free.is_empty() {
        let cycle = pattern_face_boundary(&map, two_free[0])
            .ok_or_else(|| invalid(path, "the 2-free darts do not close into a boundary cycle"))?;
        if cycle.len() != two_free.len() {
            return Err(invalid(
                path,
                format!(
                    "an f-pattern boundary must be one cycle of 2-free darts: found a cycle of {} and {} 2-free darts",
                    cycle.len(),
                    two_free.len()
                ),
            ));
        }
        map.set_dimension(2);
        (PatternKind::Face, cycle)
    } else {
        let first =
            *three_free.first().ok_or_else(|| invalid(path, "the map is closed: no 3-free darts, no boundary"))?;
        let surface = word_from(&map, Surface::PatternBoundary, Flags::None, first, None)
            .ok_or_else(|| invalid(path, "the 3-free darts do not form a closed surface"))?
            .darts;
        if surface.len() != three_free.len() {
            return Err(invalid(
                path,
                format!(
                    "a v-pattern boundary must be one closed surface: it reaches {} of {} 3-free darts",
                    surface.len(),
                    three_free.len()
                ),
            ));
        }
        (PatternKind::Volume, surface)
    };
    finish(path, map, kind, boundary, rule, file_flags, source)
}

fn finish(
    path: &Path,
    mut map: CMap3,
    kind: PatternKind,
    boundary: Vec<Dart>,
    rule: FlagRule,
    file_flags: &[Dart],
    source: Source,
) -> Result<Pattern, PatternError> {
    if kind == PatternKind::Volume && source == Source::AsIs && total_volume(&map) < 0.0 {
        // Moka files keep an arbitrary orientation class: bring the pattern to the map
        // convention so that its cells keep positive volumes once inserted.
        map.reverse_orientation();
    }
    let mark = map.reserve_mark().map_err(|e| invalid(path, e.to_string()))?;
    match rule {
        FlagRule::None => {}
        FlagRule::File => file_flags.iter().for_each(|&d| map.mark(d, mark)),
        FlagRule::Corners | FlagRule::Geometric => {
            flag_corners(&mut map, mark, &boundary, kind == PatternKind::Face);
        }
    }
    let flags = Flags::Mark(mark);
    let (signature, automorphisms, start) = match kind {
        PatternKind::Face => {
            let sig = pattern_face_signature(&map, flags, boundary[0]).expect("boundary checked above");
            let f: Vec<bool> = boundary.iter().map(|&d| flags.get(&map, d)).collect();
            (sig, cycle_automorphisms(&f), boundary[0])
        }
        PatternKind::Volume => volume_signature_from(&map, Surface::PatternBoundary, flags, boundary[0])
            .ok_or_else(|| invalid(path, "the boundary surface is open"))?,
    };
    let (first, boundary_darts) = (boundary[0], boundary.len());
    let (cycle, surface) = match kind {
        PatternKind::Face => (boundary, Vec::new()),
        PatternKind::Volume => (Vec::new(), boundary),
    };
    Ok(Pattern {
        file: path.to_path_buf(),
        kind,
        boundary: first,
        boundary_darts,
        map,
        flags: mark,
        signature,
        automorphisms,
        start,
        cycle,
        surface,
        interior: Default::default(),
    })
}
