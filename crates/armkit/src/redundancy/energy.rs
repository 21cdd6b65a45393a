//! Joint torques for a load, and seed 001's energy weights and energy measure.
//!
//! Seed 001 weighs each joint velocity by its joint torque: the cost
//! `F = sum (q_dot_i tau_i)^2` (eq 9) is the sum of the squared joint powers
//! (W^2), so the energy-optimal distribution is the weighted least norm with
//! `a_i = tau_i^2` (eq 17). The torques are the static holding torques for
//! a load ([`Load`]): an end-effector wrench `w` gives `tau = J' w`, and link
//! weights give the gravity torques, when the model has mass properties.
//!
//! A joint whose torque is zero (a vertical axis, a horizontal rail, a joint
//! the load happens to pass through) would get weight zero: moving it costs
//! nothing in eq 9, and `A^-1` does not exist. The rule here
//! ([`TorqueFloor`]): each torque's magnitude is floored before squaring,
//! `a_i = max(|tau_i|, f)^2`, by default `f = 0.05 max_j |tau_j|`: such a
//! joint is 400 times cheaper to move than the most loaded one, never free.
//! When every torque is zero, eq 9 is zero for every motion and cannot choose
//! one: that is an error, not a silent fallback.
//!
//! Why 5 % and not a token 1e-3: the floor is also a regularisation. Where
//! unloaded joints can move together without moving the end effector (the
//! Panda's joints 1 and 3, nearly on one vertical line, holding a payload;
//! gantry9's vertical axes 4 and 7 with the rail and beam compensating),
//! that self-motion costs almost nothing, and with a tiny floor the optimum
//! asks for fast, useless joint motion. Measured (`armkit redundancy`):
//! * Panda, 50 N payload, (0.1, 0.1, -0.1) m in 2 s: with a 1e-3 floor
//!   joints 1 and 3 spin in opposite directions at their 2.175 rad/s limit,
//!   159 of 200 steps are slowed down and the end effector lags by up to
//!   0.14 m; with 5 % the fastest joint turns at 0.32 rad/s, nothing is
//!   slowed down, and F still ends below the minimum-norm motion's.
//! * gantry9, one configuration: eq 17 without a floor asks for 17 rad/s
//!   for a 0.1 m/s twist, to save 0.6 % of F over the 1e-3 floor.
//! * eq 17 minimises F at each instant, not integrated over a motion: on
//!   the gantry9 four-way comparison the 5 % floor ends with a 2.7 % lower
//!   integral (2.582e4 W^2 s) than the 1e-3 floor (2.654e4 W^2 s).
//!
//! ```
//! use armkit::kinematics::Data;
//! use armkit::redundancy::{joint_torques, JointWeights, Load, TorqueFloor};
//! let model = armkit::robots::by_name("gantry9").unwrap();
//! let mut data = Data::new(&model);
//! let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
//! // Hold a 50 N payload, with the links' own weight (seed 001's g = 9.81 m/s^2 along -z).
//! let load = Load::payload(50.0).with_seed001_gravity();
//! let mut tau = [0.0; 9];
//! joint_torques(&model, &mut data, &q, &load, &mut tau).unwrap();
//! // The vertical ram (joint 3, pointing down) carries the carriage's load.
//! assert!(tau[2].abs() > 2000.0);
//! let weights = JointWeights::from_torques(&tau, TorqueFloor::default()).unwrap();
//! assert!(weights.values()[0] > 0.0); // the rail's torque is 0: floored
//! ```

use super::JointWeights;
use crate::error::{check_finite, check_finite_vector, Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Vector3, Vector6};
use crate::model::Model;

pub use crate::seeds::STANDARD_GRAVITY;

/// What the robot holds: an end-effector wrench and, optionally, gravity on
/// its own links.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Load {
    /// Wrench the end effector applies to its payload or environment, world
    /// frame, at the end-effector origin: `[fx, fy, fz, mx, my, mz]` (N, N m).
    /// Supporting a payload of weight `m g` means `fz = +m g`.
    pub wrench: Vector6<f64>,
    /// Gravitational acceleration in the world frame (m/s^2), or `None` to
    /// ignore the links' own weight. When given, every link needs mass
    /// properties ([`crate::model::Joint::inertia`]).
    pub gravity: Option<Vector3<f64>>,
}

impl Default for Load {
    /// No wrench, no gravity.
    fn default() -> Self {
        Load {
            wrench: Vector6::zeros(),
            gravity: None,
        }
    }
}

impl Load {
    /// An end-effector wrench (world frame, N and N m, see [`Load::wrench`]), no gravity.
    pub fn wrench(wrench: Vector6<f64>) -> Self {
        Load {
            wrench,
            gravity: None,
        }
    }

    /// Supporting a payload of weight `weight` N (e.g. 50 N for a 5.1 kg
    /// mass) held at the end-effector origin, against gravity along world -z:
    /// the wrench `[0, 0, weight, 0, 0, 0]`. No gravity on the links.
    pub fn payload(weight: f64) -> Self {
        Self::wrench(Vector6::new(0.0, 0.0, weight, 0.0, 0.0, 0.0))
    }

