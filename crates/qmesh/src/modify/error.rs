//! Why a rule cannot modify.

use super::plan::Operation;
use crate::query::QueryError;

/// A query/target pair that does not fit its operation (2025 §6.1–6.3).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModifyError {
    #[error("{}", match op {
        Operation::Extend => "the query does not occur in the target (extend needs Q to be a submap of T)",
        Operation::Delete => "the target does not occur in the query (delete needs T to be a submap of Q)",
        Operation::Replace => "replace needs isomorphic boundaries",
    })]
    NotSubmap { op: Operation },
    #[error("the {} target changes nothing: it is the query itself", op.name())]
    Nothing { op: Operation },
    #[error("the boundaries of the query and the target are not isomorphic (replace keeps the boundary of the match)")]
    Boundaries,
    #[error("a created vertex of the target cannot be placed from the preserved vertices")]
    Geometry,
    #[error("the target is not a usable map: {0}")]
    Target(QueryError),
}
