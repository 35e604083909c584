//! `qmesh subdivide SURFACE --levels L [--direct] -o OUT`: octree hexahedral
//! subdivision of a surface by query-replace (2022 Algorithm 5).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Result, bail};
use qmesh::apps::{ConformalPhases, SubdivideOptions, subdivide, transitions_on_map};
use qmesh::build::{ExtractedKinds, extract, non_conformal_faces};
use qmesh::cmap::{CMap3, Dart};
use qmesh::geom::TriangleBvh;
use qmesh::io::{Format, WriteOptions, read_surface, resolve_format, write_indexed};
use qmesh::pattern::PatternSet;
use qmesh::replace::ReplaceReport;
use serde_json::json;

use super::parse_format;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Surface to approximate (off, obj, stl, ply, vtk polygons, or a volume mesh's boundary).
    pub surface: PathBuf,
    /// Maximal subdivision level l_max (the root cube is level 0).
    #[arg(long, default_value_t = 5)]
    pub levels: u8,
    #[command(flatten)]
    pub output: super::OutputArgs,
    /// Refine plain boxes with hand-written code instead of query-replace.
    #[arg(long)]
    pub direct: bool,
    #[command(flatten)]
    pub root: super::OctreeRootArgs,
    /// Drop the hexahedra outside the surface that it does not touch.
    #[arg(long)]
    pub remove_outside: bool,
    /// Pattern folders replacing the generated `hex-subdivision` set (e.g. the papers'
    /// hexa-8-subdivision, or an edited `qmesh patterns generate` output).
    /// Repeat the option or separate folders with commas.
    #[arg(long, value_delimiter = ',')]
    pub patterns: Vec<PathBuf>,
    /// Test patterns directly instead of looking signatures up.
    #[arg(long)]
    pub no_signatures: bool,
    /// Then make the mesh conformal on the same map (2022 Algorithm 7), as the authors'
    /// program's `-create-transitions` does: the output holds hexahedra, prisms, pyramids
    /// and tetrahedra with no hanging vertex (`qmesh conformal` does the same from a file).
    #[arg(long, conflicts_with = "direct")]
    pub conformal: bool,
    /// With `--conformal`: transition pattern folders (default: qmesh's generated
    /// `transitions` set; the papers' set: hexa-325-patterns and square-5-patterns).
    /// Repeat the option or separate folders with commas.
    #[arg(long, value_delimiter = ',', requires = "conformal")]
    pub transition_patterns: Vec<PathBuf>,
    /// Input format, overriding the extension.
    #[arg(long)]
    pub format: Option<String>,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

pub fn run(a: Args) -> Result<ExitCode> {
    if a.levels > 12 {
        bail!("--levels {} is too deep (at most 12: 8^12 cells would not fit in memory)", a.levels);
    }
    let root = a.root.shape()?;
    a.output.check_against(&a.surface)?;
    let out_format = resolve_format(&a.output.output, None)?;
    let surface = read_surface(&a.surface, parse_format(&a.format)?)?;
    let bvh = TriangleBvh::from_polygons(&surface.points, (0..surface.nb_polygons()).map(|i| surface.polygon(i)));
    if bvh.is_empty() {
        bail!("{}: no polygon to subdivide around", a.surface.display());
    }
    let opts = SubdivideOptions {
        levels: a.levels,
        root,
        margin: a.root.margin,
        direct: a.direct,
        remove_outside: a.remove_outside,
        use_signatures: !a.no_signatures,
    };
    let pb = crate::progress::bar(u64::from(a.levels), "subdivide", a.report.quiet || a.report.json);
    let set = super::patterns::load_sets(&a.patterns)?;
    // Read before subdividing, so a bad folder stops the run at once; timed with the
    // transitions, as the authors' program times its loading.
    let t = Instant::now();
    let transition_set =
        if a.conformal { Some(super::patterns::transition_set(&a.transition_patterns)?) } else { None };
    let loading = t.elapsed().as_secs_f64();
    let mut s = subdivide(&bvh, &opts, set.as_ref(), &|l| pb.set_position(u64::from(l) - 1))?;
    pb.finish_and_clear();
    let conformal = match (&transition_set, &mut s.map) {
        (Some(set), Some(map)) => Some(Transitions::run(map, &s.volumes, set, !a.no_signatures, loading)?),
        _ => None,
    };
    let validity = s.map.as_ref().map(|m| m.is_valid().is_empty());
    match (&conformal, &s.map) {
        (Some(_), Some(map)) => write_indexed(&a.output.output, &extract(map).0, out_format, &WriteOptions::default())?,
        _ => write_indexed(&a.output.output, &s.mesh, out_format, &WriteOptions::default())?,
    }
    let r = &s.report;
    if a.report.json {
        let j = json!({
            "surface": a.surface.display().to_string(),
            "triangles": bvh.len(),
            "output": a.output.output.display().to_string(),
            "levels": a.levels,
            "method": if a.direct { "direct" } else { "query-replace" },
            "volumes": r.volumes,
            "per_level": r.per_level,
            "faces_replaced": r.faces_replaced,
            "volumes_replaced": r.volumes_replaced,
            "balance_splits": r.balance_splits,
            "removed_outside": r.removed_outside,
            "with_hanging_vertices": r.with_hanging_vertices,
            "root": a.root.root,
            "init": a.root.init,
            "darts": s.map.as_ref().map(|m| m.nb_darts()),
            "valid": validity,
            "seconds": r.seconds,
            "phases": r.phases,
            "transitions": conformal.as_ref().map(Transitions::json),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        println!(
            "{} triangles, l_max {}: {} hexahedra ({}), {} balance splits, {} outside removed",
            bvh.len(),
            a.levels,
            r.volumes,
            per_level(&r.per_level),
            r.balance_splits,
            r.removed_outside
        );
        if !a.direct {
            println!(
                "{} face and {} volume query-replaces; map {} darts, valid: {}",
                r.faces_replaced,
                r.volumes_replaced,
                s.map.as_ref().map_or(0, |m| m.nb_darts()),
                validity.unwrap_or(true)
            );
        }
        if let Some(c) = &conformal {
            c.print();
        }
        println!("{:.3} s; wrote {}", r.seconds, a.output.output.display());
    }
    if out_format == Format::Off || out_format == Format::Obj {
        eprintln!(
            "note: {} keeps only the boundary polygons; use .vtk/.vtu for the cells and levels",
            a.output.output.display()
        );
    }
    let conformal_ok = conformal.as_ref().is_none_or(Transitions::is_conformal);
    Ok(if validity == Some(false) || !conformal_ok { ExitCode::from(1) } else { ExitCode::SUCCESS })
}

/// What `--conformal` did on the subdivision's map.
struct Transitions {
    replace: ReplaceReport,
    kinds: ExtractedKinds,
    phases: ConformalPhases,
    non_conformal_faces: usize,
    /// Loading the patterns.
    load_seconds: f64,
    /// Loading the patterns, then the transitions themselves (the step the authors'
    /// program reports as "Create transitions").
    seconds: f64,
}

impl Transitions {
    fn run(map: &mut CMap3, volumes: &[Dart], set: &PatternSet, use_signatures: bool, loading: f64) -> Result<Self> {
        let t = Instant::now();
        let mut phases = ConformalPhases::default();
        let (replace, kinds) = transitions_on_map(map, set, use_signatures, Some(volumes), &mut phases)?;
        let seconds = loading + t.elapsed().as_secs_f64();
        let non_conformal_faces = non_conformal_faces(map);
        Ok(Transitions { replace, kinds, phases, non_conformal_faces, load_seconds: loading, seconds })
    }

    fn is_conformal(&self) -> bool {
        self.non_conformal_faces == 0 && self.replace.unmatched_volumes == 0
    }

    fn json(&self) -> serde_json::Value {
        let (k, rep) = (&self.kinds, &self.replace);
        json!({
            "faces_replaced": rep.faces_replaced,
            "volumes_replaced": rep.volumes_replaced,
            "unmatched_faces": rep.unmatched_faces,
            "unmatched_volumes": rep.unmatched_volumes,
            "cell_types": {"hex": k.hex, "tet": k.tet, "prism": k.prism, "pyramid": k.pyramid, "other": k.other},
            "non_conformal_faces": self.non_conformal_faces,
            "load_seconds": self.load_seconds,
            "seconds": self.seconds,
            "phases": self.phases,
        })
    }

    fn print(&self) {
        let (k, rep) = (&self.kinds, &self.replace);
        println!(
            "transitions: {} faces and {} volumes replaced ({} / {} unmatched); {} hex, {} tet, {} prism, {} pyramid, {} other; non-conformal faces: {}; {:.3} s",
            rep.faces_replaced,
            rep.volumes_replaced,
            rep.unmatched_faces,
            rep.unmatched_volumes,
            k.hex,
            k.tet,
            k.prism,
            k.pyramid,
            k.other,
            self.non_conformal_faces,
            self.seconds
        );
    }
}

fn per_level(v: &[usize]) -> String {
    v.iter().enumerate().filter(|(_, n)| **n > 0).map(|(l, n)| format!("L{l}: {n}")).collect::<Vec<_>>().join(", ")
}
