//! Joint torques along a trajectory against the motors' limits, and the
//! uniform time scaling that brings every torque within its limit.
//!
//! Along a joint trajectory `q(t)` the inverse dynamics gives
//! `tau(t) = M(q) qdd + C(q, qd) qd + g(q)`. Playing the same path `k` times
//! slower (`t -> k t`) divides `qd` by `k` and `qdd` by `k^2`, so at the same
//! point of the path `tau_k = d / k^2 + g` with `d = M qdd + C qd qd` the
//! motion's part and `g` the gravity's. With `s = 1 / k^2` each sample and
//! joint asks `|g + s d| <= L`: an interval `[0, s_max]` when `|g| <= L`, so
//! the largest `s` that meets them all gives the smallest slow-down `k`.
//! When gravity alone exceeds a limit somewhere, no timing helps: the status
//! says so.
//!
//! ```
//! use armkit::trajectory::{
//!     rest_to_rest, scale_to_torque_limits, ProfileShape, TorqueCheckOptions, TorqueStatus,
//! };
//! let model = armkit::robots::by_name("space6r").unwrap();
//! let goal = [1.0, -0.5, 0.8, 0.3, 0.2, 0.1];
//! let traj = rest_to_rest(ProfileShape::Quintic, &[0.0; 6], &goal, 0.5, None).unwrap();
//! let limits = vec![800.0, 900.0, 400.0, 20.0, 20.0, 5.0];
//! let options = TorqueCheckOptions { limits: Some(limits), ..Default::default() };
//! let scaled = scale_to_torque_limits(&model, &traj, &options).unwrap();
//! assert_eq!(scaled.before.status, TorqueStatus::ExceedsLimits);
//! assert_eq!(scaled.after.status, TorqueStatus::WithinLimits);
//! assert!(scaled.factor > 1.0);
//! ```

use std::fmt;

use super::{JointState, Trajectory};
use crate::dynamics::{rnea, DynamicsData, DEFAULT_GRAVITY};
use crate::error::{check_finite, check_finite_vector, Error, Result};
use crate::math::Vector3;
use crate::model::Model;

/// Options of [`torque_profile`] and [`scale_to_torque_limits`].
#[derive(Clone, Debug, PartialEq)]
pub struct TorqueCheckOptions {
    /// Number of evenly spaced samples over the trajectory, both ends
    /// included (>= 2). Default 401. Peaks between samples are not seen.
    pub samples: usize,
    /// Gravity, world frame, m/s^2. Default `(0, 0, -9.81)`.
    pub gravity: Vector3<f64>,
    /// Torque limits (N m or N, > 0), one per joint, replacing the model's
    /// effort limits; `None` (default): the model's, where it has them.
    pub limits: Option<Vec<f64>>,
}

impl Default for TorqueCheckOptions {
    fn default() -> Self {
        TorqueCheckOptions {
            samples: 401,
            gravity: DEFAULT_GRAVITY,
            limits: None,
        }
    }
}

impl TorqueCheckOptions {
    /// Checks the sample count, the gravity and the limits' size and signs
    /// for a robot with `dof` joints.
    pub fn validate(&self, dof: usize) -> Result<()> {
        if self.samples < 2 {
            return Err(Error::invalid_argument(
                "samples",
                format!("at least 2 samples are needed, got {}", self.samples),
            ));
        }
        check_finite("gravity", self.gravity.as_slice())?;
        if let Some(limits) = &self.limits {
            check_finite_vector("torque_limits", limits, dof)?;
            if let Some(j) = limits.iter().position(|&l| l <= 0.0) {
                return Err(Error::invalid_argument(
                    "torque_limits",
                    format!("must be > 0, got {} for joint {j}", limits[j]),
                ));
            }
        }
        Ok(())
    }

    /// The limit of each joint: the given ones, else the model's effort limits.
    fn joint_limits(&self, model: &Model) -> Vec<Option<f64>> {
        match &self.limits {
            Some(limits) => limits.iter().map(|&l| Some(l)).collect(),
            None => model.joints().iter().map(|j| j.limits.effort).collect(),
        }
    }
}

/// Whether the torques stay within the limits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TorqueStatus {
    /// Every joint with a limit stays within it at every sample.
    WithinLimits,
    /// Some joint exceeds its limit.
    ExceedsLimits,
    /// No joint has a torque limit: peaks are reported, nothing is checked.
    NoLimits,
    /// Gravity alone exceeds a limit somewhere on the path: no timing helps.
    GravityExceedsLimits,
}

impl TorqueStatus {
    /// Short name: `within-limits`, `exceeds-limits`, `no-limits`,
    /// `gravity-exceeds-limits`.
    pub fn as_str(self) -> &'static str {
        match self {
            TorqueStatus::WithinLimits => "within-limits",
            TorqueStatus::ExceedsLimits => "exceeds-limits",
            TorqueStatus::NoLimits => "no-limits",
            TorqueStatus::GravityExceedsLimits => "gravity-exceeds-limits",
        }
    }
}

impl fmt::Display for TorqueStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The largest torque magnitude one joint needs along the trajectory.
#[derive(Clone, Debug, PartialEq)]
pub struct JointTorquePeak {
    /// Joint name.
    pub name: String,
    /// Largest `|tau|` over the samples, N m or N.
    pub peak: f64,
    /// Time of the peak, s.
    pub time: f64,
    /// The joint's limit, if known.
    pub limit: Option<f64>,
}

impl JointTorquePeak {
    /// `peak / limit`, if there is a limit (> 1: exceeded).
    pub fn ratio(&self) -> Option<f64> {
        self.limit.map(|l| self.peak / l)
    }
}

