//! The analytic solver's options: which representatives, the limits
//! filter, the verification, and a 7-DOF arm's redundancy parameter.

use super::RangeFilter;
use super::{Representatives, Verification};

/// Options of an [`AnalyticSolver`](super::AnalyticSolver). Defaults: every representative within
/// the limits, solutions outside the limits dropped, each solution checked
/// by forward kinematics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AnalyticOptions {
    /// Which 2 pi multiples of a joint angle are returned.
    pub representatives: Representatives,
    /// Whether solutions outside the joint limits are kept.
    pub limits: RangeFilter,
    /// How each solution's fit is decided.
    pub verification: Verification,
}

impl Default for AnalyticOptions {
    fn default() -> Self {
        AnalyticOptions {
            representatives: Representatives::Every,
            limits: RangeFilter::WithinLimits,
            verification: Verification::ForwardKinematics,
        }
    }
}

/// The redundancy parameter of a 7-DOF arm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Parameter {
    /// Joint `joint` (0-based) held at `value` (rad or m); the other six
    /// must form a class.
    FixedJoint {
        /// Which joint, 0-based.
        joint: usize,
        /// Its value, rad or m.
        value: f64,
    },
    /// The elbow angle of a spherical-shoulder-elbow-wrist arm, rad (see
    /// [`AnalyticSolver::elbow_angle`](super::AnalyticSolver::elbow_angle)).
    ElbowAngle(f64),
}
