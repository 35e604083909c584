//! `qmesh patterns audit DIR [--json]`: every pattern's kind, signature, automorphisms,
//! and the duplicates of the set (2022 §6.4).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use qmesh::apps::{GeneratedKind, generated_pattern_meshes, generated_pattern_set};
use qmesh::build::{BuildOptions, build_map};
use qmesh::io::{Format, WriteOptions, load_map, write_indexed, write_map};
use qmesh::pattern::{
    FlagRule, PatternKind, PatternSet, audit, boundaries_mesh, load_pattern_dir, load_patterns, write_compiled,
};
use qmesh::replace::{ReplaceOptions, Uncovered, query_replace};
use serde_json::json;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(subcommand)]
    pub action: Action,
}

#[derive(clap::Subcommand, Debug)]
pub enum Action {
    /// List every pattern with kind, signature digest and automorphism count, and the
    /// duplicate boundaries; exit status 1 when duplicates exist.
    Audit {
        /// A patterns folder (searched recursively) or one pattern file.
        dir: PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// Pattern flags: `corners` (the papers' rule) or `none`.
        #[arg(long, default_value = "corners")]
        flags: Flags,
        /// Coverage: run the set on this mesh (nothing is written) and list every face or
        /// volume configuration that no pattern matches.
        #[arg(long)]
        against: Option<PathBuf>,
        /// With --against: split every edge into K segments first.
        #[arg(long)]
        split_edges: Option<usize>,
    },
    /// Write a pattern set qmesh generates (fpattern/ and vpattern/ folders) for
    /// inspection, editing, and use with `--patterns`.
    Generate {
        /// Which set.
        kind: Generated,
        /// Output folder.
        #[arg(short, long)]
        output: PathBuf,
        /// File format of the patterns (default: vtk; moka for marching-cubes, whose
        /// flags only Moka marks can carry).
        #[arg(long)]
        format: Option<PatternFormat>,
    },
    /// Compile pattern folders into one file (`.qps`) that loads in about a millisecond:
    /// each pattern's map, flags and signature are stored as loading computes them.
    /// Use the file wherever a pattern folder is accepted; compile again after editing
    /// the patterns.
    Compile {
        /// Pattern folders or files, merged in this order (as `--patterns A,B`).
        #[arg(required = true, value_delimiter = ',')]
        dirs: Vec<PathBuf>,
        /// Output file (`.qps`).
        #[arg(short, long)]
        output: PathBuf,
        /// Pattern flags the set is compiled with; the commands using it must flag
        /// patterns the same way (`corners`: conformal, subdivide, replace by default).
        #[arg(long, default_value = "corners")]
        flags: Flags,
        #[command(flatten)]
        report: super::ReportArgs,
    },
    /// Write the boundary of every v-pattern as one polyhedral cell (side by side), e.g.
    /// to look at the configurations a set covers or to benchmark matching.
    Boundaries {
        /// A patterns folder or file.
        dir: PathBuf,
        /// Output mesh (VTK: cells are polyhedra).
        #[arg(short, long)]
        output: PathBuf,
        /// Copies of each boundary.
        #[arg(long, default_value_t = 1)]
        copies: usize,
    },
}

/// Flag rule: `corners` (patterns by geometry, input darts all flagged before edge
/// splits, as in the papers), `geometric` (input cells by the same geometric rule as
/// patterns), `file` (pattern flags from the file's marks: `.moka` mark group 0), `none`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Flags {
    /// Darts at an original corner of a cell (the papers' rule).
    Corners,
    /// Input cells flagged by the patterns' geometric corner rule (configuration meshes).
    Geometric,
    /// Pattern flags from the files' marks (`.moka` mark group 0).
    File,
    /// No flags: matching is purely topological.
    None,
}

