//! Trajectories from Python: joint-space profiles and splines
//! (`armkit.Trajectory`), and seed 002's continuous path along a Cartesian
//! line (`armkit.continuous_path`), sampled as arrays.

use armkit::kinematics::{forward_kinematics, Data};
use armkit::trajectory::{self, ProfileShape};
use armkit::trajectory::{clamped_cubic_spline, TrajectoryLimits};
use armkit::trajectory::{
    measure_path_error, plan_continuous_path, ContinuousPathOptions, PathTolerance, Segmentation,
};
use armkit::trajectory::{path_ik_for, IkTask};
use armkit::trajectory::{CartesianTrajectory, LinePath, OrientationLaw, TimeLaw};
use armkit::trajectory::{JointState, Trajectory};
use armkit::Error;
use numpy::ndarray::Dim;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::arrays::{
    copy_values, float_array, matrix_from_rows, new_array, pose_argument, shape_error, vector,
    vector_argument, write_pose,
};
use crate::errors::OrRaise;
use crate::robot::Robot;

/// A joint-space trajectory: a piecewise polynomial over all joints.
/// Times in s; positions, velocities, accelerations in rad, rad/s, rad/s^2
/// (revolute) or m, m/s, m/s^2 (prismatic).
#[pyclass(frozen, module = "armkit", name = "Trajectory")]
pub struct PyTrajectory {
    pub(crate) inner: Trajectory,
}

/// A boundary state: positions, optional velocities and accelerations (zeros by default).
fn state(
    q: &Bound<'_, PyAny>,
    v: Option<&Bound<'_, PyAny>>,
    a: Option<&Bound<'_, PyAny>>,
    prefix: &'static [&'static str; 3],
) -> PyResult<JointState> {
    let position = vector_argument_any(q, prefix[0])?;
    let dof = position.len();
    let velocity = match v {
        Some(v) => vector_argument(v, prefix[1], dof)?,
        None => vec![0.0; dof],
    };
    let acceleration = match a {
        Some(a) => vector_argument(a, prefix[2], dof)?,
        None => vec![0.0; dof],
    };
    Ok(JointState::new(position, velocity, acceleration))
}

/// A 1-D vector of any length (the library checks sizes and values).
fn vector_argument_any(obj: &Bound<'_, PyAny>, what: &'static str) -> PyResult<Vec<f64>> {
    let array = float_array(obj, what)?;
    if array.ndim() != 1 {
        return Err(shape_error(what, "(dof,)", array.shape()));
    }
    let mut values = Vec::new();
    copy_values(&array, &mut values);
    Ok(values)
}

const START: &[&str; 3] = &["q_start", "v_start", "a_start"];
const END: &[&str; 3] = &["q_end", "v_end", "a_end"];

impl PyTrajectory {
    fn wrap(inner: armkit::Result<Trajectory>) -> PyResult<Self> {
        Ok(PyTrajectory {
            inner: inner.or_raise()?,
        })
    }
}

#[pymethods]
impl PyTrajectory {
    /// Cubic from `q_start` to `q_end` in `duration` s, meeting the boundary
    /// velocities (default zero).
    #[staticmethod]
    #[pyo3(signature = (q_start, q_end, duration, v_start=None, v_end=None))]
    fn cubic(
        q_start: &Bound<'_, PyAny>,
        q_end: &Bound<'_, PyAny>,
        duration: f64,
        v_start: Option<&Bound<'_, PyAny>>,
        v_end: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let start = state(q_start, v_start, None, START)?;
        let end = state(q_end, v_end, None, END)?;
        Self::wrap(trajectory::cubic(&start, &end, duration))
    }

    /// Quintic from `q_start` to `q_end` in `duration` s, meeting boundary
    /// velocities and accelerations (default zero).
    #[staticmethod]
    #[pyo3(signature = (q_start, q_end, duration, v_start=None, v_end=None, a_start=None, a_end=None))]
    fn quintic(
        q_start: &Bound<'_, PyAny>,
        q_end: &Bound<'_, PyAny>,
        duration: f64,
        v_start: Option<&Bound<'_, PyAny>>,
        v_end: Option<&Bound<'_, PyAny>>,
        a_start: Option<&Bound<'_, PyAny>>,
        a_end: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let start = state(q_start, v_start, a_start, START)?;
        let end = state(q_end, v_end, a_end, END)?;
        Self::wrap(trajectory::quintic(&start, &end, duration))
    }

