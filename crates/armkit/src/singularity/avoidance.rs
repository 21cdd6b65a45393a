//! Velocity-level tracking of a straight-line pose path, with seed 004's
//! singularity avoidance and the damped baselines.

use super::detection::{below_threshold, DetectionOptions, Trigger};
use super::method_law::MethodLaw;
use super::plant::Plant;
use super::region_plan::RegionPlan;
use super::Manipulator;
use crate::error::{check_finite_vector, check_positive, Error, Result};
use crate::ik::{
    damped_least_squares_step, singularity_robust_step, ChiaveriniFilter, NakamuraDamping,
};
use crate::math::{Pose, Vector6};
use crate::tracking::{track, TrackingOptions, TrackingStatus};
use crate::trajectory::JointState;
use crate::trajectory::{CartesianTrajectory, LinePath, TimeLaw};

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
        /// `k`: IK every `k`-th control period of the region (>= 1).
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
}

impl Method {
    /// A short label: `plain`, `avoidance k=5`, `dls`, `dls clamped`, `sri`.
    pub fn label(&self) -> String {
        match self {
            Method::Plain => "plain".into(),
            Method::Avoidance { k } => format!("avoidance k={k}"),
            Method::DampedLeastSquares(_) => "dls".into(),
            Method::ClampedDampedLeastSquares { .. } => "dls clamped".into(),
            Method::SingularityRobust(_) => "sri".into(),
        }
    }

