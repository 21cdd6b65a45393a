//! Model-predictive trajectory planning for (redundant) manipulators, after
//! seed 000 sections 4-5 (Wang, Li, Xi), on a maintained QP solver.
//!
//! Every sample the planner
//! 1. re-linearises: the Jacobian `J(q)` at the measured joint positions (on
//!    the gantry with beam coupling, `J = J0 M` with the slope `m2` of the
//!    deflection at the carriage: seed 000 eqs 8-10, corrected);
//! 2. predicts the task outputs over `N` samples with the incremental model
//!    `x(k+1) = x(k) + T J u(k)`, `u(k) = u(k-1) + du(k)` (eqs 13-14, 21; see
//!    [`prediction`]) from the measured pose (the feedback correction of
//!    sec 4.5: the prediction restarts from the measurement, so a
//!    model error made at the previous sample, reported as
//!    [`StepReport::prediction_error`], does not accumulate);
//! 3. solves the QP of eq 22: tracking cost with weights `Q` (a terminal
//!    weight on step `N`) plus `|dU|^2_R` (the joint priorities of sec 4.4),
//!    subject to the joint velocity limits (eq 17) over the control horizon
//!    and the joint position limits (eq 18) at every one of the `N`
//!    predicted samples (the joint-space prediction `q(k+i) = q(k) + T sum u`
//!    is exact for velocity commands held over a sample, so no limit is
//!    crossed between samples either);
//! 4. applies the first input `u(k)` (receding horizon), after a last check
//!    that clamps it to the velocity limits and to the position limits one
//!    sample ahead (it only acts on solver round-off or failure, and says so).
//!
//! The task is the end-effector pose: position (m, world frame) and
//! orientation as the rotation vector from the current to the target
//! orientation (rad, world axes), each of the 6 coordinates weighted on its
//! own ([`TaskWeights`]): position only, full pose, or any subset.
//!
//! Infeasibility is handled, never hidden: a start outside the position
//! limits relaxes those joints' bounds to what they can reach moving back at
//! [`MpcOptions::recovery_speed`] of their speed limit ([`StepStatus::Recovering`]);
//! a QP failure gives a controlled stop ([`StepStatus::Stopped`]);
//! contradictory limits are rejected when the planner is built.
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::math::{Pose, Vector3};
//! use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights};
//!
//! let model = armkit::robots::by_name("panda").unwrap();
//! let mut q = vec![0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
//! let start = *forward_kinematics(&model, &mut Data::new(&model), &q).unwrap();
//! let target = Pose::new(start.rotation, start.translation + Vector3::new(0.05, -0.05, 0.05));
//! let options = MpcOptions {
//!     task_weights: TaskWeights::position_only(10.0, 200.0),
//!     ..MpcOptions::default()
//! };
//! let mut planner = MpcPlanner::new(&model, options).unwrap();
//! planner.set_target(&target).unwrap();
//! for _ in 0..100 {
//!     let report = planner.step(&q).unwrap();
//!     // Integrate the commanded joint velocities over one sample (the plant).
//!     for (qj, uj) in q.iter_mut().zip(&report.velocity) {
//!         *qj += 0.05 * uj;
//!     }
//! }
//! assert!(planner.step(&q).unwrap().position_error < 1e-4);
//! ```

pub mod prediction;
pub mod qp;
pub mod scenario;

use crate::error::{Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Pose, Rotation3, Vector3};
use crate::model::Model;

use prediction::{weighted_gram, Condensation};
use qp::{upper_triangle_len, CscMatrix, QpOutcome, QpProblem, QpSolver, QpSolverKind, QpStatus};

/// Default sample time `T`, s. Seed 000 does not print it; 0.05 s (20 Hz
/// planning, a 0.5 s horizon with `N = 10`) makes its weights behave as its
/// figures describe (see [`scenario`]).
pub const DEFAULT_SAMPLE_TIME: f64 = 0.05;

/// Commands that cross a limit by more than this (m/s or rad/s, after the
/// QP) are reported as [`StepStatus::Clamped`]; smaller crossings are solver
/// round-off, clamped silently.
pub const CLAMP_REPORT_THRESHOLD: f64 = 1e-6;

/// Diagonal task-space weights of eq 20: `tracking` on predicted samples
/// `1..N-1`, `terminal` on sample `N`. Order `[x, y, z, rx, ry, rz]`:
/// position in m, orientation as a rotation vector in rad (world axes).
/// A zero weight leaves that coordinate free (seed 000's examples track
/// position only).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaskWeights {
    /// `Q` on samples `1..N-1` (1/m^2 for position, 1/rad^2 for orientation).
    pub tracking: [f64; 6],
    /// `Q` on sample `N` (the terminal weight).
    pub terminal: [f64; 6],
}

