//! What a continuous-path study grades: seed 002's paper (its variants and
//! claims beside the main run) or only what armkit promises on any robot.

use crate::ik::closed_form::Arm4Solver;
use crate::model::Model;
use crate::trajectory::{LimitKind, LimitViolation};

/// What [`super::ContinuousPathStudy::outcome`] runs and grades.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum PathScope {
    /// The paper on a model of seed 002's structure (its 4-DOF arm), armkit's
    /// promises on any other robot (a user's robot is not the paper's).
    #[default]
    Auto,
    /// Seed 002: the main run, the paper's variants beside it (the other
    /// orientation law, Fig 6's midpoint-only test, the cubic-quintic
    /// scheme, the error against the number of segments) and its claims.
    Paper,
    /// armkit's promises only: the main run within the tolerance, continuous
    /// at the knots, within the joint limits (and the torque check).
    Armkit,
}

impl PathScope {
    /// `Paper` or `Armkit` on `model` (`Auto`: the paper on seed 002's structure).
    pub fn resolve(self, model: &Model) -> PathScope {
        match self {
            PathScope::Auto if Arm4Solver::new(model).is_ok() => PathScope::Paper,
            PathScope::Auto => PathScope::Armkit,
            other => other,
        }
    }
}

/// One limit violation in words: joint (1-based), which limit, when, how far.
pub fn violation_text(v: &LimitViolation) -> String {
    let (what, unit) = match v.kind {
        LimitKind::Position => ("position", "rad or m"),
        LimitKind::Velocity => ("velocity", "rad/s or m/s"),
        LimitKind::Acceleration => ("acceleration", "rad/s^2 or m/s^2"),
    };
    format!(
        "joint {} exceeds its {what} limit {} ({unit}) from {:.4} s to {:.4} s (peak {:.6} at {:.4} s)",
        v.joint + 1,
        v.bound,
        v.start_time,
        v.end_time,
        v.peak_value,
        v.peak_time
    )
}
