//! `qmesh info FILE [--json]`.

use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::BuildOptions;
use qmesh::io::load_map;
use qmesh::report::InfoReport;

use super::{InputArgs, parse_format};
use crate::memory::peak_rss_bytes;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub input: InputArgs,
    /// Print a JSON object instead of the human summary.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    let r = InfoReport::of(&a.input.input, &loaded);
    if a.json {
        let mut j = serde_json::to_value(&r)?;
        j["peak_memory_bytes"] = serde_json::json!(peak_rss_bytes());
        println!("{}", serde_json::to_string_pretty(&j)?);
        return Ok(ExitCode::SUCCESS);
    }
    let surface = r.dimension == 2;
    println!("{}", r.file);
    println!(
        "  {} map: {} darts ({} bytes, {} B/dart + positions)",
        if surface { "surface" } else { "volume" },
        r.darts,
        r.map_bytes,
        r.bytes_per_dart
    );
    println!("  vertices {}  edges {}  faces {}  volumes {}", r.vertices, r.edges, r.faces, r.volumes);
    if let Some(edges) = r.boundary_edges {
        println!("  boundary edges {edges}");
    } else {
        println!("  boundary faces {}  non-conformal faces {}", r.boundary_faces, r.non_conformal_faces);
        let k = &r.cell_types;
        println!("  cells: {} hex, {} tet, {} prism, {} pyramid, {} other", k.hex, k.tet, k.prism, k.pyramid, k.other);
        println!(
            "  inverted cells {}{}  tangled cells {}  degenerate cells {}",
            r.inverted_cells,
            if r.flipped_cells > 0 { " (flipped)" } else { "" },
            r.tangled_cells,
            r.degenerate_cells
        );
        if r.tangled_cells > 0 {
            println!("  note: tangled = positive volume but a negative corner Jacobian (see qmesh quality)");
        }
    }
    println!("  Euler characteristic {}  components {}", r.euler_characteristic, r.components);
    println!(
        "  valid: {}",
        if r.valid { "yes".to_string() } else { format!("NO ({} violations; run qmesh validate)", r.violations) }
    );
    for w in &r.warnings {
        println!("  warning: {w}");
    }
    println!(
        "  read {:.3} s, build {:.3} s, peak memory {:.1} MB",
        r.read_seconds,
        r.build_seconds,
        peak_rss_bytes().unwrap_or(0) as f64 / 1e6
    );
    Ok(ExitCode::SUCCESS)
}
