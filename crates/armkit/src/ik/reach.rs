//! A bound on an arm's reach, known at set-up: targets beyond it are
//! rejected at once instead of after every restart.
//!
//! With the joint axes as lines (see [`super::analytic::structure`]), each
//! joint's motion keeps the distance to a point on its own axis, so the
//! end effector is never farther from the first axis's point than the sum
//! of the distances between consecutive axis points and from the last one
//! to the end effector ("the sum of the link lengths"), plus the largest
//! travel of each prismatic joint.
//!
//! ```
//! use armkit::ik::ReachBound;
//! use armkit::math::{Pose, Vector3};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let reach = ReachBound::of_model(&model);
//! assert!(reach.radius() > 0.9 && reach.radius() < 2.0);
//! assert!(reach.excludes(&Pose::from_translation(Vector3::new(100.0, 0.0, 0.5))));
//! assert!(!reach.excludes(&Pose::identity()));
//! ```

use super::analytic::structure::ArmStructure;
use crate::math::{Pose, Vector3};
use crate::model::{JointKind, Model};

/// Relative margin on the bound (round-off): a target is excluded only
/// beyond `radius (1 + 1e-9) + 1e-9 m`.
pub const REACH_MARGIN: f64 = 1e-9;

/// The ball every end-effector position of a model lies in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReachBound {
    centre: Vector3<f64>,
    radius: f64,
}

impl ReachBound {
    /// The bound of `model`: infinite for coupled models and for prismatic
    /// joints without finite limits.
    pub fn of_model(model: &Model) -> ReachBound {
        let Ok(structure) = ArmStructure::of_model(model) else {
            return ReachBound {
                centre: Vector3::zeros(),
                radius: f64::INFINITY,
            };
        };
        let travel: Vec<f64> = model
            .joints()
            .iter()
            .map(|j| match j.kind {
                JointKind::Prismatic => j.limits.lower.abs().max(j.limits.upper.abs()),
                _ => 0.0,
            })
            .collect();
        ReachBound {
            centre: structure
                .points
                .first()
                .copied()
                .unwrap_or_else(Vector3::zeros),
            radius: structure.reach_bound(&travel),
        }
    }

    /// Centre of the ball (a point on the first joint axis), world frame, m.
    pub fn centre(&self) -> Vector3<f64> {
        self.centre
    }

    /// Radius, m (infinite when unknown).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Distance of `target`'s position from the centre, m.
    pub fn distance(&self, target: &Pose) -> f64 {
        (target.translation - self.centre).norm()
    }

    /// True when `target`'s position is beyond the reach (with [`REACH_MARGIN`]).
    pub fn excludes(&self, target: &Pose) -> bool {
        self.distance(target) > self.radius * (1.0 + REACH_MARGIN) + REACH_MARGIN
    }
}
