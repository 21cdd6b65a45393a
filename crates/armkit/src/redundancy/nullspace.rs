//! Secondary objectives in the null space: Liegeois' gradient projection in
//! the weighted metric.
//!
//! Among all joint velocities with `J q_dot = V`, take the one nearest (in the
//! metric `A` of the weights) to a preferred velocity `z`:
//! `q_dot = z + A^-1 J' (J A^-1 J')^-1 (V - J z) = J#_A V + N z`, where
//! `N = I - J#_A J` is the weighted null-space projector (`J N = 0`). With
//! `z = k A^-1 grad H` (the gradient of `H` in the metric `A`, scaled by a
//! gain `k`), the self-motion climbs `H` without disturbing the end effector
//! (Liegeois 1977). Two objectives:
//!
//! * joint-limit avoidance: descend
//!   `H(q) = 1/(2n) sum_i ((q_i - mid_i) / half_range_i)^2` (joints with an
//!   infinite limit contribute nothing);
//! * manipulability: ascend Yoshikawa's `w(q) = sqrt(det(J J'))`, its gradient
//!   by central differences of the Jacobian.
//!
//! ```
//! use armkit::kinematics::{jacobian, Data, JacobianFrame};
//! use armkit::math::Vector6;
//! use armkit::redundancy::{joint_limit_cost, SecondaryTask};
//! use armkit::redundancy::{JointWeights, SecondaryObjective, SolverOptions, WeightedLeastNorm};
//! let model = armkit::robots::by_name("panda").unwrap();
//! let mut data = Data::new(&model);
//! let mut q = vec![2.0, 1.2, 0.0, -0.4, 0.0, 2.5, 0.0]; // far from mid-range
//! let weights = JointWeights::uniform(7);
//! let mut task = SecondaryTask::new(&model, SecondaryObjective::JointLimits { gain: 1.0 }).unwrap();
//! let mut solver = WeightedLeastNorm::new(7, SolverOptions::default()).unwrap();
//! let mut z = vec![0.0; 7];
//! let before = joint_limit_cost(&model, &q).unwrap();
//! for _ in 0..100 {
//!     // Hold the end effector still (V = 0) and move in the null space.
//!     task.preferred_velocity(&model, &q, &weights, &mut z).unwrap();
//!     let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
//!     let q_dot = solver.solve_toward(j, &weights, &Vector6::zeros(), &z).unwrap().solved().unwrap();
//!     for (qi, vi) in q.iter_mut().zip(q_dot) { *qi += 0.01 * vi; }
//! }
//! assert!(joint_limit_cost(&model, &q).unwrap() < before);
//! ```

use super::JointWeights;
use crate::error::{check_finite_vector, Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::model::Model;

/// A secondary objective pursued in the null space of the Jacobian.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum SecondaryObjective {
    /// None: the weighted least-norm solution.
    #[default]
    None,
    /// Joint-limit avoidance: `z = -gain A^-1 grad H`, `H` the normalised
    /// squared distance to mid-range ([`joint_limit_cost`], dimensionless).
    /// `gain` (> 0) in (joint unit)^2/s, so that `z` is a velocity.
    JointLimits {
        /// Gain (> 0).
        gain: f64,
    },
    /// Manipulability: `z = +gain A^-1 grad w`, `w = sqrt(det(J J'))`
    /// ([`manipulability`]), the gradient by central differences with
    /// `step` (rad or m, > 0, e.g. 1e-6). Costs `2 n` Jacobians per step.
    Manipulability {
        /// Gain (> 0).
        gain: f64,
        /// Finite-difference step (> 0).
        step: f64,
    },
}

impl SecondaryObjective {
    /// Checks that the parameters are finite and > 0.
    pub fn validate(&self) -> Result<()> {
        let positive = crate::error::check_positive;
        match *self {
            SecondaryObjective::None => Ok(()),
            SecondaryObjective::JointLimits { gain } => positive("secondary.gain", gain),
            SecondaryObjective::Manipulability { gain, step } => {
                positive("secondary.gain", gain)?;
                positive("secondary.step", step)
            }
        }
    }
}

/// Liegeois' joint-limit cost `H(q) = 1/(2n) sum_i ((q_i - mid_i) / h_i)^2`,
/// `mid_i` and `h_i` the middle and half-width of joint i's position range
/// (joints with an infinite limit contribute 0). Dimensionless: 0 at
/// mid-range, `1/(2n)` per joint sitting on a limit. Errors: size, NaN.
pub fn joint_limit_cost(model: &Model, q: &[f64]) -> Result<f64> {
    model.check_joint_positions(q)?;
    let n = model.dof() as f64;
    Ok(model
        .joints()
        .iter()
        .zip(q)
        .filter(|(joint, _)| joint.limits.is_bounded())
        .map(|(joint, &value)| {
            let half = 0.5 * (joint.limits.upper - joint.limits.lower);
            let u = (value - joint.limits.midpoint()) / half;
            u * u / (2.0 * n)
        })
        .sum())
}

