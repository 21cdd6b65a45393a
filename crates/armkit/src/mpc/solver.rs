//! Building the QP backend a [`QpSolverKind`] names: the one place that
//! knows every implementation of [`QpSolver`] (the interface, [`super::qp`],
//! knows none of them).

use super::active_set::ActiveSetQp;
use super::clarabel_qp::ClarabelQp;
#[cfg(feature = "osqp")]
use super::osqp_qp::OsqpQp;
use super::qp::{QpProblem, QpSolver, QpSolverKind};
#[cfg(not(feature = "osqp"))]
use crate::error::Error;
use crate::error::Result;

impl QpSolverKind {
    /// Builds the backend for `problem`. Errors when the backend was not
    /// compiled in or rejects the problem.
    pub fn build(self, problem: &QpProblem) -> Result<Box<dyn QpSolver>> {
        match self {
            QpSolverKind::ActiveSet => Ok(Box::new(ActiveSetQp::with_fallback(problem)?)),
            QpSolverKind::Clarabel => Ok(Box::new(ClarabelQp::new(problem)?)),
            #[cfg(feature = "osqp")]
            QpSolverKind::Osqp => Ok(Box::new(OsqpQp::new(problem)?)),
            #[cfg(not(feature = "osqp"))]
            QpSolverKind::Osqp => Err(Error::invalid_argument(
                "solver",
                "OSQP is not compiled in: build armkit with the `osqp` feature",
            )),
        }
    }
}
