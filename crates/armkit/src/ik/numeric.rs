//! The numeric solver loop: attempts from the start and from seeded random
//! restarts, each iterating one of the four step rules of [`IkMethod`]
//! (the damping policies are in `damping`, the 6 x 6 linear algebra of a
//! step in `kernel`, the stand-alone pseudo-inverses in `steps`).

use std::time::Instant;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::kernel::{trace, Form, Kernel};
use super::pose_error::{masked_error_norms, pose_error};
use super::protocol::sample_joint;
use super::reach::ReachBound;
use super::{IkMethod, IkOptions, IkReport, IkSelection, IkStatus, Redundancy};
use crate::error::{Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{wrap_angle, Matrix6xX, Pose, Vector6};
use crate::model::{JointKind, Model};

/// When an attempt gives up: after `stall` iterations in a row that did not
/// lower the attempt's best objective below `progress` times itself. Near a
/// solution every step divides the error by far more, so a stall means a
/// local minimum, a singular region or a limit: restart.
#[derive(Clone, Copy, Debug)]
struct Patience {
    stall: usize,
    progress: f64,
}

impl Patience {
    /// The attempt from the caller's start is given more patience: its
    /// solution is the one continuous with the start.
    const START: Patience = Patience {
        stall: 5,
        progress: 0.9,
    };
    /// Random restarts give up sooner: another restart is cheaper than a slow one.
    const RESTART: Patience = Patience {
        stall: 4,
        progress: 0.7,
    };
}
/// Growth of Levenberg-Marquardt's damping after a rejected step.
const LM_REJECT_GROWTH: f64 = 10.0;

/// Pose error at one configuration, with its weighted objective.
#[derive(Clone, Copy, Debug)]
struct Evaluation {
    error: Vector6<f64>,
    /// `E = e' W e / 2`.
    objective: f64,
}

/// How one attempt ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AttemptEnd {
    Converged,
    Stalled,
    OutOfTime,
}

/// A numeric inverse-kinematics solver for one model: options and every
/// workspace, sized once by [`IkSolver::new`]; [`IkSolver::solve`] then
/// allocates only its report's joint vector.
///
/// Not `Sync`-shared: use one solver per thread.
#[derive(Clone, Debug)]
pub struct IkSolver {
    model: Model,
    options: IkOptions,
    kernel: Kernel,
    kinds: Vec<JointKind>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    current: Data,
    trial: Data,
    q: Vec<f64>,
    q_trial: Vec<f64>,
    step: Vec<f64>,
    start: Vec<f64>,
    best: Vec<f64>,
    solution: Vec<f64>,
    /// Joints held at a limit in the current step (active set).
    held: Vec<bool>,
    /// The Jacobian with the held joints' columns zeroed.
    held_jacobian: Matrix6xX<f64>,
    /// Targets beyond it are not attempted.
    reach: ReachBound,
}

impl IkSolver {
    /// A solver for `model` (cloned) with validated `options`.
    pub fn new(model: &Model, options: IkOptions) -> Result<IkSolver> {
        options.validate()?;
        let n = model.dof();
        if n == 0 {
            return Err(Error::invalid_argument("model", "has no moving joints"));
        }
        let (lower, upper) = model.position_limits();
        Ok(IkSolver {
            model: model.clone(),
            options,
            kernel: Kernel::new(&options.task_weights, n),
            kinds: model.joints().iter().map(|j| j.kind).collect(),
            lower,
            upper,
            current: Data::new(model),
            trial: Data::new(model),
            q: vec![0.0; n],
            q_trial: vec![0.0; n],
            step: vec![0.0; n],
            start: vec![0.0; n],
            best: vec![0.0; n],
            solution: vec![0.0; n],
            held: vec![false; n],
            held_jacobian: Matrix6xX::zeros(n),
            reach: ReachBound::of_model(model),
        })
    }

