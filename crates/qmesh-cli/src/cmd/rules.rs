//! What `query` and `modify` share: rules from a TOML file or a single query mesh, and
//! the match-coloured output mesh.

use std::path::Path;

use anyhow::{Context, Result, anyhow};
use qmesh::build::{CellArray, CellValues};
use qmesh::cmap::{CMap3, Dart, Orbit, OrbitWalker};
use qmesh::modify::{Rule, load_rules};
use qmesh::pattern::read_small_map;
use qmesh::query::{Condition, Query};

/// Options of a query given as a mesh file instead of a rule file.
#[derive(clap::Args, Debug, Clone)]
pub struct QueryArgs {
    /// Condition of the query's 3-free darts when the query is a mesh file:
    /// `*`, `eps`, `interior` or `no-connection`.
    #[arg(long, default_value = "*")]
    pub boundary: String,
    /// Of symmetric matches of a query mesh file, keep the placement fitting the query's
    /// shape and orientation best (`geometric`) or the one starting at the smallest dart.
    #[arg(long, default_value = "start")]
    pub orientation: String,
    /// Reject matches of a query mesh file whose best affine fit from the query leaves a
    /// relative residual above this: the RMS distance from the fit over the RMS distance
    /// from the centroid, 0..1 whatever the units (0.01: 1 % off an affine copy).
    #[arg(long)]
    pub max_residual: Option<f64>,
}

/// The rules of a `.toml` rule file, or one query-only rule from a mesh file.
pub fn rules_of(path: &Path, args: &QueryArgs) -> Result<Vec<Rule>> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml")) {
        return Ok(load_rules(path)?);
    }
    let c = Condition::parse(&args.boundary)
        .ok_or_else(|| anyhow!("unknown --boundary '{}' (*, eps, interior, no-connection)", args.boundary))?;
    let (map, _) = read_small_map(path)?;
    let name = path.file_stem().map_or("query".into(), |s| s.to_string_lossy().into_owned());
    let mut q = Query::new(&name, map, |_| c).with_context(|| format!("{}", path.display()))?;
    q.orient_by_geometry = match args.orientation.as_str() {
        "start" => false,
        "geometric" => true,
        o => anyhow::bail!("unknown --orientation '{o}' (start, geometric)"),
    };
    if let Some(r) = args.max_residual {
        anyhow::ensure!((0.0..=1.0).contains(&r), "--max-residual takes a relative residual in 0..1, got {r}");
        anyhow::ensure!(q.has_affine_fit(), "{}: the query's vertices do not span 3D (no affine fit)", path.display());
        q.max_residual = Some(r);
    }
    Ok(vec![Rule::find(q)])
}

/// Per-volume arrays in the map's volume order: `match` (index of the first match
/// covering the volume, −1 if none) and `match_count`.
pub fn match_arrays(map: &CMap3, matches: &[Vec<Dart>]) -> Vec<CellArray> {
    let mut first = vec![-1i32; map.dart_capacity()];
    let mut count = vec![0i32; map.dart_capacity()];
    let mut w = OrbitWalker::new();
    let mut seen = vec![u32::MAX; map.dart_capacity()];
    for (i, darts) in matches.iter().enumerate() {
        for &d in darts {
            // One visit per volume and match: darts of a volume are all in the match.
            if seen[d.idx()] == i as u32 {
                continue;
            }
            for &x in w.collect(map, d, Orbit::Volume) {
                seen[x.idx()] = i as u32;
                count[x.idx()] += 1;
                if first[x.idx()] < 0 {
                    first[x.idx()] = i as i32;
                }
            }
        }
    }
    let vols: Vec<Dart> = map.cells(Orbit::Volume).collect();
    vec![
        CellArray { name: "match".into(), values: CellValues::Int(vols.iter().map(|d| first[d.idx()]).collect()) },
        CellArray {
            name: "match_count".into(),
            values: CellValues::Int(vols.iter().map(|d| count[d.idx()]).collect()),
        },
    ]
}
