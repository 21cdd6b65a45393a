//! A resolved-rate tracking loop: follow a Cartesian path at the velocity
//! level with position feedback, distributing each twist by any of the
//! redundancy methods of this module.
//!
//! At each sample `t_k` (step `dt`), with the pose error
//! `e = [p_d - p; log(R_d R')]` (world frame, m and rad) and the path's twist
//! `V_d`, the commanded twist is `V = V_d + K e` (`K` the feedback gain, 1/s),
//! shared among the joints by the chosen [`Distribution`] and [`Formulation`],
//! plus a null-space [`SecondaryObjective`]; then `q_{k+1} = q_k + dt q_dot`.
//!
//! Limits are never exceeded:
//! * velocity: `q_dot` is scaled uniformly by `s = min(1, min_i vmax_i / |q_dot_i|)`
//!   (the end effector keeps its direction, only slower; the feedback makes
//!   up the lag);
//! * position: a joint whose step would cross a position limit is locked
//!   (infinite weight) for this step and the twist is re-distributed among
//!   the others; when the remaining joints cannot realise it, the step is
//!   shortened to stop at the limit and the run ends with
//!   [`TrackingStatus::StoppedAtJointLimit`].
//!
//! ```
//! use armkit::math::{Pose, Vector3};
//! use armkit::redundancy::{
//!     Distribution, JointWeights, LinePath, ResolvedRateTracker, TrackingOptions, TrackingStatus,
//! };
//! let model = armkit::robots::by_name("panda").unwrap();
//! let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
//! let mut data = armkit::Data::new(&model);
//! let start = *armkit::forward_kinematics(&model, &mut data, &q0).unwrap();
//! let goal = Pose::from_translation(Vector3::new(0.1, 0.1, -0.1)) * start;
//! let path = LinePath::new(start, goal, 2.0).unwrap();
//! let distribution = Distribution::Weights(JointWeights::uniform(7));
//! let mut tracker = ResolvedRateTracker::new(&model, distribution, TrackingOptions::default()).unwrap();
//! let report = tracker.run(&model, &q0, &path).unwrap();
//! assert_eq!(report.status, TrackingStatus::Completed);
//! assert!(report.final_position_error < 1e-3);
//! ```

use super::energy::{energy_measure, joint_torques, Load, TorqueFloor};
use super::nullspace::{weighted_direction, SecondaryObjective, SecondaryTask};
use super::partition::{best_partition, Partition, PartitionedSolver};
use super::weighted::WeightedLeastNorm;
use super::{Damping, JointWeights, SolverOptions};
use crate::error::{check_finite, check_positive, Error, Result};
use crate::ik::pose_error;
use crate::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use crate::math::{rotation_log, Pose, Rotation3, Vector3, Vector6};
use crate::model::Model;

/// A desired end-effector motion: a pose (world frame) for each time in
/// `[0, duration]` (s).
pub trait CartesianPath {
    /// Duration, s (> 0).
    fn duration(&self) -> f64;

    /// Desired end-effector pose at `time` (s, in `[0, duration]`), world frame.
    fn pose(&self, time: f64) -> Pose;

    /// Desired twist `[v; w]` at `time` (world frame, m/s and rad/s). The
    /// default differentiates [`CartesianPath::pose`] centrally with a step of
    /// 1e-6 s (one-sided at the ends).
    fn twist(&self, time: f64) -> Vector6<f64> {
        let h = 1e-6;
        let before = (time - h).max(0.0);
        let after = (time + h).min(self.duration());
        if after <= before {
            return Vector6::zeros();
        }
        pose_error(&self.pose(after), &self.pose(before)) / (after - before)
    }
}

/// A straight line in position with the orientation turning about one fixed
/// axis (world frame), both timed by a quintic `s(t) = 10 u^3 - 15 u^4 + 6 u^5`,
/// `u = t / duration`: zero velocity and acceleration at both ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinePath {
    start: Pose,
    goal: Pose,
    duration: f64,
    /// `log(R_goal R_start')`, world frame, rad.
    rotation: Vector3<f64>,
}

