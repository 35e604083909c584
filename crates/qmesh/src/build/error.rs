//! Errors of the builders: they name the cells (0-based, in file order).

/// Why an indexed mesh cannot become a valid map.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    #[error("cell {cell}: node index {index} is out of range (the mesh has {points} points)")]
    IndexOutOfRange { cell: usize, index: u32, points: usize },
    #[error("cell {cell}: {reason}")]
    BadCell { cell: usize, reason: String },
    #[error("polygon {polygon}: {reason}")]
    BadPolygon { polygon: usize, reason: String },
    #[error(
        "three cells on one face: face {} is shared by cells {a}, {b} and {c} (a face bounds at most two cells)",
        nodes(face)
    )]
    FaceSharedByMoreThanTwo { face: Vec<u32>, a: usize, b: usize, c: usize },
    #[error(
        "cells {a} and {b} meet on face {} with inconsistent orientation (or are duplicates); \
         try --fix-orientation",
        nodes(face)
    )]
    InconsistentOrientation { face: Vec<u32>, a: usize, b: usize },
    #[error(
        "edge {u}-{v} is used in the same direction by polygons {a} and {b}: \
         a non-manifold edge or inconsistently oriented polygons"
    )]
    NonManifoldEdge { u: u32, v: u32, a: usize, b: usize },
    #[error("the mesh has no cells and no polygons")]
    Empty,
}

/// Node numbers joined by dashes, as a face reads in a message.
fn nodes(face: &[u32]) -> String {
    face.iter().map(u32::to_string).collect::<Vec<_>>().join("-")
}

/// What a [`BuildError`] is about: a cell or a polygon, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subject {
    Cell(usize),
    Polygon(usize),
}

impl BuildError {
    /// The cells or polygons the error names, the one where it was detected last.
    pub fn subjects(&self) -> Vec<Subject> {
        use BuildError::*;
        match *self {
            IndexOutOfRange { cell, .. } | BadCell { cell, .. } => vec![Subject::Cell(cell)],
            BadPolygon { polygon, .. } => vec![Subject::Polygon(polygon)],
            FaceSharedByMoreThanTwo { a, b, c, .. } => vec![Subject::Cell(a), Subject::Cell(b), Subject::Cell(c)],
            InconsistentOrientation { a, b, .. } => vec![Subject::Cell(a), Subject::Cell(b)],
            NonManifoldEdge { a, b, .. } => vec![Subject::Polygon(a), Subject::Polygon(b)],
            Empty => Vec::new(),
        }
    }
}
