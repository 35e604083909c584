//! Hanging vertices of a 2:1 octree written as plain hexahedra (the output of
//! `subdivide`): each hexahedron gets the vertices lying at its edge midpoints and face
//! centres inserted into its faces, so that the map built from it sews every fine face
//! to the matching part of the coarse face (2022 Algorithm 7, first step).

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use crate::build::{CellKind, IndexedMesh};

/// What [`insert_hanging_vertices`] found.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct HangingReport {
    /// Distinct vertices lying on another cell's edge or face.
    pub hanging_vertices: usize,
    /// Hexahedra that became polyhedra.
    pub cells_with_hanging: usize,
}

/// Why a mesh is not a 2:1 octree mesh.
#[derive(Debug, thiserror::Error)]
pub enum HangingError {
    #[error("cell {cell}: a vertex lies at a quarter of its edge {a}–{b}: the mesh is not 2:1 balanced")]
    Unbalanced { cell: usize, a: u32, b: u32 },
    #[error("cell {cell} has a zero-length edge")]
    Degenerate { cell: usize },
}

/// Points looked up by position on a lattice finer than any edge: two points closer
/// than a quarter of the shortest hexahedron edge are the same.
struct PointIndex {
    lo: [f64; 3],
    unit: f64,
    ids: FxHashMap<[i64; 3], u32>,
}

impl PointIndex {
    fn new(points: &[[f64; 3]], shortest_edge: f64) -> PointIndex {
        let lo = points.iter().fold([f64::INFINITY; 3], |a, p| [0, 1, 2].map(|k| a[k].min(p[k])));
        let mut idx = PointIndex { lo, unit: shortest_edge / 4.0, ids: FxHashMap::default() };
        for (i, &p) in points.iter().enumerate() {
            idx.ids.entry(idx.key(p)).or_insert(i as u32);
        }
        idx
    }

    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        [0, 1, 2].map(|k| ((p[k] - self.lo[k]) / self.unit).round() as i64)
    }

    fn at(&self, p: [f64; 3]) -> Option<u32> {
        self.ids.get(&self.key(p)).copied()
    }
}

/// Cells rewritten by one core: their kinds, labels and nodes (polyhedron streams), the
/// hanging vertices met.
struct Rewritten {
    kinds: Vec<(CellKind, Option<i32>)>,
    offsets: Vec<usize>,
    nodes: Vec<u32>,
    hanging: Vec<u32>,
    polyhedra: usize,
}

impl Default for Rewritten {
    fn default() -> Self {
        Rewritten { kinds: Vec::new(), offsets: vec![0], nodes: Vec::new(), hanging: Vec::new(), polyhedra: 0 }
    }
}

impl Rewritten {
    /// Appends cell `c` of `mesh`: a hexahedron with vertices on its edges or at its
    /// face centres becomes a polyhedron whose faces hold them.
    fn cell(&mut self, mesh: &IndexedMesh, index: &PointIndex, c: usize) -> Result<(), HangingError> {
        let (kind, n) = mesh.cell(c);
        let label = mesh.label(c);
        if kind != CellKind::Hex {
            self.push(kind, label, n);
            return Ok(());
        }
        let p = |v: u32| mesh.points[v as usize];
        let mut stream: Vec<u32> = vec![0];
        let mut nb_faces = 0;
        let mut changed = false;
        for f in CellKind::Hex.face_table() {
            // The table gives map (inward) order; polyhedron faces are outward.
            let corners: Vec<u32> = f.iter().rev().map(|&k| n[k]).collect();
            let mids: Vec<Option<u32>> = (0..4)
                .map(|i| {
                    let (a, b) = (corners[i], corners[(i + 1) % 4]);
                    if index.at(lerp(p(a), p(b), 0.25)).is_some() || index.at(lerp(p(a), p(b), 0.75)).is_some() {
                        return Err(HangingError::Unbalanced { cell: c, a, b });
                    }
                    Ok(index.at(lerp(p(a), p(b), 0.5)))
                })
                .collect::<Result<_, _>>()?;
            // (a centre is only used when the four edges are split)
            let all_split = mids.iter().all(Option::is_some);
            let centre = all_split
                .then(|| {
                    index.at(lerp(
                        lerp(p(corners[0]), p(corners[1]), 0.5),
                        lerp(p(corners[3]), p(corners[2]), 0.5),
                        0.5,
                    ))
                })
                .flatten();
            let mut polys: Vec<Vec<u32>> = Vec::new();
            match (centre, all_split) {
                (Some(z), true) => {
                    for i in 0..4 {
                        let (m, prev) = (mids[i].unwrap_or(0), mids[(i + 3) % 4].unwrap_or(0));
                        polys.push(vec![corners[i], m, z, prev]);
                    }
                    self.hanging.push(z);
                }
                _ => polys.push((0..4).flat_map(|i| std::iter::once(corners[i]).chain(mids[i])).collect()),
            }
            self.hanging.extend(mids.iter().flatten());
            changed |= polys.len() > 1 || polys[0].len() > 4;
            for poly in polys {
                stream.push(poly.len() as u32);
                stream.extend(poly);
                nb_faces += 1;
            }
        }
        if changed {
            stream[0] = nb_faces;
            self.push(CellKind::Polyhedron, label, &stream);
            self.polyhedra += 1;
        } else {
            self.push(kind, label, n);
        }
        Ok(())
    }

