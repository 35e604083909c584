//! Headless pictures of meshes (software rasterisation to PNG): cells shrunk apart,
//! cut open, coloured by type, level, quality, label or component, with a legend.

mod font;
mod raster;
mod scene;

pub use font::{draw_text, text_width};
pub use raster::{Canvas, Rgb};
pub use scene::{Clip, ColorBy, RenderOptions, RenderReport, render, render_titled};
