//! Replacing a face by the interior of an f-pattern (2022 Algorithm 3, §5.1.1); a face
//! shared by two volumes gets the mirrored copy on its other side, 3-sewn to the first.

use rustc_hash::FxHashMap;

use super::vertices::place_vertices;
use crate::cmap::{CMap3, Dart};
use crate::pattern::Pattern;
use crate::signature::Flags;

fn half_face(map: &CMap3, d: Dart) -> Vec<Dart> {
    let mut v = vec![d];
    let mut x = map.next(d);
    while x != d {
        v.push(x);
        x = map.next(x);
    }
    v
}

/// The darts of the half-face of `d`, rotated so that dart i corresponds to the
/// pattern's boundary dart i with the same flag; None when no rotation fits.
pub fn align_face(map: &CMap3, flags: Flags, d: Dart, p: &Pattern) -> Option<Vec<Dart>> {
    let t = half_face(map, d);
    let k = t.len();
    if k != p.cycle.len() {
        return None;
    }
    let pf: Vec<bool> = p.cycle.iter().map(|&b| p.map.is_marked(b, p.flags)).collect();
    let tf: Vec<bool> = t.iter().map(|&x| flags.get(map, x)).collect();
    (0..k).find(|&s| (0..k).all(|i| pf[i] == tf[(s + i) % k])).map(|s| (0..k).map(|i| t[(s + i) % k]).collect())
}

/// Inserts the interior of f-pattern `p` into the half-face whose darts `aligned[i]`
/// correspond to the pattern's boundary darts `p.cycle[i]`. When that face is 3-sewn,
/// the opposite half-face receives the mirrored interior and both are 3-sewn.
/// Returns the number of darts added.
pub fn replace_face(map: &mut CMap3, p: &Pattern, aligned: &[Dart]) -> usize {
    let pm = &p.map;
    let boundary_of: FxHashMap<Dart, usize> = p.cycle.iter().enumerate().map(|(i, &b)| (b, i)).collect();
    let vb: FxHashMap<u32, u32> =
        p.cycle.iter().zip(aligned).map(|(&b, &t)| (pm.vertex_of(b), map.vertex_of(t))).collect();
    let vmap = place_vertices(map, p, vb);
    let interior: Vec<Dart> = pm.darts().filter(|&x| !pm.is_free(x, 2)).collect();
    let label = map.label_of(aligned[0]);
    let mut copy: FxHashMap<Dart, Dart> = FxHashMap::default();
    for &x in &interior {
        let c = map.create_dart(vmap[&pm.vertex_of(x)]);
        map.set_label_of(c, label);
        copy.insert(x, c);
    }
    let rep = |x: Dart| boundary_of.get(&x).map_or_else(|| copy[&x], |&i| aligned[i]);
    for x in pm.darts() {
        map.link(rep(x), 1, rep(pm.next(x)));
    }
    for &x in &interior {
        map.link(copy[&x], 2, copy[&pm.beta(x, 2).expect("interior darts are 2-sewn")]);
    }
    let mut added = interior.len();
    // The other side of a face between two volumes: the same interior, reversed.
    if let Some(other0) = map.beta(aligned[0], 3) {
        let mirrored: Vec<Dart> =
            aligned.iter().map(|&t| map.beta(t, 3).expect("a 3-sewn face is 3-sewn everywhere")).collect();
        let label = map.label_of(other0);
        let mut mirror: FxHashMap<Dart, Dart> = FxHashMap::default();
        for &x in &interior {
            let c = map.create_dart(vmap[&pm.vertex_of(pm.next(x))]);
            map.set_label_of(c, label);
            mirror.insert(x, c);
        }
        let mrep = |x: Dart| boundary_of.get(&x).map_or_else(|| mirror[&x], |&i| mirrored[i]);
        for x in pm.darts() {
            map.link(mrep(x), 1, mrep(pm.prev(x)));
        }
        for &x in &interior {
            map.link(mirror[&x], 2, mirror[&pm.beta(x, 2).expect("interior darts are 2-sewn")]);
            map.link(copy[&x], 3, mirror[&x]);
        }
        added *= 2;
    }
    added
}