/// The torques along a trajectory and their peaks.
#[derive(Clone, Debug, PartialEq)]
pub struct TorqueReport {
    /// Sample times, s.
    pub times: Vec<f64>,
    /// Joint torques at each sample (N m or N), `torques[sample][joint]`.
    pub torques: Vec<Vec<f64>>,
    /// Gravity's part `g(q)` at each sample, `gravity[sample][joint]`.
    pub gravity: Vec<Vec<f64>>,
    /// Per joint: the peak and its limit.
    pub peaks: Vec<JointTorquePeak>,
    /// Within the limits or not.
    pub status: TorqueStatus,
}

/// The joint torques `tau = M qdd + C qd qd + g` along `traj` at
/// `options.samples` evenly spaced times, their peaks against the limits.
///
/// Errors: a trajectory for another number of joints, invalid options, a
/// model without mass properties (see [`crate::dynamics::check_dynamics_model`]).
pub fn torque_profile(
    model: &Model,
    traj: &Trajectory,
    options: &TorqueCheckOptions,
) -> Result<TorqueReport> {
    options.validate(model.dof())?;
    if traj.dof() != model.dof() {
        return Err(Error::DimensionMismatch {
            what: "trajectory joints",
            expected: model.dof(),
            got: traj.dof(),
        });
    }
    let n = model.dof();
    let mut data = DynamicsData::new(model)?.with_gravity(options.gravity)?;
    let mut state = JointState::zeros(n);
    let zeros = vec![0.0; n];
    let last = (options.samples - 1) as f64;
    let mut times = Vec::with_capacity(options.samples);
    let mut torques = Vec::with_capacity(options.samples);
    let mut gravity = Vec::with_capacity(options.samples);
    for i in 0..options.samples {
        let t = traj.start_time() + traj.duration() * i as f64 / last;
        traj.sample_into(t, &mut state)?;
        torques.push(
            rnea(
                model,
                &mut data,
                &state.position,
                &state.velocity,
                &state.acceleration,
            )?
            .to_vec(),
        );
        gravity.push(rnea(model, &mut data, &state.position, &zeros, &zeros)?.to_vec());
        times.push(t);
    }
    let limits = options.joint_limits(model);
    let peaks: Vec<JointTorquePeak> = model
        .joints()
        .iter()
        .enumerate()
        .map(|(j, joint)| {
            let (sample, peak) = torques.iter().map(|tau| tau[j].abs()).enumerate().fold(
                (0, 0.0),
                |best, (i, p)| if p > best.1 { (i, p) } else { best },
            );
            JointTorquePeak {
                name: joint.name.clone(),
                peak,
                time: times[sample],
                limit: limits[j],
            }
        })
        .collect();
    let gravity_exceeds = gravity.iter().any(|g| {
        g.iter()
            .zip(&limits)
            .any(|(g, l)| l.is_some_and(|l| g.abs() > l))
    });
    let status = if limits.iter().all(Option::is_none) {
        TorqueStatus::NoLimits
    } else if gravity_exceeds {
        TorqueStatus::GravityExceedsLimits
    } else if peaks.iter().any(|p| p.ratio().is_some_and(|r| r > 1.0)) {
        TorqueStatus::ExceedsLimits
    } else {
        TorqueStatus::WithinLimits
    };
    Ok(TorqueReport {
        times,
        torques,
        gravity,
        peaks,
        status,
    })
}

/// A trajectory slowed down to meet the torque limits.
#[derive(Clone, Debug, PartialEq)]
pub struct TorqueScaling {
    /// The (possibly) slowed-down trajectory; the input itself when no
    /// slow-down is needed or none can help.
    pub trajectory: Trajectory,
    /// New duration / old duration (>= 1).
    pub factor: f64,
    /// The torques before scaling.
    pub before: TorqueReport,
    /// The torques of the returned trajectory, sampled at the same points of
    /// the path ([`TorqueStatus::WithinLimits`] unless gravity alone exceeds
    /// a limit, or there are no limits).
    pub after: TorqueReport,
}

/// Slows `traj` down uniformly, by the smallest factor `k >= 1` with which
/// every sampled torque is within its limit (see the module documentation):
/// `k = 1 / sqrt(s)`, `s` the largest value in `(0, 1]` with
/// `|g + s d| <= L` at every sample and joint. Exact at the samples, up to a
/// relative margin of 1e-9 on `k`.
///
/// Returns the trajectory unchanged (factor 1) when it is already within the
/// limits, has no limits, or when gravity alone exceeds a limit
/// ([`TorqueStatus::GravityExceedsLimits`] in `after`). Errors as
/// [`torque_profile`].
pub fn scale_to_torque_limits(
    model: &Model,
    traj: &Trajectory,
    options: &TorqueCheckOptions,
) -> Result<TorqueScaling> {
    let before = torque_profile(model, traj, options)?;
    if before.status != TorqueStatus::ExceedsLimits {
        return Ok(TorqueScaling {
            trajectory: traj.clone(),
            factor: 1.0,
            after: before.clone(),
            before,
        });
    }
    let limits = options.joint_limits(model);
    let mut s_max = 1.0_f64;
    for (tau, g) in before.torques.iter().zip(&before.gravity) {
        for j in 0..model.dof() {
            let Some(limit) = limits[j] else { continue };
            let d = tau[j] - g[j];
            if d > 0.0 {
                s_max = s_max.min((limit - g[j]) / d);
            } else if d < 0.0 {
                s_max = s_max.min((-limit - g[j]) / d);
            }
        }
    }
    let factor = (1.0 / s_max.sqrt()) * (1.0 + 1e-9);
    let trajectory = traj.time_scaled(factor)?;
    let after = torque_profile(model, &trajectory, options)?;
    Ok(TorqueScaling {
        trajectory,
        factor,
        before,
        after,
    })
}
