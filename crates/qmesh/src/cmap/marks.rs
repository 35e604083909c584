//! Per-dart marks with a reserve/free API (like CGAL's `get_new_mark`/`free_mark`).
//! The papers' *flags* (2022 §4.2.2) are one reserved mark. The mark table is
//! allocated when a mark is first reserved or set; until then every bit reads clear.

use super::dart::Dart;
use super::error::MapError;
use super::storage::CMap3;

/// A reserved mark: one bit per dart, obtained with [`CMap3::reserve_mark`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mark(u8);

impl Mark {
    #[inline]
    fn bit(self) -> u32 {
        1 << self.0
    }

    /// Which of the 32 marks this is (to store it; see [`CMap3::reserved_mark`]).
    pub fn index(self) -> u8 {
        self.0
    }
}

impl CMap3 {
    /// Reserves a mark, initially clear on every dart.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, (i * i * i) as f64])).collect();
    /// let d = m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    /// let flag = m.reserve_mark().unwrap();
    /// m.mark(d, flag);
    /// assert!(m.is_marked(d, flag) && !m.is_marked(m.next(d), flag));
    /// m.free_mark(flag);
    /// ```
    ///
    /// # Errors
    /// [`MapError::NoMarkLeft`] when all 32 marks are in use.
    pub fn reserve_mark(&mut self) -> Result<Mark, MapError> {
        let free = (!self.used_marks).trailing_zeros();
        if free >= 32 {
            return Err(MapError::NoMarkLeft);
        }
        self.used_marks |= 1 << free;
        let m = Mark(free as u8);
        self.clear_mark(m);
        Ok(m)
    }

    /// Mark number `index` if this map has it reserved (a mark read back from a file).
    pub fn reserved_mark(&self, index: u8) -> Option<Mark> {
        (index < 32 && self.used_marks & (1 << index) != 0).then_some(Mark(index))
    }

    /// Releases a mark (its bits are cleared on the next reservation).
    pub fn free_mark(&mut self, m: Mark) {
        self.used_marks &= !m.bit();
    }

    #[inline]
    pub fn is_marked(&self, d: Dart, m: Mark) -> bool {
        self.mark_bits(d) & m.bit() != 0
    }

    #[inline]
    pub fn mark(&mut self, d: Dart, m: Mark) {
        self.mark_table()[d.idx()] |= m.bit();
    }

    #[inline]
    pub fn unmark(&mut self, d: Dart, m: Mark) {
        if let Some(w) = self.marks.get_mut(d.idx()) {
            *w &= !m.bit();
        }
    }

    /// Clears mark `m` on every dart (on all cores: the table is as long as the map).
    pub fn clear_mark(&mut self, m: Mark) {
        use rayon::prelude::*;
        let keep = !m.bit();
        self.mark_table().par_iter_mut().with_min_len(1 << 16).for_each(|w| *w &= keep);
    }

    /// All mark bits of d (bit k = mark k).
    #[inline]
    pub fn mark_bits(&self, d: Dart) -> u32 {
        self.marks.get(d.idx()).copied().unwrap_or(0)
    }

    /// Replaces all mark bits of d.
    #[inline]
    pub fn set_mark_bits(&mut self, d: Dart, bits: u32) {
        if bits != 0 || !self.marks.is_empty() {
            self.mark_table()[d.idx()] = bits;
        }
    }

    /// The mark table, allocated (all clear) on first use.
    #[inline]
    fn mark_table(&mut self) -> &mut Vec<u32> {
        if self.marks.is_empty() {
            self.marks = vec![0; self.betas.len()];
            super::page_backing::advise_huge_pages(&self.marks);
        }
        &mut self.marks
    }
}