    /// This load with gravity `gravity` (m/s^2, world frame) on the links.
    pub fn with_gravity(mut self, gravity: Vector3<f64>) -> Self {
        self.gravity = Some(gravity);
        self
    }

    /// This load with seed 001's gravity ([`crate::seeds::SEED001_GRAVITY`],
    /// 9.81 m/s^2) along world -z. For the conventional value use
    /// [`Load::with_gravity`] with [`STANDARD_GRAVITY`] (9.80665 m/s^2).
    pub fn with_seed001_gravity(self) -> Self {
        self.with_gravity(Vector3::new(0.0, 0.0, -crate::seeds::SEED001_GRAVITY))
    }

    /// Checks that every number is finite.
    pub fn validate(&self) -> Result<()> {
        check_finite("load.wrench", self.wrench.as_slice())?;
        if let Some(g) = &self.gravity {
            check_finite("load.gravity", g.as_slice())?;
        }
        Ok(())
    }
}

/// Static joint torques (N m for rotational joints, N for prismatic ones)
/// that hold `load` at joint positions `q`: `tau = J' w + tau_gravity`, where
/// `J` is the world-frame Jacobian (coupling included) and `w` the wrench of
/// [`Load::wrench`]; see [`gravity_torques`] for the second term. Writes one
/// torque per joint into `torques`. Leaves `data` holding the forward
/// kinematics and the world-frame Jacobian at `q`. Allocates nothing.
///
/// Errors: sizes, NaN, a load with gravity on a model without mass properties.
pub fn joint_torques(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    load: &Load,
    torques: &mut [f64],
) -> Result<()> {
    load.validate()?;
    check_torque_buffer(model, torques)?;
    jacobian(model, data, q, JacobianFrame::World)?;
    torques_at_evaluated(model, data, q, load, torques)
}

/// [`joint_torques`] from a `data` that already holds the forward kinematics
/// and the world-frame Jacobian at `q` (a tracking plant's evaluation):
/// the same arithmetic without evaluating the model again. The load is
/// assumed validated and the buffer sized.
pub(crate) fn torques_at_evaluated(
    model: &Model,
    data: &Data,
    q: &[f64],
    load: &Load,
    torques: &mut [f64],
) -> Result<()> {
    for (tau, column) in torques.iter_mut().zip(data.jacobian().column_iter()) {
        *tau = column.dot(&load.wrench);
    }
    if let Some(gravity) = load.gravity {
        accumulate_gravity_torques(model, data, q, &gravity, torques)?;
    }
    Ok(())
}

/// Static joint torques (N m or N) that hold the links up against gravity
/// `gravity` (m/s^2, world frame) at joint positions `q`:
/// `tau = sum_links J_com' (-m g)` with `J_com` the Jacobian of each link's
/// centre of mass, i.e. the gradient of the potential energy. With a joint
/// coupling (the gantry beam's `d3' = d3 + w(d2)`), `tau = M' tau0`.
/// Link mass properties come from [`crate::model::Joint::inertia`],
/// expressed in each joint's motion frame ([`Data::joint_frames`]).
/// Allocates nothing.
///
/// Errors: sizes, NaN, a link without mass properties (named).
pub fn gravity_torques(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    gravity: &Vector3<f64>,
    torques: &mut [f64],
) -> Result<()> {
    check_finite("gravity", gravity.as_slice())?;
    check_torque_buffer(model, torques)?;
    crate::kinematics::forward_kinematics(model, data, q)?;
    torques.fill(0.0);
    accumulate_gravity_torques(model, data, q, gravity, torques)
}

fn check_torque_buffer(model: &Model, torques: &[f64]) -> Result<()> {
    if torques.len() != model.dof() {
        return Err(Error::DimensionMismatch {
            what: "torques (output buffer)",
            expected: model.dof(),
            got: torques.len(),
        });
    }
    Ok(())
}

