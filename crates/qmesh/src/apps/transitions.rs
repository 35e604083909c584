//! qmesh's own transition patterns for 2:1 octree meshes (2022 §7.3), generated for
//! every configuration rather than drawn: a cube whose faces are either refined (4
//! quadrilaterals around a face centre) or whole with any subset of their edges split.
//! Faces with split edges are fanned into triangles around their centre (5 f-patterns);
//! the cube is split into one pyramid or tetrahedron per boundary piece, all sharing
//! the cube centre. One v-pattern per configuration class under the 24 rotations.

use rustc_hash::FxHashMap;

use super::cube::{corner, edge_index, edges, edges_of_faces, faces, rotations};

use crate::build::{CellKind, IndexedMesh};

/// A configuration: refined faces (bit f) and split edges (bit e, ⊇ edges of refined faces).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Configuration {
    pub refined_faces: u8,
    pub split_edges: u16,
}

impl Configuration {
    fn rotated(self, r: &[u8; 8]) -> Configuration {
        let es = edges();
        let fs = faces();
        let split_edges = (0..12).filter(|e| self.split_edges >> e & 1 == 1).fold(0u16, |m, e| {
            let (a, b) = es[e];
            m | 1 << edge_index(r[a as usize], r[b as usize])
        });
        let refined_faces = (0..6).filter(|f| self.refined_faces >> f & 1 == 1).fold(0u8, |m, f| {
            let image: Vec<u8> = fs[f].iter().map(|&c| r[c as usize]).collect();
            let g = fs.iter().position(|g| g.iter().all(|c| image.contains(c))).expect("a face maps to a face");
            m | 1 << g
        });
        Configuration { refined_faces, split_edges }
    }
}

/// Every 2:1 configuration except the plain cube (6,209), and one representative per
/// class under the 24 rotations (the smallest).
pub fn transition_configurations() -> (Vec<Configuration>, Vec<Configuration>) {
    let rots = rotations();
    let mut all = Vec::new();
    for refined_faces in 0..64u8 {
        let forced = edges_of_faces(refined_faces);
        for split_edges in 0..4096u16 {
            if split_edges & forced == forced && (refined_faces, split_edges) != (0, 0) {
                all.push(Configuration { refined_faces, split_edges });
            }
        }
    }
    let classes: std::collections::BTreeSet<Configuration> =
        all.iter().map(|c| rots.iter().map(|r| c.rotated(r)).min().expect("24 rotations")).collect();
    (all, classes.into_iter().collect())
}

/// Builds a mesh with points created on demand by key.
struct Builder {
    mesh: IndexedMesh,
    ids: FxHashMap<[i32; 3], u32>,
}

impl Builder {
    /// The point at `p` (coordinates in halves of the unit cube: 0, 1 or 2).
    fn point(&mut self, p: [i32; 3]) -> u32 {
        *self.ids.entry(p).or_insert_with(|| {
            self.mesh.points.push(p.map(|c| f64::from(c) / 2.0));
            (self.mesh.points.len() - 1) as u32
        })
    }
}

fn halves(p: [f64; 3]) -> [i32; 3] {
    p.map(|c| (c * 2.0).round() as i32)
}

fn mid(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [0, 1, 2].map(|k| (a[k] + b[k]) / 2)
}

/// The boundary pieces of a face (outward cycles, in halves), given which of its 4
/// edges are split and whether it is refined.
fn face_pieces(corners: [[i32; 3]; 4], split: [bool; 4], refined: bool) -> Vec<Vec<[i32; 3]>> {
    let centre = mid(corners[0], corners[2]);
    let mids: [[i32; 3]; 4] = std::array::from_fn(|i| mid(corners[i], corners[(i + 1) % 4]));
    if refined {
        return (0..4).map(|i| vec![corners[i], mids[i], centre, mids[(i + 3) % 4]]).collect();
    }
    let ring: Vec<[i32; 3]> =
        (0..4).flat_map(|i| std::iter::once(corners[i]).chain(split[i].then_some(mids[i]))).collect();
    if ring.len() == 4 {
        return vec![ring];
    }
    (0..ring.len()).map(|i| vec![ring[i], ring[(i + 1) % ring.len()], centre]).collect()
}

