//! `is_valid`: every property of Definition 1 (2022 §2.2) plus our storage invariants.

use std::fmt;

use super::dart::Dart;
use super::orbit::Orbit;
use super::storage::CMap3;

/// One violated property, naming the dart where it was seen.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Violation {
    /// βi(d) points to a deleted dart or outside the map.
    Dangling { dart: u32, i: usize, target: u32 },
    /// β1 (or β0) free: faces must be closed cycles.
    Beta1Free { dart: u32 },
    /// β2 free in a volume map: volumes must be closed.
    Beta2Free { dart: u32 },
    /// β0(β1(d)) ≠ d: β0 is not the inverse of β1.
    Beta0NotInverse { dart: u32 },
    /// βi(βi(d)) ≠ d for i = 2, 3.
    NotInvolution { dart: u32, i: usize },
    /// βi(d) = d.
    FixedPoint { dart: u32, i: usize },
    /// β1∘β3 is not an involution at d (β3(β1(d)) ≠ β0(β3(d))).
    Beta13NotInvolution { dart: u32 },
    /// Two darts of the same vertex orbit carry different vertex ids.
    VertexIdMismatch { dart: u32, other: u32 },
    /// A vertex id outside the position table.
    VertexIdOutOfRange { dart: u32, id: u32 },
    /// Two distinct vertex orbits share one vertex id.
    VertexIdShared { id: u32, dart: u32, other: u32 },
    /// A surface map (dimension 2) with a 3-sewn dart.
    Beta3InSurface { dart: u32 },
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use Violation::*;
        match *self {
            Dangling { dart, i, target } => write!(f, "dart {dart}: β{i} points to {target}, which is not a live dart"),
            Beta1Free { dart } => write!(f, "dart {dart}: β1 or β0 is free (open face)"),
            Beta2Free { dart } => {
                write!(f, "dart {dart}: β2 is free in a volume map (open volume)")
            }
            Beta0NotInverse { dart } => write!(f, "dart {dart}: β0(β1(d)) ≠ d"),
            NotInvolution { dart, i } => write!(f, "dart {dart}: β{i} is not an involution"),
            FixedPoint { dart, i } => write!(f, "dart {dart}: β{i}(d) = d"),
            Beta13NotInvolution { dart } => write!(f, "dart {dart}: β1∘β3 is not an involution"),
            VertexIdMismatch { dart, other } => {
                write!(f, "darts {dart} and {other} share a vertex but have different vertex ids")
            }
            VertexIdOutOfRange { dart, id } => {
                write!(f, "dart {dart}: vertex id {id} has no position")
            }
            VertexIdShared { id, dart, other } => {
                write!(f, "vertex id {id} is used by two distinct vertices (darts {dart} and {other})")
            }
            Beta3InSurface { dart } => write!(f, "dart {dart}: β3 is sewn in a surface map"),
        }
    }
}

/// How many darts ahead the local checks prefetch the 3-sewn neighbour.
const PREFETCH_AHEAD: usize = 16;

