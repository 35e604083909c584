//! What `qmesh info`, `validate` and `quality` report about a mesh, as plain structs
//! that serialise to the CLI's JSON keys, so the command line and the Python package
//! print the same numbers under the same names.

mod info;
mod quality;

pub use info::{CellTypeCounts, InfoReport};
pub use quality::{QualityReport, SignedVolumes, Summary, ValidityReport};
