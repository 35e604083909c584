//! The reports and applications on a mesh: each builds the map off the Python thread,
//! runs, and returns the new mesh with the CLI's JSON report (a string the Python layer
//! parses).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use numpy::PyReadonlyArray3;
use pyo3::prelude::*;
use qmesh::apps::{
    ConformalPhases, GeneratedKind, McFlags, RecombineOptions, RootShape, SplitChoice, SubdivideOptions,
    TetrahedralizeOptions, conformal as conformal_map, generated_pattern_set, marching_cubes_field, mc_pattern_set,
    recombine as recombine_map, recombined_mesh, subdivide as subdivide_surface, tet_to_hex,
    tetrahedralize as split_hexes, transitions_on_map, triangulate,
};
use qmesh::build::{
    BuildOptions, IndexedMesh, build_surface_map, build_volume_map, count_cell_kinds, extract, non_conformal_faces,
};
use qmesh::geom::TriangleBvh;
use qmesh::io::LoadedMap;
use qmesh::modify::{load_rules, run_rules};
use qmesh::pattern::{FlagRule, PatternSet, load_patterns};
use qmesh::query::Strategy;
use qmesh::replace::{ReplaceOptions, query_replace};
use qmesh::report::{InfoReport, QualityReport, ValidityReport};
use serde_json::json;

use crate::errors::value_error;
use crate::raw_mesh::RawMesh;
use crate::work::interruptible;

/// The map of a mesh, with what building it reported, as `qmesh info` loads a file.
pub fn load(mesh: &IndexedMesh, read_seconds: f64) -> Result<LoadedMap, String> {
    let t = Instant::now();
    let built =
        if mesh.is_volume() { build_volume_map(mesh, &BuildOptions::default()) } else { build_surface_map(mesh) };
    let (map, report) = built.map_err(|e| e.to_string())?;
    Ok(LoadedMap {
        map,
        report,
        warnings: mesh.warnings.clone(),
        read_seconds,
        build_seconds: t.elapsed().as_secs_f64(),
        cell_arrays: mesh.cell_arrays.clone(),
    })
}

/// Runs `f` on the mesh's map off the Python thread; its error becomes a MeshValueError.
fn on_map<T: Send + 'static>(
    py: Python<'_>,
    mesh: &RawMesh,
    f: impl FnOnce(LoadedMap, &Path) -> Result<T, String> + Send + 'static,
) -> PyResult<T> {
    let (cells, name, read_seconds) = (Arc::clone(&mesh.mesh), PathBuf::from(&mesh.name), mesh.read_seconds);
    interruptible(py, move || load(&cells, read_seconds).and_then(|loaded| f(loaded, &name)))?
        .map_err(|e| value_error(py, format!("{}: {e}", mesh.name)))
}

fn to_json(value: &impl serde::Serialize) -> Result<String, String> {
    serde_json::to_string(value).map_err(|e| e.to_string())
}

/// `qmesh info --json`.
#[pyfunction]
pub fn info(py: Python<'_>, mesh: &RawMesh) -> PyResult<String> {
    on_map(py, mesh, |loaded, name| to_json(&InfoReport::of(name, &loaded)))
}

/// `qmesh validate --json`, listing at most `max` violations.
#[pyfunction]
#[pyo3(signature = (mesh, max=20))]
pub fn validate(py: Python<'_>, mesh: &RawMesh, max: usize) -> PyResult<String> {
    on_map(py, mesh, move |loaded, name| to_json(&ValidityReport::of(name, &loaded, max)))
}

/// `qmesh quality --json` (with every cell's value when `per_cell`).
#[pyfunction]
#[pyo3(signature = (mesh, per_cell=false))]
pub fn quality(py: Python<'_>, mesh: &RawMesh, per_cell: bool) -> PyResult<String> {
    on_map(py, mesh, move |loaded, name| to_json(&QualityReport::of(name, &extract(&loaded.map).0, per_cell)))
}

