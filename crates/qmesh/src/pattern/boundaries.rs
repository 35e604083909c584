//! The boundaries of v-patterns as cells of one mesh: the configurations a set covers,
//! laid out side by side (for inspection, coverage checks and benchmarks).

use super::{PatternKind, PatternSet};
use crate::build::{CellKind, IndexedMesh, boundary_polygons};

/// One VTK polyhedron per v-pattern boundary (repeated `copies` times), translated on a
/// grid of 2-unit steps so that cells do not touch.
pub fn boundaries_mesh(set: &PatternSet, copies: usize) -> IndexedMesh {
    let mut mesh = IndexedMesh::new();
    let mut n = 0usize;
    for _ in 0..copies {
        for p in set.patterns.iter().filter(|p| p.kind == PatternKind::Volume) {
            let b = boundary_polygons(&p.map);
            let base = mesh.points.len() as u32;
            let (dx, dy) = (2.0 * (n % 32) as f64, 2.0 * (n / 32) as f64);
            mesh.points.extend(b.points.iter().map(|q| [q[0] + dx, q[1] + dy, q[2]]));
            let mut stream = vec![b.nb_polygons() as u32];
            for i in 0..b.nb_polygons() {
                let f = b.polygon(i);
                stream.push(f.len() as u32);
                stream.extend(f.iter().map(|v| v + base));
            }
            mesh.push_cell(CellKind::Polyhedron, &stream, None);
            n += 1;
        }
    }
    mesh
}
