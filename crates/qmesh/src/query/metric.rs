//! Metrics that rank matches for the `best` selection (2025 §5.2.2, §7.1).

use std::fmt;
use std::sync::Arc;

use super::query_map::Query;
use crate::cmap::CMap3;

/// A user metric: the input map, the query, and the matched raw darts in label order.
pub type MetricFn = dyn Fn(&CMap3, &Query, &[u32]) -> f64 + Send + Sync;

/// How to score a match (higher is better).
#[derive(Clone)]
pub enum Metric {
    /// Scaled Jacobian (Verdict) of the hexahedron spanned by the match's corners;
    /// −1 for queries without hexahedral corners.
    HexQuality,
    /// Sum of the signed volumes of the matched volumes.
    Volume,
    /// Any function of the match.
    Custom(Arc<MetricFn>),
}

impl fmt::Debug for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Metric {
    /// Reads `hex-quality` (or `scaled-jacobian`) and `volume`.
    pub fn parse(s: &str) -> Option<Metric> {
        match s {
            "hex-quality" | "scaled-jacobian" | "jacobian" => Some(Metric::HexQuality),
            "volume" => Some(Metric::Volume),
            _ => None,
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            Metric::HexQuality => "hex-quality",
            Metric::Volume => "volume",
            Metric::Custom(_) => "custom",
        }
    }

    /// The score of a match (`matched[k-1]` = raw input dart of label k).
    pub fn evaluate(&self, map: &CMap3, query: &Query, matched: &[u32]) -> f64 {
        match self {
            Metric::HexQuality => query.matched_hex_quality(map, matched).unwrap_or(-1.0),
            Metric::Volume => query.matched_volume(map, matched),
            Metric::Custom(f) => f(map, query, matched),
        }
    }
}
