//! `qmesh demo [-o DIR]`: a tour on built-in inputs through what qmesh can do so far.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Result;
use qmesh::apps::{GeneratedKind, generated_pattern_set};
use qmesh::build::{BuildOptions, build_volume_map, count_cell_kinds};
use qmesh::cmap::CMap3;
use qmesh::generate::{hex_grid, tet_grid};
use qmesh::io::{WriteOptions, write_map};
use qmesh::pattern::FlagRule;
use qmesh::replace::{ReplaceOptions, query_replace};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Folder for the files the demo writes.
    #[arg(short, long, default_value = "qmesh-demo")]
    pub output: PathBuf,
}

fn describe(step: &str, m: &CMap3) {
    let c = m.count_cells();
    let k = count_cell_kinds(m);
    let valid = m.is_valid().is_empty();
    println!(
        "  {step:<34} {:>8} darts {:>6} vertices {:>6} volumes ({} hex, {} tet, {} other)  χ = {}  valid = {valid}",
        c.darts,
        c.vertices,
        c.volumes,
        k.hex,
        k.tet,
        k.other,
        c.euler_characteristic(3)
    );
}

pub fn run(a: Args) -> Result<ExitCode> {
    std::fs::create_dir_all(&a.output)?;
    let t = Instant::now();
    println!("qmesh demo: writing into {}", a.output.display());
    let opts = BuildOptions::default();
    let (mut hex, _) = build_volume_map(&hex_grid(6, 4, 3), &opts)?;
    describe("6×4×3 hex grid", &hex);
    write_map(&a.output.join("hex_grid.vtk"), &hex, None, &WriteOptions::default())?;
    let (tet, _) = build_volume_map(&tet_grid(4, 4, 4), &opts)?;
    describe("4×4×4 grid split into 384 tets", &tet);
    write_map(&a.output.join("tet_grid.mesh"), &tet, None, &WriteOptions::default())?;
    write_map(&a.output.join("hex_grid_boundary.off"), &hex, None, &WriteOptions::default())?;
    write_map(&a.output.join("tet_grid.moka"), &tet, None, &WriteOptions::default())?;
    let mut split = hex.clone();
    let edges = split.split_all_edges(2)?;
    describe(&format!("hex grid, {edges} edges split in 2"), &split);
    write_map(&a.output.join("hex_grid_split.vtk"), &split, None, &WriteOptions::default())?;
    // Query-replace (2022) with pattern sets qmesh generates itself.
    let opts = ReplaceOptions { split_edges: Some(2), ..ReplaceOptions::default() };
    let subdivision = generated_pattern_set(GeneratedKind::HexSubdivision, FlagRule::Corners)?;
    let r = query_replace(&mut hex, &subdivision, &opts)?;
    describe(&format!("subdivided: {} faces, {} hexes replaced", r.faces_replaced, r.volumes_replaced), &hex);
    write_map(&a.output.join("hex_grid_subdivided.vtk"), &hex, None, &WriteOptions::default())?;
    let mut tet = tet;
    let r = query_replace(&mut tet, &generated_pattern_set(GeneratedKind::Tet2Hex, FlagRule::Corners)?, &opts)?;
    describe(&format!("tets to hexes: {} tets replaced", r.volumes_replaced), &tet);
    write_map(&a.output.join("tet_grid_to_hex.vtk"), &tet, None, &WriteOptions::default())?;
    println!("files: hex_grid.vtk, tet_grid.mesh, hex_grid_boundary.off (boundary surface), tet_grid.moka");
    println!("       (generalized map), hex_grid_split.vtk (edges split: cells become polyhedra),");
    println!("       hex_grid_subdivided.vtk (each hex in 8), tet_grid_to_hex.vtk (each tet in 4 hexes)");
    println!("done in {:.2} s — try: qmesh info {}/tet_grid.mesh", t.elapsed().as_secs_f64(), a.output.display());
    Ok(ExitCode::SUCCESS)
}
