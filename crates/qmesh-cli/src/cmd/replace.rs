//! `qmesh replace --patterns DIR… [--split-edges K] IN OUT`: the 2022 query-replace
//! pipeline with user pattern sets, no code.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, bail};
use qmesh::build::{BuildOptions, CellValues, count_cell_kinds, extract, volume_values};
use qmesh::io::{Format, WriteOptions, load_map, resolve_format, write_indexed, write_map};
use qmesh::pattern::{PatternKind, PatternSet};
use qmesh::replace::{ReplaceOptions, query_replace};
use serde_json::json;

use super::patterns::Flags;
use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output mesh.
    pub output: PathBuf,
    /// Pattern folders (searched recursively; `fpattern/`, `vpattern/` layout honoured) or files.
    /// Repeat the option or separate folders with commas.
    #[arg(long, value_delimiter = ',', required = true)]
    pub patterns: Vec<PathBuf>,
    /// Split every edge into K segments first (the e-pattern).
    #[arg(long)]
    pub split_edges: Option<usize>,
    /// Flags on input and patterns (see the values below).
    #[arg(long, default_value = "corners")]
    pub flags: Flags,
    /// Test every pattern directly instead of looking signatures up (2022 §2.3).
    #[arg(long)]
    pub no_signatures: bool,
    #[command(flatten)]
    pub report: super::ReportArgs,
    /// Allow the output to be the input file.
    #[arg(long)]
    pub force: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    super::refuse_to_overwrite(&a.input.input, &a.output, a.force)?;
    let mut set = PatternSet::default();
    for dir in &a.patterns {
        let s = super::patterns::pattern_dir(dir, a.flags.into())?;
        set.skipped.extend(s.skipped);
        for p in s.patterns {
            set.insert(p);
        }
    }
    if set.patterns.is_empty() && a.split_edges.is_none() {
        bail!("no usable pattern in {}", super::patterns::path_list(&a.patterns));
    }
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let mut phases = crate::phases::Phases::start();
    let mut loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    phases.lap("read");
    let before = loaded.map.count_cells();
    let pb = crate::progress::spinner("query-replace", a.report.quiet || a.report.json);
    let r = query_replace(
        &mut loaded.map,
        &set,
        &ReplaceOptions { split_edges: a.split_edges, flags: a.flags.into(), use_signatures: !a.no_signatures },
    )?;
    pb.finish_and_clear();
    phases.lap_replace("select", &r);
    let violations = loaded.map.is_valid();
    let after = loaded.map.count_cells();
    phases.lap("validate");
    match resolve_format(&a.output, None)? {
        // Volume formats get the cells with the index of the pattern that made each one.
        f @ (Format::Vtk | Format::Vtu) if loaded.map.dimension() == 3 => {
            let (mut cells, _) = extract(&loaded.map);
            let ids = volume_values(&loaded.map, &r.created_volumes, -1);
            cells.set_cell_array("pattern_id", CellValues::Int(ids));
            write_indexed(&a.output, &cells, f, &WriteOptions::default())?;
        }
        _ => write_map(&a.output, &loaded.map, None, &WriteOptions::default())?,
    }
    phases.lap("write");
    let kinds = count_cell_kinds(&loaded.map);
    if a.report.json {
        let j = json!({
            "input": a.input.input.display().to_string(),
            "output": a.output.display().to_string(),
            "edges_split": r.edges_split,
            "faces_replaced": r.faces_replaced,
            "volumes_replaced": r.volumes_replaced,
            "unmatched_faces": r.unmatched_faces,
            "unmatched_volumes": r.unmatched_volumes,
            "matches": set.patterns.iter().zip(&r.matches).map(|(p, n)| json!({"file": p.file.display().to_string(), "kind": p.kind.name(), "matches": n})).collect::<Vec<_>>(),
            "uncovered": super::patterns::uncovered_json(&r.uncovered),
            "skipped_patterns": set.skipped.iter().map(|s| json!({"file": s.file.display().to_string(), "reason": s.reason})).collect::<Vec<_>>(),
            "volumes_before": before.volumes,
            "volumes": after.volumes,
            "darts": after.darts,
            "cell_types": {"tet": kinds.tet, "pyramid": kinds.pyramid, "prism": kinds.prism, "hex": kinds.hex, "other": kinds.other},
            "euler_characteristic": after.euler_characteristic(3),
            "valid": violations.is_empty(),
            "query_seconds": r.query_seconds,
            "replace_seconds": r.replace_seconds,
            "phases": phases.json(),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        println!(
            "{} f-patterns, {} v-patterns; {} edges split, {} faces and {} volumes replaced ({} faces, {} volumes unmatched)",
            set.count(PatternKind::Face),
            set.count(PatternKind::Volume),
            r.edges_split,
            r.faces_replaced,
            r.volumes_replaced,
            r.unmatched_faces,
            r.unmatched_volumes
        );
        println!(
            "volumes {} -> {} ({} hex, {} tet, {} other), χ {} -> {}, valid: {}; query {:.3} s, replace {:.3} s",
            before.volumes,
            after.volumes,
            kinds.hex,
            kinds.tet,
            kinds.other,
            before.euler_characteristic(3),
            after.euler_characteristic(3),
            violations.is_empty(),
            r.query_seconds,
            r.replace_seconds
        );
        for u in r.uncovered.iter().take(10) {
            println!("uncovered {:<9} {}  ×{}  e.g. at {:?}", u.kind.name(), u.signature.digest(), u.count, u.sample);
        }
        for s in &set.skipped {
            println!("skipped pattern {}: {}", s.file.display(), s.reason);
        }
        println!("wrote {}", a.output.display());
    }
    Ok(if violations.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) })
}
