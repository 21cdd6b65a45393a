//! The planner's options: horizons, sample time, weights of eq 20, joint
//! limits (in [`crate::model::JointLimits`] terms), the QP backend and the
//! goal posture's settings.

use crate::error::{self, Error, Result};
use crate::model::JointLimits;

use super::prediction;
use super::qp::QpSolverKind;
use super::DEFAULT_SAMPLE_TIME;

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

/// Longest sample time accepted, s: one sample holds a joint velocity
/// constant, and beyond a minute the prediction's squared terms (`T^2` in
/// the QP's Hessian) leave the range the solvers are tuned for.
pub const MAX_SAMPLE_TIME: f64 = 60.0;

/// Options of the [`super::MpcPlanner`], with seed 000's defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct MpcOptions {
    /// Prediction horizon `N`, samples (>= 1). Default 10 (seed 000).
    pub horizon: usize,
    /// Control horizon `M`, `1 <= M <= N`: increments after `M` are zero.
    /// Default 1 (seed 000).
    pub control_horizon: usize,
    /// Sample time `T`, s, in (0, [`MAX_SAMPLE_TIME`]]. Default
    /// [`DEFAULT_SAMPLE_TIME`].
    pub sample_time: f64,
    /// Task-space weights `Q` (eq 20). Default: full pose, 10 and 200.
    pub task_weights: TaskWeights,
    /// Increment weights `R`, one per joint (> 0): the joint priorities of
    /// sec 4.4 (a larger weight, a lower priority). `None`: 1 for every joint.
    pub increment_weights: Option<Vec<f64>>,
    /// How the increment weights set the joints' priorities: weighted in
    /// one cost (eq 20, the default) or strict, level by level
    /// ([`PriorityMode`]).
    pub priority: PriorityMode,
    /// Velocity weights `W`: an extra cost `sum_{j<N} u(k+j)' W u(k+j)` on
    /// the joint velocities over the horizon (not in seed 000's eq 20).
    /// Default [`VelocityWeights::Proportional`]`(0.01)`; see
    /// [`VelocityWeights`] for why.
    pub velocity_weights: VelocityWeights,
    /// Joint limits, one per joint, overriding the model's: position
    /// `lower`/`upper` (m or rad; infinite means unbounded; eq 24) and
    /// `velocity` (> 0, m/s or rad/s; `None`: no velocity constraint; eq 23).
    /// `None`: the model's limits.
    pub joint_limits: Option<Vec<JointLimits>>,
    /// Fraction of a joint's speed limit, in (0, 1], at which a joint that
    /// is outside its position limits is brought back (the bounds of eq 18
    /// are relaxed to what that motion reaches). Default 0.5.
    pub recovery_speed: f64,
    /// The QP backend. Default: [`QpSolverKind::ActiveSet`] (with
    /// Clarabel as its fallback).
    pub solver: QpSolverKind,
    /// What helps the planner out of the local minima of its linearised
    /// task cost. Default: [`ReachAid::GoalPosture`] with its defaults;
    /// [`ReachAid::Off`] is seed 000's plain planner.
    pub reach: ReachAid,
}

impl Default for MpcOptions {
    fn default() -> Self {
        MpcOptions {
            horizon: 10,
            control_horizon: 1,
            sample_time: DEFAULT_SAMPLE_TIME,
            task_weights: TaskWeights::default(),
            increment_weights: None,
            priority: PriorityMode::default(),
            velocity_weights: VelocityWeights::default(),
            joint_limits: None,
            recovery_speed: 0.5,
            solver: QpSolverKind::default(),
            reach: ReachAid::default(),
        }
    }
}

impl MpcOptions {
    /// Checks the options on their own (sizes against a model are checked by
    /// [`crate::mpc::MpcPlanner::new`]).
    pub fn validate(&self) -> Result<()> {
        prediction::check_horizons(self.horizon, self.control_horizon)?;
        if !(self.sample_time.is_finite()
            && self.sample_time > 0.0
            && self.sample_time <= MAX_SAMPLE_TIME)
        {
            return Err(Error::invalid_argument(
                "sample_time",
                format!(
                    "must be > 0 and <= {MAX_SAMPLE_TIME} s, got {} s",
                    crate::error::brief(self.sample_time)
                ),
            ));
        }
        self.task_weights.validate()?;
        if let Some(r) = &self.increment_weights {
            check_positive("increment_weights", r)?;
        }
        self.velocity_weights.validate()?;
        if let Some(limits) = &self.joint_limits {
            check_joint_limits(limits)?;
        }
        self.reach.validate()?;
        if !(self.recovery_speed > 0.0 && self.recovery_speed <= 1.0) {
            return Err(Error::invalid_argument(
                "recovery_speed",
                format!("must be in (0, 1], got {}", self.recovery_speed),
            ));
        }
        Ok(())
    }
}

/// Checks each joint's limits: `lower <= upper`, neither NaN, `lower`
/// not `+inf`, and a velocity limit (if any) finite and > 0.
pub(crate) fn check_joint_limits(limits: &[JointLimits]) -> Result<()> {
    for (j, l) in limits.iter().enumerate() {
        let (lo, hi) = (l.lower, l.upper);
        if lo.is_nan() || hi.is_nan() || lo > hi || lo == f64::INFINITY {
            return Err(Error::invalid_argument(
                "joint_limits",
                format!(
                    "joint {j}: contradictory position limits [{lo}, {hi}] (need lower <= upper)"
                ),
            ));
        }
        if let Some(v) = l.velocity {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid_argument(
                    "joint_limits",
                    format!("joint {j}: velocity limit must be finite and > 0, got {v}"),
                ));
            }
        }
    }
    Ok(())
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

