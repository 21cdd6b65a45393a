//! The simulated system a tracking run drives: its state, its end-effector
//! pose and Jacobian, and how it advances at given joint rates.

use crate::error::Result;
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Matrix6xX, Pose};
use crate::model::Model;

/// A system driven at the velocity level: joint positions, the end-effector
/// pose and Jacobian (6 x n, rows `[vx, vy, vz, wx, wy, wz]`, world or
/// inertial frame) at them, and a step at constant joint rates.
///
/// Plants in armkit: [`FixedBase`] (any arm on a fixed base, the flexible
/// gantry included: its model carries the beam coupling), and, in the
/// modules above this one, [`crate::space::FloatingBase`] (a free-floating
/// space robot, attitude held or fully free, seed 004) and the attitude-held
/// system placed by its centre of mass that
/// [`crate::singularity::PathTracker`] uses.
pub trait Plant {
    /// Number of joints.
    fn dof(&self) -> usize;

    /// Current joint positions, rad or m.
    fn joint_positions(&self) -> &[f64];

    /// Computes the end-effector pose and the Jacobian at the current state.
    /// Errors: a numerical failure of the model (an overflow): an error, not
    /// a singularity.
    fn evaluate(&mut self) -> Result<()>;

    /// End-effector pose at the last [`Plant::evaluate`], world (inertial) frame.
    fn end_effector(&self) -> &Pose;

    /// Jacobian at the last [`Plant::evaluate`] (`J`, or the generalized `J*`).
    fn jacobian(&self) -> &Matrix6xX<f64>;

    /// Base pose (inertial frame); the identity on a fixed base.
    fn base(&self) -> Pose {
        Pose::identity()
    }

    /// Advances the state by `dt` s at constant joint rates `rates` (rad/s or m/s).
    fn advance(&mut self, rates: &[f64], dt: f64) -> Result<()>;
}

/// An arm on a fixed base: `q += dt q_dot`, forward kinematics and the
/// world-frame Jacobian of its model. Borrows a [`Data`] workspace sized for
/// the model, so that a run allocates only its joint vector.
#[derive(Debug)]
pub struct FixedBase<'a> {
    model: &'a Model,
    data: &'a mut Data,
    q: Vec<f64>,
}

impl<'a> FixedBase<'a> {
    /// `model` at joint positions `q0` (checked against the size and the
    /// limits). Errors: wrong size, NaN, outside the limits, a workspace made
    /// for another model.
    pub fn new(model: &'a Model, data: &'a mut Data, q0: &[f64]) -> Result<Self> {
        model.check_limits(q0)?;
        Ok(FixedBase {
            model,
            data,
            q: q0.to_vec(),
        })
    }

    /// The model.
    pub fn model(&self) -> &'a Model {
        self.model
    }

    /// The workspace: after [`Plant::evaluate`], forward kinematics and the
    /// Jacobian at the current joint positions.
    pub fn data(&self) -> &Data {
        self.data
    }
}

impl Plant for FixedBase<'_> {
    fn dof(&self) -> usize {
        self.q.len()
    }

    fn joint_positions(&self) -> &[f64] {
        &self.q
    }

    fn evaluate(&mut self) -> Result<()> {
        jacobian(self.model, self.data, &self.q, JacobianFrame::World)?;
        Ok(())
    }

    fn end_effector(&self) -> &Pose {
        self.data.end_effector_pose()
    }

    fn jacobian(&self) -> &Matrix6xX<f64> {
        self.data.jacobian()
    }

    fn advance(&mut self, rates: &[f64], dt: f64) -> Result<()> {
        for (qi, vi) in self.q.iter_mut().zip(rates) {
            *qi += dt * vi;
        }
        Ok(())
    }
}
