//! Resolved-rate tracking of a Cartesian pose path with the generalized
//! Jacobian (seed 004, eqs 20-28 at velocity level).

use super::dynamics::generalized_jacobian;
use super::simulate::step;
use super::{check_pose, BaseMode, FreeFloatingModel, FreeFloatingState, SpaceData};
use crate::error::{Error, Result};
use crate::ik::pose_error;
use crate::math::{Matrix6, Pose, Vector6};

/// Options of [`track_pose_path`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackingOptions {
    /// Control period, s (> 0). Default 0.01 s. The path's duration is split
    /// into `ceil(duration / dt)` equal steps.
    pub dt: f64,
    /// Damping `lambda` of the least-squares inverse
    /// `q_dot = J*' (J* J*' + lambda^2 I)^-1 x_dot`, in the units of `J*`
    /// (m/rad), >= 0. Default 0: the plain inverse (pseudo-inverse for more
    /// than 6 joints), as the seed's eq 28; singularity handling is left to
    /// the caller.
    pub damping: f64,
}

impl Default for TrackingOptions {
    fn default() -> Self {
        TrackingOptions {
            dt: 0.01,
            damping: 0.0,
        }
    }
}

impl TrackingOptions {
    /// Checks `dt` finite and > 0, `damping` finite and >= 0.
    pub fn validate(&self) -> Result<()> {
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(Error::invalid_argument(
                "dt",
                format!("must be finite and > 0 s, got {}", self.dt),
            ));
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(Error::invalid_argument(
                "damping",
                format!("must be finite and >= 0, got {}", self.damping),
            ));
        }
        Ok(())
    }
}

/// How a tracking run ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TrackingStatus {
    /// Every step of the path was tracked.
    Completed,
    /// `J* J*' + lambda^2 I` became singular (reciprocal condition below
    /// 1e-14) at `time` (s); the run stopped there.
    Singular {
        /// Time of the step that could not be solved, s.
        time: f64,
    },
}

/// One sample of a tracking run, at the start of a control period.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingSample {
    /// Time, s.
    pub time: f64,
    /// Joint positions, rad or m.
    pub q: Vec<f64>,
    /// Joint rates applied from this sample to the next (zero on the last
    /// sample), rad/s or m/s.
    pub joint_rates: Vec<f64>,
    /// Base pose, inertial frame.
    pub base: Pose,
    /// End-effector pose, inertial frame.
    pub end_effector: Pose,
    /// Distance from the path's position at `time`, m.
    pub position_error: f64,
    /// Angle of the rotation from the end effector to the path's orientation
    /// at `time`, rad.
    pub orientation_error: f64,
}

/// Result of [`track_pose_path`].
#[derive(Clone, Debug, PartialEq)]
pub struct TrackingReport {
    /// Completed, or where it stopped.
    pub status: TrackingStatus,
    /// One sample per control period, from `t = 0` to the last time reached.
    pub samples: Vec<TrackingSample>,
    /// Largest position error over the samples, m.
    pub max_position_error: f64,
    /// Largest orientation error over the samples, rad.
    pub max_orientation_error: f64,
}

/// Resolved-rate tracking of the end-effector pose path `path(t)` (inertial
/// frame, `t` in `[0, duration]` s) by the free-floating system from
/// `initial`, the base moving as `mode` says.
///
/// Every period `h`: `J*` at the current state; the pose error `e` from the
/// current end-effector pose to `path(t + h)` (position difference, and the
/// axis-angle vector `k phi` of `R_goal R'`, seed 004 eqs 26-27); the twist
/// `e / h`; joint rates from the (damped) least-squares inverse of `J*`
/// (eq 28); then [`step`]. The error is thus fed back every period.
///
/// Errors: bad options, an arm with fewer than 6 joints, a non-positive
/// duration, `path` returning a pose that is not a finite proper rigid
/// transform, and the errors of [`generalized_jacobian`] and [`step`].
/// Reaching a singular `J*` is a status, not an error.
pub fn track_pose_path<F: Fn(f64) -> Pose>(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    mode: BaseMode,
    initial: &FreeFloatingState,
    path: F,
    duration: f64,
    options: &TrackingOptions,
) -> Result<TrackingReport> {
    options.validate()?;
    let n = model.dof();
    if n < 6 {
        return Err(Error::invalid_argument(
            "model",
            format!("tracking a 6-D pose needs at least 6 joints, the arm has {n}"),
        ));
    }
    if !(duration.is_finite() && duration > 0.0) {
        return Err(Error::invalid_argument(
            "duration",
            format!("must be finite and > 0 s, got {duration}"),
        ));
    }
    let goal_at = |t: f64| -> Result<Pose> {
        let pose = path(t);
        check_pose(&pose)
            .map_err(|reason| Error::invalid_argument("path", format!("at t = {t} s: {reason}")))?;
        Ok(pose)
    };
    let steps = ((duration / options.dt) - 1e-9).ceil().max(1.0) as usize;
    let h = duration / steps as f64;
    let mut state = initial.clone();
    let mut rates = vec![0.0; n];
    let mut samples = Vec::with_capacity(steps + 1);
    let mut status = TrackingStatus::Completed;
    for k in 0..=steps {
        let time = k as f64 * h;
        generalized_jacobian(model, data, &state.base, &state.q, mode)?;
        let current = data.end_effector;
        let here = pose_error(&goal_at(time)?, &current);
        let mut sample = TrackingSample {
            time,
            q: state.q.clone(),
            joint_rates: vec![0.0; n],
            base: state.base,
            end_effector: current,
            position_error: here.fixed_rows::<3>(0).norm(),
            orientation_error: here.fixed_rows::<3>(3).norm(),
        };
        if k == steps {
            samples.push(sample);
            break;
        }
        let twist = pose_error(&goal_at(time + h)?, &current) / h;
        if !least_squares_rates(&data.jacobian, &twist, options.damping, &mut rates) {
            status = TrackingStatus::Singular { time };
            samples.push(sample);
            break;
        }
        sample.joint_rates.copy_from_slice(&rates);
        samples.push(sample);
        step(model, data, &mut state, &rates, h, mode)?;
    }
    let max_position_error = samples.iter().map(|s| s.position_error).fold(0.0, f64::max);
    let max_orientation_error = samples
        .iter()
        .map(|s| s.orientation_error)
        .fold(0.0, f64::max);
    Ok(TrackingReport {
        status,
        samples,
        max_position_error,
        max_orientation_error,
    })
}

/// `rates = J' (J J' + lambda^2 I)^-1 twist` (6 x n `J`, n >= 6); false when
/// the 6 x 6 matrix is singular (reciprocal condition estimate from the
/// Cholesky factor below 1e-14). Allocates nothing.
fn least_squares_rates(
    jacobian: &nalgebra::Matrix6xX<f64>,
    twist: &Vector6<f64>,
    damping: f64,
    rates: &mut [f64],
) -> bool {
    let mut gram = Matrix6::identity() * (damping * damping);
    for column in jacobian.column_iter() {
        gram += column * column.transpose();
    }
    let Some(cholesky) = gram.cholesky() else {
        return false;
    };
    let diagonal = cholesky.l_dirty().diagonal();
    let (smallest, largest) = (diagonal.min(), diagonal.max());
    if !(smallest > 0.0 && (smallest / largest).powi(2) > 1e-14) {
        return false;
    }
    let y = cholesky.solve(twist);
    for (rate, column) in rates.iter_mut().zip(jacobian.column_iter()) {
        *rate = column.dot(&y);
    }
    true
}
