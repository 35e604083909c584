//! What one modification does to a match, computed once per rule from Q, T and m_QT
//! (2025 Algorithms 2–4, §6.5) and then executed on every selected match. Everything
//! is expressed in query labels, so executing a plan needs only the match.

use rustc_hash::FxHashMap;

use super::correspondence::{boundary_correspondence, embed};
use super::error::ModifyError;
use crate::cmap::{CMap3, Dart};
use crate::pattern::{PatternKind, interior_coordinates};
use crate::query::{Condition, Query};

/// The three target-based operations (2025 §6.1–6.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Operation {
    /// Q is a submap of T: add T ∖ Q around the match (Algorithm 2).
    Extend,
    /// T is a submap of Q: remove Q ∖ T from the match (Algorithm 3).
    Delete,
    /// Q and T have isomorphic boundaries: replace the match's interior (Algorithm 4).
    Replace,
}

impl Operation {
    pub fn parse(s: &str) -> Option<Operation> {
        match s {
            "extend" => Some(Operation::Extend),
            "delete" => Some(Operation::Delete),
            "replace" => Some(Operation::Replace),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Operation::Extend => "extend",
            Operation::Delete => "delete",
            Operation::Replace => "replace",
        }
    }
}

/// Where a link of a new dart goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Link {
    Free,
    /// The new dart of this index.
    New(u32),
    /// The input dart matched by this query label.
    Matched(u32),
}

/// The origin vertex of a new dart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum VertexOf {
    /// The vertex of the input dart matched by this label (a preserved vertex).
    Matched(u32),
    /// The created vertex of this index.
    Created(u32),
}

#[derive(Clone, Debug)]
pub(crate) struct NewDart {
    /// β1, β2, β3.
    pub links: [Link; 3],
    pub vertex: VertexOf,
    /// The label whose matched dart's volume label the new dart takes…
    pub label_from: u32,
    /// … unless the target gives its volume a label of its own (non-zero).
    pub label: i32,
}

/// A modification in query labels.
#[derive(Clone, Debug)]
pub struct Plan {
    pub op: Operation,
    /// Labels whose matched darts are removed.
    pub(crate) deleted: Vec<u32>,
    pub(crate) new_darts: Vec<NewDart>,
    /// Links of matched darts to reset, as (label, i, target of βi): β2 on the boundary
    /// of a replaced interior, β1 around a replaced face.
    pub(crate) relink: Vec<(u32, usize, Link)>,
    /// Created vertices as weights over matched labels (mean value coordinates).
    pub(crate) created: Vec<Vec<(u32, f64)>>,
}

impl Plan {
    /// Darts added per match.
    pub fn darts_added(&self) -> usize {
        self.new_darts.len()
    }

    /// Darts removed per match.
    pub fn darts_removed(&self) -> usize {
        self.deleted.len()
    }

    /// The plan of `op` for query `q` and target `t`. For extend, the query darts that
    /// the target glues new volumes to get the `ε` condition (2025 §6.1).
    ///
    /// # Errors
    /// When the query and target do not fit the operation (Q ⊄ T, T ⊄ Q, or different
    /// boundaries).
    pub fn new(op: Operation, q: &mut Query, t: &CMap3) -> Result<Plan, ModifyError> {
        match op {
            Operation::Extend => extend_plan(q, t),
            Operation::Delete => delete_plan(q, t),
            Operation::Replace => replace_plan(q, t),
        }
    }

    /// The plan of [`Operation::Replace`], which leaves the query as it is.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn replace(q: &Query, t: &CMap3) -> Result<Plan, ModifyError> {
        replace_plan(q, t)
    }
}

/// Index of each T vertex id among created vertices, or the label of a query dart
/// at the same vertex; MVC weights of created vertices over the preserved ones.
struct Vertices {
    preserved: FxHashMap<u32, u32>,
    created: FxHashMap<u32, u32>,
    weights: Vec<Vec<(u32, f64)>>,
}

impl Vertices {
    /// `preserved`: T vertex id → label; `cage`: T darts of the closed surface whose
    /// mean value coordinates place the created vertices.
    fn new(t: &CMap3, preserved: FxHashMap<u32, u32>, cage: &[Dart]) -> Result<Vertices, ModifyError> {
        let mut created = FxHashMap::default();
        let mut weights = Vec::new();
        for iv in interior_coordinates(t, PatternKind::Volume, cage) {
            if preserved.contains_key(&iv.vertex) {
                continue;
            }
            let w: Option<Vec<(u32, f64)>> =
                iv.weights.iter().map(|&(v, w)| preserved.get(&v).map(|&l| (l, w))).collect();
            created.insert(iv.vertex, weights.len() as u32);
            weights.push(w.ok_or(ModifyError::Geometry)?);
        }
        Ok(Vertices { preserved, created, weights })
    }

    fn of(&self, t_vertex: u32) -> VertexOf {
        match self.preserved.get(&t_vertex) {
            Some(&l) => VertexOf::Matched(l),
            None => VertexOf::Created(self.created[&t_vertex]),
        }
    }
}

