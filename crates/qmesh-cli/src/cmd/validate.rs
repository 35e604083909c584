//! `qmesh validate FILE`: exit status 1 and the violations when the map is invalid.

use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::{BuildOptions, extract, tangled_cells};
use qmesh::io::load_map;

use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// How many violations to print at most.
    #[arg(long, default_value_t = 20)]
    pub max: usize,
    /// Also fail (exit status 1) on geometric defects: inverted, tangled or degenerate
    /// cells. Without it they are warnings.
    #[arg(long)]
    pub strict: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    let v = loaded.map.is_valid();
    let r = &loaded.report;
    let tangled = if loaded.map.dimension() == 3 { tangled_cells(&extract(&loaded.map).0) } else { 0 };
    let inverted = r.inverted_cells - r.flipped_cells;
    let geometric = [
        (inverted, "inverted (negative volume; --fix-orientation reverses their node order)"),
        (tangled, "tangled (positive volume, negative corner Jacobian; no node order fixes them)"),
        (r.degenerate_cells, "degenerate (zero volume)"),
    ];
    for &(n, what) in geometric.iter().filter(|g| g.0 > 0) {
        eprintln!("{}: {n} cells {what}", if a.strict { "error" } else { "warning" });
    }
    let defects = geometric.iter().any(|g| g.0 > 0);
    if v.is_empty() {
        let status = if defects { "combinatorially valid, geometrically defective" } else { "valid" };
        println!("{}: {status} ({} darts)", a.input.input.display(), loaded.map.nb_darts());
        return Ok(if defects && a.strict { ExitCode::from(1) } else { ExitCode::SUCCESS });
    }
    println!("{}: INVALID, {} violations", a.input.input.display(), v.len());
    for x in v.iter().take(a.max) {
        println!("  {x}");
    }
    if v.len() > a.max {
        println!("  … and {} more", v.len() - a.max);
    }
    Ok(ExitCode::from(1))
}
