//! The rewriting plans of a pattern set's f- and v-patterns, made when a pattern first
//! matches and kept for the passes that follow with the same set (each refinement step
//! of a subdivision is a pass of its own). Kept per [`PatternSet::version`], like the
//! lookups of `lookup_memo`, so a plan is never used for another set.

use std::sync::{Arc, Mutex, OnceLock};

use crate::modify::{FacePattern, VolumePattern};
use crate::pattern::PatternSet;

/// The plans of one set, by pattern index (`None`: the pattern has no plan of that kind).
#[derive(Debug)]
pub(super) struct Plans {
    version: u64,
    faces: Vec<OnceLock<Option<FacePattern>>>,
    volumes: Vec<OnceLock<Option<VolumePattern>>>,
}

/// The plans of the set used last (one set at a time is the common case; another set
/// replaces them).
static LAST: Mutex<Option<Arc<Plans>>> = Mutex::new(None);

impl Plans {
    /// The plans of `set`: those of the last passes if they used the same set.
    pub(super) fn of(set: &PatternSet) -> Arc<Plans> {
        let mut last = LAST.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        match &*last {
            Some(p) if p.version == set.version() && p.faces.len() == set.patterns.len() => Arc::clone(p),
            _ => {
                let n = set.patterns.len();
                let plans = Arc::new(Plans {
                    version: set.version(),
                    faces: (0..n).map(|_| OnceLock::new()).collect(),
                    volumes: (0..n).map(|_| OnceLock::new()).collect(),
                });
                *last = Some(Arc::clone(&plans));
                plans
            }
        }
    }

    /// The face plan of pattern `i` of `set` (the set these plans are of).
    pub(super) fn face(&self, set: &PatternSet, i: usize) -> Option<&FacePattern> {
        self.faces[i].get_or_init(|| FacePattern::new(&set.patterns[i])).as_ref()
    }

    /// The volume plan of pattern `i` of `set` (the set these plans are of).
    pub(super) fn volume(&self, set: &PatternSet, i: usize) -> Option<&VolumePattern> {
        self.volumes[i].get_or_init(|| VolumePattern::new(&set.patterns[i])).as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apps::{GeneratedKind, generated_pattern_set};
    use crate::pattern::FlagRule;

    /// Passes alternating between two sets (as two programs sharing the library would)
    /// never get the other set's plans, and a set's plans are its patterns' plans.
    #[test]
    fn plans_are_never_those_of_another_set() {
        let sets = [GeneratedKind::HexSubdivision, GeneratedKind::Tet2Hex]
            .map(|k| generated_pattern_set(k, FlagRule::Corners).expect("generated sets are valid"));
        for _ in 0..3 {
            for set in &sets {
                let plans = Plans::of(set);
                assert_eq!((plans.version, plans.faces.len()), (set.version(), set.patterns.len()));
                for i in 0..set.patterns.len() {
                    let made = FacePattern::new(&set.patterns[i]).map(|p| format!("{p:?}"));
                    assert_eq!(plans.face(set, i).map(|p| format!("{p:?}")), made);
                }
            }
        }
    }
}
