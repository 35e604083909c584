//! Placing a pattern's vertices in a target: boundary vertices map to the target's,
//! interior vertices are created at their mean value coordinates (2022 §5.2).

use rustc_hash::FxHashMap;

use crate::cmap::CMap3;
use crate::pattern::Pattern;

/// Pattern vertex id → target vertex id, given the boundary correspondence; creates the
/// interior vertices of the pattern in `map`.
pub fn place_vertices(map: &mut CMap3, p: &Pattern, boundary: FxHashMap<u32, u32>) -> FxHashMap<u32, u32> {
    let mut vmap = boundary;
    for iv in &p.interior {
        let mut pos = [0.0; 3];
        for &(v, w) in &iv.weights {
            let q = map.position(vmap[&v]);
            for k in 0..3 {
                pos[k] += w * q[k];
            }
        }
        let id = map.add_vertex(pos);
        vmap.insert(iv.vertex, id);
    }
    vmap
}
