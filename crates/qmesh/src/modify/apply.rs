//! Built-in query-apply operations (2025 §6.4), reachable from rule files by name
//! (`op = "apply"`, `apply = "flatten-top"`) and from code as [`ApplyFn`]s.
//!
//! Which faces of a match are "inside" or "on top" is read on the *query*: its darts
//! are labelled, and label k of the query is `matched[k - 1]` in the map, so the
//! operation does the same thing on every match whatever the geometry of the map.

use std::sync::Arc;

use super::rule::ApplyFn;
use crate::cmap::{CMap3, Dart, MapError, Orbit, OrbitWalker};
use crate::geom::{face_normal, signed_volume_of_map_volume};
use crate::query::Query;

/// Names of the built-in apply operations, for messages.
pub const BUILTIN_APPLY: &[&str] = &["merge", "flatten-top"];

/// The built-in apply operation called `name`.
pub fn builtin_apply(name: &str) -> Option<Arc<ApplyFn>> {
    match name {
        "merge" => Some(Arc::new(|m: &mut CMap3, q: &Query, d: &[Dart]| merge_volumes(m, q, d).map(drop))),
        "flatten-top" => Some(Arc::new(flatten_top)),
        _ => None,
    }
}

/// Merges the matched volumes into one: removes every face the query has between two
/// of its volumes (2025 §6.3's face removal, one face at a time).
///
/// # Errors
/// [`MapError::Refused`] when a face cannot be removed in any order.
pub fn merge_volumes(map: &mut CMap3, query: &Query, matched: &[Dart]) -> Result<usize, MapError> {
    let inner: Vec<Dart> = face_representatives(query, |d| !query.map().is_free(d, 3))
        .into_iter()
        .map(|k| matched[k as usize - 1])
        .collect();
    let n = inner.len();
    retry_until_done(inner, |d| map.remove_face(d), "inner face")?;
    Ok(n)
}

/// 2025 §7.4, step 2: merges the matched volumes into one ([`merge_volumes`]), then
/// the faces of its top (the boundary faces of the query whose normal points up,
/// within 60° of +z) into one face, and moves that face's vertices to the mean height
/// of the top faces' vertices before the merge.
///
/// ```
/// use std::sync::Arc;
/// use qmesh::build::{BuildOptions, build_volume_map};
/// use qmesh::generate::{TerrainOptions, terrain};
/// use qmesh::modify::{Action, Rule, flatten_top, run_rules};
/// use qmesh::query::{Condition, Query};
/// let opts = BuildOptions::default();
/// let flat = TerrainOptions { nx: 3, ny: 3, relief: 0.0, ..Default::default() };
/// let (block, _) = build_volume_map(&terrain(&flat), &opts).unwrap();
/// let mut rule = Rule::find(Query::new("block", block, |_| Condition::Any).unwrap());
/// rule.action = Action::Apply(Arc::new(flatten_top));
/// let hilly = TerrainOptions { nx: 4, ny: 3, relief: 2.0, ..flat };
/// let (mut map, _) = build_volume_map(&terrain(&hilly), &opts).unwrap();
/// let r = run_rules(&mut map, &[rule]);
/// // 3×3 voxels became one volume: 12 inner faces and 12 top edges gone.
/// assert_eq!((r[0].modified, r[0].volumes_after, r[0].darts_after), (1, 4, 12 * 26 - 120));
/// assert!(r[0].valid);
/// ```
///
/// # Errors
/// [`MapError::Refused`] when the query has no top face, or its faces cannot be
/// merged.
pub fn flatten_top(map: &mut CMap3, query: &Query, matched: &[Dart]) -> Result<(), MapError> {
    let q = query.map();
    let label = |d: Dart| query.labelling().label[d.idx()];
    let image = |d: Dart| matched[label(d) as usize - 1];
    // A positively oriented volume of the map runs its faces clockwise seen from
    // outside (Newell's normal points in).
    let mut w = OrbitWalker::new();
    let volume: f64 = q.cells(Orbit::Volume).map(|d| signed_volume_of_map_volume(q, d, &mut w)).sum();
    let outward = if volume >= 0.0 { -1.0 } else { 1.0 };
    let is_top = |d: Dart| q.is_free(d, 3) && points_up(q, d, outward);
    let top: Vec<Dart> = q.darts().filter(|&d| is_top(d)).collect();
    // One dart per edge between two top faces (neighbours around the edge through the
    // inner faces, which are gone from the map but not from the query).
    let across = |d: Dart| {
        let mut x = q.beta(d, 2).expect("queries are 2-closed");
        while !is_top(x) {
            x = q.beta(q.beta(x, 3)?, 2).expect("queries are 2-closed");
        }
        Some(x)
    };
    let Some(&outer) = top.iter().find(|&&d| across(d).is_none()) else {
        return Err(MapError::Refused(format!("query {} has no top face to flatten", query.name)));
    };
    let mut vertices: Vec<u32> = top.iter().map(|&d| map.vertex_of(image(d))).collect();
    vertices.sort_unstable();
    vertices.dedup();
    let height = vertices.iter().map(|&v| map.position(v)[2]).sum::<f64>() / vertices.len() as f64;
    merge_volumes(map, query, matched)?;
    let inner_edges: Vec<Dart> =
        top.iter().filter(|&&d| across(d).is_some_and(|o| label(d) < label(o))).map(|&d| image(d)).collect();
    retry_until_done(inner_edges, |d| map.remove_edge(d), "edge between top faces")?;
    let face: Vec<Dart> = map.with_scratch(|m, w| w.collect(m, image(outer), Orbit::HalfFace).to_vec());
    for d in face {
        let v = map.vertex_of(d);
        let [x, y, _] = map.position(v);
        map.set_position(v, [x, y, height]);
    }
    Ok(())
}

