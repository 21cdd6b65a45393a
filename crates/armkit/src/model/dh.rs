//! Denavit-Hartenberg parameters, standard and modified (Craig).

use super::{JointKind, JointLimits, LinkInertia};
use crate::math::Pose;

/// Which Denavit-Hartenberg convention a table uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DhConvention {
    /// Standard (distal) DH: `A_j = Rz(theta_j) Tz(d_j) Tx(a_j) Rx(alpha_j)`.
    Standard,
    /// Modified (proximal, Craig) DH: `A_j = Rx(alpha_{j-1}) Tx(a_{j-1}) Rz(theta_j) Tz(d_j)`,
    /// where row j stores `alpha_{j-1}` and `a_{j-1}` in its `alpha` and `a`.
    Modified,
}

/// One row of a DH table: one moving joint and the link it moves.
///
/// Lengths in metres, angles in radians. The joint variable `q_j` is added,
/// after `offset`, to `theta` for a revolute joint and to `d` for a prismatic
/// one: `theta_j = theta + q_j + offset` or `d_j = d + q_j + offset`. This is
/// the Robotics Toolbox convention (where the constant `theta` of a revolute
/// joint and `d` of a prismatic one are zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DhLink {
    /// Revolute (or continuous) or prismatic.
    pub kind: JointKind,
    /// Joint angle constant, rad.
    pub theta: f64,
    /// Link offset along z, m.
    pub d: f64,
    /// Link length along x, m.
    pub a: f64,
    /// Link twist about x, rad.
    pub alpha: f64,
    /// Joint offset added to the joint variable (rad or m).
    pub offset: f64,
    /// Position, velocity and acceleration limits.
    pub limits: JointLimits,
    /// Mass properties, in this link's DH frame (standard: frame j at the
    /// link's distal end; modified: frame j on joint j's axis).
    pub inertia: Option<LinkInertia>,
}

impl DhLink {
    fn new(kind: JointKind, theta: f64, d: f64, a: f64, alpha: f64) -> Self {
        DhLink {
            kind,
            theta,
            d,
            a,
            alpha,
            offset: 0.0,
            limits: JointLimits::UNLIMITED,
            inertia: None,
        }
    }

    /// A revolute joint with link parameters `d`, `a`, `alpha`, no limits yet.
    pub fn revolute(d: f64, a: f64, alpha: f64) -> Self {
        Self::new(JointKind::Revolute, 0.0, d, a, alpha)
    }

    /// A prismatic joint with link parameters `theta`, `a`, `alpha`, no limits yet.
    pub fn prismatic(theta: f64, a: f64, alpha: f64) -> Self {
        Self::new(JointKind::Prismatic, theta, 0.0, a, alpha)
    }

    /// Sets the position limits (rad or m).
    pub fn with_limits(mut self, lower: f64, upper: f64) -> Self {
        self.limits.lower = lower;
        self.limits.upper = upper;
        self
    }

    /// Sets the velocity limit magnitude (rad/s or m/s).
    pub fn with_velocity_limit(mut self, velocity: f64) -> Self {
        self.limits.velocity = Some(velocity);
        self
    }

    /// Sets the joint offset (rad or m).
    pub fn with_offset(mut self, offset: f64) -> Self {
        self.offset = offset;
        self
    }

    /// Sets the constant `d` (m), e.g. of a prismatic joint.
    pub fn with_d(mut self, d: f64) -> Self {
        self.d = d;
        self
    }

    /// Sets the constant `theta` (rad), e.g. of a revolute joint.
    pub fn with_theta(mut self, theta: f64) -> Self {
        self.theta = theta;
        self
    }

    /// Sets the mass properties (in this link's DH frame).
    pub fn with_inertia(mut self, inertia: LinkInertia) -> Self {
        self.inertia = Some(inertia);
        self
    }

    pub(super) fn check_numbers(&self) -> std::result::Result<(), (&'static str, String)> {
        for (field, value) in [
            ("theta", self.theta),
            ("d", self.d),
            ("a", self.a),
            ("alpha", self.alpha),
            ("offset", self.offset),
        ] {
            if !value.is_finite() {
                return Err((field, format!("must be finite, got {value}")));
            }
        }
        Ok(())
    }

    /// The fixed transform before the joint's motion, in the previous DH
    /// frame, and the one after it, up to this link's DH frame.
    pub(super) fn split(&self, convention: DhConvention) -> (Pose, Pose) {
        let rotational = self.kind.is_rotational();
        let (theta0, d0) = if rotational {
            (self.theta + self.offset, self.d)
        } else {
            (self.theta, self.d + self.offset)
        };
        let z_part = Pose::rot_z(theta0) * Pose::trans_z(d0);
        let x_part = Pose::trans_x(self.a) * Pose::rot_x(self.alpha);
        match convention {
            DhConvention::Standard => (z_part, x_part),
            DhConvention::Modified => (
                Pose::rot_x(self.alpha) * Pose::trans_x(self.a) * z_part,
                Pose::identity(),
            ),
        }
    }
}
