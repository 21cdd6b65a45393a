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

    /// `a + m x (S rate)`: adds the velocity-product acceleration of a body
    /// moving with `m` whose joint moves at `rate` (Featherstone eq 5.7's
    /// `v x S qd`) to `a`.
    #[inline(always)]
    pub(crate) fn add_velocity_product(self, a: &mut Motion, m: &Motion, rate: f64) {
        // u x e_z = (u_y, -u_x, 0).
        let turn = |a: &mut Vector3<f64>, u: &Vector3<f64>| {
            a.x += u.y * rate;
            a.y -= u.x * rate;
        };
        match self {
            JointAxis::Rotation => {
                turn(&mut a.angular, &m.angular);
                turn(&mut a.linear, &m.linear);
            }
            JointAxis::Translation => turn(&mut a.linear, &m.angular),
        }
    }

    /// `S' (X* f)`: the generalized force on the joint of a force `f` given
    /// in a frame placed at `placement` in the joint's frame (the last step
    /// of carrying a force inwards, one component of
    /// [`Force::transformed`]).
    #[inline(always)]
    pub(crate) fn component_of_transformed(self, f: &Force, placement: &Pose) -> f64 {
        let r = &placement.rotation;
        let p = &placement.translation;
        // Rows 0 and 1, or row 2, of R f; (p x R f)_z = p_x (R f)_y - p_y (R f)_x.
        match self {
            JointAxis::Rotation => {
                let fx = r.row(0).transpose().dot(&f.force);
                let fy = r.row(1).transpose().dot(&f.force);
                r.row(2).transpose().dot(&f.moment) + p.x * fy - p.y * fx
            }
            JointAxis::Translation => r.row(2).transpose().dot(&f.force),
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