    /// The options in use.
    pub fn options(&self) -> &IkOptions {
        &self.options
    }

    /// The model solved for.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Replaces the options (validated); workspaces are kept.
    pub fn set_options(&mut self, options: IkOptions) -> Result<()> {
        options.validate()?;
        self.kernel = Kernel::new(&options.task_weights, self.model.dof());
        self.options = options;
        Ok(())
    }

    /// Solves for joint positions that put the end-effector at `target`
    /// (world frame), starting from `start` (one value per joint, rad or m;
    /// clamped into the limits if outside).
    ///
    /// Errors only for bad input: `start` of the wrong size or not finite, a
    /// `target` with a non-finite entry or a rotation that is not
    /// orthonormal (to 1e-6) with determinant +1. Not reaching the target is
    /// [`IkStatus::NotConverged`] with the best iterate; a target beyond the
    /// arm's reach ([`ReachBound`], when all three position components are
    /// weighted) is not attempted: `NotConverged` at once, with the start
    /// (projected into the limits) and no iterations.
    pub fn solve(&mut self, target: &Pose, start: &[f64]) -> Result<IkReport> {
        let began = Instant::now();
        self.model.check_joint_positions(start)?;
        check_target(target)?;
        let deadline = self.options.time_budget.map(|b| began + b);
        let mut rng = ChaCha8Rng::seed_from_u64(self.options.seed);
        for (j, value) in start.iter().enumerate() {
            self.start[j] = self.project(j, *value);
        }
        let wanted = match self.options.selection {
            IkSelection::First => 1,
            IkSelection::Nearest { solutions } => solutions,
        };
        let mut best_objective = f64::INFINITY;
        let mut found = 0usize;
        let mut solution_distance = f64::INFINITY;
        let mut iterations = 0usize;
        let mut restarts = 0usize;
        let attempts = if self.beyond_reach(target) {
            self.best.copy_from_slice(&self.start);
            0
        } else {
            self.options.max_restarts + 1
        };
        for attempt in 0..attempts {
            if attempt == 0 {
                self.q.copy_from_slice(&self.start);
            } else {
                restarts += 1;
                self.random_configuration(&mut rng);
            }
            let patience = if attempt == 0 {
                Patience::START
            } else {
                Patience::RESTART
            };
            let (end, used) = self.attempt(target, deadline, &mut best_objective, patience)?;
            iterations += used;
            if end == AttemptEnd::Converged {
                self.nearest_representation();
                let distance = self.distance_to_start(&self.q);
                if distance < solution_distance {
                    solution_distance = distance;
                    self.solution.copy_from_slice(&self.q);
                }
                found += 1;
                if found >= wanted {
                    break;
                }
            }
            if end == AttemptEnd::OutOfTime || deadline.is_some_and(|d| Instant::now() >= d) {
                break;
            }
        }
        if found > 0 {
            self.q.copy_from_slice(&self.solution);
            if let Redundancy::PullToStart {
                gain,
                iterations: extra,
            } = self.options.redundancy
            {
                iterations += self.pull_to_start(target, gain, extra)?;
            }
        } else {
            self.q.copy_from_slice(&self.best);
        }
        // The report is computed afresh at the returned q: never a success
        // above tolerance, whatever happened before.
        let evaluation = self.evaluate_current(target)?;
        let (position_error, orientation_error) =
            masked_error_norms(&evaluation.error, &self.options.task_weights);
        let status = if self.within_tolerance(&evaluation.error) {
            IkStatus::Converged
        } else {
            IkStatus::NotConverged
        };
        Ok(IkReport {
            status,
            q: self.q.clone(),
            position_error,
            orientation_error,
            iterations,
            restarts,
            elapsed: began.elapsed(),
        })
    }

    /// True when every position component is weighted and `target` is
    /// beyond the reach bound.
    pub fn beyond_reach(&self, target: &Pose) -> bool {
        self.options.task_weights[..3].iter().all(|w| *w > 0.0) && self.reach.excludes(target)
    }