    /// Checks the parameters: `k >= 1`, a positive finite `max_rate`, and
    /// the baselines' own checks.
    pub fn validate(&self) -> Result<()> {
        match self {
            Method::Plain => Ok(()),
            Method::Avoidance { k } => {
                if *k == 0 {
                    Err(Error::invalid_argument(
                        "k",
                        "the knot stride must be >= 1 (IK every k-th planned pose of the singular region)",
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

/// Options of a [`PathTracker`]. Defaults: the tracking defaults (`dt`
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
    /// Newton-Raphson iterations per solve (>= 1).
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
        if self.ik_max_iterations == 0 {
            return Err(Error::invalid_argument("ik_max_iterations", "must be >= 1"));
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
    /// [`RegionPlan::Greedy`] (also for regions whose knots are all exact).
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
    /// `|det J|` at each sample ([`super::jacobian_determinant`]).
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

/// A path to track, checked and planned once; [`PathTracker::run`] then
/// runs any [`Method`] on it from the same start.
pub struct PathTracker<'m> {
    manipulator: Manipulator<'m>,
    task: LineTask,
    pub(super) options: AvoidanceOptions,
    pub(super) trajectory: CartesianTrajectory,
    pub(super) steps: usize,
    /// The control period, s.
    pub(super) h: f64,
}

impl std::fmt::Debug for PathTracker<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathTracker")
            .field("task", &self.task)
            .field("options", &self.options)
            .field("steps", &self.steps)
            .finish_non_exhaustive()
    }
}

/// Spacing of the reachability check along the path, s.
const REACH_CHECK_SPACING: f64 = 0.25;

impl<'m> PathTracker<'m> {
    /// Checks the options and the task, builds the timed line from the start
    /// configuration's pose to the goal, and checks that the path stays
    /// within reach: a continuation IK every 0.25 s along it (damped,
    /// from the previous solution; with restarts on a fixed base) must reach
    /// each pose within 1e-6 m and 1e-6 rad.
    ///
    /// Errors: bad options; `start` of the wrong size or not finite; a
    /// duration or acceleration time out of range; a goal that is not a
    /// proper rigid transform; a path out of reach (the error gives the first
    /// time at which no solution was found and the remaining error).
    pub fn new(
        manipulator: Manipulator<'m>,
        task: LineTask,
        options: AvoidanceOptions,
    ) -> Result<PathTracker<'m>> {
        options.validate()?;
        let n = manipulator.dof();
        check_finite_vector("start", &task.start, n)?;
        check_positive("duration", task.duration)?;
        let timing = TimeLaw::Trapezoidal {
            acceleration_time: task.acceleration_time,
        }
        .timing(task.duration)?;
        let mut plant = Plant::new(
            &manipulator,
            &task.start,
            options.ik_tolerance,
            options.ik_max_iterations,
        )?;
        plant.evaluate_state()?;
        let line = LinePath::new(*plant.pose(), task.goal)
            .map_err(|e| crate::trajectory::rename_argument(e, "end", "goal"))?;
        let trajectory = CartesianTrajectory::new(line, timing)?;
        let (steps, h) = options.tracking.periods(task.duration);
        let tracker = PathTracker {
            manipulator,
            task,
            options,
            trajectory,
            steps,
            h,
        };
        tracker.check_reach(&mut plant)?;
        Ok(tracker)
    }

    /// The manipulator.
    pub fn manipulator(&self) -> Manipulator<'m> {
        self.manipulator
    }

    /// The planned path.
    pub fn trajectory(&self) -> &CartesianTrajectory {
        &self.trajectory
    }

    /// The task.
    pub fn task(&self) -> &LineTask {
        &self.task
    }

    /// The options.
    pub fn options(&self) -> &AvoidanceOptions {
        &self.options
    }

    /// Number of control periods, and their length (s).
    pub fn steps(&self) -> (usize, f64) {
        (self.steps, self.h)
    }

    fn check_reach(&self, plant: &mut Plant<'_>) -> Result<()> {
        let samples = (self.task.duration / REACH_CHECK_SPACING).ceil().max(1.0) as usize;
        let mut q = self.task.start.clone();
        for i in 1..=samples {
            let t = self.task.duration * i as f64 / samples as f64;
            let target = self.trajectory.pose_at(t);
            let solve = plant.reach(&target, &q)?;
            if !solve.converged {
                return Err(Error::invalid_argument(
                    "goal",
                    format!(
                        "the path is out of reach: no joint solution near its pose at t = {t:.2} s \
                         (best position error {:.3e} m, orientation error {:.3e} rad)",
                        solve.position_error, solve.orientation_error
                    ),
                ));
            }
            q = solve.q;
        }
        Ok(())
    }

    /// Tracks the path from the start configuration with `method`.
    ///
    /// Every control period `h` from `t`: the pose error `e` from the current
    /// pose to the planned pose at `t + h` (seed 004, eqs 26-27), the twist
    /// `e / h` (the planned motion plus position feedback), and joint rates
    /// from it by the method's inverse of `J` (`J*` on the free-floating
    /// base); the state then advances by `h` (the base moving on a
    /// free-floating system).
    ///
    /// The avoidance method checks every period ([`super::detect`]) with the plain
    /// rates as candidate; when a test triggers at sample `i`, it solves the
    /// IK of the planned poses at samples `i + k, i + 2k, ...` (each
    /// warm-started from the previous solution) until a solution's `|det J|`
    /// is back above the threshold (or the path ends), fits the clamped C2
    /// cubic through the knots (starting with the current rates, ending with
    /// the plain rates of the planned twist at the exit knot; eqs 33-42), and
    /// follows it (`q_dot = (q_fit(t + h) - q) / h`, so the joints are on the
    /// fit at every sample). Plain tracking resumes from the exit.
    ///
    /// The `|det J|` threshold by seed 004's own rule (sec 2.3.1) on this
    /// tracker's line: [`calibrate_determinant_threshold`] on a
    /// [`Method::Plain`] run with this tracker's `eps_dq`
    /// ([`DetectionOptions::joint_step_threshold`]). `None` when the plain
    /// run never jumps (a line tracked smoothly: there is nothing to
    /// calibrate on). m^3 for a 6R arm.
    ///
    /// [`calibrate_determinant_threshold`]: super::calibrate_determinant_threshold
    pub fn calibrated_threshold(&self) -> Result<Option<f64>> {
        let plain = self.run(&Method::Plain)?;
        Ok(super::calibrate_determinant_threshold(
            &plain,
            self.options.detection.joint_step_threshold,
        ))
    }

    /// Errors: bad method parameters, and numerical failures of the model
    /// evaluation. An exactly singular Jacobian under the plain method is a
    /// status ([`TrackingStatus::Singular`]).
    pub fn run(&self, method: &Method) -> Result<MethodRun> {
        method.validate()?;
        let n = self.manipulator.dof();
        let mut plant = Plant::new(
            &self.manipulator,
            &self.task.start,
            self.options.ik_tolerance,
            self.options.ik_max_iterations,
        )?;
        let capacity = self.steps + 1;
        let mut run = MethodRun {
            method: *method,
            status: TrackingStatus::Completed,
            time: Vec::with_capacity(capacity),
            // One buffer per joint, each sized once (`vec![v; n]` would
            // clone empty buffers and regrow them every run).
            joint_positions: (0..n).map(|_| Vec::with_capacity(capacity)).collect(),
            joint_rates: (0..n).map(|_| Vec::with_capacity(capacity)).collect(),
            position_error: Vec::with_capacity(capacity),
            orientation_error: Vec::with_capacity(capacity),
            determinant: Vec::with_capacity(capacity),
            in_region: Vec::with_capacity(capacity),
            base_position: Vec::with_capacity(capacity),
            regions: Vec::new(),
            summary: MethodSummary::default(),
        };
        let mut law = MethodLaw {
            tracker: self,
            method: *method,
            active: None,
            previous_rates: vec![0.0; n],
            candidate: vec![0.0; n],
            fit_state: JointState::zeros(n),
            regions: Vec::new(),
        };
        let mut rates = vec![0.0; n];
        run.status = track(
            &mut plant,
            &mut law,
            &self.trajectory,
            &self.options.tracking,
            &mut run,
            &mut rates,
        )?;
        run.regions = law.regions;
        run.summary = self.summarize(&run);
        Ok(run)
    }

    /// The method's joint rates for `twist` at the plant's last evaluation
    /// (the avoidance method's candidate is the plain inverse); false when
    /// the plain inverse meets an exactly singular Jacobian.
    pub(super) fn rates(
        &self,
        method: &Method,
        plant: &Plant<'_>,
        twist: &Vector6<f64>,
        rates: &mut [f64],
    ) -> bool {
        let j = plant.jacobian();
        let outcome = match method {
            Method::Plain | Method::Avoidance { .. } => {
                damped_least_squares_step(j, twist, 0.0, rates).map(|_| ())
            }
            Method::DampedLeastSquares(nakamura) => {
                damped_least_squares_step(j, twist, nakamura.damping_at(j), rates).map(|_| ())
            }
            Method::ClampedDampedLeastSquares { damping, max_rate } => {
                damped_least_squares_step(j, twist, damping.damping_at(j), rates).map(|_| {
                    let peak = rates.iter().fold(0.0, |m: f64, r| m.max(r.abs()));
                    if peak > *max_rate {
                        let scale = max_rate / peak;
                        rates.iter_mut().for_each(|r| *r *= scale);
                    }
                })
            }
            Method::SingularityRobust(filter) => {
                singularity_robust_step(j, twist, filter, rates).map(|_| ())
            }
        };
        outcome.is_ok() && rates.iter().all(|r| r.is_finite())
    }

    fn summarize(&self, run: &MethodRun) -> MethodSummary {
        let peak_joint_rate = run
            .joint_rates
            .iter()
            .flatten()
            .fold(0.0, |m: f64, r| m.max(r.abs()));
        let max = |v: &[f64]| v.iter().fold(0.0, |m: f64, x| m.max(*x));
        let threshold = self.options.detection.determinant_threshold;
        // Samples of the singular region (the last sample starts no period),
        // and their error sums, in one pass without a buffer.
        let (mut count, mut position_sum, mut orientation_sum) = (0usize, 0.0, 0.0);
        for i in 0..run.determinant.len().saturating_sub(1) {
            if below_threshold(run.determinant[i], threshold) {
                count += 1;
                position_sum += run.position_error[i];
                orientation_sum += run.orientation_error[i];
            }
        }
        let mean = |sum: f64| if count == 0 { 0.0 } else { sum / count as f64 };
        MethodSummary {
            peak_joint_rate,
            max_position_error: max(&run.position_error),
            max_orientation_error: max(&run.orientation_error),
            max_pose_error: run
                .position_error
                .iter()
                .zip(&run.orientation_error)
                .fold(0.0, |m: f64, (p, o)| m.max(p.hypot(*o))),
            final_position_error: run.position_error.last().copied().unwrap_or(0.0),
            final_orientation_error: run.orientation_error.last().copied().unwrap_or(0.0),
            time_in_singular_region: count as f64 * self.h,
            mean_region_position_error: mean(position_sum),
            mean_region_orientation_error: mean(orientation_sum),
            ik_solves: run.regions.iter().map(|r| r.ik_solves).sum(),
        }
    }
}
