//! `qmesh generate grid|tet-grid|terrain --size N -o OUT`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Result;
use qmesh::generate::{TerrainOptions, hex_grid, terrain, terrain_map, tet_grid};
use qmesh::io::{Format, WriteOptions, resolve_format, write_indexed};
use serde_json::json;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// What to generate.
    pub kind: Kind,
    /// Cells along each axis: N (N×N×N; N×N voxels for a terrain), or NX,NY,NZ
    /// (NX,NY for a terrain).
    #[arg(long, default_value = "10")]
    pub size: String,
    /// Terrain: seed of the height map.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Terrain: share of the random displacement kept at each halving of the
    /// diamond-square step (0 < R ≤ 1; smaller is smoother).
    #[arg(long, default_value_t = 0.5)]
    pub roughness: f64,
    /// Terrain: height between the lowest and the highest top corner (0: flat).
    #[arg(long, default_value_t = 8.0)]
    pub relief: f64,
    /// Terrain: height of the lowest top corner (bottoms are at 0).
    #[arg(long, default_value_t = 1.0)]
    pub base: f64,
    /// Output file.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write binary legacy VTK.
    #[arg(long)]
    pub binary: bool,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Unit hexahedra.
    Grid,
    /// The grid with each cell split into 6 tetrahedra.
    TetGrid,
    /// One layer of voxels under a diamond-square height map, bottoms split in two
    /// triangles (2025 §7.4): polyhedra, so write .vtk or .vtu.
    Terrain,
}

pub fn parse_size(s: &str) -> Result<[usize; 3]> {
    let v: Vec<usize> = s.split(',').map(|x| x.trim().parse()).collect::<Result<_, _>>()?;
    match v.as_slice() {
        [n] => Ok([*n; 3]),
        [x, y, z] => Ok([*x, *y, *z]),
        _ => anyhow::bail!("--size takes N or NX,NY,NZ, got '{s}'"),
    }
}

pub fn run(a: Args) -> Result<ExitCode> {
    let t = Instant::now();
    // A terrain's map is made directly (2025 Table 2, step 1, counts its darts), checked
    // before writing; grids are written as they are.
    let mut built = None;
    let mesh = match a.kind {
        Kind::Grid | Kind::TetGrid => {
            let [x, y, z] = parse_size(&a.size)?;
            anyhow::ensure!(x > 0 && y > 0 && z > 0, "--size must be positive");
            if a.kind == Kind::Grid { hex_grid(x, y, z) } else { tet_grid(x, y, z) }
        }
        Kind::Terrain => {
            let [nx, ny] = parse_terrain_size(&a.size)?;
            anyhow::ensure!(
                a.roughness > 0.0 && a.roughness <= 1.0,
                "--roughness must be in (0, 1], got {}",
                a.roughness
            );
            anyhow::ensure!(a.relief >= 0.0 && a.relief.is_finite(), "--relief must be 0 or more, got {}", a.relief);
            anyhow::ensure!(a.base > 0.0 && a.base.is_finite(), "--base must be above 0, got {}", a.base);
            let o = TerrainOptions { nx, ny, seed: a.seed, roughness: a.roughness, relief: a.relief, base: a.base };
            let map = terrain_map(&o);
            let seconds = t.elapsed().as_secs_f64();
            if let Some(v) = map.is_valid().first() {
                anyhow::bail!("the generated map is not valid ({v}); nothing written");
            }
            built = Some((map.count_cells(), seconds));
            terrain(&o)
        }
    };
    let generate_seconds = built.as_ref().map_or_else(|| t.elapsed().as_secs_f64(), |b| b.1);
    let format: Format = resolve_format(&a.output, None)?;
    write_indexed(&a.output, &mesh, format, &WriteOptions { binary: a.binary })?;
    if a.report.json {
        let j = json!({
            "output": a.output.display().to_string(),
            "points": mesh.points.len(),
            "cells": mesh.nb_cells(),
            "volumes": built.as_ref().map(|(c, _)| c.volumes),
            "darts": built.as_ref().map(|(c, _)| c.darts),
            "generate_seconds": generate_seconds,
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        let map = built.map_or(String::new(), |(c, _)| format!("; map: {} volumes, {} darts", c.volumes, c.darts));
        println!(
            "wrote {} ({} points, {} cells{map}; generated in {generate_seconds:.3} s)",
            a.output.display(),
            mesh.points.len(),
            mesh.nb_cells(),
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// A terrain's `--size`: N (N×N voxels) or NX,NY.
fn parse_terrain_size(s: &str) -> Result<[usize; 2]> {
    let v: Vec<usize> = s
        .split(',')
        .map(|x| x.trim().parse())
        .collect::<Result<_, _>>()
        .map_err(|_| anyhow::anyhow!("--size takes N or NX,NY for a terrain, got '{s}'"))?;
    match v.as_slice() {
        [n] if *n > 0 => Ok([*n, *n]),
        [x, y] if *x > 0 && *y > 0 => Ok([*x, *y]),
        _ => anyhow::bail!("--size takes N or NX,NY (positive) for a terrain, got '{s}'"),
    }
}