impl TaskWeights {
    /// Position only: `tracking` on x, y, z for samples `1..N-1`, `terminal`
    /// on sample `N`; orientation free (seed 000: Q = 10, terminal 200).
    pub fn position_only(tracking: f64, terminal: f64) -> Self {
        TaskWeights {
            tracking: [tracking, tracking, tracking, 0.0, 0.0, 0.0],
            terminal: [terminal, terminal, terminal, 0.0, 0.0, 0.0],
        }
    }

    /// Full pose: the same weights on position (per m) and orientation (per rad).
    pub fn full_pose(tracking: f64, terminal: f64) -> Self {
        TaskWeights {
            tracking: [tracking; 6],
            terminal: [terminal; 6],
        }
    }

    /// True when some orientation coordinate has a non-zero weight.
    pub fn tracks_orientation(&self) -> bool {
        self.tracking[3..]
            .iter()
            .chain(&self.terminal[3..])
            .any(|&w| w > 0.0)
    }

    /// Checks every weight is finite and `>= 0`, and at least one is `> 0`.
    pub fn validate(&self) -> Result<()> {
        for (name, weights) in [
            ("task_weights.tracking", &self.tracking),
            ("task_weights.terminal", &self.terminal),
        ] {
            if let Some(w) = weights.iter().find(|w| !(w.is_finite() && **w >= 0.0)) {
                return Err(Error::invalid_argument(
                    name,
                    format!("weights must be finite and >= 0, got {w}"),
                ));
            }
        }
        if self
            .tracking
            .iter()
            .chain(&self.terminal)
            .all(|&w| w == 0.0)
        {
            return Err(Error::invalid_argument(
                "task_weights",
                "at least one weight must be > 0 (nothing to track)",
            ));
        }
        Ok(())
    }
}

impl Default for TaskWeights {
    /// Full pose, seed 000's values: 10 on samples `1..N-1`, 200 on sample `N`.
    fn default() -> Self {
        TaskWeights::full_pose(10.0, 200.0)
    }
}

/// Options of the [`MpcPlanner`], with seed 000's defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct MpcOptions {
    /// Prediction horizon `N`, samples (>= 1). Default 10 (seed 000).
    pub horizon: usize,
    /// Control horizon `M`, `1 <= M <= N`: increments after `M` are zero.
    /// Default 1 (seed 000).
    pub control_horizon: usize,
    /// Sample time `T`, s (> 0). Default [`DEFAULT_SAMPLE_TIME`].
    pub sample_time: f64,
    /// Task-space weights `Q` (eq 20). Default: full pose, 10 and 200.
    pub task_weights: TaskWeights,
    /// Increment weights `R`, one per joint (> 0): the joint priorities of
    /// sec 4.4 (a larger weight, a lower priority). `None`: 1 for every joint.
    pub increment_weights: Option<Vec<f64>>,
    /// Velocity weights `W`: an extra cost `sum_{j<N} u(k+j)' W u(k+j)` on
    /// the joint velocities over the horizon (not in seed 000's eq 20).
    /// Default [`VelocityWeights::Proportional`]`(0.01)`; see
    /// [`VelocityWeights`] for why.
    pub velocity_weights: VelocityWeights,
    /// Velocity limits (> 0, m/s or rad/s), one per joint, overriding the
    /// model's (eq 23). `None`: the model's; a joint with no limit there has
    /// no velocity constraint.
    pub velocity_limits: Option<Vec<f64>>,
    /// Position limits `(lower, upper)` (m or rad), one pair per joint,
    /// overriding the model's (eq 24); infinite values mean unbounded.
    /// `None`: the model's.
    pub position_limits: Option<(Vec<f64>, Vec<f64>)>,
    /// Fraction of a joint's speed limit, in (0, 1], at which a joint that
    /// is outside its position limits is brought back (the bounds of eq 18
    /// are relaxed to what that motion reaches). Default 0.5.
    pub recovery_speed: f64,
    /// The QP backend. Default: [`QpSolverKind::default`] (OSQP when
    /// compiled in, else Clarabel).
    pub solver: QpSolverKind,
}

impl Default for MpcOptions {
    fn default() -> Self {
        MpcOptions {
            horizon: 10,
            control_horizon: 1,
            sample_time: DEFAULT_SAMPLE_TIME,
            task_weights: TaskWeights::default(),
            increment_weights: None,
            velocity_weights: VelocityWeights::default(),
            velocity_limits: None,
            position_limits: None,
            recovery_speed: 0.5,
            solver: QpSolverKind::default(),
        }
    }
}

