//! The 2022 v-pattern replacement (2022 Algorithm 4, §5.1.2) as a [`Plan`]: the
//! pattern's boundary traversal gives the labels, its interior darts are the new
//! darts, its interior vertices the created ones. The 2022 engine finds the matching
//! volume by signature and hands its traversal to [`execute`](fn@super::execute), the
//! code that rewires darts for both engines.

use rustc_hash::FxHashMap;

use super::Job;
use super::plan::{Link, NewDart, Operation, Plan, VertexOf};
use crate::cmap::{CMap3, Dart, Orbit};
use crate::pattern::Pattern;
use crate::signature::{Flags, Surface, VolumeWord, word_from};

/// A v-pattern ready to replace volumes: its plan and its boundary word.
#[derive(Clone, Debug)]
pub struct VolumePattern {
    pub plan: Plan,
    word: Vec<u32>,
    /// For each volume of the pattern with interior darts, the index among the new
    /// darts of its first one: one dart per volume a replacement creates, without
    /// walking the result.
    pub volume_starts: Vec<u32>,
}

impl VolumePattern {
    /// The plan of v-pattern `p`, labelled by the traversal of its boundary from
    /// `p.start`; None when that boundary is not a closed surface.
    pub fn new(p: &Pattern) -> Option<VolumePattern> {
        let pm = &p.map;
        let pw = word_from(pm, Surface::PatternBoundary, Flags::Mark(p.flags), p.start, None)?;
        let label: FxHashMap<Dart, u32> = pw.darts.iter().enumerate().map(|(k, &d)| (d, k as u32 + 1)).collect();
        let interior: Vec<Dart> = pm.darts().filter(|&x| !pm.is_free(x, 3)).collect();
        let index: FxHashMap<Dart, u32> = interior.iter().enumerate().map(|(i, &d)| (d, i as u32)).collect();
        let link = |n: Option<Dart>| match n {
            None => Link::Free,
            Some(n) => index.get(&n).map_or_else(|| Link::Matched(label[&n]), |&i| Link::New(i)),
        };
        let preserved: FxHashMap<u32, u32> = pw.darts.iter().map(|&d| (pm.vertex_of(d), label[&d])).collect();
        let created: FxHashMap<u32, u32> =
            p.interior().iter().enumerate().map(|(i, iv)| (iv.vertex, i as u32)).collect();
        let weights: Option<Vec<Vec<(u32, f64)>>> = p
            .interior()
            .iter()
            .map(|iv| iv.weights.iter().map(|&(v, w)| preserved.get(&v).map(|&l| (l, w))).collect())
            .collect();
        let new_darts = interior
            .iter()
            .map(|&x| {
                let v = pm.vertex_of(x);
                let vertex = match preserved.get(&v) {
                    Some(&l) => VertexOf::Matched(l),
                    None => VertexOf::Created(*created.get(&v)?),
                };
                Some(NewDart { links: [1, 2, 3].map(|i| link(pm.beta(x, i))), vertex, label_from: 1, label: 0 })
            })
            .collect::<Option<Vec<_>>>()?;
        let plan =
            Plan { op: Operation::Replace, deleted: Vec::new(), new_darts, relink: Vec::new(), created: weights? };
        Some(VolumePattern { plan, word: pw.word, volume_starts: first_of_each_volume(pm, &interior) })
    }

    /// Inserts the pattern's interior into the volume of `target`, whose traversal
    /// from `target` must give the pattern boundary's word. Returns the darts added.
    pub fn replace(&self, map: &mut CMap3, target: Dart, flags: Flags) -> Option<Vec<Dart>> {
        self.replace_traversed(map, &word_from(map, Surface::Cell, flags, target, None)?)
    }

    /// [`replace`](Self::replace) given the traversal of the volume from the target
    /// dart (computed beforehand, on any thread).
    pub fn replace_traversed(&self, map: &mut CMap3, traversal: &VolumeWord) -> Option<Vec<Dart>> {
        (traversal.word == self.word).then(|| super::execute(map, &self.plan, &traversal.darts).1)
    }

    /// The replacement of [`replace_traversed`](Self::replace_traversed) as a [`Job`],
    /// for [`DisjointExecutor`](super::DisjointExecutor); None when the words differ.
    pub fn job(&self, traversal: VolumeWord) -> Option<Job<'_>> {
        (traversal.word == self.word).then_some(Job { plan: &self.plan, matched: traversal.darts })
    }

    /// [`job`](Self::job) on a traversal kept elsewhere (its darts are copied).
    pub fn job_following(&self, traversal: &VolumeWord) -> Option<Job<'_>> {
        (traversal.word == self.word).then(|| Job { plan: &self.plan, matched: traversal.darts.clone() })
    }
}

/// The positions in `darts` of the first dart of each volume of `map` they meet.
fn first_of_each_volume(map: &CMap3, darts: &[Dart]) -> Vec<u32> {
    let mut seen = rustc_hash::FxHashSet::default();
    let mut firsts = Vec::new();
    for (k, &d) in darts.iter().enumerate() {
        if !seen.contains(&d) {
            seen.extend(map.orbit(d, Orbit::Volume));
            firsts.push(k as u32);
        }
    }
    firsts
}