    /// Trapezoidal velocity from rest to rest, synchronized over the joints:
    /// `acceleration_time` s of constant acceleration, cruise, the same of
    /// deceleration (seed 004's path: 20 s with 4 s).
    #[staticmethod]
    fn trapezoidal(
        q_start: &Bound<'_, PyAny>,
        q_end: &Bound<'_, PyAny>,
        duration: f64,
        acceleration_time: f64,
    ) -> PyResult<Self> {
        let q0 = vector_argument_any(q_start, "q_start")?;
        let qf = vector_argument_any(q_end, "q_end")?;
        Self::wrap(trajectory::trapezoidal(
            &q0,
            &qf,
            duration,
            acceleration_time,
        ))
    }

    /// The fastest rest-to-rest profile of `shape` (`"trapezoidal"`,
    /// `"cubic"`, `"quintic"`) within per-joint velocity and acceleration limits.
    #[staticmethod]
    #[pyo3(signature = (q_start, q_end, velocity_limits, acceleration_limits, shape="trapezoidal"))]
    fn minimum_time(
        q_start: &Bound<'_, PyAny>,
        q_end: &Bound<'_, PyAny>,
        velocity_limits: &Bound<'_, PyAny>,
        acceleration_limits: &Bound<'_, PyAny>,
        shape: &str,
    ) -> PyResult<Self> {
        let shape = match shape {
            "trapezoidal" => ProfileShape::Trapezoidal,
            "cubic" => ProfileShape::Cubic,
            "quintic" => ProfileShape::Quintic,
            other => {
                return Err(Error::invalid_argument(
                    "shape",
                    format!("expected \"trapezoidal\", \"cubic\" or \"quintic\", got \"{other}\""),
                ))
                .or_raise()
            }
        };
        let q0 = vector_argument_any(q_start, "q_start")?;
        let qf = vector_argument_any(q_end, "q_end")?;
        let limits = TrajectoryLimits::new(
            vector_argument_any(velocity_limits, "velocity_limits")?,
            vector_argument_any(acceleration_limits, "acceleration_limits")?,
        )
        .or_raise()?;
        Self::wrap(trajectory::minimum_time(shape, &q0, &qf, &limits))
    }

    /// The clamped C2 cubic spline through `positions` (K, dof) at `times`
    /// (K,) s, strictly increasing, with boundary velocities (default zero).
    #[staticmethod]
    #[pyo3(signature = (times, positions, v_start=None, v_end=None))]
    fn spline(
        times: &Bound<'_, PyAny>,
        positions: &Bound<'_, PyAny>,
        v_start: Option<&Bound<'_, PyAny>>,
        v_end: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let times = vector_argument_any(times, "times")?;
        let array = float_array(positions, "positions")?;
        if array.ndim() != 2 {
            return Err(shape_error("positions", "(K, dof)", array.shape()));
        }
        let dof = array.shape()[1];
        let mut values = Vec::new();
        copy_values(&array, &mut values);
        let rows: Vec<&[f64]> = values.chunks_exact(dof.max(1)).collect();
        let v0 = match v_start {
            Some(v) => vector_argument(v, "v_start", dof)?,
            None => vec![0.0; dof],
        };
        let v1 = match v_end {
            Some(v) => vector_argument(v, "v_end", dof)?,
            None => vec![0.0; dof],
        };
        Self::wrap(clamped_cubic_spline(&times, &rows, &v0, &v1))
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// Start time, s.
    #[getter]
    fn start_time(&self) -> f64 {
        self.inner.start_time()
    }

    /// End time, s.
    #[getter]
    fn end_time(&self) -> f64 {
        self.inner.end_time()
    }

    /// Duration, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    /// Segment boundaries (knots), s, shape (segments + 1,).
    #[getter]
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.inner.knots())
    }

    /// Position, velocity and acceleration at time(s) `t` (s; clamped to
    /// the trajectory's span): three arrays of shape (dof,) for a scalar `t`,
    /// (N, dof) for `t` of shape (N,).
    #[allow(clippy::type_complexity)]
    fn sample<'py>(
        &self,
        t: &Bound<'py, PyAny>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = t.py();
        let array = float_array(t, "t")?;
        let mut times = Vec::new();
        copy_values(&array, &mut times);
        let dof = self.inner.dof();
        let mut state = JointState::zeros(dof);
        let n = times.len();
        let (mut q, mut qd, mut qdd) = (vec![0.0; n * dof], vec![0.0; n * dof], vec![0.0; n * dof]);
        for (i, &time) in times.iter().enumerate() {
            self.inner.sample_into(time, &mut state).or_raise()?;
            q[i * dof..(i + 1) * dof].copy_from_slice(&state.position);
            qd[i * dof..(i + 1) * dof].copy_from_slice(&state.velocity);
            qdd[i * dof..(i + 1) * dof].copy_from_slice(&state.acceleration);
        }
        let shape = match array.ndim() {
            0 => vec![dof],
            1 => vec![n, dof],
            _ => return Err(shape_error("t", "() or (N,)", array.shape())),
        };
        let make = |values: Vec<f64>| -> PyResult<Bound<'py, PyAny>> {
            Ok(PyArray1::from_vec(py, values)
                .reshape(shape.clone())?
                .into_any())
        };
        Ok((make(q)?, make(qd)?, make(qdd)?))
    }

    fn __repr__(&self) -> String {
        format!(
            "Trajectory(dof={}, start_time={}, duration={}, segments={})",
            self.inner.dof(),
            self.inner.start_time(),
            self.inner.duration(),
            self.inner.segment_count()
        )
    }
}

