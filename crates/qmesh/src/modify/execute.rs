//! Executing a [`Plan`] on one match: the only code of the 2025 engine that rewires
//! darts (2025 Algorithms 2–4). Deleted darts are unsewn from what stays, new darts
//! are created on preserved or created vertices (mean value coordinates of the match's
//! positions, §6.5) and linked as in the target.

use super::plan::{Link, Plan, VertexOf};
use crate::cmap::{CMap3, Dart};

/// What one execution did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Executed {
    pub darts_added: usize,
    pub darts_removed: usize,
    pub vertices_created: usize,
}

/// Executes `plan` on the match `matched` (query label k at `matched[k - 1]`). New
/// darts take the volume label of the matched dart their plan names. Returns one new dart per
/// created dart range (empty for delete).
pub fn execute(map: &mut CMap3, plan: &Plan, matched: &[Dart]) -> (Executed, Vec<Dart>) {
    let at = |l: u32| matched[l as usize - 1];
    // Created vertices first: their weights read the match's positions.
    let created: Vec<u32> = plan
        .created
        .iter()
        .map(|w| {
            let mut p = [0.0; 3];
            for &(l, x) in w {
                let q = map.point(at(l));
                (0..3).for_each(|k| p[k] += x * q[k]);
            }
            map.add_vertex(p)
        })
        .collect();
    // Remove: unsew from what stays, then delete.
    let mut gone: Vec<Dart> = plan.deleted.iter().map(|&l| at(l)).collect();
    gone.sort_unstable();
    let mut touched = Vec::new();
    for &x in &gone {
        if let Some(o) = map.beta(x, 3)
            && gone.binary_search(&o).is_err()
        {
            map.unlink(x, 3);
            touched.push(o);
        }
    }
    for &x in &gone {
        map.delete_dart(x);
    }
    // Add: create, then link as in the target.
    if plan.new_darts.iter().any(|n| n.label != 0) {
        map.enable_labels();
    }
    let new: Vec<Dart> = plan
        .new_darts
        .iter()
        .map(|n| {
            let v = match n.vertex {
                VertexOf::Matched(l) => map.vertex_of(at(l)),
                VertexOf::Created(i) => created[i as usize],
            };
            let d = map.create_dart(v);
            let label = if n.label != 0 { n.label } else { map.label_of(at(n.label_from)) };
            map.set_label_of(d, label);
            d
        })
        .collect();
    let resolve = |l: Link| match l {
        Link::Free => None,
        Link::New(i) => Some(new[i as usize]),
        Link::Matched(k) => Some(at(k)),
    };
    for (n, &d) in plan.new_darts.iter().zip(&new) {
        for (i, &l) in n.links.iter().enumerate() {
            if let Some(o) = resolve(l) {
                map.link(d, i + 1, o);
            }
        }
    }
    for &(k, i, l) in &plan.relink {
        let o = resolve(l).expect("relinked darts are never left free");
        map.link(at(k), i, o);
    }
    if !touched.is_empty() {
        // Vertices joined only through removed volumes come apart.
        map.split_vertex_ids(&touched);
    }
    let done = Executed { darts_added: new.len(), darts_removed: gone.len(), vertices_created: created.len() };
    (done, new)
}