/// Marching cubes of a field sampled on a grid (value of point (i, j, k) at
/// `field[i, j, k]`): the surface where it crosses `iso`, point (i, j, k) placed at
/// origin + (i, j, k)·spacing.
#[pyfunction]
#[pyo3(signature = (field, iso=0.0, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), triangles=true))]
pub fn marching_cubes(
    py: Python<'_>,
    field: PyReadonlyArray3<'_, f32>,
    iso: f64,
    spacing: (f64, f64, f64),
    origin: (f64, f64, f64),
    triangles: bool,
) -> PyResult<(RawMesh, String)> {
    let a = field.as_array();
    let dims = [a.shape()[0], a.shape()[1], a.shape()[2]];
    let values: Vec<f32> = match field.as_slice() {
        Ok(s) => s.to_vec(),
        Err(_) => a.iter().copied().collect(),
    };
    let result = interruptible(py, move || {
        let (mut mesh, report) = marching_cubes_field(&values, dims, iso, &mc_pattern_set(), McFlags::Inside)?;
        if triangles {
            mesh = triangulate(&mesh);
        }
        let (s, o) = ([spacing.0, spacing.1, spacing.2], [origin.0, origin.1, origin.2]);
        for p in &mut mesh.points {
            *p = [0, 1, 2].map(|k| o[k] + s[k] * p[k]);
        }
        Ok::<_, String>((mesh, to_json(&report)?))
    })?;
    let (mesh, report) = result.map_err(|e| value_error(py, format!("marching_cubes: {e}")))?;
    Ok((RawMesh::new(mesh, "<memory>"), report))
}

/// Octree subdivision (2022 Algorithm 5) of the box around a surface mesh (or the
/// boundary of a volume mesh), `levels` deep; with `init`, the root cells are the
/// bounding box cut into `init` cells along its longest axis (the authors' set-up).
/// With `conformal`, the transitions (2022 Algorithm 7) then run on the same map, with
/// the `transition_patterns` folders or compiled sets (default: the generated set).
#[pyfunction]
#[pyo3(signature = (surface, levels=4, margin=0.01, remove_outside=false, direct=false, init=None,
                    conformal=false, transition_patterns=None))]
#[allow(clippy::too_many_arguments)] // the Python keywords, as `qmesh subdivide`'s options
pub fn subdivide(
    py: Python<'_>,
    surface: &RawMesh,
    levels: u8,
    margin: f64,
    remove_outside: bool,
    direct: bool,
    init: Option<u32>,
    conformal: bool,
    transition_patterns: Option<Vec<PathBuf>>,
) -> PyResult<(RawMesh, String)> {
    let cells = Arc::clone(&surface.mesh);
    let root = match init {
        None => RootShape::Cube,
        Some(0) => return Err(value_error(py, "init must be at least 1".to_string())),
        Some(init) => RootShape::BoundingBox { init },
    };
    if direct && conformal {
        return Err(value_error(py, "conformal needs the map: it cannot go with direct".to_string()));
    }
    if transition_patterns.is_some() && !conformal {
        return Err(value_error(py, "transition_patterns only go with conformal=True".to_string()));
    }
    let transitions = match (conformal, transition_patterns) {
        (false, _) => None,
        (true, None) => {
            Some(generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners).map_err(|e| value_error(py, e))?)
        }
        (true, Some(dirs)) => Some(pattern_set(&dirs, "corners").map_err(|e| value_error(py, e))?.0),
    };
    let result = interruptible(py, move || {
        let boundary;
        let s = if cells.is_volume() {
            boundary = cells.boundary_surface();
            &boundary
        } else {
            &*cells
        };
        if s.nb_polygons() == 0 {
            return Err("no surface to subdivide around".to_string());
        }
        let bvh = TriangleBvh::from_polygons(&s.points, (0..s.nb_polygons()).map(|i| s.polygon(i)));
        let opts = SubdivideOptions { levels, root, margin, direct, remove_outside, use_signatures: true };
        let mut sub = subdivide_surface(&bvh, &opts, None, &|_| {}).map_err(|e| e.to_string())?;
        match (&transitions, &mut sub.map) {
            (Some(set), Some(map)) => {
                let mut phases = ConformalPhases::default();
                let (replace, kinds) =
                    transitions_on_map(map, set, true, Some(&sub.volumes), &mut phases).map_err(|e| e.to_string())?;
                let mut report: serde_json::Value =
                    serde_json::from_str(&to_json(&sub.report)?).map_err(|e| e.to_string())?;
                report["transitions"] = json!({
                    "replace": replace,
                    "cell_types": kinds,
                    "non_conformal_faces": non_conformal_faces(map),
                });
                Ok((extract(map).0, report.to_string()))
            }
            _ => Ok((sub.mesh, to_json(&sub.report)?)),
        }
    })?;
    let (mesh, report) = result.map_err(|e| value_error(py, format!("{}: {e}", surface.name)))?;
    Ok((RawMesh::new(mesh, "<memory>"), report))
}

