//! Executing plans on many matches that share no dart (the faces or the volumes of one
//! query-replace pass, 2022 §5.1): each match is resolved on any core into plain
//! stores (positions, vertex ids, labels, betas), which one thread then makes in the
//! matches' order. Darts and vertices are allocated as [`execute`](fn@super::execute)
//! allocates them, match after match, so the map is the same, dart for dart, as
//! executing the matches one by one, whatever the number of threads.

use rayon::prelude::*;

use super::plan::{Link, Plan, VertexOf};
use crate::cmap::{CMap3, Dart};

/// A plan and the match it runs on (query label k at `matched[k - 1]`).
#[derive(Debug)]
pub struct Job<'a> {
    pub plan: &'a Plan,
    pub matched: Vec<Dart>,
}

/// A link end: a new dart of the job (by index) or a dart of the map.
#[derive(Clone, Copy)]
enum End {
    New(u32),
    Old(Dart),
}

/// One beta store into a dart of the map: β`slot` of raw dart `at` becomes raw `to`.
#[derive(Clone, Copy, Debug, Default)]
struct Store {
    at: u32,
    slot: u8,
    to: u32,
}

/// A new dart as stored: betas (raw), vertex id, label.
#[derive(Clone, Copy, Debug, Default)]
struct NewRecord {
    betas: [u32; 4],
    vertex: u32,
    label: i32,
}

/// What one job writes, resolved before anything is written.
struct Resolved<'a> {
    positions: &'a mut [[f64; 3]],
    darts: &'a mut [NewRecord],
    stores: &'a mut [Store],
}

/// Runs batches of jobs with [`execute`](Self::execute), keeping its buffers from one
/// batch to the next (a batch of a few thousand volumes resolves into megabytes).
#[derive(Debug, Default)]
pub struct DisjointExecutor {
    positions: Vec<[f64; 3]>,
    darts: Vec<NewRecord>,
    stores: Vec<Store>,
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
    /// not add to the peak memory of what comes after).
    pub fn release_recycled() {
        RECYCLED.with(|r| r.borrow_mut().clear());
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
    /// matches must be pairwise disjoint and no plan may delete darts (such jobs run
    /// one by one instead). Returns the new darts, job after job, in each plan's order.
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
        let counts = |f: fn(&Sizes) -> usize| sizes.iter().map(f).collect::<Vec<_>>();
        let (vertex_counts, dart_counts, store_counts) =
            (counts(|s| s.vertices), counts(|s| s.darts), counts(|s| s.stores));
        let first_vertex = map.nb_vertex_ids() as u32;
        map.reserve_darts(dart_counts.iter().sum(), &mut self.new);
        refill(&mut self.positions, vertex_counts.iter().sum());
        refill(&mut self.darts, self.new.len());
        refill(&mut self.stores, store_counts.iter().sum());
        let parts: Vec<Resolved> = split(&mut self.positions, &vertex_counts)
            .into_iter()
            .zip(split(&mut self.darts, &dart_counts))
            .zip(split(&mut self.stores, &store_counts))
            .map(|((positions, darts), stores)| Resolved { positions, darts, stores })
            .collect();
        let starts = |c: &[usize]| c.iter().scan(0, |s, &n| Some(std::mem::replace(s, *s + n))).collect::<Vec<_>>();
        let (vertex_starts, dart_starts) = (starts(&vertex_counts), starts(&dart_counts));
        let (shared, new): (&CMap3, &[Dart]) = (map, &self.new);
        parts.into_par_iter().enumerate().with_min_len(64).for_each(|(k, out)| {
            let mine = &new[dart_starts[k]..dart_starts[k] + dart_counts[k]];
            resolve(shared, &jobs[k], mine, first_vertex + vertex_starts[k] as u32, out);
        });
        for &p in &self.positions {
            map.add_vertex(p);
        }
        for (&d, r) in self.new.iter().zip(&self.darts) {
            map.store_dart(d, r.betas, r.vertex, r.label);
        }
        for s in &self.stores {
            map.set_beta_raw(s.at, usize::from(s.slot), s.to);
        }
        &self.new
    }
}

/// `v` holding `n` default values, keeping its allocation.
fn refill<T: Default + Clone>(v: &mut Vec<T>, n: usize) {
    v.clear();
    v.resize(n, T::default());
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
    /// Stores into darts of the map: the link ends that are matched darts (a link
    /// between two new darts stays among the new darts' records).
    stores: usize,
    /// Whether the target gives a volume a label of its own.
    labels: bool,
}

impl Sizes {
    fn of(plan: &Plan) -> Sizes {
        let matched = |l: &Link| matches!(l, Link::Matched(_));
        let to_matched = plan.new_darts.iter().flat_map(|n| n.links).filter(matched).count();
        let relinked = plan.relink.iter().map(|(_, _, l)| 1 + usize::from(matched(l))).sum::<usize>();
        Sizes {
            vertices: plan.created.len(),
            darts: plan.new_darts.len(),
            stores: to_matched + relinked,
            labels: plan.new_darts.iter().any(|n| n.label != 0),
        }
    }
}

/// Resolves `job`, whose new darts are `new` and first created vertex `first_vertex`:
/// the stores of [`execute`](fn@super::execute)'s links, in its order, into the new
/// darts' records or into `out.stores`.
fn resolve(map: &CMap3, job: &Job, new: &[Dart], first_vertex: u32, out: Resolved) {
    let plan = job.plan;
    let at = |l: u32| job.matched[l as usize - 1];
    for (w, p) in plan.created.iter().zip(out.positions.iter_mut()) {
        for &(l, x) in w {
            let q = map.point(at(l));
            (0..3).for_each(|k| p[k] += x * q[k]);
        }
    }
    for (n, d) in plan.new_darts.iter().zip(out.darts.iter_mut()) {
        d.vertex = match n.vertex {
            VertexOf::Matched(l) => map.vertex_of(at(l)),
            VertexOf::Created(i) => first_vertex + i,
        };
        d.label = if n.label != 0 { n.label } else { map.label_of(at(n.label_from)) };
    }
    let end = |l: Link| match l {
        Link::Free => None,
        Link::New(i) => Some(End::New(i)),
        Link::Matched(k) => Some(End::Old(at(k))),
    };
    let raw = |e: End| match e {
        End::New(i) => new[i as usize].raw(),
        End::Old(d) => d.raw(),
    };
    let (darts, stores) = (out.darts, out.stores);
    let mut next_store = 0;
    let mut store = |e: End, slot: usize, to: u32| match e {
        End::New(i) => darts[i as usize].betas[slot] = to,
        End::Old(d) => {
            stores[next_store] = Store { at: d.raw(), slot: slot as u8, to };
            next_store += 1;
        }
    };
    let mut link = |a: End, i: usize, b: End| {
        store(a, i, raw(b));
        store(b, back_slot(i), raw(a));
    };
    for (j, n) in plan.new_darts.iter().enumerate() {
        for (i, &l) in n.links.iter().enumerate() {
            if let Some(o) = end(l) {
                link(End::New(j as u32), i + 1, o);
            }
        }
    }
    for &(k, i, l) in &plan.relink {
        link(End::Old(at(k)), i, end(l).expect("relinked darts are never left free"));
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
