//! The `qmesh` command line: one module per subcommand, no algorithms here.

mod cmd;
mod memory;
mod phases;
mod progress;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// qmesh — edit 3D meshes by topological rewriting on combinatorial maps.
#[derive(Parser, Debug)]
#[command(name = "qmesh", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Worker threads (default: RAYON_NUM_THREADS, else all cores).
    #[arg(long, global = true)]
    threads: Option<std::num::NonZeroUsize>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Counts, topology, cell types, validity and timings of a mesh file.
    Info(cmd::info::Args),
    /// Checks the combinatorial map of a mesh; exit status 1 when invalid.
    Validate(cmd::validate::Args),
    /// Converts between mesh formats (by extension, or --format / --to).
    Convert(cmd::convert::Args),
    /// Writes built-in meshes (structured hex or tet grids).
    Generate(cmd::generate::Args),
    /// Element quality: scaled Jacobian per cell type (Verdict) and signed volumes.
    Quality(cmd::quality::Args),
    /// Query-replace (2022): split edges, replace matching faces, then volumes.
    Replace(cmd::replace::Args),
    /// Query (2025): match connected sets of volumes from every dart; counts, selection, matched cells.
    Query(cmd::query::Args),
    /// Query-modify (2025): extend / delete / replace the matches of each rule of a TOML rule file.
    Modify(cmd::modify::Args),
    /// Pattern sets: audit (kinds, signatures, automorphisms, duplicates), generate
    /// (the sets qmesh builds), boundaries (each v-pattern's boundary as a cell).
    Patterns(cmd::patterns::Args),
    /// Octree hexahedral subdivision of a surface (2022 Algorithm 5), with 2:1 balance.
    Subdivide(cmd::subdivide::Args),
    /// Conformal transitions of a 2:1 octree hex mesh (2022 Algorithm 7).
    Conformal(cmd::conformal::Args),
    /// Tetrahedra to hexahedra: each tetrahedron into 4 hexahedra (2022 §7.4).
    Tet2hex(cmd::tet2hex::Args),
    /// Hexahedra to tetrahedra on their corners, conformal and positive (2025 §7.1.1 data).
    Tetrahedralize(cmd::tetrahedralize::Args),
    /// Tetrahedra to hexahedra with every subdivision of the hexahedron as a query (2025 §7.1).
    Recombine(cmd::recombine::Args),
    /// Marching cubes by query-replace (2022 Algorithm 6), from a surface or a field.
    MarchingCubes(cmd::marching_cubes::Args),
    /// A PNG picture: cells shrunk apart, optionally clipped, coloured by type/level/quality/label/component.
    Render(cmd::render::Args),
    /// A short tour on built-in inputs, written into a folder: a torus surface, its
    /// octree hexahedra, their conformal transitions, marching cubes, tet → hex, each
    /// with a mesh file and a PNG picture, and what each step did.
    Demo(cmd::demo::Args),
}

/// The stack of each worker thread: Linux's default for a main thread.
const MAIN_STACK_BYTES: usize = 8 << 20;

fn main() -> ExitCode {
    // Like other Unix tools, end quietly when the reader of stdout goes away
    // (`qmesh info x.vtk | head`) instead of panicking on the broken pipe.
    #[cfg(unix)]
    // SAFETY: restoring the default action of a signal before any thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // glibc raises its heap trim threshold each time a large (mmapped) block is freed,
    // up to 64 MB, and then keeps that much freed memory mapped. Pinned at 4 MB,
    // freed heap goes back to the system: peak RSS of `recombine` on Armadillo
    // 137 → 112 MB, same run time (a lower threshold trims on too many frees).
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: sets one allocator parameter before any thread exists.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, 4 << 20);
    }
    let cli = Cli::parse();
    // glibc gives each thread that allocates under contention a heap of its own, and
    // keeps what is freed there. `recombine` allocates almost nothing per thread
    // (matching takes no allocation per start dart), so its workers share the main
    // heap: peak RSS 1.3-1.5 MB lower on meshes of 10^4 tets (rockerarm_1, block_out,
    // gmsh_torus `--any`), the same time on those and on Armadillo's 192,000 tets.
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if matches!(cli.command, Command::Recombine(_)) {
        // SAFETY: sets one allocator parameter before the command starts a thread.
        unsafe {
            libc::mallopt(libc::M_ARENA_MAX, 1);
        }
    }
    // Every command runs on a worker of rayon's pool, so that its parallel steps are
    // handed to the other workers directly instead of each putting this thread to sleep
    // until a worker has run it (a subdivision makes hundreds of such steps). Workers
    // get the main thread's stack size, as the commands ran here before.
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(MAIN_STACK_BYTES);
    if let Some(n) = cli.threads {
        pool = pool.num_threads(n.get());
    }
    if let Err(e) = pool.build_global() {
        eprintln!("error: cannot start the worker threads: {e}");
        return ExitCode::from(2);
    }
    let result = rayon::scope(|_| match cli.command {
        Command::Info(a) => cmd::info::run(a),
        Command::Validate(a) => cmd::validate::run(a),
        Command::Convert(a) => cmd::convert::run(a),
        Command::Generate(a) => cmd::generate::run(a),
        Command::Demo(a) => cmd::demo::run(a),
        Command::Patterns(a) => cmd::patterns::run(a),
        Command::Replace(a) => cmd::replace::run(a),
        Command::Query(a) => cmd::query::run(a),
        Command::Modify(a) => cmd::modify::run(a),
        Command::Quality(a) => cmd::quality::run(a),
        Command::Subdivide(a) => cmd::subdivide::run(a),
        Command::Conformal(a) => cmd::conformal::run(a),
        Command::Tet2hex(a) => cmd::tet2hex::run(a),
        Command::Tetrahedralize(a) => cmd::tetrahedralize::run(a),
        Command::Recombine(a) => cmd::recombine::run(a),
        Command::MarchingCubes(a) => cmd::marching_cubes::run(a),
        Command::Render(a) => cmd::render::run(a),
    });
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
