//! Fixed-size spatial (6-D) vectors and rigid-body inertias (Featherstone,
//! *Rigid Body Dynamics Algorithms*, ch. 2), in Plücker coordinates.
//!
//! Every quantity here is expressed in one frame's axes and about that
//! frame's origin. The inverse dynamics and the mass matrix work in each
//! body's own joint frame and carry vectors and inertias from one joint
//! frame to the next with [`Motion::inverse_transformed`],
//! [`Force::transformed`] and [`SpatialInertia::transformed`] (Featherstone
//! 2.8 and 2.13, done on the 3 x 3 blocks); the articulated-body algorithm
//! works in the world frame. Motion vectors are `(angular, linear)` = `(w, v)` with `v` the velocity of
//! the body point that passes through the origin; force vectors are
//! `(moment, force)` = `(n, f)` with `n` the moment about the origin.

use std::ops::{Add, AddAssign, Mul, Sub};

use crate::math::{Matrix3, Matrix6, Pose, Vector3, Vector6};
use crate::model::LinkInertia;

/// A spatial motion vector: angular velocity `w` (rad/s) and the linear
/// velocity `v` (m/s) of the body point at the origin; or their
/// accelerations (rad/s^2, m/s^2).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Motion {
    /// Angular part `w`.
    pub angular: Vector3<f64>,
    /// Linear part `v`, at the origin of the frame.
    pub linear: Vector3<f64>,
}

/// A spatial force vector: moment `n` about the origin (N m) and force `f` (N).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Force {
    /// Moment about the origin `n`.
    pub moment: Vector3<f64>,
    /// Force `f`.
    pub force: Vector3<f64>,
}

/// The zero 3-vector, usable in `const` contexts.
const ZERO3: Vector3<f64> = Vector3::new(0.0, 0.0, 0.0);

// Scalar forms of the 3-vector products the recursions run per joint:
// written out, they compile to fewer instructions than nalgebra's generic
// products (which pack pairs of lanes and shuffle them).