    /// The reach bound of the model.
    pub fn reach(&self) -> &ReachBound {
        &self.reach
    }

    /// One attempt from `self.q`: iterates until converged, stalled, out of
    /// iterations or out of time. Keeps `self.best` (the lowest objective
    /// seen over all attempts) up to date. Returns how it ended and the
    /// iterations used.
    fn attempt(
        &mut self,
        target: &Pose,
        deadline: Option<Instant>,
        best_objective: &mut f64,
        patience: Patience,
    ) -> Result<(AttemptEnd, usize)> {
        let mut current = self.evaluate_current(target)?;
        self.record_best(&current, best_objective);
        let mut attempt_best = current.objective;
        let mut stall = 0usize;
        let mut damping_scale = 1.0;
        for iteration in 0..self.options.max_iterations {
            if self.within_tolerance(&current.error) {
                return Ok((AttemptEnd::Converged, iteration));
            }
            if iteration % 4 == 3 && deadline.is_some_and(|d| Instant::now() >= d) {
                return Ok((AttemptEnd::OutOfTime, iteration));
            }
            let stepped = self.compute_step(&current, damping_scale);
            let mut progressed = false;
            if stepped {
                for j in 0..self.q.len() {
                    self.q_trial[j] = self.project(j, self.q[j] + self.step[j]);
                }
                let trial = self.evaluate_trial(target)?;
                let accept = match self.options.method {
                    IkMethod::LevenbergMarquardt(_) => trial.objective < current.objective,
                    _ => trial.objective.is_finite(),
                };
                if accept {
                    std::mem::swap(&mut self.current, &mut self.trial);
                    std::mem::swap(&mut self.q, &mut self.q_trial);
                    current = trial;
                    self.record_best(&current, best_objective);
                    damping_scale = (damping_scale * 0.5).max(1.0);
                } else {
                    damping_scale *= LM_REJECT_GROWTH;
                }
                if current.objective < patience.progress * attempt_best {
                    attempt_best = current.objective;
                    progressed = true;
                }
            } else {
                damping_scale *= LM_REJECT_GROWTH;
            }
            if progressed {
                stall = 0;
            } else {
                stall += 1;
                if stall >= patience.stall && !self.within_tolerance(&current.error) {
                    return Ok((AttemptEnd::Stalled, iteration + 1));
                }
            }
        }
        let end = if self.within_tolerance(&current.error) {
            AttemptEnd::Converged
        } else {
            AttemptEnd::Stalled
        };
        Ok((end, self.options.max_iterations))
    }

    /// The method's step at the current iterate into `self.step`; false if
    /// no finite step could be formed.
    ///
    /// Joint limits are an active set: a joint at a limit whose step would
    /// push it further out is held (its Jacobian column zeroed) and the step
    /// recomputed, so that the other joints make up for it instead of the
    /// whole step being distorted by clamping.
    fn compute_step(&mut self, current: &Evaluation, damping_scale: f64) -> bool {
        let method = self.options.method;
        if !method_step(
            &self.kernel,
            method,
            self.current.jacobian(),
            current,
            damping_scale,
            &mut self.step,
        ) {
            return false;
        }
        let mut any_held = false;
        for (j, held) in self.held.iter_mut().enumerate() {
            let q = self.q[j];
            *held = (q <= self.lower[j] && self.step[j] < 0.0)
                || (q >= self.upper[j] && self.step[j] > 0.0);
            any_held |= *held;
        }
        if !any_held {
            return true;
        }
        self.held_jacobian.copy_from(self.current.jacobian());
        for (j, held) in self.held.iter().enumerate() {
            if *held {
                self.held_jacobian.column_mut(j).fill(0.0);
            }
        }
        let ok = method_step(
            &self.kernel,
            method,
            &self.held_jacobian,
            current,
            damping_scale,
            &mut self.step,
        );
        for (value, held) in self.step.iter_mut().zip(&self.held) {
            if *held {
                *value = 0.0;
            }
        }
        ok
    }

