//! The tracking loop, its options, rate laws and what it records.

use super::plant::Plant;
use super::status::TrackingStatus;
use crate::error::{brief, check_finite, check_positive, Error, Result};
use crate::ik::pose_error;
use crate::linalg::{damped_least_squares_rates, Solve, GRAM_THRESHOLD};
use crate::math::{Pose, Vector6};
use crate::trajectory::TimedPath;

/// How the commanded twist feeds the pose error back.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum Feedback {
    /// `V = V_d(t) + K e(t)`: the path's twist plus the gain `K` (1/s, with
    /// `0 <= K dt <= 1`) times the pose error `e = [p_d - p; log(R_d R')]`
    /// now (seed 001's tracking).
    Proportional {
        /// `K`, 1/s.
        gain: f64,
    },
    /// `V = e(t + dt) / dt`: the error from the current pose to the pose due
    /// one period later (seed 004, eqs 26-27): the planned motion and the
    /// correction of the current error in one period.
    NextPose,
    /// `V = V_d(t)`: the path's twist alone, no error feedback (open loop).
    /// The pose error the discrete steps make accumulates instead of being
    /// corrected: the tracker seed 004's explanation of Figs 7-8 assumes
    /// (the error carried into a singular region is what was accumulated
    /// before it).
    OpenLoop,
}

impl Feedback {
    /// `proportional`, `next-pose` or `open-loop`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Feedback::Proportional { .. } => "proportional",
            Feedback::NextPose => "next-pose",
            Feedback::OpenLoop => "open-loop",
        }
    }
}

impl std::str::FromStr for Feedback {
    type Err = Error;

    /// `next-pose` or `open-loop` (the proportional law needs its gain);
    /// the error (named `feedback`) lists them.
    fn from_str(name: &str) -> Result<Self> {
        [Feedback::NextPose, Feedback::OpenLoop]
            .into_iter()
            .find(|f| f.as_str() == name)
            .ok_or_else(|| {
                Error::invalid_argument(
                    "feedback",
                    format!("expected \"next-pose\" or \"open-loop\", got \"{name}\""),
                )
            })
    }
}

impl std::fmt::Display for Feedback {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Most control periods one tracking run takes (`ceil(duration / dt)`): a
/// run records the state of every period (joint positions and rates, pose
/// errors), so the count bounds its memory as well as its time; 10^6
/// periods are 10^4 s at the default 0.01 s.
pub const MAX_PERIODS: usize = 1_000_000;

/// Options of a tracking run (every tracker's; the rate law has its own).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackingOptions {
    /// Control period, s (> 0). The path's duration is split into
    /// `ceil(duration / dt)` equal steps, at most [`MAX_PERIODS`]. Default
    /// 0.01 s.
    pub dt: f64,
    /// The feedback. Default [`Feedback::NextPose`].
    pub feedback: Feedback,
}

impl Default for TrackingOptions {
    fn default() -> Self {
        TrackingOptions {
            dt: 0.01,
            feedback: Feedback::NextPose,
        }
    }
}

impl TrackingOptions {
    /// Seed 001's loop: period `dt`, proportional feedback with gain 10 1/s.
    pub fn proportional(dt: f64, gain: f64) -> Self {
        TrackingOptions {
            dt,
            feedback: Feedback::Proportional { gain },
        }
    }