/// `a x b`.
#[inline(always)]
fn cross(a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// `R v`.
#[inline(always)]
fn rotate(r: &Matrix3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(
        r.m11 * v.x + r.m12 * v.y + r.m13 * v.z,
        r.m21 * v.x + r.m22 * v.y + r.m23 * v.z,
        r.m31 * v.x + r.m32 * v.y + r.m33 * v.z,
    )
}

/// `R' v`.
#[inline(always)]
fn rotate_back(r: &Matrix3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(
        r.m11 * v.x + r.m21 * v.y + r.m31 * v.z,
        r.m12 * v.x + r.m22 * v.y + r.m32 * v.z,
        r.m13 * v.x + r.m23 * v.y + r.m33 * v.z,
    )
}

/// `S v` for a symmetric `S` (its upper triangle is read).
#[inline(always)]
fn symmetric_product(s: &Matrix3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(
        s.m11 * v.x + s.m12 * v.y + s.m13 * v.z,
        s.m12 * v.x + s.m22 * v.y + s.m23 * v.z,
        s.m13 * v.x + s.m23 * v.y + s.m33 * v.z,
    )
}

impl Motion {
    /// The zero motion.
    pub const ZERO: Motion = Motion {
        angular: ZERO3,
        linear: ZERO3,
    };

    /// A motion from its angular and linear parts.
    #[inline(always)]
    pub fn new(angular: Vector3<f64>, linear: Vector3<f64>) -> Self {
        Motion { angular, linear }
    }

    /// Motion cross product `self x m` (`crm` in Featherstone):
    /// `(w1 x w2, w1 x v2 + v1 x w2)`.
    #[inline(always)]
    pub fn cross(&self, m: &Motion) -> Motion {
        Motion {
            angular: cross(&self.angular, &m.angular),
            linear: cross(&self.angular, &m.linear) + cross(&self.linear, &m.angular),
        }
    }

    /// Force cross product `self x* f` (`crf`): `(w x n + v x f, w x f)`.
    #[inline(always)]
    pub fn cross_force(&self, f: &Force) -> Force {
        Force {
            moment: cross(&self.angular, &f.moment) + cross(&self.linear, &f.force),
            force: cross(&self.angular, &f.force),
        }
    }

    /// The power pairing `m . f = w . n + v . f` (W for velocity and force).
    #[inline(always)]
    pub fn dot(&self, f: &Force) -> f64 {
        self.angular.dot(&f.moment) + self.linear.dot(&f.force)
    }

    /// The same motion seen from a frame placed at `placement` (that
    /// frame's pose in this vector's frame): `(R' w, R' (v + w x p))`, the
    /// velocity of the point at the new origin `p`, in the new axes `R`
    /// (Featherstone's `X` of eq 2.24).
    #[inline(always)]
    pub fn inverse_transformed(&self, placement: &Pose) -> Motion {
        let r = &placement.rotation;
        let linear = self.linear + cross(&self.angular, &placement.translation);
        Motion {
            angular: rotate_back(r, &self.angular),
            linear: rotate_back(r, &linear),
        }
    }

    /// As a 6-vector `[w; v]`.
    #[inline(always)]
    pub fn to_vector(&self) -> Vector6<f64> {
        Vector6::new(
            self.angular.x,
            self.angular.y,
            self.angular.z,
            self.linear.x,
            self.linear.y,
            self.linear.z,
        )
    }

    /// From a 6-vector `[w; v]`.
    #[inline(always)]
    pub fn from_vector(v: &Vector6<f64>) -> Self {
        Motion {
            angular: Vector3::new(v[0], v[1], v[2]),
            linear: Vector3::new(v[3], v[4], v[5]),
        }
    }
}

impl Force {
    /// The zero force.
    pub const ZERO: Force = Force {
        moment: ZERO3,
        force: ZERO3,
    };

    /// The same force seen from the frame in which this vector's frame sits
    /// at `placement`: `(R n + p x R f, R f)` (Featherstone's `X^*`, the
    /// transpose of [`Motion::inverse_transformed`]'s matrix).
    #[inline(always)]
    pub fn transformed(&self, placement: &Pose) -> Force {
        let r = &placement.rotation;
        let force = rotate(r, &self.force);
        Force {
            moment: rotate(r, &self.moment) + cross(&placement.translation, &force),
            force,
        }
    }

    /// As a 6-vector `[n; f]`.
    #[inline(always)]
    pub fn to_vector(&self) -> Vector6<f64> {
        Vector6::new(
            self.moment.x,
            self.moment.y,
            self.moment.z,
            self.force.x,
            self.force.y,
            self.force.z,
        )
    }

    /// From a 6-vector `[n; f]`.
    #[inline(always)]
    pub fn from_vector(v: &Vector6<f64>) -> Self {
        Force {
            moment: Vector3::new(v[0], v[1], v[2]),
            force: Vector3::new(v[3], v[4], v[5]),
        }
    }
}

impl Add for Motion {
    type Output = Motion;
    #[inline(always)]
    fn add(self, m: Motion) -> Motion {
        Motion::new(self.angular + m.angular, self.linear + m.linear)
    }
}

impl Sub for Motion {
    type Output = Motion;
    #[inline(always)]
    fn sub(self, m: Motion) -> Motion {
        Motion::new(self.angular - m.angular, self.linear - m.linear)
    }
}

impl Mul<f64> for Motion {
    type Output = Motion;
    #[inline(always)]
    fn mul(self, s: f64) -> Motion {
        Motion::new(self.angular * s, self.linear * s)
    }
}

impl Add for Force {
    type Output = Force;
    #[inline(always)]
    fn add(self, f: Force) -> Force {
        Force {
            moment: self.moment + f.moment,
            force: self.force + f.force,
        }
    }
}

impl AddAssign for Force {
    #[inline(always)]
    fn add_assign(&mut self, f: Force) {
        self.moment += f.moment;
        self.force += f.force;
    }
}

/// A rigid body's spatial inertia about a frame's origin, in its axes:
/// mass `m` (kg), first moment `h = m c` (kg m, `c` the centre of mass) and
/// rotational inertia about the origin `I_O = I_c + m (|c|^2 E - c c')`
/// (kg m^2). As a 6 x 6 matrix acting on `[w; v]`:
/// `[[I_O, h x], [-h x, m E]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpatialInertia {
    /// Mass, kg.
    pub mass: f64,
    /// First moment of mass `m c`, kg m.
    pub first_moment: Vector3<f64>,
    /// Rotational inertia about the origin, kg m^2 (symmetric).
    pub rotational: Matrix3<f64>,
}

