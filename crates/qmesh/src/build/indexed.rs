//! Indexed meshes as files store them: points plus cells given by node indices.

use crate::cmap::Standard;

/// Kind of a volume cell, with VTK node orders (GUIDE §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellKind {
    Tet,
    Pyramid,
    Prism,
    Hex,
    /// VTK polyhedron: connectivity `[nf, n0, v…, n1, v…]`, faces with outward normals.
    Polyhedron,
}

impl From<Standard> for CellKind {
    fn from(s: Standard) -> Self {
        match s {
            Standard::Tet => CellKind::Tet,
            Standard::Pyramid => CellKind::Pyramid,
            Standard::Prism => CellKind::Prism,
            Standard::Hex => CellKind::Hex,
        }
    }
}

impl CellKind {
    /// Number of nodes of a fixed-size cell (None for polyhedra).
    pub fn nodes(self) -> Option<usize> {
        match self {
            CellKind::Tet => Some(4),
            CellKind::Pyramid => Some(5),
            CellKind::Prism => Some(6),
            CellKind::Hex => Some(8),
            CellKind::Polyhedron => None,
        }
    }

    /// The VTK cell type number.
    pub fn vtk_type(self) -> u8 {
        match self {
            CellKind::Tet => 10,
            CellKind::Pyramid => 14,
            CellKind::Prism => 13,
            CellKind::Hex => 12,
            CellKind::Polyhedron => 42,
        }
    }

    /// The kind of a VTK volume cell type number.
    pub fn from_vtk_type(t: i64) -> Option<CellKind> {
        match t {
            10 => Some(CellKind::Tet),
            14 => Some(CellKind::Pyramid),
            13 => Some(CellKind::Prism),
            12 => Some(CellKind::Hex),
            42 => Some(CellKind::Polyhedron),
            _ => None,
        }
    }

    /// The standard cell of a fixed-size kind.
    pub fn standard(self) -> Option<Standard> {
        match self {
            CellKind::Tet => Some(Standard::Tet),
            CellKind::Pyramid => Some(Standard::Pyramid),
            CellKind::Prism => Some(Standard::Prism),
            CellKind::Hex => Some(Standard::Hex),
            CellKind::Polyhedron => None,
        }
    }

    /// Face table in map orientation for fixed-size kinds (empty for polyhedra).
    pub fn face_table(self) -> &'static [&'static [usize]] {
        self.standard().map_or(&[], Standard::faces)
    }

    /// A node order of the same cell with the opposite orientation.
    pub fn flipped_order(self) -> &'static [usize] {
        match self {
            CellKind::Tet => &[0, 2, 1, 3],
            CellKind::Pyramid => &[0, 3, 2, 1, 4],
            CellKind::Prism => &[3, 4, 5, 0, 1, 2],
            CellKind::Hex => &[4, 5, 6, 7, 0, 1, 2, 3],
            CellKind::Polyhedron => &[],
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            CellKind::Tet => "tet",
            CellKind::Pyramid => "pyramid",
            CellKind::Prism => "prism",
            CellKind::Hex => "hex",
            CellKind::Polyhedron => "polyhedron",
        }
    }
}

/// Corners of a VTK hexahedron as bit sets (bit k = upper side along axis k): node i
/// of an axis-aligned box hexahedron is its corner `HEX_CORNER_BITS[i]`.
pub const HEX_CORNER_BITS: [u32; 8] = [0, 1, 3, 2, 4, 5, 7, 6];

/// Points, volume cells and polygons as read from (or written to) a file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IndexedMesh {
    pub points: Vec<[f64; 3]>,
    pub kinds: Vec<CellKind>,
    /// `offsets[i]..offsets[i + 1]` is the connectivity of cell i.
    pub offsets: Vec<usize>,
    pub conn: Vec<u32>,
    /// One label per volume cell (Medit reference, gmsh entity, VTK CellEntityIds), or empty.
    pub labels: Vec<i32>,
    /// Polygons (surface meshes): `poly_offsets[i]..poly_offsets[i + 1]` in `poly_conn`.
    pub poly_offsets: Vec<usize>,
    pub poly_conn: Vec<u32>,
    /// Things the reader skipped or repaired, for the user.
    pub warnings: Vec<String>,
    /// Source line of each cell / polygon when the reader knows it (text formats), so
    /// that builder errors can point into the file; empty otherwise.
    pub cell_lines: Vec<u32>,
    pub poly_lines: Vec<u32>,
    /// Further per-cell (or per-polygon, for surfaces) arrays written for ParaView:
    /// `level`, `pattern_id`, `scaled_jacobian`, …
    pub cell_arrays: Vec<CellArray>,
    /// Boundary faces listed beside the cells of a volume file, with their reference
    /// (Medit `Triangles`/`Quadrilaterals` in a file with volume cells): per-face
    /// boundary conditions of queries (2025 §5.1.2) are given this way.
    pub face_labels: Vec<(Vec<u32>, i32)>,
}