impl CMap3 {
    /// ```
    /// use qmesh::cmap::{CMap3, Violation};
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, (i * i * i) as f64])).collect();
    /// let d = m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    /// assert!(m.is_valid().is_empty());
    /// m.unlink(d, 2); // low-level: opens the volume
    /// assert!(m.is_valid().iter().any(|x| matches!(x, Violation::Beta2Free { .. })));
    /// ```
    ///
    /// Every violated property (empty when the map is valid): β1 a permutation with β0
    /// its inverse; β2, β3 and β1∘β3 involutions without fixed points; β1 never free,
    /// β2 never free in volume maps; one vertex id per vertex orbit and one orbit per
    /// id; no live dart pointing at a deleted one.
    ///
    /// The local checks run in parallel over chunks of darts (rayon); the result is the
    /// same, in dart order, whatever the number of threads.
    pub fn is_valid(&self) -> Vec<Violation> {
        let mut out = self.local_violations_all();
        if out.is_empty() && self.has_shared_vertex_id() {
            out = self.vertex_census().1;
        }
        out
    }

    /// The checks of [`CMap3::is_valid`] that read a dart and its neighbours only, over
    /// all darts in parallel chunks, in dart order: all of them but the vertex census
    /// (for a map just built, whose builder gave each vertex orbit its own id).
    pub fn local_violations_all(&self) -> Vec<Violation> {
        use rayon::prelude::*;
        const CHUNK: usize = 1 << 16;
        let n = self.dart_capacity();
        if n <= CHUNK {
            // Small maps (patterns): no hand-over to the thread pool.
            return self.local_violations(0..n);
        }
        let chunks: Vec<std::ops::Range<usize>> =
            (0..n).step_by(CHUNK).map(|s| s..n.min(s.saturating_add(CHUNK))).collect();
        chunks.into_par_iter().map(|c| self.local_violations(c)).collect::<Vec<_>>().concat()
    }

    /// Number of vertex orbits, and a violation for every orbit whose vertex id another
    /// orbit already uses (one vertex id per orbit is only meaningful once the local
    /// checks pass).
    pub(super) fn vertex_census(&self) -> (usize, Vec<Violation>) {
        let mut owner = vec![0u32; self.positions.len()];
        let mut out = Vec::new();
        let mut count = 0;
        for d in self.cells(Orbit::Vertex) {
            count += 1;
            let Some(slot) = owner.get_mut(self.vertex_of(d) as usize) else { continue };
            match *slot {
                0 => *slot = d.raw(),
                other => out.push(Violation::VertexIdShared { id: self.vertex_of(d), dart: d.raw(), other }),
            }
        }
        (count, out)
    }

    /// The 3-sewn neighbour lives in another cell, usually far away in memory: ask for
    /// the one of the dart a few places ahead of `r` so that its cache line is there
    /// when needed. A hint only (no effect on any result: `.cargo/mutants.toml`).
    #[inline]
    fn prefetch_ahead(&self, r: usize, end: usize) {
        if let Some(ahead) = self.betas.get(end.min(r.saturating_add(PREFETCH_AHEAD))) {
            self.prefetch_dart(ahead[3]);
        }
    }

    /// The checks that only look at a dart and its neighbours, for raw indices in `range`.
    pub(super) fn local_violations(&self, range: std::ops::Range<usize>) -> Vec<Violation> {
        let mut out = Vec::new();
        // (is_live is false out of range; dart 0 is no dart)
        let live = |x: u32| Dart::from_raw(x).is_some_and(|d| self.is_live(d));
        let end = range.end;
        for r in range.map(|i| i as u32).filter(|&i| live(i)) {
            self.prefetch_ahead(r as usize, end);
            let b = self.betas[r as usize];
            let mut dangling = false;
            for (i, &t) in b.iter().enumerate() {
                if t != 0 && !live(t) {
                    out.push(Violation::Dangling { dart: r, i, target: t });
                    dangling = true;
                }
            }
            if dangling {
                continue;
            }
            if b[1] == 0 || b[0] == 0 {
                out.push(Violation::Beta1Free { dart: r });
            } else {
                if self.beta_raw(b[1], 0) != r || self.beta_raw(b[0], 1) != r {
                    out.push(Violation::Beta0NotInverse { dart: r });
                }
                if b[1] == r {
                    out.push(Violation::FixedPoint { dart: r, i: 1 });
                }
            }
            if b[2] == 0 && self.dimension == 3 {
                out.push(Violation::Beta2Free { dart: r });
            }
            if b[3] != 0 && self.dimension == 2 {
                out.push(Violation::Beta3InSurface { dart: r });
            }
            for i in [2, 3] {
                if b[i] == r {
                    out.push(Violation::FixedPoint { dart: r, i });
                } else if b[i] != 0 && self.beta_raw(b[i], i) != r {
                    out.push(Violation::NotInvolution { dart: r, i });
                }
            }
            if b[3] != 0 && b[1] != 0 && self.beta_raw(b[1], 3) != self.beta_raw(b[3], 0) {
                out.push(Violation::Beta13NotInvolution { dart: r });
            }
            let v = self.vertex[r as usize];
            if v as usize >= self.positions.len() {
                out.push(Violation::VertexIdOutOfRange { dart: r, id: v });
                continue;
            }
            // β2(d) and β3(d) start where β1(d) starts: vertex ids are uniform per orbit.
            if b[1] != 0 {
                let target = self.vertex[b[1] as usize];
                for i in [2, 3] {
                    if b[i] != 0 && self.vertex[b[i] as usize] != target {
                        out.push(Violation::VertexIdMismatch { dart: b[i], other: b[1] });
                    }
                }
            }
        }
        out
    }
}
