//! The native part of the `qmesh` Python package (`qmesh._qmesh`): reading, writing,
//! numpy arrays in and out, the reports and every application. The Python layer
//! (`python/qmesh/`) wraps it in the documented API.

mod apps;
mod errors;
mod making;
mod raw_mesh;
mod rules;
mod work;

use pyo3::prelude::*;

#[pymodule]
fn _qmesh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<raw_mesh::RawMesh>()?;
    m.add_function(wrap_pyfunction!(making::read, m)?)?;
    m.add_function(wrap_pyfunction!(making::from_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(apps::info, m)?)?;
    m.add_function(wrap_pyfunction!(apps::validate, m)?)?;
    m.add_function(wrap_pyfunction!(apps::quality, m)?)?;
    m.add_function(wrap_pyfunction!(apps::marching_cubes, m)?)?;
    m.add_function(wrap_pyfunction!(apps::subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(apps::tet2hex, m)?)?;
    m.add_function(wrap_pyfunction!(apps::tetrahedralize, m)?)?;
    m.add_function(wrap_pyfunction!(apps::recombine, m)?)?;
    m.add_function(wrap_pyfunction!(apps::modify, m)?)?;
    m.add_function(wrap_pyfunction!(apps::replace, m)?)?;
    m.add_function(wrap_pyfunction!(apps::conformal, m)?)?;
    m.add_function(wrap_pyfunction!(rules::query, m)?)?;
    m.add_function(wrap_pyfunction!(rules::query_apply, m)?)?;
    Ok(())
}