impl MpcOptions {
    /// Checks the options on their own (sizes against a model are checked by
    /// [`MpcPlanner::new`]).
    pub fn validate(&self) -> Result<()> {
        prediction::check_horizons(self.horizon, self.control_horizon)?;
        if !(self.sample_time.is_finite() && self.sample_time > 0.0) {
            return Err(Error::invalid_argument(
                "sample_time",
                format!("must be finite and > 0 s, got {}", self.sample_time),
            ));
        }
        self.task_weights.validate()?;
        if let Some(r) = &self.increment_weights {
            check_positive("increment_weights", r)?;
        }
        self.velocity_weights.validate()?;
        if let Some(v) = &self.velocity_limits {
            check_positive("velocity_limits", v)?;
        }
        if let Some((lower, upper)) = &self.position_limits {
            if lower.len() != upper.len() {
                return Err(Error::DimensionMismatch {
                    what: "position_limits (upper)",
                    expected: lower.len(),
                    got: upper.len(),
                });
            }
            for (j, (&lo, &hi)) in lower.iter().zip(upper).enumerate() {
                if lo.is_nan() || hi.is_nan() || lo > hi || lo == f64::INFINITY {
                    return Err(Error::invalid_argument(
                        "position_limits",
                        format!(
                            "joint {j}: contradictory limits [{lo}, {hi}] (need lower <= upper)"
                        ),
                    ));
                }
            }
        }
        if !(self.recovery_speed > 0.0 && self.recovery_speed <= 1.0) {
            return Err(Error::invalid_argument(
                "recovery_speed",
                format!("must be in (0, 1], got {}", self.recovery_speed),
            ));
        }
        Ok(())
    }
}

fn check_positive(name: &str, values: &[f64]) -> Result<()> {
    match values
        .iter()
        .enumerate()
        .find(|(_, v)| !(v.is_finite() && **v > 0.0))
    {
        Some((j, v)) => Err(Error::invalid_argument(
            name,
            format!("joint {j}: must be finite and > 0, got {v}"),
        )),
        None => Ok(()),
    }
}

/// The velocity term `sum_{j<N} u(k+j)' W u(k+j)` of the cost (`W`
/// diagonal, one weight per joint, >= 0).
///
/// Seed 000's eq 20 penalises only the increments `du`. For a redundant
/// robot a velocity along its self-motion (the null space of the tracked
/// task) then costs nothing to keep, and nothing stops it: on gantry9 with a
/// position-only task and `W = 0`, the hand reaches the target and stays
/// there while the joints keep drifting (the paper's Fig 9 describes rotary
/// joints that diverge and a system that never settles). A small `W` damps
/// that motion; it vanishes at rest, so it adds no steady-state error.
#[derive(Clone, Debug, PartialEq)]
pub enum VelocityWeights {
    /// `W = 0`: eq 20 as printed.
    Zero,
    /// `W = factor R` (the increment weights): the damping rate of each
    /// joint's self-motion is then the same whatever its priority. `factor`
    /// finite and >= 0.
    Proportional(f64),
    /// One weight per joint, finite and >= 0.
    PerJoint(Vec<f64>),
}

impl Default for VelocityWeights {
    /// `Proportional(0.01)`.
    fn default() -> Self {
        VelocityWeights::Proportional(0.01)
    }
}

impl VelocityWeights {
    /// Checks the factor or weights are finite and >= 0.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: String| Error::invalid_argument("velocity_weights", what);
        match self {
            VelocityWeights::Zero => Ok(()),
            VelocityWeights::Proportional(f) if f.is_finite() && *f >= 0.0 => Ok(()),
            VelocityWeights::Proportional(f) => {
                Err(bad(format!("factor must be finite and >= 0, got {f}")))
            }
            VelocityWeights::PerJoint(w) => match w
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
            {
                Some((j, v)) => Err(bad(format!("joint {j}: must be finite and >= 0, got {v}"))),
                None => Ok(()),
            },
        }
    }

    /// The per-joint weights for increment weights `r`.
    pub fn resolve(&self, r: &[f64]) -> Result<Vec<f64>> {
        self.validate()?;
        match self {
            VelocityWeights::Zero => Ok(vec![0.0; r.len()]),
            VelocityWeights::Proportional(f) => Ok(r.iter().map(|x| f * x).collect()),
            VelocityWeights::PerJoint(w) if w.len() == r.len() => Ok(w.clone()),
            VelocityWeights::PerJoint(w) => Err(Error::DimensionMismatch {
                what: "velocity_weights",
                expected: r.len(),
                got: w.len(),
            }),
        }
    }
}

