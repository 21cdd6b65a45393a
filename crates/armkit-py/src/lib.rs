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

mod analytic;
mod arrays;
mod batched;
mod beam;
mod description;
mod dynamics;
mod errors;
mod ik;
mod mpc;
mod parallel;
mod reach;
mod redundancy;
mod robot;
mod singularity;
mod space;
mod study;
mod trajectory;
mod view;

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
    m.add_function(wrap_pyfunction!(view::view_page, m)?)?;
    m.add_class::<robot::Robot>()?;
    m.add_class::<ik::IkResult>()?;
    m.add_class::<analytic::IkSolutions>()?;
    m.add_class::<trajectory::PyTrajectory>()?;
    m.add_class::<trajectory::ContinuousPath>()?;
    m.add_function(wrap_pyfunction!(trajectory::continuous_path, m)?)?;
    let py = m.py();
    let redundancy = PyModule::new(py, "redundancy")?;
    redundancy.add_function(wrap_pyfunction!(
        redundancy::weighted_least_norm,
        &redundancy
    )?)?;
    redundancy.add_function(wrap_pyfunction!(redundancy::energy_optimal, &redundancy)?)?;
    redundancy.add_function(wrap_pyfunction!(redundancy::joint_torques, &redundancy)?)?;
    redundancy.add_function(wrap_pyfunction!(redundancy::energy_measure, &redundancy)?)?;
    m.add_submodule(&redundancy)?;
    let dynamics = PyModule::new(py, "dynamics")?;
    dynamics.add_function(wrap_pyfunction!(dynamics::rnea, &dynamics)?)?;
    dynamics.add_function(wrap_pyfunction!(dynamics::aba, &dynamics)?)?;
    dynamics.add_function(wrap_pyfunction!(dynamics::mass_matrix, &dynamics)?)?;
    dynamics.add_function(wrap_pyfunction!(dynamics::gravity_torques, &dynamics)?)?;
    dynamics.add_function(wrap_pyfunction!(dynamics::coriolis_torques, &dynamics)?)?;
    dynamics.add_function(wrap_pyfunction!(dynamics::kinetic_energy, &dynamics)?)?;
    m.add_submodule(&dynamics)?;
    let singularity = PyModule::new(py, "singularity")?;
    singularity.add_function(wrap_pyfunction!(singularity::classify, &singularity)?)?;
    singularity.add_function(wrap_pyfunction!(singularity::line_through, &singularity)?)?;
    singularity.add_function(wrap_pyfunction!(singularity::track_line, &singularity)?)?;
    m.add_submodule(&singularity)?;
    let study = PyModule::new(py, "study")?;
    study.add_function(wrap_pyfunction!(study::run, &study)?)?;
    study.add_function(wrap_pyfunction!(study::names, &study)?)?;
    study.add_class::<study::StudyReport>()?;
    m.add_submodule(&study)?;
    m.add_class::<mpc::MpcPlanner>()?;
    m.add_class::<beam::Beam>()?;
    m.add_class::<space::SpaceRobot>()?;
    reach::add_module(m)?;
    Ok(())
}
