//! What a tracking run of the singularity study is: the methods
//! ([`Method`]), the path task and options, and what a run records
//! ([`MethodRun`], filled through the tracking loop's [`Recorder`]), with the
//! determinant threshold calibrated from a plain run.

use super::detection::{jacobian_determinant, DetectionOptions, Trigger};
use super::region_plan::RegionPlan;
use crate::error::{check_positive, Error, Result};
use crate::ik::{ChiaveriniFilter, DampedReciprocal, NakamuraDamping};
use crate::math::Pose;
use crate::tracking::{
    RateOutcome, Recorder, SampleState, TrackingOptions, TrackingStatus, MAX_PERIODS,
};

/// Most Newton-Raphson iterations per solve [`AvoidanceOptions`] takes.
pub const MAX_IK_ITERATIONS: usize = 10_000;

/// The label and name of [`Method::SeparatedDampedReciprocal`].
pub const SEPARATION: &str = "separation";

/// How the joint rates are obtained from the commanded end-effector twist.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Classic resolved rate, `q_dot = J^-1 x_dot` (the pseudo-inverse for
    /// n > 6; seed 004, eq 28): blows up near a singularity (Fig 5).
    Plain,
    /// Seed 004's avoidance: plain tracking outside the singular region;
    /// inside it, Newton-Raphson IK of every `k`-th planned pose
    /// (warm-started from the previous one) and the C2 cubic fit of the
    /// joint angles (eqs 33-42) through them; tracking resumes after.
    Avoidance {
        /// `k`: IK every `k`-th control period of the region, in
        /// `1..=`[`MAX_PERIODS`] (a run's longest).
        k: usize,
    },
    /// Damped least squares with Nakamura's adaptive damping.
    DampedLeastSquares(NakamuraDamping),
    /// Damped least squares (Nakamura) with its rates scaled down, all
    /// joints by one factor (the direction kept), so that none exceeds
    /// `max_rate`: the damped baseline at the arm's joint speed limit, the
    /// bound the avoidance's knots keep.
    ClampedDampedLeastSquares {
        /// The damping.
        damping: NakamuraDamping,
        /// Largest joint rate, rad/s or m/s (> 0).
        max_rate: f64,
    },
    /// Chiaverini's singularity-robust inverse with numerical filtering.
    SingularityRobust(ChiaveriniFilter),
    /// Singularity separation with a damped reciprocal, seed 004's
    /// reference [9] (the comparator of its conclusion 1): the arm and
    /// wrist blocks solved apart at the wrist centre, only the wrist block's
    /// smallest singular value's reciprocal damped
    /// ([`crate::ik::separated_damped_reciprocal_step`]). 6-joint arms with
    /// a spherical wrist.
    SeparatedDampedReciprocal(DampedReciprocal),
}

impl Method {
    /// A short label: `plain`, `avoidance k=5`, `dls`, `dls clamped`, `sri`,
    /// `separation` (the name it is selected by, too).
    pub fn label(&self) -> String {
        match self {
            Method::Plain => "plain".into(),
            Method::Avoidance { k } => format!("avoidance k={k}"),
            Method::DampedLeastSquares(_) => "dls".into(),
            Method::ClampedDampedLeastSquares { .. } => "dls clamped".into(),
            Method::SingularityRobust(_) => "sri".into(),
            Method::SeparatedDampedReciprocal(_) => SEPARATION.into(),
        }
    }

    /// Checks the parameters: `k` in `1..=`[`MAX_PERIODS`], a positive
    /// finite `max_rate`, and the baselines' own checks.
    pub fn validate(&self) -> Result<()> {
        match self {
            Method::Plain => Ok(()),
            Method::Avoidance { k } => {
                if !(1..=MAX_PERIODS).contains(k) {
                    Err(Error::invalid_argument(
                        "k",
                        format!(
                            "the knot stride must be in 1..={MAX_PERIODS} (IK every k-th planned \
                             pose of the singular region), got {k}"
                        ),
                    ))
                } else {
                    Ok(())
                }
            }
            Method::DampedLeastSquares(d) => d.validate(),
            Method::ClampedDampedLeastSquares { damping, max_rate } => {
                damping.validate()?;
                check_positive("max_rate", *max_rate)
            }
            Method::SingularityRobust(f) => f.validate(),
            Method::SeparatedDampedReciprocal(d) => d.validate(),
        }
    }
}