/// What a planner step did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StepStatus {
    /// The QP was solved and its first input respects every limit.
    Solved,
    /// The QP was solved, but its input crossed a velocity limit or the
    /// position limits one sample ahead by more than
    /// [`CLAMP_REPORT_THRESHOLD`] (an inaccurate solve): the applied input is
    /// clamped to the limits ([`StepReport::limit_correction`] says by how much).
    Clamped,
    /// A joint is outside its position limits: its bounds were relaxed to
    /// what it reaches moving back at [`MpcOptions::recovery_speed`] of its
    /// speed limit, and the input moves it back (never further out).
    Recovering,
    /// The QP failed (status inside): controlled stop. The input is zero,
    /// except for joints outside their position limits, which move back in.
    Stopped(QpStatus),
}

impl StepStatus {
    /// True unless the step stopped on a QP failure.
    pub fn is_ok(self) -> bool {
        !matches!(self, StepStatus::Stopped(_))
    }
}

/// The result of one [`MpcPlanner::step`]; its vectors are reused from step
/// to step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepReport {
    /// What happened.
    pub status: StepStatus,
    /// The QP backend's status and iterations.
    pub qp: QpOutcome,
    /// Joint velocities `u(k)` to apply for the next sample (m/s or rad/s),
    /// one per joint.
    pub velocity: Vec<f64>,
    /// Distance from the measured end-effector position to the target's, m,
    /// at this step (before the move).
    pub position_error: f64,
    /// Angle of the rotation from the measured orientation to the target's,
    /// rad, at this step.
    pub orientation_error: f64,
    /// Distance between the measured position and the one predicted at the
    /// previous step (the feedback correction of sec 4.5), m; 0 on the first
    /// step.
    pub prediction_error: f64,
    /// Wall-clock time of the QP solve alone (update + solve in the backend).
    pub solve_time: std::time::Duration,
    /// Largest change the final limit check made to the QP's input (m/s or
    /// rad/s); round-off-sized unless the status is [`StepStatus::Clamped`]
    /// or [`StepStatus::Stopped`].
    pub limit_correction: f64,
}

/// The seed 000 MPC planner, built once for a model and options; each
/// [`MpcPlanner::step`] re-linearises, updates the QP in place and solves it,
/// allocating nothing.
pub struct MpcPlanner {
    model: Model,
    data: Data,
    options: MpcOptions,
    dof: usize,
    condensation: Condensation,
    increment_weights: Vec<f64>,
    velocity_weights: Vec<f64>,
    /// `W v_old`, per joint.
    weighted_velocity: Vec<f64>,
    /// Per joint, `+inf` when unlimited.
    velocity_limit: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    velocity_rows: Vec<usize>,
    position_rows: Vec<usize>,
    /// Predicted samples `i` whose joint positions are constrained.
    position_steps: Vec<usize>,
    solver: Box<dyn QpSolver>,
    // Workspaces, sized once.
    bt: Vec<f64>,
    gram_tracking: Vec<f64>,
    gram_terminal: Vec<f64>,
    hessian_upper: Vec<f64>,
    gradient: Vec<f64>,
    bound_lower: Vec<f64>,
    bound_upper: Vec<f64>,
    solution: Vec<f64>,
    previous_velocity: Vec<f64>,
    target: Pose,
    predicted_position: Option<Vector3<f64>>,
    report: StepReport,
}

impl MpcPlanner {
    /// Builds the planner and its QP (with [`MpcOptions::solver`]) for `model`.
    /// The target starts at the neutral configuration's pose; set it with
    /// [`MpcPlanner::set_target`].
    ///
    /// Errors: invalid options, option vectors of the wrong size,
    /// contradictory limits, or the QP backend failing to set up.
    pub fn new(model: &Model, options: MpcOptions) -> Result<Self> {
        let kind = options.solver;
        Self::with_solver(model, options, |problem| kind.build(problem))
    }

