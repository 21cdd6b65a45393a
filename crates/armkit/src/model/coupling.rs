//! Couplings between joint variables, such as the gantry beam's deflection.

use super::{JointKind, Model};
use crate::beam::CarriageDeflection;
use crate::error::{Error, Result};

/// How a coupled joint's extra displacement depends on its source joint.
#[derive(Clone, Debug, PartialEq)]
pub enum CouplingLaw {
    /// The deflection `w(a)` (m, positive downward) of a simply supported beam
    /// under a carriage at `a = q[source]` (seed 000, eq 1 with the load at
    /// the point of interest; eq 4 corrected: `d3' = d3 + w(d2)`).
    BeamDeflection(CarriageDeflection),
}

impl CouplingLaw {
    /// The extra displacement of the target joint and its derivative with
    /// respect to the source joint's position: `(f(x), df/dx)`.
    pub fn offset_and_slope(&self, source_position: f64) -> (f64, f64) {
        match self {
            CouplingLaw::BeamDeflection(beam) => beam.deflection_and_slope(source_position),
        }
    }

    /// Checks the law's parameters (a beam deflection: the carriage weight
    /// is finite and >= 0).
    pub fn validate(&self) -> Result<()> {
        match self {
            CouplingLaw::BeamDeflection(beam) => beam.validate(),
        }
    }
}

/// Joint `target` moves by `q[target] + f(q[source])`.
///
/// Forward kinematics uses the effective position; the Jacobian becomes
/// `J = J0 M`, `M` the identity with `M[target][source] = df/dx` (seed 000,
/// eqs 8-10, corrected), recomputed at every configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct JointCoupling {
    /// Index of the joint whose position drives the coupling.
    pub source: usize,
    /// Index of the (prismatic) joint that is displaced.
    pub target: usize,
    /// The law `f`.
    pub law: CouplingLaw,
}

impl JointCoupling {
    pub(crate) fn validate(&self, model: &Model) -> Result<()> {
        let dof = model.dof();
        self.law.validate()?;
        let bad = |reason: String| Error::invalid_argument("coupling", reason);
        if self.source >= dof || self.target >= dof {
            return Err(bad(format!(
                "joint indices source {} and target {} must be below the model's {dof} joints",
                self.source, self.target
            )));
        }
        if self.source == self.target {
            return Err(bad("source and target must be different joints".into()));
        }
        if model.joints()[self.target].kind != JointKind::Prismatic {
            return Err(bad(format!(
                "target joint {} must be prismatic",
                self.target
            )));
        }
        Ok(())
    }
}
