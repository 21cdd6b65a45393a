//! The box a map covers: where the tool point can be.
//!
//! An arm on prismatic axes (a gantry's rails and ram, `gantry9`) carries
//! its first rotational axis over a box: the leading prismatic joints only
//! translate what follows, along axes that do not turn, so the point on
//! the first rotational axis ([`crate::ik::analytic::structure`]'s point
//! at `q = 0`) moves to `p0 + sum_i q_i a_i` with each `q_i` within its
//! limits, an affine image of a box (its bounding box per world axis:
//! `p0 + sum_i [min, max](q_lo a_i, q_hi a_i)`). The rest of the chain
//! keeps the tool within the rest's reach bound (the sum of its link
//! lengths plus its prismatic travel, [`crate::ik::ReachBound`]'s
//! argument) of that point. The tool is then within that distance of the
//! core box, and within the core box grown by it on every side. An arm
//! without leading prismatic joints has a core box of one point: the
//! reach ball's cube, as before.

use crate::error::{Error, Result};
use crate::ik::analytic::structure::{ArmStructure, Motion};
use crate::ik::REACH_MARGIN;
use crate::math::Vector3;
use crate::model::Model;

/// The world-frame box holding every tool position of a model (m): a core
/// box the first rotational axis's point moves in (a point for an arm on a
/// fixed base) grown by the reach of the joints after it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReachBox {
    core_lower: Vector3<f64>,
    core_upper: Vector3<f64>,
    radius: f64,
}

impl ReachBox {
    /// The box of `model` (see the module docs).
    ///
    /// Errors: a coupled model, or a prismatic joint without finite
    /// limits (the message names the robot; a map needs a bounded box).
    pub fn of_model(model: &Model) -> Result<ReachBox> {
        let unbounded = || {
            Error::invalid_argument(
                "robot",
                format!(
                    "`{}` has no finite reach bound (a coupled model or a prismatic joint without limits): a map needs a bounded box",
                    model.name()
                ),
            )
        };
        let structure = ArmStructure::of_model(model).map_err(|_| unbounded())?;
        let joints = model.joints();
        let rails = structure
            .motions
            .iter()
            .take_while(|m| **m == Motion::Translation)
            .count();
        let start = structure
            .points
            .get(rails)
            .copied()
            .unwrap_or(structure.home.translation);
        let (mut lower, mut upper) = (start, start);
        for (axis, joint) in structure.axes.iter().zip(joints).take(rails) {
            let (lo, hi) = (joint.limits.lower, joint.limits.upper);
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(unbounded());
            }
            for a in 0..3 {
                let (x, y) = (lo * axis[a], hi * axis[a]);
                lower[a] += x.min(y);
                upper[a] += x.max(y);
            }
        }
        // The rest of the chain as an arm of its own, from the point on
        // its first axis.
        let rest = ArmStructure::from_lines(
            structure.points[rails..].to_vec(),
            structure.axes[rails..].to_vec(),
            structure.motions[rails..].to_vec(),
            structure.home,
        );
        let travel: Vec<f64> = joints[rails..]
            .iter()
            .map(|j| j.limits.lower.abs().max(j.limits.upper.abs()))
            .collect();
        let radius = rest.reach_bound(&travel);
        if !radius.is_finite() {
            return Err(unbounded());
        }
        Ok(ReachBox {
            core_lower: lower,
            core_upper: upper,
            radius,
        })
    }

    /// Lower corner of the box, world frame, m.
    pub fn lower(&self) -> Vector3<f64> {
        self.core_lower.add_scalar(-self.radius)
    }

    /// Upper corner of the box, world frame, m.
    pub fn upper(&self) -> Vector3<f64> {
        self.core_upper.add_scalar(self.radius)
    }

    /// Reach of the joints after the leading prismatic ones from the point
    /// on their first axis, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// True when `position` (world frame, m) is farther than the radius
    /// (with [`REACH_MARGIN`]) from the core box: no tool position is there.
    pub fn excludes(&self, position: &Vector3<f64>) -> bool {
        let mut squared = 0.0;
        for a in 0..3 {
            let d = (self.core_lower[a] - position[a]).max(position[a] - self.core_upper[a]);
            squared += d.max(0.0).powi(2);
        }
        squared.sqrt() > self.radius * (1.0 + REACH_MARGIN) + REACH_MARGIN
    }
}