    /// As [`MpcPlanner::new`], with a QP backend made by `build` from the
    /// problem's structure (to plug in another solver). `options.solver` is
    /// ignored.
    pub fn with_solver(
        model: &Model,
        options: MpcOptions,
        build: impl FnOnce(&QpProblem) -> Result<Box<dyn QpSolver>>,
    ) -> Result<Self> {
        options.validate()?;
        let dof = model.dof();
        let increment_weights = sized_option("increment_weights", &options.increment_weights, dof)?
            .unwrap_or_else(|| vec![1.0; dof]);
        let velocity_weights = options.velocity_weights.resolve(&increment_weights)?;
        let velocity_limit = match sized_option("velocity_limits", &options.velocity_limits, dof)? {
            Some(v) => v,
            None => model
                .joints()
                .iter()
                .map(|j| j.limits.velocity.unwrap_or(f64::INFINITY))
                .collect(),
        };
        if let Some((j, v)) = velocity_limit
            .iter()
            .enumerate()
            .find(|(_, v)| v.is_nan() || **v <= 0.0)
        {
            return Err(Error::invalid_argument(
                "velocity_limits",
                format!("joint {j}: the model's velocity limit {v} must be > 0"),
            ));
        }
        let (lower, upper) = match &options.position_limits {
            Some((lower, upper)) => {
                if lower.len() != dof {
                    return Err(Error::DimensionMismatch {
                        what: "position_limits",
                        expected: dof,
                        got: lower.len(),
                    });
                }
                (lower.clone(), upper.clone())
            }
            None => model.position_limits(),
        };
        if let Some(j) =
            (0..dof).find(|&j| lower[j].is_nan() || upper[j].is_nan() || lower[j] > upper[j])
        {
            return Err(Error::invalid_argument(
                "position_limits",
                format!(
                    "joint {j}: contradictory limits [{}, {}] (need lower <= upper)",
                    lower[j], upper[j]
                ),
            ));
        }
        let velocity_rows: Vec<usize> = (0..dof)
            .filter(|&j| velocity_limit[j].is_finite())
            .collect();
        let position_rows: Vec<usize> = (0..dof)
            .filter(|&j| lower[j].is_finite() || upper[j].is_finite())
            .collect();
        let condensation = Condensation::new(options.horizon, options.control_horizon)?;
        let variables = dof * options.control_horizon;
        let position_steps = constrained_steps(options.horizon, options.control_horizon);
        let constraints = constraint_matrix(
            dof,
            options.control_horizon,
            options.sample_time,
            &velocity_rows,
            &position_rows,
            &position_steps,
        );
        let rows = constraints.rows;
        let mut planner = MpcPlanner {
            model: model.clone(),
            data: Data::new(model),
            dof,
            condensation,
            increment_weights,
            velocity_weights,
            weighted_velocity: vec![0.0; dof],
            velocity_limit,
            lower,
            upper,
            velocity_rows,
            position_rows,
            position_steps,
            solver: Box::new(NoSolver),
            bt: vec![0.0; 6 * dof],
            gram_tracking: vec![0.0; dof * dof],
            gram_terminal: vec![0.0; dof * dof],
            hessian_upper: vec![0.0; upper_triangle_len(variables)],
            gradient: vec![0.0; variables],
            bound_lower: vec![0.0; rows],
            bound_upper: vec![0.0; rows],
            solution: vec![0.0; variables],
            previous_velocity: vec![0.0; dof],
            target: Pose::identity(),
            predicted_position: None,
            report: StepReport {
                status: StepStatus::Solved,
                qp: QpOutcome {
                    status: QpStatus::Solved,
                    iterations: 0,
                },
                velocity: vec![0.0; dof],
                position_error: 0.0,
                orientation_error: 0.0,
                prediction_error: 0.0,
                solve_time: std::time::Duration::ZERO,
                limit_correction: 0.0,
            },
            options,
        };
        // Set the QP up with representative data: the neutral configuration
        // (clamped into the limits), at rest, its own pose as the target.
        let q0: Vec<f64> = planner
            .model
            .neutral_configuration()
            .iter()
            .zip(planner.lower.iter().zip(&planner.upper))
            .map(|(&q, (&lo, &hi))| q.clamp(lo, hi))
            .collect();
        let pose = *crate::kinematics::forward_kinematics(&planner.model, &mut planner.data, &q0)?;
        planner.target = pose;
        planner.assemble(&q0, None)?;
        let problem = QpProblem::new(
            variables,
            planner.hessian_upper.clone(),
            planner.gradient.clone(),
            constraints,
            planner.bound_lower.clone(),
            planner.bound_upper.clone(),
        )?;
        planner.solver = build(&problem)?;
        Ok(planner)
    }

    /// The model the planner was built for.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The options the planner was built with.
    pub fn options(&self) -> &MpcOptions {
        &self.options
    }

