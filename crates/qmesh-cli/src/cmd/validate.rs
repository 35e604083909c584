//! `qmesh validate FILE`: exit status 1 and the violations when the map is invalid.

use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::BuildOptions;
use qmesh::io::load_map;
use qmesh::report::ValidityReport;

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
    /// Print a JSON object (the same exit status).
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    let r = ValidityReport::of(&a.input.input, &loaded, a.max);
    let failed = !r.valid || (a.strict && !r.geometrically_valid);
    let status = if failed { ExitCode::from(1) } else { ExitCode::SUCCESS };
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(status);
    }
    let geometric = [
        (r.inverted_cells, "inverted (negative volume; --fix-orientation reverses their node order)"),
        (r.tangled_cells, "tangled (positive volume, negative corner Jacobian; no node order fixes them)"),
        (r.degenerate_cells, "degenerate (zero volume)"),
    ];
    for &(n, what) in geometric.iter().filter(|g| g.0 > 0) {
        eprintln!("{}: {n} cells {what}", if a.strict { "error" } else { "warning" });
    }
    if r.valid {
        let state = if r.geometrically_valid { "valid" } else { "combinatorially valid, geometrically defective" };
        println!("{}: {state} ({} darts)", r.file, r.darts);
        return Ok(status);
    }
    println!("{}: INVALID, {} violations", r.file, r.violations);
    for x in &r.problems {
        println!("  {x}");
    }
    if r.violations > r.problems.len() {
        println!("  … and {} more", r.violations - r.problems.len());
    }
    Ok(status)
}
