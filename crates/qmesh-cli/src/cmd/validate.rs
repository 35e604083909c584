//! `qmesh validate FILE`: exit status 1 and the violations when the map is invalid.

use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::BuildOptions;
use qmesh::io::load_map;

use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// How many violations to print at most.
    #[arg(long, default_value_t = 20)]
    pub max: usize,
}

pub fn run(a: Args) -> Result<ExitCode> {
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    let v = loaded.map.is_valid();
    if v.is_empty() {
        println!("{}: valid ({} darts)", a.input.input.display(), loaded.map.nb_darts());
        return Ok(ExitCode::SUCCESS);
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
