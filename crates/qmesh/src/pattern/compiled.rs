//! Compiled pattern sets (`.qps`): every pattern of a set with what loading computes
//! for it (the map, its flags and orientation, the signature, automorphisms and
//! canonical start) in one binary file. Reading one back skips reading, building and
//! signing each pattern file again: the authors' 330 transition patterns load in about
//! a millisecond instead of tens. `qmesh patterns compile` writes them; every option
//! that takes a pattern folder also takes a compiled set.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::flags::FlagRule;
use super::load::PatternError;
use super::set::load_pattern_dir;
use super::{Pattern, PatternKind, PatternSet};
use crate::cmap::{CMap3, Dart, MapTables};
use crate::io::{IoError, write_atomically};
use crate::signature::Signature;

/// The extension of compiled pattern sets.
pub const COMPILED_EXTENSION: &str = "qps";

/// The first bytes of every compiled set.
const MAGIC: &[u8; 8] = b"qmeshps\n";

/// The layout of the stored set and of what loading computes: raised whenever either
/// changes, so that an older file is refused instead of misread.
const FORMAT: u32 = 1;

/// Pattern flags as the rule that made them: `Corners` and `Geometric` flag patterns
/// alike (they differ on input cells only).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum PatternFlags {
    Corners = 0,
    File = 1,
    None = 2,
}

impl PatternFlags {
    fn of(rule: FlagRule) -> Self {
        match rule {
            FlagRule::Corners | FlagRule::Geometric => PatternFlags::Corners,
            FlagRule::File => PatternFlags::File,
            FlagRule::None => PatternFlags::None,
        }
    }

    fn words(self) -> &'static str {
        match self {
            PatternFlags::Corners => "corner flags (--flags corners or geometric)",
            PatternFlags::File => "flags from the files' marks (--flags file)",
            PatternFlags::None => "no flags (--flags none)",
        }
    }
}

#[derive(Serialize, Deserialize)]
struct StoredPattern {
    file: PathBuf,
    face: bool,
    map: MapTables,
    mark: u8,
    boundary: u32,
    boundary_darts: usize,
    signature: Vec<u32>,
    automorphisms: usize,
    start: u32,
    cycle: Vec<u32>,
    surface: Vec<u32>,
}

/// Whether `path` names a compiled set (by its extension).
pub fn is_compiled_set(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case(COMPILED_EXTENSION))
}

/// The patterns of a folder, a pattern file or a compiled set, with `rule`.
///
/// # Errors
/// A compiled set that cannot be read (see [`read_compiled`]); folders never fail, their
/// unusable files are listed in the set's `skipped`.
pub fn load_patterns(path: &Path, rule: FlagRule) -> Result<PatternSet, PatternError> {
    if is_compiled_set(path) { read_compiled(path, rule) } else { Ok(load_pattern_dir(path, rule)) }
}

/// Writes `set`, whose patterns were loaded with `rule`, to `path` (through a temporary
/// file); returns the bytes written.
///
/// The file: the magic `qmeshps\n`, the format number (1) and a checksum of the rest, then the flags (one
/// byte), the number of patterns, and each pattern as its length and its encoding
/// (apart, so that they are decoded on all cores).
///
/// # Errors
/// The file cannot be written.
pub fn write_compiled(set: &PatternSet, rule: FlagRule, path: &Path) -> Result<u64, PatternError> {
    let blobs: Vec<Vec<u8>> = set
        .patterns
        .par_iter()
        .map(|p| postcard::to_stdvec(&stored(p)))
        .collect::<Result<_, _>>()
        .map_err(|e| invalid(path, format!("cannot encode the set: {e}")))?;
    let mut payload = vec![PatternFlags::of(rule) as u8];
    payload.extend_from_slice(&(blobs.len() as u32).to_le_bytes());
    for b in &blobs {
        payload.extend_from_slice(&(b.len() as u32).to_le_bytes());
        payload.extend_from_slice(b);
    }
    let mut bytes = Vec::with_capacity(payload.len() + 20);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(&checksum(&payload).to_le_bytes());
    bytes.extend_from_slice(&payload);
    write_atomically(path, |w| w.write_all(&bytes).map_err(|e| IoError::io(path, e)))?;
    Ok(bytes.len() as u64)
}

