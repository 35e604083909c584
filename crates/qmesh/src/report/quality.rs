//! Scaled Jacobians and signed volumes (`qmesh quality`), and the combinatorial and
//! geometric validity of a loaded mesh (`qmesh validate`).

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;

use crate::build::{CellKind, IndexedMesh, QualityByKind, QualitySummary, extract, quality_by_kind, tangled_cells};
use crate::geom::signed_volume_of_table;
use crate::io::LoadedMap;

/// A scaled Jacobian summary, as Verdict users read it.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    pub count: usize,
    pub min: f64,
    pub mean: f64,
    pub max: f64,
    pub histogram_bins: &'static str,
    pub histogram: [usize; 10],
    #[serde(rename = "at_most_0")]
    pub at_most_zero: usize,
    #[serde(rename = "below_0.5")]
    pub below_half: usize,
}

impl From<&QualitySummary> for Summary {
    fn from(s: &QualitySummary) -> Summary {
        Summary {
            count: s.count,
            min: s.min,
            mean: s.mean,
            max: s.max,
            histogram_bins: "10 bins of width 0.2 from -1 to 1",
            histogram: s.histogram,
            at_most_zero: s.at_most_zero,
            below_half: s.below_half,
        }
    }
}

impl Summary {
    /// `{kind: summary}` for every kind present.
    pub fn by_kind(q: &QualityByKind) -> BTreeMap<String, Summary> {
        q.kinds.iter().map(|(k, s)| (k.name().to_string(), Summary::from(s))).collect()
    }

    /// One line per kind, as the CLI prints it.
    pub fn by_kind_text(q: &QualityByKind) -> String {
        q.kinds
            .iter()
            .map(|(k, s)| {
                format!(
                    "  {:<8} {:>8} cells  scaled Jacobian min {:.4}  mean {:.4}  max {:.4}  ≤0: {}  <0.5: {}  histogram[-1..1] {:?}\n",
                    k.name(),
                    s.count,
                    s.min,
                    s.mean,
                    s.max,
                    s.at_most_zero,
                    s.below_half,
                    s.histogram
                )
            })
            .collect()
    }
}

/// Signed volumes of the standard cells.
#[derive(Clone, Debug, Serialize)]
pub struct SignedVolumes {
    /// None without standard cells.
    pub min: Option<f64>,
    pub total: f64,
    pub non_positive: usize,
}

/// `qmesh quality`.
#[derive(Clone, Debug, Serialize)]
pub struct QualityReport {
    pub file: String,
    pub cells: usize,
    pub scaled_jacobian: BTreeMap<String, Summary>,
    pub signed_volume: SignedVolumes,
    /// Every cell's scaled Jacobian in the order qmesh writes cells (None for
    /// polyhedra), when asked for.
    pub per_cell: Option<Vec<Option<f64>>>,
    #[serde(skip)]
    pub by_kind: QualityByKind,
}

impl QualityReport {
    /// The report of the cells `cells` of `file`.
    pub fn of(file: &Path, cells: &IndexedMesh, per_cell: bool) -> QualityReport {
        let by_kind = quality_by_kind(cells);
        let volumes: Vec<f64> = (0..cells.nb_cells())
            .filter(|&i| cells.kinds[i] != CellKind::Polyhedron)
            .map(|i| signed_volume_of_table(cells.kinds[i].face_table(), cells.cell(i).1, &cells.points))
            .collect();
        let min = volumes.iter().copied().reduce(f64::min);
        QualityReport {
            file: file.display().to_string(),
            cells: cells.nb_cells(),
            scaled_jacobian: Summary::by_kind(&by_kind),
            signed_volume: SignedVolumes {
                min,
                total: volumes.iter().sum(),
                non_positive: volumes.iter().filter(|&&v| v <= 0.0).count(),
            },
            per_cell: per_cell.then(|| by_kind.per_cell.iter().map(|v| (!v.is_nan()).then_some(*v)).collect()),
            by_kind,
        }
    }
}

/// `qmesh validate`: the map's violations and the cells a geometric check flags.
#[derive(Clone, Debug, Serialize)]
pub struct ValidityReport {
    pub file: String,
    pub darts: usize,
    /// No combinatorial violation.
    pub valid: bool,
    pub violations: usize,
    /// The first violations, in words.
    pub problems: Vec<String>,
    /// Negative volume and not reversed on reading.
    pub inverted_cells: usize,
    pub tangled_cells: usize,
    pub degenerate_cells: usize,
    /// No inverted, tangled or degenerate cell.
    pub geometrically_valid: bool,
}

impl ValidityReport {
    /// The report of `loaded`, listing at most `max` violations.
    pub fn of(file: &Path, loaded: &LoadedMap, max: usize) -> ValidityReport {
        let v = loaded.map.is_valid();
        let r = &loaded.report;
        let tangled = if loaded.map.dimension() == 3 { tangled_cells(&extract(&loaded.map).0) } else { 0 };
        let inverted = r.inverted_cells - r.flipped_cells;
        ValidityReport {
            file: file.display().to_string(),
            darts: loaded.map.nb_darts(),
            valid: v.is_empty(),
            violations: v.len(),
            problems: v.iter().take(max).map(|x| x.to_string()).collect(),
            inverted_cells: inverted,
            tangled_cells: tangled,
            degenerate_cells: r.degenerate_cells,
            geometrically_valid: inverted == 0 && tangled == 0 && r.degenerate_cells == 0,
        }
    }
}