    /// Null-space steps toward the start after convergence (redundant
    /// robots, [`Redundancy::PullToStart`]); `self.q` stays converged.
    /// Returns the iterations used.
    fn pull_to_start(&mut self, target: &Pose, gain: f64, extra: usize) -> Result<usize> {
        if self.kernel.form != Form::Task || self.kernel.rank >= self.model.dof() {
            return Ok(0);
        }
        let mut current = self.evaluate_current(target)?;
        // self.q is converged: it is the fallback answer.
        self.solution.copy_from_slice(&self.q);
        let mut best_distance = self.distance_to_start(&self.q);
        let mut used = extra;
        for iteration in 0..extra {
            let j = self.current.jacobian();
            let kernel = &self.kernel;
            let a0 = kernel.normal_matrix(j);
            let rhs = kernel.rhs(j, &current.error);
            // r = gain (q_start - q); its null-space part is r - J' S (S J J' S)^-1 S J r.
            let mut task_of_r = Vector6::zeros();
            for (c, col) in j.column_iter().enumerate() {
                task_of_r.axpy(gain * (self.start[c] - self.q[c]), &col, 1.0);
            }
            let task_of_r = task_of_r.component_mul(&kernel.sqrt_weights);
            let mu = 1e-12 * trace(&a0).max(f64::MIN_POSITIVE);
            let (Some(y), Some(y_null)) = (
                kernel.solve_damped(&a0, mu, &rhs),
                kernel.solve_damped(&a0, mu, &task_of_r),
            ) else {
                used = iteration;
                break;
            };
            let combined = y - y_null;
            kernel.map_back(j, &combined, &mut self.step);
            let mut moved = 0.0;
            for c in 0..self.q.len() {
                let null_part = gain * (self.start[c] - self.q[c]);
                let value = self.project(c, self.q[c] + self.step[c] + null_part);
                moved += (value - self.q[c]).powi(2);
                self.q_trial[c] = value;
            }
            // Every step is taken (the task part corrects the second-order
            // drift of the previous null-space move); the answer is the
            // converged iterate nearest the start.
            current = self.evaluate_trial(target)?;
            std::mem::swap(&mut self.current, &mut self.trial);
            std::mem::swap(&mut self.q, &mut self.q_trial);
            let distance = self.distance_to_start(&self.q);
            if self.within_tolerance(&current.error) && distance < best_distance {
                best_distance = distance;
                self.solution.copy_from_slice(&self.q);
            }
            if moved.sqrt() < 1e-12 {
                used = iteration + 1;
                break;
            }
        }
        self.q.copy_from_slice(&self.solution);
        Ok(used)
    }

    fn evaluate_current(&mut self, target: &Pose) -> Result<Evaluation> {
        jacobian(
            &self.model,
            &mut self.current,
            &self.q,
            JacobianFrame::World,
        )?;
        Ok(self.evaluation(target, self.current.end_effector_pose()))
    }

    fn evaluate_trial(&mut self, target: &Pose) -> Result<Evaluation> {
        jacobian(
            &self.model,
            &mut self.trial,
            &self.q_trial,
            JacobianFrame::World,
        )?;
        Ok(self.evaluation(target, self.trial.end_effector_pose()))
    }

    fn evaluation(&self, target: &Pose, pose: &Pose) -> Evaluation {
        let error = pose_error(target, pose);
        let weighted = error.component_mul(&self.kernel.sqrt_weights);
        Evaluation {
            error,
            objective: 0.5 * weighted.norm_squared(),
        }
    }

    fn record_best(&mut self, evaluation: &Evaluation, best_objective: &mut f64) {
        if evaluation.objective < *best_objective {
            *best_objective = evaluation.objective;
            self.best.copy_from_slice(&self.q);
        }
    }

