//! Conformal transitions of a 2:1 octree hexahedral mesh (2022 Algorithm 7, §7.3):
//! hanging vertices inserted into the coarse cells' faces, faces with hanging vertices
//! query-replaced by face transitions, then the cells by volume transitions, giving
//! hexahedra, prisms, pyramids and tetrahedra with no hanging vertex.

use std::time::Instant;

use rayon::prelude::*;

use super::box_cells::{box_corner_darts, is_corner, walker_chunk};
use super::hanging::{HangingError, HangingReport, insert_hanging_vertices};
use crate::build::{BuildError, BuildOptions, CellKind, ExtractedKinds, IndexedMesh, build_map, count_cell_kinds};
use crate::cmap::{CMap3, Dart, MapError, Orbit, OrbitWalker};
use crate::geom::Aabb;
use crate::pattern::PatternSet;
use crate::replace::{ReplaceReport, replace_cells};
use crate::signature::Flags;

/// Why the conformal pipeline stopped.
#[derive(Debug, thiserror::Error)]
pub enum ConformalError {
    #[error(
        "cell {cell} is not an axis-aligned box hexahedron: conformal transitions need an octree mesh (e.g. from `qmesh subdivide`)"
    )]
    NotOctree { cell: usize },
    #[error(transparent)]
    Hanging(#[from] HangingError),
    #[error("the mesh with its hanging vertices does not build: {0}")]
    Build(#[from] BuildError),
    #[error(transparent)]
    Map(#[from] MapError),
}

/// What [`conformal`] did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct ConformalReport {
    pub hanging: HangingReport,
    pub replace: ReplaceReport,
    pub kinds: ExtractedKinds,
    pub seconds: f64,
    /// Where the time went (seconds): the hanging vertices inserted, the map built, the
    /// box corners flagged and the cells to replace chosen, the patterns looked up and
    /// applied, the cells counted.
    pub phases: ConformalPhases,
}

/// The phases of [`conformal`] (seconds).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct ConformalPhases {
    pub hanging: f64,
    pub build: f64,
    pub select: f64,
    pub lookup: f64,
    pub apply: f64,
    pub count: f64,
}

impl ConformalPhases {
    /// The phases by name, in order.
    pub fn list(&self) -> [(&'static str, f64); 6] {
        [
            ("hanging", self.hanging),
            ("build", self.build),
            ("select", self.select),
            ("lookup", self.lookup),
            ("apply", self.apply),
            ("count", self.count),
        ]
    }
}

/// Whether cell `c` is an axis-aligned box: a hexahedron whose 8 nodes are the corners
/// of its bounding box, or a polyhedron with those 8 corners among its nodes (a box
/// whose hanging vertices are already inserted).
fn is_box_cell(mesh: &IndexedMesh, c: usize) -> bool {
    let nodes: Vec<u32> = match mesh.cell(c).0 {
        CellKind::Hex => mesh.cell(c).1.to_vec(),
        CellKind::Polyhedron => mesh.cell_faces(c).unwrap_or_default().into_iter().flatten().collect(),
        _ => return false,
    };
    let b = Aabb::of(nodes.iter().map(|&v| mesh.points[v as usize]));
    let centre = b.centre();
    let mut corners: Vec<u32> = nodes
        .iter()
        .map(|&v| mesh.points[v as usize])
        .filter(|&p| is_corner(&b, p))
        .map(|p| (0..3).fold(0, |m, k| m | u32::from(p[k] > centre[k]) << k))
        .collect();
    corners.sort_unstable();
    corners.dedup();
    corners.len() == 8
        && (mesh.cell(c).0 != CellKind::Hex || nodes.iter().all(|&v| is_corner(&b, mesh.points[v as usize])))
}

/// Darts per volume of a plain hexahedron (6 quadrilaterals).
const PLAIN_HEX_DARTS: usize = 24;

/// Runs Algorithm 7 on a hexahedral mesh with hanging vertices, with the face and
/// volume transitions of `set` (the papers' square-5 + 325 patterns, or qmesh's
/// generated `transitions`). Faces and cells without hanging vertices are left alone.
///
/// # Errors
/// A mesh that is not 2:1 balanced, does not build, or exhausts the map's marks.
pub fn conformal(
    mesh: &IndexedMesh,
    set: &PatternSet,
    use_signatures: bool,
) -> Result<(CMap3, ConformalReport), ConformalError> {
    let t = Instant::now();
    if let Some(cell) = (0..mesh.nb_cells()).find(|&c| !is_box_cell(mesh, c)) {
        return Err(ConformalError::NotOctree { cell });
    }
    let mut phases = ConformalPhases::default();
    let mut lap = {
        let mut last = Instant::now();
        move || {
            let now = Instant::now();
            let s = (now - last).as_secs_f64();
            last = now;
            s
        }
    };
    let (cells, hanging) = insert_hanging_vertices(mesh)?;
    phases.hanging = lap();
    let (mut map, _) = build_map(cells, &BuildOptions { fix_orientation: true })?;
    phases.build = lap();
    let flag = map.reserve_mark()?;
    // Each volume's box corners, and whether it is more than a plain hexahedron (then it
    // is replaced), found on all cores; then flagged.
    let reps: Vec<Dart> = map.cells(Orbit::Volume).collect();
    let (corners, volumes): (Vec<Vec<Dart>>, Vec<Vec<Dart>>) = reps
        .par_chunks(walker_chunk(reps.len()))
        .map(|chunk| {
            let (mut w, mut corners, mut volumes) = (OrbitWalker::new(), Vec::new(), Vec::new());
            for &d in chunk {
                let darts = w.collect(&map, d, Orbit::Volume);
                let b = Aabb::of(darts.iter().map(|&x| map.point(x)));
                corners.extend(box_corner_darts(&map, darts, &b));
                if darts.len() != PLAIN_HEX_DARTS {
                    volumes.push(d);
                }
            }
            (corners, volumes)
        })
        .unzip();
    for x in corners.into_iter().flatten() {
        map.mark(x, flag);
    }
    let volumes = volumes.concat();
    let faces: Vec<Dart> = map.cells(Orbit::Face).filter(|&d| map.face_degree(d) > 4).collect();
    phases.select = lap();
    let replace = replace_cells(&mut map, set, Flags::Mark(flag), &faces, &volumes, use_signatures);
    map.free_mark(flag);
    (phases.lookup, phases.apply) = (replace.query_seconds, lap() - replace.query_seconds);
    let kinds = count_cell_kinds(&map);
    phases.count = lap();
    Ok((map, ConformalReport { hanging, replace, kinds, seconds: t.elapsed().as_secs_f64(), phases }))
}
