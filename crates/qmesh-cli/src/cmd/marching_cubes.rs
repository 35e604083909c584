//! `qmesh marching-cubes (SURFACE --levels L | --field FILE --dims NX,NY,NZ [--iso V])
//! -o OUT [--triangulate]`: surface extraction by query-replace (2022 Algorithm 6).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use qmesh::apps::{
    FieldOptions, McFlags, marching_cubes_field_with, marching_cubes_surface, mc_pattern_set, triangulate_owned,
};
use qmesh::build::surface_topology;
use qmesh::geom::TriangleBvh;
use qmesh::io::{WriteOptions, read_surface, resolve_format, write_indexed};
use qmesh::pattern::{FlagRule, PatternKind, PatternSet};
use serde_json::json;

use super::parse_format;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Surface whose octree hexahedra are marched (with --levels).
    #[arg(conflicts_with = "field", required_unless_present = "field")]
    pub surface: Option<PathBuf>,
    /// Octree depth for a surface input.
    #[arg(long, default_value_t = 5)]
    pub levels: u8,
    /// The octree's level-0 cells, as `subdivide` (`--root box --init X`: the authors'
    /// set-up, the same crossed cells as their `-marching-cubes`).
    #[command(flatten)]
    pub root: super::OctreeRootArgs,
    /// Raw little-endian float32 field, value of point (i, j, k) at (i·NY + j)·NZ + k.
    #[arg(long, requires = "dims")]
    pub field: Option<PathBuf>,
    /// Grid points per axis of the field: NX,NY,NZ.
    #[arg(long, value_delimiter = ',')]
    pub dims: Vec<usize>,
    /// Isovalue: inside where value ≤ iso.
    #[arg(long, default_value_t = 0.0)]
    pub iso: f64,
    /// How a field is marched: `compiled` query-replaces each case of cell once and lays
    /// its surface on every cell of the case; `maps` query-replaces every crossed cell
    /// on the maps of slabs of the grid. Both give the same surface; sets that place
    /// vertices inside cubes are always marched on maps.
    #[arg(long, value_enum, default_value_t = FieldEngine::Compiled)]
    pub engine: FieldEngine,
    /// Crossed cells marched at once per core (a field is marched slab by slab; the
    /// surface does not depend on it, memory does).
    #[arg(long, default_value_t = FieldOptions::default().slab_cells, value_parser = clap::value_parser!(usize))]
    pub slab_cells: usize,
    #[command(flatten)]
    pub output: super::OutputArgs,
    /// Pattern folders (.moka with mark 0 on inside-corner darts, as `qmesh patterns
    /// generate marching-cubes` writes them); default: the built-in set.
    /// Repeat the option or separate folders with commas.
    #[arg(long, value_delimiter = ',')]
    pub patterns: Vec<PathBuf>,
    /// Which darts are flagged: `inside` (inside corners: qmesh's generated set, flags
    /// in the files' marks) or `corners` (the cube's corners, inside or not: the authors'
    /// set). Default: `inside` when the pattern files carry flag marks, else `corners`.
    #[arg(long)]
    pub flags: Option<McFlagsArg>,
    /// Split the polygons into triangles.
    #[arg(long)]
    pub triangulate: bool,
    /// Surface input format, overriding the extension.
    #[arg(long)]
    pub format: Option<String>,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldEngine {
    Compiled,
    Maps,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum McFlagsArg {
    /// Darts at inside corners (inside/outside is part of the query).
    Inside,
    /// Darts at the cube's corners (only the split boundary's topology is queried).
    Corners,
}

/// The pattern set and flag rule for marching cubes: the built-in set, or the
/// folders' patterns read with the rule asked for (or the one their files imply).
fn mc_patterns(a: &Args) -> Result<(PatternSet, McFlags)> {
    if a.patterns.is_empty() {
        if a.flags == Some(McFlagsArg::Corners) {
            bail!("--flags corners needs --patterns (the built-in set flags inside corners)");
        }
        return Ok((mc_pattern_set(), McFlags::Inside));
    }
    let load = |rule: FlagRule| super::patterns::merged_sets(&a.patterns, rule);
    let flags = match a.flags {
        Some(McFlagsArg::Inside) => McFlags::Inside,
        Some(McFlagsArg::Corners) => McFlags::Corners,
        None => {
            // Inside-corner marks (qmesh's sets): every v-pattern marks some of its cube
            // corners and nothing else. The authors' files carry no such marks (a few
            // hold stray modeller marks): their rule is the cube corners.
            let marked = load(FlagRule::File)?;
            let corners = load(FlagRule::Corners)?;
            let flagged = |p: &qmesh::pattern::Pattern| -> Vec<qmesh::cmap::Dart> {
                p.map.darts().filter(|&d| p.map.is_marked(d, p.flags)).collect()
            };
            let geometric: std::collections::HashMap<&std::path::Path, Vec<qmesh::cmap::Dart>> =
                corners.patterns.iter().map(|p| (p.file.as_path(), flagged(p))).collect();
            let inside_marks = marked.patterns.iter().filter(|p| p.kind == PatternKind::Volume).all(|p| {
                let (marks, at_corners) = (flagged(p), geometric.get(p.file.as_path()));
                !marks.is_empty() && at_corners.is_some_and(|c| marks.iter().all(|d| c.contains(d)))
            });
            if inside_marks {
                super::patterns::warn_skipped(&marked);
                return Ok((marked, McFlags::Inside));
            }
            if !a.report.quiet && !a.report.json {
                eprintln!("note: the patterns flag the cube's corners (the authors' rule): --flags corners");
            }
            super::patterns::warn_skipped(&corners);
            return Ok((corners, McFlags::Corners));
        }
    };
    let rule = if flags == McFlags::Inside { FlagRule::File } else { FlagRule::Corners };
    let set = load(rule)?;
    super::patterns::warn_skipped(&set);
    Ok((set, flags))
}

pub fn run(a: Args) -> Result<ExitCode> {
    for input in a.surface.iter().chain(&a.field) {
        a.output.check_against(input)?;
    }
    let out_format = resolve_format(&a.output.output, None)?;
    let (set, flags) = mc_patterns(&a)?;
    let pb = crate::progress::spinner("marching cubes", a.report.quiet || a.report.json);
    let (polygons, r, hexes, source) = if let Some(field) = &a.field {
        let values = read_f32(field)?;
        let &[nx, ny, nz] = a.dims.as_slice() else {
            bail!("--dims takes three sizes NX,NY,NZ, got {:?}", a.dims);
        };
        let dims = [nx, ny, nz];
        if a.slab_cells == 0 {
            bail!("--slab-cells must be at least 1");
        }
        let opts = FieldOptions { compiled: a.engine == FieldEngine::Compiled, slab_cells: a.slab_cells };
        let (s, r) = marching_cubes_field_with(&values, dims, a.iso, &set, flags, &opts)
            .map_err(|e| anyhow::anyhow!("{}: {e}", field.display()))?;
        drop(values);
        let hexes = (dims[0] - 1) * (dims[1] - 1) * (dims[2] - 1);
        (s, r, hexes, field.clone())
    } else {
        let path = a.surface.clone().expect("clap requires a surface or a field");
        if a.levels > 12 {
            bail!("--levels {} is too deep (at most 12)", a.levels);
        }
        let surface = read_surface(&path, parse_format(&a.format)?)?;
        let bvh = TriangleBvh::from_polygons(&surface.points, (0..surface.nb_polygons()).map(|i| surface.polygon(i)));
        if bvh.is_empty() {
            bail!("{}: no polygon", path.display());
        }
        let (s, r, hexes) = marching_cubes_surface(&bvh, a.levels, a.root.shape()?, a.root.margin, &set, flags)
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        (s, r, hexes, path)
    };
    pb.finish_and_clear();
    release_freed_memory();
    // (a fan of a polygon of n sides has n − 2 triangles)
    let nb_polygons = polygons.nb_polygons();
    let triangles: usize = (0..nb_polygons).map(|i| polygons.polygon(i).len().saturating_sub(2)).sum();
    let out = if a.triangulate { triangulate_owned(polygons) } else { polygons };
    let topology = surface_topology(&out);
    let (open_edges, chi) = (topology.map(|t| t.open_edges), topology.map(|t| t.euler_characteristic));
    if out.nb_polygons() > 0 {
        write_indexed(&a.output.output, &out, out_format, &WriteOptions::default())?;
    }
    if a.report.json {
        let j = json!({
            "input": source.display().to_string(),
            "output": a.output.output.display().to_string(),
            "hexahedra": hexes,
            "root": if a.field.is_some() { None } else { Some(&a.root.root) },
            "init": if a.field.is_some() { None } else { Some(a.root.init) },
            "cells_built": r.cells_built,
            "f_patterns": r.f_patterns,
            "flags": if flags == McFlags::Inside { "inside" } else { "corners" },
            "v_patterns": r.v_patterns,
            "edges_split": r.edges_split,
            "faces_replaced": r.faces_replaced,
            "volumes_replaced": r.volumes_replaced,
            "unmatched_faces": r.unmatched_faces,
            "unmatched_volumes": r.unmatched_volumes,
            "polygons": nb_polygons,
            "triangles": triangles,
            "open_edges": open_edges,
            "manifold": open_edges.is_some(),
            "euler_characteristic": chi,
            "seconds": r.seconds,
            "phases": r.phases,
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        println!(
            "{} hexahedra ({} built), {} f- and {} v-patterns: {} edges split, {} faces and {} cubes replaced ({} / {} unmatched)",
            hexes,
            r.cells_built,
            r.f_patterns,
            r.v_patterns,
            r.edges_split,
            r.faces_replaced,
            r.volumes_replaced,
            r.unmatched_faces,
            r.unmatched_volumes
        );
        println!(
            "surface: {} polygons ({} triangles), open edges {}, Euler characteristic {}; {:.3} s",
            nb_polygons,
            triangles,
            open_edges.map_or("n/a (non-manifold)".into(), |e| e.to_string()),
            chi.map_or("n/a".into(), |c| c.to_string()),
            r.seconds
        );
        if out.nb_polygons() > 0 {
            println!("wrote {}", a.output.output.display());
        } else {
            println!("empty surface: nothing written");
        }
    }
    Ok(if r.unmatched_volumes + r.unmatched_faces == 0 && open_edges.is_some() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// A raw little-endian float32 file, read straight into its values.
fn read_f32(path: &std::path::Path) -> Result<Vec<f32>> {
    use std::io::Read;
    let mut file = std::fs::File::open(path).with_context(|| format!("reading {}", path.display()))?;
    let len = file.metadata().with_context(|| format!("reading {}", path.display()))?.len() as usize;
    if !len.is_multiple_of(4) {
        bail!("{}: {len} bytes is not a whole number of float32 values", path.display());
    }
    let mut values = vec![0f32; len / 4];
    let mut chunk = vec![0u8; 1 << 16];
    let mut at = 0;
    while at < values.len() {
        let n = ((values.len() - at) * 4).min(chunk.len());
        file.read_exact(&mut chunk[..n]).with_context(|| format!("reading {}", path.display()))?;
        for (v, b) in values[at..].iter_mut().zip(chunk[..n].chunks_exact(4)) {
            *v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        }
        at += n / 4;
    }
    Ok(values)
}

/// Gives the memory freed by the marching (the field, every core's working memory) back
/// to the system before the surface is triangulated, checked and written: glibc keeps
/// freed blocks inside each thread's heap otherwise (gyroid 128³: peak RSS 37.6 → 35.1 MB).
fn release_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free pages of the allocator's heaps to the kernel.
    unsafe {
        libc::malloc_trim(0);
    }
}
