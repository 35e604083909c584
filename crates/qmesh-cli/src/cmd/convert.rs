//! `qmesh convert IN OUT`: read, build the map, write (atomically).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, bail};
use qmesh::build::BuildOptions;
use qmesh::io::{WriteOptions, load_map, write_map_with_arrays};

use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output file; its extension picks the format unless --to is given.
    pub output: PathBuf,
    /// Output format, overriding the output extension.
    #[arg(long)]
    pub to: Option<String>,
    /// Write binary legacy VTK.
    #[arg(long)]
    pub binary: bool,
    /// Allow the output to be the input file.
    #[arg(long)]
    pub force: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    if !a.force && same_file(&a.input.input, &a.output) {
        bail!("{} is the input file; refusing to overwrite it (use --force)", a.output.display());
    }
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    if loaded.report.inverted_cells > 0 && loaded.report.flipped_cells == 0 {
        eprintln!(
            "warning: {} cells have negative volume (use --fix-orientation to flip them)",
            loaded.report.inverted_cells
        );
    }
    write_map_with_arrays(
        &a.output,
        &loaded.map,
        &loaded.cell_arrays,
        parse_format(&a.to)?,
        &WriteOptions { binary: a.binary },
    )?;
    let c = loaded.map.count_cells();
    println!(
        "wrote {} ({} vertices, {} volumes, {} faces)",
        a.output.display(),
        c.vertices,
        if loaded.map.dimension() == 3 { c.volumes } else { 0 },
        c.faces
    );
    Ok(ExitCode::SUCCESS)
}

/// Whether two paths name the same existing file.
pub fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}
