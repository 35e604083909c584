//! Vertex → cells incidence (compressed rows), used to find the cells sharing a face,
//! and the node checks that precede building.

use super::error::BuildError;
use super::indexed::{CellKind, IndexedMesh};

/// For every point, the cells that use it, in increasing cell order.
#[derive(Debug)]
pub struct VertexCells {
    start: Vec<u32>,
    cells: Vec<u32>,
}

/// Checks every cell's nodes (in range, not repeated, polyhedron streams well formed)
/// before any dart is created.
pub fn check_cells(mesh: &IndexedMesh, np: usize) -> Result<(), BuildError> {
    let mut nodes = Vec::new();
    for c in 0..mesh.nb_cells() {
        cell_nodes(mesh, c, &mut nodes)?;
        if let Some(&v) = nodes.iter().find(|&&v| v as usize >= np) {
            return Err(BuildError::IndexOutOfRange { cell: c, index: v, points: np });
        }
    }
    Ok(())
}

impl VertexCells {
    /// Builds the incidence over `np` points from the distinct vertex ids of each cell,
    /// given by `nodes_of` (cells in order; ids already checked to be below `np`).
    pub fn new(np: usize, cells: usize, mut nodes_of: impl FnMut(usize, &mut Vec<u32>)) -> VertexCells {
        let mut count = vec![0u32; np + 1];
        let mut nodes = Vec::new();
        for c in 0..cells {
            nodes_of(c, &mut nodes);
            nodes.iter().for_each(|&v| count[v as usize + 1] += 1);
        }
        for i in 0..np {
            count[i + 1] += count[i];
        }
        let mut cells_of = vec![0u32; count[np] as usize];
        // Filling moves each row's start to its end; the starts are restored after.
        for c in 0..cells {
            nodes_of(c, &mut nodes);
            for &v in &nodes {
                cells_of[count[v as usize] as usize] = c as u32;
                count[v as usize] += 1;
            }
        }
        for i in (1..=np).rev() {
            count[i] = count[i - 1];
        }
        count[0] = 0;
        VertexCells { start: count, cells: cells_of }
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
