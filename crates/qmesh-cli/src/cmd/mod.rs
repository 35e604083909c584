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
    /// Flip cells with negative signed volume instead of only counting them.
    #[arg(long)]
    pub fix_orientation: bool,
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
    /// Refuses to overwrite `input` without `--force`.
    pub fn check_against(&self, input: &std::path::Path) -> Result<()> {
        if !self.force && convert::same_file(input, &self.output) {
            anyhow::bail!("{} is the input file; refusing to overwrite it (use --force)", self.output.display());
        }
        Ok(())
    }
}

/// How a long command reports: JSON for machines, progress on stderr for people.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct ReportArgs {
    /// Print a JSON report.
    #[arg(long)]
    pub json: bool,
    /// No progress display on stderr.
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
