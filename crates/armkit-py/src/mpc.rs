//! Seed 000's MPC planner from Python: `armkit.MpcPlanner`.

use armkit::mpc::qp::QpSolverKind;
use armkit::mpc::scenario::{simulate, SimulationOptions};
use armkit::mpc::{
    ActuatorPrecision, MpcOptions, MpcPlanner as LibraryPlanner, PlantModel, PriorityMode,
    ReachAid, TaskWeights,
};
use armkit::Error;
use numpy::ndarray::Dim;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{matrix_from_rows, new_array, pose_argument, vector, vector_argument};
use crate::errors::OrRaise;
use crate::robot::Robot;

/// Seed 000's incremental MPC (Clarabel QP) with joint position and
/// velocity limits as constraints. Each `step(q)` re-linearises at the
/// measured joint positions and returns the joint velocities to apply for
/// one sample. Units: s, m, rad; poses in the world frame.
#[pyclass(unsendable, module = "armkit", name = "MpcPlanner")]
pub struct MpcPlanner {
    planner: LibraryPlanner,
    options: MpcOptions,
    target: Target,
}

/// Whether `set_target` has been called: `step` before it would track the
/// library's placeholder target (the neutral pose) and report "solved".
#[derive(Clone, Copy, PartialEq, Eq)]
enum Target {
    Unset,
    Set,
}

