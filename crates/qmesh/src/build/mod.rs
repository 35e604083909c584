//! Builders between indexed meshes (what files hold) and combinatorial maps.
//!
//! [`build_volume_map`] creates one volume per cell and 3-sews cells sharing a face
//! (matched by vertex cycles in a hash map); [`build_surface_map`] 2-sews polygons
//! along opposite half-edges; [`extract`](fn@extract) goes back to indexed cells for writing.

mod adjacency;
mod boundary;
mod conformity;
mod error;
mod extract;
mod half_edges;
mod indexed;
mod quality;
mod recognise;
mod surface;
mod surface_topology;
mod volume;

pub use conformity::{non_conformal_faces, non_conformal_faces_of};
pub use error::{BuildError, Subject};
pub use extract::{
    ExtractedKinds, boundary_polygons, classify_volume, count_cell_kinds, count_kinds_of, extract, extract_all_points,
    extract_with, polyhedron_stream, recognise_volume, volume_values,
};
pub use half_edges::HalfEdges;
pub use indexed::{CellArray, CellKind, CellValues, HEX_CORNER_BITS, IndexedMesh};
pub use quality::{
    QualityByKind, QualitySummary, cell_scaled_jacobian, quality_by_kind, scaled_jacobians, tangled_cells,
};
pub use recognise::{StandardNodes, standard_cell};
pub use surface::build_surface_map;
pub use surface_topology::{SurfaceTopology, surface_topology};
pub use volume::{BuildOptions, BuildReport, build_volume_map, build_volume_map_owned};

use crate::cmap::CMap3;

/// Builds a volume map when the mesh has volume cells, a surface map otherwise.
pub fn build_map(mesh: IndexedMesh, opts: &BuildOptions) -> Result<(CMap3, BuildReport), BuildError> {
    if mesh.is_volume() { build_volume_map_owned(mesh, opts) } else { build_surface_map(&mesh) }
}
