//! A joint's motion subspace in its own frame: every joint of a
//! [`Model`](crate::model::Model) turns about or slides along its frame's z
//! axis, so `S` is the constant `(e_z, 0)` or `(0, e_z)` (Featherstone table
//! 4.1), and every product with it picks or places a component.

use super::spatial::{Force, Motion, SpatialInertia};
use crate::math::{Pose, Vector3};
use crate::model::JointKind;

/// The motion subspace of one joint, in the joint's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum JointAxis {
    /// Rotation about local z: `S = (e_z, 0)`.
    Rotation,
    /// Translation along local z: `S = (0, e_z)`.
    Translation,
}

impl JointAxis {
    pub(crate) fn of(kind: JointKind) -> Self {
        if kind.is_rotational() {
            JointAxis::Rotation
        } else {
            JointAxis::Translation
        }
    }

    /// `m + S rate`.
    #[inline(always)]
    pub(crate) fn add_rate(self, m: &mut Motion, rate: f64) {
        match self {
            JointAxis::Rotation => m.angular.z += rate,
            JointAxis::Translation => m.linear.z += rate,
        }
    }

    /// `m x (S rate)`: the velocity-product acceleration of a body moving
    /// with `m` whose joint moves at `rate` (Featherstone eq 5.7's `v x S qd`).
    #[inline(always)]
    pub(crate) fn velocity_product(self, m: &Motion, rate: f64) -> Motion {
        // w x e_z = (w_y, -w_x, 0).
        let turn = |u: &Vector3<f64>| Vector3::new(u.y * rate, -u.x * rate, 0.0);
        match self {
            JointAxis::Rotation => Motion::new(turn(&m.angular), turn(&m.linear)),
            JointAxis::Translation => Motion::new(Vector3::zeros(), turn(&m.angular)),
        }
    }

    /// `S' f`: the generalized force of `f` on the joint (N m or N).
    #[inline(always)]
    pub(crate) fn component(self, f: &Force) -> f64 {
        match self {
            JointAxis::Rotation => f.moment.z,
            JointAxis::Translation => f.force.z,
        }
    }

    /// `I S`: the force that a unit joint acceleration takes on a body of
    /// inertia `I` at rest.
    #[inline(always)]
    pub(crate) fn inertia_column(self, inertia: &SpatialInertia) -> Force {
        let h = &inertia.first_moment;
        match self {
            // (I_O e_z, -h x e_z)
            JointAxis::Rotation => Force {
                moment: inertia.rotational.column(2).into_owned(),
                force: Vector3::new(-h.y, h.x, 0.0),
            },
            // (h x e_z, m e_z)
            JointAxis::Translation => Force {
                moment: Vector3::new(h.y, -h.x, 0.0),
                force: Vector3::new(0.0, 0.0, inertia.mass),
            },
        }
    }

    /// `S` seen from the frame in which the joint's frame sits at `frame`:
    /// `(z, p x z)` or `(0, z)`, `z` the joint axis and `p` its origin there.
    #[inline(always)]
    pub(crate) fn in_frame(self, frame: &Pose) -> Motion {
        let z: Vector3<f64> = frame.rotation.column(2).into_owned();
        match self {
            JointAxis::Rotation => Motion::new(z, frame.translation.cross(&z)),
            JointAxis::Translation => Motion::new(Vector3::zeros(), z),
        }
    }

    /// The joint's own frame after it moved to position `position` (whose
    /// `(sin, cos)` is `sin_cos`), in the frame in which it sits at
    /// `placement` before moving: `placement Rz(position)` or
    /// `placement Tz(position)`.
    #[inline(always)]
    pub(crate) fn moved(self, placement: &Pose, position: f64, (s, c): (f64, f64)) -> Pose {
        let mut frame = *placement;
        match self {
            JointAxis::Rotation => {
                let x = placement.rotation.column(0);
                let y = placement.rotation.column(1);
                frame.rotation.set_column(0, &(x * c + y * s));
                frame.rotation.set_column(1, &(y * c - x * s));
            }
            JointAxis::Translation => {
                frame.translation += placement.rotation.column(2) * position;
            }
        }
        frame
    }
}