    /// Name of the QP backend in use.
    pub fn solver_name(&self) -> &'static str {
        self.solver.name()
    }

    /// QP size: `(variables, constraint rows)` = `(M dof, M nv + (M + 1) np)`
    /// (`M nv + N np` when `M = N`), with
    /// `nv`, `np` the joints with velocity and position limits.
    pub fn problem_size(&self) -> (usize, usize) {
        (self.gradient.len(), self.bound_lower.len())
    }

    /// Velocity limits in use, one per joint (`+inf` where unlimited).
    pub fn velocity_limits(&self) -> &[f64] {
        &self.velocity_limit
    }

    /// Position limits in use: `(lower, upper)`, one per joint.
    pub fn position_limits(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    /// The target pose (world frame).
    pub fn target(&self) -> &Pose {
        &self.target
    }

    /// Sets the target end-effector pose (world frame, m); coordinates with
    /// zero weight in [`MpcOptions::task_weights`] are ignored.
    pub fn set_target(&mut self, target: &Pose) -> Result<()> {
        if !target.is_finite() {
            return Err(Error::invalid_argument("target", "pose must be finite"));
        }
        self.target = *target;
        Ok(())
    }

    /// The increments `dU` of the last step's QP solution (`M dof` values,
    /// control step major: `du(0)` for every joint, then `du(1)`, ...): the
    /// whole planned input sequence is `u(k+l) = v_old + sum_{m<=l} du(m)`,
    /// held after `M`. Zero before the first step and after a QP failure.
    pub fn increments(&self) -> &[f64] {
        &self.solution
    }

    /// The input `u(k-1)` of the previous step (`v_old` of eq 14), one per joint.
    pub fn previous_velocity(&self) -> &[f64] {
        &self.previous_velocity
    }

    /// Sets `v_old` (e.g. the robot's current joint velocities when the
    /// planner takes over; zero after construction) and forgets the last
    /// prediction. Errors: wrong size or non-finite values.
    pub fn reset(&mut self, velocity: &[f64]) -> Result<()> {
        crate::error::check_finite_vector("velocity", velocity, self.dof)?;
        self.previous_velocity.copy_from_slice(velocity);
        self.predicted_position = None;
        Ok(())
    }

    /// One MPC step at measured joint positions `q` (m or rad): the pose is
    /// the model's forward kinematics of `q`. Returns the input to apply.
    ///
    /// Errors only on bad input (`q` of the wrong size or not finite); QP
    /// trouble is a [`StepStatus`]. Allocates nothing.
    pub fn step(&mut self, q: &[f64]) -> Result<&StepReport> {
        self.step_inner(q, None)
    }

    /// As [`MpcPlanner::step`], with the end-effector pose measured
    /// independently (e.g. by a tracker, including deflections the model
    /// lacks): the prediction starts from `measured_pose`, the Jacobian is
    /// evaluated at `q`.
    pub fn step_with_measured_pose(
        &mut self,
        q: &[f64],
        measured_pose: &Pose,
    ) -> Result<&StepReport> {
        if !measured_pose.is_finite() {
            return Err(Error::invalid_argument(
                "measured_pose",
                "pose must be finite",
            ));
        }
        self.step_inner(q, Some(measured_pose))
    }

    fn step_inner(&mut self, q: &[f64], measured: Option<&Pose>) -> Result<&StepReport> {
        let (pose, outside) = self.assemble(q, measured)?;
        let started = std::time::Instant::now();
        let outcome = self.solver.solve(
            &self.hessian_upper,
            &self.gradient,
            &self.bound_lower,
            &self.bound_upper,
            &mut self.solution,
        );
        self.report.solve_time = started.elapsed();
        let t = self.options.sample_time;
        let mut outcome = outcome;
        if outcome.status.has_solution() && self.solution[..self.dof].iter().any(|v| !v.is_finite())
        {
            outcome.status = QpStatus::NumericalFailure;
        }
        if !outcome.status.has_solution() {
            self.solution.iter_mut().for_each(|v| *v = 0.0);
        }
        let mut correction: f64 = 0.0;
        for (j, &qj) in q.iter().enumerate() {
            // Receding horizon: only the first increment is applied (eq 14);
            // on a QP failure, a controlled stop.
            let planned = if outcome.status.has_solution() {
                self.previous_velocity[j] + self.solution[j]
            } else {
                0.0
            };
            let (lo, hi) = self.step_bounds(j, qj);
            let applied =
                guard_position(qj, planned.max(lo).min(hi), t, self.lower[j], self.upper[j]);
            correction = correction.max((applied - planned).abs());
            self.report.velocity[j] = applied;
        }
        self.report.status = if !outcome.status.has_solution() {
            StepStatus::Stopped(outcome.status)
        } else if outside {
            StepStatus::Recovering
        } else if correction > CLAMP_REPORT_THRESHOLD {
            StepStatus::Clamped
        } else {
            StepStatus::Solved
        };
        self.report.qp = outcome;
        self.report.limit_correction = correction;
        // One-sample prediction of the position (eq 13), compared with the
        // next measurement.
        let mut predicted = pose.translation;
        for (r, p) in predicted.iter_mut().enumerate() {
            *p += (0..self.dof)
                .map(|j| self.bt[r * self.dof + j] * self.report.velocity[j])
                .sum::<f64>();
        }
        self.predicted_position = Some(predicted);
        self.previous_velocity
            .copy_from_slice(&self.report.velocity);
        Ok(&self.report)
    }

    /// Re-linearises at `q`, measures the errors and writes the QP data
    /// (Hessian, gradient, bounds). Returns the pose used and whether a
    /// joint is outside its position limits.
    fn assemble(&mut self, q: &[f64], measured: Option<&Pose>) -> Result<(Pose, bool)> {
        let dof = self.dof;
        let t = self.options.sample_time;
        let j = jacobian(&self.model, &mut self.data, q, JacobianFrame::World)?;
        // Eq 13: B = T J(q), re-evaluated every sample (with the beam slope m2).
        for r in 0..6 {
            for c in 0..dof {
                self.bt[r * dof + c] = t * j[(r, c)];
            }
        }
        let pose = match measured {
            Some(p) => *p,
            None => *self.data.end_effector_pose(),
        };
        // Output error a = y(k) - y_d: position in the world frame; the
        // orientation output is the rotation vector from the current
        // orientation (0 now) to the target's: a = -log(R_d R').
        let position_error = pose.translation - self.target.translation;
        let rotation =
            Rotation3::from_matrix_unchecked(self.target.rotation * pose.rotation.transpose());
        let angle_axis = rotation.scaled_axis();
        let mut error = [0.0; 6];
        for r in 0..3 {
            error[r] = position_error[r];
            error[r + 3] = -angle_axis[r];
        }
        self.report.position_error = position_error.norm();
        self.report.orientation_error = angle_axis.norm();
        self.report.prediction_error = self
            .predicted_position
            .map_or(0.0, |p| (pose.translation - p).norm());
        let mut drift = [0.0; 6];
        for (r, d) in drift.iter_mut().enumerate() {
            *d = (0..dof)
                .map(|c| self.bt[r * dof + c] * self.previous_velocity[c])
                .sum();
        }
        let weights = self.options.task_weights;
        weighted_gram(&self.bt, &weights.tracking, &mut self.gram_tracking);
        weighted_gram(&self.bt, &weights.terminal, &mut self.gram_terminal);
        self.condensation.fill_hessian(
            &self.gram_tracking,
            &self.gram_terminal,
            &self.increment_weights,
            &self.velocity_weights,
            &mut self.hessian_upper,
        );
        for ((wv, w), v) in self
            .weighted_velocity
            .iter_mut()
            .zip(&self.velocity_weights)
            .zip(&self.previous_velocity)
        {
            *wv = w * v;
        }
        self.condensation.fill_gradient(
            &self.bt,
            &error,
            &drift,
            &weights.tracking,
            &weights.terminal,
            &self.weighted_velocity,
            &mut self.gradient,
        );
        let outside = self.fill_bounds(q);
        Ok((pose, outside))
    }

    /// Bounds of eqs 17-18 in terms of the increments. Velocity rows: for
    /// `l < M`, `vmin - v_old <= sum_{m<=l} du(m) <= vmax - v_old`. Position
    /// rows: for `i = 1..N`, `q(k+i) = q + i T v_old + T sum_l c(i,l) du(l)`
    /// within `[lo_i, hi_i]`, the limits, relaxed for a joint outside them to
    /// what it reaches returning at the recovery speed. Returns whether a
    /// joint is outside its limits.
    fn fill_bounds(&mut self, q: &[f64]) -> bool {
        let t = self.options.sample_time;
        let nv = self.velocity_rows.len();
        for l in 0..self.options.control_horizon {
            for (k, &j) in self.velocity_rows.iter().enumerate() {
                let row = l * nv + k;
                let v = self.velocity_limit[j];
                self.bound_lower[row] = -v - self.previous_velocity[j];
                self.bound_upper[row] = v - self.previous_velocity[j];
            }
        }
        let offset = self.options.control_horizon * nv;
        let np = self.position_rows.len();
        let recovery = self.options.recovery_speed;
        let mut outside = false;
        for (s, &i) in self.position_steps.iter().enumerate() {
            let it = i as f64 * t;
            for (k, &j) in self.position_rows.iter().enumerate() {
                let row = offset + s * np + k;
                let (mut lo, mut hi) = (self.lower[j], self.upper[j]);
                let reach = it * recovery * self.velocity_limit[j];
                if q[j] > hi {
                    outside = true;
                    hi = hi.max(q[j] - reach);
                }
                if q[j] < lo {
                    outside = true;
                    lo = lo.min(q[j] + reach);
                }
                // An unbounded side gets a bound the joint cannot reach
                // within the horizon, so every bound stays finite and modest.
                let far = it * self.velocity_limit[j].min(1e3) + 1.0;
                if !lo.is_finite() {
                    lo = q[j] - far;
                }
                if !hi.is_finite() {
                    hi = q[j] + far;
                }
                let drift = q[j] + it * self.previous_velocity[j];
                self.bound_lower[row] = lo - drift;
                self.bound_upper[row] = hi - drift;
            }
        }
        outside
    }

    /// Interval of inputs for joint `j` at position `qj` that respect the
    /// velocity limit and keep the joint within its position limits one
    /// sample ahead; a joint already outside may only move back (or hold).
    fn step_bounds(&self, j: usize, qj: f64) -> (f64, f64) {
        let t = self.options.sample_time;
        let v = self.velocity_limit[j];
        let (lower, upper) = (self.lower[j], self.upper[j]);
        let hi = if qj > upper {
            0.0
        } else {
            v.min((upper - qj) / t)
        };
        let lo = if qj < lower {
            0.0
        } else {
            (-v).max((lower - qj) / t)
        };
        (lo, hi.max(lo))
    }
}

