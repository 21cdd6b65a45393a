//! Seed 001's energy measure and energy weights with the real torques of a
//! moving arm.
//!
//! Seed 001 weighs joint velocities by the torques the joints deliver:
//! `F = sum (q_dot_i tau_i)^2` (eq 9), weights `a_i = tau_i^2` (eq 17).
//! [`super::joint_torques`] takes `tau` as the static torques holding a
//! load, `tau = J' w + g(q)`. Here `tau` may instead be the full inverse
//! dynamics of the motion, `tau = M(q) qdd + C(q, qd) qd + g(q) + J' w`
//! ([`TorqueModel::Dynamic`], by [`crate::dynamics::rnea`]), so a fast or
//! heavy motion's inertia counts.
//!
//! ```
//! use armkit::redundancy::{energy_along_motion, Load, TorqueModel};
//! let model = armkit::robots::by_name("space6r").unwrap();
//! // A motion sampled every 10 ms: q, q_dot.
//! let times: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
//! let q: Vec<Vec<f64>> = times.iter().map(|t| vec![0.5 * t * t, 0.2 * t, 0.0, 0.0, 0.0, 0.0]).collect();
//! let q_dot: Vec<Vec<f64>> = times.iter().map(|&t| vec![t, 0.2, 0.0, 0.0, 0.0, 0.0]).collect();
//! let load = Load::payload(20.0).with_seed001_gravity();
//! let fixed = energy_along_motion(&model, &times, &q, &q_dot, &load, TorqueModel::Static).unwrap();
//! let moving = energy_along_motion(&model, &times, &q, &q_dot, &load, TorqueModel::Dynamic).unwrap();
//! assert!(fixed.energy > 0.0 && moving.energy != fixed.energy);
//! ```

use std::fmt;

use super::energy::{energy_measure, joint_torques, Load, TorqueFloor};
use super::JointWeights;
use crate::dynamics::{rnea, DynamicsData};
use crate::error::{check_finite_vector, Error, Result};
use crate::kinematics::Data;
use crate::math::Vector3;
use crate::model::Model;

/// Which torques enter seed 001's eq 9 and eq 17.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TorqueModel {
    /// The torques holding the load still: `J' w + g(q)` (gravity only when
    /// the load has one), as [`super::joint_torques`].
    Static,
    /// The full inverse dynamics of the motion:
    /// `M(q) qdd + C(q, qd) qd + J' w` plus `g(q)` when the load has gravity.
    Dynamic,
}

impl TorqueModel {
    /// `static` or `dynamic`.
    pub fn as_str(self) -> &'static str {
        match self {
            TorqueModel::Static => "static",
            TorqueModel::Dynamic => "dynamic",
        }
    }
}

impl fmt::Display for TorqueModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Workspace for [`EnergyTorques::torques`]: the torques of either model at
/// one state, allocation-free after [`EnergyTorques::new`].
#[derive(Clone, Debug)]
pub struct EnergyTorques {
    kinematics: Data,
    dynamics: DynamicsData,
    wrench_torques: Vec<f64>,
}

impl EnergyTorques {
    /// A workspace for `model`. Errors: a model without mass properties
    /// (the dynamic torques need them; see [`crate::dynamics::check_dynamics_model`]).
    pub fn new(model: &Model) -> Result<Self> {
        Ok(EnergyTorques {
            kinematics: Data::new(model),
            dynamics: DynamicsData::new(model)?,
            wrench_torques: vec![0.0; model.dof()],
        })
    }

    /// Joint torques (N m or N) of `model` at `q` (rad or m), `q_dot`
    /// (rad/s or m/s), `q_ddot` (rad/s^2 or m/s^2) holding `load`, by
    /// `torque_model`, into `torques`. Allocates nothing.
    ///
    /// Errors: sizes, NaN, a load with gravity on a model without masses.
    #[allow(clippy::too_many_arguments)]
    pub fn torques(
        &mut self,
        model: &Model,
        q: &[f64],
        q_dot: &[f64],
        q_ddot: &[f64],
        load: &Load,
        torque_model: TorqueModel,
        torques: &mut [f64],
    ) -> Result<()> {
        match torque_model {
            TorqueModel::Static => joint_torques(model, &mut self.kinematics, q, load, torques),
            TorqueModel::Dynamic => {
                load.validate()?;
                if torques.len() != model.dof() {
                    return Err(Error::DimensionMismatch {
                        what: "torques (output buffer)",
                        expected: model.dof(),
                        got: torques.len(),
                    });
                }
                let wrench_only = Load::wrench(load.wrench);
                joint_torques(
                    model,
                    &mut self.kinematics,
                    q,
                    &wrench_only,
                    &mut self.wrench_torques,
                )?;
                self.dynamics
                    .set_gravity(load.gravity.unwrap_or_else(Vector3::zeros))?;
                let inverse = rnea(model, &mut self.dynamics, q, q_dot, q_ddot)?;
                for ((t, a), b) in torques.iter_mut().zip(inverse).zip(&self.wrench_torques) {
                    *t = a + b;
                }
                Ok(())
            }
        }
    }