/// Seed 002's continuous path: the result of `armkit.continuous_path`.
#[pyclass(frozen, module = "armkit", name = "ContinuousPath")]
pub struct ContinuousPath {
    /// `"tolerance_met"` or `"tolerance_not_met"`.
    #[pyo3(get)]
    status: &'static str,
    /// The joint trajectory (one polynomial per segment).
    #[pyo3(get)]
    trajectory: Py<PyTrajectory>,
    /// IK solutions at the knots, shape (segments + 1, dof).
    #[pyo3(get)]
    configurations: Py<PyArray2<f64>>,
    /// Largest position error found at the check points, m.
    #[pyo3(get)]
    checked_position_error: f64,
    /// Largest orientation error found at the check points, rad.
    #[pyo3(get)]
    checked_orientation_error: f64,
    /// Largest position / orientation error on 100 points per segment, m / rad.
    #[pyo3(get)]
    interior_position_error: f64,
    #[pyo3(get)]
    interior_orientation_error: f64,
    /// Segmentation passes (adaptive: each doubles the failing segments).
    #[pyo3(get)]
    passes: usize,
    /// IK solves over all passes.
    #[pyo3(get)]
    ik_solves: usize,
    /// The IK used at the knots.
    #[pyo3(get)]
    ik_method: &'static str,
    path: CartesianTrajectory,
}

#[pymethods]
impl ContinuousPath {
    /// The Cartesian path's pose(s) at time(s) `t` (s): (4, 4) or (N, 4, 4), world frame, m.
    fn path_poses<'py>(&self, t: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let py = t.py();
        let array = float_array(t, "t")?;
        let mut times = Vec::new();
        copy_values(&array, &mut times);
        if let Some(index) = times.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                what: "t",
                index,
                value: times[index],
            })
            .or_raise();
        }
        let fill = |out: &mut [f64]| {
            for (chunk, &time) in out.chunks_exact_mut(16).zip(&times) {
                write_pose(&self.path.pose_at(time), chunk);
            }
            Ok(())
        };
        match array.ndim() {
            0 => Ok(new_array(py, Dim([4, 4]), fill)?.into_any()),
            1 => Ok(new_array(py, Dim([times.len(), 4, 4]), fill)?.into_any()),
            _ => Err(shape_error("t", "() or (N,)", array.shape())),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "ContinuousPath(status='{}', ik_solves={}, checked_position_error={:.3e})",
            self.status, self.ik_solves, self.checked_position_error
        )
    }
}