/// Every tetrahedron into four hexahedra (2022 §7.4).
#[pyfunction]
pub fn tet2hex(py: Python<'_>, mesh: &RawMesh) -> PyResult<(RawMesh, String)> {
    let (cells, report) = on_map(py, mesh, |mut loaded, _| {
        if count_cell_kinds(&loaded.map).tet == 0 {
            return Err("no tetrahedra: tet2hex turns tetrahedra into hexahedra".into());
        }
        let r = tet_to_hex(&mut loaded.map, None, true).map_err(|e| e.to_string())?;
        Ok((extract(&loaded.map).0, to_json(&r)?))
    })?;
    Ok((RawMesh::new(cells, "<memory>"), report))
}

/// Every hexahedron split into tetrahedra without new points, conformally (2025
/// §7.1.1): among all its positive subdivisions (`five=False`) or 5-tetrahedron splits
/// where a consistent choice of diagonals allows.
#[pyfunction]
#[pyo3(signature = (mesh, seed=0, five=false))]
pub fn tetrahedralize(py: Python<'_>, mesh: &RawMesh, seed: u64, five: bool) -> PyResult<(RawMesh, String)> {
    let cells = Arc::clone(&mesh.mesh);
    let opts = TetrahedralizeOptions { choice: if five { SplitChoice::Five } else { SplitChoice::Any }, seed };
    let result = interruptible(py, move || {
        let (out, report) = split_hexes(&cells, &opts).map_err(|e| e.to_string())?;
        Ok::<_, String>((out, to_json(&report)?))
    })?;
    let (out, report) = result.map_err(|e| value_error(py, format!("{}: {e}", mesh.name)))?;
    Ok((RawMesh::new(out, "<memory>"), report))
}

/// Tetrahedra → hexahedra over every hexahedron subdivision (2025 §7.1).
#[pyfunction]
#[pyo3(signature = (mesh, strategy="best", min_quality=0.0, repair_effort=0.25, conformal=false))]
pub fn recombine(
    py: Python<'_>,
    mesh: &RawMesh,
    strategy: &str,
    min_quality: f64,
    repair_effort: f64,
    conformal: bool,
) -> PyResult<(RawMesh, String)> {
    let strategy = match strategy {
        "best" => Strategy::Best,
        "greedy" => Strategy::Greedy,
        s => return Err(value_error(py, format!("unknown strategy '{s}' (best, greedy)"))),
    };
    let (cells, report) = on_map(py, mesh, move |mut loaded, _| {
        let (r, hexes) = recombine_map(&mut loaded.map, &RecombineOptions { strategy, min_quality, repair_effort })
            .map_err(|e| e.to_string())?;
        let (cells, kinds) = recombined_mesh(&loaded.map, &hexes, conformal);
        let j = json!({
            "recombine": r,
            "cell_types": {"hex": kinds.hex, "tet": kinds.tet, "prism": kinds.prism, "pyramid": kinds.pyramid, "polyhedron": kinds.other},
            "valid": loaded.map.is_valid().is_empty(),
        });
        Ok((cells, j.to_string()))
    })?;
    Ok((RawMesh::new(cells, "<memory>"), report))
}