/// The v-pattern of a configuration: one pyramid or tetrahedron per boundary piece,
/// with the cube centre as apex.
pub fn transition_volume(c: Configuration) -> IndexedMesh {
    let mut b = Builder { mesh: IndexedMesh::new(), ids: FxHashMap::default() };
    let centre = b.point([1, 1, 1]);
    for (f, cycle) in faces().iter().enumerate() {
        let corners = cycle.map(|k| halves(corner(k)));
        let split: [bool; 4] =
            std::array::from_fn(|i| c.split_edges >> edge_index(cycle[i], cycle[(i + 1) % 4]) & 1 == 1);
        for piece in face_pieces(corners, split, c.refined_faces >> f & 1 == 1) {
            // Outward piece → base turning toward the inner apex: reversed.
            let mut nodes: Vec<u32> = piece.iter().rev().map(|&p| b.point(p)).collect();
            nodes.push(centre);
            let kind = if nodes.len() == 5 { CellKind::Pyramid } else { CellKind::Tet };
            b.mesh.push_cell(kind, &nodes, None);
        }
    }
    b.mesh
}

/// A cube in configuration `c` as one polyhedron, the way [`super::conformal`](fn@super::conformal) finds
/// it in a mesh: refined faces as 4 quadrilaterals, other faces with the midpoints of
/// their split edges (for audits and tests of pattern sets).
pub fn configuration_cell(c: Configuration) -> IndexedMesh {
    let mut b = Builder { mesh: IndexedMesh::new(), ids: FxHashMap::default() };
    let mut stream = vec![0u32];
    for (f, cycle) in faces().iter().enumerate() {
        let corners = cycle.map(|k| halves(corner(k)));
        let split: [bool; 4] =
            std::array::from_fn(|i| c.split_edges >> edge_index(cycle[i], cycle[(i + 1) % 4]) & 1 == 1);
        let refined = c.refined_faces >> f & 1 == 1;
        let pieces = if refined {
            face_pieces(corners, split, true)
        } else {
            let mids: [[i32; 3]; 4] = std::array::from_fn(|i| mid(corners[i], corners[(i + 1) % 4]));
            vec![(0..4).flat_map(|i| std::iter::once(corners[i]).chain(split[i].then_some(mids[i]))).collect()]
        };
        for piece in pieces {
            stream.push(piece.len() as u32);
            for p in piece {
                let id = b.point(p);
                stream.push(id);
            }
            stream[0] += 1;
        }
    }
    b.mesh.push_cell(CellKind::Polyhedron, &stream, None);
    b.mesh
}

/// The f-pattern of a square with the given edges split: the square fanned around its
/// centre (one of the 5 classes: 1, 2 adjacent, 2 opposite, 3 or 4 split edges).
pub fn transition_face(split: [bool; 4]) -> IndexedMesh {
    let corners = [[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]];
    let mut b = Builder { mesh: IndexedMesh::new(), ids: FxHashMap::default() };
    for piece in face_pieces(corners, split, false) {
        let nodes: Vec<u32> = piece.iter().map(|&p| b.point(p)).collect();
        b.mesh.push_polygon(&nodes);
    }
    b.mesh
}

/// The 5 face configurations (split edges up to rotation), with file stems.
pub fn transition_face_configurations() -> [(&'static str, [bool; 4]); 5] {
    [
        ("face-split-1", [true, false, false, false]),
        ("face-split-2-adjacent", [true, true, false, false]),
        ("face-split-2-opposite", [true, false, true, false]),
        ("face-split-3", [true, true, true, false]),
        ("face-split-4", [true, true, true, true]),
    ]
}