/// Shrinks `u` so that `q + T u` stays within `[lower, upper]` in floating
/// point when `q` is (a clamp to `(upper - q) / T` can overshoot by an ulp).
fn guard_position(q: f64, mut u: f64, t: f64, lower: f64, upper: f64) -> f64 {
    for _ in 0..4 {
        let next = q + t * u;
        if q <= upper && next > upper {
            u = (upper - q) / t - (next - upper).abs() / t;
        } else if q >= lower && next < lower {
            u = (lower - q) / t + (lower - next).abs() / t;
        } else {
            break;
        }
    }
    u
}

fn sized_option(
    what: &'static str,
    values: &Option<Vec<f64>>,
    dof: usize,
) -> Result<Option<Vec<f64>>> {
    match values {
        Some(v) if v.len() != dof => Err(Error::DimensionMismatch {
            what,
            expected: dof,
            got: v.len(),
        }),
        other => Ok(other.clone()),
    }
}

/// The predicted samples whose joint positions the QP constrains:
/// `1, ..., M` and `N`. The input changes only at the first `M` samples and
/// is then held, so the predicted joint positions are piecewise linear in
/// the sample index with breakpoints at `1..=M` and end at `N`: within the
/// (constant) limits at these samples means within them at all `N` samples
/// and in between (seed 000 eq 18 over the whole horizon, with `M + 1`
/// instead of `N` rows per joint).
pub(crate) fn constrained_steps(horizon: usize, control_horizon: usize) -> Vec<usize> {
    let mut steps: Vec<usize> = (1..=control_horizon).collect();
    if horizon > control_horizon {
        steps.push(horizon);
    }
    steps
}

