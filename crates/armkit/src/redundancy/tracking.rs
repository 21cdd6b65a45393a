//! Resolved-rate tracking with redundancy resolution: the joint-rate law
//! that distributes each commanded twist by any of the methods of this
//! module, run by the one tracking loop ([`crate::tracking::track`]) on a
//! fixed-base plant.
//!
//! At each sample `t_k` (step `dt`), with the pose error
//! `e = [p_d - p; log(R_d R')]` (world frame, m and rad) and the path's twist
//! `V_d`, the commanded twist is `V = V_d + K e` (`K` the feedback gain, 1/s,
//! [`crate::tracking::Feedback::Proportional`]), shared among the joints by
//! the chosen [`Distribution`] and [`Formulation`], plus a null-space
//! [`SecondaryObjective`]; then `q_{k+1} = q_k + dt q_dot`.
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
//! use armkit::redundancy::{Distribution, DistributionOptions, JointWeights, ResolvedRateTracker};
//! use armkit::tracking::TrackingStatus;
//! use armkit::trajectory::{CartesianTrajectory, TimeLaw};
//! let model = armkit::robots::by_name("panda").unwrap();
//! let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
//! let mut data = armkit::Data::new(&model);
//! let start = *armkit::forward_kinematics(&model, &mut data, &q0).unwrap();
//! let goal = Pose::from_translation(Vector3::new(0.1, 0.1, -0.1)) * start;
//! let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 2.0).unwrap();
//! let distribution = Distribution::Weights(JointWeights::uniform(7));
//! let mut tracker = ResolvedRateTracker::new(&model, distribution, DistributionOptions::default()).unwrap();
//! let report = tracker.run(&model, &q0, &path).unwrap();
//! assert_eq!(report.status, TrackingStatus::Completed);
//! assert!(report.final_position_error < 1e-3);
//! ```

use super::energy::{energy_measure, joint_torques, torques_at_evaluated, Load, TorqueFloor};
use super::nullspace::{weighted_direction, SecondaryObjective, SecondaryTask};
use super::partition::{best_partition, Partition, PartitionedSolver};
use super::weighted::WeightedLeastNorm;
use super::{Damping, JointWeights, SolverOptions};
use crate::error::{Error, Result};
use crate::kinematics::Data;
use crate::linalg::Solve;
use crate::math::Vector6;
use crate::model::Model;
#[cfg(doc)]
use crate::tracking::TrackingStatus;
use crate::tracking::{
    track_samples, FixedBase, Plant, RateLaw, RateOutcome, Step, TimedPath, TrackingOptions,
    TrackingReport,
};

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

/// Options of [`ResolvedRateTracker`]: the loop's and the distribution's.
#[derive(Clone, Debug, PartialEq)]
pub struct DistributionOptions {
    /// Control period and feedback. Default: 0.01 s, proportional feedback
    /// with gain `K` = 10 1/s (`0 <= K dt <= 1`).
    pub tracking: TrackingOptions,
    /// Damping of the weighted least norm. Default none.
    pub damping: Damping,
    /// Null-space objective. Default none.
    pub secondary: SecondaryObjective,
    /// Solver. Default [`Formulation::WeightedLeastNorm`].
    pub formulation: Formulation,
}

impl Default for DistributionOptions {
    fn default() -> Self {
        DistributionOptions {
            tracking: TrackingOptions::proportional(0.01, 10.0),
            damping: Damping::None,
            secondary: SecondaryObjective::None,
            formulation: Formulation::WeightedLeastNorm,
        }
    }
}

/// Condition number above which a partition's block counts as singular.
const PARTITION_MAX_CONDITION: f64 = 1e10;