impl LinePath {
    /// From `start` to `goal` (world frame) in `duration` s (> 0). Errors:
    /// a non-finite pose or duration.
    pub fn new(start: Pose, goal: Pose, duration: f64) -> Result<Self> {
        check_positive("duration", duration)?;
        if !start.is_finite() || !goal.is_finite() {
            return Err(Error::invalid_argument(
                "start/goal",
                "poses must have finite entries",
            ));
        }
        Ok(LinePath {
            start,
            goal,
            duration,
            rotation: rotation_log(&(goal.rotation * start.rotation.transpose())),
        })
    }

    /// The path parameter `s` in `[0, 1]` and its rate `ds/dt` (1/s) at `time`.
    fn timing(&self, time: f64) -> (f64, f64) {
        let u = (time / self.duration).clamp(0.0, 1.0);
        let s = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
        let rate = 30.0 * u * u * (1.0 - u) * (1.0 - u) / self.duration;
        (s, rate)
    }
}

impl CartesianPath for LinePath {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn pose(&self, time: f64) -> Pose {
        let (s, _) = self.timing(time);
        let turn = Rotation3::from_scaled_axis(self.rotation * s).into_inner();
        Pose::new(
            turn * self.start.rotation,
            self.start.translation + (self.goal.translation - self.start.translation) * s,
        )
    }

    fn twist(&self, time: f64) -> Vector6<f64> {
        let (_, rate) = self.timing(time);
        let v = (self.goal.translation - self.start.translation) * rate;
        let w = self.rotation * rate;
        Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z)
    }
}

/// A path given by a closure `time -> Pose` (world frame) over
/// `[0, duration]`; its twist is differentiated numerically.
pub struct FnPath<F: Fn(f64) -> Pose> {
    duration: f64,
    pose: F,
}

impl<F: Fn(f64) -> Pose> FnPath<F> {
    /// A path of `duration` s (> 0) following `pose`.
    pub fn new(duration: f64, pose: F) -> Result<Self> {
        check_positive("duration", duration)?;
        Ok(FnPath { duration, pose })
    }
}

impl<F: Fn(f64) -> Pose> CartesianPath for FnPath<F> {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn pose(&self, time: f64) -> Pose {
        (self.pose)(time)
    }
}

/// How the tracker chooses the joint weights at each step.
#[derive(Clone, Debug, PartialEq)]
pub enum Distribution {
    /// Fixed weights: minimum norm ([`JointWeights::uniform`]), priorities
    /// (seed 000), locked joints.
    Weights(JointWeights),
    /// Seed 001's energy-optimal distribution: weights `max(|tau_i|, f)^2`
    /// recomputed at every step from the joint torques that hold `load` at
    /// the current configuration.
    Energy {
        /// The load whose holding torques weigh the joints.
        load: Load,
        /// The zero-torque rule.
        floor: TorqueFloor,
    },
}

/// Which solver distributes the twist (both give the same velocities).
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Formulation {
    /// [`WeightedLeastNorm`] (damping allowed).
    #[default]
    WeightedLeastNorm,
    /// Seed 001's [`PartitionedSolver`] with this partition, or, with `None`,
    /// the best-conditioned one chosen again at every step (84 SVDs for 9
    /// joints). No damping.
    Partitioned(Option<Partition>),
}

/// Options of [`ResolvedRateTracker`].
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingOptions {
    /// Control period `dt`, s (> 0). The path's duration is split into
    /// `ceil(duration / dt)` equal steps. Default 0.01 s.
    pub time_step: f64,
    /// Feedback gain `K` (1/s) on the pose error, `0 <= K dt <= 1`. Default 10.
    pub feedback_gain: f64,
    /// Damping of the weighted least norm. Default none.
    pub damping: Damping,
    /// Null-space objective. Default none.
    pub secondary: SecondaryObjective,
    /// Solver. Default [`Formulation::WeightedLeastNorm`].
    pub formulation: Formulation,
}