/// The constant constraint matrix of eq 19 in the increments `dU` (column
/// `l dof + j` is increment `l` of joint `j`): velocity rows (eq 17) `l = 0..M-1`
/// for each velocity-limited joint, ones on increments `0..=l`; position rows
/// (eq 18) for each sample `i` of `steps` and each position-limited joint,
/// `T c(i, l)` on increments `l < min(i, M)`. Only the bounds change from
/// sample to sample.
fn constraint_matrix(
    dof: usize,
    control_horizon: usize,
    sample_time: f64,
    velocity_rows: &[usize],
    position_rows: &[usize],
    steps: &[usize],
) -> CscMatrix {
    let nv = velocity_rows.len();
    let np = position_rows.len();
    let rows = control_horizon * nv + steps.len() * np;
    let cols = dof * control_horizon;
    let mut col_ptr = Vec::with_capacity(cols + 1);
    let mut row_indices = Vec::new();
    let mut values = Vec::new();
    col_ptr.push(0);
    for l in 0..control_horizon {
        for j in 0..dof {
            if let Some(k) = velocity_rows.iter().position(|&v| v == j) {
                for step in l..control_horizon {
                    row_indices.push(step * nv + k);
                    values.push(1.0);
                }
            }
            if let Some(k) = position_rows.iter().position(|&p| p == j) {
                for (s, &i) in steps.iter().enumerate() {
                    if i > l {
                        row_indices.push(control_horizon * nv + s * np + k);
                        values.push(sample_time * prediction::increment_coefficient(i, l));
                    }
                }
            }
            col_ptr.push(row_indices.len());
        }
    }
    CscMatrix {
        rows,
        cols,
        col_ptr,
        row_indices,
        values,
    }
}

/// Placeholder backend while the planner is being built.
struct NoSolver;

impl QpSolver for NoSolver {
    fn name(&self) -> &'static str {
        "none"
    }
    fn solve(&mut self, _: &[f64], _: &[f64], _: &[f64], _: &[f64], _: &mut [f64]) -> QpOutcome {
        QpOutcome {
            status: QpStatus::NumericalFailure,
            iterations: 0,
        }
    }
}
