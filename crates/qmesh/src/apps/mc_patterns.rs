//! Marching-cubes patterns (2022 §7.2), generated for all 256 corner configurations.
//!
//! Flags mark the darts starting at *inside* corners, so a pattern knows which side is
//! which. Edges with one inside and one outside corner are split at their middle.
//! A face is cut by one segment between its two split edges; when all four are split
//! (two inside corners on a diagonal: the ambiguous face) each inside corner is cut off
//! alone — inside corners are never joined across a face. Both neighbours of a face
//! see the same cut, so the surface is closed. Inside the cube, the cuts on its faces
//! close into cycles; each cycle bounds one polygon of the surface (a disc, never a
//! tunnel), and the cube splits into one volume per region between them.

use rustc_hash::FxHashMap;

use super::cube::{corner, edge_index, faces, rotations};
use crate::build::{BuildOptions, CellKind, IndexedMesh, build_map};
use crate::cmap::{CMap3, Dart};
use crate::disjoint_sets::DisjointSets;
use crate::pattern::{FlagRule, PatternSet, pattern_from_map};
use std::path::PathBuf;

/// A point of a pattern: a corner (0..8) or the middle of a cube edge (8 + edge).
type Node = u8;

fn position(n: Node) -> [f64; 3] {
    if n < 8 {
        return corner(n);
    }
    let (a, b) = super::cube::edges()[usize::from(n - 8)];
    let (p, q) = (corner(a), corner(b));
    [0, 1, 2].map(|k| (p[k] + q[k]) / 2.0)
}

/// Cuts polygon `poly` along the chord between its vertices `a` and `b`.
fn cut(poly: &[Node], a: Node, b: Node) -> (Vec<Node>, Vec<Node>) {
    let n = poly.len();
    let (ia, ib) = (poly.iter().position(|&x| x == a), poly.iter().position(|&x| x == b));
    let (ia, ib) = (ia.expect("chord end on the polygon"), ib.expect("chord end on the polygon"));
    let walk = |from: usize, to: usize| {
        let mut v = vec![poly[from]];
        let mut i = from;
        while i != to {
            i = (i + 1) % n;
            v.push(poly[i]);
        }
        v
    };
    (walk(ia, ib), walk(ib, ia))
}

/// The pieces (outward polygons) of a face given as its outward corner cycle, for the
/// inside corners `inside` (bit c = corner c inside).
pub(crate) fn face_pieces(cycle: [u8; 4], inside: u8) -> Vec<Vec<Node>> {
    let is_in = |c: u8| inside >> c & 1 == 1;
    let split: Vec<usize> = (0..4).filter(|&i| is_in(cycle[i]) != is_in(cycle[(i + 1) % 4])).collect();
    let mid = |i: usize| 8 + edge_index(cycle[i], cycle[(i + 1) % 4]) as u8;
    let ring: Vec<Node> =
        (0..4).flat_map(|i| std::iter::once(cycle[i]).chain(split.contains(&i).then(|| mid(i)))).collect();
    let chords: Vec<(Node, Node)> = match split.len() {
        2 => vec![(mid(split[0]), mid(split[1]))],
        4 => (0..4).filter(|&k| is_in(cycle[k])).map(|k| (mid((k + 3) % 4), mid(k))).collect(),
        _ => Vec::new(),
    };
    let mut pieces = vec![ring];
    for (a, b) in chords {
        let i = pieces.iter().position(|p| p.contains(&a) && p.contains(&b)).expect("chords do not cross");
        let (p, q) = cut(&pieces.swap_remove(i), a, b);
        pieces.extend([p, q]);
    }
    pieces
}

/// The v-pattern of inside-corner set `inside` (neither empty nor full): one
/// polyhedron per region, as VTK face streams over nodes.
fn volume_regions(inside: u8) -> Vec<Vec<Vec<Node>>> {
    let pieces: Vec<Vec<Node>> = faces().iter().flat_map(|&f| face_pieces(f, inside)).collect();
    // Regions: corners joined when they share a piece.
    let mut corners = DisjointSets::new(8);
    for piece in &pieces {
        let cs: Vec<u8> = piece.iter().copied().filter(|&n| n < 8).collect();
        for w in cs.windows(2) {
            corners.union(u32::from(w[0]), u32::from(w[1]));
        }
    }
    let mut regions: Vec<u8> = (0..8).map(|c| corners.find(c) as u8).collect();
    regions.sort_unstable();
    regions.dedup();
    regions
        .iter()
        .map(|&r| {
            let mut faces: Vec<Vec<Node>> = Vec::new();
            // Chords reversed: the region's surface polygons run against its pieces.
            let mut next: FxHashMap<Node, Node> = FxHashMap::default();
            for piece in pieces.iter().filter(|p| p.iter().any(|&n| n < 8 && corners.find(u32::from(n)) as u8 == r)) {
                faces.push(piece.clone());
                for i in 0..piece.len() {
                    let (p, q) = (piece[i], piece[(i + 1) % piece.len()]);
                    if p >= 8 && q >= 8 {
                        next.insert(q, p);
                    }
                }
            }
            while let Some(&start) = next.keys().min() {
                let mut poly = vec![start];
                let mut x = next.remove(&start).expect("key present");
                while x != start {
                    poly.push(x);
                    x = next.remove(&x).expect("chords close into cycles");
                }
                faces.push(poly);
            }
            faces
        })
        .collect()
}