#[pymethods]
impl MpcPlanner {
    /// A planner for `robot`: prediction horizon `horizon` (N samples),
    /// `control_horizon` (M), `sample_time` (s); task weights `tracking` on
    /// samples 1..N-1 and `terminal` on N, on position and, with
    /// `orientation`, on orientation; `increment_weights` (one per joint,
    /// seed 000's priorities: larger moves less; default 1); the velocity
    /// and position limits are the robot's. `solver`: the QP backend,
    /// `"active-set"` (default, Clarabel as its fallback), `"clarabel"` or
    /// `"osqp"` (when built in); `reach`: the goal-posture aid (IK of the
    /// target pulls the predicted joints when progress stalls), on by
    /// default, off for seed 000's planner as printed. `priority`:
    /// `"weighted"` (the increment weights in one cost, eq 20) or
    /// `"strict"` (joints of equal weight form a level, the smallest weight
    /// first; one QP per level with the levels above held at their optimum).
    #[new]
    #[pyo3(signature = (robot, horizon=10, control_horizon=1, sample_time=0.05, tracking=10.0, terminal=200.0, orientation=true, increment_weights=None, solver="active-set", reach=true, priority="weighted"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        robot: &Robot,
        horizon: usize,
        control_horizon: usize,
        sample_time: f64,
        tracking: f64,
        terminal: f64,
        orientation: bool,
        increment_weights: Option<Vec<f64>>,
        solver: &str,
        reach: bool,
        priority: &str,
    ) -> PyResult<Self> {
        let priority = match priority {
            "weighted" => PriorityMode::Weighted,
            "strict" => PriorityMode::Strict,
            other => {
                return Err(Error::invalid_argument(
                    "priority",
                    format!("unknown priority mode `{other}`; expected weighted or strict"),
                ))
                .or_raise()
            }
        };
        let solver = QpSolverKind::available()
            .iter()
            .copied()
            .find(|kind| kind.name() == solver)
            .ok_or_else(|| {
                let known: Vec<&str> = QpSolverKind::available().iter().map(|k| k.name()).collect();
                Error::invalid_argument(
                    "solver",
                    format!(
                        "unknown QP solver `{solver}`; this build has {}",
                        known.join(", ")
                    ),
                )
            })
            .or_raise()?;
        let options = MpcOptions {
            horizon,
            control_horizon,
            sample_time,
            task_weights: if orientation {
                TaskWeights::full_pose(tracking, terminal)
            } else {
                TaskWeights::position_only(tracking, terminal)
            },
            increment_weights,
            priority,
            solver,
            reach: if reach {
                ReachAid::default()
            } else {
                ReachAid::Off
            },
            ..MpcOptions::default()
        };
        let planner = LibraryPlanner::new(&robot.model, options.clone()).or_raise()?;
        Ok(MpcPlanner {
            planner,
            options,
            target: Target::Unset,
        })
    }

    /// The QP backend's name.
    #[getter]
    fn solver(&self) -> &'static str {
        self.planner.solver_name()
    }

    /// Sets the target end-effector pose ((4, 4), world frame, m).
    #[allow(non_snake_case)]
    fn set_target(&mut self, T: &Bound<'_, PyAny>) -> PyResult<()> {
        let target = pose_argument(T, "T")?;
        self.planner.set_target(&target).or_raise()?;
        self.target = Target::Set;
        Ok(())
    }

    /// One planner step at measured joint positions `q` (dof,), after
    /// `set_target` (ValueError before it). Returns a
    /// dict: `status` (`"solved"`, `"clamped"`, `"recovering"` or
    /// `"stopped"`), `velocity` (dof,) to apply for one sample (rad/s or
    /// m/s), `position_error` (m), `orientation_error` (rad),
    /// `prediction_error` (m), `solve_time` (s), `limit_correction`.
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        if self.target == Target::Unset {
            return Err(PyValueError::new_err(
                "MpcPlanner.step: no target; call set_target(T) first",
            ));
        }
        let q = vector_argument(q, "joint_positions", self.planner.model().dof())?;
        let report = self.planner.step(&q).or_raise()?;
        let out = PyDict::new(py);
        out.set_item("status", report.status.as_str())?;
        out.set_item("velocity", vector(py, &report.velocity))?;
        out.set_item("position_error", report.position_error)?;
        out.set_item("orientation_error", report.orientation_error)?;
        out.set_item("prediction_error", report.prediction_error)?;
        out.set_item("solve_time", report.solve_time.as_secs_f64())?;
        out.set_item("limit_correction", report.limit_correction)?;
        Ok(out)
    }

    /// Closed loop from `q_start` to the target `T` (velocities integrated
    /// exactly, or by actuators of limited precision: `*_resolution` the
    /// position resolution (m for prismatic joints, rad for rotary ones),
    /// `*_deadband` the speed below which an axis does not move (m/s,
    /// rad/s); seed 000 Example 3's prismatic drives) until converged or
    /// `max_steps`. Returns a dict of arrays:
    /// `time` (K,), `q` (K, dof), `velocity` (K, dof), `position` (K, 3),
    /// `position_error` (K,), `orientation_error` (K,), `status` (list), and
    /// the summary: `converged`, `steps`, `final_position_error`,
    /// `final_orientation_error`, `max_velocity_violation`,
    /// `max_position_violation`. Not converging is `converged = False`.
    #[pyo3(signature = (T, q_start, max_steps=2000, position_tolerance=1e-4, orientation_tolerance=1e-3, velocity_tolerance=1e-3, prismatic_resolution=0.0, prismatic_deadband=0.0, rotary_resolution=0.0, rotary_deadband=0.0))]
    #[allow(non_snake_case, clippy::too_many_arguments)]
    fn run<'py>(
        &self,
        py: Python<'py>,
        T: &Bound<'py, PyAny>,
        q_start: &Bound<'py, PyAny>,
        max_steps: usize,
        position_tolerance: f64,
        orientation_tolerance: f64,
        velocity_tolerance: f64,
        prismatic_resolution: f64,
        prismatic_deadband: f64,
        rotary_resolution: f64,
        rotary_deadband: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let model = self.planner.model().clone();
        let dof = model.dof();
        let target = pose_argument(T, "T")?;
        let start = vector_argument(q_start, "q_start", dof)?;
        let simulation = SimulationOptions {
            max_steps,
            position_tolerance,
            orientation_tolerance,
            velocity_tolerance,
            plant: PlantModel::of_actuators(
                ActuatorPrecision {
                    position_resolution: prismatic_resolution,
                    deadband: prismatic_deadband,
                    ..ActuatorPrecision::EXACT
                },
                ActuatorPrecision {
                    position_resolution: rotary_resolution,
                    deadband: rotary_deadband,
                    ..ActuatorPrecision::EXACT
                },
            )
            .or_raise()?,
            ..SimulationOptions::default()
        };
        let options = self.options.clone();
        let run = py
            .detach(move || simulate(&model, options, &start, &target, &simulation))
            .or_raise()?;
        let samples = &run.samples;
        let out = PyDict::new(py);
        let column = |f: &dyn Fn(&armkit::mpc::scenario::Sample) -> f64| -> Vec<f64> {
            samples.iter().map(f).collect()
        };
        out.set_item("time", vector(py, &column(&|s| s.time)))?;
        let q: Vec<Vec<f64>> = samples.iter().map(|s| s.q.clone()).collect();
        out.set_item("q", matrix_from_rows(py, &q, dof)?)?;
        let velocity: Vec<Vec<f64>> = samples.iter().map(|s| s.velocity.clone()).collect();
        out.set_item("velocity", matrix_from_rows(py, &velocity, dof)?)?;
        out.set_item(
            "position",
            new_array(py, Dim([samples.len(), 3]), |values| {
                for (row, s) in values.chunks_exact_mut(3).zip(samples) {
                    row.copy_from_slice(&s.position);
                }
                Ok(())
            })?,
        )?;
        out.set_item("position_error", vector(py, &column(&|s| s.position_error)))?;
        out.set_item(
            "orientation_error",
            vector(py, &column(&|s| s.orientation_error)),
        )?;
        let statuses: Vec<&str> = samples.iter().map(|s| s.status.as_str()).collect();
        out.set_item("status", statuses)?;
        let summary = &run.summary;
        out.set_item("converged", summary.converged)?;
        out.set_item("steps", summary.steps)?;
        out.set_item("final_position_error", summary.final_position_error)?;
        out.set_item("final_orientation_error", summary.final_orientation_error)?;
        out.set_item("max_velocity_violation", summary.max_velocity_violation)?;
        out.set_item("max_position_violation", summary.max_position_violation)?;
        Ok(out)
    }
}