impl Default for TrackingOptions {
    fn default() -> Self {
        TrackingOptions {
            time_step: 0.01,
            feedback_gain: 10.0,
            damping: Damping::None,
            secondary: SecondaryObjective::None,
            formulation: Formulation::WeightedLeastNorm,
        }
    }
}

/// Condition number above which a partition's block counts as singular.
const PARTITION_MAX_CONDITION: f64 = 1e10;

impl TrackingOptions {
    /// Checks every field.
    pub fn validate(&self) -> Result<()> {
        check_positive("time_step", self.time_step)?;
        if !(self.feedback_gain >= 0.0 && self.feedback_gain * self.time_step <= 1.0) {
            return Err(Error::invalid_argument(
                "feedback_gain",
                format!(
                    "must satisfy 0 <= gain * time_step <= 1 (a stable discrete loop), got \
                     gain {} with time_step {}",
                    self.feedback_gain, self.time_step
                ),
            ));
        }
        self.damping.validate()?;
        self.secondary.validate()?;
        if matches!(self.formulation, Formulation::Partitioned(_)) && self.damping != Damping::None
        {
            return Err(Error::invalid_argument(
                "damping",
                "seed 001's partitioned form has no damped variant: use \
                 Formulation::WeightedLeastNorm with damping",
            ));
        }
        Ok(())
    }
}

/// How a tracking run ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TrackingStatus {
    /// The whole path was run; see the report's errors for how well.
    Completed,
    /// A joint position limit stopped the motion: with the joints at their
    /// limits locked, the others could not realise the twist. The last step
    /// stops short of the limit.
    StoppedAtJointLimit {
        /// 0-based joint index.
        joint: usize,
        /// Time of the last step, s.
        time: f64,
    },
    /// The undamped distribution met a singular Jacobian (use damping).
    Singular {
        /// Time of the singular step, s.
        time: f64,
    },
}

/// One control step of a tracking run.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingSample {
    /// Time, s.
    pub time: f64,
    /// Joint positions at `time` (rad or m).
    pub q: Vec<f64>,
    /// Joint velocities applied from `time` to the next sample (rad/s or
    /// m/s); zero in the last sample.
    pub q_dot: Vec<f64>,
    /// `|p_d - p|` at `time`, m.
    pub position_error: f64,
    /// Angle of `R_d R'` at `time`, rad.
    pub orientation_error: f64,
    /// Uniform velocity scale applied for the velocity limits, in `(0, 1]`.
    pub velocity_scale: f64,
    /// Number of joints locked in this step because they would have crossed
    /// a position limit.
    pub limit_locks: usize,
}

/// The result of [`ResolvedRateTracker::run`].
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingReport {
    /// How the run ended.
    pub status: TrackingStatus,
    /// Every sample, the initial one first and the final state last.
    pub samples: Vec<TrackingSample>,
    /// Largest position error over the run, m.
    pub max_position_error: f64,
    /// Largest orientation error over the run, rad.
    pub max_orientation_error: f64,
    /// Position error at the end, m.
    pub final_position_error: f64,
    /// Orientation error at the end, rad.
    pub final_orientation_error: f64,
    /// Steps whose velocities were scaled down for the velocity limits.
    pub velocity_scaled_steps: usize,
    /// Steps in which a joint was locked at a position limit.
    pub limit_locked_steps: usize,
}

/// One computed control step.
#[derive(Clone, Copy, Debug, PartialEq)]
struct StepOutcome {
    velocity_scale: f64,
    limit_locks: usize,
    position_error: f64,
    orientation_error: f64,
    /// `Some(joint)` when a position limit stopped the motion.
    stopped_by: Option<usize>,
}

/// The solver behind a [`Formulation`].
#[derive(Clone, Debug)]
enum Solver {
    LeastNorm(WeightedLeastNorm),
    Partitioned(PartitionedSolver, Option<Partition>),
}

