//! Rigid-body dynamics from Python (`armkit.dynamics`): inverse dynamics
//! (RNEA), the mass matrix (CRBA), forward dynamics (ABA), gravity,
//! Coriolis and nonlinear torques, energies; one state at a time or
//! batched over (N, dof) arrays with the GIL released.
//!
//! Units: q in rad or m, v in rad/s or m/s, a in rad/s^2 or m/s^2, torques
//! in N m or N, mass matrix in kg m^2 / kg, energies in J; gravity a
//! world-frame acceleration, default (0, 0, -9.81) m/s^2.

use armkit::dynamics::{self as library, DynamicsData, DEFAULT_GRAVITY};
use armkit::math::Vector3;
use armkit::Model;
use numpy::{PyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::arrays::{
    copy_values, float_array, new_array, read_flat_sequence, shape_error, RowMajor,
};
use crate::errors::{row_error, OrRaise};
use crate::parallel::{for_each_row, thread_count, RowsMut};
use crate::robot::Robot;

/// States per thread below which a batched call stays on fewer threads.
const DYNAMICS_ROWS_PER_THREAD: usize = 512;

/// One dynamics algorithm: writes its result for one state into `out`.
type Algorithm =
    dyn Fn(&Model, &mut DynamicsData, &[&[f64]], &mut [f64]) -> armkit::Result<()> + Sync;

/// Evaluates `algorithm` on `inputs` (each (dof,) or each (N, dof)), giving
/// an array of shape `item` (a float when `item` is empty) or (N, *item).
/// One state runs on the robot's cached workspace with the GIL held (a few
/// microseconds at most); a batch runs on `threads` threads without it.
fn evaluate<'py>(
    py: Python<'py>,
    robot: &Robot,
    gravity: Option<Vec<f64>>,
    inputs: &[(&Bound<'py, PyAny>, &'static str)],
    item: &[usize],
    threads: Option<i64>,
    algorithm: &Algorithm,
) -> PyResult<Bound<'py, PyAny>> {
    let model = &robot.model;
    let dof = model.dof();
    let gravity = match gravity {
        None => DEFAULT_GRAVITY,
        Some(g) => {
            armkit::error::check_finite_vector("gravity", &g, 3).or_raise()?;
            Vector3::new(g[0], g[1], g[2])
        }
    };
    let width: usize = item.iter().product();
    // One state given as flat lists: no NumPy at all.
    let mut values: Vec<Vec<f64>> = vec![Vec::new(); inputs.len()];
    if inputs
        .iter()
        .zip(values.iter_mut())
        .all(|((obj, _), out)| read_flat_sequence(obj, out))
    {
        return single(py, robot, gravity, &values, item, algorithm);
    }
    let arrays: Vec<Bound<'py, PyArrayDyn<f64>>> = inputs
        .iter()
        .map(|(obj, what)| float_array(obj, what))
        .collect::<PyResult<_>>()?;
    let rows = match arrays[0].ndim() {
        1 => None,
        2 => Some(arrays[0].shape()[0]),
        _ => {
            return Err(shape_error(
                inputs[0].1,
                &format!("({dof},) or (N, {dof})"),
                arrays[0].shape(),
            ))
        }
    };
    for (array, (_, what)) in arrays.iter().zip(inputs) {
        let fits = match rows {
            None => array.ndim() == 1,
            Some(n) => array.shape() == [n, dof],
        };
        if !fits {
            let expected = match rows {
                None => format!("({dof},)"),
                Some(n) => format!("({n}, {dof})"),
            };
            return Err(shape_error(what, &expected, array.shape()));
        }
    }
    let Some(n) = rows else {
        for (array, out) in arrays.iter().zip(values.iter_mut()) {
            copy_values(array, out);
        }
        return single(py, robot, gravity, &values, item, algorithm);
    };
    let mut data = DynamicsData::new(model).or_raise()?;
    data.set_gravity(gravity).or_raise()?;
    let inputs_by_row: Vec<RowMajor<'py>> =
        arrays.iter().map(RowMajor::new).collect::<PyResult<_>>()?;
    let slices: Vec<&[f64]> = inputs_by_row.iter().map(RowMajor::as_slice).collect();
    let threads = thread_count(threads)?;
    let mut dims = vec![n];
    dims.extend_from_slice(item);
    let out = new_array(py, numpy::ndarray::IxDyn(&dims), |out| {
        py.detach(|| {
            for_each_row(
                n,
                threads,
                DYNAMICS_ROWS_PER_THREAD,
                RowsMut::new(out, width),
                || data.clone(),
                |data, row, local, out| {
                    let state: Vec<&[f64]> = slices
                        .iter()
                        .map(|s| &s[row * dof..(row + 1) * dof])
                        .collect();
                    algorithm(model, data, &state, out.row(local))
                },
            )
        })
        .map_err(|e| row_error(inputs[0].1, e.row, &e.error))
    })?;
    Ok(out.into_any())
}

