//! `qmesh conformal IN -o OUT [--patterns DIR…]`: conformal transitions of a 2:1
//! octree hexahedral mesh (2022 Algorithm 7).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, bail};
use qmesh::apps::conformal;
use qmesh::build::{CellValues, extract, volume_values};
use qmesh::io::{Loaded, WriteOptions, read, resolve_format, write_indexed};
use qmesh::pattern::PatternKind;
use serde_json::json;

use super::parse_format;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// A 2:1-balanced octree hexahedral mesh (e.g. from `qmesh subdivide`).
    pub input: PathBuf,
    #[command(flatten)]
    pub output: super::OutputArgs,
    /// Transition pattern folders (default: qmesh's generated `transitions` set). The
    /// papers' set: hexa-325-patterns and square-5-patterns.
    /// Repeat the option or separate folders with commas.
    #[arg(long, value_delimiter = ',')]
    pub patterns: Vec<PathBuf>,
    /// Test every pattern directly instead of looking signatures up.
    #[arg(long)]
    pub no_signatures: bool,
    /// Input format, overriding the extension.
    #[arg(long)]
    pub format: Option<String>,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

pub fn run(a: Args) -> Result<ExitCode> {
    a.output.check_against(&a.input)?;
    let out_format = resolve_format(&a.output.output, None)?;
    let set = super::patterns::transition_set(&a.patterns)?;
    let mut phases = crate::phases::Phases::start();
    let mesh = match read(&a.input, parse_format(&a.format)?)? {
        Loaded::Indexed(m) if m.is_volume() => m,
        _ => bail!("{}: expected a hexahedral volume mesh", a.input.display()),
    };
    let pb = crate::progress::spinner("conformal", a.report.quiet || a.report.json);
    phases.lap("read");
    let (map, r) = conformal(&mesh, &set, !a.no_signatures)?;
    pb.finish_and_clear();
    phases.lap_inner("check_octree", &r.phases.list());
    let valid = map.is_valid().is_empty();
    phases.lap("validate");
    let nonconformal = qmesh::build::non_conformal_faces(&map);
    phases.lap("conformity");
    let (mut cells, _) = extract(&map);
    cells.set_cell_array("pattern_id", CellValues::Int(volume_values(&map, &r.replace.created_volumes, -1)));
    phases.lap("extract");
    let quality = qmesh::build::quality_by_kind(&cells);
    phases.lap("quality");
    write_indexed(&a.output.output, &cells, out_format, &WriteOptions::default())?;
    phases.lap("write");
    let k = &r.kinds;
    let rep = &r.replace;
    if a.report.json {
        let j = json!({
            "input": a.input.display().to_string(),
            "output": a.output.output.display().to_string(),
            "f_patterns": set.count(PatternKind::Face),
            "v_patterns": set.count(PatternKind::Volume),
            "hanging_vertices": r.hanging.hanging_vertices,
            "cells_with_hanging_vertices": r.hanging.cells_with_hanging,
            "faces_replaced": rep.faces_replaced,
            "volumes_replaced": rep.volumes_replaced,
            "unmatched_faces": rep.unmatched_faces,
            "unmatched_volumes": rep.unmatched_volumes,
            "uncovered": super::patterns::uncovered_json(&rep.uncovered),
            "cell_types": {"hex": k.hex, "tet": k.tet, "prism": k.prism, "pyramid": k.pyramid, "other": k.other},
            "non_conformal_faces": nonconformal,
            "scaled_jacobian": qmesh::report::Summary::by_kind(&quality),
            "valid": valid,
            "query_seconds": rep.query_seconds,
            "replace_seconds": rep.replace_seconds,
            "seconds": r.seconds,
            "phases": phases.json(),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        println!(
            "{} f- and {} v-patterns; {} hanging vertices in {} cells; {} faces and {} volumes replaced ({} / {} unmatched)",
            set.count(PatternKind::Face),
            set.count(PatternKind::Volume),
            r.hanging.hanging_vertices,
            r.hanging.cells_with_hanging,
            rep.faces_replaced,
            rep.volumes_replaced,
            rep.unmatched_faces,
            rep.unmatched_volumes
        );
        println!(
            "{} hex, {} tet, {} prism, {} pyramid, {} other; non-conformal faces: {nonconformal}; valid: {valid}",
            k.hex, k.tet, k.prism, k.pyramid, k.other
        );
        print!("{}", qmesh::report::Summary::by_kind_text(&quality));
        println!(
            "query {:.3} s, replace {:.3} s, total {:.3} s; wrote {}",
            rep.query_seconds,
            rep.replace_seconds,
            r.seconds,
            a.output.output.display()
        );
    }
    Ok(if valid && nonconformal == 0 && rep.unmatched_volumes == 0 { ExitCode::SUCCESS } else { ExitCode::from(1) })
}