/// Polyhedra (or a polygon set for a face) over nodes → indexed mesh, with the points
/// of the nodes used; returns the mesh and each point's node.
fn mesh_of(cells: &[Vec<Vec<Node>>], polygons: &[Vec<Node>]) -> (IndexedMesh, Vec<Node>) {
    let mut mesh = IndexedMesh::new();
    let mut id: FxHashMap<Node, u32> = FxHashMap::default();
    let mut nodes = Vec::new();
    let mut point = |mesh: &mut IndexedMesh, n: Node| {
        *id.entry(n).or_insert_with(|| {
            mesh.points.push(position(n));
            nodes.push(n);
            (mesh.points.len() - 1) as u32
        })
    };
    for cell in cells {
        let mut stream = vec![cell.len() as u32];
        for f in cell {
            stream.push(f.len() as u32);
            for &n in f {
                let p = point(&mut mesh, n);
                stream.push(p);
            }
        }
        mesh.push_cell(CellKind::Polyhedron, &stream, None);
    }
    for poly in polygons {
        let ids: Vec<u32> = poly.iter().map(|&n| point(&mut mesh, n)).collect();
        mesh.push_polygon(&ids);
    }
    (mesh, nodes)
}

/// A pattern map with its flagged darts (those starting at inside corners).
fn flagged_map(mesh: IndexedMesh, nodes: &[Node], inside: u8) -> (CMap3, Vec<Dart>) {
    let (map, _) = build_map(mesh, &BuildOptions { fix_orientation: true }).expect("generated pattern builds");
    let flags = map
        .darts()
        .filter(|&d| nodes.get(map.vertex_of(d) as usize).is_some_and(|&n| n < 8 && inside >> n & 1 == 1))
        .collect();
    (map, flags)
}

/// The f-patterns: one per class of inside corners of a square under rotation
/// (1, 2 adjacent, 2 opposite, 3), on the cube's bottom face; (name, map, flags).
pub fn mc_face_patterns() -> Vec<(String, CMap3, Vec<Dart>)> {
    let bottom = faces()[4]; // z = 0, outward (downward)
    let cycle: [u8; 4] = [bottom[0], bottom[3], bottom[2], bottom[1]]; // upward: counter-clockwise from +z
    [
        ("mc-face-1-inside", 0b0001u8),
        ("mc-face-2-adjacent", 0b0011),
        ("mc-face-2-opposite", 0b0101),
        ("mc-face-3-inside", 0b0111),
    ]
    .into_iter()
    .map(|(name, bits)| {
        let inside = (0..4).filter(|&i| bits >> i & 1 == 1).fold(0u8, |m, i| m | 1 << cycle[i]);
        let (mesh, nodes) = mesh_of(&[], &face_pieces(cycle, inside));
        let (map, flags) = flagged_map(mesh, &nodes, inside);
        (name.to_string(), map, flags)
    })
    .collect()
}

/// The v-patterns: one per class of the 254 non-trivial corner sets under the 24
/// rotations; (name, map, flags).
pub fn mc_volume_patterns() -> Vec<(String, CMap3, Vec<Dart>)> {
    let rots = rotations();
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for inside in 1..255u8 {
        let canonical = rots
            .iter()
            .map(|r| (0..8).filter(|&c| inside >> c & 1 == 1).fold(0u8, |m, c| m | 1 << r[c as usize]))
            .min()
            .expect("24 rotations");
        if seen.insert(canonical) {
            let (mesh, nodes) = mesh_of(&volume_regions(canonical), &[]);
            let (map, flags) = flagged_map(mesh, &nodes, canonical);
            out.push((format!("mc-cube-{canonical:02x}"), map, flags));
        }
    }
    out
}

/// The marching-cubes pattern set (flags read from the generator: inside corners).
pub fn mc_pattern_set() -> PatternSet {
    let mut set = PatternSet::default();
    for (name, map, flags) in mc_face_patterns().into_iter().chain(mc_volume_patterns()) {
        let p = pattern_from_map(&PathBuf::from(format!("marching-cubes/{name}")), map, FlagRule::File, &flags)
            .expect("generated marching-cubes patterns are valid (tested)");
        set.insert(p);
    }
    set
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ambiguous_face_cuts_off_each_inside_corner() {
        let f = faces()[4];
        let pieces = face_pieces(f, 1 << f[0] | 1 << f[2]);
        let mut sizes: Vec<usize> = pieces.iter().map(Vec::len).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, vec![3, 3, 6]);
    }

    #[test]
    fn one_inside_corner_gives_a_triangle_between_two_regions() {
        let regions = volume_regions(1);
        assert_eq!(regions.len(), 2);
        let triangles = regions.iter().flatten().filter(|f| f.iter().all(|&n| n >= 8)).count();
        assert_eq!(triangles, 2, "the surface triangle, once from each side");
    }
}
