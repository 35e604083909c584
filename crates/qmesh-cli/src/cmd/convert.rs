//! `qmesh convert IN OUT` (or `-o OUT`): read, build the map, write (atomically).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::BuildOptions;
use qmesh::io::{Format, WriteOptions, indexed_for, load_map, resolve_format, write_indexed, write_map};
use serde_json::{Value, json};

use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("out").required(true).args(["output", "output_flag"])))]
#[command(
    override_usage = "qmesh convert [OPTIONS] <INPUT> <OUTPUT>\n       qmesh convert [OPTIONS] <INPUT> -o <OUTPUT>"
)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output file; its extension picks the format unless --to is given.
    pub output: Option<PathBuf>,
    /// The output file given as the other commands take it (`-o OUT`), instead of
    /// after the input.
    #[arg(short = 'o', long = "output", value_name = "OUTPUT")]
    pub output_flag: Option<PathBuf>,
    /// Output format, overriding the output extension.
    #[arg(long)]
    pub to: Option<String>,
    /// Write binary legacy VTK.
    #[arg(long)]
    pub binary: bool,
    /// Allow the output to be the input file.
    #[arg(long)]
    pub force: bool,
    /// Leave out the points that no cell uses (kept by default).
    #[arg(long)]
    pub drop_unused: bool,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

pub fn run(mut a: Args) -> Result<ExitCode> {
    let output = a.output.take().or(a.output_flag.take()).expect("clap requires one output");
    super::refuse_to_overwrite(&a.input.input, &output, a.force)?;
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
    let format = resolve_format(&output, parse_format(&a.to)?)?;
    let opts = WriteOptions { binary: a.binary };
    let io = json!({"input": a.input.input.display().to_string(), "output": output.display().to_string(),
        "format": format.name()});
    if format == Format::Moka {
        write_map(&output, &loaded.map, Some(format), &opts)?;
        let (darts, volumes) = (loaded.map.nb_darts(), loaded.map.count_cells().volumes);
        if a.report.json {
            print_json(io, json!({"darts": darts, "volumes": volumes}))?;
        } else if !a.report.quiet {
            println!("wrote {} (the map: {darts} darts, {volumes} volumes)", output.display());
        }
        return Ok(ExitCode::SUCCESS);
    }
    let unused = loaded.report.unreferenced_points;
    let mesh = indexed_for(&loaded.map, &loaded.cell_arrays, format, !a.drop_unused);
    write_indexed(&output, &mesh, format, &opts)?;
    // What the file holds, as written (a surface format gets the boundary surface).
    let boundary = format.is_surface() && loaded.map.dimension() == 3;
    if a.report.json {
        let counts = json!({
            "points": mesh.points.len(), "cells": mesh.nb_cells(), "polygons": mesh.nb_polygons(),
            "boundary_of_volumes": boundary.then(|| loaded.map.count_cells().volumes),
            "unused_points": if boundary { 0 } else { unused },
            "unused_points_left_out": if a.drop_unused && !boundary { unused } else { 0 },
        });
        print_json(io, counts)?;
        return Ok(ExitCode::SUCCESS);
    }
    if a.report.quiet {
        return Ok(ExitCode::SUCCESS);
    }
    let what = if boundary && mesh.nb_polygons() > 0 {
        format!("{} polygons: the boundary surface of {} cells", mesh.nb_polygons(), loaded.map.count_cells().volumes)
    } else if mesh.is_volume() {
        format!("{} cells", mesh.nb_cells())
    } else {
        format!("{} polygons", mesh.nb_polygons())
    };
    println!("wrote {} ({} points, {what})", output.display(), mesh.points.len());
    if unused > 0 && !boundary {
        if a.drop_unused {
            println!("  {unused} points that no cell uses were left out (--drop-unused)");
        } else {
            println!("  {unused} of the points are used by no cell; kept (--drop-unused leaves them out)");
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Prints the input and output names and `counts` as one JSON object.
fn print_json(io: Value, counts: Value) -> Result<()> {
    let mut all = io;
    if let (Value::Object(all), Value::Object(counts)) = (&mut all, counts) {
        all.extend(counts);
        all.insert("peak_memory_bytes".into(), json!(crate::memory::peak_rss_bytes()));
    }
    println!("{}", serde_json::to_string_pretty(&all)?);
    Ok(())
}
