//! `qmesh modify IN OUT --rules RULES.toml`: run each rule of a rule file in order
//! (query, select, then extend / delete / replace every selected match, 2025 §6).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::BuildOptions;
use qmesh::io::{WriteOptions, load_map, write_map};
use qmesh::modify::{load_rules, run_rules};
use serde_json::json;

use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output mesh.
    pub output: PathBuf,
    /// The rule file (TOML, see `qmesh::modify` docs and examples/).
    #[arg(long)]
    pub rules: PathBuf,
    #[command(flatten)]
    pub report: super::ReportArgs,
    /// Allow the output to be the input file.
    #[arg(long)]
    pub force: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    super::refuse_to_overwrite(&a.input.input, &a.output, a.force)?;
    let rules = load_rules(&a.rules)?;
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let mut loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    let pb = crate::progress::spinner("modify", a.report.quiet || a.report.json);
    let reports = run_rules(&mut loaded.map, &rules);
    pb.finish_and_clear();
    let valid = reports.iter().all(|r| r.valid);
    if valid {
        write_map(&a.output, &loaded.map, None, &WriteOptions::default())?;
    }
    let after = loaded.map.count_cells();
    if a.report.json {
        let j = json!({
            "input": a.input.input.display().to_string(),
            "output": valid.then(|| a.output.display().to_string()),
            "rules": reports,
            "volumes": after.volumes,
            "darts": after.darts,
            "euler_characteristic": after.euler_characteristic(3),
            "valid": valid,
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        for r in &reports {
            println!(
                "rule {} ({}): {} matches, {} selected, {} modified; volumes {} -> {}, darts {} -> {}; query {:.4} s, modify {:.4} s; valid: {}",
                r.rule,
                r.op,
                r.matches,
                r.selected,
                r.modified,
                r.volumes_before,
                r.volumes_after,
                r.darts_before,
                r.darts_after,
                r.query_seconds,
                r.modify_seconds,
                r.valid
            );
            if let Some(p) = &r.problem {
                println!("  problem: {p}");
            }
        }
        if valid {
            println!("wrote {} ({} volumes, χ {})", a.output.display(), after.volumes, after.euler_characteristic(3));
        }
    }
    if !valid {
        eprintln!("error: the map is not valid after the rules; nothing written");
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}
