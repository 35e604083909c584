//! Standard-cell recognition: a volume is a tetrahedron, pyramid, prism or hexahedron
//! when its darts correspond one to one with the kind's dart layout (the one cell
//! constructors build from), β1 and β2 preserved, with distinct vertex ids on the
//! kind's nodes. No allocation: the correspondence lives in two small arrays.

use crate::cmap::{CMap3, Dart, Standard};

/// Vertex ids of a recognised cell's nodes in VTK order (the first `kind.nodes()`).
pub type StandardNodes = [u32; 8];

/// The standard kind of the volume of `d` and its nodes in VTK order, or None for any
/// other volume (more or fewer darts, other face shapes, repeated vertex ids, or open
/// faces). Kinds are tried by the degree of d's face; every start in the layout on a
/// face of that degree is tried, so the answer does not depend on which dart is given.
pub fn standard_cell(map: &CMap3, d: Dart) -> Option<(Standard, StandardNodes)> {
    let kinds: &[Standard] = match map.face_degree(d) {
        3 => &[Standard::Tet, Standard::Prism, Standard::Pyramid],
        4 => &[Standard::Hex, Standard::Prism, Standard::Pyramid],
        _ => return None,
    };
    let degree = map.face_degree(d);
    for &kind in kinds {
        let layout = kind.layout();
        let starts = (0..layout.face_start.len() - 1)
            .filter(|&f| layout.face_len(f) == degree)
            .flat_map(|f| layout.face_start[f]..layout.face_start[f + 1]);
        for start in starts {
            if let Some(nodes) = match_layout(map, d, kind, start as usize) {
                return Some((kind, nodes));
            }
        }
    }
    None
}

/// Walks the volume of `d` and the layout of `kind` together from `d` ↔ local dart
/// `start`; the nodes when every β1/β2 step agrees and the nodes get distinct ids.
///
/// Why this is enough: agreeing steps make dart → local a covering of the layout by
/// the volume's orbit (both are connected). Distinct node ids rule out a cover of
/// degree > 1: a second sheet would be a rotation of the cell fixing every node.
fn match_layout(map: &CMap3, d: Dart, kind: Standard, start: usize) -> Option<StandardNodes> {
    let layout = kind.layout();
    let mut dart_of = [0u32; 24];
    let mut nodes = [u32::MAX; 8];
    let mut stack = [0u8; 24];
    let mut top = 1;
    stack[0] = start as u8;
    dart_of[start] = d.raw();
    while top > 0 {
        top -= 1;
        let k = stack[top] as usize;
        let x = dart_of[k];
        let node = &mut nodes[layout.origin[k] as usize];
        let v = map.vertex_of(Dart::from_raw(x)?);
        if *node == u32::MAX {
            *node = v;
        } else if *node != v {
            return None;
        }
        for i in [1, 2] {
            let (local, real) = (layout.local_betas[k][i] as usize, map.beta_raw(x, i));
            if real == 0 {
                return None;
            }
            if dart_of[local] == 0 {
                dart_of[local] = real;
                stack[top] = local as u8;
                top += 1;
            } else if dart_of[local] != real {
                return None;
            }
        }
    }
    let n = kind.nodes();
    let distinct = (0..n).all(|i| nodes[i] != u32::MAX && !nodes[..i].contains(&nodes[i]));
    distinct.then_some(nodes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cmap::Orbit;

    fn cube_points(m: &mut CMap3) -> Vec<u32> {
        (0..8).map(|i| m.add_vertex([(i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64])).collect()
    }

    #[test]
    fn every_dart_of_every_standard_cell_recognises_it_with_vtk_nodes() {
        for kind in Standard::ALL {
            let mut m = CMap3::new();
            let v = cube_points(&mut m);
            let nodes: Vec<u32> = v[..kind.nodes()].to_vec();
            let mut out = [0u32; 24];
            let n = m.make_standard_cell(kind, &nodes, &mut out);
            for &x in &out[..n] {
                let (k, found) = standard_cell(&m, Dart::from_raw(x).unwrap()).expect("recognised");
                assert_eq!(k, kind);
                // A rotation of the VTK order: the same face table, as vertex cycles.
                let cycles = |ns: &[u32]| {
                    let mut c: Vec<Vec<u32>> = kind
                        .faces()
                        .iter()
                        .map(|f| {
                            let mut c: Vec<u32> = f.iter().map(|&i| ns[i]).collect();
                            let r = c.iter().enumerate().min_by_key(|p| p.1).unwrap().0;
                            c.rotate_left(r);
                            c
                        })
                        .collect();
                    c.sort();
                    c
                };
                assert_eq!(cycles(&found[..kind.nodes()]), cycles(&nodes), "{kind:?}");
            }
        }
    }

    #[test]
    fn repeated_ids_and_other_polyhedra_are_not_standard() {
        let mut m = CMap3::new();
        let v = cube_points(&mut m);
        // A hexahedron whose top face reuses the bottom ids: the right darts, repeated ids.
        let d = m.make_hexahedron([v[0], v[1], v[2], v[3], v[0], v[1], v[2], v[3]]);
        assert!(standard_cell(&m, d).is_none());
        // A pentagonal prism (7 faces).
        let mut p = CMap3::new();
        let ids: Vec<u32> = (0..10).map(|i| p.add_vertex([i as f64, (i * i) as f64, 0.0])).collect();
        let (b, t) = (&ids[..5], &ids[5..]);
        let mut faces: Vec<Vec<u32>> = vec![b.iter().rev().copied().collect(), t.to_vec()];
        for i in 0..5 {
            faces.push(vec![b[i], b[(i + 1) % 5], t[(i + 1) % 5], t[i]]);
        }
        let firsts = p.make_polyhedron_faces(&faces).unwrap();
        for x in p.orbit(firsts[0], Orbit::Volume) {
            assert!(standard_cell(&p, x).is_none());
        }
    }
}
