//! Executing plans on many matches that share no dart (the faces or the volumes of one
//! query-replace pass, 2022 §5.1), on all cores. Darts and vertices are allocated
//! first, as [`execute`](fn@super::execute) allocates them match after match; then each
//! match writes its new darts and its matched darts' links, which no other match reads
//! or writes ([`SharedDarts`]). The map is the same, dart for dart, as executing the
//! matches one by one, whatever the number of threads.

use rayon::prelude::*;

use super::plan::{Link, Plan, VertexOf};
use crate::cmap::{CMap3, Dart, SharedDarts};

/// A plan and the match it runs on (query label k at `matched[k - 1]`).
#[derive(Debug)]
pub struct Job<'a> {
    pub plan: &'a Plan,
    pub matched: Vec<Dart>,
}

/// Runs batches of jobs with [`execute`](Self::execute), keeping its list of new darts
/// from one batch to the next (a batch of a few thousand volumes makes megabytes).
#[derive(Debug, Default)]
pub struct DisjointExecutor {
    new: Vec<Dart>,
}

thread_local! {
    /// Executors handed back on this thread, with their buffers.
    static RECYCLED: std::cell::RefCell<Vec<DisjointExecutor>> = const { std::cell::RefCell::new(Vec::new()) };
}

impl DisjointExecutor {
    /// An executor with the buffers of the last one [`recycle`](Self::recycle)d on this
    /// thread, if any: passes that follow one another (the levels of a subdivision)
    /// write into memory already in use instead of fresh pages.
    pub fn reuse() -> Self {
        RECYCLED.with(|r| r.borrow_mut().pop()).unwrap_or_default()
    }

    /// Frees the buffers kept on this thread (when no more passes follow, so that they do
    /// not add to the peak memory of what comes after), on another core when one is free.
    pub fn release_recycled() {
        let kept = RECYCLED.with(|r| std::mem::take(&mut *r.borrow_mut()));
        if !kept.is_empty() {
            rayon::spawn(move || drop(kept));
        }
    }

    /// Keeps this executor's buffers for the next [`reuse`](Self::reuse) on this thread.
    pub fn recycle(self) {
        RECYCLED.with(|r| {
            let mut r = r.borrow_mut();
            if r.len() < 2 {
                r.push(self);
            }
        });
    }

    /// Executes every job, as [`execute`](fn@super::execute) would one after another. The
    /// matches must be pairwise disjoint (overlapping ones give a wrong map, never
    /// undefined behaviour) and no plan may delete darts (such jobs run one by one
    /// instead). Returns the new darts, job after job, in each plan's order.
    pub fn execute(&mut self, map: &mut CMap3, jobs: &[Job]) -> &[Dart] {
        self.new.clear();
        if jobs.iter().any(|j| !j.plan.deleted.is_empty()) {
            for j in jobs {
                self.new.extend(super::execute(map, j.plan, &j.matched).1);
            }
            return &self.new;
        }
        // Sizes of each job, computed once per run of jobs with the same plan (a pass
        // has a few plans and thousands of jobs).
        let mut last: Option<(&Plan, Sizes)> = None;
        let sizes: Vec<Sizes> = jobs
            .iter()
            .map(|j| match last {
                Some((p, n)) if std::ptr::eq(p, j.plan) => n,
                _ => last.insert((j.plan, Sizes::of(j.plan))).1,
            })
            .collect();
        if sizes.iter().any(|s| s.labels) {
            map.enable_labels();
        }
        let (vertex_counts, dart_counts): (Vec<usize>, Vec<usize>) =
            sizes.iter().map(|s| (s.vertices, s.darts)).unzip();
        let first_vertex = map.nb_vertex_ids() as u32;
        map.reserve_darts(dart_counts.iter().sum(), &mut self.new);
        let (shared, positions, created) = map.shared_darts(vertex_counts.iter().sum());
        let starts = |c: &[usize]| c.iter().scan(0, |s, &n| Some(std::mem::replace(s, *s + n))).collect::<Vec<_>>();
        let (vertex_starts, dart_starts) = (starts(&vertex_counts), starts(&dart_counts));
        let new = &self.new;
        // 64 jobs a piece: left to itself, rayon hands out a few large pieces, and the
        // core with the slower one then finishes alone.
        split(created, &vertex_counts).into_par_iter().enumerate().with_min_len(64).with_max_len(64).for_each(
            |(k, created)| {
                let mine = &new[dart_starts[k]..dart_starts[k] + dart_counts[k]];
                let first = first_vertex + vertex_starts[k] as u32;
                write(&shared, positions, &jobs[k], mine, (first, created));
            },
        );
        &self.new
    }
}

