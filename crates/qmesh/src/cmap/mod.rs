//! Topology only: the 3D combinatorial map (2022 §2.2–2.3, 2025 §3.2–3.3, §6.6).
//!
//! A [`CMap3`] stores darts with β0..β3, an origin vertex id per dart and mark bits.
//! Every operation here keeps the map valid ([`CMap3::is_valid`]); low-level
//! [`CMap3::link`]/[`CMap3::unlink`] are for algorithms that rewire in bulk and restore
//! validity themselves.

mod bitset;
mod census;
mod compact;
mod constructors;
mod counts;
mod dart;
mod error;
mod marks;
mod orbit;
mod orientation;
mod page_backing;
mod remove;
mod sew;
mod shared_darts;
mod split;
mod storage;
mod tables;
mod validity;

pub use bitset::BitSet;
pub use compact::Compaction;
pub use constructors::{Layout, Standard, faces};
pub use counts::{CellCounts, Census, FaceSweep};
pub use dart::{Dart, raw_of};
pub use error::MapError;
pub use marks::Mark;
pub use orbit::{Cells, Orbit, OrbitWalker, Visited, walk_orbit};
pub(crate) use shared_darts::SharedDarts;
pub use storage::CMap3;
pub use tables::MapTables;
pub use validity::Violation;