impl SpatialInertia {
    /// No mass.
    pub const ZERO: SpatialInertia = SpatialInertia {
        mass: 0.0,
        first_moment: ZERO3,
        rotational: Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    };

    /// The inertia of `link` about its body frame's origin, in that frame's
    /// axes (the frame its centre of mass and inertia are given in).
    pub fn of_link(link: &LinkInertia) -> Self {
        let m = link.mass;
        let c = link.com;
        let h = c * m;
        // I_O = I_c + m (|c|^2 E - c c') (parallel-axis theorem).
        let rotational =
            link.inertia + Matrix3::from_diagonal_element(c.dot(&h)) - h * c.transpose();
        SpatialInertia {
            mass: m,
            first_moment: h,
            rotational,
        }
    }

    /// This inertia (about its frame's origin, in its axes) seen from the
    /// frame in which its frame sits at `placement` (`R`, `p`):
    /// `h' = R h + m p` and, by the parallel-axis theorem,
    /// `I' = R I R' - (p k' + k p') + 2 (k . p) E` with `k = R h + m p / 2`
    /// (Featherstone eq 2.66 on the 3 x 3 blocks; the six distinct entries of
    /// the symmetric result only).
    #[inline(always)]
    pub fn transformed(&self, placement: &Pose) -> Self {
        let r = &placement.rotation;
        let p = placement.translation;
        let m = self.mass;
        let rotated_moment = r * self.first_moment;
        let k = rotated_moment + p * (0.5 * m);
        let kp = 2.0 * k.dot(&p);
        let a = r * self.rotational;
        let entry = |i: usize, j: usize| a.row(i).dot(&r.row(j)) - p[i] * k[j] - k[i] * p[j];
        let (xy, xz, yz) = (entry(0, 1), entry(0, 2), entry(1, 2));
        let rotational = Matrix3::new(
            entry(0, 0) + kp,
            xy,
            xz,
            xy,
            entry(1, 1) + kp,
            yz,
            xz,
            yz,
            entry(2, 2) + kp,
        );
        SpatialInertia {
            mass: m,
            first_moment: rotated_moment + p * m,
            rotational,
        }
    }

    /// The inertia of `link` (given in a body frame: centre of mass and
    /// inertia about it in that frame's axes) seen from the frame in which
    /// the body frame sits at `frame`: `c' = R c + p`, `I_c' = R I_c R'`,
    /// then moved to the origin (parallel-axis theorem).
    #[inline(always)]
    pub fn from_link(link: &LinkInertia, frame: &Pose) -> Self {
        Self::of_link(link).transformed(frame)
    }

    /// `I m`: the momentum (for a velocity) or the force (for an
    /// acceleration) `(I_O w + h x v, m v - h x w)`.
    #[inline(always)]
    pub fn apply(&self, m: &Motion) -> Force {
        Force {
            moment: symmetric_product(&self.rotational, &m.angular)
                + cross(&self.first_moment, &m.linear),
            force: m.linear * self.mass - cross(&self.first_moment, &m.angular),
        }
    }

    /// The 6 x 6 matrix acting on `[w; v]`, giving `[n; f]`.
    pub fn to_matrix(&self) -> Matrix6<f64> {
        let mut out = Matrix6::zeros();
        let h = crate::math::skew(&self.first_moment);
        out.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.rotational);
        out.fixed_view_mut::<3, 3>(0, 3).copy_from(&h);
        out.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-h));
        out.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&Matrix3::from_diagonal_element(self.mass));
        out
    }

    /// Kinetic energy `v' I v / 2` of the body moving with velocity `v` (J).
    #[inline(always)]
    pub fn kinetic_energy(&self, v: &Motion) -> f64 {
        0.5 * v.dot(&self.apply(v))
    }
}

impl Add for SpatialInertia {
    type Output = SpatialInertia;
    #[inline(always)]
    fn add(mut self, other: SpatialInertia) -> SpatialInertia {
        self += other;
        self
    }
}

