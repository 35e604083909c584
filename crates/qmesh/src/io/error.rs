//! I/O errors: every parse error names the file, the line (or byte offset for binary
//! data) and what was expected.

use std::path::PathBuf;

use crate::build::BuildError;

/// Where in a file a parse error was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    Line(usize),
    Byte(usize),
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte {b}"),
        }
    }
}

/// Why a mesh could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    #[error("{path}:{at}: {msg}", path = path.display())]
    Parse { path: PathBuf, at: Location, msg: String },
    #[error("{path}: {cause}", path = path.display())]
    Io { path: PathBuf, cause: std::io::Error },
    #[error("{path}: {msg}", path = path.display())]
    Unsupported { path: PathBuf, msg: String },
    #[error("{path}: {cause}", path = path.display())]
    Build { path: PathBuf, cause: BuildError },
}

impl IoError {
    pub fn io(path: &std::path::Path, cause: std::io::Error) -> Self {
        IoError::Io { path: path.to_path_buf(), cause }
    }

    pub fn unsupported(path: &std::path::Path, msg: impl Into<String>) -> Self {
        IoError::Unsupported { path: path.to_path_buf(), msg: msg.into() }
    }
}

pub type IoResult<T> = Result<T, IoError>;
