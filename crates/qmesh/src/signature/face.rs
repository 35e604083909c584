//! f-signatures (2022 §4.2): the flagged gap sequence around a face or around the
//! boundary cycle of an f-pattern, normalised to its lexicographic minimum.

use super::{Flags, Signature};
use crate::cmap::{CMap3, Dart};

/// The signature of a cycle of darts given in order, with their flags.
pub fn cycle_signature(flagged: &[bool]) -> Signature {
    let k = flagged.len();
    let at: Vec<usize> = (0..k).filter(|&i| flagged[i]).collect();
    if at.is_empty() {
        return Signature::Face(vec![0, k as u32]);
    }
    let gaps: Vec<u32> = (0..at.len()).map(|j| ((at[(j + 1) % at.len()] + k - at[j] - 1) % k + 1) as u32).collect();
    let best = (0..gaps.len())
        .map(|r| gaps[r..].iter().chain(&gaps[..r]).copied().collect::<Vec<u32>>())
        .min()
        .expect("at least one flagged dart");
    Signature::Face(best)
}

/// How many rotations of a flagged cycle give its minimal gap sequence (the cycle's
/// automorphisms that preserve flags; all k rotations without flags).
pub fn cycle_automorphisms(flagged: &[bool]) -> usize {
    let k = flagged.len();
    (0..k).filter(|&r| (0..k).all(|i| flagged[(i + r) % k] == flagged[i])).count()
}

/// The f-signature of the input face of `d` (its β1 cycle).
pub fn face_signature(map: &CMap3, flags: Flags, d: Dart) -> Signature {
    let mut f = vec![flags.get(map, d)];
    let mut x = map.next(d);
    while x != d {
        f.push(flags.get(map, x));
        x = map.next(x);
    }
    cycle_signature(&f)
}

/// The boundary cycle of an f-pattern from a 2-free dart: the next boundary dart is
/// found by turning around the tip vertex with β1∘β2 (2022 §4.2.1). None when `start`
/// is not 2-free or the walk does not close.
pub fn pattern_face_boundary(map: &CMap3, start: Dart) -> Option<Vec<Dart>> {
    if !map.is_free(start, 2) {
        return None;
    }
    // (both walks are bounded by the number of darts: a broken map cannot hang them)
    let limit = map.nb_darts();
    let mut cycle = vec![start];
    for _ in 0..limit {
        let x = next_free_around_tip(map, *cycle.last().expect("never empty"), limit)?;
        if x == start {
            return Some(cycle);
        }
        cycle.push(x);
    }
    None
}

/// The first 2-free dart met turning around the tip of `d` with β1∘β2.
fn next_free_around_tip(map: &CMap3, d: Dart, limit: usize) -> Option<Dart> {
    let mut x = map.next(d);
    for _ in 0..limit {
        match map.beta(x, 2) {
            None => return Some(x),
            Some(o) => x = map.next(o),
        }
    }
    None
}

/// The f-signature of the boundary cycle of an f-pattern containing 2-free `start`.
pub fn pattern_face_signature(map: &CMap3, flags: Flags, start: Dart) -> Option<Signature> {
    let cycle = pattern_face_boundary(map, start)?;
    Some(cycle_signature(&cycle.iter().map(|&d| flags.get(map, d)).collect::<Vec<_>>()))
}

#[cfg(test)]
mod tests {
    use super::{Signature, cycle_signature};

    #[test]
    fn gaps_as_in_the_papers() {
        // A quad with its 4 edges split: flags every other dart → [2, 2, 2, 2].
        let f = [true, false, true, false, true, false, true, false];
        assert_eq!(cycle_signature(&f), Signature::Face(vec![2, 2, 2, 2]));
        // One split edge: [1, 1, 1, 2] (minimal rotation).
        let f = [true, true, false, true, true];
        assert_eq!(cycle_signature(&f), Signature::Face(vec![1, 1, 1, 2]));
        assert_eq!(cycle_signature(&[false; 6]), Signature::Face(vec![0, 6]));
    }
}
