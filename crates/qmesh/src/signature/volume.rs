//! v-signatures: words of a labelled breadth-first traversal of a closed surface
//! (2022 Algorithm 2 and Definition 6), minimised over start darts, flag bits appended.

use std::cell::RefCell;

use super::labels::Labels;
use super::{Flags, Signature, Surface};
use crate::cmap::{CMap3, Dart};

/// The word of one traversal: for each dart in label order, the labels of its β1 and
/// opposite neighbours; then one flag bit per dart (0/1).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VolumeWord {
    pub word: Vec<u32>,
    pub bits: Vec<u32>,
    /// Darts in label order (d_1, d_2, …).
    pub darts: Vec<Dart>,
}

/// Labels the surface from `start` (Algorithm 2) and returns its word, or None when the
/// surface is open (a missing opposite) — not a closed boundary. If `bound` is given,
/// stops early (returning None) as soon as the word exceeds it.
pub fn word_from(
    map: &CMap3,
    surface: Surface,
    flags: Flags,
    start: Dart,
    bound: Option<&[u32]>,
) -> Option<VolumeWord> {
    let mut out = VolumeWord::default();
    with_labels(|labels| word_with(map, surface, flags, start, bound, labels, &mut out))?;
    Some(out)
}

thread_local! {
    /// The labels of one traversal, one table per thread, cleared after every traversal.
    static LABELS: RefCell<Labels> = RefCell::new(Labels::default());
}

/// Runs `f` with this thread's label table.
fn with_labels<R>(f: impl FnOnce(&mut Labels) -> R) -> R {
    LABELS.with(|l| f(&mut l.borrow_mut()))
}

/// [`word_from`] into `out`'s buffers (cleared first): whether the surface is closed.
/// For loops over many volumes, which keep one `out`.
pub fn word_into(map: &CMap3, surface: Surface, flags: Flags, start: Dart, out: &mut VolumeWord) -> bool {
    with_labels(|label| word_with(map, surface, flags, start, None, label, out).is_some())
}

/// [`word_from`] into `out` (cleared first), on a label table that is all zeros on
/// entry and left so on exit.
fn word_with(
    map: &CMap3,
    surface: Surface,
    flags: Flags,
    start: Dart,
    bound: Option<&[u32]>,
    label: &mut Labels,
    out: &mut VolumeWord,
) -> Option<()> {
    out.word.clear();
    out.bits.clear();
    out.darts.clear();
    let result = label_traversal(map, surface, start, bound, label, out);
    label.clear();
    result?;
    out.bits.extend(out.darts.iter().map(|&d| flags.get(map, d) as u32));
    Some(())
}

/// The traversal proper: fills `out.darts` and `out.word`; None when the surface is
/// open or the word exceeds `bound`.
fn label_traversal(
    map: &CMap3,
    surface: Surface,
    start: Dart,
    bound: Option<&[u32]>,
    label: &mut Labels,
    out: &mut VolumeWord,
) -> Option<()> {
    label.set(start, 1);
    out.darts.push(start);
    let mut k = 0;
    let mut below = false; // the word is already strictly below the bound
    while k < out.darts.len() {
        let d = out.darts[k];
        k += 1;
        for n in [Some(map.next(d)), surface.opposite(map, d)] {
            let n = n?;
            let mut l = label.get(n);
            if l == 0 {
                out.darts.push(n);
                l = out.darts.len() as u32;
                label.set(n, l);
            }
            out.word.push(l);
            if let Some(b) = bound
                && !below
            {
                match b.get(out.word.len() - 1).map(|&x| l.cmp(&x)) {
                    Some(std::cmp::Ordering::Less) => below = true,
                    Some(std::cmp::Ordering::Greater) | None => return None,
                    Some(std::cmp::Ordering::Equal) => {}
                }
            }
        }
    }
    Some(())
}

/// The direct isomorphism test of 2022 §2.3 (no signature): the word of surface A from
/// `a_start` is compared with the words of surface B from each of its darts; returns the
/// dart of B matching `a_start`, if the surfaces are isomorphic (flags preserved).
pub fn match_direct(a: (&CMap3, Surface, Flags, Dart), b: (&CMap3, Surface, Flags, Dart)) -> Option<Dart> {
    let wa = word_from(a.0, a.1, a.2, a.3, None)?;
    let full_a: Vec<u32> = wa.word.iter().chain(&wa.bits).copied().collect();
    let starts = word_from(b.0, b.1, b.2, b.3, None)?.darts;
    if starts.len() != wa.darts.len() {
        return None;
    }
    starts
        .into_iter()
        .find(|&t| word_from(b.0, b.1, b.2, t, Some(&full_a)).is_some_and(|w| w.word == wa.word && w.bits == wa.bits))
}

/// The v-signature of the surface containing `any` (a pattern's boundary or an input
/// volume) and its automorphism count (start darts giving the minimal word), or None
/// when the surface is not closed. With flags, only flagged darts start traversals.
pub fn volume_signature(map: &CMap3, surface: Surface, flags: Flags, any: Dart) -> Option<(Signature, usize)> {
    volume_signature_from(map, surface, flags, any).map(|(s, n, _)| (s, n))
}

