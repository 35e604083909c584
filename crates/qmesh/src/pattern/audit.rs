//! Audits of pattern sets (2022 §6.4): every pattern's kind, signature digest and
//! automorphism count, and the groups of duplicate boundaries.

use super::PatternSet;

/// One line of an audit.
#[derive(Clone, Debug)]
pub struct AuditEntry {
    pub file: String,
    pub kind: &'static str,
    pub signature: String,
    pub automorphisms: usize,
    pub boundary_darts: usize,
}

/// The audit of a set.
#[derive(Clone, Debug, Default)]
pub struct Audit {
    pub patterns: Vec<AuditEntry>,
    /// Files sharing one signature.
    pub duplicates: Vec<Vec<String>>,
    /// Patterns whose placement is ambiguous (more than one flag-preserving automorphism).
    pub ambiguous: Vec<String>,
    pub skipped: Vec<(String, String)>,
}

pub fn audit(set: &PatternSet) -> Audit {
    let name = |i: usize| set.patterns[i].file.display().to_string();
    Audit {
        patterns: set
            .patterns
            .iter()
            .map(|p| AuditEntry {
                file: p.file.display().to_string(),
                kind: p.kind.name(),
                signature: p.signature.digest(),
                automorphisms: p.automorphisms,
                boundary_darts: p.boundary_darts,
            })
            .collect(),
        duplicates: set.duplicates().into_iter().map(|g| g.into_iter().map(name).collect()).collect(),
        ambiguous: (0..set.patterns.len()).filter(|&i| set.patterns[i].automorphisms > 1).map(name).collect(),
        skipped: set.skipped.iter().map(|s| (s.file.display().to_string(), s.reason.clone())).collect(),
    }
}
