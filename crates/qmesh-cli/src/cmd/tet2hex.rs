//! `qmesh tet2hex IN -o OUT`: every tetrahedron into 4 hexahedra by query-replace
//! (2022 §7.4).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, bail};
use qmesh::apps::tet_to_hex;
use qmesh::build::{BuildOptions, CellValues, count_cell_kinds, extract, quality_by_kind, volume_values};
use qmesh::io::{WriteOptions, load_map, resolve_format, write_indexed};
use serde_json::json;

use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub output: super::OutputArgs,
    /// Pattern folders replacing the generated `tet2hex` set.
    /// Repeat the option or separate folders with commas.
    #[arg(long, value_delimiter = ',')]
    pub patterns: Vec<PathBuf>,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

pub fn run(a: Args) -> Result<ExitCode> {
    a.output.check_against(&a.input.input)?;
    let out_format = resolve_format(&a.output.output, None)?;
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let mut phases = crate::phases::Phases::start();
    let mut loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    phases.lap("read");
    let before = loaded.map.count_cells();
    let input_kinds = count_cell_kinds(&loaded.map);
    let others = before.volumes - input_kinds.tet;
    if input_kinds.tet == 0 {
        bail!(
            "{}: no tetrahedra ({} other cells); tet2hex turns tetrahedra into hexahedra, so nothing was written",
            a.input.input.display(),
            before.volumes
        );
    }
    if others > 0 {
        eprintln!(
            "warning: {others} cells are not tetrahedra; every edge is split (so that the mesh stays conformal), \
             so they are written as polyhedra"
        );
    }
    let set = super::patterns::load_sets(&a.patterns)?;
    let pb = crate::progress::spinner("tet2hex", a.report.quiet || a.report.json);
    phases.lap("patterns");
    let r = tet_to_hex(&mut loaded.map, set.as_ref(), true)?;
    pb.finish_and_clear();
    phases.lap_replace("select", &r);
    let valid = loaded.map.is_valid().is_empty();
    phases.lap("validate");
    let (mut cells, kinds) = extract(&loaded.map);
    cells.set_cell_array("pattern_id", CellValues::Int(volume_values(&loaded.map, &r.created_volumes, -1)));
    phases.lap("extract");
    let quality = quality_by_kind(&cells);
    phases.lap("quality");
    write_indexed(&a.output.output, &cells, out_format, &WriteOptions::default())?;
    phases.lap("write");
    if a.report.json {
        let j = json!({
            "input": a.input.input.display().to_string(),
            "output": a.output.output.display().to_string(),
            "volumes_before": before.volumes,
            "edges_split": r.edges_split,
            "faces_replaced": r.faces_replaced,
            "volumes_replaced": r.volumes_replaced,
            "unmatched_volumes": r.unmatched_volumes,
            "cell_types": {"hex": kinds.hex, "tet": kinds.tet, "prism": kinds.prism, "pyramid": kinds.pyramid, "other": kinds.other},
            "scaled_jacobian": qmesh::report::Summary::by_kind(&quality),
            "valid": valid,
            "query_seconds": r.query_seconds,
            "replace_seconds": r.replace_seconds,
            "phases": phases.json(),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        println!(
            "{} volumes -> {} hex ({} other cells kept); {} edges split, {} faces and {} tetrahedra replaced; valid: {valid}",
            before.volumes,
            kinds.hex,
            kinds.tet + kinds.prism + kinds.pyramid + kinds.other,
            r.edges_split,
            r.faces_replaced,
            r.volumes_replaced
        );
        print!("{}", qmesh::report::Summary::by_kind_text(&quality));
        println!(
            "query {:.3} s, replace {:.3} s; wrote {}",
            r.query_seconds,
            r.replace_seconds,
            a.output.output.display()
        );
    }
    Ok(if valid { ExitCode::SUCCESS } else { ExitCode::from(1) })
}
