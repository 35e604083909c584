//! A growable bit set indexed by raw dart indices, used for visit marks.

/// Fixed-width bit set; `clear_list` resets only the bits that were set.
#[derive(Clone, Debug, Default)]
pub struct BitSet {
    words: Vec<u64>,
}

impl BitSet {
    /// An empty set able to hold indices below `n` (it grows on demand).
    pub fn with_len(n: usize) -> Self {
        BitSet { words: vec![0; n.div_ceil(64)] }
    }

    /// Make room for indices below `n`.
    pub fn grow(&mut self, n: usize) {
        let w = n.div_ceil(64);
        if w > self.words.len() {
            self.words.resize(w, 0);
        }
    }

    #[inline]
    pub fn get(&self, i: usize) -> bool {
        self.words.get(i >> 6).is_some_and(|w| w & (1 << (i & 63)) != 0)
    }

    /// Sets bit `i`; returns whether it was clear before.
    #[inline]
    pub fn insert(&mut self, i: usize) -> bool {
        let w = &mut self.words[i >> 6];
        let bit = 1u64 << (i & 63);
        let was_clear = *w & bit == 0;
        *w |= bit;
        was_clear
    }

    #[inline]
    pub fn remove(&mut self, i: usize) {
        if let Some(w) = self.words.get_mut(i >> 6) {
            *w &= !(1u64 << (i & 63));
        }
    }

    /// The bits, 64 to a word (bit i is bit i % 64 of word i / 64).
    pub(crate) fn words(&self) -> &[u64] {
        &self.words
    }

    /// Clears every bit.
    pub fn clear(&mut self) {
        self.words.iter_mut().for_each(|w| *w = 0);
    }
}
