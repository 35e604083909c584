//! Volume lookups remembered per thread, keyed by the word of one traversal from the
//! volume's own dart (2022 Algorithm 2, flag bits appended). Two volumes with the same
//! word from their darts are isomorphic, flags included, by the label order (the word
//! fixes every β1 and opposite link between labels): the pattern they match is the same,
//! and so is the position, in that order, of the start the lookup returns. A lookup then
//! costs one traversal instead of one per start dart, for as many volumes as share a
//! configuration (every cube of one marching-cubes case, every cell of one octree
//! transition).
//!
//! Face lookups are remembered the same way, keyed by the flags around the half-face
//! from its dart: they fix the signature and the rotation that aligns the face with its
//! pattern.

use std::cell::RefCell;

use rustc_hash::FxHashMap;

use crate::cmap::{CMap3, Dart};
use crate::pattern::PatternSet;
use crate::signature::{Flags, Surface, VolumeWord, word_into};

/// Words remembered per thread, at most (the rest are looked up every time).
const CAPACITY: usize = 1 << 16;

/// A lookup's answer: the pattern and the label of its start (0-based), or no match.
pub(super) type Found = Option<(u32, u32)>;

/// A face lookup's answer: the pattern and the rotation aligning the half-face with its
/// boundary cycle, or no match.
pub(super) type FaceFound = Option<(u32, u32)>;

/// Lookups in one pattern set, by key.
struct Memo<K, V> {
    /// The [`PatternSet::version`] the keys were looked up in.
    version: u64,
    found: FxHashMap<K, V>,
}

impl<K: std::hash::Hash + Eq, V: Copy> Memo<K, V> {
    fn new() -> Self {
        Memo { version: 0, found: FxHashMap::default() }
    }

    fn get<Q: std::hash::Hash + Eq + ?Sized>(&self, set: &PatternSet, key: &Q) -> Option<V>
    where
        K: std::borrow::Borrow<Q>,
    {
        if self.version == set.version() { self.found.get(key).copied() } else { None }
    }

    fn put(&mut self, set: &PatternSet, key: K, found: V) {
        if self.version != set.version() {
            self.found.clear();
            self.version = set.version();
        }
        if self.found.len() < CAPACITY {
            self.found.insert(key, found);
        }
    }
}

thread_local! {
    /// Volume lookups by word.
    static MEMO: RefCell<Memo<Box<[u32]>, Found>> = RefCell::new(Memo::new());
    /// Face lookups by (darts, flag bits) around the half-face.
    static FACE_MEMO: RefCell<Memo<(u32, u64), FaceFound>> = RefCell::new(Memo::new());
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
    MEMO.with(|m| m.borrow().get(set, word))
}

/// Remembers what a lookup of `word` in `set` gave.
pub(super) fn remember(set: &PatternSet, word: &[u32], found: Found) {
    MEMO.with(|m| m.borrow_mut().put(set, word.into(), found));
}

/// The face lookup of `key` (darts around the half-face, flag bits from its dart) in
/// `set` on this thread: remembered, or `look_up()` remembered.
pub(super) fn face(set: &PatternSet, key: (u32, u64), look_up: impl FnOnce() -> FaceFound) -> FaceFound {
    if let Some(found) = FACE_MEMO.with(|m| m.borrow().get(set, &key)) {
        return found;
    }
    let found = look_up();
    FACE_MEMO.with(|m| m.borrow_mut().put(set, key, found));
    found
}