/// The slot of the reverse link of a βi link: plans link through β1 (whose inverse is
/// β0), β2 and β3 (involutions).
fn back_slot(i: usize) -> usize {
    debug_assert!((1..=3).contains(&i), "plans link through β1, β2 and β3");
    if i == 1 { 0 } else { i }
}

/// What executing a plan once adds.
#[derive(Clone, Copy)]
struct Sizes {
    vertices: usize,
    darts: usize,
    /// Whether the target gives a volume a label of its own.
    labels: bool,
}

impl Sizes {
    fn of(plan: &Plan) -> Sizes {
        Sizes {
            vertices: plan.created.len(),
            darts: plan.new_darts.len(),
            labels: plan.new_darts.iter().any(|n| n.label != 0),
        }
    }
}

/// Writes what [`execute`](fn@super::execute) makes of `job`, whose new darts are `new`
/// (reserved) and created vertices `created` (their first id, their positions to
/// write): the created positions from `positions` (the vertices before the batch), the
/// new darts, then every link in `execute`'s order. A job writes only its new darts and
/// its matched darts' links, and reads only what no other job of the batch writes.
fn write(map: &SharedDarts, positions: &[[f64; 3]], job: &Job, new: &[Dart], created: (u32, &mut [[f64; 3]])) {
    let plan = job.plan;
    let at = |l: u32| job.matched[l as usize - 1];
    let (first_vertex, created) = created;
    for (w, p) in plan.created.iter().zip(created.iter_mut()) {
        for &(l, x) in w {
            let q = positions[map.vertex_of(at(l)) as usize];
            (0..3).for_each(|k| p[k] += x * q[k]);
        }
    }
    for (n, &d) in plan.new_darts.iter().zip(new) {
        let vertex = match n.vertex {
            VertexOf::Matched(l) => map.vertex_of(at(l)),
            VertexOf::Created(i) => first_vertex + i,
        };
        let label = if n.label != 0 { n.label } else { map.label_of(at(n.label_from)) };
        map.store_dart(d, [0; 4], vertex, label);
    }
    let end = |l: Link| match l {
        Link::Free => None,
        Link::New(i) => Some(new[i as usize]),
        Link::Matched(k) => Some(at(k)),
    };
    let link = |a: Dart, i: usize, b: Dart| {
        map.set_beta(a.raw(), i, b.raw());
        map.set_beta(b.raw(), back_slot(i), a.raw());
    };
    for (n, &d) in plan.new_darts.iter().zip(new) {
        for (i, &l) in n.links.iter().enumerate() {
            if let Some(o) = end(l) {
                link(d, i + 1, o);
            }
        }
    }
    for &(k, i, l) in &plan.relink {
        link(at(k), i, end(l).expect("relinked darts are never left free"));
    }
}

/// `items` cut into consecutive parts of the given lengths.
fn split<'a, T>(mut items: &'a mut [T], lengths: &[usize]) -> Vec<&'a mut [T]> {
    lengths
        .iter()
        .map(|&n| {
            let (part, rest) = std::mem::take(&mut items).split_at_mut(n);
            items = rest;
            part
        })
        .collect()
}
