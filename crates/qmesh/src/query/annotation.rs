//! The annotation of Algorithm 1 (2025 §5.1): input dart → label, or ∅ for darts that
//! a `↔` condition reserved. A small open-addressing table sized for one query and
//! reused from one start dart to the next: clearing it is one generation increment,
//! and every insertion is logged so that the prefix-tree walk can undo back to any
//! earlier point (last in, first out).

/// The ∅ annotation (2025 §5.1.2 case (c)).
pub(crate) const RESERVED: u32 = 0;

#[derive(Clone, Debug, Default)]
pub(crate) struct Annotation {
    /// `generation << 32 | dart` of the entry in each slot; stale generations are empty.
    keys: Vec<u64>,
    values: Vec<u32>,
    generation: u64,
    shift: u32,
    /// Slots filled, in insertion order.
    log: Vec<u32>,
}

impl Annotation {
    /// A table for up to `n` entries (load factor ≤ 1/4).
    pub(crate) fn with_capacity(n: usize) -> Annotation {
        let slots = (4 * n.max(4)).next_power_of_two();
        Annotation {
            keys: vec![0; slots],
            values: vec![0; slots],
            generation: 1,
            shift: 32 - slots.trailing_zeros(),
            log: Vec::with_capacity(n),
        }
    }

    /// The entries it holds at load factor ≤ 1/4.
    pub(crate) fn capacity(&self) -> usize {
        self.keys.len() / 4
    }

    #[inline]
    fn slot(&self, d: u32) -> usize {
        (d.wrapping_mul(0x9E37_79B9) >> self.shift) as usize
    }

    #[inline]
    fn live(&self, s: usize) -> bool {
        self.keys[s] >> 32 == self.generation
    }

    /// The annotation of input dart `d` (raw, non-zero).
    #[inline]
    pub(crate) fn get(&self, d: u32) -> Option<u32> {
        let mask = self.keys.len() - 1;
        let want = self.generation << 32 | d as u64;
        let mut s = self.slot(d);
        loop {
            let k = self.keys[s];
            if k == want {
                return Some(self.values[s]);
            }
            if k >> 32 != self.generation {
                return None;
            }
            s = (s + 1) & mask;
        }
    }

    /// Annotates `d` with `value` unless it is annotated already; returns whether it
    /// was inserted.
    #[inline]
    pub(crate) fn insert_new(&mut self, d: u32, value: u32) -> bool {
        let mask = self.keys.len() - 1;
        let want = self.generation << 32 | d as u64;
        let mut s = self.slot(d);
        while self.live(s) {
            if self.keys[s] == want {
                return false;
            }
            s = (s + 1) & mask;
        }
        self.keys[s] = want;
        self.values[s] = value;
        self.log.push(s as u32);
        true
    }

    /// Number of insertions not undone.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.log.len()
    }

    /// Undoes the insertions after the first `len`. Removing the most recent key of a
    /// linear-probing table by emptying its slot is exact: no key inserted before it
    /// probed past that slot, which was empty when they were inserted.
    #[inline]
    pub(crate) fn undo_to(&mut self, len: usize) {
        while self.log.len() > len {
            let s = self.log.pop().expect("log is longer than len") as usize;
            self.keys[s] = 0;
        }
    }

    /// Removes every annotation.
    #[inline]
    pub(crate) fn clear(&mut self) {
        self.log.clear();
        self.generation += 1;
        if self.generation >> 31 != 0 {
            self.keys.iter_mut().for_each(|k| *k = 0);
            self.generation = 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn insert_get_and_undo_in_any_pattern() {
        let mut a = Annotation::with_capacity(50);
        let keys: Vec<u32> = (0..50).map(|i| 1 + i * 1024).collect(); // many collisions
        for (i, &k) in keys.iter().enumerate() {
            assert_eq!(a.get(k), None);
            assert!(a.insert_new(k, i as u32 + 1));
            assert!(!a.insert_new(k, 0));
        }
        for (i, &k) in keys.iter().enumerate() {
            assert_eq!(a.get(k), Some(i as u32 + 1));
        }
        a.undo_to(20);
        for (i, &k) in keys.iter().enumerate() {
            assert_eq!(a.get(k), (i < 20).then_some(i as u32 + 1), "key {k}");
        }
        a.clear();
        assert!(keys.iter().all(|&k| a.get(k).is_none()));
        assert!(a.insert_new(keys[3], 9));
        assert_eq!(a.get(keys[3]), Some(9));
    }

    /// After 2^31 clears the generations start again from 1, and no key stored under
    /// an old generation 1 comes back.
    #[test]
    fn generations_wrap_around_without_stale_keys() {
        let mut a = Annotation::with_capacity(8);
        assert!(a.insert_new(7, 3)); // stored under generation 1
        a.generation = (1 << 31) - 1;
        assert!(a.insert_new(9, 4));
        a.clear();
        assert_eq!(a.generation, 1);
        assert_eq!((a.get(7), a.get(9)), (None, None));
        assert!(a.insert_new(7, 5));
        assert_eq!(a.get(7), Some(5));
    }
}
