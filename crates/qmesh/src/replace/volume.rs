//! Replacing a volume by the interior of a v-pattern (2022 Algorithm 4, §5.1.2).

use rustc_hash::FxHashMap;

use super::vertices::place_vertices;
use crate::cmap::{CMap3, Dart};
use crate::pattern::Pattern;
use crate::signature::{Flags, Surface, word_from};

/// Inserts the interior of v-pattern `p` into the volume of `target`, whose traversal
/// from `target` corresponds dart by dart to the pattern boundary's traversal from
/// `p.start` (the canonical starts of equal signatures, or a direct-test match).
/// Returns the darts added (the pattern's interior), or None if the traversals do not
/// correspond.
pub fn replace_volume(map: &mut CMap3, p: &Pattern, target: Dart, flags: Flags) -> Option<Vec<Dart>> {
    let pm = &p.map;
    let pw = word_from(pm, Surface::PatternBoundary, Flags::Mark(p.flags), p.start, None)?;
    let tw = word_from(map, Surface::Cell, flags, target, None)?;
    if pw.word != tw.word {
        return None;
    }
    let f: FxHashMap<Dart, Dart> = pw.darts.iter().copied().zip(tw.darts.iter().copied()).collect();
    let vb: FxHashMap<u32, u32> = f.iter().map(|(&b, &t)| (pm.vertex_of(b), map.vertex_of(t))).collect();
    let vmap = place_vertices(map, p, vb);
    let interior: Vec<Dart> = pm.darts().filter(|&x| !pm.is_free(x, 3)).collect();
    let label = map.label_of(target);
    let mut copy: FxHashMap<Dart, Dart> = FxHashMap::default();
    for &x in &interior {
        let c = map.create_dart(vmap[&pm.vertex_of(x)]);
        map.set_label_of(c, label);
        copy.insert(x, c);
    }
    let rep = |x: Dart| copy.get(&x).copied().unwrap_or_else(|| f[&x]);
    for &x in &interior {
        let c = copy[&x];
        map.link(c, 1, copy[&pm.next(x)]);
        map.link(c, 2, rep(pm.beta(x, 2).expect("volumes are closed")));
        map.link(c, 3, copy[&pm.beta(x, 3).expect("interior darts are 3-sewn")]);
    }
    Some(interior.iter().map(|x| copy[x]).collect())
}
