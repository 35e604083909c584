//! Rule files from Python: `query` (the selected matches as arrays of volume indices)
//! and `query_apply` (a Python function per match, 2025 §6.4), both through the
//! library's query-apply mechanism, so every selection option of a rule file applies.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use numpy::{PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use qmesh::build::extract;
use qmesh::cmap::{CMap3, Dart, MapError, Orbit, OrbitWalker};
use qmesh::modify::{Action, ApplyFn, RuleReport, load_rules, run_rules};
use serde_json::json;

use crate::apps::load;
use crate::errors::value_error;
use crate::raw_mesh::RawMesh;

/// The index (in the map's volume order, which is the mesh's cell order) of every
/// dart's volume.
fn volume_index(map: &CMap3) -> Vec<u32> {
    let mut index = vec![u32::MAX; map.dart_capacity()];
    let mut walker = OrbitWalker::new();
    for (i, d) in map.cells(Orbit::Volume).enumerate() {
        for &x in walker.collect(map, d, Orbit::Volume) {
            index[x.idx()] = i as u32;
        }
    }
    index
}

/// The distinct volumes of a match, in the order its darts first reach them.
fn volumes_of(index: &[u32], darts: &[Dart]) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::new();
    for d in darts {
        let v = index[d.idx()];
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// The distinct map vertices of a match, in the order of the query's labels.
fn vertices_of(map: &CMap3, darts: &[Dart]) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::new();
    for &d in darts {
        let v = map.vertex_of(d);
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// Runs the rules of `rules` on the mesh with `action(rule index)` in place of theirs.
fn run_with(
    py: Python<'_>,
    mesh: &RawMesh,
    rules: &std::path::Path,
    action: impl Fn(usize) -> Arc<ApplyFn>,
) -> PyResult<(CMap3, Vec<RuleReport>)> {
    let mut rules = load_rules(rules).map_err(|e| value_error(py, e))?;
    for (i, r) in rules.iter_mut().enumerate() {
        r.action = Action::Apply(action(i));
    }
    let mut map = load(&mesh.mesh, 0.0).map_err(|e| value_error(py, format!("{}: {e}", mesh.name)))?.map;
    // The functions below take the GIL when they call Python: release it meanwhile.
    let reports = py.detach(|| run_rules(&mut map, &rules));
    Ok((map, reports))
}

/// The matches each rule selects, as arrays of volume (cell) indices, with each rule's
/// report (`qmesh query` counts: matches, selected, automorphisms, times).
#[pyfunction]
pub fn query(py: Python<'_>, mesh: &RawMesh, rules: PathBuf) -> PyResult<(String, Vec<Vec<Vec<u32>>>)> {
    type Found = Arc<Mutex<Vec<Vec<Vec<Dart>>>>>;
    let found: Found = Arc::new(Mutex::new(Vec::new()));
    let record = |i: usize| -> Arc<ApplyFn> {
        let found = Arc::clone(&found);
        Arc::new(move |_: &mut CMap3, _: &qmesh::query::Query, darts: &[Dart]| {
            let mut f = found.lock().expect("not poisoned");
            if f.len() <= i {
                f.resize(i + 1, Vec::new());
            }
            f[i].push(darts.to_vec());
            Ok(())
        })
    };
    let (map, mut reports) = run_with(py, mesh, &rules, record)?;
    let index = volume_index(&map);
    let found = found.lock().expect("not poisoned");
    let matches: Vec<Vec<Vec<u32>>> = (0..reports.len())
        .map(|i| found.get(i).map(|ms| ms.iter().map(|m| volumes_of(&index, m)).collect()).unwrap_or_default())
        .collect();
    for r in &mut reports {
        r.op = "query";
        r.modified = 0;
    }
    Ok((json!({ "rules": reports }).to_string(), matches))
}

/// Each rule's selected matches given to `function(points, volumes)`: the positions of
/// the match's vertices (k×3, in the order of the query's labels) and its volumes; it
/// returns new positions (k×3) or None to leave them. Returns the mesh and the report.
#[pyfunction]
pub fn query_apply(py: Python<'_>, mesh: &RawMesh, rules: PathBuf, function: Py<PyAny>) -> PyResult<(RawMesh, String)> {
    let failure: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let index = Arc::new(Mutex::new(Vec::<u32>::new()));
    let call = |_: usize| -> Arc<ApplyFn> {
        let (function, failure, index) = (function.clone_ref(py), Arc::clone(&failure), Arc::clone(&index));
        Arc::new(move |map: &mut CMap3, _: &qmesh::query::Query, darts: &[Dart]| {
            let mut index = index.lock().expect("not poisoned");
            if index.is_empty() {
                *index = volume_index(map);
            }
            let vertices = vertices_of(map, darts);
            let volumes = volumes_of(&index, darts);
            let moved = Python::attach(|py| -> PyResult<Option<Vec<[f64; 3]>>> {
                let points: Vec<Vec<f64>> = vertices.iter().map(|&v| map.position(v).to_vec()).collect();
                let points = PyArray2::from_vec2(py, &points).expect("k×3");
                let out = function.call1(py, (points, volumes.clone()))?;
                if out.is_none(py) {
                    return Ok(None);
                }
                let a: PyReadonlyArray2<'_, f64> = out.extract(py)?;
                let a = a.as_array();
                if a.shape() != [vertices.len(), 3] {
                    return Err(pyo3::exceptions::PyValueError::new_err(format!(
                        "query_apply: the function returned a {:?} array for {} vertices (expected {}×3)",
                        a.shape(),
                        vertices.len(),
                        vertices.len()
                    )));
                }
                Ok(Some(a.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect()))
            });
            match moved {
                Ok(Some(p)) => vertices.iter().zip(p).for_each(|(&v, q)| map.set_position(v, q)),
                Ok(None) => {}
                Err(e) => {
                    let msg = e.to_string();
                    failure.lock().expect("not poisoned").get_or_insert(e);
                    return Err(MapError::Refused(msg));
                }
            }
            Ok(())
        })
    };
    let (map, reports) = run_with(py, mesh, &rules, call)?;
    if let Some(e) = failure.lock().expect("not poisoned").take() {
        return Err(e);
    }
    let j = json!({"rules": reports, "valid": reports.iter().all(|r| r.valid)});
    Ok((RawMesh::new(extract(&map).0, "<memory>"), j.to_string()))
}
