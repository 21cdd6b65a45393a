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

    /// `X S`: the subspace seen from a frame placed at `placement` in the
    /// joint's frame (a child body's frame): `(R' e_z, R' (e_z x p))` or
    /// `(0, R' e_z)` ([`Motion::inverse_transformed`] of `S`), so that
    /// `S' (X* f) = (X S) . f` for a force `f` given in that frame.
    #[inline(always)]
    pub(crate) fn in_child_frame(self, placement: &Pose) -> Motion {
        let r = &placement.rotation;
        let p = &placement.translation;
        // R' e_z is R's last row.
        let z = Vector3::new(r.m31, r.m32, r.m33);
        match self {
            JointAxis::Rotation => {
                // R' (e_z x p) = R' (-p_y, p_x, 0).
                let linear = Vector3::new(
                    r.m21 * p.x - r.m11 * p.y,
                    r.m22 * p.x - r.m12 * p.y,
                    r.m23 * p.x - r.m13 * p.y,
                );
                Motion::new(z, linear)
            }
            JointAxis::Translation => Motion::new(Vector3::zeros(), z),
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

    /// Writes into `frame` the joint's own frame after it moved to position
    /// `position` (whose `(sin, cos)` is `sin_cos`), in the frame in which it
    /// sits at `placement` before moving: `placement Rz(position)` or
    /// `placement Tz(position)`. Only the part that moves is written (the
    /// first two rotation columns, or the translation): `frame` must hold
    /// `placement` or an earlier result of this call for it.
    #[inline(always)]
    pub(crate) fn move_frame(
        self,
        frame: &mut Pose,
        placement: &Pose,
        position: f64,
        (s, c): (f64, f64),
    ) {
        match self {
            JointAxis::Rotation => {
                let x = placement.rotation.column(0);
                let y = placement.rotation.column(1);
                frame.rotation.set_column(0, &(x * c + y * s));
                frame.rotation.set_column(1, &(y * c - x * s));
            }
            JointAxis::Translation => {
                frame.translation = placement.translation + placement.rotation.column(2) * position;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Rotation3, Vector3};
    use crate::model::LinkInertia;

    /// `S` as a spatial motion in the joint's own frame.
    fn subspace(axis: JointAxis) -> Motion {
        let z = Vector3::z();
        match axis {
            JointAxis::Rotation => Motion::new(z, Vector3::zeros()),
            JointAxis::Translation => Motion::new(Vector3::zeros(), z),
        }
    }

    #[test]
    fn shortcuts_equal_the_general_spatial_products() {
        let m = Motion::new(Vector3::new(0.3, -1.2, 0.7), Vector3::new(-0.4, 0.9, 1.5));
        let f = Force {
            moment: Vector3::new(1.1, -0.6, 0.2),
            force: Vector3::new(-2.0, 0.5, 0.8),
        };
        let inertia = SpatialInertia::of_link(&LinkInertia {
            mass: 2.5,
            com: Vector3::new(0.1, -0.3, 0.2),
            inertia: nalgebra::Matrix3::new(0.4, 0.02, -0.03, 0.02, 0.3, 0.05, -0.03, 0.05, 0.2),
        });
        let placement = Pose::new(
            Rotation3::from_euler_angles(0.7, -0.2, 1.9).into_inner(),
            Vector3::new(0.2, 0.5, -0.3),
        );
        let close = |a: &Motion, b: &Motion| (a.to_vector() - b.to_vector()).amax() < 1e-15;
        for axis in [JointAxis::Rotation, JointAxis::Translation] {
            let s = subspace(axis);
            let mut moved = m;
            axis.add_rate(&mut moved, 0.6);
            assert!(close(&moved, &(m + s * 0.6)));
            let mut a = m;
            axis.add_velocity_product(&mut a, &moved, 0.6);
            assert!(close(&a, &(m + moved.cross(&(s * 0.6)))));
            assert!((axis.component(&f) - s.dot(&f)).abs() < 1e-15);
            let column = axis.inertia_column(&inertia).to_vector();
            assert!((column - inertia.apply(&s).to_vector()).amax() < 1e-15);
            let carried = s.dot(&f.transformed(&placement));
            assert!((axis.in_child_frame(&placement).dot(&f) - carried).abs() < 1e-14);
            let inverse = s.inverse_transformed(&placement);
            assert!(close(&axis.in_child_frame(&placement), &inverse));
            // The axis seen from the outer frame carries the same power.
            let outer = axis.in_frame(&placement);
            assert!((outer.dot(&f.transformed(&placement)) - s.dot(&f)).abs() < 1e-14);
            // The moved frame: placement, then Rz(q) or Tz(q).
            let q = 0.8_f64;
            let mut frame = placement;
            axis.move_frame(&mut frame, &placement, 0.3, 0.3_f64.sin_cos());
            axis.move_frame(&mut frame, &placement, q, q.sin_cos());
            let motion = match axis {
                JointAxis::Rotation => Pose::rot_z(q),
                JointAxis::Translation => Pose::trans_z(q),
            };
            let expected = placement * motion;
            assert!((frame.rotation - expected.rotation).amax() < 1e-15);
            assert!((frame.translation - expected.translation).amax() < 1e-15);
        }
    }
}
