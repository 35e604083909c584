//! Darts: the elements of a combinatorial map (2022 §2.2).

use std::fmt;
use std::num::NonZeroU32;

/// A dart of a [`CMap3`](super::CMap3).
///
/// Internally a dart is an index into the map's arrays; index 0 is reserved for the
/// null dart ε, so a free β is `None` and `Option<Dart>` still fits in four bytes.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Dart(NonZeroU32);

impl Dart {
    /// The dart with raw index `i`, or `None` for the null index 0.
    #[inline]
    pub fn from_raw(i: u32) -> Option<Dart> {
        NonZeroU32::new(i).map(Dart)
    }

    /// The raw index of this dart (never 0).
    #[inline]
    pub fn raw(self) -> u32 {
        self.0.get()
    }

    /// The raw index as a `usize`, for indexing arrays.
    #[inline]
    pub fn idx(self) -> usize {
        self.0.get() as usize
    }
}

/// Raw index of an optional dart: 0 for ε.
#[inline]
pub fn raw_of(d: Option<Dart>) -> u32 {
    d.map_or(0, Dart::raw)
}

impl fmt::Debug for Dart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "d{}", self.0)
    }
}

impl fmt::Display for Dart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}
