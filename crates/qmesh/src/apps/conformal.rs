//! Conformal transitions of a 2:1 octree hexahedral mesh (2022 Algorithm 7, §7.3):
//! hanging vertices inserted into the coarse cells' faces, faces with hanging vertices
//! query-replaced by face transitions, then the cells by volume transitions, giving
//! hexahedra, prisms, pyramids and tetrahedra with no hanging vertex.

use std::time::Instant;

use rayon::prelude::*;

use super::box_cells::{box_corner_darts, is_corner, walker_chunk};
use super::hanging::{HangingError, HangingReport, insert_hanging_vertices};
use crate::build::{
    BuildError, BuildOptions, CellKind, ExtractedKinds, IndexedMesh, build_map, classify_volume, count_kinds_of,
};
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
    let (replace, kinds) = transitions_on_map(&mut map, set, use_signatures, None, &mut phases)?;
    Ok((map, ConformalReport { hanging, replace, kinds, seconds: t.elapsed().as_secs_f64(), phases }))
}

/// The transitions of Algorithm 7 on a map whose volumes are axis-aligned boxes with
/// their hanging vertices already in place (the map [`conformal`] builds, or the map a
/// query-replace subdivision leaves, as the authors' program runs them): box corners
/// flagged, faces with more than four vertices and volumes with more than a plain
/// hexahedron's darts replaced. `volumes` names one dart of each volume, in increasing
/// order (by default the map's walk finds them). Fills `phases`' select, lookup, apply
/// and count.
///
/// # Errors
/// Only if the map has no free mark.
pub fn transitions_on_map(
    map: &mut CMap3,
    set: &PatternSet,
    use_signatures: bool,
    volumes: Option<&[Dart]>,
    phases: &mut ConformalPhases,
) -> Result<(ReplaceReport, ExtractedKinds), MapError> {
    let t = Instant::now();
    let flag = map.reserve_mark()?;
    // Whether each volume is more than a plain hexahedron (then it is replaced, with its
    // faces of more than four vertices, and its box corners are flagged) or else its
    // kind, found on all cores. Faces come by name (the smallest dart of both sides, the
    // dart `cells(Orbit::Face)` gives), so in the order of the map's faces.
    let walked: Vec<Dart>;
    let reps = match volumes {
        Some(v) => v,
        None => {
            walked = map.cells(Orbit::Volume).collect();
            &walked
        }
    };
    let shared = &*map;
    let found: Vec<Selected> = reps
        .par_chunks(walker_chunk(reps.len()))
        .map(|chunk| {
            let (mut w, mut out) = (OrbitWalker::new(), Selected::default());
            for &d in chunk {
                let darts = w.collect(shared, d, Orbit::Volume);
                if darts.len() == PLAIN_HEX_DARTS {
                    out.kept.add(classify_volume(shared, d));
                } else {
                    // Only the darts looked up need their flags: those of the volumes
                    // replaced, which hold both sides of every face replaced.
                    let b = Aabb::of(darts.iter().map(|&x| shared.point(x)));
                    out.corners.extend(box_corner_darts(shared, darts, &b));
                    out.volumes.push(d);
                    out.faces.extend(darts.iter().copied().filter(|&x| is_named_wide_face(shared, x)));
                }
            }
            out
        })
        .collect();
    let mut kinds = ExtractedKinds::default();
    let (mut volumes, mut faces) = (Vec::new(), Vec::new());
    for f in found {
        f.corners.iter().for_each(|&x| map.mark(x, flag));
        kinds = kinds.plus(&f.kept);
        volumes.extend(f.volumes);
        faces.extend(f.faces);
    }
    faces.sort_unstable();
    faces.dedup();
    phases.select = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let replace = replace_cells(map, set, Flags::Mark(flag), &faces, &volumes, use_signatures);
    map.free_mark(flag);
    (phases.lookup, phases.apply) = (replace.query_seconds, t.elapsed().as_secs_f64() - replace.query_seconds);
    // The cells that stay were classified above; a volume left unmatched has more than
    // a hexahedron's darts, so it is no standard cell; the rest are the created volumes.
    let t = Instant::now();
    let created: Vec<Dart> = replace.created_volumes.iter().map(|&(d, _)| d).collect();
    kinds = kinds.plus(&count_kinds_of(map, &created));
    kinds.other += replace.unmatched_volumes;
    phases.count = t.elapsed().as_secs_f64();
    Ok((replace, kinds))
}

/// What the selection of [`transitions_on_map`] finds in a run of volumes.
#[derive(Default)]
struct Selected {
    corners: Vec<Dart>,
    volumes: Vec<Dart>,
    faces: Vec<Dart>,
    /// The kinds of the volumes that are not replaced.
    kept: ExtractedKinds,
}

/// Whether `x` names a face of more than four vertices: the smallest dart of the face
/// and of the face across.
fn is_named_wide_face(map: &CMap3, x: Dart) -> bool {
    let mut degree = 0;
    for y in map.face_cycle(x) {
        degree += 1;
        if y < x || map.beta(y, 3).is_some_and(|o| o < x) {
            return false;
        }
    }
    degree > 4
}
