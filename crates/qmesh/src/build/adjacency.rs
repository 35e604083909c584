//! Vertex → cells incidence (compressed rows), used to find the cells sharing a face.

use super::error::BuildError;
use super::indexed::{CellKind, IndexedMesh};

/// For every point, the cells that use it, in increasing cell order.
#[derive(Debug)]
pub struct VertexCells {
    start: Vec<u32>,
    cells: Vec<u32>,
}

impl VertexCells {
    /// Builds the incidence over `np` points; checks every node index against it.
    pub fn new(mesh: &IndexedMesh, np: usize) -> Result<VertexCells, BuildError> {
        let mut count = vec![0u32; np + 1];
        let mut nodes = Vec::new();
        for c in 0..mesh.nb_cells() {
            cell_nodes(mesh, c, &mut nodes)?;
            for &v in &nodes {
                if v as usize >= np {
                    return Err(BuildError::IndexOutOfRange { cell: c, index: v, points: np });
                }
                count[v as usize + 1] += 1;
            }
        }
        for i in 0..np {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut cells = vec![0u32; count[np] as usize];
        for c in 0..mesh.nb_cells() {
            cell_nodes(mesh, c, &mut nodes)?;
            for &v in &nodes {
                cells[fill[v as usize] as usize] = c as u32;
                fill[v as usize] += 1;
            }
        }
        Ok(VertexCells { start: count, cells })
    }

    /// Cells using point `v`.
    pub fn of(&self, v: u32) -> &[u32] {
        &self.cells[self.start[v as usize] as usize..self.start[v as usize + 1] as usize]
    }

    /// Cells using both `a` and `b`.
    pub fn common(&self, a: u32, b: u32) -> impl Iterator<Item = u32> + '_ {
        let other = self.of(b);
        self.of(a).iter().copied().filter(move |c| other.binary_search(c).is_ok())
    }

    /// Cells using `a`, `b` and `c` (the candidates to share a face through them).
    pub fn common3(&self, a: u32, b: u32, c: u32) -> impl Iterator<Item = u32> + '_ {
        let (lb, lc) = (self.of(b), self.of(c));
        self.of(a).iter().copied().filter(move |k| lb.binary_search(k).is_ok() && lc.binary_search(k).is_ok())
    }

    /// Whether no point is used by any cell.
    pub fn is_unused(&self, v: u32) -> bool {
        self.of(v).is_empty()
    }
}

/// The distinct nodes of cell `c` (for polyhedra, of its face stream).
fn cell_nodes(mesh: &IndexedMesh, c: usize, out: &mut Vec<u32>) -> Result<(), BuildError> {
    out.clear();
    let (kind, nodes) = mesh.cell(c);
    if kind == CellKind::Polyhedron {
        let faces = mesh
            .cell_faces(c)
            .ok_or_else(|| BuildError::BadCell { cell: c, reason: "malformed polyhedron face stream".into() })?;
        out.extend(faces.iter().flatten());
        out.sort_unstable();
        out.dedup();
        return Ok(());
    }
    let need = kind.nodes().unwrap_or(0);
    if nodes.len() != need {
        return Err(BuildError::BadCell {
            cell: c,
            reason: format!("a {} needs {need} nodes, got {}", kind.name(), nodes.len()),
        });
    }
    out.extend_from_slice(nodes);
    out.sort_unstable();
    if let Some(w) = out.windows(2).find(|w| w[0] == w[1]) {
        return Err(BuildError::BadCell {
            cell: c,
            reason: format!("node {} is repeated (degenerate {})", w[0], kind.name()),
        });
    }
    Ok(())
}
