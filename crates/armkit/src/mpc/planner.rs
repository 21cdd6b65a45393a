//! The planner: [`MpcPlanner`] and what one step reports.

use crate::error::{Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Pose, Rotation3, Vector3};
use crate::model::Model;

use super::constraints::JointBounds;
use super::lexicographic::LexicographicQp;
use super::options::{sized_option, MpcOptions, PriorityMode, ReachAid};
use super::prediction::{weighted_gram, Condensation};
use super::qp::{upper_triangle_len, QpOutcome, QpProblem, QpSolver, QpStatus};
use super::reach::{GoalPosture, GoalSearch};
use super::timing::SolveTimes;
use super::CLAMP_REPORT_THRESHOLD;

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
    /// `solved`, `clamped`, `recovering` or `stopped`.
    pub fn as_str(self) -> &'static str {
        match self {
            StepStatus::Solved => "solved",
            StepStatus::Clamped => "clamped",
            StepStatus::Recovering => "recovering",
            StepStatus::Stopped(_) => "stopped",
        }
    }

    /// True unless the step stopped on a QP failure.
    pub fn is_ok(self) -> bool {
        !matches!(self, StepStatus::Stopped(_))
    }
}

impl std::fmt::Display for StepStatus {
    /// The name, with the QP's status when stopped (`stopped (infeasible)`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepStatus::Stopped(qp) => write!(f, "stopped ({qp})"),
            other => f.write_str(other.as_str()),
        }
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
    bounds: JointBounds,
    solver: Box<dyn QpSolver>,
    goal: Option<GoalPosture>,
    /// Posture weights `(P, P_N)` per rad^2 or m^2 (0 without a goal posture).
    posture_weights: (f64, f64),
    /// `q - q_g`, per joint.
    posture_error: Vec<f64>,
    solve_times: SolveTimes,
    fallback_solves: usize,
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
    /// Builds the planner and its QP (with [`MpcOptions::solver`]; one QP
    /// per priority level with [`PriorityMode::Strict`]) for `model`.
    /// The target starts at the neutral configuration's pose; set it with
    /// [`MpcPlanner::set_target`].
    ///
    /// Errors: invalid options, option vectors of the wrong size,
    /// contradictory limits, or the QP backend failing to set up.
    pub fn new(model: &Model, options: MpcOptions) -> Result<Self> {
        let kind = options.solver;
        let dof = model.dof();
        let control_horizon = options.control_horizon;
        let strict_levels = match options.priority {
            PriorityMode::Weighted => None,
            PriorityMode::Strict => {
                let r = options
                    .increment_weights
                    .clone()
                    .unwrap_or_else(|| vec![1.0; dof]);
                Some(PriorityMode::Strict.joint_levels(&r))
            }
        };
        Self::with_solver(model, options, |problem| match &strict_levels {
            None => kind.build(problem),
            Some(joint_levels) => {
                // Variable `l dof + j` is joint j's increment at control step l.
                let count = joint_levels.iter().max().map_or(0, |m| m + 1);
                let levels: Vec<Vec<usize>> = (0..count)
                    .map(|level| {
                        (0..control_horizon)
                            .flat_map(|l| {
                                joint_levels
                                    .iter()
                                    .enumerate()
                                    .filter(move |&(_, &jl)| jl == level)
                                    .map(move |(j, _)| l * dof + j)
                            })
                            .collect()
                    })
                    .collect();
                Ok(Box::new(LexicographicQp::new(problem, &levels, kind)?) as Box<dyn QpSolver>)
            }
        })
    }

    /// As [`MpcPlanner::new`], with a QP backend made by `build` from the
    /// problem's structure (to plug in another solver). `options.solver` and
    /// `options.priority` are ignored (the backend is `build`'s).
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
        let bounds = JointBounds::new(
            model,
            options.joint_limits.as_deref(),
            options.horizon,
            options.control_horizon,
        )?;
        let goal = match &options.reach {
            ReachAid::Off => None,
            ReachAid::GoalPosture(g) => Some(GoalPosture::new(model, g, &options.task_weights)?),
        };
        let posture_weights = match &options.reach {
            ReachAid::Off => (0.0, 0.0),
            ReachAid::GoalPosture(g) => {
                let mean = |w: &[f64; 6]| {
                    let active: Vec<f64> = w.iter().copied().filter(|&v| v > 0.0).collect();
                    active.iter().sum::<f64>() / active.len().max(1) as f64
                };
                let w = &options.task_weights;
                (g.weight * mean(&w.tracking), g.weight * mean(&w.terminal))
            }
        };
        let condensation = Condensation::new(options.horizon, options.control_horizon)?;
        let variables = dof * options.control_horizon;
        let constraints = bounds.matrix(dof, options.control_horizon, options.sample_time);
        let rows = constraints.rows;
        let mut planner = MpcPlanner {
            model: model.clone(),
            data: Data::new(model),
            dof,
            condensation,
            increment_weights,
            velocity_weights,
            weighted_velocity: vec![0.0; dof],
            bounds,
            solver: Box::new(NoSolver),
            goal,
            posture_weights,
            posture_error: vec![0.0; dof],
            solve_times: SolveTimes::new(),
            fallback_solves: 0,
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
            .zip(planner.bounds.lower.iter().zip(&planner.bounds.upper))
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
        &self.bounds.velocity_limit
    }

    /// Position limits in use: `(lower, upper)`, one per joint.
    pub fn position_limits(&self) -> (&[f64], &[f64]) {
        (&self.bounds.lower, &self.bounds.upper)
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
        if let Some(goal) = &mut self.goal {
            goal.reset();
        }
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
    /// trouble is a [`StepStatus`]. Allocates nothing, except the goal
    /// posture's IK search ([`super::ReachAid::GoalPosture`]: at the first
    /// step after [`MpcPlanner::set_target`], and after a stall while no
    /// goal posture is found).
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
        let fallbacks = self.solver.fallback_solves();
        let outcome = self.solver.solve(
            &self.hessian_upper,
            &self.gradient,
            &self.bound_lower,
            &self.bound_upper,
            &mut self.solution,
        );
        self.report.solve_time = started.elapsed();
        self.solve_times.record(self.report.solve_time);
        self.fallback_solves += self.solver.fallback_solves() - fallbacks;
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
            let applied = self.bounds.applied(j, qj, planned, t);
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
        let posture_scale = self.update_goal_posture(q, &error)?;
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
        let (p_tracking, p_terminal) = (
            posture_scale * self.posture_weights.0,
            posture_scale * self.posture_weights.1,
        );
        for c in 0..dof {
            // The goal-posture term (see `reach`): `T I` is its `Bt`.
            self.gram_tracking[c * dof + c] += t * t * p_tracking;
            self.gram_terminal[c * dof + c] += t * t * p_terminal;
        }
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
        if posture_scale > 0.0 {
            self.condensation.add_joint_gradient(
                t,
                &self.posture_error,
                &self.previous_velocity,
                p_tracking,
                p_terminal,
                &mut self.gradient,
            );
        }
        let outside = self.bounds.fill(
            q,
            &self.previous_velocity,
            &self.options,
            &mut self.bound_lower,
            &mut self.bound_upper,
        );
        Ok((pose, outside))
    }

    /// Runs the goal-posture search when due (see `reach`) and writes
    /// `q - q_g`; returns the factor on the posture weights (0 when no goal
    /// posture is in use).
    fn update_goal_posture(&mut self, q: &[f64], error: &[f64; 6]) -> Result<f64> {
        let Some(goal) = &mut self.goal else {
            return Ok(0.0);
        };
        let w = &self.options.task_weights;
        let weighted: f64 = (0..6)
            .map(|r| {
                let on = if w.tracking[r] > 0.0 || w.terminal[r] > 0.0 {
                    1.0
                } else {
                    0.0
                };
                on * error[r] * error[r]
            })
            .sum::<f64>()
            .sqrt();
        if !goal.update(&self.target, q, weighted, 1e-6)? {
            return Ok(0.0);
        }
        for ((e, &qj), &g) in self.posture_error.iter_mut().zip(q).zip(&goal.posture) {
            *e = qj - g;
        }
        Ok(goal.fade(weighted))
    }

    /// The goal-posture search's result for the current target
    /// ([`GoalSearch::Pending`] without [`ReachAid::GoalPosture`] or before
    /// the first step).
    pub fn goal_search(&self) -> GoalSearch {
        self.goal.as_ref().map_or(GoalSearch::Pending, |g| g.search)
    }

    /// The goal posture in use (joint positions, m or rad), if any.
    pub fn goal_posture(&self) -> Option<&[f64]> {
        self.goal
            .as_ref()
            .filter(|g| g.search == GoalSearch::Found)
            .map(|g| g.posture.as_slice())
    }

    /// Statistics of the QP solve times of every step so far.
    pub fn solve_times(&self) -> &SolveTimes {
        &self.solve_times
    }

    /// Steps whose QP was answered by the backend's fallback (Clarabel,
    /// behind the active-set solver).
    pub fn fallback_solves(&self) -> usize {
        self.fallback_solves
    }

    /// The joint limits in use, as the QP's bounds see them.
    pub(crate) fn bounds(&self) -> &JointBounds {
        &self.bounds
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
