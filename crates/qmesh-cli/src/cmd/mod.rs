//! Subcommands.

pub mod conformal;
pub mod convert;
pub mod demo;
pub mod generate;
pub mod info;
pub mod marching_cubes;
pub mod modify;
pub mod patterns;
pub mod quality;
pub mod query;
pub mod recombine;
pub mod render;
pub mod replace;
pub mod rules;
pub mod subdivide;
pub mod tet2hex;
pub mod tetrahedralize;
pub mod validate;

use std::path::PathBuf;

use anyhow::{Result, anyhow};
use qmesh::io::Format;

/// Options shared by commands that read a mesh.
#[derive(clap::Args, Debug, Clone)]
pub struct InputArgs {
    /// Input mesh (vtk, vtu, mesh, msh, off, obj, stl, ply, moka).
    pub input: PathBuf,
    /// Input format, overriding the file extension.
    #[arg(long)]
    pub format: Option<String>,
    /// Flip cells with negative signed volume (reverse their node order) instead of
    /// only counting them. Tangled cells (some corners negative, volume positive) cannot
    /// be fixed this way: `qmesh quality` lists them.
    #[arg(long)]
    pub fix_orientation: bool,
}

/// The level-0 cells of an octree around a surface (`subdivide`, `marching-cubes`).
#[derive(clap::Args, Debug, Clone)]
pub struct OctreeRootArgs {
    /// Level-0 cells: `cube` (one cube around the surface, qmesh's) or `box` (the
    /// authors' program: the bounding box itself, in `--init` cells along its longest axis).
    #[arg(long, default_value = "cube", value_parser = ["cube", "box"])]
    pub root: String,
    /// With `--root box`: level-0 cells along the longest axis (the authors' `-init`).
    #[arg(long, default_value_t = 1)]
    pub init: u32,
    /// Root cube side beyond the surface's longest extent, as a fraction (0.01 = 1 %).
    #[arg(long, default_value_t = 0.01)]
    pub margin: f64,
}

impl OctreeRootArgs {
    /// The root shape asked for.
    ///
    /// # Errors
    /// A margin outside [0, 10] or an `--init` outside [1, 1024].
    pub fn shape(&self) -> Result<qmesh::apps::RootShape> {
        if !(0.0..=10.0).contains(&self.margin) {
            anyhow::bail!("--margin {} is outside [0, 10]", self.margin);
        }
        if self.init == 0 || self.init > 1024 {
            anyhow::bail!("--init {} is outside [1, 1024]", self.init);
        }
        Ok(match self.root.as_str() {
            "box" => qmesh::apps::RootShape::BoundingBox { init: self.init },
            _ => qmesh::apps::RootShape::Cube,
        })
    }
}

/// The output of a command that writes one mesh.
#[derive(clap::Args, Debug, Clone)]
pub struct OutputArgs {
    /// Output mesh (format from the extension).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Allow the output to be the input file.
    #[arg(long)]
    pub force: bool,
}

impl OutputArgs {
    /// Refuses to overwrite `input` without `--force` ([`refuse_to_overwrite`]).
    pub fn check_against(&self, input: &std::path::Path) -> Result<()> {
        refuse_to_overwrite(input, &self.output, self.force)
    }
}

/// Every command that writes calls this before reading: `output` must not be `input`
/// (whatever the path says: `./`, `..`, symbolic or hard links) unless `force`.
///
/// # Errors
/// When `output` is `input` and `force` is false.
pub fn refuse_to_overwrite(input: &std::path::Path, output: &std::path::Path, force: bool) -> Result<()> {
    if !force && same_file(input, output) {
        anyhow::bail!("{} is the input file; refusing to overwrite it (use --force)", output.display());
    }
    Ok(())
}

/// Whether two paths name the same existing file (same device and inode).
#[cfg(unix)]
pub fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

/// Whether two paths name the same existing file (same canonical path).
#[cfg(not(unix))]
pub fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// How a long command reports: JSON for machines, progress on stderr for people.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct ReportArgs {
    /// Print a JSON report.
    #[arg(long)]
    pub json: bool,
    /// No progress display and no summary (warnings and errors are still printed, on
    /// stderr; the exit status tells the outcome).
    #[arg(short, long)]
    pub quiet: bool,
}

/// Parses a `--format` value.
pub fn parse_format(s: &Option<String>) -> Result<Option<Format>> {
    s.as_deref()
        .map(|f| {
            Format::from_name(f)
                .ok_or_else(|| anyhow!("unknown format '{f}' (vtk, vtu, mesh, msh, off, obj, stl, ply, moka)"))
        })
        .transpose()
}
