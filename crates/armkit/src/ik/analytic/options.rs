//! The analytic solver's options: which representatives, the limits
//! filter, the verification, how arms without a closed form are solved, and a 7-DOF arm's
//! redundancy parameter.

use super::RangeFilter;
use super::{Representatives, Verification};
use crate::error::Result;

/// Options of an [`AnalyticSolver`](super::AnalyticSolver). Defaults: every representative within
/// the limits, solutions outside the limits dropped, each solution checked
/// by forward kinematics, elimination for the arms without a closed form.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AnalyticOptions {
    /// Which 2 pi multiples of a joint angle are returned.
    pub representatives: Representatives,
    /// Whether solutions outside the joint limits are kept.
    pub limits: RangeFilter,
    /// How each solution's fit is decided.
    pub verification: Verification,
    /// How arms without a closed form are solved.
    pub search: SearchPolicy,
}

/// How an [`AnalyticSolver`](super::AnalyticSolver) solves the 6R arms
/// without a closed form (set-up decides the class). Closed-form classes are
/// solved in closed form under every policy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SearchPolicy {
    /// Algebraic elimination ([`elimination`](super::elimination): the 16
    /// roots of a degree-8 trigonometric polynomial; tens of microseconds)
    /// for every 6R arm of rotation joints it applies to: one intersecting
    /// or parallel pair anywhere, the general arm, the pairs no 1-D search
    /// handles. The 1-D searches where it does not apply (a spherical wrist
    /// behind three general axes). The default.
    #[default]
    Elimination,
    /// Closed forms and the 1-D searches (the subproblem method of IK-Geo;
    /// hundreds of microseconds); a general 6R arm is refused.
    UpToOneDimension,
}

impl SearchPolicy {
    /// A short snake-case name.
    pub fn as_str(&self) -> &'static str {
        match self {
            SearchPolicy::Elimination => "elimination",
            SearchPolicy::UpToOneDimension => "up_to_one_dimension",
        }
    }
}

impl std::fmt::Display for SearchPolicy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Default for AnalyticOptions {
    fn default() -> Self {
        AnalyticOptions {
            representatives: Representatives::Every,
            limits: RangeFilter::WithinLimits,
            verification: Verification::ForwardKinematics,
            search: SearchPolicy::Elimination,
        }
    }
}

impl AnalyticOptions {
    /// Nothing to check (every combination is valid); kept for uniformity.
    pub fn validate(&self) -> Result<()> {
        Ok(())
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
