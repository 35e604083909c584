//! `qmesh convert IN OUT` (or `-o OUT`): read, build the map, write (atomically).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::BuildOptions;
use qmesh::io::{Format, WriteOptions, indexed_for, load_map, resolve_format, write_indexed, write_map};

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
    /// No summary (warnings and errors are still printed, on stderr; the exit status
    /// tells the outcome), as with the other commands.
    #[arg(short, long)]
    pub quiet: bool,
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
    if format == Format::Moka {
        write_map(&output, &loaded.map, Some(format), &opts)?;
        if !a.quiet {
            let c = loaded.map.count_cells();
            println!("wrote {} (the map: {} darts, {} volumes)", output.display(), loaded.map.nb_darts(), c.volumes);
        }
        return Ok(ExitCode::SUCCESS);
    }
    let unused = loaded.report.unreferenced_points;
    let mesh = indexed_for(&loaded.map, &loaded.cell_arrays, format, !a.drop_unused);
    write_indexed(&output, &mesh, format, &opts)?;
    if a.quiet {
        return Ok(ExitCode::SUCCESS);
    }
    // What the file holds, as written (a surface format gets the boundary surface).
    let what = if format.is_surface() && mesh.nb_polygons() > 0 && loaded.map.dimension() == 3 {
        format!("{} polygons: the boundary surface of {} cells", mesh.nb_polygons(), loaded.map.count_cells().volumes)
    } else if mesh.is_volume() {
        format!("{} cells", mesh.nb_cells())
    } else {
        format!("{} polygons", mesh.nb_polygons())
    };
    println!("wrote {} ({} points, {what})", output.display(), mesh.points.len());
    if unused > 0 && !(format.is_surface() && loaded.map.dimension() == 3) {
        if a.drop_unused {
            println!("  {unused} points that no cell uses were left out (--drop-unused)");
        } else {
            println!("  {unused} of the points are used by no cell; kept (--drop-unused leaves them out)");
        }
    }
    Ok(ExitCode::SUCCESS)
}