/// Resolved-rate tracking of a Cartesian path; workspaces sized once for one
/// model (a control step allocates nothing; a run allocates its samples).
#[derive(Clone, Debug)]
pub struct ResolvedRateTracker {
    dof: usize,
    options: TrackingOptions,
    distribution: Distribution,
    data: Data,
    weights: JointWeights,
    torques: Vec<f64>,
    solver: Solver,
    secondary: SecondaryTask,
    preferred: Vec<f64>,
    q_dot: Vec<f64>,
    /// The secondary objective's improving direction at the current step.
    direction: Vec<f64>,
    velocity_limits: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

impl ResolvedRateTracker {
    /// A tracker for `model` with `distribution` and `options` (validated;
    /// fixed weights must be for `model.dof()` joints). Joints without a
    /// velocity limit are not scaled.
    pub fn new(
        model: &Model,
        distribution: Distribution,
        options: TrackingOptions,
    ) -> Result<Self> {
        options.validate()?;
        let dof = model.dof();
        let weights = match &distribution {
            Distribution::Weights(w) => {
                w.check_size("weights", dof)?;
                w.clone()
            }
            Distribution::Energy { load, floor } => {
                load.validate()?;
                floor.validate()?;
                JointWeights::uniform(dof)
            }
        };
        let solver = match &options.formulation {
            Formulation::WeightedLeastNorm => Solver::LeastNorm(WeightedLeastNorm::new(
                dof,
                SolverOptions {
                    damping: options.damping,
                    ..SolverOptions::default()
                },
            )?),
            Formulation::Partitioned(partition) => {
                if let Some(p) = partition {
                    if p.dof() != dof {
                        return Err(Error::DimensionMismatch {
                            what: "partition (joints)",
                            expected: dof,
                            got: p.dof(),
                        });
                    }
                }
                Solver::Partitioned(
                    PartitionedSolver::new(dof, PARTITION_MAX_CONDITION)?,
                    partition.clone(),
                )
            }
        };
        let (lower, upper) = model.position_limits();
        Ok(ResolvedRateTracker {
            dof,
            secondary: SecondaryTask::new(model, options.secondary)?,
            options,
            distribution,
            data: Data::new(model),
            weights,
            torques: vec![0.0; dof],
            solver,
            preferred: vec![0.0; dof],
            q_dot: vec![0.0; dof],
            direction: vec![0.0; dof],
            velocity_limits: model
                .joints()
                .iter()
                .map(|j| j.limits.velocity.unwrap_or(f64::INFINITY))
                .collect(),
            lower,
            upper,
        })
    }

    /// The options.
    pub fn options(&self) -> &TrackingOptions {
        &self.options
    }

    /// Follows `path` from joint positions `q0` (within the limits; the
    /// path should start at or near `FK(q0)`, the feedback pulls it in).
    ///
    /// Errors: `q0` of the wrong size, NaN or outside the limits; a model
    /// with a different number of joints; a path whose poses are not
    /// finite. A singular Jacobian or a joint limit that stops the motion
    /// is a status, not an error.
    pub fn run(
        &mut self,
        model: &Model,
        q0: &[f64],
        path: &dyn CartesianPath,
    ) -> Result<TrackingReport> {
        self.check_model(model)?;
        model.check_limits(q0)?;
        let duration = path.duration();
        if !(duration.is_finite() && duration > 0.0) {
            return Err(Error::invalid_argument(
                "path",
                format!("duration must be finite and > 0, got {duration}"),
            ));
        }
        let steps = (duration / self.options.time_step).ceil().max(1.0) as usize;
        let dt = duration / steps as f64;
        let mut q = q0.to_vec();
        let mut samples = Vec::with_capacity(steps + 1);
        let mut status = TrackingStatus::Completed;
        for k in 0..steps {
            let time = k as f64 * dt;
            let desired = path.pose(time);
            let twist = path.twist(time);
            check_path_point(&desired, &twist)?;
            let outcome = match self.control(model, &q, &desired, &twist, dt) {
                Ok(outcome) => outcome,
                Err(Error::Numerical { .. }) => {
                    status = TrackingStatus::Singular { time };
                    break;
                }
                Err(other) => return Err(other),
            };
            samples.push(TrackingSample {
                time,
                q: q.clone(),
                q_dot: self.q_dot.clone(),
                position_error: outcome.position_error,
                orientation_error: outcome.orientation_error,
                velocity_scale: outcome.velocity_scale,
                limit_locks: outcome.limit_locks,
            });
            for (qi, vi) in q.iter_mut().zip(&self.q_dot) {
                *qi += dt * vi;
            }
            if let Some(joint) = outcome.stopped_by {
                status = TrackingStatus::StoppedAtJointLimit { joint, time };
                break;
            }
        }
        // The final state, against the pose due at the time reached.
        let time = samples.last().map_or(0.0, |s| s.time + dt);
        let pose = *forward_kinematics(model, &mut self.data, &q)?;
        let error = pose_error(&path.pose(time.min(duration)), &pose);
        samples.push(TrackingSample {
            time,
            q,
            q_dot: vec![0.0; self.dof],
            position_error: error.fixed_rows::<3>(0).norm(),
            orientation_error: error.fixed_rows::<3>(3).norm(),
            velocity_scale: 1.0,
            limit_locks: 0,
        });
        Ok(TrackingReport::new(status, samples))
    }