/// The rules of a rule file, in order (`qmesh modify`).
#[pyfunction]
pub fn modify(py: Python<'_>, mesh: &RawMesh, rules: PathBuf) -> PyResult<(RawMesh, String)> {
    let (cells, report) = on_map(py, mesh, move |mut loaded, _| {
        let rules = load_rules(&rules).map_err(|e| e.to_string())?;
        let reports = run_rules(&mut loaded.map, &rules);
        let j = json!({"rules": reports, "valid": reports.iter().all(|r| r.valid)});
        Ok((extract(&loaded.map).0, j.to_string()))
    })?;
    Ok((RawMesh::new(cells, "<memory>"), report))
}

/// The pattern folders (or files) `dirs` in one set, with the flag rule `flags`.
fn pattern_set(dirs: &[PathBuf], flags: &str) -> Result<(PatternSet, FlagRule), String> {
    let rule = match flags {
        "corners" => FlagRule::Corners,
        "geometric" => FlagRule::Geometric,
        "file" => FlagRule::File,
        "none" => FlagRule::None,
        f => return Err(format!("unknown flags '{f}' (corners, geometric, file, none)")),
    };
    let mut set = PatternSet::default();
    for dir in dirs {
        if !dir.exists() {
            return Err(format!("{}: no such pattern folder or file", dir.display()));
        }
        load_patterns(dir, rule).map_err(|e| e.to_string())?.patterns.into_iter().for_each(|p| {
            set.insert(p);
        });
    }
    Ok((set, rule))
}

/// 2022 query-replace with the patterns of `patterns` (folders or files), after
/// splitting every edge into `split_edges` when given.
#[pyfunction]
#[pyo3(signature = (mesh, patterns, split_edges=None, flags="corners"))]
pub fn replace(
    py: Python<'_>,
    mesh: &RawMesh,
    patterns: Vec<PathBuf>,
    split_edges: Option<usize>,
    flags: &str,
) -> PyResult<(RawMesh, String)> {
    let (set, rule) = pattern_set(&patterns, flags).map_err(|e| value_error(py, e))?;
    if set.patterns.is_empty() && split_edges.is_none() {
        return Err(value_error(py, "no usable pattern in the given folders"));
    }
    let (cells, report) = on_map(py, mesh, move |mut loaded, _| {
        let opts = ReplaceOptions { split_edges, flags: rule, use_signatures: true };
        let r = query_replace(&mut loaded.map, &set, &opts).map_err(|e| e.to_string())?;
        Ok((extract(&loaded.map).0, to_json(&r)?))
    })?;
    Ok((RawMesh::new(cells, "<memory>"), report))
}

/// Conformal 2:1 transitions (2022 Algorithm 7) of an octree mesh with hanging
/// vertices, with qmesh's generated transitions or the patterns of `patterns`.
#[pyfunction]
#[pyo3(signature = (mesh, patterns=None))]
pub fn conformal(py: Python<'_>, mesh: &RawMesh, patterns: Option<Vec<PathBuf>>) -> PyResult<(RawMesh, String)> {
    let set = match patterns {
        Some(dirs) => pattern_set(&dirs, "corners").map_err(|e| value_error(py, e))?.0,
        None => generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners).map_err(|e| value_error(py, e))?,
    };
    let cells = Arc::clone(&mesh.mesh);
    let result = interruptible(py, move || {
        let (map, report) = conformal_map(&cells, &set, true).map_err(|e| e.to_string())?;
        Ok::<_, String>((extract(&map).0, to_json(&report)?))
    })?;
    let (out, report) = result.map_err(|e| value_error(py, format!("{}: {e}", mesh.name)))?;
    Ok((RawMesh::new(out, "<memory>"), report))
}
