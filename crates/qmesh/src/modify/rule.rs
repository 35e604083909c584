//! A rule: a query, what to do with its matches, and how to choose them; and running
//! rules on a map (2025 §4: query, then modify every selected match in one pass).

use std::fmt;
use std::sync::Arc;
use std::time::Instant;

use super::execute::{Executed, execute};
use super::plan::Plan;
use crate::cmap::{CMap3, Dart, MapError};
use crate::query::{
    MatchOptions, Metric, Query, QuerySet, Separation, Strategy, find_matches, select_random_lazily, select_separated,
};

/// A query-apply function (2025 §6.4): receives the map and one match (query label k
/// at `matched[k - 1]`) and may use any map operation (`remove_face` to merge
/// volumes, `set_position`, `sew3`/`unsew3`, …). The map is validated afterwards.
pub type ApplyFn = dyn Fn(&mut CMap3, &Query, &[Dart]) -> Result<(), MapError> + Send + Sync;

/// What a rule does with the matches it selects.
#[derive(Clone)]
pub enum Action {
    /// Nothing: the rule only queries.
    Find,
    /// Extend, delete or replace (a plan computed from the target).
    Plan(Plan),
    /// A function per match.
    Apply(Arc<ApplyFn>),
}

impl fmt::Debug for Action {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Action {
    pub fn name(&self) -> &'static str {
        match self {
            Action::Find => "query",
            Action::Plan(p) => p.op.name(),
            Action::Apply(_) => "apply",
        }
    }
}

/// One rule.
#[derive(Clone, Debug)]
pub struct Rule {
    pub name: String,
    pub query: Query,
    pub action: Action,
    pub strategy: Strategy,
    /// Scores matches for [`Strategy::Best`].
    pub metric: Option<Metric>,
    /// At most this many matches are modified.
    pub max: Option<usize>,
    /// What two selected matches may not share.
    pub separation: Separation,
}

impl Rule {
    /// A rule that only queries, greedily.
    pub fn find(query: Query) -> Rule {
        Rule {
            name: query.name.clone(),
            query,
            action: Action::Find,
            strategy: Strategy::Greedy,
            metric: None,
            max: None,
            separation: Separation::Darts,
        }
    }
}

/// What one rule did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct RuleReport {
    pub rule: String,
    pub op: &'static str,
    /// Matches found (one per set of darts): all of them, or, for a random selection
    /// with a `max`, those found from the start darts tried until it had enough.
    pub matches: usize,
    /// Start darts tried by a random selection with a `max` (it stops once it has
    /// `max` matches); `None` when every dart was matched.
    pub starts_tested: Option<usize>,
    /// Matches counting automorphic copies.
    pub matches_with_automorphisms: usize,
    pub automorphisms: usize,
    pub selected: usize,
    pub modified: usize,
    pub darts_added: usize,
    pub darts_removed: usize,
    pub vertices_created: usize,
    pub volumes_before: usize,
    pub volumes_after: usize,
    pub darts_before: usize,
    pub darts_after: usize,
    pub query_seconds: f64,
    pub modify_seconds: f64,
    /// Whether the map is valid after the rule.
    pub valid: bool,
    /// The first validity problem, if any.
    pub problem: Option<String>,
}

/// Runs `rules` in order on `map`: each one queries the map as the previous rules
/// left it, selects, and modifies every selected match.
///
/// ```
/// use qmesh::build::{BuildOptions, build_volume_map};
/// use qmesh::modify::{Action, Operation, Plan, Rule, run_rules};
/// use qmesh::query::{Condition, Query};
/// let opts = BuildOptions::default();
/// let (mut grid, _) = build_volume_map(&qmesh::generate::hex_grid(4, 1, 1), &opts).unwrap();
/// let (pair, _) = build_volume_map(&qmesh::generate::hex_grid(2, 1, 1), &opts).unwrap();
/// let (one, _) = build_volume_map(&qmesh::generate::hex_grid(1, 1, 1), &opts).unwrap();
/// // Delete: keep one hexahedron of every pair.
/// let mut q = Query::new("pair", pair, |_| Condition::Any).unwrap();
/// let plan = Plan::new(Operation::Delete, &mut q, &one).unwrap();
/// let mut rule = Rule::find(q);
/// rule.action = Action::Plan(plan);
/// let r = run_rules(&mut grid, &[rule]);
/// assert_eq!((r[0].selected, r[0].volumes_after), (2, 2));
/// assert!(r[0].valid);
/// ```
pub fn run_rules(map: &mut CMap3, rules: &[Rule]) -> Vec<RuleReport> {
    rules.iter().map(|r| run_rule(map, r)).collect()
}

fn run_rule(map: &mut CMap3, rule: &Rule) -> RuleReport {
    let before = map.count_cells();
    let t = Instant::now();
    let set = QuerySet::new(vec![rule.query.clone()]);
    let metric = if rule.strategy == Strategy::Best { rule.metric.as_ref() } else { None };
    let (chosen, matches, with_automorphisms, starts_tested) = match (rule.strategy, rule.max) {
        (Strategy::Random(seed), Some(max)) => {
            let (chosen, seen) = select_random_lazily(map, &set, &MatchOptions::default(), seed, max, rule.separation);
            (chosen, seen.matches, seen.with_automorphisms, Some(seen.starts_tested))
        }
        _ => {
            let found = find_matches(map, &set, &MatchOptions { metric, ..Default::default() });
            let chosen = select_separated(map, &set, &found.matches, rule.strategy, rule.max, rule.separation);
            (chosen, found.per_query[0], found.with_automorphisms[0], None)
        }
    };
    let query_seconds = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut r = RuleReport {
        rule: rule.name.clone(),
        op: rule.action.name(),
        matches,
        matches_with_automorphisms: with_automorphisms,
        starts_tested,
        automorphisms: rule.query.automorphisms.count(),
        selected: chosen.len(),
        query_seconds,
        volumes_before: before.volumes,
        darts_before: before.darts,
        ..Default::default()
    };
    let mut failure = None;
    for s in &chosen {
        match &rule.action {
            Action::Find => {}
            Action::Plan(plan) => {
                let (done, _) = execute(map, plan, &s.darts);
                add(&mut r, done);
            }
            Action::Apply(f) => {
                if let Err(e) = f(map, &rule.query, &s.darts) {
                    failure.get_or_insert(e.to_string());
                    continue;
                }
                r.modified += 1;
            }
        }
    }
    r.modify_seconds = t.elapsed().as_secs_f64();
    let after = map.count_cells();
    let violations = map.is_valid();
    r.volumes_after = after.volumes;
    r.darts_after = after.darts;
    r.valid = violations.is_empty();
    r.problem = failure.or_else(|| violations.first().map(|v| v.to_string()));
    r
}

fn add(r: &mut RuleReport, e: Executed) {
    r.modified += 1;
    r.darts_added += e.darts_added;
    r.darts_removed += e.darts_removed;
    r.vertices_created += e.vertices_created;
}
