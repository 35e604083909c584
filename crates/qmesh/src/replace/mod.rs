//! e/f/v replacement (2022 §5): finds each cell's pattern and correspondence; the darts
//! are rewired by the modify layer (`modify::FacePattern`, `modify::VolumePattern`).

mod engine;
mod face;
mod lookup_memo;
mod plans;
mod volume;

pub use engine::{
    LOOKUP_CHUNK, ReplaceOptions, ReplaceReport, Uncovered, find_face, find_volume, query_replace, replace_cells,
};
pub use face::{align_face, replace_face};
pub use volume::replace_volume;