/// Adds the gravity torques to `torques`; `data` must hold the forward
/// kinematics at `q`.
fn accumulate_gravity_torques(
    model: &Model,
    data: &Data,
    q: &[f64],
    gravity: &Vector3<f64>,
    torques: &mut [f64],
) -> Result<()> {
    if model.has_mimic_joints() {
        // The loop below pairs the chain's frames with the configuration's
        // joints, which differ when mimic joints follow their leaders.
        return Err(Error::invalid_argument(
            "load.gravity",
            format!(
                "model `{}` has mimic joints: gravity torques are not modelled for them yet (use a load without gravity)",
                model.name()
            ),
        ));
    }
    let joints = model.joints();
    let frames = data.joint_frames();
    // Each link's weight -m g is held by the joints up to its own;
    // coupled_target_torque is tau0[target] for the coupling below.
    let mut coupled_target_torque = 0.0;
    for (link, joint) in joints.iter().enumerate() {
        let inertia = joint.inertia.as_ref().ok_or_else(|| {
            Error::invalid_argument(
                "load.gravity",
                format!(
                    "model `{}` has no mass properties for link {link} (`{}`): gravity \
                     torques need every link's mass (use a load without gravity)",
                    model.name(),
                    joint.name
                ),
            )
        })?;
        let centre = frames[link].transform_point(&inertia.com);
        let holding_force = -inertia.mass * gravity;
        for (i, frame) in frames.iter().enumerate().take(link + 1) {
            let axis: Vector3<f64> = frame.rotation.column(2).into_owned();
            let term = if joints[i].kind.is_rotational() {
                axis.dot(&(centre - frame.translation).cross(&holding_force))
            } else {
                axis.dot(&holding_force)
            };
            torques[i] += term;
            if model.coupling().is_some_and(|c| c.target == i) {
                coupled_target_torque += term;
            }
        }
    }
    // J = J0 M with M[target][source] = slope: tau = M' tau0 adds
    // slope * tau0[target] to the source joint (seed 000, eq 10).
    if let Some(coupling) = model.coupling() {
        let (_, slope) = coupling.law.offset_and_slope(q[coupling.source]);
        torques[coupling.source] += slope * coupled_target_torque;
    }
    Ok(())
}

/// How a zero (or tiny) joint torque becomes a positive energy weight:
/// `a_i = max(|tau_i|, f)^2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TorqueFloor {
    /// `f = fraction * max_j |tau_j|`, `fraction` in `(0, 1]`. All torques
    /// zero is an error (eq 9 cannot choose a motion). Mixes N and N m when a
    /// robot has prismatic and rotational joints, as eq 9 itself does.
    Relative(f64),
    /// `f` given (N m or N, > 0), the same for every joint.
    Absolute(f64),
}

impl Default for TorqueFloor {
    /// `Relative(0.05)` (see the module documentation for why).
    fn default() -> Self {
        TorqueFloor::Relative(0.05)
    }
}

impl TorqueFloor {
    /// Checks the parameter.
    pub fn validate(&self) -> Result<()> {
        match *self {
            TorqueFloor::Relative(fraction) if fraction > 0.0 && fraction <= 1.0 => Ok(()),
            TorqueFloor::Relative(fraction) => Err(Error::invalid_argument(
                "torque_floor",
                format!("relative fraction must be in (0, 1], got {fraction}"),
            )),
            TorqueFloor::Absolute(value) if value.is_finite() && value > 0.0 => Ok(()),
            TorqueFloor::Absolute(value) => Err(Error::invalid_argument(
                "torque_floor",
                format!("absolute floor must be finite and > 0, got {value}"),
            )),
        }
    }

    /// The floor `f` (N m or N) for these torques.
    fn floor(&self, torques: &[f64]) -> Result<f64> {
        self.validate()?;
        match *self {
            TorqueFloor::Absolute(value) => Ok(value),
            TorqueFloor::Relative(fraction) => {
                let largest = torques.iter().fold(0.0_f64, |m, t| m.max(t.abs()));
                if largest > 0.0 {
                    Ok(fraction * largest)
                } else {
                    Err(Error::invalid_argument(
                        "torques",
                        "every joint torque is zero: seed 001's energy measure (eq 9) is \
                         zero for every motion and cannot choose one; give a load (wrench \
                         or gravity with link masses) or an absolute torque floor",
                    ))
                }
            }
        }
    }
}

impl JointWeights {
    /// Seed 001's energy weights (eq 17): `a_i = max(|tau_i|, f)^2` for the
    /// joint torques `torques` (N m or N), `f` from `floor`.
    pub fn from_torques(torques: &[f64], floor: TorqueFloor) -> Result<Self> {
        let mut weights = JointWeights::uniform(torques.len());
        weights.set_from_torques(torques, floor)?;
        Ok(weights)
    }

    /// Sets every weight (unlocking all joints) to `max(|tau_i|, f)^2`, in
    /// place, without allocating.
    pub fn set_from_torques(&mut self, torques: &[f64], floor: TorqueFloor) -> Result<()> {
        check_finite_vector("torques", torques, self.dof())?;
        let f = floor.floor(torques)?;
        for (joint, &tau) in torques.iter().enumerate() {
            let magnitude = tau.abs().max(f);
            self.set(joint, magnitude * magnitude)?;
        }
        Ok(())
    }
}

/// Seed 001's energy measure, eq 9: `F = sum_i (q_dot_i tau_i)^2`, the sum of
/// the squared joint powers (W^2), for joint velocities `q_dot` (rad/s or
/// m/s) and torques `torques` (N m or N). Errors: sizes differ, NaN.
pub fn energy_measure(q_dot: &[f64], torques: &[f64]) -> Result<f64> {
    check_finite("joint_velocities", q_dot)?;
    check_finite_vector("torques", torques, q_dot.len())?;
    Ok(q_dot
        .iter()
        .zip(torques)
        .map(|(v, t)| (v * t) * (v * t))
        .sum())
}
