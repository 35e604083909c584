//! `qmesh generate grid|tet-grid --size N -o OUT`.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use qmesh::generate::{hex_grid, tet_grid};
use qmesh::io::{Format, WriteOptions, resolve_format, write_indexed};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// What to generate: `grid` (hexahedra) or `tet-grid` (6 tets per grid cell).
    pub kind: Kind,
    /// Cells along each axis (N×N×N), or NX,NY,NZ.
    #[arg(long, default_value = "10")]
    pub size: String,
    /// Output file.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write binary legacy VTK.
    #[arg(long)]
    pub binary: bool,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Kind {
    Grid,
    TetGrid,
}

pub fn parse_size(s: &str) -> Result<[usize; 3]> {
    let v: Vec<usize> = s.split(',').map(|x| x.trim().parse()).collect::<Result<_, _>>()?;
    match v.as_slice() {
        [n] => Ok([*n; 3]),
        [x, y, z] => Ok([*x, *y, *z]),
        _ => anyhow::bail!("--size takes N or NX,NY,NZ, got '{s}'"),
    }
}

pub fn run(a: Args) -> Result<ExitCode> {
    let [x, y, z] = parse_size(&a.size)?;
    anyhow::ensure!(x > 0 && y > 0 && z > 0, "--size must be positive");
    let mesh = match a.kind {
        Kind::Grid => hex_grid(x, y, z),
        Kind::TetGrid => tet_grid(x, y, z),
    };
    let format: Format = resolve_format(&a.output, None)?;
    write_indexed(&a.output, &mesh, format, &WriteOptions { binary: a.binary })?;
    println!("wrote {} ({} points, {} cells)", a.output.display(), mesh.points.len(), mesh.nb_cells());
    Ok(ExitCode::SUCCESS)
}
