//! The analytic solver's options: which representatives, the limits
//! filter, the verification, the searches it may run, and a 7-DOF arm's
//! redundancy parameter.

use super::RangeFilter;
use super::{Representatives, Verification};
use crate::error::Result;

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
    /// Which searches the solver may run.
    pub search: SearchPolicy,
}

/// Which searches an [`AnalyticSolver`](super::AnalyticSolver) may run (set-up decides the class).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SearchPolicy {
    /// Closed forms and 1-D searches (tens of microseconds); a general 6R
    /// arm is refused. The default.
    #[default]
    UpToOneDimension,
    /// Also the 2-D search of a general 6R arm ([`search2d`](super::search2d): milliseconds,
    /// may miss solutions).
    TwoDimensions,
}

impl SearchPolicy {
    /// A short snake-case name.
    pub fn as_str(&self) -> &'static str {
        match self {
            SearchPolicy::UpToOneDimension => "up_to_one_dimension",
            SearchPolicy::TwoDimensions => "two_dimensions",
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
            search: SearchPolicy::UpToOneDimension,
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
