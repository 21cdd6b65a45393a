//! The IK solvers by name: one vocabulary for `armkit ik --solver` and
//! Python's `Robot.ik(solver=...)`, so that a name means the same solver
//! in both.
//!
//! ```
//! use armkit::ik::SolverName;
//! assert_eq!(SolverName::parse("analytic").unwrap(), SolverName::Analytic);
//! assert_eq!(SolverName::parse("closed-form").unwrap(), SolverName::Analytic);
//! assert_eq!(SolverName::ALL.map(|s| s.as_str()), ["auto", "analytic", "lm", "nr", "dls", "sri"]);
//! ```

use super::IkMethod;
use crate::error::{Error, Result};

/// An IK solver, as the CLI and Python name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SolverName {
    /// [`super::AutoSolver`]: the analytic solver where the arm's class
    /// allows, else Levenberg-Marquardt.
    Auto,
    /// Every solution by [`super::analytic`] (the route of
    /// [`super::analytic::AnalyticRoute`]).
    Analytic,
    /// Levenberg-Marquardt (Sugihara's damping).
    Lm,
    /// Newton-Raphson with the pseudo-inverse.
    Nr,
    /// Damped least squares (Nakamura's adaptive damping).
    Dls,
    /// Chiaverini's singularity-robust inverse.
    Sri,
}

/// Other spellings accepted for a solver (`closed-form` names the
/// analytic solver: the closed forms are its classes).
pub const SOLVER_ALIASES: [(&str, SolverName); 2] = [
    ("closed-form", SolverName::Analytic),
    ("closed_form", SolverName::Analytic),
];

impl SolverName {
    /// Every solver, in the order the help lists them.
    pub const ALL: [SolverName; 6] = [
        SolverName::Auto,
        SolverName::Analytic,
        SolverName::Lm,
        SolverName::Nr,
        SolverName::Dls,
        SolverName::Sri,
    ];

    /// The name: `auto`, `analytic`, `lm`, `nr`, `dls` or `sri`.
    pub fn as_str(&self) -> &'static str {
        match self {
            SolverName::Auto => "auto",
            SolverName::Analytic => "analytic",
            SolverName::Lm => "lm",
            SolverName::Nr => "nr",
            SolverName::Dls => "dls",
            SolverName::Sri => "sri",
        }
    }

    /// The solver named `name` (a name of [`SolverName::ALL`] or an alias
    /// of [`SOLVER_ALIASES`]). Error (named `solver`): any other name, the
    /// message listing the names.
    pub fn parse(name: &str) -> Result<SolverName> {
        let alias = SOLVER_ALIASES.iter().find(|(a, _)| *a == name);
        SolverName::ALL
            .into_iter()
            .find(|s| s.as_str() == name)
            .or(alias.map(|(_, s)| *s))
            .ok_or_else(|| {
                let names: Vec<&str> = SolverName::ALL.iter().map(|s| s.as_str()).collect();
                Error::invalid_argument(
                    "solver",
                    format!(
                        "unknown IK solver `{name}`; expected {} or {}",
                        names[..names.len() - 1].join(", "),
                        names[names.len() - 1]
                    ),
                )
            })
    }

    /// The numeric method: the solver's own, Levenberg-Marquardt for
    /// `auto` (its numeric route) and `analytic` (its best effort when no
    /// solution lies within the limits).
    pub fn method(&self) -> IkMethod {
        match self {
            SolverName::Nr => IkMethod::NewtonRaphson,
            SolverName::Dls => IkMethod::DampedLeastSquares(Default::default()),
            SolverName::Sri => IkMethod::SingularityRobust(Default::default()),
            SolverName::Auto | SolverName::Analytic | SolverName::Lm => {
                IkMethod::LevenbergMarquardt(Default::default())
            }
        }
    }

    /// True for the numeric methods (`lm`, `nr`, `dls`, `sri`), which take
    /// no analytic option (redundancy parameter, representatives, search).
    pub fn is_numeric(&self) -> bool {
        !matches!(self, SolverName::Auto | SolverName::Analytic)
    }
}

impl std::fmt::Display for SolverName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}
