//! Volume lookups remembered per thread, keyed by the word of one traversal from the
//! volume's own dart (2022 Algorithm 2, flag bits appended). Two volumes with the same
//! word from their darts are isomorphic, flags included, by the label order (the word
//! fixes every β1 and opposite link between labels): the pattern they match is the same,
//! and so is the position, in that order, of the start the lookup returns. A lookup then
//! costs one traversal instead of one per start dart, for as many volumes as share a
//! configuration (every cube of one marching-cubes case, every cell of one octree
//! transition).

use std::cell::RefCell;

use rustc_hash::FxHashMap;

use crate::cmap::{CMap3, Dart};
use crate::pattern::PatternSet;
use crate::signature::{Flags, Surface, VolumeWord, word_into};

/// Words remembered per thread, at most (the rest are looked up every time).
const CAPACITY: usize = 1 << 16;

/// A lookup's answer: the pattern and the label of its start (0-based), or no match.
pub(super) type Found = Option<(u32, u32)>;

#[derive(Default)]
struct Memo {
    /// The [`PatternSet::version`] the words were looked up in.
    version: u64,
    found: FxHashMap<Box<[u32]>, Found>,
}

thread_local! {
    static MEMO: RefCell<Memo> = RefCell::new(Memo::default());
    /// The last traversal and its word (labels, then flag bits), reused.
    static WORD: RefCell<(VolumeWord, Vec<u32>)> = RefCell::new(Default::default());
}

/// Runs `f` with the traversal of the volume from `d` (its darts in label order) and
/// its word (labels, then flag bits), both in this thread's buffers; None when the
/// volume is not closed. `f` must not call it again.
pub(super) fn with_word<R>(map: &CMap3, flags: Flags, d: Dart, f: impl FnOnce(&VolumeWord, &[u32]) -> R) -> Option<R> {
    WORD.with(|buffers| {
        let (w, word) = &mut *buffers.borrow_mut();
        if !word_into(map, Surface::Cell, flags, d, w) {
            return None;
        }
        word.clear();
        word.extend_from_slice(&w.word);
        word.extend_from_slice(&w.bits);
        Some(f(w, word))
    })
}

/// What a lookup of `word` in `set` gave on this thread, if it was remembered.
pub(super) fn recall(set: &PatternSet, word: &[u32]) -> Option<Found> {
    MEMO.with(|m| {
        let m = m.borrow();
        if m.version == set.version() { m.found.get(word).copied() } else { None }
    })
}

/// Remembers what a lookup of `word` in `set` gave.
pub(super) fn remember(set: &PatternSet, word: &[u32], found: Found) {
    MEMO.with(|m| {
        let mut m = m.borrow_mut();
        if m.version != set.version() {
            m.found.clear();
            m.version = set.version();
        }
        if m.found.len() < CAPACITY {
            m.found.insert(word.into(), found);
        }
    });
}
