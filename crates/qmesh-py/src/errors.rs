//! qmesh errors as Python exceptions (classes of `qmesh.errors`): `MeshIOError`, an
//! `OSError`, when a file cannot be opened, read or written; `MeshValueError`, a
//! `ValueError`, for bad content, bad arguments and refused operations. The message is
//! the CLI's: the file, the line, what was expected.

use pyo3::prelude::*;
use qmesh::io::IoError;

fn raise(py: Python<'_>, class: &str, msg: String) -> PyErr {
    match py.import("qmesh.errors").and_then(|m| m.getattr(class)).and_then(|c| c.call1((msg,))) {
        Ok(exception) => PyErr::from_value(exception),
        Err(e) => e,
    }
}

/// A `MeshValueError` with `msg`.
pub fn value_error(py: Python<'_>, msg: impl std::fmt::Display) -> PyErr {
    raise(py, "MeshValueError", msg.to_string())
}

/// The exception for a reading or writing error.
pub fn io_error(py: Python<'_>, e: &IoError) -> PyErr {
    match e {
        IoError::Io { .. } => raise(py, "MeshIOError", e.to_string()),
        _ => value_error(py, e),
    }
}
