//! Rule files (TOML, no code needed): a list of `[[rule]]` tables, each naming a query
//! mesh, an operation and (for extend/delete/replace) a target mesh.
//!
//! ```toml
//! [[rule]]
//! name = "roof"            # optional, defaults to the query file's stem
//! op = "extend"            # query | extend | delete | replace | apply
//! query = "block.mesh"     # paths are relative to the rule file
//! target = "block_roof.mesh"
//! # apply = "flatten-top"  # for op = "apply": a built-in operation (merge, flatten-top)
//! boundary = "*"           # condition of the query's 3-free darts: * | eps | interior | no-connection
//! faces = { 7 = "eps" }    # per-face overrides: Medit reference of a boundary face → condition
//! strategy = "greedy"      # greedy | best | random
//! metric = "hex-quality"   # for best: hex-quality | volume
//! max = 50                 # modify at most this many matches
//! separation = "darts"     # what two selected matches may not share: darts | vertices
//! seed = 1                 # for random
//! orientation = "geometric" # of automorphic matches: the image fitting the query's
//!                           # shape and orientation best (default: smallest start dart)
//! max_residual = 0.01       # reject matches whose shape is not an affine copy of the
//!                           # query's (relative residual of the best affine fit, 0..1)
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use super::apply::{BUILTIN_APPLY, builtin_apply};
use super::plan::{Operation, Plan};
use super::rule::{Action, Rule};
use crate::pattern::read_small_map;
use crate::query::{Condition, Metric, Query, Separation, Strategy};