/// One state on the robot's cached dynamics workspace.
fn single<'py>(
    py: Python<'py>,
    robot: &Robot,
    gravity: Vector3<f64>,
    values: &[Vec<f64>],
    item: &[usize],
    algorithm: &Algorithm,
) -> PyResult<Bound<'py, PyAny>> {
    let slices: Vec<&[f64]> = values.iter().map(Vec::as_slice).collect();
    let mut out = vec![0.0; item.iter().product()];
    robot
        .with_dynamics(gravity, |data| {
            algorithm(&robot.model, data, &slices, &mut out)
        })
        .or_raise()?;
    if item.is_empty() {
        return Ok(out[0].into_pyobject(py)?.into_any());
    }
    Ok(new_array(py, numpy::ndarray::IxDyn(item), |values| {
        values.copy_from_slice(&out);
        Ok(())
    })?
    .into_any())
}

/// Inverse dynamics (RNEA): the joint torques `tau` (N m or N) that give
/// accelerations `a` at positions `q` and velocities `v`:
/// `tau = M(q) a + C(q, v) v + g(q)`. Each of q, v, a of shape (dof,) or
/// (N, dof); batched: GIL released, `threads` threads.
#[pyfunction]
#[pyo3(signature = (robot, q, v, a, gravity=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn rnea<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    gravity: Option<Vec<f64>>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    let dof = robot.model.dof();
    evaluate(
        py,
        robot,
        gravity,
        &[(q, "q"), (v, "v"), (a, "a")],
        &[dof],
        threads,
        &|m, d, s, out| {
            out.copy_from_slice(library::rnea(m, d, s[0], s[1], s[2])?);
            Ok(())
        },
    )
}

/// Forward dynamics (ABA): the joint accelerations (rad/s^2 or m/s^2) under
/// torques `tau` at `q`, `v`: `a = M(q)^-1 (tau - C(q, v) v - g(q))`.
/// `ValueError` naming the joint when `M(q)` is numerically singular
/// (`armkit::dynamics::MASS_MATRIX_THRESHOLD`), never accelerations.
#[pyfunction]
#[pyo3(signature = (robot, q, v, tau, gravity=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn aba<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    gravity: Option<Vec<f64>>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    let dof = robot.model.dof();
    evaluate(
        py,
        robot,
        gravity,
        &[(q, "q"), (v, "v"), (tau, "tau")],
        &[dof],
        threads,
        &|m, d, s, out| {
            out.copy_from_slice(library::aba(m, d, s[0], s[1], s[2])?);
            Ok(())
        },
    )
}

/// The joint-space mass matrix M(q) (CRBA), (dof, dof) or (N, dof, dof),
/// symmetric positive definite.
#[pyfunction]
#[pyo3(signature = (robot, q, threads=None))]
pub fn mass_matrix<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    let dof = robot.model.dof();
    evaluate(
        py,
        robot,
        None,
        &[(q, "q")],
        &[dof, dof],
        threads,
        &move |m, d, s, out| {
            let matrix = library::mass_matrix(m, d, s[0])?;
            for r in 0..dof {
                for c in 0..dof {
                    out[r * dof + c] = matrix[(r, c)];
                }
            }
            Ok(())
        },
    )
}

/// The gravity torques g(q) (N m or N): the torques that hold the arm still.
#[pyfunction]
#[pyo3(signature = (robot, q, gravity=None, threads=None))]
pub fn gravity_torques<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    gravity: Option<Vec<f64>>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    let dof = robot.model.dof();
    evaluate(
        py,
        robot,
        gravity,
        &[(q, "q")],
        &[dof],
        threads,
        &|m, d, s, out| {
            out.copy_from_slice(library::gravity_torques(m, d, s[0])?);
            Ok(())
        },
    )
}

/// The Coriolis and centrifugal torques C(q, v) v (N m or N).
#[pyfunction]
#[pyo3(signature = (robot, q, v, threads=None))]
pub fn coriolis_torques<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    let dof = robot.model.dof();
    evaluate(
        py,
        robot,
        None,
        &[(q, "q"), (v, "v")],
        &[dof],
        threads,
        &|m, d, s, out| {
            out.copy_from_slice(library::coriolis_torques(m, d, s[0], s[1])?);
            Ok(())
        },
    )
}

/// The kinetic energy v' M(q) v / 2, J: a float, or (N,) for a batch.
#[pyfunction]
#[pyo3(signature = (robot, q, v, threads=None))]
pub fn kinetic_energy<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    evaluate(
        py,
        robot,
        None,
        &[(q, "q"), (v, "v")],
        &[],
        threads,
        &|m, d, s, out| {
            out[0] = library::kinetic_energy(m, d, s[0], s[1])?;
            Ok(())
        },
    )
}