    /// Seed 001's energy weights (eq 17), `a_i = max(|tau_i|, f)^2`, from
    /// the torques of `torque_model` at this state (see [`Self::torques`]).
    #[allow(clippy::too_many_arguments)]
    pub fn weights(
        &mut self,
        model: &Model,
        q: &[f64],
        q_dot: &[f64],
        q_ddot: &[f64],
        load: &Load,
        torque_model: TorqueModel,
        floor: TorqueFloor,
    ) -> Result<JointWeights> {
        let mut torques = vec![0.0; model.dof()];
        self.torques(model, q, q_dot, q_ddot, load, torque_model, &mut torques)?;
        JointWeights::from_torques(&torques, floor)
    }
}

/// Seed 001's energy measure over a sampled motion.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionEnergy {
    /// Which torques were used.
    pub torque_model: TorqueModel,
    /// `integral of F dt` (W^2 s), `F = sum (q_dot_i tau_i)^2` (eq 9) at each
    /// sample times the step to the next (as
    /// [`super::MotionSummary`] does).
    pub energy: f64,
    /// `F` at each sample, W^2.
    pub measure: Vec<f64>,
    /// Largest `|tau_i|` of each joint over the samples, N m or N.
    pub peak_torques: Vec<f64>,
}

/// Seed 001's energy measure of a motion sampled at `times` (s, increasing)
/// with joint positions `q[k]` and velocities `q_dot[k]` (one vector per
/// sample), holding `load`, with the torques of `torque_model`. For
/// [`TorqueModel::Dynamic`] the accelerations are the central differences
/// of `q_dot` (one-sided at the ends). Use it on the samples of a
/// [`crate::tracking::TrackingReport`] (its `time`, `q`, `q_dot`) to
/// compare distributions under static and dynamic torques.
///
/// Errors: fewer than 2 samples, sizes, times not increasing, NaN, a model
/// without mass properties.
pub fn energy_along_motion(
    model: &Model,
    times: &[f64],
    q: &[Vec<f64>],
    q_dot: &[Vec<f64>],
    load: &Load,
    torque_model: TorqueModel,
) -> Result<MotionEnergy> {
    let count = times.len();
    if count < 2 || q.len() != count || q_dot.len() != count {
        return Err(Error::invalid_argument(
            "motion",
            format!(
                "needs at least 2 samples with one time, one q and one q_dot each, got {} times, {} q, {} q_dot",
                count,
                q.len(),
                q_dot.len()
            ),
        ));
    }
    if let Some(k) = times
        .windows(2)
        .position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
    {
        return Err(Error::invalid_argument(
            "times",
            format!(
                "must increase strictly; sample {} is at {} after {}",
                k + 1,
                times[k + 1],
                times[k]
            ),
        ));
    }
    let n = model.dof();
    let mut workspace = EnergyTorques::new(model)?;
    let mut torques = vec![0.0; n];
    let mut q_ddot = vec![0.0; n];
    let mut measure = Vec::with_capacity(count);
    let mut peak_torques = vec![0.0_f64; n];
    let mut energy = 0.0;
    for k in 0..count {
        check_finite_vector("q_dot", &q_dot[k], n)?;
        let (a, b) = (k.saturating_sub(1), (k + 1).min(count - 1));
        for j in 0..n {
            q_ddot[j] = (q_dot[b][j] - q_dot[a][j]) / (times[b] - times[a]);
        }
        workspace.torques(
            model,
            &q[k],
            &q_dot[k],
            &q_ddot,
            load,
            torque_model,
            &mut torques,
        )?;
        let f = energy_measure(&q_dot[k], &torques)?;
        for (p, t) in peak_torques.iter_mut().zip(&torques) {
            *p = p.max(t.abs());
        }
        if k + 1 < count {
            energy += f * (times[k + 1] - times[k]);
        }
        measure.push(f);
    }
    Ok(MotionEnergy {
        torque_model,
        energy,
        measure,
        peak_torques,
    })
}
