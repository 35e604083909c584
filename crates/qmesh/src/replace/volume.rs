//! Replacing a volume by the interior of a v-pattern (2022 Algorithm 4, §5.1.2), through
//! the modify layer's [`VolumePattern`] (one rewiring code for both engines).

use crate::cmap::{CMap3, Dart};
use crate::modify::VolumePattern;
use crate::pattern::Pattern;
use crate::signature::Flags;

/// Inserts the interior of v-pattern `p` into the volume of `target`, whose traversal
/// from `target` corresponds dart by dart to the pattern boundary's traversal from
/// `p.start` (the canonical starts of equal signatures, or a direct-test match).
/// Returns the darts added (the pattern's interior), or None if the traversals do not
/// correspond. Replacing many volumes: build the [`VolumePattern`] once instead.
pub fn replace_volume(map: &mut CMap3, p: &Pattern, target: Dart, flags: Flags) -> Option<Vec<Dart>> {
    VolumePattern::new(p)?.replace(map, target, flags)
}
