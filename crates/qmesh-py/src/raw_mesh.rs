//! The mesh object Python holds: indexed cells (or polygons) with their arrays. It is
//! never changed after it is made (every operation returns a new one), so its points
//! can be shared with numpy without a copy.

use std::sync::Arc;

use numpy::ndarray::{Array2, ArrayView2};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use qmesh::build::{CellKind, CellValues, IndexedMesh};
use qmesh::io::{Format, WriteOptions, resolve_format, write_indexed};

use crate::errors::{io_error, value_error};

/// meshio's name of a cell kind.
pub fn block_name(kind: CellKind) -> &'static str {
    match kind {
        CellKind::Tet => "tetra",
        CellKind::Pyramid => "pyramid",
        CellKind::Prism => "wedge",
        CellKind::Hex => "hexahedron",
        CellKind::Polyhedron => "polyhedron",
    }
}

/// The cell kind of a meshio block name (standard cells only).
pub fn block_kind(name: &str) -> Option<CellKind> {
    [CellKind::Tet, CellKind::Pyramid, CellKind::Prism, CellKind::Hex].into_iter().find(|&k| block_name(k) == name)
}

fn polygon_block(n: usize) -> &'static str {
    match n {
        3 => "triangle",
        4 => "quad",
        _ => "polygon",
    }
}

/// A mesh as read or made: cells of a volume mesh or polygons of a surface.
#[pyclass(module = "qmesh._qmesh", frozen)]
pub struct RawMesh {
    /// Shared with the computations that read it (on their own threads).
    pub mesh: Arc<IndexedMesh>,
    /// Where it was read from ("<memory>" otherwise), for reports.
    pub name: String,
    pub read_seconds: f64,
}

impl RawMesh {
    pub fn new(mesh: IndexedMesh, name: impl Into<String>) -> RawMesh {
        RawMesh { mesh: Arc::new(mesh), name: name.into(), read_seconds: 0.0 }
    }

    /// The cells (or polygons) of each block, in the order of the blocks' first cells.
    pub fn blocks(&self) -> Vec<(&'static str, Vec<usize>)> {
        let m = &self.mesh;
        let (count, name): (usize, Box<dyn Fn(usize) -> &'static str>) = if m.is_volume() {
            (m.nb_cells(), Box::new(|i| block_name(m.kinds[i])))
        } else {
            (m.nb_polygons(), Box::new(|i| polygon_block(m.polygon(i).len())))
        };
        let mut blocks: Vec<(&'static str, Vec<usize>)> = Vec::new();
        for i in 0..count {
            let n = name(i);
            match blocks.iter_mut().find(|b| b.0 == n) {
                Some(b) => b.1.push(i),
                None => blocks.push((n, vec![i])),
            }
        }
        blocks
    }

    /// The cells (or polygons) of block `name`, none if it has none.
    fn members(&self, name: &str) -> Vec<usize> {
        self.blocks().into_iter().find(|b| b.0 == name).map(|b| b.1).unwrap_or_default()
    }

    fn nodes(&self, i: usize) -> &[u32] {
        if self.mesh.is_volume() { self.mesh.cell(i).1 } else { self.mesh.polygon(i) }
    }
}

#[pymethods]
impl RawMesh {
    /// n×3 float64, read-only, shared with the mesh (no copy).
    #[getter]
    fn points<'py>(slf: Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let points = &slf.get().mesh.points;
        let view = ArrayView2::from_shape((points.len(), 3), points.as_flattened()).expect("n×3 points");
        // SAFETY: the array keeps `slf` alive, and a RawMesh is never changed.
        let array = unsafe { PyArray2::borrow_from_array(&view, slf.clone().into_any()) };
        array.getattr("flags")?.setattr("writeable", false)?;
        Ok(array)
    }

    /// {block: m×k int64 array} for the blocks of equal-size cells (not "polyhedron",
    /// nor "polygon").
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, members) in self.blocks() {
            if name == "polyhedron" || name == "polygon" {
                continue;
            }
            let k = self.nodes(members[0]).len();
            let flat: Vec<i64> = members.iter().flat_map(|&i| self.nodes(i).iter().map(|&v| i64::from(v))).collect();
            let array = Array2::from_shape_vec((members.len(), k), flat).expect("equal-size cells");
            d.set_item(name, array.into_pyarray(py))?;
        }
        Ok(d)
    }

    /// Every polyhedron as a list of faces (lists of point indices, counter-clockwise
    /// seen from outside, as VTK and meshio have them), in block order.
    #[getter]
    fn polyhedra<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        for i in self.members("polyhedron") {
            // (the cell's faces come inward, as the map runs them)
            let mut faces = self.mesh.cell_faces(i).unwrap_or_default();
            faces.iter_mut().for_each(|f| f.reverse());
            out.append(faces)?;
        }
        Ok(out)
    }

    /// Polygons with other than 3 or 4 corners, as lists of point indices.
    #[getter]
    fn polygons<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        for i in self.members("polygon") {
            out.append(self.nodes(i).to_vec())?;
        }
        Ok(out)
    }

    /// {name: {block: array}}: `label` (the file's references) and the per-cell arrays
    /// (`level`, `pattern_id`, `scaled_jacobian`, …), split like `cells`.
    #[getter]
    fn cell_data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        let blocks = self.blocks();
        let split_int = |values: &dyn Fn(usize) -> i32| -> PyResult<Bound<'py, PyDict>> {
            let d = PyDict::new(py);
            for (name, members) in &blocks {
                let v: Vec<i32> = members.iter().map(|&i| values(i)).collect();
                d.set_item(*name, PyArray1::from_vec(py, v))?;
            }
            Ok(d)
        };
        if !self.mesh.labels.is_empty() {
            out.set_item("label", split_int(&|i| self.mesh.labels[i])?)?;
        }
        for a in &self.mesh.cell_arrays {
            let d = match &a.values {
                CellValues::Int(v) => split_int(&|i| v[i])?,
                CellValues::Float(v) => {
                    let d = PyDict::new(py);
                    for (name, members) in &blocks {
                        let x: Vec<f64> = members.iter().map(|&i| v[i]).collect();
                        d.set_item(*name, PyArray1::from_vec(py, x))?;
                    }
                    d
                }
            };
            out.set_item(&a.name, d)?;
        }
        Ok(out)
    }

    /// Whether the mesh has volume cells (else it is a surface).
    #[getter]
    fn is_volume(&self) -> bool {
        self.mesh.is_volume()
    }

    /// Where the mesh was read from, or "<memory>".
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Writes the mesh to `path` (format from the extension unless `format` is given),
    /// atomically: a temporary file renamed into place.
    #[pyo3(signature = (path, format=None, binary=false))]
    fn write(&self, py: Python<'_>, path: std::path::PathBuf, format: Option<&str>, binary: bool) -> PyResult<()> {
        let forced = parse_format(py, format)?;
        let format = resolve_format(&path, forced).map_err(|e| io_error(py, &e))?;
        let mesh = &*self.mesh;
        py.detach(|| write_indexed(&path, mesh, format, &WriteOptions { binary })).map_err(|e| io_error(py, &e))
    }
}

/// A format name, or None.
pub fn parse_format(py: Python<'_>, format: Option<&str>) -> PyResult<Option<Format>> {
    format
        .map(|f| {
            Format::from_name(f).ok_or_else(|| {
                value_error(py, format!("unknown format '{f}' (vtk, vtu, mesh, msh, off, obj, stl, ply, moka)"))
            })
        })
        .transpose()
}