    fn push(&mut self, kind: CellKind, label: Option<i32>, nodes: &[u32]) {
        self.kinds.push((kind, label));
        self.nodes.extend_from_slice(nodes);
        self.offsets.push(self.nodes.len());
    }
}

fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]))
}

/// The mesh with every hexahedron that has hanging vertices turned into a polyhedron
/// whose faces contain them: a face whose centre is a vertex becomes 4 quadrilaterals,
/// any other face gets the vertices at its edge midpoints. Other cells, labels and
/// cell arrays are kept in order.
///
/// # Errors
/// A vertex at a quarter of an edge (2:1 balance broken) or a zero-length edge.
pub fn insert_hanging_vertices(mesh: &IndexedMesh) -> Result<(IndexedMesh, HangingReport), HangingError> {
    let faces_in = CellKind::Hex.face_table();
    let mut shortest = f64::INFINITY;
    for c in (0..mesh.nb_cells()).filter(|&c| mesh.kinds[c] == CellKind::Hex) {
        let n = mesh.cell(c).1;
        for f in faces_in {
            for i in 0..4 {
                let (a, b) = (mesh.points[n[f[i]] as usize], mesh.points[n[f[(i + 1) % 4]] as usize]);
                let len = crate::geom::dot(crate::geom::sub(a, b), crate::geom::sub(a, b)).sqrt();
                if len == 0.0 {
                    return Err(HangingError::Degenerate { cell: c });
                }
                shortest = shortest.min(len);
            }
        }
    }
    let mut out = IndexedMesh { points: mesh.points.clone(), ..IndexedMesh::new() };
    let mut report = HangingReport::default();
    if !shortest.is_finite() {
        out.clone_from(mesh);
        return Ok((out, report));
    }
    let index = PointIndex::new(&mesh.points, shortest);
    // Cells are rewritten on all cores, a run at a time, and appended in order.
    let runs: Vec<Result<Rewritten, HangingError>> = (0..mesh.nb_cells())
        .collect::<Vec<_>>()
        .par_chunks(4096)
        .map(|cells| {
            let mut run = Rewritten::default();
            for &c in cells {
                run.cell(mesh, &index, c)?;
            }
            Ok(run)
        })
        .collect();
    let mut hanging = vec![false; mesh.points.len()];
    for run in runs {
        let run = run?;
        for (k, &(kind, label)) in run.kinds.iter().enumerate() {
            out.push_cell(kind, &run.nodes[run.offsets[k]..run.offsets[k + 1]], label);
        }
        for v in run.hanging {
            hanging[v as usize] = true;
        }
        report.cells_with_hanging += run.polyhedra;
    }
    report.hanging_vertices = hanging.iter().filter(|&&h| h).count();
    out.cell_arrays = mesh.cell_arrays.clone();
    Ok((out, report))
}
