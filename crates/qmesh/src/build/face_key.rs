//! Canonical keys of vertex cycles, for matching faces shared by two cells.

use std::hash::Hash;

/// A vertex cycle rotated to start at its smallest vertex, keeping its direction.
/// Triangles and quads use a fixed array (no allocation); larger faces a `Vec`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum FaceKey {
    Small([u32; 4]),
    Large(Vec<u32>),
}

impl FaceKey {
    /// The key of `cycle` read forward (`reversed = false`) or backward.
    pub fn of(cycle: &[u32], reversed: bool) -> FaceKey {
        let n = cycle.len();
        let at = |k: usize| {
            if reversed { cycle[(n - k % n) % n] } else { cycle[k % n] }
        };
        let start = (0..n).min_by_key(|&k| at(k)).unwrap_or(0);
        if n <= 4 {
            let mut a = [u32::MAX; 4];
            for (k, slot) in a.iter_mut().enumerate().take(n) {
                *slot = at(start + k);
            }
            FaceKey::Small(a)
        } else {
            FaceKey::Large((0..n).map(|k| at(start + k)).collect())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::FaceKey;

    #[test]
    fn rotations_match_and_reversal_matches_opposite() {
        assert_eq!(FaceKey::of(&[5, 2, 9], false), FaceKey::of(&[2, 9, 5], false));
        assert_eq!(FaceKey::of(&[5, 2, 9], true), FaceKey::of(&[9, 2, 5], false));
        assert_ne!(FaceKey::of(&[5, 2, 9], false), FaceKey::of(&[9, 2, 5], false));
        assert_eq!(FaceKey::of(&[1, 2, 3, 4, 5], true), FaceKey::of(&[5, 4, 3, 2, 1], false));
    }
}
