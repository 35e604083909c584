//! Reading a small map (a pattern, a query or a target) from any mesh file qmesh reads,
//! with the references of its labelled boundary faces.

use std::path::Path;

use rustc_hash::FxHashMap;

use super::PatternError;
use crate::build::{BuildOptions, build_map};
use crate::cmap::{CMap3, Dart};
use crate::io::{IoError, Loaded, read};

/// Face references of a small map: sorted vertex ids of a face → reference.
#[derive(Clone, Debug, Default)]
pub struct FaceLabels(FxHashMap<Vec<u32>, i32>);

impl FaceLabels {
    /// The reference of the half-face of `d`, if the file labelled that face.
    pub fn of(&self, map: &CMap3, d: Dart) -> Option<i32> {
        if self.0.is_empty() {
            return None;
        }
        let mut ids = vec![map.vertex_of(d)];
        let mut x = map.next(d);
        while x != d {
            ids.push(map.vertex_of(x));
            x = map.next(x);
        }
        ids.sort_unstable();
        self.0.get(&ids).copied()
    }

    /// Number of labelled faces.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The distinct references.
    pub fn references(&self) -> Vec<i32> {
        let mut r: Vec<i32> = self.0.values().copied().collect();
        r.sort_unstable();
        r.dedup();
        r
    }
}

/// Reads `path` into an oriented map (cells flipped to positive volume) and the
/// references of the boundary faces the file lists (Medit `Triangles` /
/// `Quadrilaterals` beside volume cells).
///
/// # Errors
/// An unreadable or malformed file, or cells the builder refuses.
pub fn read_small_map(path: &Path) -> Result<(CMap3, FaceLabels), PatternError> {
    let (map, labels) = match read(path, None)? {
        Loaded::Map(m) => (m, Vec::new()),
        Loaded::Indexed(mut mesh) => {
            let labels = std::mem::take(&mut mesh.face_labels);
            let (m, _) = build_map(mesh, &BuildOptions { fix_orientation: true })
                .map_err(|cause| IoError::Build { path: path.into(), cause })?;
            (m, labels)
        }
    };
    let table = labels
        .into_iter()
        .map(|(mut f, r)| {
            f.sort_unstable();
            (f, r)
        })
        .collect();
    Ok((map, FaceLabels(table)))
}
