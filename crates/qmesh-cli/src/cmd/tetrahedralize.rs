//! `qmesh tetrahedralize IN -o OUT [--five|--any] [--seed S]`: every hexahedron split
//! into tetrahedra on its corners, conformally (the synthetic data of 2025 §7.1.1).

use std::process::ExitCode;

use anyhow::{Result, bail};
use qmesh::apps::{SplitChoice, TetrahedralizeOptions, tetrahedralize};
use qmesh::io::{Loaded, WriteOptions, read, resolve_format, write_indexed};
use serde_json::json;

use super::{InputArgs, OutputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub output: OutputArgs,
    /// As many 5-tetrahedron splits as a consistent choice of diagonals allows.
    #[arg(long, conflicts_with = "any")]
    pub five: bool,
    /// Any positive subdivision of each hexahedron, drawn uniformly (the default).
    #[arg(long)]
    pub any: bool,
    /// Seed of the random choices (diagonals and subdivisions).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

pub fn run(a: Args) -> Result<ExitCode> {
    a.output.check_against(&a.input.input)?;
    let out_format = resolve_format(&a.output.output, None)?;
    let mesh = match read(&a.input.input, parse_format(&a.input.format)?)? {
        Loaded::Indexed(m) => m,
        Loaded::Map(_) => {
            bail!("{}: a combinatorial map file; tetrahedralize reads cell meshes", a.input.input.display())
        }
    };
    let choice = if a.five { SplitChoice::Five } else { SplitChoice::Any };
    let t = std::time::Instant::now();
    let (tets, r) = tetrahedralize(&mesh, &TetrahedralizeOptions { choice, seed: a.seed })?;
    let seconds = t.elapsed().as_secs_f64();
    write_indexed(&a.output.output, &tets, out_format, &WriteOptions::default())?;
    if a.report.json {
        let j = json!({
            "input": a.input.input.display().to_string(),
            "output": a.output.output.display().to_string(),
            "choice": if a.five { "five" } else { "any" },
            "seed": a.seed,
            "report": r,
            "seconds": seconds,
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        let hist: Vec<String> = r.by_tet_count.iter().map(|(n, c)| format!("{n}:{c}")).collect();
        println!(
            "{} hexahedra -> {} tetrahedra ({} tetrahedra kept); tets per hex {}; {} classes used; {} diagonals flipped for positivity",
            r.hexes,
            r.tets,
            r.tets_kept,
            hist.join(" "),
            r.by_class.len(),
            r.diagonals_flipped
        );
        if a.five {
            let five = r.by_tet_count.get(&5).copied().unwrap_or(0);
            println!(
                "5-tet splits: {five} of {} hexahedra ({}; a 5-tet split of every hexahedron needs bipartite hex edges and positive 5-tet splits)",
                r.hexes,
                if r.bipartite { "the hex edges are bipartite" } else { "the hex edges are NOT bipartite" }
            );
        }
        println!("{seconds:.3} s; wrote {}", a.output.output.display());
    }
    Ok(ExitCode::SUCCESS)
}
