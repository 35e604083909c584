//! Scaled Jacobian per cell kind of an indexed mesh, summarised the way Verdict and
//! ParaView users read it: min, mean, max, a 10-bin histogram over [−1, 1], the
//! counts ≤ 0 and < 0.5.

use super::indexed::{CellKind, IndexedMesh};
use crate::geom::{hex_scaled_jacobian, prism_scaled_jacobian, pyramid_scaled_jacobian, tet_scaled_jacobian};

/// Scaled Jacobian of cell `i`, or None for a polyhedron.
pub fn cell_scaled_jacobian(mesh: &IndexedMesh, i: usize) -> Option<f64> {
    let (kind, nodes) = mesh.cell(i);
    let p = |k: usize| mesh.points[nodes[k] as usize];
    Some(match kind {
        CellKind::Hex => hex_scaled_jacobian(&std::array::from_fn(p)),
        CellKind::Tet => tet_scaled_jacobian(&std::array::from_fn(p)),
        CellKind::Prism => prism_scaled_jacobian(&std::array::from_fn(p)),
        CellKind::Pyramid => pyramid_scaled_jacobian(&std::array::from_fn(p)),
        CellKind::Polyhedron => return None,
    })
}

/// Every cell's scaled Jacobian, 0 for polyhedra (as Verdict reports them), for the
/// `scaled_jacobian` array of VTK outputs.
pub fn scaled_jacobians(mesh: &IndexedMesh) -> Vec<f64> {
    (0..mesh.nb_cells()).map(|i| cell_scaled_jacobian(mesh, i).unwrap_or(0.0)).collect()
}

/// Cells that are tangled: positive signed volume, yet a negative scaled Jacobian (some
/// corner turned inside out). Reordering nodes (`--fix-orientation`) cannot repair them,
/// unlike inverted cells (negative volume), which are not counted here.
///
/// ```
/// use qmesh::build::{CellKind, IndexedMesh, tangled_cells};
/// let mut m = IndexedMesh::new();
/// m.points = vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.],
///                 [0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]];
/// m.push_cell(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7], None);
/// assert_eq!(tangled_cells(&m), 0);
/// m.points[6] = [0.2, 0.2, 0.2]; // the top corner pushed through the bottom one
/// assert_eq!(tangled_cells(&m), 1);
/// ```
pub fn tangled_cells(mesh: &IndexedMesh) -> usize {
    use rayon::prelude::*;
    (0..mesh.nb_cells())
        .into_par_iter()
        .with_min_len(1 << 10)
        .filter(|&i| {
            let (kind, nodes) = mesh.cell(i);
            let Some(std) = kind.standard() else { return false };
            cell_scaled_jacobian(mesh, i).is_some_and(|j| j < 0.0)
                && crate::geom::signed_volume_of_table(std.faces(), nodes, &mesh.points) > 0.0
        })
        .count()
}

/// Summary of one measure over the cells of one kind.
#[derive(Clone, Debug, PartialEq)]
pub struct QualitySummary {
    pub count: usize,
    pub min: f64,
    pub mean: f64,
    pub max: f64,
    /// 10 bins of width 0.2 from −1 to 1.
    pub histogram: [usize; 10],
    pub at_most_zero: usize,
    pub below_half: usize,
}

impl QualitySummary {
    pub fn of(values: &[f64]) -> Option<QualitySummary> {
        if values.is_empty() {
            return None;
        }
        let mut histogram = [0usize; 10];
        for &v in values {
            histogram[(((v + 1.0) / 0.2).floor() as i64).clamp(0, 9) as usize] += 1;
        }
        Some(QualitySummary {
            count: values.len(),
            min: values.iter().copied().fold(f64::INFINITY, f64::min),
            mean: values.iter().sum::<f64>() / values.len() as f64,
            max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            histogram,
            at_most_zero: values.iter().filter(|&&v| v <= 0.0).count(),
            below_half: values.iter().filter(|&&v| v < 0.5).count(),
        })
    }
}

/// Scaled Jacobian summaries per kind (tet, pyramid, prism, hex), plus every cell's value
/// (NaN for polyhedra), in cell order.
#[derive(Clone, Debug, Default)]
pub struct QualityByKind {
    pub per_cell: Vec<f64>,
    pub kinds: Vec<(CellKind, QualitySummary)>,
}

/// The scaled Jacobian of every cell and its summary per kind.
pub fn quality_by_kind(mesh: &IndexedMesh) -> QualityByKind {
    let per_cell: Vec<f64> = (0..mesh.nb_cells()).map(|i| cell_scaled_jacobian(mesh, i).unwrap_or(f64::NAN)).collect();
    let kinds = [CellKind::Tet, CellKind::Pyramid, CellKind::Prism, CellKind::Hex]
        .into_iter()
        .filter_map(|k| {
            let v: Vec<f64> = (0..mesh.nb_cells()).filter(|&i| mesh.kinds[i] == k).map(|i| per_cell[i]).collect();
            QualitySummary::of(&v).map(|s| (k, s))
        })
        .collect();
    QualityByKind { per_cell, kinds }
}
