//! The labels of one traversal (2022 Algorithm 2): dart → label, 0 for a dart not yet
//! labelled. A traversal labels a few dozen to a few thousand darts scattered over the
//! map, so a small open-addressing table that stays in cache serves it better than a
//! table as long as the map (one cache miss per dart read, and as many pages per
//! thread as the map has darts).

use crate::cmap::Dart;

/// Slots of a fresh table: a subdivided hexahedron's 96 darts fit without growing.
const MIN_SLOTS: usize = 256;

/// Labels of the darts of one traversal; cleared between traversals.
#[derive(Debug)]
pub(super) struct Labels {
    /// (raw dart, label) slots; raw dart 0 (ε) marks an empty slot.
    slots: Vec<(u32, u32)>,
    len: usize,
}

impl Default for Labels {
    fn default() -> Self {
        Labels { slots: vec![(0, 0); MIN_SLOTS], len: 0 }
    }
}

impl Labels {
    /// The label of `d`, 0 when it has none.
    #[inline]
    pub fn get(&self, d: Dart) -> u32 {
        let mask = self.slots.len() - 1;
        let mut i = slot_of(d.raw(), mask);
        loop {
            match self.slots[i] {
                (0, _) => return 0,
                (k, l) if k == d.raw() => return l,
                _ => i = (i + 1) & mask,
            }
        }
    }

    /// Gives `d` (unlabelled) the label `l`.
    #[inline]
    pub fn set(&mut self, d: Dart, l: u32) {
        if 2 * (self.len + 1) > self.slots.len() {
            self.grow();
        }
        let mask = self.slots.len() - 1;
        let mut i = slot_of(d.raw(), mask);
        while self.slots[i].0 != 0 && self.slots[i].0 != d.raw() {
            i = (i + 1) & mask;
        }
        self.len += usize::from(self.slots[i].0 == 0);
        self.slots[i] = (d.raw(), l);
    }

    /// Forgets every label (and a table grown for a much larger traversal).
    pub fn clear(&mut self) {
        if self.len == 0 {
            return;
        }
        let fit = (4 * self.len).next_power_of_two().max(MIN_SLOTS);
        if self.slots.len() > 4 * fit {
            self.slots = vec![(0, 0); fit];
        } else {
            self.slots.fill((0, 0));
        }
        self.len = 0;
    }

    fn grow(&mut self) {
        let bigger = vec![(0, 0); 2 * self.slots.len()];
        let old = std::mem::replace(&mut self.slots, bigger);
        self.len = 0;
        for (k, l) in old.into_iter().filter(|s| s.0 != 0) {
            self.set(Dart::from_raw(k).expect("slots hold no ε"), l);
        }
    }
}

/// Fibonacci hashing of a raw dart onto `mask + 1` slots (a power of two).
#[inline]
fn slot_of(raw: u32, mask: usize) -> usize {
    (raw.wrapping_mul(0x9E37_79B9) as usize >> 8) & mask
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_kept_through_growth_and_forgotten_on_clear() {
        let mut t = Labels::default();
        let darts: Vec<Dart> = (1..5000u32).map(|i| Dart::from_raw(i * 7919 % 100_003 + 1).unwrap()).collect();
        for (i, &d) in darts.iter().enumerate() {
            assert_eq!(t.get(d), 0);
            t.set(d, i as u32 + 1);
        }
        assert!(darts.iter().enumerate().all(|(i, &d)| t.get(d) == i as u32 + 1));
        assert_eq!(t.len, darts.len());
        t.clear();
        assert!(darts.iter().all(|&d| t.get(d) == 0));
        t.set(darts[3], 9);
        assert_eq!((t.get(darts[3]), t.get(darts[4]), t.len), (9, 0, 1));
    }
}