/// Whether the face of `d` has a normal within 60° of +z (Newell's normal, times
/// `outward` = ±1 for the map's orientation).
fn points_up(map: &CMap3, d: Dart, outward: f64) -> bool {
    let n = face_normal(map, d);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    len > 0.0 && outward * n[2] > 0.5 * len
}

/// The smallest label of each face of the query (one side of it) whose darts satisfy
/// `keep`, each face once: a 3-sewn face is named by its side with the smaller label.
fn face_representatives(query: &Query, keep: impl Fn(Dart) -> bool) -> Vec<u32> {
    let q = query.map();
    let label = |d: Dart| query.labelling().label[d.idx()];
    let mut seen = vec![false; q.dart_capacity()];
    let mut out = Vec::new();
    for &d in &query.labelling().darts {
        if seen[d.idx()] || !keep(d) {
            continue;
        }
        let mut best = label(d);
        let mut x = d;
        loop {
            seen[x.idx()] = true;
            best = best.min(label(x));
            if let Some(o) = q.beta(x, 3) {
                seen[o.idx()] = true;
                best = best.min(label(o));
            }
            x = q.next(x);
            if x == d {
                break;
            }
        }
        out.push(best);
    }
    out
}

/// Runs `op` on every item, retrying those it refuses while others succeed (a face or
/// edge that cannot go yet may after its neighbours have).
fn retry_until_done(
    mut items: Vec<Dart>,
    mut op: impl FnMut(Dart) -> Result<(), MapError>,
    what: &str,
) -> Result<(), MapError> {
    while !items.is_empty() {
        let before = items.len();
        let mut last = None;
        items.retain(|&d| match op(d) {
            Ok(()) => false,
            Err(e) => {
                last = Some(e);
                true
            }
        });
        if items.len() == before {
            let e = last.expect("an item was refused");
            return Err(MapError::Refused(format!("{} {what}s cannot be removed: {e}", items.len())));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube tilted by `degrees` about the x or the y axis: the dart of the face
    /// that was on top, and the cube.
    fn tilted_cube(degrees: f64, about_x: bool) -> (CMap3, Dart) {
        let (s, c) = degrees.to_radians().sin_cos();
        let mut m = CMap3::new();
        let v: Vec<u32> = (0..8)
            .map(|i: u32| {
                let [x, y, z] = [(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64];
                m.add_vertex(if about_x {
                    [x, c * y - s * z, s * y + c * z]
                } else {
                    [c * x + s * z, y, c * z - s * x]
                })
            })
            .collect();
        m.make_hexahedron([v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]]);
        // The top face: the one whose four vertices were at z = 1 (ids 4 to 7).
        let top = m.darts().find(|&d| {
            let mut x = d;
            (0..4).all(|_| {
                let up = m.vertex_of(x) >= 4;
                x = m.next(x);
                up
            })
        });
        (m, top.expect("a top face"))
    }

    #[test]
    fn a_face_points_up_within_sixty_degrees_of_z_on_its_outer_side() {
        for about_x in [true, false] {
            for (degrees, up) in [(0.0, true), (25.0, true), (-55.0, true), (59.0, true), (61.0, false), (-65.0, false)]
            {
                let (m, top) = tilted_cube(degrees, about_x);
                let sides = [points_up(&m, top, 1.0), points_up(&m, top, -1.0)];
                let expected = if up { 1 } else { 0 };
                assert_eq!(sides.iter().filter(|&&s| s).count(), expected, "{degrees}° about {about_x}");
            }
        }
        // A face upside down points up from the other side only.
        let (m, top) = tilted_cube(180.0, true);
        assert_ne!(points_up(&m, top, 1.0), points_up(&m, top, -1.0));
    }
}