/// As [`volume_signature`], also returning the first start dart that gives the minimal
/// word: traversals of two isomorphic surfaces from their canonical starts list
/// corresponding darts in the same order.
pub fn volume_signature_from(
    map: &CMap3,
    surface: Surface,
    flags: Flags,
    any: Dart,
) -> Option<(Signature, usize, Dart)> {
    with_labels(|label| signature_with(map, surface, flags, any, label))
}

fn signature_with(
    map: &CMap3,
    surface: Surface,
    flags: Flags,
    any: Dart,
    label: &mut Labels,
) -> Option<(Signature, usize, Dart)> {
    let mut w = VolumeWord::default();
    word_with(map, surface, flags, any, None, label, &mut w)?;
    let flagged: Vec<Dart> = w.darts.iter().copied().filter(|&d| flags.get(map, d)).collect();
    let starts = if flagged.is_empty() { w.darts.clone() } else { flagged };
    let mut best: Option<(Vec<u32>, Dart)> = None;
    let mut count = 0;
    for &s in &starts {
        let bound = best.as_ref().map(|b| b.0.as_slice());
        if word_with(map, surface, flags, s, bound, label, &mut w).is_none() {
            continue;
        }
        let full = w.word.iter().chain(&w.bits);
        match best.as_ref().map(|b| full.clone().cmp(&b.0)) {
            None | Some(std::cmp::Ordering::Less) => {
                best = Some((full.copied().collect(), s));
                count = 1;
            }
            Some(std::cmp::Ordering::Equal) => count += 1,
            Some(std::cmp::Ordering::Greater) => {}
        }
    }
    best.map(|(b, s)| (Signature::Volume(b), count, s))
}

/// The number of darts and of flagged darts of the closed surface of `any` (None when
/// it is open): an invariant of its v-signature, read from it by [`signature_shape`].
pub fn volume_shape(map: &CMap3, surface: Surface, flags: Flags, any: Dart) -> Option<(usize, usize)> {
    with_labels(|label| {
        let mut all = VolumeWord::default();
        word_with(map, surface, flags, any, None, label, &mut all)?;
        Some((all.darts.len(), all.bits.iter().filter(|&&b| b == 1).count()))
    })
}

/// The [`volume_shape`] of every surface with v-signature `s` (a word of two labels
/// per dart, then one flag bit per dart).
pub fn signature_shape(s: &[u32]) -> (usize, usize) {
    let n = s.len() / 3;
    (n, s[2 * n..].iter().filter(|&&b| b == 1).count())
}

/// The start dart that [`volume_signature_from`] would return for the surface of `any`
/// if its v-signature is `expected`, and None when it is not: the starts are tried in
/// the same order, each traversal stopping at its first symbol that differs, and the
/// first to reproduce `expected` is the first to reach the minimal word. For a set
/// whose only candidate for this surface is one pattern, this replaces minimising over
/// every start (24 full traversals of a subdivided hexahedron) by about one.
pub fn start_with_signature(map: &CMap3, surface: Surface, flags: Flags, any: Dart, expected: &[u32]) -> Option<Dart> {
    with_labels(|label| {
        let mut all = VolumeWord::default();
        word_with(map, surface, flags, any, None, label, &mut all)?;
        let n = all.darts.len();
        if 3 * n != expected.len() || signature_shape(expected) != (n, all.bits.iter().filter(|&&b| b == 1).count()) {
            return None;
        }
        let flagged: Vec<Dart> = all.darts.iter().copied().filter(|&d| flags.get(map, d)).collect();
        let starts = if flagged.is_empty() { all.darts } else { flagged };
        starts.into_iter().find(|&s| {
            let mut out = VolumeWord::default();
            let same = exact_traversal(map, surface, s, &expected[..2 * n], label, &mut out);
            label.clear();
            same && out.darts.iter().zip(&expected[2 * n..]).all(|(&d, &b)| u32::from(flags.get(map, d)) == b)
        })
    })
}

/// [`label_traversal`] that stops at the first symbol differing from `expected`;
/// whether the whole word equals it.
fn exact_traversal(
    map: &CMap3,
    surface: Surface,
    start: Dart,
    expected: &[u32],
    label: &mut Labels,
    out: &mut VolumeWord,
) -> bool {
    label.set(start, 1);
    out.darts.push(start);
    let (mut k, mut at) = (0, 0);
    while k < out.darts.len() {
        let d = out.darts[k];
        k += 1;
        for n in [Some(map.next(d)), surface.opposite(map, d)] {
            let Some(n) = n else { return false };
            let mut l = label.get(n);
            if l == 0 {
                out.darts.push(n);
                l = out.darts.len() as u32;
                label.set(n, l);
            }
            if expected.get(at) != Some(&l) {
                return false;
            }
            at += 1;
        }
    }
    at == expected.len()
}
