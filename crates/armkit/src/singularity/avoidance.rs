//! Velocity-level tracking of a straight-line pose path, with seed 004's
//! singularity avoidance and the damped baselines: the [`PathTracker`] and
//! the rate law of each [`Method`] it hands to the tracking loop
//! ([`crate::tracking::track`]).

use super::detection::{below_threshold, detect};
use super::method::{
    calibrate_determinant_threshold, AvoidanceOptions, LineTask, Method, MethodRun, MethodSummary,
    SingularRegion,
};
use super::plant::Plant;
use super::Manipulator;
use crate::error::{check_finite_vector, check_positive, Error, Result};
use crate::ik::{
    damped_least_squares_step, separated_damped_reciprocal_step, singularity_robust_step,
};
use crate::math::Vector6;
use crate::tracking::{track, RateLaw, RateOutcome, Step, TrackingStatus};
use crate::trajectory::{CartesianTrajectory, JointState, LinePath, TimeLaw, Trajectory};

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
        // Before any work: the run's size.
        let (steps, h) = options.tracking.periods(task.duration, n)?;
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
    /// The avoidance method checks every period ([`detect`]) with the plain
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
    /// ([`super::DetectionOptions::joint_step_threshold`]). `None` when the plain
    /// run never jumps (a line tracked smoothly: there is nothing to
    /// calibrate on). m^3 for a 6R arm.
    pub fn calibrated_threshold(&self) -> Result<Option<f64>> {
        let plain = self.run(&Method::Plain)?;
        Ok(calibrate_determinant_threshold(
            &plain,
            self.options.detection.joint_step_threshold,
        ))
    }

    /// Errors: bad method parameters, [`Method::SeparatedDampedReciprocal`]
    /// on an arm without 6 joints, and numerical failures of the model
    /// evaluation. An exactly singular Jacobian under the plain method is a
    /// status ([`TrackingStatus::Singular`]).
    pub fn run(&self, method: &Method) -> Result<MethodRun> {
        method.validate()?;
        let n = self.manipulator.dof();
        if matches!(method, Method::SeparatedDampedReciprocal(_)) && n != 6 {
            return Err(Error::invalid_argument(
                "method",
                format!(
                    "{} (singularity separation) needs a 6-joint arm with a spherical wrist, \
                     this one has {n} joints",
                    method.label()
                ),
            ));
        }
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
    fn rates(
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
            Method::SeparatedDampedReciprocal(damping) => {
                separated_damped_reciprocal_step(j, twist, damping, rates).map(|_| ())
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

/// The rate law of one [`Method`] on a [`PathTracker`]'s path: the plain,
/// damped or singularity-robust inverse, or seed 004's avoidance (plain
/// outside a singular region, the fitted joint motion across it).
struct MethodLaw<'t, 'm> {
    tracker: &'t PathTracker<'m>,
    method: Method,
    /// The active region: its fit and the sample index where it ends.
    active: Option<(Trajectory, usize)>,
    /// The rates applied in the last period.
    previous_rates: Vec<f64>,
    /// The plain rates' joint steps, for detection.
    candidate: Vec<f64>,
    fit_state: JointState,
    regions: Vec<SingularRegion>,
}

impl RateLaw<Plant<'_>> for MethodLaw<'_, '_> {
    fn rates(
        &mut self,
        plant: &mut Plant<'_>,
        step: &Step<'_>,
        rates: &mut [f64],
    ) -> Result<RateOutcome> {
        let (i, t, h) = (step.index, step.time, step.dt);
        if self.active.as_ref().is_some_and(|(_, end)| i >= *end) {
            self.active = None;
        }
        if self.active.is_none() {
            let solved = self.tracker.rates(&self.method, plant, &step.twist, rates);
            match self.method {
                Method::Avoidance { k } => {
                    for (c, r) in self.candidate.iter_mut().zip(rates.iter()) {
                        *c = if solved { r * h } else { f64::INFINITY };
                    }
                    let detection = detect(
                        plant.jacobian(),
                        &self.candidate,
                        &self.tracker.options.detection,
                    )?;
                    if let Some(trigger) = detection.trigger {
                        let (fit, end, region) =
                            self.tracker
                                .plan_region(plant, i, k, trigger, &self.previous_rates)?;
                        self.regions.push(region);
                        self.active = Some((fit, end));
                    } else if !solved {
                        return Ok(RateOutcome::Singular);
                    }
                }
                _ if !solved => return Ok(RateOutcome::Singular),
                _ => {}
            }
        }
        let planned = if let Some((fit, _)) = &self.active {
            fit.sample_into(t + h, &mut self.fit_state)?;
            for ((rate, target), q) in rates
                .iter_mut()
                .zip(&self.fit_state.position)
                .zip(plant.q())
            {
                *rate = (target - q) / h;
            }
            true
        } else {
            false
        };
        self.previous_rates.copy_from_slice(rates);
        Ok(RateOutcome::Rates {
            velocity_scale: 1.0,
            limit_locks: 0,
            planned,
            stopped_at: None,
        })
    }
}