impl AddAssign for SpatialInertia {
    #[inline(always)]
    fn add_assign(&mut self, other: SpatialInertia) {
        self.mass += other.mass;
        self.first_moment += other.first_moment;
        self.rotational += other.rotational;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrix_form_matches_apply_and_is_symmetric() {
        let link = LinkInertia {
            mass: 2.0,
            com: Vector3::new(0.1, -0.2, 0.3),
            inertia: Matrix3::new(0.3, 0.01, 0.02, 0.01, 0.2, 0.03, 0.02, 0.03, 0.1),
        };
        let frame = Pose::new(
            crate::math::Rotation3::from_euler_angles(0.3, -0.7, 1.1).into_inner(),
            Vector3::new(0.5, 0.4, -0.2),
        );
        let inertia = SpatialInertia::from_link(&link, &frame);
        let m = Motion::new(Vector3::new(0.3, -1.0, 2.0), Vector3::new(-0.5, 0.7, 0.1));
        let by_matrix = inertia.to_matrix() * m.to_vector();
        let by_apply = inertia.apply(&m).to_vector();
        assert!((by_matrix - by_apply).amax() < 1e-14);
        let matrix = inertia.to_matrix();
        assert!((matrix - matrix.transpose()).amax() < 1e-15);
        // The centre of mass maps as a point.
        let c = frame.transform_point(&link.com);
        assert!((inertia.first_moment / inertia.mass - c).norm() < 1e-15);
    }

    #[test]
    fn transforms_keep_power_and_momentum() {
        let link = LinkInertia {
            mass: 1.5,
            com: Vector3::new(-0.2, 0.1, 0.4),
            inertia: Matrix3::new(0.2, 0.02, -0.01, 0.02, 0.3, 0.04, -0.01, 0.04, 0.25),
        };
        let placement = Pose::new(
            crate::math::Rotation3::from_euler_angles(-0.4, 0.9, 2.1).into_inner(),
            Vector3::new(0.3, -0.6, 0.8),
        );
        // A motion in the outer frame, seen in the inner one.
        let outer = Motion::new(Vector3::new(0.7, -0.2, 1.1), Vector3::new(0.4, 0.9, -0.3));
        let inner = outer.inverse_transformed(&placement);
        // The velocity of the inner origin: v + w x p, in inner axes.
        let point = outer.linear + outer.angular.cross(&placement.translation);
        assert!((placement.rotation * inner.linear - point).amax() < 1e-15);
        // Power is frame-independent: (X m) . f = m . (X* f).
        let force = Force::from_vector(&Vector6::new(0.5, -1.0, 0.2, 2.0, 0.3, -0.7));
        let power_inner = inner.dot(&force);
        let power_outer = outer.dot(&force.transformed(&placement));
        assert!((power_inner - power_outer).abs() < 1e-14);
        // The body's inertia seen from the outer frame: I' m = X* (I (X m)).
        let local = SpatialInertia::of_link(&link);
        let moved = local.transformed(&placement);
        let direct = moved.apply(&outer).to_vector();
        let through = local.apply(&inner).transformed(&placement).to_vector();
        assert!((direct - through).amax() < 1e-14);
        // The same as placing the link directly.
        let placed = SpatialInertia::from_link(&link.transformed(&placement), &Pose::identity());
        assert!((placed.to_matrix() - moved.to_matrix()).amax() < 1e-14);
    }

    #[test]
    fn cross_products_match_their_matrix_forms() {
        let a = Motion::new(Vector3::new(0.3, -1.0, 2.0), Vector3::new(-0.5, 0.7, 0.1));
        let b = Motion::new(Vector3::new(1.3, 0.2, -0.4), Vector3::new(0.9, -0.3, 0.6));
        let mut crm = Matrix6::zeros();
        let w = crate::math::skew(&a.angular);
        let v = crate::math::skew(&a.linear);
        crm.fixed_view_mut::<3, 3>(0, 0).copy_from(&w);
        crm.fixed_view_mut::<3, 3>(3, 3).copy_from(&w);
        crm.fixed_view_mut::<3, 3>(3, 0).copy_from(&v);
        assert!((crm * b.to_vector() - a.cross(&b).to_vector()).amax() < 1e-15);
        // crf = -crm'.
        let f = Force::from_vector(&b.to_vector());
        let crf = -crm.transpose();
        assert!((crf * f.to_vector() - a.cross_force(&f).to_vector()).amax() < 1e-15);
    }
}
