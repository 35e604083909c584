//! The census of a loaded mesh (`qmesh info`).

use std::path::Path;

use serde::Serialize;

use crate::build::{count_kinds_of, extract, non_conformal_faces_of, tangled_cells};
use crate::io::LoadedMap;

/// Volumes by cell type.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct CellTypeCounts {
    pub tet: usize,
    pub pyramid: usize,
    pub prism: usize,
    pub hex: usize,
    pub other: usize,
}

/// Counts, conformity, geometric defects and validity of a loaded mesh, with the
/// reading and building times.
#[derive(Clone, Debug, Serialize)]
pub struct InfoReport {
    pub file: String,
    /// 3 for a volume map, 2 for a surface.
    pub dimension: u8,
    pub darts: usize,
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub volumes: usize,
    pub boundary_faces: usize,
    /// Boundary edges of a surface (absent for volume maps).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub boundary_edges: Option<usize>,
    pub euler_characteristic: i64,
    pub components: usize,
    pub cell_types: CellTypeCounts,
    pub non_conformal_faces: usize,
    pub conformity_seconds: f64,
    /// Negative signed volume in the file's node order …
    pub inverted_cells: usize,
    /// … of which reversed on reading (`fix_orientation`).
    pub flipped_cells: usize,
    pub degenerate_cells: usize,
    /// Positive volume but a negative corner Jacobian.
    pub tangled_cells: usize,
    pub split_nonmanifold_vertices: usize,
    pub unreferenced_points: usize,
    pub valid: bool,
    pub violations: usize,
    pub map_bytes: usize,
    pub bytes_per_dart: usize,
    pub warnings: Vec<String>,
    pub read_seconds: f64,
    pub build_seconds: f64,
}

impl InfoReport {
    /// The report of `loaded`, read from `file`.
    pub fn of(file: &Path, loaded: &LoadedMap) -> InfoReport {
        let map = &loaded.map;
        let census = map.census();
        let c = &census.counts;
        let surface = map.dimension() == 2;
        let kinds = count_kinds_of(map, &census.volume_reps);
        let t = std::time::Instant::now();
        let non_conformal_faces = if surface { 0 } else { non_conformal_faces_of(map, &census.boundary_reps) };
        let conformity_seconds = t.elapsed().as_secs_f64();
        let r = &loaded.report;
        InfoReport {
            file: file.display().to_string(),
            dimension: map.dimension(),
            darts: c.darts,
            vertices: c.vertices,
            edges: c.edges,
            faces: c.faces,
            volumes: if surface { 0 } else { c.volumes },
            boundary_faces: if surface { 0 } else { c.boundary_faces },
            boundary_edges: surface.then(|| map.boundary_edges()),
            euler_characteristic: c.euler_characteristic(map.dimension()),
            components: c.components,
            cell_types: CellTypeCounts {
                tet: kinds.tet,
                pyramid: kinds.pyramid,
                prism: kinds.prism,
                hex: kinds.hex,
                other: kinds.other,
            },
            non_conformal_faces,
            conformity_seconds,
            inverted_cells: r.inverted_cells,
            flipped_cells: r.flipped_cells,
            degenerate_cells: r.degenerate_cells,
            tangled_cells: if surface { 0 } else { tangled_cells(&extract(map).0) },
            split_nonmanifold_vertices: r.split_vertices,
            unreferenced_points: r.unreferenced_points,
            valid: census.violations.is_empty(),
            violations: census.violations.len(),
            map_bytes: map.heap_bytes(),
            bytes_per_dart: map.bytes_per_dart(),
            warnings: loaded.warnings.clone(),
            read_seconds: loaded.read_seconds,
            build_seconds: loaded.build_seconds,
        }
    }
}
