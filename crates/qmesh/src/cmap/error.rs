//! Errors of topological operations.

use super::dart::Dart;

/// Why a topological operation was refused. The map is left unchanged.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MapError {
    #[error("dart {0} is not a live dart of this map")]
    DeadDart(Dart),
    #[error("cannot {i}-sew darts {d1} and {d2}: {why}")]
    NotSewable { i: usize, d1: Dart, d2: Dart, why: &'static str },
    #[error("dart {0} is {1}-free: nothing to unsew")]
    AlreadyFree(Dart, usize),
    #[error("face of dart {0} lies on the boundary (3-free): there is no second volume to merge")]
    FaceOnBoundary(Dart),
    #[error("face of dart {0} is folded onto itself (an edge of it is 2-sewn within the removed face)")]
    DegenerateFace(Dart),
    #[error(
        "edge of dart {0} cannot be removed: it is not between exactly two faces, or removing it would cut its face in two"
    )]
    EdgeNotRemovable(Dart),
    #[error("all 32 marks are reserved")]
    NoMarkLeft,
    #[error("polyhedron is not closed: edge {0}->{1} has no opposite edge {1}->{0}")]
    OpenPolyhedron(u32, u32),
    #[error("polyhedron is not manifold: edge {0}->{1} occurs more than once")]
    NonManifoldPolyhedron(u32, u32),
    #[error("a face needs at least {min} vertices, got {got}")]
    FaceTooSmall { min: usize, got: usize },
    #[error("edge split needs k >= 1 segments, got {0}")]
    BadSegmentCount(usize),
    /// A composite operation (a query-apply function) that cannot do its work on this
    /// match; the primitives it ran before keep the map valid.
    #[error("{0}")]
    Refused(String),
}
