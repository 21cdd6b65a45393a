//! armkit for Python: the `armkit._armkit` extension module (PyO3 + NumPy),
//! re-exported by the `armkit` package (`python/armkit`).
//!
//! Conventions are the library's: SI units (m, rad, s, kg, N), poses in the
//! world frame as homogeneous 4 x 4 arrays, Jacobian and twist rows
//! `[vx, vy, vz, wx, wy, wz]`. Arrays come in as any float array-like and go
//! out as new C-ordered float64 arrays; batched calls release the GIL and run
//! on every core; bad input raises `ValueError` (or `FileNotFoundError`)
//! with the library's message; a solver that did not converge says so in its
//! result's status.

mod arrays;
mod errors;
mod ik;
mod parallel;
mod robot;

use pyo3::prelude::*;

/// The names of the built-in robots.
#[pyfunction]
fn builtin_robots() -> Vec<&'static str> {
    armkit::robots::names().collect()
}

/// The extension module.
#[pymodule]
fn _armkit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(builtin_robots, m)?)?;
    m.add_class::<robot::Robot>()?;
    m.add_class::<ik::IkResult>()?;
    Ok(())
}