fn extend_plan(q: &mut Query, t: &CMap3) -> Result<Plan, ModifyError> {
    let e = embed(q, t).ok_or(ModifyError::NotSubmap { op: Operation::Extend })?;
    let mut label_in_t: FxHashMap<Dart, u32> = FxHashMap::default();
    for (k, &d) in e.iter().enumerate() {
        label_in_t.insert(d, k as u32 + 1);
    }
    let new: Vec<Dart> = t.darts().filter(|d| !label_in_t.contains_key(d)).collect();
    if new.is_empty() {
        return Err(ModifyError::Nothing { op: Operation::Extend });
    }
    let index: FxHashMap<Dart, u32> = new.iter().enumerate().map(|(i, &d)| (d, i as u32)).collect();
    let preserved: FxHashMap<u32, u32> = e.iter().enumerate().map(|(k, &d)| (t.vertex_of(d), k as u32 + 1)).collect();
    let cage: Vec<Dart> = q.word.free_labels().map(|k| e[k - 1]).collect();
    let vertices = Vertices::new(t, preserved, &cage)?;
    let mut attached = Vec::new();
    let mut new_darts = Vec::with_capacity(new.len());
    for &d in &new {
        let mut links = [Link::Free; 3];
        for (i, link) in links.iter_mut().enumerate() {
            let Some(n) = t.beta(d, i + 1) else { continue };
            *link = match (index.get(&n), label_in_t.get(&n)) {
                (Some(&j), _) => Link::New(j),
                (None, Some(&l)) => {
                    // Only across faces: the query's volumes are whole in the target, so
                    // their β1 and β2 partners are query darts too.
                    debug_assert_eq!(i + 1, 3, "a new dart β{}-linked to a query dart", i + 1);
                    attached.push(l);
                    Link::Matched(l)
                }
                _ => return Err(ModifyError::NotSubmap { op: Operation::Extend }),
            };
        }
        new_darts.push(NewDart { links, vertex: vertices.of(t.vertex_of(d)), label_from: 1, label: t.label_of(d) });
    }
    // The match darts that new volumes are glued to must be on the input's boundary.
    let attached: rustc_hash::FxHashSet<u32> = attached.into_iter().collect();
    let dart_labels = q.labelling().clone();
    let word = q.word.clone();
    q.set_conditions(|d| {
        let k = dart_labels.of(d);
        if attached.contains(&k) { Condition::Boundary } else { word.condition(k as usize).unwrap_or(Condition::Any) }
    });
    Ok(Plan { op: Operation::Extend, deleted: Vec::new(), new_darts, relink: Vec::new(), created: vertices.weights })
}

fn delete_plan(q: &Query, t: &CMap3) -> Result<Plan, ModifyError> {
    let tq = Query::new("target", t.clone(), |_| Condition::Any).map_err(ModifyError::Target)?;
    let e = embed(&tq, q.map()).ok_or(ModifyError::NotSubmap { op: Operation::Delete })?;
    let kept: rustc_hash::FxHashSet<Dart> = e.into_iter().collect();
    let deleted: Vec<u32> =
        q.labelling().darts.iter().filter(|d| !kept.contains(d)).map(|&d| q.labelling().of(d)).collect();
    if deleted.is_empty() {
        return Err(ModifyError::Nothing { op: Operation::Delete });
    }
    Ok(Plan { op: Operation::Delete, deleted, new_darts: Vec::new(), relink: Vec::new(), created: Vec::new() })
}

fn replace_plan(q: &Query, t: &CMap3) -> Result<Plan, ModifyError> {
    let pairs = boundary_correspondence(q.map(), t).ok_or(ModifyError::Boundaries)?;
    let label_of_t: FxHashMap<Dart, u32> = pairs.iter().map(|&(qd, td)| (td, q.labelling().of(qd))).collect();
    let deleted: Vec<u32> =
        q.labelling().darts.iter().filter(|&&d| !q.map().is_free(d, 3)).map(|&d| q.labelling().of(d)).collect();
    let new: Vec<Dart> = t.darts().filter(|&d| !t.is_free(d, 3)).collect();
    let index: FxHashMap<Dart, u32> = new.iter().enumerate().map(|(i, &d)| (d, i as u32)).collect();
    let link_to = |n: Dart| match index.get(&n) {
        Some(&j) => Link::New(j),
        None => Link::Matched(label_of_t[&n]),
    };
    let preserved: FxHashMap<u32, u32> =
        pairs.iter().map(|&(qd, td)| (t.vertex_of(td), q.labelling().of(qd))).collect();
    let cage: Vec<Dart> = pairs.iter().map(|p| p.1).collect();
    let vertices = Vertices::new(t, preserved, &cage)?;
    let mut new_darts = Vec::with_capacity(new.len());
    for &d in &new {
        let links = [1, 2, 3].map(|i| t.beta(d, i).map_or(Link::Free, link_to));
        new_darts.push(NewDart { links, vertex: vertices.of(t.vertex_of(d)), label_from: 1, label: t.label_of(d) });
    }
    let relink = pairs
        .iter()
        .map(|&(qd, td)| (q.labelling().of(qd), 2, link_to(t.beta(td, 2).expect("targets are 2-sewn"))))
        .collect();
    Ok(Plan { op: Operation::Replace, deleted, new_darts, relink, created: vertices.weights })
}