/// The gradient of [`joint_limit_cost`]: `(q_i - mid_i) / (n h_i^2)` (1/rad
/// or 1/m), into `gradient`. Errors: sizes, NaN. Allocates nothing.
pub fn joint_limit_gradient(model: &Model, q: &[f64], gradient: &mut [f64]) -> Result<()> {
    model.check_joint_positions(q)?;
    check_output("gradient", gradient, model.dof())?;
    let n = model.dof() as f64;
    for ((g, joint), &value) in gradient.iter_mut().zip(model.joints()).zip(q) {
        *g = if joint.limits.is_bounded() {
            let half = 0.5 * (joint.limits.upper - joint.limits.lower);
            (value - joint.limits.midpoint()) / (n * half * half)
        } else {
            0.0
        };
    }
    Ok(())
}

/// Yoshikawa's manipulability of a 6 x n Jacobian (the one kernel, [`crate::linalg::manipulability`]).
pub use crate::linalg::manipulability;

fn check_output(what: &'static str, buffer: &[f64], dof: usize) -> Result<()> {
    if buffer.len() != dof {
        return Err(Error::DimensionMismatch {
            what,
            expected: dof,
            got: buffer.len(),
        });
    }
    Ok(())
}

/// Workspace that turns a [`SecondaryObjective`] into a preferred joint
/// velocity `z = k A^-1 (improving gradient)` at a configuration, for
/// [`super::WeightedLeastNorm::solve_toward`]. Sized once for one model;
/// allocates nothing per call.
#[derive(Clone, Debug)]
pub struct SecondaryTask {
    objective: SecondaryObjective,
    /// `+-gain * grad` (unweighted).
    direction: Vec<f64>,
    /// For the manipulability gradient's Jacobians.
    data: Data,
    probe: Vec<f64>,
}

impl SecondaryTask {
    /// A workspace for `model` and `objective` (validated).
    pub fn new(model: &Model, objective: SecondaryObjective) -> Result<Self> {
        objective.validate()?;
        Ok(SecondaryTask {
            objective,
            direction: vec![0.0; model.dof()],
            data: Data::new(model),
            probe: vec![0.0; model.dof()],
        })
    }

    /// The objective.
    pub fn objective(&self) -> &SecondaryObjective {
        &self.objective
    }

    /// The improving direction at `q`, unweighted: `-gain grad H` (joint
    /// limits), `+gain grad w` (manipulability), zeros for none; rad/s or m/s
    /// once multiplied by `A^-1`. Errors: size, NaN, another model.
    pub fn direction(&mut self, model: &Model, q: &[f64]) -> Result<&[f64]> {
        model.check_joint_positions(q)?;
        check_output("secondary task (model)", &self.direction, model.dof())?;
        match self.objective {
            SecondaryObjective::None => self.direction.fill(0.0),
            SecondaryObjective::JointLimits { gain } => {
                joint_limit_gradient(model, q, &mut self.direction)?;
                self.direction.iter_mut().for_each(|g| *g *= -gain);
            }
            SecondaryObjective::Manipulability { gain, step } => {
                self.probe.copy_from_slice(q);
                for (i, &qi) in q.iter().enumerate() {
                    self.probe[i] = qi + step;
                    let plus = manipulability(jacobian(
                        model,
                        &mut self.data,
                        &self.probe,
                        JacobianFrame::World,
                    )?);
                    self.probe[i] = qi - step;
                    let minus = manipulability(jacobian(
                        model,
                        &mut self.data,
                        &self.probe,
                        JacobianFrame::World,
                    )?);
                    self.probe[i] = qi;
                    self.direction[i] = gain * (plus - minus) / (2.0 * step);
                }
            }
        }
        Ok(&self.direction)
    }

    /// The preferred velocity `z = A^-1 direction` (rad/s or m/s; 0 for a
    /// locked joint) at `q` for `weights`, into `preferred`.
    pub fn preferred_velocity(
        &mut self,
        model: &Model,
        q: &[f64],
        weights: &JointWeights,
        preferred: &mut [f64],
    ) -> Result<()> {
        weights.check_size("weights", model.dof())?;
        check_output("preferred", preferred, model.dof())?;
        self.direction(model, q)?;
        weighted_direction(weights, &self.direction, preferred)
    }
}

/// `out_i = direction_i / a_i` (0 for locked joints): a gradient in the
/// metric of the weights. Errors: sizes or NaN.
pub fn weighted_direction(
    weights: &JointWeights,
    direction: &[f64],
    out: &mut [f64],
) -> Result<()> {
    check_finite_vector("direction", direction, weights.dof())?;
    check_output("preferred", out, weights.dof())?;
    for ((o, &d), &inv) in out.iter_mut().zip(direction).zip(weights.inverse()) {
        *o = d * inv;
    }
    Ok(())
}