    fn check_model(&self, model: &Model) -> Result<()> {
        if model.dof() != self.dof {
            return Err(Error::DimensionMismatch {
                what: "model (joints of the tracker's model)",
                expected: self.dof,
                got: model.dof(),
            });
        }
        Ok(())
    }

    /// One control step at `q`: the joint velocities for the next `dt` s
    /// into `self.q_dot`. Allocates nothing (the best-conditioned partition,
    /// if asked for, allocates its result).
    fn control(
        &mut self,
        model: &Model,
        q: &[f64],
        desired: &Pose,
        desired_twist: &Vector6<f64>,
        dt: f64,
    ) -> Result<StepOutcome> {
        // Weights and Jacobian at q (the torque computation leaves the
        // Jacobian in `data`).
        match &self.distribution {
            Distribution::Weights(w) => {
                jacobian(model, &mut self.data, q, JacobianFrame::World)?;
                self.weights.copy_from(w)?;
            }
            Distribution::Energy { load, floor } => {
                joint_torques(model, &mut self.data, q, load, &mut self.torques)?;
                self.weights.set_from_torques(&self.torques, *floor)?;
            }
        }
        let error = pose_error(desired, self.data.end_effector_pose());
        let twist = desired_twist + error * self.options.feedback_gain;
        let direction_is_zero = self.options.secondary == SecondaryObjective::None;
        if !direction_is_zero {
            // Computed once per step; re-weighted below when joints lock.
            let direction = self.secondary.direction(model, q)?;
            self.direction.copy_from_slice(direction);
        }
        let mut outcome = StepOutcome {
            velocity_scale: 1.0,
            limit_locks: 0,
            position_error: error.fixed_rows::<3>(0).norm(),
            orientation_error: error.fixed_rows::<3>(3).norm(),
            stopped_by: None,
        };
        // At most one round per joint: each round locks at least one more.
        for _round in 0..=self.dof {
            if direction_is_zero {
                self.preferred.fill(0.0);
            } else {
                weighted_direction(&self.weights, &self.direction, &mut self.preferred)?;
            }
            let solved = self.distribute(&twist);
            if let Err(error) = solved {
                if outcome.limit_locks == 0 {
                    return Err(error);
                }
                // The joints left free cannot realise the twist: keep the
                // previous round's velocities, shortened to stop at the limit.
                return Ok(self.stop_at_limit(q, dt, outcome));
            }
            let scale = self.velocity_scale();
            outcome.velocity_scale = scale;
            for v in self.q_dot.iter_mut() {
                *v *= scale;
            }
            let mut crossing = false;
            for (j, &qj) in q.iter().enumerate() {
                let next = qj + dt * self.q_dot[j];
                if next < self.lower[j] || next > self.upper[j] {
                    self.weights.lock(j)?;
                    outcome.limit_locks += 1;
                    crossing = true;
                }
            }
            if !crossing {
                return Ok(outcome);
            }
            // This round's velocities stay in `self.q_dot` for the fallback:
            // the next round overwrites them only when its solve succeeds.
        }
        Ok(self.stop_at_limit(q, dt, outcome))
    }

