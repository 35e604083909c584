//! 3-map → indexed cells for writing: tet/pyramid/prism/hex recognised from their
//! topology (nodes put back in VTK order), any other volume as a VTK polyhedron.

use super::indexed::{CellKind, IndexedMesh};
use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};

/// Counts of the cell kinds found by [`extract`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExtractedKinds {
    pub tet: usize,
    pub pyramid: usize,
    pub prism: usize,
    pub hex: usize,
    pub other: usize,
}

impl ExtractedKinds {
    pub fn add(&mut self, k: CellKind) {
        match k {
            CellKind::Tet => self.tet += 1,
            CellKind::Pyramid => self.pyramid += 1,
            CellKind::Prism => self.prism += 1,
            CellKind::Hex => self.hex += 1,
            CellKind::Polyhedron => self.other += 1,
        }
    }
}

/// The vertex id at the far end of the side edge leaving the origin of `d`
/// (the node "above" it when d's face is the base of a prism-like cell).
fn above(map: &CMap3, d: Dart) -> u32 {
    let side = map.next(map.beta(d, 2).expect("closed volume"));
    map.vertex_of(map.next(side))
}

fn face_len(map: &CMap3, d: Dart) -> usize {
    let mut n = 1;
    let mut x = map.next(d);
    while x != d {
        n += 1;
        x = map.next(x);
    }
    n
}

fn cycle(map: &CMap3, d: Dart, n: usize) -> Vec<Dart> {
    let mut out = Vec::with_capacity(n);
    let mut x = d;
    for _ in 0..n {
        out.push(x);
        x = map.next(x);
    }
    out
}

/// Recognises the volume of `d` and returns its kind and nodes (VTK order), or for any
/// other volume the VTK polyhedron face stream (outward faces). `walker` is scratch.
pub fn recognise_volume(map: &CMap3, d: Dart, walker: &mut OrbitWalker) -> (CellKind, Vec<u32>) {
    let darts: Vec<Dart> = walker.collect(map, d, Orbit::Volume).to_vec();
    let mut faces: Vec<(Dart, usize)> = Vec::new();
    let mut in_face = rustc_hash::FxHashSet::default();
    for &x in &darts {
        if in_face.insert(x) {
            let n = face_len(map, x);
            cycle(map, x, n).into_iter().skip(1).for_each(|y| {
                in_face.insert(y);
            });
            faces.push((x, n));
        }
    }
    let count = |k: usize| faces.iter().filter(|f| f.1 == k).count();
    let (tris, quads, nf) = (count(3), count(4), faces.len());
    let guess = match (nf, tris, quads, darts.len()) {
        (4, 4, 0, 12) => Some(CellKind::Tet),
        (5, 4, 1, 16) => Some(CellKind::Pyramid),
        (5, 2, 3, 18) => Some(CellKind::Prism),
        (6, 0, 6, 24) => Some(CellKind::Hex),
        _ => None,
    };
    if let Some(kind) = guess
        && let Some(nodes) = standard_nodes(map, kind, &faces)
    {
        return (kind, nodes);
    }
    let mut stream = vec![nf as u32];
    for &(x, n) in &faces {
        stream.push(n as u32);
        // Map orientation is inward; VTK polyhedron faces are outward: reverse.
        stream.extend(cycle(map, x, n).iter().rev().map(|&y| map.vertex_of(y)));
    }
    (CellKind::Polyhedron, stream)
}

/// Nodes in VTK order for a volume whose face counts match `kind`, checked against the
/// kind's face table; None when the topology is not that of the standard cell.
fn standard_nodes(map: &CMap3, kind: CellKind, faces: &[(Dart, usize)]) -> Option<Vec<u32>> {
    let base_len = match kind {
        CellKind::Tet | CellKind::Prism => 3,
        _ => 4,
    };
    let base = faces.iter().find(|f| f.1 == base_len)?.0;
    let b = cycle(map, base, base_len);
    let ids: Vec<u32> = b.iter().map(|&x| map.vertex_of(x)).collect();
    let nodes: Vec<u32> = match kind {
        CellKind::Tet | CellKind::Pyramid => {
            let mut n = ids.clone();
            n.push(above(map, b[0]));
            n
        }
        CellKind::Hex => {
            let mut n = ids.clone();
            n.extend(b.iter().map(|&x| above(map, x)));
            n
        }
        CellKind::Prism => {
            // VTK's 0-1-2 normal points away from 3-4-5: reverse the inward base cycle.
            let order = [b[0], b[2], b[1]];
            let mut n: Vec<u32> = order.iter().map(|&x| map.vertex_of(x)).collect();
            n.extend(order.iter().map(|&x| above(map, x)));
            n
        }
        CellKind::Polyhedron => return None,
    };
    let mut sorted = nodes.clone();
    sorted.sort_unstable();
    sorted.dedup();
    if sorted.len() != nodes.len() {
        return None;
    }
    // Every face of the table must be a face of the volume (as a vertex cycle).
    let have: rustc_hash::FxHashSet<super::face_key::FaceKey> = faces
        .iter()
        .map(|&(x, n)| {
            super::face_key::FaceKey::of(&cycle(map, x, n).iter().map(|&y| map.vertex_of(y)).collect::<Vec<_>>(), false)
        })
        .collect();
    let ok = kind.face_table().iter().all(|f| {
        let c: Vec<u32> = f.iter().map(|&k| nodes[k]).collect();
        have.contains(&super::face_key::FaceKey::of(&c, false))
    });
    ok.then_some(nodes)
}