/// Reads a compiled set for a command that flags patterns with `rule`.
///
/// # Errors
/// An unreadable file, a file that is not a compiled set, one compiled by a qmesh with
/// another format or with other flags than `rule` gives, or a damaged one (checksum,
/// encoding, or a stored map or dart that is not valid).
pub fn read_compiled(path: &Path, rule: FlagRule) -> Result<PatternSet, PatternError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    if bytes.len() < 20 || &bytes[..8] != MAGIC {
        return Err(invalid(path, "not a compiled pattern set (`qmesh patterns compile` makes them)"));
    }
    let format = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if format != FORMAT {
        return Err(invalid(
            path,
            format!("compiled in pattern-set format {format}, this qmesh reads format {FORMAT}: compile the set again"),
        ));
    }
    let payload = &bytes[20..];
    if checksum(payload) != u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes")) {
        return Err(invalid(path, "damaged: the checksum does not match the contents"));
    }
    let damaged = |what: &str| invalid(path, format!("damaged: {what}"));
    let (&flags, mut rest) = payload.split_first().ok_or_else(|| damaged("no flags"))?;
    let stored_flags = [PatternFlags::Corners, PatternFlags::File, PatternFlags::None]
        .into_iter()
        .find(|&f| f as u8 == flags)
        .ok_or_else(|| damaged("unknown flags"))?;
    let wanted = PatternFlags::of(rule);
    if stored_flags != wanted {
        return Err(invalid(
            path,
            format!("compiled with {}, but this command needs {}", stored_flags.words(), wanted.words()),
        ));
    }
    let mut take = |n: usize| -> Result<&[u8], PatternError> {
        let (head, tail) = rest.split_at_checked(n).ok_or_else(|| damaged("the file ends early"))?;
        rest = tail;
        Ok(head)
    };
    let word = |b: &[u8]| u32::from_le_bytes(b.try_into().expect("4 bytes")) as usize;
    let count = word(take(4)?);
    let blobs = (0..count).map(|_| take(4).map(word).and_then(&mut take)).collect::<Result<Vec<&[u8]>, _>>();
    let blobs = blobs?;
    if !rest.is_empty() {
        return Err(damaged("bytes after the last pattern"));
    }
    // Decoded and checked on all cores, inserted in stored order.
    let patterns: Vec<Pattern> = blobs
        .into_par_iter()
        .enumerate()
        .map(|(k, blob)| {
            let p: StoredPattern =
                postcard::from_bytes(blob).map_err(|e| damaged(&format!("cannot decode pattern {k} ({e})")))?;
            let file = p.file.clone();
            restored(p).map_err(|msg| invalid(path, format!("pattern {}: {msg}", file.display())))
        })
        .collect::<Result<_, _>>()?;
    let mut set = PatternSet::default();
    for p in patterns {
        set.insert(p);
    }
    Ok(set)
}

fn stored(p: &Pattern) -> StoredPattern {
    let raw = |ds: &[Dart]| ds.iter().map(|d| d.raw()).collect();
    StoredPattern {
        file: p.file.clone(),
        face: p.kind == PatternKind::Face,
        map: p.map.to_tables(),
        mark: p.flags.index(),
        boundary: p.boundary.raw(),
        boundary_darts: p.boundary_darts,
        signature: match &p.signature {
            Signature::Face(w) | Signature::Volume(w) => w.clone(),
        },
        automorphisms: p.automorphisms,
        start: p.start.raw(),
        cycle: raw(&p.cycle),
        surface: raw(&p.surface),
    }
}

/// The pattern stored in `p`, every dart checked to be a live dart of its map.
fn restored(p: StoredPattern) -> Result<Pattern, String> {
    let map = CMap3::from_tables(p.map)?;
    let dart = |raw: u32| Dart::from_raw(raw).filter(|&d| map.is_live(d)).ok_or_else(|| format!("no live dart {raw}"));
    let darts = |raws: &[u32]| raws.iter().map(|&r| dart(r)).collect::<Result<Vec<Dart>, String>>();
    let flags = map.reserved_mark(p.mark).ok_or_else(|| format!("mark {} is not reserved", p.mark))?;
    let (kind, signature) = if p.face {
        (PatternKind::Face, Signature::Face(p.signature))
    } else {
        (PatternKind::Volume, Signature::Volume(p.signature))
    };
    Ok(Pattern {
        file: p.file,
        kind,
        flags,
        boundary: dart(p.boundary)?,
        boundary_darts: p.boundary_darts,
        signature,
        automorphisms: p.automorphisms,
        start: dart(p.start)?,
        cycle: darts(&p.cycle)?,
        surface: darts(&p.surface)?,
        interior: Default::default(),
        map,
    })
}

