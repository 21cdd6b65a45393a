//! Timed end-effector paths: a pose for every time, the input of the
//! velocity-level tracking loop ([`crate::tracking`]).
//!
//! [`TimedPath`] is what a tracker needs: a duration, the pose at a time and
//! the twist at a time. A [`CartesianTrajectory`] (a geometric path timed by
//! a scalar law) is one; [`TimeFn`] turns any closure `t -> Pose` into one,
//! its twist by central differences.
//!
//! Frames and units: poses in the world (inertial) frame, metres and
//! radians; twists `[v; w]` in world axes, m/s and rad/s; times in s from 0.
//!
//! ```
//! use armkit::math::{Pose, Vector3};
//! use armkit::trajectory::{CartesianTrajectory, TimeFn, TimeLaw, TimedPath};
//! let start = Pose::identity();
//! let goal = Pose::from_translation(Vector3::new(0.2, 0.0, 0.0));
//! let line = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 2.0).unwrap();
//! assert!((line.pose(1.0).translation.x - 0.1).abs() < 1e-12);
//! let drift = TimeFn::new(2.0, |t| Pose::from_translation(Vector3::new(0.1 * t, 0.0, 0.0))).unwrap();
//! assert!((drift.twist(1.0)[0] - 0.1).abs() < 1e-9);
//! ```

use super::cartesian::{CartesianTrajectory, LinePath, TimeLaw};
use crate::error::{check_positive, Error, Result};
use crate::ik::pose_error;
use crate::math::{Pose, Vector6};

/// A desired end-effector motion: a pose (world frame) for each time in
/// `[0, duration]` (s).
pub trait TimedPath {
    /// Duration, s (> 0).
    fn duration(&self) -> f64;

    /// Desired end-effector pose at `time` (s, in `[0, duration]`), world frame.
    fn pose(&self, time: f64) -> Pose;

    /// Desired twist `[v; w]` at `time` (world frame, m/s and rad/s). The
    /// default differentiates [`TimedPath::pose`] centrally with a step of
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

impl TimedPath for CartesianTrajectory {
    fn duration(&self) -> f64 {
        CartesianTrajectory::duration(self)
    }

    fn pose(&self, time: f64) -> Pose {
        self.pose_at(self.start_time() + time)
    }

    /// The exact twist of [`CartesianTrajectory::sample`] (zero for a
    /// non-finite time).
    fn twist(&self, time: f64) -> Vector6<f64> {
        self.sample(self.start_time() + time)
            .map_or_else(|_| Vector6::zeros(), |state| state.twist)
    }
}

impl CartesianTrajectory {
    /// The straight line from `start` to `goal` (world frame; position
    /// linear, orientation by slerp, [`LinePath`]) timed by `law` over
    /// `duration` s (> 0), from time 0.
    ///
    /// Errors name `start`, `goal` (not finite, not a proper rotation) or
    /// `duration`, and the law's own parameters.
    pub fn line(start: Pose, goal: Pose, law: TimeLaw, duration: f64) -> Result<Self> {
        check_positive("duration", duration)?;
        let line = LinePath::new(start, goal).map_err(|e| rename_argument(e, "end", "goal"))?;
        CartesianTrajectory::new(line, law.timing(duration)?)
    }
}

/// A path given by a closure `time -> Pose` (world frame) over
/// `[0, duration]`; its twist is differentiated numerically
/// ([`TimedPath::twist`]'s default).
pub struct TimeFn<F: Fn(f64) -> Pose> {
    duration: f64,
    pose: F,
}

impl<F: Fn(f64) -> Pose> std::fmt::Debug for TimeFn<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TimeFn")
            .field("duration", &self.duration)
            .finish_non_exhaustive()
    }
}

impl<F: Fn(f64) -> Pose> TimeFn<F> {
    /// A path of `duration` s (finite, > 0) following `pose`. Errors name
    /// `duration`.
    pub fn new(duration: f64, pose: F) -> Result<Self> {
        check_positive("duration", duration)?;
        Ok(TimeFn { duration, pose })
    }
}

impl<F: Fn(f64) -> Pose> TimedPath for TimeFn<F> {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn pose(&self, time: f64) -> Pose {
        (self.pose)(time)
    }
}

/// The same error with the argument renamed (`LinePath::new` names its
/// arguments `start` and `end`; a task names the end its goal).
pub(crate) fn rename_argument(error: Error, from: &str, to: &str) -> Error {
    match error {
        Error::InvalidArgument { name, reason } if name == from => Error::InvalidArgument {
            name: to.into(),
            reason,
        },
        other => other,
    }
}
