//! e/f/v replacement (2022 §5): the only code that rewires darts for query-replace.

mod engine;
mod face;
mod vertices;
mod volume;

pub use engine::{ReplaceOptions, ReplaceReport, Uncovered, find_face, find_volume, query_replace, replace_cells};
pub use face::{align_face, replace_face};
pub use volume::replace_volume;
