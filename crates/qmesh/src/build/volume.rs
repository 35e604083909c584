//! Indexed volume cells → 3-map: one volume per cell, shared faces 3-sewn.

use rustc_hash::FxHashMap;

use super::error::BuildError;
use super::face_key::FaceKey;
use super::indexed::IndexedMesh;
use crate::cmap::{CMap3, Dart, Orbit};
use crate::geom::signed_volume_of_faces;

/// Options of [`build_volume_map`].
#[derive(Clone, Copy, Debug, Default)]
pub struct BuildOptions {
    /// Flip cells whose signed volume is negative instead of only counting them.
    pub fix_orientation: bool,
}

/// What the builder saw and did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildReport {
    /// Cells with negative signed volume in the input node order.
    pub inverted_cells: usize,
    /// Of those, how many were flipped (`fix_orientation`).
    pub flipped_cells: usize,
    /// Cells with zero volume.
    pub degenerate_cells: usize,
    /// Vertices touched by cells that share no face or edge there (non-manifold), which
    /// the map represents as several vertices.
    pub split_vertices: usize,
    /// Points that no cell uses.
    pub unreferenced_points: usize,
}

/// A face waiting for its partner: the cell it belongs to, its first dart, whether it is
/// already matched.
#[derive(Clone, Copy)]
struct OpenFace {
    cell: u32,
    dart: Dart,
    partner: Option<u32>,
}

/// Builds a volume map from the cells of `mesh`.
///
/// # Errors
/// A node index out of range, a cell that is not a closed manifold polyhedron, a face
/// shared by more than two cells, or two cells meeting with inconsistent orientation.
pub fn build_volume_map(mesh: &IndexedMesh, opts: &BuildOptions) -> Result<(CMap3, BuildReport), BuildError> {
    if mesh.nb_cells() == 0 {
        return Err(BuildError::Empty);
    }
    let mut report = BuildReport::default();
    let est_darts: usize = (0..mesh.nb_cells()).map(|i| mesh.offsets[i + 1] - mesh.offsets[i]).sum::<usize>() * 3;
    let mut map = CMap3::with_capacity(est_darts, mesh.points.len());
    for &p in &mesh.points {
        map.add_vertex(p);
    }
    let labelled = mesh.labels.iter().any(|&l| l != mesh.labels[0]);
    if labelled {
        map.enable_labels();
    }
    let mut used = vec![false; mesh.points.len()];
    let mut open: FxHashMap<FaceKey, OpenFace> = FxHashMap::default();
    open.reserve(est_darts / 6);
    for cell in 0..mesh.nb_cells() {
        let mut faces = mesh
            .cell_faces(cell)
            .ok_or_else(|| BuildError::BadCell { cell, reason: "malformed polyhedron face stream".into() })?;
        for &v in faces.iter().flatten() {
            if v as usize >= mesh.points.len() {
                return Err(BuildError::IndexOutOfRange { cell, index: v, points: mesh.points.len() });
            }
            used[v as usize] = true;
        }
        let vol = signed_volume_of_faces(&faces, &mesh.points);
        if vol < 0.0 {
            report.inverted_cells += 1;
            if opts.fix_orientation {
                faces.iter_mut().for_each(|f| f.reverse());
                report.flipped_cells += 1;
            }
        } else if vol == 0.0 {
            report.degenerate_cells += 1;
        }
        let firsts =
            map.make_polyhedron_faces(&faces).map_err(|e| BuildError::BadCell { cell, reason: e.to_string() })?;
        if labelled {
            let label = mesh.labels[cell];
            for d in map.orbit(firsts[0], Orbit::Volume) {
                map.set_label_of(d, label);
            }
        }
        for (f, &d) in faces.iter().zip(&firsts) {
            sew_or_register(&mut map, &mut open, cell, d, f)?;
        }
    }
    report.unreferenced_points = used.iter().filter(|u| !**u).count();
    report.split_vertices = split_shared_vertex_ids(&mut map);
    Ok((map, report))
}

/// 3-sews face `f` (first dart `d`) to its registered opposite, or registers it.
fn sew_or_register(
    map: &mut CMap3,
    open: &mut FxHashMap<FaceKey, OpenFace>,
    cell: usize,
    d: Dart,
    f: &[u32],
) -> Result<(), BuildError> {
    if let Some(other) = open.get_mut(&FaceKey::of(f, true)) {
        if let Some(b) = other.partner {
            let (a, b) = (other.cell as usize, b as usize);
            return Err(BuildError::FaceSharedByMoreThanTwo { face: f.to_vec(), a, b, c: cell });
        }
        other.partner = Some(cell as u32);
        let mut y = other.dart;
        // Partner of d runs target(d) → origin(d): find the dart of the other face
        // starting at target(d).
        let target = map.vertex_of(map.next(d));
        while map.vertex_of(y) != target {
            y = map.next(y);
        }
        let mut x = d;
        loop {
            map.link(x, 3, y);
            x = map.next(x);
            y = map.prev(y);
            if x == d {
                break;
            }
        }
        return Ok(());
    }
    let key = FaceKey::of(f, false);
    if let Some(same) = open.get(&key) {
        return Err(BuildError::InconsistentOrientation { face: f.to_vec(), a: same.cell as usize, b: cell });
    }
    open.insert(key, OpenFace { cell: cell as u32, dart: d, partner: None });
    Ok(())
}

/// Gives a fresh vertex id to every vertex orbit whose id another orbit already uses
/// (cells touching only at a vertex); returns how many were split.
fn split_shared_vertex_ids(map: &mut CMap3) -> usize {
    let reps: Vec<Dart> = map.cells(Orbit::Vertex).collect();
    let mut seen = vec![false; map.nb_vertex_ids()];
    let mut split = 0;
    for d in reps {
        let v = map.vertex_of(d) as usize;
        if !seen[v] {
            seen[v] = true;
            continue;
        }
        let fresh = map.add_vertex(map.position(v as u32));
        for x in map.orbit(d, Orbit::Vertex) {
            map.set_vertex_of(x, fresh);
        }
        split += 1;
    }
    split
}
