//! Pattern sets generated from their definition (2022 §7.1, §7.4): hexahedron split in
//! 2×2×2 (with its face pattern, a square split in 2×2) and tetrahedron split into 4
//! hexahedra (with its face pattern, a triangle split into 3 quadrilaterals).

use std::path::PathBuf;

use super::transitions::{
    transition_configurations, transition_face, transition_face_configurations, transition_volume,
};
use crate::build::{BuildOptions, CellKind, IndexedMesh, build_map};
use crate::pattern::{FlagRule, PatternError, PatternSet, pattern_from_map};

/// The pattern sets qmesh can generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeneratedKind {
    /// Octree refinement: every edge split in 2, faces in 4, hexahedra in 8.
    HexSubdivision,
    /// Tetrahedra to hexahedra: edges split in 2, triangles in 3 quads, tets in 4 hexes.
    Tet2Hex,
    /// Conformal transitions of 2:1 octree meshes: every configuration of refined faces
    /// and split edges, one v-pattern per class under rotation (see `transitions.rs`).
    Transitions,
}

impl GeneratedKind {
    pub fn name(self) -> &'static str {
        match self {
            GeneratedKind::HexSubdivision => "hex-subdivision",
            GeneratedKind::Tet2Hex => "tet2hex",
            GeneratedKind::Transitions => "transitions",
        }
    }
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0, (a[2] + b[2]) / 2.0]
}

fn mean(ps: &[[f64; 3]]) -> [f64; 3] {
    let n = ps.len() as f64;
    let s = ps.iter().fold([0.0; 3], |s, p| [s[0] + p[0], s[1] + p[1], s[2] + p[2]]);
    [s[0] / n, s[1] / n, s[2] / n]
}

/// The unit square split in 2×2 quads (an f-pattern as a polygon mesh).
fn square_2x2() -> IndexedMesh {
    let mut m = IndexedMesh::new();
    for j in 0..3 {
        for i in 0..3 {
            m.points.push([i as f64 / 2.0, j as f64 / 2.0, 0.0]);
        }
    }
    let id = |i: u32, j: u32| i + 3 * j;
    for j in 0..2 {
        for i in 0..2 {
            m.push_polygon(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    m
}

/// The unit cube split in 2×2×2 hexahedra.
fn cube_2x2x2() -> IndexedMesh {
    let mut m = crate::generate::hex_grid(2, 2, 2);
    m.points.iter_mut().for_each(|p| *p = p.map(|c| c / 2.0));
    m
}

/// A triangle split into 3 quads around its centre.
fn triangle_3_quads() -> IndexedMesh {
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mut m = IndexedMesh::new();
    m.points.extend_from_slice(&t);
    for i in 0..3 {
        m.points.push(mid(t[i], t[(i + 1) % 3])); // 3 + i: middle of edge i → i+1
    }
    m.points.push(mean(&t)); // 6
    for i in 0..3u32 {
        m.push_polygon(&[i, 3 + i, 6, 3 + (i + 2) % 3]);
    }
    m
}

/// A tetrahedron split into 4 hexahedra, one per corner (corner, 3 edge middles, 3 face
/// centres, the centroid); cells are oriented by the builder.
fn tet_4_hexes() -> IndexedMesh {
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut m = IndexedMesh::new();
    m.points.extend_from_slice(&t);
    let mut edge = [[0u32; 4]; 4];
    for a in 0..4 {
        for b in a + 1..4 {
            edge[a][b] = m.points.len() as u32;
            edge[b][a] = edge[a][b];
            m.points.push(mid(t[a], t[b]));
        }
    }
    let mut face = std::collections::BTreeMap::new();
    for a in 0..4 {
        for b in a + 1..4 {
            for c in b + 1..4 {
                face.insert([a, b, c], m.points.len() as u32);
                m.points.push(mean(&[t[a], t[b], t[c]]));
            }
        }
    }
    let g = m.points.len() as u32;
    m.points.push(mean(&t));
    let f = |mut k: [usize; 3]| {
        k.sort_unstable();
        face[&k]
    };
    for (a, e) in edge.iter().enumerate() {
        let o: Vec<usize> = (0..4).filter(|&x| x != a).collect();
        let (b, c, d) = (o[0], o[1], o[2]);
        let hex = [a as u32, e[b], f([a, b, c]), e[c], e[d], f([a, b, d]), g, f([a, c, d])];
        m.push_cell(CellKind::Hex, &hex, None);
    }
    m
}

/// The meshes of a generated set: (file stem, is a v-pattern, mesh).
pub fn generated_pattern_meshes(kind: GeneratedKind) -> Vec<(String, bool, IndexedMesh)> {
    match kind {
        GeneratedKind::HexSubdivision => {
            vec![("square-2x2".into(), false, square_2x2()), ("cube-2x2x2".into(), true, cube_2x2x2())]
        }
        GeneratedKind::Tet2Hex => {
            vec![("triangle-3-quads".into(), false, triangle_3_quads()), ("tet-4-hexes".into(), true, tet_4_hexes())]
        }
        GeneratedKind::Transitions => {
            let faces = transition_face_configurations()
                .into_iter()
                .map(|(stem, split)| (stem.to_string(), false, transition_face(split)));
            let volumes = transition_configurations().1.into_iter().map(|c| {
                (format!("transition-f{:02x}-e{:03x}", c.refined_faces, c.split_edges), true, transition_volume(c))
            });
            faces.chain(volumes).collect()
        }
    }
}

/// A generated set, ready to use.
///
/// # Errors
/// Only if a generator is broken (the tests check they are not).
pub fn generated_pattern_set(kind: GeneratedKind, rule: FlagRule) -> Result<PatternSet, PatternError> {
    let mut set = PatternSet::default();
    for (stem, _, mesh) in generated_pattern_meshes(kind) {
        let (map, _) = build_map(mesh, &BuildOptions { fix_orientation: true })
            .map_err(|e| PatternError::Invalid { path: PathBuf::from(&stem), msg: e.to_string() })?;
        set.insert(pattern_from_map(&PathBuf::from(format!("{}/{stem}", kind.name())), map, rule, &[])?);
    }
    Ok(set)
}

/// `given`, or else the generated set of `kind` (corner flags), kept in `slot`: for the
/// applications whose `--patterns` replaces a built-in set.
pub(crate) fn given_or_generated<'a>(
    given: Option<&'a PatternSet>,
    kind: GeneratedKind,
    slot: &'a mut Option<PatternSet>,
) -> &'a PatternSet {
    match given {
        Some(p) => p,
        None => slot
            .insert(generated_pattern_set(kind, FlagRule::Corners).expect("generated pattern sets are valid (tested)")),
    }
}