    fn within_tolerance(&self, error: &Vector6<f64>) -> bool {
        let (position, orientation) = masked_error_norms(error, &self.options.task_weights);
        position <= self.options.position_tolerance
            && orientation <= self.options.orientation_tolerance
    }

    /// Joint j's value moved into its limits: clamped, or wrapped to
    /// (-pi, pi] for a continuous joint.
    fn project(&self, j: usize, value: f64) -> f64 {
        match self.kinds[j] {
            JointKind::Continuous => wrap_angle(value),
            _ => value.clamp(self.lower[j], self.upper[j]),
        }
    }

    /// A configuration drawn uniformly within the limits into `self.q`
    /// (see [`super::protocol::sample_joint`]).
    fn random_configuration(&mut self, rng: &mut ChaCha8Rng) {
        for (j, joint) in self.model.joints().iter().enumerate() {
            self.q[j] = sample_joint(joint, self.start[j], rng);
        }
    }

    /// For each rotational joint, the 2 pi multiple of `self.q[j]` nearest
    /// the start that lies within the limits (the pose does not change).
    fn nearest_representation(&mut self) {
        use std::f64::consts::TAU;
        for j in 0..self.q.len() {
            if !self.kinds[j].is_rotational() {
                continue;
            }
            let value = self.q[j];
            let turns = ((self.start[j] - value) / TAU).round();
            let mut chosen = value;
            for k in [turns, turns - 1.0, turns + 1.0] {
                let candidate = value + k * TAU;
                let inside = match self.kinds[j] {
                    JointKind::Continuous => true,
                    _ => candidate >= self.lower[j] && candidate <= self.upper[j],
                };
                if inside && (candidate - self.start[j]).abs() < (chosen - self.start[j]).abs() {
                    chosen = candidate;
                }
            }
            self.q[j] = chosen;
        }
    }

    fn distance_to_start(&self, q: &[f64]) -> f64 {
        q.iter()
            .zip(&self.start)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt()
    }
}

/// One step of `method` for the Jacobian `j` at the evaluation `current`
/// into `step`; false if no finite step could be formed.
fn method_step(
    kernel: &Kernel,
    method: IkMethod,
    j: &Matrix6xX<f64>,
    current: &Evaluation,
    damping_scale: f64,
    step: &mut [f64],
) -> bool {
    let a0 = kernel.normal_matrix(j);
    let rhs = kernel.rhs(j, &current.error);
    let y = match method {
        IkMethod::NewtonRaphson => kernel.solve_damped(&a0, 0.0, &rhs).or_else(|| {
            let mu = 1e-12 * trace(&a0).max(f64::MIN_POSITIVE);
            kernel.solve_damped(&a0, mu, &rhs)
        }),
        IkMethod::DampedLeastSquares(nakamura) => {
            let lambda = nakamura.damping(kernel.manipulability(&a0));
            kernel.solve_damped(&a0, lambda * lambda, &rhs)
        }
        IkMethod::LevenbergMarquardt(lm) => {
            let mu = damping_scale * (current.objective + lm.floor);
            kernel.solve_damped(&a0, mu, &rhs)
        }
        IkMethod::SingularityRobust(filter) => Some(
            kernel
                .solve_filtered(&a0, &rhs, |s| filter.damping(s), filter.filter)
                .0,
        ),
    };
    match y {
        Some(y) => {
            kernel.map_back(j, &y, step);
            step.iter().all(|v| v.is_finite())
        }
        None => false,
    }
}

/// Checks an IK target: finite, rotation orthonormal to 1e-6, determinant +1.
pub(crate) fn check_target(target: &Pose) -> Result<()> {
    // The one pose validation (`Pose::check_rigid`, tolerance `ROTATION_TOLERANCE`).
    target
        .check_rigid()
        .map_err(|reason| Error::invalid_argument("target", reason))
}
