//! 3-map → indexed cells for writing: tet/pyramid/prism/hex recognised from their
//! topology (nodes put back in VTK order), any other volume as a VTK polyhedron.

use super::indexed::{CellKind, IndexedMesh};
use super::recognise::standard_cell;
use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};

/// Counts of the cell kinds found by [`extract`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
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

    /// The counts of both, kind by kind.
    pub fn plus(&self, o: &ExtractedKinds) -> ExtractedKinds {
        ExtractedKinds {
            tet: self.tet + o.tet,
            pyramid: self.pyramid + o.pyramid,
            prism: self.prism + o.prism,
            hex: self.hex + o.hex,
            other: self.other + o.other,
        }
    }
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
    match standard_cell(map, d) {
        Some((kind, nodes)) => (kind.into(), nodes[..kind.nodes()].to_vec()),
        None => polyhedron_stream(map, d, walker),
    }
}

/// The VTK polyhedron face stream of any volume (faces reversed to point outward).
pub fn polyhedron_stream(map: &CMap3, d: Dart, walker: &mut OrbitWalker) -> (CellKind, Vec<u32>) {
    let darts: Vec<Dart> = walker.collect(map, d, Orbit::Volume).to_vec();
    let mut in_face = rustc_hash::FxHashSet::default();
    let mut stream = vec![0u32];
    for &x in &darts {
        if in_face.insert(x) {
            let n = map.face_degree(x);
            let c = cycle(map, x, n);
            c.iter().skip(1).for_each(|&y| {
                in_face.insert(y);
            });
            stream[0] += 1;
            stream.push(n as u32);
            stream.extend(c.iter().rev().map(|&y| map.vertex_of(y)));
        }
    }
    (CellKind::Polyhedron, stream)
}

/// How many volumes of each kind the map holds.
///
/// Volumes are classified in parallel (rayon) once their representatives are known.
pub fn count_cell_kinds(map: &CMap3) -> ExtractedKinds {
    if map.dimension() != 3 {
        return ExtractedKinds::default();
    }
    let reps: Vec<Dart> = map.cells(Orbit::Volume).collect();
    count_kinds_of(map, &reps)
}

/// Kinds of the volumes of the given representative darts (one per volume), classified
/// in parallel.
pub fn count_kinds_of(map: &CMap3, reps: &[Dart]) -> ExtractedKinds {
    use rayon::prelude::*;
    if map.dimension() != 3 {
        return ExtractedKinds::default();
    }
    reps.par_chunks(4096)
        .map(|chunk| {
            let mut kinds = ExtractedKinds::default();
            chunk.iter().for_each(|&d| kinds.add(classify_volume(map, d)));
            kinds
        })
        .reduce(ExtractedKinds::default, |a, b| a.plus(&b))
}

/// The kind of the volume of `d` (as [`recognise_volume`], without building its node
/// list or face stream).
pub fn classify_volume(map: &CMap3, d: Dart) -> CellKind {
    standard_cell(map, d).map_or(CellKind::Polyhedron, |(kind, _)| kind.into())
}

/// A per-cell array in [`extract`]'s cell order: `value` of the volumes holding the
/// given darts, `default` for the others (e.g. `pattern_id` from the replacements'
/// created volumes, −1 where no pattern applied).
pub fn volume_values(map: &CMap3, tagged: &[(Dart, u32)], default: i32) -> Vec<i32> {
    let mut tag = vec![default; map.dart_capacity()];
    let mut walker = OrbitWalker::new();
    for &(d, v) in tagged {
        if map.is_live(d) {
            for &x in walker.collect(map, d, Orbit::Volume) {
                tag[x.idx()] = v as i32;
            }
        }
    }
    map.cells(Orbit::Volume).map(|d| tag[d.idx()]).collect()
}

/// Indexed cells of every volume of a volume map (labels kept when the map has them),
/// or the polygons of a surface map. Points are the vertex ids in use, renumbered in
/// increasing id order.
pub fn extract(map: &CMap3) -> (IndexedMesh, ExtractedKinds) {
    extract_with(map, polyhedron_stream)
}

/// As [`extract`], with `other(map, d, walker)` giving the cell of each volume that is
/// not a standard cell (default: its polyhedron stream).
pub fn extract_with(
    map: &CMap3,
    other: impl FnMut(&CMap3, Dart, &mut OrbitWalker) -> (CellKind, Vec<u32>),
) -> (IndexedMesh, ExtractedKinds) {
    extract_cells(map, other, false)
}

/// As [`extract`], keeping the points that no cell uses (a file's unreferenced points,
/// which [`extract`] drops), in their order: `qmesh convert` loses nothing.
pub fn extract_all_points(map: &CMap3) -> (IndexedMesh, ExtractedKinds) {
    extract_cells(map, polyhedron_stream, true)
}

fn extract_cells(
    map: &CMap3,
    mut other: impl FnMut(&CMap3, Dart, &mut OrbitWalker) -> (CellKind, Vec<u32>),
    keep_unused_points: bool,
) -> (IndexedMesh, ExtractedKinds) {
    let mut out = IndexedMesh::new();
    let mut kinds = ExtractedKinds::default();
    let mut walker = OrbitWalker::new();
    let mut cells: Vec<(CellKind, Vec<u32>, i32)> = Vec::new();
    let mut polys: Vec<Vec<u32>> = Vec::new();
    if map.dimension() == 3 {
        for d in map.cells(Orbit::Volume) {
            let (k, nodes) = match standard_cell(map, d) {
                Some((kind, nodes)) => (kind.into(), nodes[..kind.nodes()].to_vec()),
                None => other(map, d, &mut walker),
            };
            kinds.add(k);
            cells.push((k, nodes, map.label_of(d)));
        }
    } else {
        for d in map.cells(Orbit::HalfFace) {
            polys.push(cycle(map, d, map.face_degree(d)).iter().map(|&x| map.vertex_of(x)).collect());
        }
    }
    let mut newid = vec![u32::MAX; map.nb_vertex_ids()];
    let mut used = vec![keep_unused_points; map.nb_vertex_ids()];
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
        let mut p: Vec<u32> = cycle(map, d, map.face_degree(d)).iter().map(|&x| map.vertex_of(x)).collect();
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
