//! `qmesh patterns audit DIR [--json]`: every pattern's kind, signature, automorphisms,
//! and the duplicates of the set (2022 §6.4).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use qmesh::io::{Format, WriteOptions, write_indexed};
use qmesh::pattern::{FlagRule, PatternKind, audit, boundaries_mesh, load_pattern_dir};
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
/// patterns), `none`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Flags {
    Corners,
    Geometric,
    None,
}

impl From<Flags> for FlagRule {
    fn from(f: Flags) -> FlagRule {
        match f {
            Flags::Corners => FlagRule::Corners,
            Flags::Geometric => FlagRule::Geometric,
            Flags::None => FlagRule::None,
        }
    }
}

pub fn run(a: Args) -> Result<ExitCode> {
    let (dir, as_json, flags) = match a.action {
        Action::Audit { dir, json, flags } => (dir, json, flags),
        Action::Boundaries { dir, output, copies } => return boundaries(&dir, &output, copies),
    };
    let t = std::time::Instant::now();
    let set = load_pattern_dir(&dir, flags.into());
    let report = audit(&set);
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
    }
    Ok(if report.duplicates.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) })
}

/// `qmesh patterns boundaries`: each v-pattern's boundary as a VTK polyhedron.
fn boundaries(dir: &std::path::Path, output: &std::path::Path, copies: usize) -> Result<ExitCode> {
    let set = load_pattern_dir(dir, FlagRule::None);
    let mesh = boundaries_mesh(&set, copies);
    write_indexed(output, &mesh, Format::Vtk, &WriteOptions::default())?;
    let n = mesh.nb_cells();
    println!("wrote {} ({n} cells, the boundaries of {} v-patterns)", output.display(), set.count(PatternKind::Volume));
    Ok(ExitCode::SUCCESS)
}
