//! The closed surface whose darts a v-signature labels: the 3-free darts of a pattern
//! (opposite = β2∘β3… to the next 3-free dart, 2022 Algorithm 2) or the darts of one
//! input volume (opposite = β2).

use crate::cmap::{CMap3, Dart};

/// How to read a closed surface out of a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surface {
    /// The boundary of a v-pattern: its 3-free darts.
    PatternBoundary,
    /// One volume of an input mesh.
    Cell,
}

impl Surface {
    /// The dart across the edge of `d` on the same surface.
    #[inline]
    pub fn opposite(self, map: &CMap3, d: Dart) -> Option<Dart> {
        let mut x = map.beta(d, 2)?;
        if self == Surface::PatternBoundary {
            // Step over inner faces until the next boundary (3-free) dart.
            let mut guard = 0usize;
            while let Some(y) = map.beta(x, 3) {
                x = map.beta(y, 2)?;
                guard += 1;
                if guard > map.nb_darts() {
                    return None;
                }
            }
        }
        Some(x)
    }
}