/// How many volumes of each kind the map holds.
pub fn count_cell_kinds(map: &CMap3) -> ExtractedKinds {
    let mut kinds = ExtractedKinds::default();
    if map.dimension() == 3 {
        let mut walker = OrbitWalker::new();
        for d in map.cells(Orbit::Volume) {
            kinds.add(recognise_volume(map, d, &mut walker).0);
        }
    }
    kinds
}

/// Indexed cells of every volume of a volume map (labels kept when the map has them),
/// or the polygons of a surface map. Points are the vertex ids in use, renumbered in
/// increasing id order.
pub fn extract(map: &CMap3) -> (IndexedMesh, ExtractedKinds) {
    let mut out = IndexedMesh::new();
    let mut kinds = ExtractedKinds::default();
    let mut walker = OrbitWalker::new();
    let mut cells: Vec<(CellKind, Vec<u32>, i32)> = Vec::new();
    let mut polys: Vec<Vec<u32>> = Vec::new();
    if map.dimension() == 3 {
        for d in map.cells(Orbit::Volume) {
            let (k, nodes) = recognise_volume(map, d, &mut walker);
            kinds.add(k);
            cells.push((k, nodes, map.label_of(d)));
        }
    } else {
        for d in map.cells(Orbit::HalfFace) {
            polys.push(cycle(map, d, face_len(map, d)).iter().map(|&x| map.vertex_of(x)).collect());
        }
    }
    let mut newid = vec![u32::MAX; map.nb_vertex_ids()];
    let mut used = vec![false; map.nb_vertex_ids()];
    for d in map.darts() {
        used[map.vertex_of(d) as usize] = true;
    }
    for (v, &u) in used.iter().enumerate() {
        if u {
            newid[v] = out.points.len() as u32;
            out.points.push(map.position(v as u32));
        }
    }
    let labelled = map.has_labels();
    for (k, nodes, label) in cells {
        let renumbered: Vec<u32> = if k == CellKind::Polyhedron {
            renumber_stream(&nodes, &newid)
        } else {
            nodes.iter().map(|&v| newid[v as usize]).collect()
        };
        out.push_cell(k, &renumbered, labelled.then_some(label));
    }
    for p in polys {
        out.push_polygon(&p.iter().map(|&v| newid[v as usize]).collect::<Vec<_>>());
    }
    (out, kinds)
}

fn renumber_stream(stream: &[u32], newid: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(stream.len());
    out.push(stream[0]);
    let mut k = 1;
    while k < stream.len() {
        let n = stream[k] as usize;
        out.push(stream[k]);
        out.extend(stream[k + 1..k + 1 + n].iter().map(|&v| newid[v as usize]));
        k += 1 + n;
    }
    out
}

/// The boundary of a volume map as outward polygons (3-free faces, reversed), or the
/// faces of a surface map; with the points of [`extract`]'s numbering.
pub fn boundary_polygons(map: &CMap3) -> IndexedMesh {
    if map.dimension() == 2 {
        return extract(map).0;
    }
    let mut out = IndexedMesh::new();
    let mut newid = vec![u32::MAX; map.nb_vertex_ids()];
    for d in map.cells(Orbit::HalfFace) {
        if !map.is_free(d, 3) {
            continue;
        }
        let mut p: Vec<u32> = cycle(map, d, face_len(map, d)).iter().map(|&x| map.vertex_of(x)).collect();
        p.reverse();
        for v in p.iter_mut() {
            if newid[*v as usize] == u32::MAX {
                newid[*v as usize] = out.points.len() as u32;
                out.points.push(map.position(*v));
            }
            *v = newid[*v as usize];
        }
        out.push_polygon(&p);
    }
    out
}
