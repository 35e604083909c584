//! Replacing a face by the interior of an f-pattern (2022 Algorithm 3, §5.1.1); a face
//! shared by two volumes gets the mirrored copy on its other side, 3-sewn to the first
//! (through the modify layer's [`FacePattern`]: one rewiring code for both engines).

use crate::cmap::{CMap3, Dart};
use crate::modify::FacePattern;
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
/// Returns the number of darts added (0 if the pattern's geometry is unusable).
/// Replacing many faces: build the [`FacePattern`] once instead.
pub fn replace_face(map: &mut CMap3, p: &Pattern, aligned: &[Dart]) -> usize {
    FacePattern::new(p).map_or(0, |f| f.replace(map, aligned))
}
