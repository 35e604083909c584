//! `qmesh query RULES_OR_QUERY IN`: match queries (2025 §5) from every dart, report
//! counts per query, optionally select non-overlapping matches and write the mesh with
//! a `match` cell array.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, anyhow, bail};
use qmesh::build::BuildOptions;
use qmesh::io::{WriteOptions, load_map, write_map_with_arrays};
use qmesh::query::{MatchOptions, Metric, QuerySet, Separation, Strategy, find_matches, select, select_random_lazily};
use serde_json::json;

use super::rules::{QueryArgs, match_arrays, rules_of};
use super::{InputArgs, parse_format};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// A rule file (.toml; every rule's query is matched) or a query mesh file.
    pub rules: PathBuf,
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub query: QueryArgs,
    /// Keep every automorphic copy of a match (by default one per set of darts).
    #[arg(long)]
    pub all: bool,
    /// Also select non-overlapping matches: `greedy`, `best` (needs --metric) or `random`.
    #[arg(long)]
    pub strategy: Option<String>,
    /// Metric ranking matches for `best`: `hex-quality` or `volume`.
    #[arg(long)]
    pub metric: Option<String>,
    /// Select at most N matches.
    #[arg(long)]
    pub max: Option<usize>,
    /// Seed of the `random` order.
    #[arg(long, default_value = "0")]
    pub seed: u64,
    /// Write the input mesh with `match` and `match_count` cell arrays.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub report: super::ReportArgs,
    /// Allow the output to be the input file.
    #[arg(long)]
    pub force: bool,
}

pub fn run(a: Args) -> Result<ExitCode> {
    if let Some(o) = &a.output {
        super::refuse_to_overwrite(&a.input.input, o, a.force)?;
    }
    let rules = rules_of(&a.rules, &a.query)?;
    let metric = a
        .metric
        .as_deref()
        .map(|m| Metric::parse(m).ok_or_else(|| anyhow!("unknown --metric '{m}' (hex-quality, volume)")))
        .transpose()?;
    let strategy = a
        .strategy
        .as_deref()
        .map(|s| Strategy::parse(s, a.seed).ok_or_else(|| anyhow!("unknown --strategy '{s}' (greedy, best, random)")))
        .transpose()?;
    if strategy == Some(Strategy::Best) && metric.is_none() {
        bail!("--strategy best needs --metric (hex-quality, volume)");
    }
    let opts = BuildOptions { fix_orientation: a.input.fix_orientation };
    let loaded = load_map(&a.input.input, parse_format(&a.input.format)?, &opts)?;
    let map = &loaded.map;
    let set = QuerySet::new(rules.into_iter().map(|r| r.query).collect());
    let pb = crate::progress::spinner("query", a.report.quiet || a.report.json);
    let found = find_matches(
        map,
        &set,
        &MatchOptions { all_automorphisms: a.all, metric: metric.as_ref(), ..Default::default() },
    );
    let t = std::time::Instant::now();
    // A random choice with a max is the one `qmesh modify` makes (start darts drawn
    // lazily), so that the same seed picks the same matches in both commands.
    let chosen = strategy.map(|s| match (s, a.max) {
        (Strategy::Random(seed), Some(max)) => {
            select_random_lazily(map, &set, &MatchOptions::default(), seed, max, Separation::Darts).0
        }
        _ => select(map, &set, &found.matches, s, a.max),
    });
    let select_seconds = t.elapsed().as_secs_f64();
    pb.finish_and_clear();
    if let Some(out) = &a.output {
        let darts: Vec<Vec<qmesh::cmap::Dart>> = match &chosen {
            Some(c) => c.iter().map(|s| s.darts.clone()).collect(),
            None => {
                let mut annot = set.annotator();
                found.matches.iter().map(|m| set.darts_of(map, m, &mut annot)).collect()
            }
        };
        write_map_with_arrays(out, map, &match_arrays(map, &darts), None, &WriteOptions::default())?;
    }
    let counts = map.count_cells();
    let rate = found.steps as f64 / found.seconds.max(1e-9);
    if a.report.json {
        let queries: Vec<_> = set
            .queries
            .iter()
            .enumerate()
            .map(|(i, q)| {
                json!({
                    "name": q.name, "darts": q.nb_darts(), "volumes": q.nb_volumes(),
                    "automorphisms": q.automorphisms.count(),
                    "topological_automorphisms": q.automorphisms.topological_count(),
                    "matches": found.per_query[i],
                    "matches_with_automorphisms": found.with_automorphisms[i],
                })
            })
            .collect();
        let j = json!({
            "input": a.input.input.display().to_string(),
            "darts": counts.darts, "volumes": counts.volumes,
            "threads": rayon::current_num_threads(),
            "prefix_tree_nodes": set.tree.nb_nodes(),
            "queries": queries,
            "matches": found.matches.len(),
            "selected": chosen.as_ref().map(|c| c.len()),
            "strategy": strategy.map(|s| s.name()),
            "query_seconds": found.seconds,
            "select_seconds": select_seconds,
            "symbols_checked": found.steps,
            "symbols_per_second": rate,
            "output": a.output.as_ref().map(|o| o.display().to_string()),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
        return Ok(ExitCode::SUCCESS);
    }
    if a.report.quiet {
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{}: {} darts, {} volumes; {} queries, prefix tree of {} nodes, {} threads",
        a.input.input.display(),
        counts.darts,
        counts.volumes,
        set.queries.len(),
        set.tree.nb_nodes(),
        rayon::current_num_threads()
    );
    for (i, q) in set.queries.iter().enumerate() {
        println!(
            "  {:<20} {:>4} darts {:>3} volumes  automorphisms {:>2}  matches {:>10} ({} counting automorphisms)",
            q.name,
            q.nb_darts(),
            q.nb_volumes(),
            q.automorphisms.count(),
            found.per_query[i],
            found.with_automorphisms[i]
        );
    }
    println!("query {:.3} s, {:.3e} symbols checked ({:.3e}/s)", found.seconds, found.steps as f64, rate);
    if let Some(c) = &chosen {
        println!(
            "selected {} non-overlapping matches ({}) in {:.3} s",
            c.len(),
            strategy.unwrap().name(),
            select_seconds
        );
    }
    if let Some(o) = &a.output {
        println!("wrote {}", o.display());
    }
    Ok(ExitCode::SUCCESS)
}
