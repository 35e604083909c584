//! `qmesh info FILE [--json]`.

use std::process::ExitCode;

use anyhow::Result;
use qmesh::build::{BuildOptions, count_kinds_of, extract, non_conformal_faces_of, tangled_cells};
use qmesh::cmap::CMap3;
use qmesh::io::load_map;
use serde_json::json;

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
    let map: &CMap3 = &loaded.map;
    let census = map.census();
    let (c, violations) = (&census.counts, &census.violations);
    let surface = map.dimension() == 2;
    let kinds = count_kinds_of(map, &census.volume_reps);
    let t = std::time::Instant::now();
    let non_conformal = if surface { 0 } else { non_conformal_faces_of(map, &census.boundary_reps) };
    let conformity_seconds = t.elapsed().as_secs_f64();
    let tangled = if surface { 0 } else { tangled_cells(&extract(map).0) };
    let mut j = json!({
        "file": a.input.input.display().to_string(),
        "dimension": map.dimension(),
        "darts": c.darts,
        "vertices": c.vertices,
        "edges": c.edges,
        "faces": c.faces,
        "volumes": if surface { 0 } else { c.volumes },
        "boundary_faces": if surface { 0 } else { c.boundary_faces },
        "euler_characteristic": c.euler_characteristic(map.dimension()),
        "components": c.components,
        "cell_types": {"tet": kinds.tet, "pyramid": kinds.pyramid, "prism": kinds.prism, "hex": kinds.hex, "other": kinds.other},
        "non_conformal_faces": non_conformal,
        "conformity_seconds": conformity_seconds,
        "inverted_cells": loaded.report.inverted_cells,
        "flipped_cells": loaded.report.flipped_cells,
        "degenerate_cells": loaded.report.degenerate_cells,
        "tangled_cells": tangled,
        "split_nonmanifold_vertices": loaded.report.split_vertices,
        "unreferenced_points": loaded.report.unreferenced_points,
        "valid": violations.is_empty(),
        "violations": violations.len(),
        "map_bytes": map.heap_bytes(),
        "bytes_per_dart": map.bytes_per_dart(),
        "warnings": loaded.warnings,
        "read_seconds": loaded.read_seconds,
        "build_seconds": loaded.build_seconds,
        "peak_memory_bytes": peak_rss_bytes(),
    });
    if surface {
        j["boundary_edges"] = json!(map.boundary_edges());
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&j)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!("{}", a.input.input.display());
    println!(
        "  {} map: {} darts ({} bytes, {} B/dart + positions)",
        if surface { "surface" } else { "volume" },
        c.darts,
        map.heap_bytes(),
        map.bytes_per_dart()
    );
    println!(
        "  vertices {}  edges {}  faces {}  volumes {}",
        c.vertices,
        c.edges,
        c.faces,
        if surface { 0 } else { c.volumes }
    );
    if surface {
        println!("  boundary edges {}", map.boundary_edges());
    } else {
        println!("  boundary faces {}  non-conformal faces {non_conformal}", c.boundary_faces);
        println!(
            "  cells: {} hex, {} tet, {} prism, {} pyramid, {} other",
            kinds.hex, kinds.tet, kinds.prism, kinds.pyramid, kinds.other
        );
        println!(
            "  inverted cells {}{}  tangled cells {tangled}  degenerate cells {}",
            loaded.report.inverted_cells,
            if loaded.report.flipped_cells > 0 { " (flipped)" } else { "" },
            loaded.report.degenerate_cells
        );
        if tangled > 0 {
            println!("  note: tangled = positive volume but a negative corner Jacobian (see qmesh quality)");
        }
    }
    println!("  Euler characteristic {}  components {}", c.euler_characteristic(map.dimension()), c.components);
    println!(
        "  valid: {}",
        if violations.is_empty() {
            "yes".to_string()
        } else {
            format!("NO ({} violations; run qmesh validate)", violations.len())
        }
    );
    for w in &loaded.warnings {
        println!("  warning: {w}");
    }
    println!(
        "  read {:.3} s, build {:.3} s, peak memory {:.1} MB",
        loaded.read_seconds,
        loaded.build_seconds,
        peak_rss_bytes().unwrap_or(0) as f64 / 1e6
    );
    Ok(ExitCode::SUCCESS)
}