impl From<Flags> for FlagRule {
    fn from(f: Flags) -> FlagRule {
        match f {
            Flags::Corners => FlagRule::Corners,
            Flags::Geometric => FlagRule::Geometric,
            Flags::File => FlagRule::File,
            Flags::None => FlagRule::None,
        }
    }
}

pub fn run(a: Args) -> Result<ExitCode> {
    let (dir, as_json, flags, against, split_edges) = match a.action {
        Action::Audit { dir, json, flags, against, split_edges } => (dir, json, flags, against, split_edges),
        Action::Boundaries { dir, output, copies } => return boundaries(&dir, &output, copies),
        Action::Compile { dirs, output, flags, report } => return compile(&dirs, &output, flags.into(), &report),
        Action::Generate { kind, output, format } => return generate(kind, &output, format),
    };
    let t = std::time::Instant::now();
    let set = pattern_dir(&dir, flags.into())?;
    let report = audit(&set);
    let coverage = match &against {
        Some(mesh) => {
            let mut m = load_map(mesh, None, &BuildOptions::default())?.map;
            let opts = ReplaceOptions { split_edges, flags: flags.into(), use_signatures: true };
            Some(query_replace(&mut m, &set, &opts)?)
        }
        None => None,
    };
    let seconds = t.elapsed().as_secs_f64();
    if as_json {
        let j = json!({
            "patterns": report.patterns.iter().map(|p| json!({
                "file": p.file, "kind": p.kind, "signature": p.signature,
                "automorphisms": p.automorphisms, "boundary_darts": p.boundary_darts,
            })).collect::<Vec<_>>(),
            "duplicates": report.duplicates,
            "ambiguous": report.ambiguous,
            "skipped": report.skipped.iter().map(|(f, r)| json!({"file": f, "reason": r})).collect::<Vec<_>>(),
            "uncovered": coverage.as_ref().map(|r| uncovered_json(&r.uncovered)),
            "f_patterns": set.count(PatternKind::Face),
            "v_patterns": set.count(PatternKind::Volume),
            "seconds": seconds,
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else {
        for p in &report.patterns {
            println!("{:<9} {}  automorphisms {:>2}  {}", p.kind, p.signature, p.automorphisms, p.file);
        }
        for (f, r) in &report.skipped {
            println!("skipped   {f}: {r}");
        }
        println!(
            "{} f-patterns, {} v-patterns, {} duplicate groups, {} ambiguous, {} skipped ({:.2} s)",
            set.count(PatternKind::Face),
            set.count(PatternKind::Volume),
            report.duplicates.len(),
            report.ambiguous.len(),
            report.skipped.len(),
            seconds
        );
        for g in &report.duplicates {
            println!("duplicate: {}", g.join(" = "));
        }
        if !report.ambiguous.is_empty() {
            println!(
                "ambiguous: a pattern whose boundary maps onto itself in more than one way that keeps the \
                 flags (automorphisms > 1): a matching cell can be replaced in several placements, and the \
                 one taken is fixed by the pattern's canonical start dart, not by the cell's geometry or its \
                 inside/outside. Harmless when the inside is symmetric too (subdivision); for the marching-cubes \
                 face with four split edges it decides which two opposite corners are cut off."
            );
        }
        if let Some(r) = &coverage {
            println!(
                "coverage on {}: {} faces and {} volumes matched, {} faces and {} volumes in {} configurations uncovered",
                against.as_ref().map(|p| p.display().to_string()).unwrap_or_default(),
                r.faces_replaced,
                r.volumes_replaced,
                r.unmatched_faces,
                r.unmatched_volumes,
                r.uncovered.len()
            );
            for u in &r.uncovered {
                println!(
                    "uncovered {:<9} {}  ×{}  e.g. at {:?}",
                    u.kind.name(),
                    u.signature.digest(),
                    u.count,
                    u.sample
                );
            }
        }
    }
    Ok(if report.duplicates.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) })
}

/// `qmesh patterns boundaries`: each v-pattern's boundary as a VTK polyhedron.
fn boundaries(dir: &std::path::Path, output: &std::path::Path, copies: usize) -> Result<ExitCode> {
    let set = pattern_dir(dir, FlagRule::None)?;
    let mesh = boundaries_mesh(&set, copies);
    write_indexed(output, &mesh, Format::Vtk, &WriteOptions::default())?;
    let n = mesh.nb_cells();
    println!("wrote {} ({n} cells, the boundaries of {} v-patterns)", output.display(), set.count(PatternKind::Volume));
    Ok(ExitCode::SUCCESS)
}

/// `qmesh patterns compile DIR... -o SET.qps`: the merged set of `dirs`, stored as
/// loading computes it.
fn compile(dirs: &[PathBuf], output: &std::path::Path, rule: FlagRule, report: &super::ReportArgs) -> Result<ExitCode> {
    let t = std::time::Instant::now();
    let set = merged_sets(dirs, rule)?;
    warn_skipped(&set);
    let load_seconds = t.elapsed().as_secs_f64();
    let bytes = write_compiled(&set, rule, output)?;
    let (faces, volumes) = (set.count(PatternKind::Face), set.count(PatternKind::Volume));
    if report.json {
        let j = json!({
            "output": output.display().to_string(),
            "f_patterns": faces,
            "v_patterns": volumes,
            "skipped": set.skipped.len(),
            "bytes": bytes,
            "load_seconds": load_seconds,
            "seconds": t.elapsed().as_secs_f64(),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !report.quiet {
        println!(
            "wrote {} ({faces} f-patterns, {volumes} v-patterns, {} skipped, {bytes} bytes)",
            output.display(),
            set.skipped.len()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// The uncovered configurations of a replace report as JSON.
pub fn uncovered_json(u: &[Uncovered]) -> serde_json::Value {
    serde_json::Value::Array(
        u.iter()
            .map(|u| json!({"kind": u.kind.name(), "signature": u.signature.digest(), "count": u.count, "sample": u.sample}))
            .collect(),
    )
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Generated {
    /// Octree refinement: every hexahedron into 8 (2022 §7.1).
    HexSubdivision,
    /// Every tetrahedron into 4 hexahedra (2022 §7.4).
    Tet2hex,
    /// Conformal 2:1 transitions: 5 f-patterns, 325 v-patterns (2022 §7.3).
    Transitions,
    /// Marching cubes: 4 f-patterns, 21 v-patterns, flags as Moka marks (2022 §7.2).
    MarchingCubes,
    /// The subdivisions of the hexahedron into tetrahedra (2025 §7.1): per oriented
    /// class with a positive realisation, its query and target.
    HexTetrahedralizations,
}

impl Generated {
    /// The library's generated set, or None for marching cubes (written separately).
    fn kind(self) -> Option<GeneratedKind> {
        match self {
            Generated::HexSubdivision => Some(GeneratedKind::HexSubdivision),
            Generated::Tet2hex => Some(GeneratedKind::Tet2Hex),
            Generated::Transitions => Some(GeneratedKind::Transitions),
            Generated::MarchingCubes | Generated::HexTetrahedralizations => None,
        }
    }
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum PatternFormat {
    /// f-patterns as OFF, v-patterns as VTK.
    Vtk,
    /// Moka generalized maps (the papers' format).
    Moka,
}

/// `qmesh patterns generate`: writes `DIR/fpattern/*` and `DIR/vpattern/*`.
fn generate(kind: Generated, dir: &std::path::Path, format: Option<PatternFormat>) -> Result<ExitCode> {
    if let Generated::HexTetrahedralizations = kind {
        return generate_hex_splits(dir, format.unwrap_or(PatternFormat::Vtk));
    }
    let Some(kind) = kind.kind() else {
        return generate_marching_cubes(dir, format.unwrap_or(PatternFormat::Moka));
    };
    let format = format.unwrap_or(PatternFormat::Vtk);
    for (stem, volume, mesh) in generated_pattern_meshes(kind) {
        let sub = dir.join(if volume { "vpattern" } else { "fpattern" });
        std::fs::create_dir_all(&sub)?;
        let file = match format {
            PatternFormat::Vtk => {
                let f = sub.join(format!("{stem}.{}", if volume { "vtk" } else { "off" }));
                let fmt = if volume { Format::Vtk } else { Format::Off };
                write_indexed(&f, &mesh, fmt, &WriteOptions::default())?;
                f
            }
            PatternFormat::Moka => {
                let f = sub.join(format!("{stem}.moka"));
                let (map, _) = build_map(mesh, &BuildOptions { fix_orientation: true })?;
                write_map(&f, &map, None, &WriteOptions::default())?;
                f
            }
        };
        println!("wrote {}", file.display());
    }
    let set = load_pattern_dir(dir, FlagRule::Corners);
    let report = audit(&set);
    println!(
        "{}: {} f-patterns, {} v-patterns, {} duplicates, {} skipped",
        kind.name(),
        set.count(PatternKind::Face),
        set.count(PatternKind::Volume),
        report.duplicates.len(),
        report.skipped.len()
    );
    Ok(ExitCode::SUCCESS)
}

/// The marching-cubes set: its flags mark inside corners, which geometry cannot tell,
/// so it is written as `.moka` with mark 0 and read back with `--flags file`.
fn generate_marching_cubes(dir: &std::path::Path, format: PatternFormat) -> Result<ExitCode> {
    if let PatternFormat::Vtk = format {
        anyhow::bail!("marching-cubes patterns flag inside corners, which VTK cannot carry: use --format moka");
    }
    let faces = qmesh::apps::mc_face_patterns().into_iter().map(|p| (p, "fpattern"));
    let volumes = qmesh::apps::mc_volume_patterns().into_iter().map(|p| (p, "vpattern"));
    for ((name, mut map, flags), sub) in faces.chain(volumes) {
        let sub = dir.join(sub);
        std::fs::create_dir_all(&sub)?;
        let mark = map.reserve_mark()?;
        flags.iter().for_each(|&d| map.mark(d, mark));
        let file = sub.join(format!("{name}.moka"));
        qmesh::io::write_moka_with_flags(&file, &map, mark)?;
        println!("wrote {}", file.display());
    }
    let set = load_pattern_dir(dir, FlagRule::File);
    let report = audit(&set);
    println!(
        "marching-cubes: {} f-patterns, {} v-patterns, {} duplicates, {} skipped",
        set.count(PatternKind::Face),
        set.count(PatternKind::Volume),
        report.duplicates.len(),
        report.skipped.len()
    );
    Ok(ExitCode::SUCCESS)
}

/// The patterns of `dir` (a folder searched recursively, one pattern file, or a
/// compiled set), which must exist: a mistyped folder is an error, not an empty set.
///
/// # Errors
/// When `dir` does not exist, or is a compiled set that cannot be read.
pub fn pattern_dir(dir: &std::path::Path, rule: FlagRule) -> Result<PatternSet> {
    if !dir.exists() {
        anyhow::bail!("{}: no such pattern folder or file", dir.display());
    }
    Ok(load_patterns(dir, rule)?)
}

/// Paths as a person reads them in a message.
pub fn path_list(paths: &[PathBuf]) -> String {
    paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
}

/// The patterns of every folder (or file) of `dirs` in one set, with `rule`; the files
/// skipped are listed in the set (see [`warn_skipped`]).
///
/// # Errors
/// A missing folder, or no usable pattern at all.
pub fn merged_sets(dirs: &[PathBuf], rule: FlagRule) -> Result<PatternSet> {
    let mut set: Option<PatternSet> = None;
    for dir in dirs {
        let s = pattern_dir(dir, rule)?;
        match &mut set {
            None => set = Some(s),
            Some(all) => {
                all.skipped.extend(s.skipped);
                s.patterns.into_iter().for_each(|p| {
                    all.insert(p);
                });
            }
        }
    }
    let set = set.unwrap_or_default();
    if set.patterns.is_empty() {
        anyhow::bail!("no usable pattern in {}", path_list(dirs));
    }
    Ok(set)
}

/// Prints a warning per pattern file a set skipped.
pub fn warn_skipped(set: &PatternSet) {
    for sk in &set.skipped {
        eprintln!("warning: skipped pattern {}: {}", sk.file.display(), sk.reason);
    }
}

/// The transition patterns of `conformal` and `subdivide --conformal`: the folders
/// given (the papers' corner flags), or qmesh's generated `transitions` set.
///
/// # Errors
/// As [`merged_sets`], or a set without v-pattern.
pub fn transition_set(dirs: &[PathBuf]) -> Result<PatternSet> {
    let set = match load_sets(dirs)? {
        Some(set) => set,
        None => generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners)?,
    };
    if set.count(PatternKind::Volume) == 0 {
        anyhow::bail!("no v-pattern in {}", path_list(dirs));
    }
    Ok(set)
}

/// The `--patterns` folders with the papers' corner flags, or None without any.
///
/// # Errors
/// As [`merged_sets`].
pub fn load_sets(dirs: &[PathBuf]) -> Result<Option<PatternSet>> {
    if dirs.is_empty() {
        return Ok(None);
    }
    let set = merged_sets(dirs, FlagRule::Corners)?;
    warn_skipped(&set);
    Ok(Some(set))
}

/// `qmesh patterns generate hex-tetrahedralizations`: `DIR/query/split-NNN-Tt.*` (the
/// tetrahedra on a positive realisation) and `DIR/target/split-NNN-Tt.*` (one volume
/// bounded by the same 12 triangles) per oriented class, and the counts.
fn generate_hex_splits(dir: &std::path::Path, format: PatternFormat) -> Result<ExitCode> {
    use qmesh::apps::{HexSplits, split_query_mesh, split_target_mesh};
    // The generator itself, not the stored table: the counts printed are computed.
    let s = HexSplits::enumerate();
    let mut written = 0;
    for (o, class) in s.oriented.iter().enumerate() {
        let Some(p) = class.realization else { continue };
        let stem = format!("split-{o:03}-{}t", class.tets.len());
        for (sub, mesh) in
            [("query", split_query_mesh(&class.tets, &p)), ("target", split_target_mesh(&class.tets, &p))]
        {
            let folder = dir.join(sub);
            std::fs::create_dir_all(&folder)?;
            match format {
                PatternFormat::Vtk => {
                    write_indexed(&folder.join(format!("{stem}.vtk")), &mesh, Format::Vtk, &WriteOptions::default())?
                }
                PatternFormat::Moka => {
                    let (map, _) = build_map(mesh, &BuildOptions { fix_orientation: false })?;
                    write_map(&folder.join(format!("{stem}.moka")), &map, None, &WriteOptions::default())?;
                }
            }
        }
        written += 1;
    }
    let hist: Vec<String> = s.histogram().iter().map(|(t, n)| format!("{t} tets: {n}")).collect();
    let realised = s.classes.iter().filter(|c| c.realization.is_some()).count();
    println!(
        "{} labelled subdivisions; {} classes up to the 48 symmetries of the cube ({}); {} up to the 24 rotations",
        s.splits().len(),
        s.classes.len(),
        hist.join(", "),
        s.oriented.len()
    );
    println!(
        "{realised} classes with a positive realisation found ({} without: {}); {written} query/target pairs written to {}",
        s.classes.len() - realised,
        s.classes
            .iter()
            .enumerate()
            .filter(|c| c.1.realization.is_none())
            .map(|c| c.0.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        dir.display()
    );
    Ok(ExitCode::SUCCESS)
}
