//! Why a map cannot be a query.

use crate::cmap::{CMap3, Dart};

/// A query map that the engine refuses (2025 §5: connected, 1- and 2-sewn everywhere).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QueryError {
    #[error("the query has no darts")]
    Empty,
    #[error(
        "the query is not connected: {reached} of its {total} darts are reachable from the first one; {face} is not"
    )]
    NotConnected { reached: usize, total: usize, face: String },
    #[error("dart {dart} of the query is {beta}-free ({face}): queries must be closed faces and closed volumes")]
    Free { dart: Dart, beta: usize, face: String },
    #[error("the query is not a valid map: {0}")]
    Invalid(String),
    #[error("the query has {0} darts; at most {max} are supported", max = super::MAX_QUERY_DARTS)]
    TooLarge(usize),
}

impl QueryError {
    pub(crate) fn free(map: &CMap3, d: Dart, beta: usize) -> QueryError {
        QueryError::Free { dart: d, beta, face: describe_face(map, d) }
    }
}

/// At most this many vertices are listed in a face's description.
const LISTED_VERTICES: usize = 64;

/// "the face with vertices 3-7-8 (first at x, y, z)": the vertex ids around the
/// half-face of `d` (followed while β1 is sewn, "…" after the first
/// [`LISTED_VERTICES`]) and its first vertex's position.
pub(crate) fn describe_face(map: &CMap3, d: Dart) -> String {
    let mut ids = vec![map.vertex_of(d).to_string()];
    let mut x = map.beta(d, 1);
    while let Some(y) = x
        && y != d
    {
        if ids.len() == LISTED_VERTICES {
            ids.push("…".into());
            break;
        }
        ids.push(map.vertex_of(y).to_string());
        x = map.beta(y, 1);
    }
    let p = map.point(d);
    format!("the face with vertices {} (first at {:.3}, {:.3}, {:.3})", ids.join("-"), p[0], p[1], p[2])
}