/// A straight-line pose path: from the pose of the start configuration to
/// `goal`, position linear and orientation by slerp, timed by seed 004's
/// trapezoidal speed profile.
#[derive(Clone, Debug, PartialEq)]
pub struct LineTask {
    /// Start joint positions, rad or m; the path starts at their pose.
    pub start: Vec<f64>,
    /// End pose, inertial (world) frame.
    pub goal: Pose,
    /// Duration, s (> 0). Seed 004: 20 s.
    pub duration: f64,
    /// Acceleration and deceleration time of the trapezoid, s, in
    /// `(0, duration / 2]`. Seed 004: 4 s.
    pub acceleration_time: f64,
}

/// Options of a [`super::PathTracker`]. Defaults: the tracking defaults (`dt`
/// 0.01 s, [`crate::tracking::Feedback::NextPose`]: seed 004's
/// `e(t + h) / h`), the detection defaults ([`DetectionOptions`]), IK
/// tolerance 1e-8 (m and rad), 50 IK iterations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AvoidanceOptions {
    /// Control period and feedback; the duration is split into
    /// `ceil(duration / dt)` equal steps.
    pub tracking: TrackingOptions,
    /// The singular-region tests.
    pub detection: DetectionOptions,
    /// `eps_T`: position (m) and orientation (rad) tolerance of the
    /// Newton-Raphson solves inside the region (> 0). Seed 004 step 3 uses
    /// 1e-8.
    pub ik_tolerance: f64,
    /// Newton-Raphson iterations per solve, in `1..=`[`MAX_IK_ITERATIONS`].
    pub ik_max_iterations: usize,
    /// How a region's knots are chosen when the arm cannot follow its
    /// planned poses exactly (a path missing the singular pose). Default
    /// [`RegionPlan::Joint`].
    pub region_plan: RegionPlan,
}

impl Default for AvoidanceOptions {
    fn default() -> Self {
        AvoidanceOptions {
            tracking: TrackingOptions::default(),
            detection: DetectionOptions::default(),
            ik_tolerance: 1e-8,
            ik_max_iterations: 50,
            region_plan: RegionPlan::default(),
        }
    }
}

impl AvoidanceOptions {
    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<()> {
        self.tracking.validate()?;
        self.detection.validate()?;
        check_positive("ik_tolerance", self.ik_tolerance)?;
        if !(1..=MAX_IK_ITERATIONS).contains(&self.ik_max_iterations) {
            return Err(Error::invalid_argument(
                "ik_max_iterations",
                format!(
                    "must be in 1..={MAX_IK_ITERATIONS}, got {}",
                    self.ik_max_iterations
                ),
            ));
        }
        Ok(())
    }
}

/// One singular region crossed by the avoidance method.
#[derive(Clone, Debug, PartialEq)]
pub struct SingularRegion {
    /// Entry time (the state where detection triggered), s.
    pub start_time: f64,
    /// Exit time (the knot whose `|det J|` is back above the threshold, or
    /// the path's end), s.
    pub end_time: f64,
    /// The test that triggered at entry.
    pub trigger: Trigger,
    /// Knot times, s (entry, then every `k`-th period, then exit).
    pub knot_times: Vec<f64>,
    /// IK solves (one per knot after the entry).
    pub ik_solves: usize,
    /// Newton-Raphson iterations over those solves.
    pub ik_iterations: usize,
    /// Solves that did not reach the IK tolerance (their best iterate was used).
    pub ik_failures: usize,
    /// Knots whose planned pose the arm cannot reach within `eps_dq` per
    /// control period of the last knot (the Newton solution jumped, or the
    /// solve did not converge): each is the least-squares knot, the nearest
    /// pose within that reach, and may miss the planned pose (see
    /// `max_knot_error`).
    pub bounded_knots: usize,
    /// Largest position (m) and orientation (rad) error of a knot (of the
    /// plan kept).
    pub max_knot_error: (f64, f64),
    /// The plan kept: [`RegionPlan::Joint`] when the joint plan ran on a
    /// region with least-squares knots and lowered its largest error, else
    /// [`RegionPlan::Greedy`] (also for regions whose knots are all exact);
    /// [`RegionPlan::Exact`] under the plan as printed.
    pub plan: RegionPlan,
    /// Largest knot error of the greedy plan (norm of the 6-vector pose
    /// error, m and rad); equal to the kept plan's when that is the greedy.
    pub greedy_max_error: f64,
    /// Cone programs the joint plan solved (0 when it did not run).
    pub cone_programs: usize,
}

