//! qmesh: topological rewriting of 3D meshes on combinatorial maps.
//!
//! Layers (each only uses those listed before it): [`cmap`] (topology), [`geom`]
//! (positions, volumes), [`build`] (indexed cells ↔ map), [`io`] (file formats).
#![deny(unsafe_code)]
#![warn(missing_debug_implementations)]

pub mod apps;
pub mod awake_pool;
pub mod build;
pub mod cmap;
mod disjoint_sets;
pub mod generate;
pub mod geom;
pub mod io;
pub mod modify;
pub mod pattern;
pub mod query;
mod random;
pub mod render;
pub mod replace;
pub mod report;
pub mod signature;