    /// Checks `dt` finite and > 0, and a gain with `0 <= gain dt <= 1` (a
    /// stable discrete loop). The error names the field.
    pub fn validate(&self) -> Result<()> {
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(Error::invalid_argument(
                "dt",
                format!("must be finite and > 0 s, got {}", brief(self.dt)),
            ));
        }
        if let Feedback::Proportional { gain } = self.feedback {
            if !(gain >= 0.0 && gain * self.dt <= 1.0) {
                return Err(Error::invalid_argument(
                    "feedback_gain",
                    format!(
                        "must satisfy 0 <= gain * time_step <= 1 (a stable discrete loop), got \
                         gain {gain} with time_step {}",
                        self.dt
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Number of control periods for a path of `duration` s and their length
    /// (s): `ceil(duration / dt)` equal periods (at least one).
    ///
    /// Errors: more than [`MAX_PERIODS`] periods (named `dt`, with the count
    /// and the memory the record of a `dof`-joint run would need, before any
    /// work).
    pub fn periods(&self, duration: f64, dof: usize) -> Result<(usize, f64)> {
        let count = ((duration / self.dt) - 1e-9).ceil().max(1.0);
        // A NaN count (a NaN duration or dt) is refused too.
        if count.is_nan() || count > MAX_PERIODS as f64 {
            // A sample: time, q and rates per joint, and about six figures.
            let bytes = count * (2 * dof + 7) as f64 * 8.0;
            return Err(Error::invalid_argument(
                "dt",
                format!(
                    "duration {} s / dt {} s = {} control periods: at most {MAX_PERIODS} \
                     (a run records every period: {} bytes)",
                    brief(duration),
                    brief(self.dt),
                    brief(count),
                    brief(bytes)
                ),
            ));
        }
        let steps = count as usize;
        Ok((steps, duration / steps as f64))
    }
}

/// One control period as the rate law sees it.
#[derive(Clone, Copy)]
pub struct Step<'p> {
    /// Period index, from 0.
    pub index: usize,
    /// Number of periods of the run.
    pub periods: usize,
    /// Time at the period's start, s.
    pub time: f64,
    /// Period length, s.
    pub dt: f64,
    /// The commanded twist (world frame, m/s and rad/s): the path's motion
    /// plus the feedback.
    pub twist: Vector6<f64>,
    /// The path being tracked.
    pub path: &'p dyn TimedPath,
}

/// What a rate law did in one period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RateOutcome {
    /// Joint rates written; apply them for the period.
    Rates {
        /// Uniform scale applied for velocity limits, in `(0, 1]` (1 if none).
        velocity_scale: f64,
        /// Joints locked this period because they would have crossed a limit.
        limit_locks: usize,
        /// True when the rates follow a planned joint motion (seed 004's fit
        /// across a singular region) instead of inverting the Jacobian.
        planned: bool,
        /// `Some(joint)`: a position limit stops the motion after this period.
        stopped_at: Option<usize>,
    },
    /// The Jacobian was numerically singular: no rates.
    Singular,
}

impl RateOutcome {
    /// Rates inverted from the Jacobian, unscaled, no limit involved.
    pub const PLAIN: RateOutcome = RateOutcome::Rates {
        velocity_scale: 1.0,
        limit_locks: 0,
        planned: false,
        stopped_at: None,
    };
}

/// Joint rates from the commanded twist: the inverse-kinematics law of a
/// tracker (minimum norm, weighted / energy-optimal, damped least squares,
/// singularity-robust, seed 004's avoidance).
pub trait RateLaw<P: Plant + ?Sized> {
    /// Writes the joint rates for `step` into `rates` (the plant evaluated at
    /// its current state). Errors are bad input or model failures only; a
    /// singular Jacobian is [`RateOutcome::Singular`].
    fn rates(&mut self, plant: &mut P, step: &Step<'_>, rates: &mut [f64]) -> Result<RateOutcome>;
}

/// The damped least-squares inverse `q_dot = J' (J J' + lambda^2 I)^-1 V`
/// ([`crate::linalg::damped_least_squares_rates`]): the pseudo-inverse
/// (minimum norm, seed 004 eq 28) for `damping` 0. Singular as that kernel
/// with [`GRAM_THRESHOLD`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeastSquares {
    /// `lambda`, in the units of the Jacobian (>= 0).
    pub damping: f64,
}

impl LeastSquares {
    /// Checks `damping` finite and >= 0.
    pub fn validate(&self) -> Result<()> {
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(Error::invalid_argument(
                "damping",
                format!("must be finite and >= 0, got {}", self.damping),
            ));
        }
        Ok(())
    }
}

impl<P: Plant + ?Sized> RateLaw<P> for LeastSquares {
    fn rates(&mut self, plant: &mut P, step: &Step<'_>, rates: &mut [f64]) -> Result<RateOutcome> {
        Ok(
            match damped_least_squares_rates(
                plant.jacobian(),
                &step.twist,
                self.damping,
                GRAM_THRESHOLD,
                rates,
            ) {
                Solve::Solved(()) => RateOutcome::PLAIN,
                Solve::Singular { .. } => RateOutcome::Singular,
            },
        )
    }
}

/// The state of one sample, handed to a [`Recorder`] before the rate law runs.
#[derive(Clone, Copy, Debug)]
pub struct SampleState<'a> {
    /// Time, s.
    pub time: f64,
    /// Joint positions, rad or m.
    pub q: &'a [f64],
    /// End-effector pose, world (inertial) frame.
    pub end_effector: &'a Pose,
    /// Base pose, inertial frame (identity on a fixed base).
    pub base: Pose,
    /// Desired pose at `time`, world frame.
    pub desired: &'a Pose,
    /// `|p_d - p|`, m.
    pub position_error: f64,
    /// Angle of `R_d R'`, rad.
    pub orientation_error: f64,
    /// The Jacobian at the sample.
    pub jacobian: &'a crate::math::Matrix6xX<f64>,
}

/// What a run records: the state at every sample, then the rates applied
/// from it (zero for the last sample, and for the sample where the run stopped
/// at a singularity).
pub trait Recorder {
    /// The state at a sample.
    fn state(&mut self, sample: &SampleState<'_>) -> Result<()>;

    /// The rates applied from the last recorded state, and the law's outcome
    /// (`None` for the final sample or a singular stop).
    fn rates(&mut self, rates: &[f64], outcome: Option<&RateOutcome>);
}

/// Runs `law` on `plant` along `path` from the plant's current state: at
/// every period start `t_k = k dt` (`k = 0 .. N`, `N = ceil(duration / dt)`):
/// evaluate the plant; the pose error from the path's pose at `t_k`; record;
/// the commanded twist by `options.feedback`; the law's joint rates; record
/// them; advance the plant by `dt`. The last sample (at the duration, or one
/// period after a joint limit stopped the motion, or where the Jacobian
/// became singular) is recorded with zero rates.
///
/// Errors: bad options, a path with a non-finite duration or a pose that is
/// not a finite proper rigid transform (named `path`, with the time), and the
/// plant's and the law's errors (a model overflow is an error). A singular
/// Jacobian or a joint limit that stops the motion is a status.
pub fn track<P: Plant + ?Sized, L: RateLaw<P> + ?Sized, R: Recorder + ?Sized>(
    plant: &mut P,
    law: &mut L,
    path: &dyn TimedPath,
    options: &TrackingOptions,
    recorder: &mut R,
    rates: &mut [f64],
) -> Result<TrackingStatus> {
    options.validate()?;
    let duration = path.duration();
    check_positive("duration", duration)?;
    let (periods, dt) = options.periods(duration, plant.dof())?;
    let desired_at = |time: f64| -> Result<Pose> {
        let pose = path.pose(time);
        pose.check_rigid().map_err(|reason| {
            Error::invalid_argument("path", format!("at t = {time} s: {reason}"))
        })?;
        Ok(pose)
    };
    let mut status = TrackingStatus::Completed;
    let mut last = false;
    for index in 0..=periods {
        let time = index as f64 * dt;
        plant.evaluate()?;
        let desired = desired_at(time.min(duration))?;
        let error = pose_error(&desired, plant.end_effector());
        recorder.state(&SampleState {
            time,
            q: plant.joint_positions(),
            end_effector: plant.end_effector(),
            base: plant.base(),
            desired: &desired,
            position_error: error.fixed_rows::<3>(0).norm(),
            orientation_error: error.fixed_rows::<3>(3).norm(),
            jacobian: plant.jacobian(),
        })?;
        if index == periods || last {
            rates.fill(0.0);
            recorder.rates(rates, None);
            break;
        }
        let twist = match options.feedback {
            Feedback::Proportional { gain } => {
                let planned = path.twist(time);
                check_finite("path twist", planned.as_slice())?;
                planned + error * gain
            }
            Feedback::NextPose => pose_error(&desired_at(time + dt)?, plant.end_effector()) / dt,
            Feedback::OpenLoop => {
                let planned = path.twist(time);
                check_finite("path twist", planned.as_slice())?;
                planned
            }
        };
        let step = Step {
            index,
            periods,
            time,
            dt,
            twist,
            path,
        };
        let outcome = law.rates(plant, &step, rates)?;
        match outcome {
            RateOutcome::Singular => {
                status = TrackingStatus::Singular { time };
                rates.fill(0.0);
                recorder.rates(rates, None);
                break;
            }
            RateOutcome::Rates { stopped_at, .. } => {
                recorder.rates(rates, Some(&outcome));
                plant.advance(rates, dt)?;
                if let Some(joint) = stopped_at {
                    status = TrackingStatus::StoppedAtJointLimit { joint, time };
                    last = true;
                }
            }
        }
    }
    Ok(status)
}
