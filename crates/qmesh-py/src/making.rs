//! Meshes from files and from numpy arrays.

use std::path::PathBuf;
use std::time::Instant;

use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use qmesh::build::{CellArray, CellKind, CellValues, IndexedMesh, extract};
use qmesh::io::{Loaded, read as read_file};

use crate::errors::{io_error, value_error};
use crate::raw_mesh::{RawMesh, block_kind, parse_format};
use crate::work::interruptible;

/// Reads a mesh file (format from the extension unless given).
#[pyfunction]
#[pyo3(signature = (path, format=None))]
pub fn read(py: Python<'_>, path: PathBuf, format: Option<&str>) -> PyResult<RawMesh> {
    let forced = parse_format(py, format)?;
    let name = path.display().to_string();
    let (loaded, seconds) = interruptible(py, move || {
        let t = Instant::now();
        let loaded = read_file(&path, forced);
        (loaded, t.elapsed().as_secs_f64())
    })?;
    let mesh = match loaded.map_err(|e| io_error(py, &e))? {
        Loaded::Indexed(m) => m,
        Loaded::Map(map) => extract(&map).0,
    };
    Ok(RawMesh { mesh: std::sync::Arc::new(mesh), name, read_seconds: seconds })
}

/// A mesh from points (n×3), blocks of cells ({block: m×k indices}), polyhedra (lists
/// of faces) and cell data ({name: {block: values}}, blocks in the same order, with
/// "polyhedron" for the polyhedra).
#[pyfunction]
#[pyo3(signature = (points, cells, polyhedra=None, cell_data=None))]
pub fn from_arrays(
    py: Python<'_>,
    points: PyReadonlyArray2<'_, f64>,
    cells: &Bound<'_, PyDict>,
    polyhedra: Option<Vec<Vec<Vec<u32>>>>,
    cell_data: Option<&Bound<'_, PyDict>>,
) -> PyResult<RawMesh> {
    let p = points.as_array();
    if p.ncols() != 3 {
        return Err(value_error(py, format!("points: expected an n×3 array, got {}×{}", p.nrows(), p.ncols())));
    }
    let mut mesh = IndexedMesh::new();
    mesh.points = p.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect();
    let n = mesh.points.len() as i64;
    let mut order: Vec<String> = Vec::new();
    for (name, block) in cells.iter() {
        let name: String = name.extract()?;
        let block: PyReadonlyArray2<'_, i64> = block.extract().map_err(|_| {
            value_error(py, format!("cells['{name}']: expected a 2D integer array (m cells × nodes per cell)"))
        })?;
        let b = block.as_array();
        let kind = block_kind(&name);
        let nodes = match (kind, name.as_str()) {
            (Some(k), _) => k.nodes().expect("standard cell"),
            (None, "triangle") => 3,
            (None, "quad") => 4,
            _ => {
                return Err(value_error(
                    py,
                    format!("cells: unknown block '{name}' (tetra, pyramid, wedge, hexahedron, triangle, quad)"),
                ));
            }
        };
        if b.ncols() != nodes {
            return Err(value_error(py, format!("cells['{name}']: {} columns, a {name} has {nodes} nodes", b.ncols())));
        }
        for (row, c) in b.rows().into_iter().enumerate() {
            if let Some(&bad) = c.iter().find(|&&v| v < 0 || v >= n) {
                return Err(value_error(
                    py,
                    format!("cells['{name}'][{row}]: node {bad} is not a point index (0..{n})"),
                ));
            }
            let ids: Vec<u32> = c.iter().map(|&v| v as u32).collect();
            match kind {
                Some(k) => mesh.push_cell(k, &ids, None),
                None => mesh.push_polygon(&ids),
            }
        }
        order.push(name);
    }
    for (i, faces) in polyhedra.unwrap_or_default().iter().enumerate() {
        let mut stream = vec![faces.len() as u32];
        for f in faces {
            if let Some(&bad) = f.iter().find(|&&v| i64::from(v) >= n) {
                return Err(value_error(py, format!("polyhedra[{i}]: node {bad} is not a point index (0..{n})")));
            }
            stream.push(f.len() as u32);
            stream.extend(f);
        }
        mesh.push_cell(CellKind::Polyhedron, &stream, None);
        if i == 0 {
            order.push("polyhedron".into());
        }
    }
    if let Some(data) = cell_data {
        for (name, blocks) in data.iter() {
            let name: String = name.extract()?;
            let blocks = blocks
                .cast::<PyDict>()
                .map_err(|_| value_error(py, format!("cell_data['{name}']: expected a dict {{block: values}}")))?;
            let mut ints: Vec<i32> = Vec::new();
            let mut floats: Vec<f64> = Vec::new();
            for block in &order {
                let values = blocks
                    .get_item(block)?
                    .ok_or_else(|| value_error(py, format!("cell_data['{name}']: no values for block '{block}'")))?;
                if let Ok(v) = values.extract::<PyReadonlyArray1<'_, i32>>() {
                    ints.extend(v.as_array().iter());
                } else if let Ok(v) = values.extract::<Vec<i64>>() {
                    ints.extend(v.iter().map(|&x| x as i32));
                } else {
                    let v: Vec<f64> = values
                        .extract()
                        .map_err(|_| value_error(py, format!("cell_data['{name}']['{block}']: expected numbers")))?;
                    floats.extend(v);
                }
            }
            let count = if mesh.is_volume() { mesh.nb_cells() } else { mesh.nb_polygons() };
            let (len, values) = if floats.is_empty() {
                (ints.len(), CellValues::Int(ints))
            } else if ints.is_empty() {
                (floats.len(), CellValues::Float(floats))
            } else {
                return Err(value_error(py, format!("cell_data['{name}']: integers in some blocks, floats in others")));
            };
            if len != count {
                return Err(value_error(py, format!("cell_data['{name}']: {len} values for {count} cells")));
            }
            match (name.as_str(), values) {
                ("label", CellValues::Int(v)) if mesh.is_volume() => mesh.labels = v,
                (_, values) => mesh.cell_arrays.push(CellArray { name, values }),
            }
        }
    }
    Ok(RawMesh::new(mesh, "<memory>"))
}
