//! The 2022 f-pattern replacement (2022 Algorithm 3, §5.1.1) as [`Plan`]s: the face's
//! darts (aligned with the pattern's boundary cycle) are labels 1..=k and, for a face
//! between two volumes, the darts across it are labels k+1..=2k; the pattern's
//! interior is inserted on one side, mirrored on the other, and the two 3-sewn.

use rustc_hash::FxHashMap;

use super::Job;
use super::plan::{Link, NewDart, Operation, Plan, VertexOf};
use crate::cmap::{CMap3, Dart};
use crate::pattern::Pattern;

/// An f-pattern ready to replace faces: for a face on the boundary and for a face
/// between two volumes.
#[derive(Clone, Debug)]
pub struct FacePattern {
    one_side: Plan,
    two_sides: Plan,
    k: usize,
}

impl FacePattern {
    /// The plans of f-pattern `p`; None when a pattern vertex can be placed from
    /// neither its boundary nor its mean value coordinates.
    pub fn new(p: &Pattern) -> Option<FacePattern> {
        let pm = &p.map;
        let k = p.cycle.len();
        let boundary: FxHashMap<Dart, u32> = p.cycle.iter().enumerate().map(|(i, &b)| (b, i as u32 + 1)).collect();
        let interior: Vec<Dart> = pm.darts().filter(|&x| !pm.is_free(x, 2)).collect();
        let index: FxHashMap<Dart, u32> = interior.iter().enumerate().map(|(i, &d)| (d, i as u32)).collect();
        let preserved: FxHashMap<u32, u32> = p.cycle.iter().map(|&b| (pm.vertex_of(b), boundary[&b])).collect();
        let created: FxHashMap<u32, u32> =
            p.interior().iter().enumerate().map(|(i, iv)| (iv.vertex, i as u32)).collect();
        let weights: Vec<Vec<(u32, f64)>> = p
            .interior()
            .iter()
            .map(|iv| iv.weights.iter().map(|&(v, w)| preserved.get(&v).map(|&l| (l, w))).collect())
            .collect::<Option<_>>()?;
        let vertex = |v: u32| match preserved.get(&v) {
            Some(&l) => Some(VertexOf::Matched(l)),
            None => created.get(&v).map(|&i| VertexOf::Created(i)),
        };
        // Side one: copies of the interior darts; the face's darts get new β1.
        let rep = |x: Dart| boundary.get(&x).map_or_else(|| Link::New(index[&x]), |&l| Link::Matched(l));
        let mut new_darts = Vec::with_capacity(2 * interior.len());
        for &x in &interior {
            let b2 = pm.beta(x, 2).expect("interior darts are 2-sewn");
            let links = [rep(pm.next(x)), Link::New(index[&b2]), Link::Free];
            new_darts.push(NewDart { links, vertex: vertex(pm.vertex_of(x))?, label_from: 1, label: 0 });
        }
        let relink: Vec<(u32, usize, Link)> = p.cycle.iter().map(|&b| (boundary[&b], 1, rep(pm.next(b)))).collect();
        let one_side = Plan {
            op: Operation::Replace,
            deleted: Vec::new(),
            new_darts: new_darts.clone(),
            relink: relink.clone(),
            created: weights.clone(),
        };
        // Side two: the same interior reversed, each mirror dart 3-sewn to its copy.
        let n = interior.len() as u32;
        let mrep =
            |x: Dart| boundary.get(&x).map_or_else(|| Link::New(n + index[&x]), |&l| Link::Matched(l + k as u32));
        for (i, &x) in interior.iter().enumerate() {
            let b2 = pm.beta(x, 2).expect("interior darts are 2-sewn");
            let links = [mrep(pm.prev(x)), Link::New(n + index[&b2]), Link::New(i as u32)];
            new_darts.push(NewDart {
                links,
                vertex: vertex(pm.vertex_of(pm.next(x)))?,
                label_from: k as u32 + 1,
                label: 0,
            });
        }
        let mut relink = relink;
        relink.extend(p.cycle.iter().map(|&b| (boundary[&b] + k as u32, 1, mrep(pm.prev(b)))));
        let two_sides = Plan { op: Operation::Replace, deleted: Vec::new(), new_darts, relink, created: weights };
        Some(FacePattern { one_side, two_sides, k })
    }

    /// Inserts the pattern's interior into the half-face whose darts `aligned[i]`
    /// correspond to the pattern's boundary darts `p.cycle[i]`, and its mirror into the
    /// half-face across when the face is 3-sewn. Returns the number of darts added.
    pub fn replace(&self, map: &mut CMap3, aligned: &[Dart]) -> usize {
        let job = self.job(map, aligned.to_vec());
        super::execute(map, job.plan, &job.matched).0.darts_added
    }

    /// The replacement of [`replace`](Self::replace) as a [`Job`], for
    /// [`DisjointExecutor`](super::DisjointExecutor).
    pub fn job(&self, map: &CMap3, aligned: Vec<Dart>) -> Job<'_> {
        self.job_on(Self::both_sides(map, aligned))
    }

    /// The darts a replacement of the half-face `aligned` matches: `aligned`, then the
    /// darts across (β3) when the face is 3-sewn. Reads the map only (for any thread).
    pub fn both_sides(map: &CMap3, aligned: Vec<Dart>) -> Vec<Dart> {
        if map.is_free(aligned[0], 3) {
            return aligned;
        }
        let k = aligned.len();
        let mut both = aligned;
        both.extend_from_within(..);
        for t in &mut both[k..] {
            *t = map.beta(*t, 3).expect("a 3-sewn face is 3-sewn everywhere");
        }
        both
    }

    /// The job of [`job`](Self::job) on what [`both_sides`](Self::both_sides) gave.
    pub fn job_on(&self, matched: Vec<Dart>) -> Job<'_> {
        debug_assert!(matched.len() == self.k || matched.len() == 2 * self.k);
        let plan = if matched.len() == self.k { &self.one_side } else { &self.two_sides };
        Job { plan, matched }
    }
}