/// Seed 002's continuous path along the straight line from the pose at
/// `q_start` to `T_goal` ((4, 4), world frame, m) in `duration` s: IK at
/// the knots, one polynomial per segment, segments doubled where the path
/// error exceeds `tolerance` (m) / `orientation_tolerance` (rad).
/// `law`: `"quintic"`, `"linear"` or `"trapezoidal"` (then
/// `acceleration_time`, default a quarter of the duration); `task`:
/// `"pose"`, `"position"` or `"auto"` (position for arms under 6 DOF);
/// `segments`: a fixed count instead of the adaptive segmentation.
#[pyfunction]
#[pyo3(signature = (robot, q_start, T_goal, duration, law="quintic", acceleration_time=None, task="auto", tolerance=1e-4, orientation_tolerance=1e-3, segments=None, max_segments=4096))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn continuous_path(
    py: Python<'_>,
    robot: &Robot,
    q_start: &Bound<'_, PyAny>,
    T_goal: &Bound<'_, PyAny>,
    duration: f64,
    law: &str,
    acceleration_time: Option<f64>,
    task: &str,
    tolerance: f64,
    orientation_tolerance: f64,
    segments: Option<usize>,
    max_segments: usize,
) -> PyResult<ContinuousPath> {
    let model = &robot.model;
    let q0 = vector_argument_any(q_start, "q_start")?;
    let goal = pose_argument(T_goal, "T_goal")?;
    let law = match (law, acceleration_time) {
        ("quintic", None) => TimeLaw::Quintic,
        ("linear", None) => TimeLaw::Linear,
        ("trapezoidal", ta) => TimeLaw::Trapezoidal {
            acceleration_time: ta.unwrap_or(0.25 * duration),
        },
        ("quintic" | "linear", Some(_)) => {
            return Err(Error::invalid_argument(
                "acceleration_time",
                "is for law=\"trapezoidal\"",
            ))
            .or_raise()
        }
        (other, _) => {
            return Err(Error::invalid_argument(
                "law",
                format!("expected \"quintic\", \"linear\" or \"trapezoidal\", got \"{other}\""),
            ))
            .or_raise()
        }
    };
    let task = match task {
        "pose" => IkTask::Pose,
        "position" => IkTask::Position,
        "auto" if model.dof() < 6 => IkTask::Position,
        "auto" => IkTask::Pose,
        other => {
            return Err(Error::invalid_argument(
                "task",
                format!("expected \"pose\", \"position\" or \"auto\", got \"{other}\""),
            ))
            .or_raise()
        }
    };
    let tolerance = match task {
        IkTask::Position => PathTolerance::Position(tolerance),
        IkTask::Pose => PathTolerance::Pose {
            position: tolerance,
            orientation: orientation_tolerance,
        },
    };
    let options = ContinuousPathOptions {
        segmentation: match segments {
            Some(n) => Segmentation::Fixed(n),
            None => Segmentation::Adaptive {
                initial: 4.min(max_segments),
                max: max_segments,
            },
        },
        tolerance,
        ..Default::default()
    };
    let run = || -> armkit::Result<_> {
        let start = *forward_kinematics(model, &mut Data::new(model), &q0)?;
        let path = CartesianTrajectory::new(LinePath::new(start, goal)?, law.timing(duration)?)?
            .with_orientation_law(OrientationLaw::FollowPath);
        let (mut ik, method) = path_ik_for(model, task)?;
        let report = plan_continuous_path(model, &path, &mut *ik, &q0, &options)?;
        let interior = measure_path_error(model, &report.trajectory, &path, 100)?;
        Ok((path, report, interior, method))
    };
    let (path, report, interior, method) = py.detach(run).or_raise()?;
    Ok(ContinuousPath {
        status: report.status.as_str(),
        configurations: matrix_from_rows(py, &report.configurations, model.dof())?.unbind(),
        trajectory: Py::new(
            py,
            PyTrajectory {
                inner: report.trajectory,
            },
        )?,
        checked_position_error: report.checked_error.position,
        checked_orientation_error: report.checked_error.orientation,
        interior_position_error: interior.position,
        interior_orientation_error: interior.orientation,
        passes: report.passes,
        ik_solves: report.ik_solves,
        ik_method: method,
        path,
    })
}
