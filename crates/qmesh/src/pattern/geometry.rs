//! Pattern geometry (2022 §5.2): interior vertices as mean value coordinates of the
//! boundary vertices, so that they can be placed in any matched target.

use rustc_hash::FxHashMap;

use super::{InteriorVertex, PatternKind};
use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};
use crate::geom::{mvc_polygon, mvc_triangles, signed_volume_of_map_volume};

/// Sum of the signed volumes of the pattern's volumes (negative: inverted orientation).
pub fn total_volume(map: &CMap3) -> f64 {
    let mut w = OrbitWalker::new();
    map.cells(Orbit::Volume).map(|d| signed_volume_of_map_volume(map, d, &mut w)).sum()
}

/// Mean value coordinates of every interior vertex over the boundary vertices: the
/// boundary polygon (f-pattern, `boundary` is its cycle) or the fan-triangulated
/// boundary surface (v-pattern, `boundary` its 3-free darts).
pub fn interior_coordinates(map: &CMap3, kind: PatternKind, boundary: &[Dart]) -> Vec<InteriorVertex> {
    let mut on_boundary: Vec<u32> = Vec::new();
    let mut index: FxHashMap<u32, usize> = FxHashMap::default();
    let mut id = |v: u32, on: &mut Vec<u32>| {
        *index.entry(v).or_insert_with(|| {
            on.push(v);
            on.len() - 1
        })
    };
    let mut tris: Vec<[usize; 3]> = Vec::new();
    match kind {
        PatternKind::Face => {
            for &d in boundary {
                id(map.vertex_of(d), &mut on_boundary);
            }
        }
        PatternKind::Volume => {
            let mut seen = rustc_hash::FxHashSet::default();
            for &d in boundary {
                if !seen.insert(d) {
                    continue;
                }
                let mut face = vec![d];
                let mut x = map.next(d);
                while x != d {
                    seen.insert(x);
                    face.push(x);
                    x = map.next(x);
                }
                let ids: Vec<usize> = face.iter().map(|&y| id(map.vertex_of(y), &mut on_boundary)).collect();
                for k in 1..ids.len() - 1 {
                    tris.push([ids[0], ids[k], ids[k + 1]]);
                }
            }
        }
    }
    let pts: Vec<[f64; 3]> = on_boundary.iter().map(|&v| map.position(v)).collect();
    let mut inner: Vec<u32> = map.darts().map(|d| map.vertex_of(d)).filter(|v| !index.contains_key(v)).collect();
    inner.sort_unstable();
    inner.dedup();
    inner
        .into_iter()
        .map(|v| {
            let x = map.position(v);
            let w = match kind {
                PatternKind::Face => mvc_polygon(&pts, x),
                PatternKind::Volume => mvc_triangles(&pts, &tris, x),
            };
            let weights =
                w.into_iter().enumerate().filter(|(_, w)| w.abs() > 1e-12).map(|(i, w)| (on_boundary[i], w)).collect();
            InteriorVertex { vertex: v, weights }
        })
        .collect()
}