/// Summary figures of a [`MethodRun`].
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct MethodSummary {
    /// Largest `|q_dot_j|` over joints and samples, rad/s or m/s.
    pub peak_joint_rate: f64,
    /// Largest position error from the planned pose, m.
    pub max_position_error: f64,
    /// Largest orientation error from the planned pose, rad.
    pub max_orientation_error: f64,
    /// Largest norm of the 6-vector pose error (position m and rotation
    /// vector rad together), `max sqrt(p^2 + o^2)` over the samples.
    pub max_pose_error: f64,
    /// Position error at the last sample, m.
    pub final_position_error: f64,
    /// Orientation error at the last sample, rad.
    pub final_orientation_error: f64,
    /// Time during which `|det J|` was below the detection threshold, s
    /// (control periods whose start state is below it): the singular region
    /// as this method crossed it.
    pub time_in_singular_region: f64,
    /// Mean position error over the samples of the singular region (m; 0 if
    /// it was never entered).
    pub mean_region_position_error: f64,
    /// Mean orientation error over the samples of the singular region (rad).
    pub mean_region_orientation_error: f64,
    /// Position-level IK solves (avoidance only).
    pub ik_solves: usize,
}

/// Everything a run recorded, one entry per sample (control period start,
/// `t = 0, h, ..., T`), for plotting and tables.
#[derive(Clone, Debug, PartialEq)]
pub struct MethodRun {
    /// The method.
    pub method: Method,
    /// Completed, or where it stopped.
    pub status: TrackingStatus,
    /// Sample times, s.
    pub time: Vec<f64>,
    /// `joint_positions[j][i]`: joint j at sample i, rad or m.
    pub joint_positions: Vec<Vec<f64>>,
    /// `joint_rates[j][i]`: rate of joint j applied from sample i to i + 1
    /// (zero at the last sample), rad/s or m/s.
    pub joint_rates: Vec<Vec<f64>>,
    /// Distance from the planned position, m.
    pub position_error: Vec<f64>,
    /// Angle of the rotation from the end effector to the planned orientation, rad.
    pub orientation_error: Vec<f64>,
    /// `|det J|` at each sample ([`jacobian_determinant`]).
    pub determinant: Vec<f64>,
    /// True for the samples whose next period is inside a planned region (avoidance).
    pub in_region: Vec<bool>,
    /// Base position at each sample (inertial frame, m); constant on a fixed base.
    pub base_position: Vec<[f64; 3]>,
    /// The singular regions (avoidance only).
    pub regions: Vec<SingularRegion>,
    /// Peak rate, errors, time in the singular region.
    pub summary: MethodSummary,
}

impl MethodRun {
    /// Entry of the first planned singular region and exit of the last, s
    /// (`None`: no region was planned).
    pub fn region_span(&self) -> Option<(f64, f64)> {
        Some((
            self.regions.first()?.start_time,
            self.regions.last()?.end_time,
        ))
    }

    /// Total time inside the planned singular regions (the sum of their
    /// spans), s.
    pub fn region_time(&self) -> f64 {
        self.regions.iter().map(|r| r.end_time - r.start_time).sum()
    }
}

/// A [`MethodRun`] records its series column by column (sized once: a
/// period allocates nothing).
impl Recorder for MethodRun {
    fn state(&mut self, sample: &SampleState<'_>) -> Result<()> {
        self.time.push(sample.time);
        for (series, q) in self.joint_positions.iter_mut().zip(sample.q) {
            series.push(*q);
        }
        self.position_error.push(sample.position_error);
        self.orientation_error.push(sample.orientation_error);
        self.determinant.push(jacobian_determinant(sample.jacobian));
        let base = sample.base.translation;
        self.base_position.push([base.x, base.y, base.z]);
        Ok(())
    }

    fn rates(&mut self, rates: &[f64], outcome: Option<&RateOutcome>) {
        for (series, r) in self.joint_rates.iter_mut().zip(rates) {
            series.push(*r);
        }
        let planned = matches!(outcome, Some(RateOutcome::Rates { planned: true, .. }));
        self.in_region.push(planned);
    }
}

/// The paper's way of setting the determinant threshold (seed 004, sec
/// 2.3.1: "find where the joint angles jump, hence the joint range of the
/// singular region and the determinant threshold"): the largest `|det J|` at
/// a sample of `plain` (a [`Method::Plain`] run) where a joint moved more
/// than `joint_step_threshold` (rad or m) in one control period. `None` if no
/// joint ever did.
pub fn calibrate_determinant_threshold(
    plain: &MethodRun,
    joint_step_threshold: f64,
) -> Option<f64> {
    let h = match plain.time.as_slice() {
        [a, b, ..] => b - a,
        _ => return None,
    };
    (0..plain.time.len())
        .filter(|&i| {
            plain
                .joint_rates
                .iter()
                .any(|rates| (rates[i] * h).abs() > joint_step_threshold)
        })
        .map(|i| plain.determinant[i])
        .reduce(f64::max)
}