/// How the joint priorities of sec 4.4 act.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PriorityMode {
    /// One QP: the increment weights `R` weigh every joint's increments in
    /// eq 20's cost, so a low-priority joint still takes a share of a motion
    /// the others could make alone (a share scaled by the weights' ratio).
    #[default]
    Weighted,
    /// Strict (lexicographic) priority: the joints with equal `R` form a
    /// level, the smallest `R` the highest; the levels are solved one after
    /// another, each over its own joints' increments with the higher levels'
    /// optimum held fixed (equality constraints) and the lower levels' at
    /// zero, each minimising the whole cost of eq 20 (the
    /// [`super::lexicographic`] QPs). A lower level moves only for what the
    /// higher ones leave of the cost.
    Strict,
}

impl PriorityMode {
    /// `weighted` or `strict`.
    pub fn as_str(self) -> &'static str {
        match self {
            PriorityMode::Weighted => "weighted",
            PriorityMode::Strict => "strict",
        }
    }

    /// The priority level of each joint for increment weights `r`: 0 for
    /// the smallest weight, one level per distinct value (all 0 when
    /// [`PriorityMode::Weighted`]).
    pub fn joint_levels(self, r: &[f64]) -> Vec<usize> {
        match self {
            PriorityMode::Weighted => vec![0; r.len()],
            PriorityMode::Strict => {
                let mut distinct: Vec<f64> = r.to_vec();
                distinct.sort_by(f64::total_cmp);
                distinct.dedup();
                r.iter()
                    .map(|w| distinct.partition_point(|d| d < w))
                    .collect()
            }
        }
    }
}

impl std::fmt::Display for PriorityMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
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

pub(crate) fn sized_option(
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

/// What helps the planner out of the local minima of its linearised task
/// cost (a joint limit or a singularity between the start and the target,
/// where the task gradient vanishes or points into a limit).
#[derive(Clone, Debug, PartialEq)]
pub enum ReachAid {
    /// None: seed 000's planner as it is (eq 20 plus the velocity term).
    Off,
    /// A goal posture: a joint configuration within the limits that reaches
    /// the target, found by IK with restarts nearest to the current
    /// configuration, that the predicted joint positions are pulled toward
    /// in the cost (see [`GoalPostureOptions`]); re-planned when
    /// progress stalls.
    GoalPosture(GoalPostureOptions),
}

impl Default for ReachAid {
    /// `GoalPosture` with [`GoalPostureOptions::default`].
    fn default() -> Self {
        ReachAid::GoalPosture(GoalPostureOptions::default())
    }
}

impl ReachAid {
    /// `off` or `goal-posture`.
    pub fn as_str(&self) -> &'static str {
        match self {
            ReachAid::Off => "off",
            ReachAid::GoalPosture(_) => "goal-posture",
        }
    }

    /// Checks the goal-posture options.
    pub fn validate(&self) -> Result<()> {
        match self {
            ReachAid::Off => Ok(()),
            ReachAid::GoalPosture(options) => options.validate(),
        }
    }
}

impl std::fmt::Display for ReachAid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Settings of the goal posture ([`ReachAid::GoalPosture`]).
#[derive(Clone, Debug, PartialEq)]
pub struct GoalPostureOptions {
    /// `w`: weight of the joint-space pull relative to the mean task weight
    /// (> 0, finite). Default 0.2.
    pub weight: f64,
    /// Random IK restarts per search (>= 1). Default 300.
    pub ik_restarts: usize,
    /// Converged IK solutions compared for the one nearest the current
    /// configuration (>= 1). Default 4.
    pub candidates: usize,
    /// Steps without a 1 % fall of the task error that count as a stall
    /// (>= 1). Default 60. On a stall the pull is made
    /// [`GoalPostureOptions::stall_gain`] times stronger (the linearised
    /// task cost is holding the arm in a local minimum against it), and a
    /// goal posture not found yet is searched again.
    pub stall_steps: usize,
    /// Factor on the pull after each stall (>= 1). Default 4.
    pub stall_gain: f64,
    /// Searches at most per target (>= 1). Default 4.
    pub max_searches: usize,
    /// Seed of the IK restarts (each search adds its index). Default 0.
    pub seed: u64,
    /// Task error (m and rad combined, the norm over the tracked
    /// coordinates) below which the pull fades linearly to zero (> 0).
    /// Default 0.02.
    pub fade_error: f64,
}

impl Default for GoalPostureOptions {
    fn default() -> Self {
        GoalPostureOptions {
            weight: 0.2,
            ik_restarts: 300,
            candidates: 4,
            stall_steps: 60,
            stall_gain: 4.0,
            max_searches: 4,
            seed: 0,
            fade_error: 0.02,
        }
    }
}

impl GoalPostureOptions {
    /// Checks the weight is finite and > 0 and the counts are >= 1.
    pub fn validate(&self) -> Result<()> {
        error::check_positive("reach.weight", self.weight)?;
        error::check_positive("reach.fade_error", self.fade_error)?;
        if !(self.stall_gain.is_finite() && self.stall_gain >= 1.0) {
            return Err(Error::invalid_argument(
                "reach.stall_gain",
                format!("must be finite and >= 1, got {}", self.stall_gain),
            ));
        }
        for (name, value) in [
            ("reach.ik_restarts", self.ik_restarts),
            ("reach.candidates", self.candidates),
            ("reach.stall_steps", self.stall_steps),
            ("reach.max_searches", self.max_searches),
        ] {
            if value == 0 {
                return Err(Error::invalid_argument(name, "must be at least 1"));
            }
        }
        Ok(())
    }
}