    /// Shortens `self.q_dot` (the last round's velocities, which cross a
    /// limit) so that no joint crosses its limit; names the first joint to
    /// reach one.
    fn stop_at_limit(&mut self, q: &[f64], dt: f64, mut outcome: StepOutcome) -> StepOutcome {
        let mut fraction: f64 = 1.0;
        let mut stopping = 0;
        for (j, &qj) in q.iter().enumerate() {
            let v = self.q_dot[j];
            let room = if v > 0.0 {
                (self.upper[j] - qj) / (dt * v)
            } else if v < 0.0 {
                (self.lower[j] - qj) / (dt * v)
            } else {
                f64::INFINITY
            };
            if room < fraction {
                fraction = room.max(0.0);
                stopping = j;
            }
        }
        for v in self.q_dot.iter_mut() {
            *v *= fraction;
        }
        outcome.velocity_scale *= fraction;
        outcome.stopped_by = Some(stopping);
        outcome
    }

    /// `q_dot = z + J#_A (V - J z)` into `self.q_dot` (z = `self.preferred`),
    /// with the Jacobian in `self.data`. On error `self.q_dot` is unchanged.
    fn distribute(&mut self, twist: &Vector6<f64>) -> Result<()> {
        let j = self.data.jacobian();
        match &mut self.solver {
            Solver::LeastNorm(solver) => {
                let q_dot = solver.solve_toward(j, &self.weights, twist, &self.preferred)?;
                self.q_dot.copy_from_slice(q_dot);
            }
            Solver::Partitioned(solver, fixed) => {
                let mut residual = *twist;
                for (column, &z) in j.column_iter().zip(&self.preferred) {
                    residual -= column * z;
                }
                let chosen;
                let partition = match fixed {
                    Some(p) => &*p,
                    None => {
                        chosen = best_partition(j, Some(&self.weights), PARTITION_MAX_CONDITION)?;
                        &chosen.partition
                    }
                };
                let q_dot = solver.solve(j, &self.weights, &residual, partition)?;
                for ((out, &v), &z) in self.q_dot.iter_mut().zip(q_dot).zip(&self.preferred) {
                    *out = v + z;
                }
            }
        }
        Ok(())
    }

    /// `min(1, min_i vmax_i / |q_dot_i|)`.
    fn velocity_scale(&self) -> f64 {
        self.q_dot
            .iter()
            .zip(&self.velocity_limits)
            .fold(1.0, |scale: f64, (&v, &limit)| {
                if v.abs() > limit {
                    scale.min(limit / v.abs())
                } else {
                    scale
                }
            })
    }
}

fn check_path_point(pose: &Pose, twist: &Vector6<f64>) -> Result<()> {
    if !pose.is_finite() {
        return Err(Error::invalid_argument(
            "path",
            "returned a pose with a non-finite entry",
        ));
    }
    check_finite("path twist", twist.as_slice())
}

impl TrackingReport {
    fn new(status: TrackingStatus, samples: Vec<TrackingSample>) -> Self {
        let max = |f: fn(&TrackingSample) -> f64| samples.iter().map(f).fold(0.0, f64::max);
        let last = samples.last();
        TrackingReport {
            status,
            max_position_error: max(|s| s.position_error),
            max_orientation_error: max(|s| s.orientation_error),
            final_position_error: last.map_or(0.0, |s| s.position_error),
            final_orientation_error: last.map_or(0.0, |s| s.orientation_error),
            velocity_scaled_steps: samples.iter().filter(|s| s.velocity_scale < 1.0).count(),
            limit_locked_steps: samples.iter().filter(|s| s.limit_locks > 0).count(),
            samples,
        }
    }
}

/// Seed 001's energy measure over a run, and each joint's travel.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionSummary {
    /// `integral of F dt` (W^2 s): eq 9's `F = sum (q_dot_i tau_i)^2` with
    /// the torques holding the load at each sample, times the step.
    pub energy: f64,
    /// `F` at each sample (W^2), aligned with the report's samples.
    pub measure: Vec<f64>,
    /// Total distance travelled by each joint, `sum |q_{k+1} - q_k|` (rad or m).
    pub travel: Vec<f64>,
}

