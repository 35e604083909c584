//! Signatures of faces and volumes, and of f-/v-pattern boundaries (2022 §2.4, §4).
//!
//! A signature is a canonical word: two boundaries have the same signature exactly when
//! a (flag-preserving) map isomorphism exists between them, so patterns can be looked
//! up in a hash map keyed by signature (2022 §4).

mod face;
mod labels;
mod surface;
mod volume;

pub use face::{cycle_automorphisms, cycle_signature, face_signature, pattern_face_boundary, pattern_face_signature};
pub use surface::Surface;
pub use volume::{
    VolumeWord, match_direct, signature_shape, start_with_signature, volume_shape, volume_signature,
    volume_signature_from, word_from, word_into,
};

use crate::cmap::{CMap3, Dart, Mark};

/// Which darts carry the papers' flags (2022 §4.2.2, §4.3.2): a reserved mark, or none.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flags {
    None,
    Mark(Mark),
}

impl Flags {
    #[inline]
    pub fn get(self, map: &CMap3, d: Dart) -> bool {
        match self {
            Flags::None => false,
            Flags::Mark(m) => map.is_marked(d, m),
        }
    }
}

/// A canonical signature: the kind of boundary and its minimal word.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Signature {
    /// f-signature: gaps between consecutive flagged darts (minimal rotation), or
    /// `[0, k]` without flags.
    Face(Vec<u32>),
    /// v-signature: the minimal boundary word followed by the flag bits.
    Volume(Vec<u32>),
}

impl Signature {
    /// A stable 64-bit FNV-1a digest, printed in hex by audits.
    pub fn digest(&self) -> String {
        let (tag, w) = match self {
            Signature::Face(w) => (b'f', w),
            Signature::Volume(w) => (b'v', w),
        };
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in std::iter::once(tag).chain(w.iter().flat_map(|x| x.to_le_bytes())) {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
        format!("{h:016x}")
    }
}
