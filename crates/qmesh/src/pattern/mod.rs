//! Patterns (2022 §4): small maps whose boundary is searched for in a mesh and whose
//! interior replaces the match; pattern sets keyed by signature; audits (§6.4).

mod audit;
mod boundaries;
mod compiled;
mod flags;
mod geometry;
mod load;
mod set;
mod source;

pub use audit::{Audit, AuditEntry, audit};
pub use boundaries::boundaries_mesh;
pub use compiled::{COMPILED_EXTENSION, is_compiled_set, load_patterns, read_compiled, write_compiled};
pub use flags::{FlagRule, flag_corners, flag_corners_on};
pub use geometry::interior_coordinates;
pub use load::{PatternError, load_pattern, pattern_from_map};
pub use set::{PatternSet, Skipped, load_pattern_dir};
pub use source::{FaceLabels, read_small_map};

use std::path::PathBuf;

use crate::cmap::{CMap3, Dart, Mark};
use crate::signature::Signature;

/// What a pattern replaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PatternKind {
    /// f-pattern: connected faces whose boundary is one cycle of 2-free darts.
    Face,
    /// v-pattern: connected volumes whose boundary is one closed surface of 3-free darts.
    Volume,
}

impl PatternKind {
    pub fn name(self) -> &'static str {
        match self {
            PatternKind::Face => "f-pattern",
            PatternKind::Volume => "v-pattern",
        }
    }
}

/// A loaded pattern with its precomputed signature.
#[derive(Debug)]
pub struct Pattern {
    pub file: PathBuf,
    pub kind: PatternKind,
    pub map: CMap3,
    /// The mark holding the pattern's flags.
    pub flags: Mark,
    /// A boundary dart (2-free for f-patterns, 3-free for v-patterns).
    pub boundary: Dart,
    /// Number of boundary darts.
    pub boundary_darts: usize,
    pub signature: Signature,
    /// Flag-preserving automorphisms of the boundary (1 = a unique placement).
    pub automorphisms: usize,
    /// v-patterns: the canonical start dart of the signature traversal.
    pub start: Dart,
    /// f-patterns: the boundary cycle of 2-free darts, in order from `boundary`.
    pub cycle: Vec<Dart>,
    /// v-patterns: the boundary surface's darts in traversal order from `boundary`.
    pub surface: Vec<Dart>,
    /// See [`Pattern::interior`].
    interior: std::sync::OnceLock<Vec<InteriorVertex>>,
}

impl Pattern {
    /// Interior vertices and their mean value coordinates over boundary vertices
    /// (2022 §5.2), computed on the first call: a set's unused patterns never need them.
    pub fn interior(&self) -> &[InteriorVertex] {
        self.interior.get_or_init(|| {
            let boundary = match self.kind {
                PatternKind::Face => &self.cycle,
                PatternKind::Volume => &self.surface,
            };
            interior_coordinates(&self.map, self.kind, boundary)
        })
    }
}

/// A vertex inside a pattern, as weights over the pattern's boundary vertices.
#[derive(Clone, Debug)]
pub struct InteriorVertex {
    pub vertex: u32,
    pub weights: Vec<(u32, f64)>,
}