impl DistributionOptions {
    /// Checks every field.
    pub fn validate(&self) -> Result<()> {
        self.tracking.validate()?;
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

/// The solver behind a [`Formulation`].
#[derive(Clone, Debug)]
enum Solver {
    LeastNorm(WeightedLeastNorm),
    Partitioned(PartitionedSolver, Option<Partition>),
}

/// The weighted rate law: weights (fixed or from torques), the null-space
/// objective, the velocity scale and the position-limit locks. Workspaces
/// sized once; a period allocates nothing (the best-conditioned partition,
/// if asked for, allocates its result).
#[derive(Clone, Debug)]
struct WeightedRates {
    dof: usize,
    distribution: Distribution,
    weights: JointWeights,
    torques: Vec<f64>,
    solver: Solver,
    secondary_objective: SecondaryObjective,
    secondary: SecondaryTask,
    preferred: Vec<f64>,
    q_dot: Vec<f64>,
    /// The secondary objective's improving direction at the current step.
    direction: Vec<f64>,
    velocity_limits: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

/// Resolved-rate tracking of a Cartesian path with a redundancy
/// distribution: [`crate::tracking::track`] on a [`FixedBase`] plant with
/// the weighted rate law. Workspaces sized once for one model (a control
/// step allocates nothing; a run allocates its samples).
#[derive(Clone, Debug)]
pub struct ResolvedRateTracker {
    options: DistributionOptions,
    data: Data,
    law: WeightedRates,
}

impl ResolvedRateTracker {
    /// A tracker for `model` with `distribution` and `options` (validated;
    /// fixed weights must be for `model.dof()` joints). Joints without a
    /// velocity limit are not scaled.
    pub fn new(
        model: &Model,
        distribution: Distribution,
        options: DistributionOptions,
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
        let law = WeightedRates {
            dof,
            secondary: SecondaryTask::new(model, options.secondary)?,
            secondary_objective: options.secondary,
            distribution,
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
        };
        Ok(ResolvedRateTracker {
            options,
            data: Data::new(model),
            law,
        })
    }

    /// The options.
    pub fn options(&self) -> &DistributionOptions {
        &self.options
    }

    /// Follows `path` from joint positions `q0` (within the limits; the
    /// path should start at or near `FK(q0)`, the feedback pulls it in).
    ///
    /// Errors: `q0` of the wrong size, NaN or outside the limits; a model
    /// with a different number of joints; a path whose poses are not
    /// finite; a numerical failure of the model (an FK overflow). A singular
    /// Jacobian or a joint limit that stops the motion is a status, not an
    /// error.
    pub fn run(
        &mut self,
        model: &Model,
        q0: &[f64],
        path: &dyn TimedPath,
    ) -> Result<TrackingReport> {
        if model.dof() != self.law.dof {
            return Err(Error::DimensionMismatch {
                what: "model (joints of the tracker's model)",
                expected: self.law.dof,
                got: model.dof(),
            });
        }
        let mut plant = FixedBase::new(model, &mut self.data, q0)?;
        track_samples(&mut plant, &mut self.law, path, &self.options.tracking)
    }
}

impl RateLaw<FixedBase<'_>> for WeightedRates {
    /// One control step at the plant's state: the joint velocities for the
    /// next `dt` s.
    fn rates(
        &mut self,
        plant: &mut FixedBase<'_>,
        step: &Step<'_>,
        rates: &mut [f64],
    ) -> Result<RateOutcome> {
        let model = plant.model();
        // Weights at q (the plant's evaluation holds the Jacobian).
        match &self.distribution {
            Distribution::Weights(w) => self.weights.copy_from(w)?,
            Distribution::Energy { load, floor } => {
                let (data, q) = (plant.data(), plant.joint_positions());
                torques_at_evaluated(model, data, q, load, &mut self.torques)?;
                self.weights.set_from_torques(&self.torques, *floor)?;
            }
        }
        let direction_is_zero = self.secondary_objective == SecondaryObjective::None;
        if !direction_is_zero {
            // Computed once per step; re-weighted below when joints lock.
            let direction = self.secondary.direction(model, plant.joint_positions())?;
            self.direction.copy_from_slice(direction);
        }
        let q = plant.joint_positions();
        let dt = step.dt;
        let mut limit_locks = 0;
        let mut velocity_scale = 1.0;
        // At most one round per joint: each round locks at least one more.
        for _round in 0..=self.dof {
            if direction_is_zero {
                self.preferred.fill(0.0);
            } else {
                weighted_direction(&self.weights, &self.direction, &mut self.preferred)?;
            }
            if self
                .distribute(plant.jacobian(), &step.twist)?
                .is_singular()
            {
                if limit_locks == 0 {
                    return Ok(RateOutcome::Singular);
                }
                // The joints left free cannot realise the twist: keep the
                // previous round's velocities, shortened to stop at the limit.
                return Ok(self.stop_at_limit(q, dt, velocity_scale, limit_locks, rates));
            }
            let scale = self.velocity_scale();
            velocity_scale = scale;
            for v in self.q_dot.iter_mut() {
                *v *= scale;
            }
            let mut crossing = false;
            for (j, &qj) in q.iter().enumerate() {
                let next = qj + dt * self.q_dot[j];
                if next < self.lower[j] || next > self.upper[j] {
                    self.weights.lock(j)?;
                    limit_locks += 1;
                    crossing = true;
                }
            }
            if !crossing {
                rates.copy_from_slice(&self.q_dot);
                return Ok(RateOutcome::Rates {
                    velocity_scale: scale,
                    limit_locks,
                    planned: false,
                    stopped_at: None,
                });
            }
            // This round's velocities stay in `self.q_dot` for the fallback:
            // the next round overwrites them only when its solve succeeds.
        }
        Ok(self.stop_at_limit(q, dt, velocity_scale, limit_locks, rates))
    }
}

impl WeightedRates {
    /// Shortens `self.q_dot` (the last round's velocities, which cross a
    /// limit) so that no joint crosses its limit; names the first joint to
    /// reach one.
    fn stop_at_limit(
        &mut self,
        q: &[f64],
        dt: f64,
        velocity_scale: f64,
        limit_locks: usize,
        rates: &mut [f64],
    ) -> RateOutcome {
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
        rates.copy_from_slice(&self.q_dot);
        RateOutcome::Rates {
            velocity_scale: velocity_scale * fraction,
            limit_locks,
            planned: false,
            stopped_at: Some(stopping),
        }
    }

    /// `q_dot = z + J#_A (V - J z)` into `self.q_dot` (z = `self.preferred`).
    /// When singular `self.q_dot` is unchanged.
    fn distribute(
        &mut self,
        j: &crate::math::Matrix6xX<f64>,
        twist: &Vector6<f64>,
    ) -> Result<Solve<()>> {
        match &mut self.solver {
            Solver::LeastNorm(solver) => {
                match solver.solve_toward(j, &self.weights, twist, &self.preferred)? {
                    Solve::Solved(q_dot) => self.q_dot.copy_from_slice(q_dot),
                    Solve::Singular {
                        smallest_singular_value,
                    } => {
                        return Ok(Solve::Singular {
                            smallest_singular_value,
                        })
                    }
                }
            }
            Solver::Partitioned(solver, fixed) => {
                let mut residual = *twist;
                for (column, &z) in j.column_iter().zip(&self.preferred) {
                    residual -= column * z;
                }
                let chosen;
                let partition = match fixed {
                    Some(p) => &*p,
                    None => match best_partition(j, Some(&self.weights), PARTITION_MAX_CONDITION) {
                        Ok(choice) => {
                            chosen = choice;
                            &chosen.partition
                        }
                        // No nonsingular 6 x 6 block: the Jacobian of the
                        // unlocked joints has rank < 6 (inputs were checked).
                        Err(Error::Numerical { .. }) => {
                            return Ok(Solve::Singular {
                                smallest_singular_value: 0.0,
                            })
                        }
                        Err(other) => return Err(other),
                    },
                };
                // Seed 001's block G'0 or eq 19 singular: a singular step.
                let q_dot = match solver.solve(j, &self.weights, &residual, partition) {
                    Ok(q_dot) => q_dot,
                    Err(Error::Numerical { .. }) => {
                        return Ok(Solve::Singular {
                            smallest_singular_value: 0.0,
                        })
                    }
                    Err(other) => return Err(other),
                };
                for ((out, &v), &z) in self.q_dot.iter_mut().zip(q_dot).zip(&self.preferred) {
                    *out = v + z;
                }
            }
        }
        Ok(Solve::Solved(()))
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
            let f = energy_measure(&sample.joint_rates, &torques)?;
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
    path: &dyn TimedPath,
    load: &Load,
    cases: &[ComparisonCase],
    options: &DistributionOptions,
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
