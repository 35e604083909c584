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

    /// The set indices in `from..to` (both multiples of 64), in increasing order, as
    /// offsets from `from`.
    pub(crate) fn ones_in(&self, from: usize, to: usize) -> impl Iterator<Item = usize> + '_ {
        debug_assert!(from.is_multiple_of(64) && to.is_multiple_of(64), "whole words only");
        let n = self.words.len();
        self.words[(from / 64).min(n)..(to / 64).min(n)].iter().enumerate().flat_map(|(j, &bits)| {
            let mut rest = bits;
            std::iter::from_fn(move || {
                (rest != 0).then(|| {
                    let b = rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    j * 64 + b
                })
            })
        })
    }

    /// Clears every bit.
    pub fn clear(&mut self) {
        self.words.iter_mut().for_each(|w| *w = 0);
    }
}