impl MotionSummary {
    /// The summary of `report` on `model` for `load` (the torques of eq 9).
    pub fn new(model: &Model, report: &TrackingReport, load: &Load) -> Result<Self> {
        let dof = model.dof();
        let mut data = Data::new(model);
        let mut torques = vec![0.0; dof];
        let mut measure = Vec::with_capacity(report.samples.len());
        let mut travel = vec![0.0; dof];
        let mut energy = 0.0;
        for (k, sample) in report.samples.iter().enumerate() {
            joint_torques(model, &mut data, &sample.q, load, &mut torques)?;
            let f = energy_measure(&sample.q_dot, &torques)?;
            measure.push(f);
            if let Some(next) = report.samples.get(k + 1) {
                energy += f * (next.time - sample.time);
                for ((t, a), b) in travel.iter_mut().zip(&sample.q).zip(&next.q) {
                    *t += (b - a).abs();
                }
            }
        }
        Ok(MotionSummary {
            energy,
            measure,
            travel,
        })
    }
}

/// One way of distributing a motion, for [`compare_distributions`].
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonCase {
    /// Short name (e.g. `minimum-norm`).
    pub name: String,
    /// The distribution.
    pub distribution: Distribution,
}

impl ComparisonCase {
    /// The four distributions of seed 001 and seed 000 on one robot:
    /// `minimum-norm` (all weights 1), `energy-optimal` (weights from the
    /// torques holding `load`, floored by `floor`), `priorities` (the given
    /// weights, e.g. [`super::SEED000_PRIORITY_WEIGHTS`]) and `locked`
    /// (weights 1 with `locked` joints locked).
    pub fn four_way(
        dof: usize,
        load: Load,
        floor: TorqueFloor,
        priorities: JointWeights,
        locked: &[usize],
    ) -> Result<Vec<ComparisonCase>> {
        priorities.check_size("priorities", dof)?;
        Ok(vec![
            ComparisonCase {
                name: "minimum-norm".into(),
                distribution: Distribution::Weights(JointWeights::uniform(dof)),
            },
            ComparisonCase {
                name: "energy-optimal".into(),
                distribution: Distribution::Energy { load, floor },
            },
            ComparisonCase {
                name: "priorities".into(),
                distribution: Distribution::Weights(priorities),
            },
            ComparisonCase {
                name: "locked".into(),
                distribution: Distribution::Weights(
                    JointWeights::uniform(dof).with_locked(locked)?,
                ),
            },
        ])
    }
}

/// One case's run and its summary.
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonResult {
    /// The case's name.
    pub name: String,
    /// The tracking run.
    pub report: TrackingReport,
    /// Energy measure and joint travel for the comparison's load.
    pub summary: MotionSummary,
}

/// Runs the same path from the same start with each case's distribution
/// (same `options`), and measures each run with seed 001's eq 9 for `load`.
pub fn compare_distributions(
    model: &Model,
    q0: &[f64],
    path: &dyn CartesianPath,
    load: &Load,
    cases: &[ComparisonCase],
    options: &TrackingOptions,
) -> Result<Vec<ComparisonResult>> {
    cases
        .iter()
        .map(|case| {
            let mut tracker =
                ResolvedRateTracker::new(model, case.distribution.clone(), options.clone())?;
            let report = tracker.run(model, q0, path)?;
            let summary = MotionSummary::new(model, &report, load)?;
            Ok(ComparisonResult {
                name: case.name.clone(),
                report,
                summary,
            })
        })
        .collect()
}