/// A named per-cell array.
#[derive(Clone, Debug, PartialEq)]
pub struct CellArray {
    pub name: String,
    pub values: CellValues,
}

/// Values of a [`CellArray`].
#[derive(Clone, Debug, PartialEq)]
pub enum CellValues {
    Int(Vec<i32>),
    Float(Vec<f64>),
}

impl CellValues {
    pub fn len(&self) -> usize {
        match self {
            CellValues::Int(v) => v.len(),
            CellValues::Float(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl IndexedMesh {
    pub fn new() -> Self {
        IndexedMesh { offsets: vec![0], poly_offsets: vec![0], ..Default::default() }
    }

    pub fn nb_cells(&self) -> usize {
        self.kinds.len()
    }

    pub fn nb_polygons(&self) -> usize {
        self.poly_offsets.len().saturating_sub(1)
    }

    /// Appends a volume cell (nodes in VTK order, or the VTK polyhedron face stream).
    pub fn push_cell(&mut self, kind: CellKind, nodes: &[u32], label: Option<i32>) {
        self.kinds.push(kind);
        self.conn.extend_from_slice(nodes);
        self.offsets.push(self.conn.len());
        if let Some(l) = label {
            self.labels.resize(self.kinds.len() - 1, 0);
            self.labels.push(l);
        } else if !self.labels.is_empty() {
            self.labels.push(0);
        }
    }

    /// Adds (or replaces) a per-cell array; its length must be the number of cells
    /// (polygons for a surface).
    pub fn set_cell_array(&mut self, name: &str, values: CellValues) {
        let n = if self.is_volume() { self.nb_cells() } else { self.nb_polygons() };
        assert_eq!(values.len(), n, "cell array {name}: one value per cell");
        self.cell_arrays.retain(|a| a.name != name);
        self.cell_arrays.push(CellArray { name: name.to_string(), values });
    }

    /// The array called `name`, if any.
    pub fn cell_array(&self, name: &str) -> Option<&CellValues> {
        self.cell_arrays.iter().find(|a| a.name == name).map(|a| &a.values)
    }

    /// Appends a polygon.
    pub fn push_polygon(&mut self, nodes: &[u32]) {
        self.poly_conn.extend_from_slice(nodes);
        self.poly_offsets.push(self.poly_conn.len());
    }

    /// The cells listed in `cells` (with their labels), over all the points: a piece
    /// of a mesh to use as a query or pattern.
    pub fn cell_subset(&self, cells: &[usize]) -> IndexedMesh {
        let mut m = IndexedMesh { points: self.points.clone(), ..IndexedMesh::new() };
        for &i in cells {
            let (k, nodes) = self.cell(i);
            m.push_cell(k, nodes, self.label(i));
        }
        m
    }

    pub fn cell(&self, i: usize) -> (CellKind, &[u32]) {
        (self.kinds[i], &self.conn[self.offsets[i]..self.offsets[i + 1]])
    }

    pub fn polygon(&self, i: usize) -> &[u32] {
        &self.poly_conn[self.poly_offsets[i]..self.poly_offsets[i + 1]]
    }

    pub fn label(&self, i: usize) -> Option<i32> {
        self.labels.get(i).copied()
    }

    /// Whether this mesh has volume cells (otherwise it is a surface).
    pub fn is_volume(&self) -> bool {
        !self.kinds.is_empty()
    }

    /// Face cycles of cell i in map orientation (inward normals), or None when a
    /// polyhedron's face stream is malformed.
    pub fn cell_faces(&self, i: usize) -> Option<Vec<Vec<u32>>> {
        let (kind, nodes) = self.cell(i);
        if kind != CellKind::Polyhedron {
            return Some(kind.face_table().iter().map(|f| f.iter().map(|&k| nodes[k]).collect()).collect());
        }
        let nf = *nodes.first()? as usize;
        let mut faces = Vec::with_capacity(nf.min(nodes.len()));
        let mut k = 1;
        for _ in 0..nf {
            let n = *nodes.get(k)? as usize;
            let f = nodes.get(k + 1..k + 1 + n)?;
            faces.push(f.iter().rev().copied().collect());
            k += 1 + n;
        }
        (k == nodes.len()).then_some(faces)
    }

    /// Largest node index used by any cell or polygon, if any.
    pub fn max_index(&self) -> Option<u32> {
        let cells = (0..self.nb_cells()).flat_map(|i| {
            let (kind, nodes) = self.cell(i);
            let skip = if kind == CellKind::Polyhedron { 1 } else { 0 };
            nodes.iter().skip(skip).copied()
        });
        cells.chain(self.poly_conn.iter().copied()).max()
    }
}
