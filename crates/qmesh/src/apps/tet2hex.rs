//! Tetrahedra to hexahedra (2022 §7.4): every edge split in two, every triangle
//! replaced by 3 quadrilaterals, every tetrahedron by 4 hexahedra, with the generated
//! `tet2hex` patterns.

use super::generated_patterns::{GeneratedKind, given_or_generated};
use crate::cmap::{CMap3, MapError};
use crate::pattern::{FlagRule, PatternSet};
use crate::replace::{ReplaceOptions, ReplaceReport, query_replace};

/// Runs the transformation in place with `patterns` (default: the generated `tet2hex`
/// set). Cells that are not tetrahedra are left as they
/// are (their faces too, unless they are triangles shared with a tetrahedron).
///
/// # Errors
/// Only if the map has no free mark.
pub fn tet_to_hex(
    map: &mut CMap3,
    patterns: Option<&PatternSet>,
    use_signatures: bool,
) -> Result<ReplaceReport, MapError> {
    let mut generated = None;
    let set = given_or_generated(patterns, GeneratedKind::Tet2Hex, &mut generated);
    query_replace(map, set, &ReplaceOptions { split_edges: Some(2), flags: FlagRule::Corners, use_signatures })
}