/// A rule file that cannot be used: the file, the line, the key, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}: {}{msg}", key.as_ref().map(|k| format!("`{k}`: ")).unwrap_or_default(), file = file.display())]
pub struct RuleError {
    pub file: PathBuf,
    pub line: usize,
    pub key: Option<String>,
    pub msg: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    rule: Vec<Spanned<RawRule>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRule {
    name: Option<String>,
    op: Spanned<String>,
    query: Spanned<String>,
    target: Option<Spanned<String>>,
    apply: Option<Spanned<String>>,
    boundary: Option<Spanned<String>>,
    faces: Option<Spanned<BTreeMap<String, Spanned<String>>>>,
    strategy: Option<Spanned<String>>,
    metric: Option<Spanned<String>>,
    max: Option<usize>,
    separation: Option<Spanned<String>>,
    seed: Option<u64>,
    orientation: Option<Spanned<String>>,
    max_residual: Option<f64>,
}

/// Reads and compiles every rule of a rule file: loads the query and target meshes,
/// applies the boundary conditions, and computes each modification plan.
///
/// # Errors
/// A [`RuleError`] naming the line and key: TOML syntax, unknown keys or values,
/// unreadable meshes, queries that are not connected or not closed, targets that do
/// not fit the operation.
pub fn load_rules(path: &Path) -> Result<Vec<Rule>, RuleError> {
    let text = std::fs::read_to_string(path).map_err(|e| RuleError {
        file: path.into(),
        line: 0,
        key: None,
        msg: format!("cannot read: {e}"),
    })?;
    parse_rules(path, &text)
}

/// As [`load_rules`] on the text of a rule file (`path` names it and anchors relative
/// mesh paths).
///
/// # Errors
/// As [`load_rules`].
pub fn parse_rules(path: &Path, text: &str) -> Result<Vec<Rule>, RuleError> {
    let line_of = |at: usize| text[..at.min(text.len())].matches('\n').count() + 1;
    let err = |at: usize, key: Option<&str>, msg: String| RuleError {
        file: path.into(),
        line: line_of(at),
        key: key.map(str::to_string),
        msg,
    };
    let raw: RawFile = toml::from_str(text)
        .map_err(|e| err(e.span().map_or(0, |s| s.start), None, e.message().trim_end().to_string()))?;
    if raw.rule.is_empty() {
        return Err(err(0, None, "no [[rule]] tables".into()));
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut rules = Vec::new();
    for spanned in raw.rule {
        let at = spanned.span().start;
        let r = spanned.into_inner();
        let value = |s: &Spanned<String>, key: &str, what: &str| err(s.span().start, Some(key), what.to_string());
        let op = match r.op.get_ref().as_str() {
            "query" | "find" | "apply" => None,
            s => Some(Operation::parse(s).ok_or_else(|| {
                value(&r.op, "op", &format!("unknown operation '{s}' (query, extend, delete, replace, apply)"))
            })?),
        };
        let apply = match (r.op.get_ref().as_str(), &r.apply) {
            ("apply", None) => {
                let list = BUILTIN_APPLY.join(", ");
                return Err(err(at, Some("apply"), format!("op = \"apply\" needs `apply = \"…\"` ({list})")));
            }
            ("apply", Some(name)) => Some(builtin_apply(name.get_ref()).ok_or_else(|| {
                let list = BUILTIN_APPLY.join(", ");
                value(name, "apply", &format!("unknown apply operation '{}' ({list})", name.get_ref()))
            })?),
            (_, Some(name)) => return Err(value(name, "apply", "only op = \"apply\" takes an apply operation")),
            (_, None) => None,
        };
        if let (Some(_), Some(t)) = (&apply, &r.target) {
            return Err(value(t, "target", "op = \"apply\" takes no target: the operation is the modification"));
        }
        let condition = |s: &Spanned<String>, key: &str| {
            Condition::parse(s.get_ref()).ok_or_else(|| {
                value(
                    s,
                    key,
                    &format!("unknown boundary condition '{}' (*, eps, interior, no-connection)", s.get_ref()),
                )
            })
        };
        let default = r.boundary.as_ref().map(|b| condition(b, "boundary")).transpose()?.unwrap_or(Condition::Any);
        let mut by_label = BTreeMap::new();
        if let Some(faces) = &r.faces {
            for (k, v) in faces.get_ref() {
                let label: i32 = k.trim().parse().map_err(|_| {
                    err(faces.span().start, Some("faces"), format!("'{k}' is not a face reference (an integer)"))
                })?;
                by_label.insert(label, condition(v, "faces")?);
            }
        }
        let qpath = dir.join(r.query.get_ref());
        let (qmap, labels) =
            read_small_map(&qpath).map_err(|e| value(&r.query, "query", &format!("cannot use the query: {e}")))?;
        if let Some(unused) = by_label.keys().find(|l| !labels.references().contains(l)) {
            return Err(err(
                r.faces.as_ref().map_or(at, |f| f.span().start),
                Some("faces"),
                format!("no boundary face of {} has reference {unused}", qpath.display()),
            ));
        }
        let name = r.name.clone().unwrap_or_else(|| stem(&qpath));
        let mut query = Query::new(&name, qmap, |_| default)
            .map_err(|e| value(&r.query, "query", &format!("{}: {e}", qpath.display())))?;
        let map = query.map().clone();
        query.set_conditions(|d| labels.of(&map, d).and_then(|l| by_label.get(&l).copied()).unwrap_or(default));
        query.orient_by_geometry = match r.orientation.as_ref().map(|o| o.get_ref().as_str()) {
            None | Some("start") => false,
            Some("geometric") => true,
            Some(o) => {
                let s = r.orientation.as_ref().expect("matched Some");
                return Err(value(s, "orientation", &format!("unknown orientation '{o}' (start, geometric)")));
            }
        };
        if let Some(r) = r.max_residual {
            if !(0.0..=1.0).contains(&r) {
                return Err(err(at, Some("max_residual"), format!("{r} is not a relative residual in 0..1")));
            }
            if !query.has_affine_fit() {
                return Err(err(at, Some("max_residual"), "the query's vertices do not span 3D: no affine fit".into()));
            }
        }
        query.max_residual = r.max_residual;
        let action = match op {
            None if apply.is_some() => Action::Apply(apply.expect("checked")),
            None => Action::Find,
            Some(op) => {
                let t = r
                    .target
                    .as_ref()
                    .ok_or_else(|| err(at, Some("target"), format!("{} needs a target", op.name())))?;
                let tpath = dir.join(t.get_ref());
                let (tmap, _) =
                    read_small_map(&tpath).map_err(|e| value(t, "target", &format!("cannot use the target: {e}")))?;
                let plan = Plan::new(op, &mut query, &tmap)
                    .map_err(|e| value(t, "target", &format!("{}: {e}", tpath.display())))?;
                Action::Plan(plan)
            }
        };
        let seed = r.seed.unwrap_or(0);
        let strategy = match &r.strategy {
            None => Strategy::Greedy,
            Some(s) => Strategy::parse(s.get_ref(), seed).ok_or_else(|| {
                value(s, "strategy", &format!("unknown strategy '{}' (greedy, best, random)", s.get_ref()))
            })?,
        };
        let metric = match &r.metric {
            None => None,
            Some(s) => Some(Metric::parse(s.get_ref()).ok_or_else(|| {
                value(s, "metric", &format!("unknown metric '{}' (hex-quality, volume)", s.get_ref()))
            })?),
        };
        if strategy == Strategy::Best && metric.is_none() {
            return Err(err(at, Some("metric"), "strategy \"best\" needs a metric (hex-quality, volume)".into()));
        }
        if matches!(metric, Some(Metric::HexQuality)) && query.corners.is_none() {
            return Err(value(&r.query, "metric", "hex-quality needs a query whose shape spans a hexahedron"));
        }
        let separation = match &r.separation {
            None => Separation::Darts,
            Some(s) => Separation::parse(s.get_ref()).ok_or_else(|| {
                value(s, "separation", &format!("unknown separation '{}' (darts, vertices)", s.get_ref()))
            })?,
        };
        rules.push(Rule { name, query, action, strategy, metric, max: r.max, separation });
    }
    Ok(rules)
}

fn stem(p: &Path) -> String {
    p.file_stem().map_or_else(|| "rule".to_string(), |s| s.to_string_lossy().into_owned())
}