fn invalid(path: &Path, msg: impl Into<String>) -> PatternError {
    PatternError::Invalid { path: path.to_path_buf(), msg: msg.into() }
}

/// A 64-bit checksum in the manner of FNV-1a, over 8 bytes at a time: enough to tell a
/// damaged file from a whole one, and fixed here so that it never changes under a
/// dependency update.
fn checksum(bytes: &[u8]) -> u64 {
    const PRIME: u64 = 0x0100_0000_01b3;
    let mut chunks = bytes.chunks_exact(8);
    let mut h = chunks.by_ref().fold(0xcbf2_9ce4_8422_2325_u64, |h, c| {
        (h ^ u64::from_le_bytes(c.try_into().expect("8 bytes"))).wrapping_mul(PRIME).rotate_left(29)
    });
    for &b in chunks.remainder() {
        h = (h ^ u64::from(b)).wrapping_mul(PRIME);
    }
    h ^ bytes.len() as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apps::{GeneratedKind, generated_pattern_set};

    fn temp(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("qmesh-compiled-{}-{name}.qps", std::process::id()))
    }

    fn transitions() -> PatternSet {
        generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners).unwrap()
    }

    #[test]
    fn a_compiled_set_reads_back_as_loaded() {
        let set = transitions();
        let path = temp("roundtrip");
        write_compiled(&set, FlagRule::Corners, &path).unwrap();
        let back = read_compiled(&path, FlagRule::Geometric).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(back.patterns.len(), set.patterns.len());
        for (a, b) in set.patterns.iter().zip(&back.patterns) {
            assert_eq!(
                (&a.file, a.kind, &a.signature, a.automorphisms),
                (&b.file, b.kind, &b.signature, b.automorphisms)
            );
            assert_eq!((a.boundary, a.start, &a.cycle, &a.surface), (b.boundary, b.start, &b.cycle, &b.surface));
            assert!(b.map.is_valid().is_empty());
            assert!(a.map.darts().all(|d| a.map.is_marked(d, a.flags) == b.map.is_marked(d, b.flags)));
            let (ia, ib) = (a.interior(), b.interior());
            assert_eq!(ia.len(), ib.len());
            assert!(ia.iter().zip(ib).all(|(x, y)| x.vertex == y.vertex && x.weights == y.weights));
        }
        assert!(set.patterns.iter().all(|p| back.lookup(&p.signature).is_some()));
    }

    #[test]
    fn damaged_or_foreign_files_are_refused_in_words() {
        let set = transitions();
        let path = temp("damaged");
        write_compiled(&set, FlagRule::Corners, &path).unwrap();
        let good = std::fs::read(&path).unwrap();
        let error_with = |bytes: &[u8], rule: FlagRule| {
            std::fs::write(&path, bytes).unwrap();
            read_compiled(&path, rule).unwrap_err().to_string()
        };
        assert!(error_with(&good, FlagRule::None).contains("compiled with corner flags"));
        let mut flipped = good.clone();
        let mid = flipped.len() / 2;
        flipped[mid] ^= 0x40;
        assert!(error_with(&flipped, FlagRule::Corners).contains("checksum"));
        assert!(error_with(&good[..good.len() / 3], FlagRule::Corners).contains("damaged"));
        assert!(error_with(b"# vtk DataFile Version 2.0\n", FlagRule::Corners).contains("not a compiled pattern set"));
        let mut newer = good.clone();
        newer[8..12].copy_from_slice(&(FORMAT + 1).to_le_bytes());
        assert!(error_with(&newer, FlagRule::Corners).contains("compile the set again"));
        // A whole file (checksum right) holding a map that is not valid.
        let mut p = stored(&set.patterns[0]);
        let mut t = set.patterns[0].map.to_tables();
        let (a, b) = (t.betas[1][2], t.betas[2][2]);
        (t.betas[1][2], t.betas[2][2]) = (b, a);
        p.map = t;
        let blob = postcard::to_stdvec(&p).unwrap();
        let mut payload = vec![PatternFlags::Corners as u8];
        payload.extend_from_slice(&1u32.to_le_bytes());
        payload.extend_from_slice(&(blob.len() as u32).to_le_bytes());
        payload.extend_from_slice(&blob);
        let mut bytes = good[..12].to_vec();
        bytes.extend_from_slice(&checksum(&payload).to_le_bytes());
        bytes.extend_from_slice(&payload);
        let e = error_with(&bytes, FlagRule::Corners);
        std::fs::remove_file(&path).unwrap();
        assert!(e.contains("not a valid map"), "{e}");
    }
}
