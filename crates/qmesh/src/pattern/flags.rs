//! Flag rules for patterns (2022 §3, `shared/data/patterns/cgal/FORMAT.md`): which
//! boundary darts are flagged, computed from the geometry.

use rustc_hash::FxHashMap;

use crate::cmap::{CMap3, Dart, Mark};
use crate::geom::{cross, dot, face_normal, sub};
use crate::signature::{Surface, pattern_face_boundary};

/// How pattern flags are set.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FlagRule {
    /// Darts starting at an original corner of the cell the pattern replaces.
    #[default]
    Corners,
    /// No flags: signatures are purely topological.
    None,
    /// Input volumes are flagged by the same geometric corner rule as patterns (for
    /// meshes whose cells are configurations, e.g. pattern boundaries).
    Geometric,
    /// User marks: pattern flags are read from the file (`.moka` marks of group 0);
    /// input darts are all flagged as with `Corners`.
    File,
}

/// Sine of the angular tolerance (0.1°) under which two directions count as parallel.
const SIN_TOL: f64 = 0.001_745_328;

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Whether directions `a` and `b` differ by more than the tolerance.
fn not_parallel(a: [f64; 3], b: [f64; 3]) -> bool {
    let (na, nb) = (norm(a), norm(b));
    na > 0.0 && nb > 0.0 && (norm(cross(a, b)) > SIN_TOL * na * nb || dot(a, b) < 0.0)
}

/// Whether three of the directions `ns` are independent (their triple product exceeds
/// the tolerance). The product is alternating, so each unordered triple is tried once.
fn spans_space(ns: &[[f64; 3]]) -> bool {
    let norms: smallvec::SmallVec<[f64; 16]> = ns.iter().map(|&a| norm(a)).collect();
    (0..ns.len()).any(|i| {
        (i + 1..ns.len()).any(|j| {
            let ab = cross(ns[i], ns[j]);
            let tol = SIN_TOL * norms[i] * norms[j];
            (j + 1..ns.len()).any(|k| dot(ab, ns[k]).abs() > tol * norms[k])
        })
    })
}

/// Flags with `mark` the boundary darts that start at a geometric corner of the
/// pattern's boundary: for an f-pattern, where consecutive boundary edges are not
/// aligned; for a v-pattern, darts on a feature edge (between non-coplanar boundary
/// faces) whose origin is a corner (boundary normals around it span 3 dimensions).
/// Returns the number of flagged darts.
pub fn flag_corners(map: &mut CMap3, mark: Mark, boundary: &[Dart], face_pattern: bool) -> usize {
    flag_corners_on(map, mark, boundary, face_pattern, Surface::PatternBoundary)
}

/// [`flag_corners`] for the darts of a closed surface read as `surface` (a pattern
/// boundary, or one input volume with [`Surface::Cell`]).
pub fn flag_corners_on(map: &mut CMap3, mark: Mark, boundary: &[Dart], face_pattern: bool, surface: Surface) -> usize {
    let flagged: Vec<Dart> = if face_pattern {
        let cycle = pattern_face_boundary(map, boundary[0]).unwrap_or_default();
        let n = cycle.len();
        (0..n)
            .filter(|&i| {
                let (prev, d, next) = (cycle[(i + n - 1) % n], cycle[i], cycle[(i + 1) % n]);
                let before = sub(map.point(d), map.point(prev));
                let after = sub(map.point(next), map.point(d));
                not_parallel(before, after)
            })
            .map(|i| cycle[i])
            .collect()
    } else {
        // One normal per boundary face, shared by the face's darts.
        let mut normal: FxHashMap<Dart, [f64; 3]> = FxHashMap::default();
        normal.reserve(boundary.len());
        for &d in boundary {
            if !normal.contains_key(&d) {
                let n = face_normal(map, d);
                let mut x = d;
                loop {
                    normal.insert(x, n);
                    x = map.next(x);
                    if x == d {
                        break;
                    }
                }
            }
        }
        // Normals of the boundary faces around each vertex, grouped by vertex (in
        // boundary order within a group).
        let mut around: Vec<(u32, [f64; 3])> = boundary.iter().map(|&d| (map.vertex_of(d), normal[&d])).collect();
        around.sort_by_key(|&(v, _)| v);
        // A vertex is a corner when three of its faces' normals are independent: decided
        // once per vertex.
        let corner: FxHashMap<u32, bool> = around
            .chunk_by(|a, b| a.0 == b.0)
            .map(|group| {
                let ns: smallvec::SmallVec<[[f64; 3]; 16]> = group.iter().map(|&(_, n)| n).collect();
                (group[0].0, spans_space(&ns))
            })
            .collect();
        boundary
            .iter()
            .copied()
            .filter(|&d| {
                let Some(o) = surface.opposite(map, d) else { return false };
                corner[&map.vertex_of(d)] && not_parallel(normal[&d], normal.get(&o).copied().unwrap_or([0.0; 3]))
            })
            .collect()
    };
    for &d in &flagged {
        map.mark(d, mark);
    }
    flagged.len()
}
