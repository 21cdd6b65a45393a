//! Redundancy resolution from Python (`armkit.redundancy`): seed 001's
//! weighted least norm and energy-optimal distribution of one end-effector
//! twist over the joints.

use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::math::{Vector3, Vector6};
use armkit::redundancy::{
    energy_measure as library_energy_measure, joint_torques as library_joint_torques, Damping,
    JointWeights, Load, SolverOptions, TorqueFloor, WeightedLeastNorm,
};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::arrays::{vector, vector_argument};
use crate::errors::OrRaise;
use crate::robot::Robot;

/// Per-joint weights `a_i` from Python: None is uniform (minimum norm), an
/// infinite weight locks the joint.
fn joint_weights(values: Option<Vec<f64>>, dof: usize) -> armkit::Result<JointWeights> {
    let Some(values) = values else {
        return Ok(JointWeights::uniform(dof));
    };
    if values.len() != dof {
        return Err(armkit::Error::DimensionMismatch {
            what: "weights",
            expected: dof,
            got: values.len(),
        });
    }
    let mut weights = JointWeights::uniform(dof);
    for (joint, &value) in values.iter().enumerate() {
        if value == f64::INFINITY {
            weights.lock(joint)?;
        } else {
            weights.set(joint, value)?;
        }
    }
    Ok(weights)
}

/// The velocities of a solve, or `ValueError` when `J A^-1 J'` was
/// numerically singular (the message gives the smallest singular value and
/// suggests damping).
fn solved(solve: armkit::linalg::Solve<&[f64]>) -> PyResult<&[f64]> {
    match solve {
        armkit::linalg::Solve::Solved(q_dot) => Ok(q_dot),
        armkit::linalg::Solve::Singular {
            smallest_singular_value,
        } => Err(pyo3::exceptions::PyValueError::new_err(format!(
            "the weighted Jacobian is numerically singular at q (smallest singular value \
             {smallest_singular_value:.3e}): no joint velocities realize every twist; give damping"
        ))),
    }
}

fn solver_options(damping: Option<f64>) -> SolverOptions {
    SolverOptions {
        damping: damping.map_or(Damping::None, Damping::Constant),
        ..SolverOptions::default()
    }
}

/// The static load: a wrench at the end effector (N, N m, world frame;
/// default a payload of `payload` N along -z, i.e. `[0, 0, payload, 0, 0, 0]`
/// held) plus, with `gravity`, the links' own weights (standard gravity).
fn load(payload: f64, wrench: Option<Vec<f64>>, gravity: bool) -> armkit::Result<Load> {
    let mut load = match wrench {
        Some(w) => {
            armkit::error::check_finite_vector("wrench", &w, 6)?;
            Load::wrench(Vector6::from_column_slice(&w))
        }
        None => Load::payload(payload),
    };
    if gravity {
        load = load.with_gravity(Vector3::new(
            0.0,
            0.0,
            -armkit::redundancy::STANDARD_GRAVITY,
        ));
    }
    load.validate()?;
    Ok(load)
}

/// Joint velocities `q_dot` (rad/s or m/s) realizing the end-effector
/// `twist` `[vx, vy, vz, wx, wy, wz]` (m/s, rad/s, world frame) at `q` with
/// the least weighted norm `sum a_i q_dot_i^2` (seed 001, eq 18). `weights`:
/// `a_i > 0` per joint (default 1: the pseudo-inverse), `inf` locks a joint;
/// `damping`: a constant damping factor for near-singular arms.
#[pyfunction]
#[pyo3(signature = (robot, q, twist, weights=None, damping=None))]
pub fn weighted_least_norm<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    twist: &Bound<'py, PyAny>,
    weights: Option<Vec<f64>>,
    damping: Option<f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let model = &robot.model;
    let dof = model.dof();
    let q = vector_argument(q, "joint_positions", dof)?;
    let twist = Vector6::from_column_slice(&vector_argument(twist, "twist", 6)?);
    let weights = joint_weights(weights, dof).or_raise()?;
    let mut solver = WeightedLeastNorm::new(dof, solver_options(damping)).or_raise()?;
    let mut data = Data::new(model);
    let j = jacobian(model, &mut data, &q, JacobianFrame::World).or_raise()?;
    let q_dot = solved(solver.solve(j, &weights, &twist).or_raise()?)?;
    Ok(vector(py, q_dot))
}

/// Static joint torques (N m or N) holding the load at `q`: `J' w` for the
/// end-effector wrench `w` (default a payload of `payload` N) plus, with
/// `gravity`, the links' weights (needs the robot's mass properties).
#[pyfunction]
#[pyo3(signature = (robot, q, payload=0.0, wrench=None, gravity=true))]
pub fn joint_torques<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    payload: f64,
    wrench: Option<Vec<f64>>,
    gravity: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let model = &robot.model;
    let q = vector_argument(q, "joint_positions", model.dof())?;
    let load = load(payload, wrench, gravity).or_raise()?;
    let mut torques = vec![0.0; model.dof()];
    library_joint_torques(model, &mut Data::new(model), &q, &load, &mut torques).or_raise()?;
    Ok(vector(py, &torques))
}

/// Seed 001's energy measure `F = sum (q_dot_i tau_i)^2` (eq 9).
#[pyfunction]
pub fn energy_measure(q_dot: &Bound<'_, PyAny>, torques: &Bound<'_, PyAny>) -> PyResult<f64> {
    let q_dot = crate::arrays::float_array(q_dot, "joint_velocities")?;
    let mut velocities = Vec::new();
    crate::arrays::copy_values(&q_dot, &mut velocities);
    let torques = vector_argument(torques, "torques", velocities.len())?;
    library_energy_measure(&velocities, &torques).or_raise()
}

/// Seed 001's energy-optimal distribution: the weighted least norm with
/// `a_i = tau_i^2` from the static torques of the load (zero torques get a
/// floor of `torque_floor` times the largest). Returns `(q_dot, torques, F)`.
#[pyfunction]
#[pyo3(signature = (robot, q, twist, payload=0.0, wrench=None, gravity=true, torque_floor=0.05))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn energy_optimal<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    twist: &Bound<'py, PyAny>,
    payload: f64,
    wrench: Option<Vec<f64>>,
    gravity: bool,
    torque_floor: f64,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>, f64)> {
    let model = &robot.model;
    let dof = model.dof();
    let q = vector_argument(q, "joint_positions", dof)?;
    let twist = Vector6::from_column_slice(&vector_argument(twist, "twist", 6)?);
    let load = load(payload, wrench, gravity).or_raise()?;
    let mut data = Data::new(model);
    let mut torques = vec![0.0; dof];
    library_joint_torques(model, &mut data, &q, &load, &mut torques).or_raise()?;
    let weights =
        JointWeights::from_torques(&torques, TorqueFloor::Relative(torque_floor)).or_raise()?;
    let mut solver = WeightedLeastNorm::new(dof, SolverOptions::default()).or_raise()?;
    let j = jacobian(model, &mut data, &q, JacobianFrame::World).or_raise()?;
    let q_dot = solved(solver.solve(j, &weights, &twist).or_raise()?)?.to_vec();
    let energy = library_energy_measure(&q_dot, &torques).or_raise()?;
    Ok((vector(py, &q_dot), vector(py, &torques), energy))
}
