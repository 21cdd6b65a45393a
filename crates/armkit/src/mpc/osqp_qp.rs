//! The OSQP backend of the planner's QP ([`super::qp`]), behind the `osqp`
//! feature.

use super::qp::{numerical, upper_triangle_pattern, QpOutcome, QpProblem, QpSolver, QpStatus};
use crate::error::Result;

/// The OSQP backend (OSQP 0.6.3 through the `osqp` crate; feature `osqp`).
///
/// Tolerances 1e-7 absolute and relative, solution polishing on (it turns
/// ADMM's 1e-7 into an active-set accurate answer), warm start from the
/// previous sample's primal and dual solution. OSQP's own `osqp 1.x` crate
/// could not be used: its build script downloads QDLDL from GitHub, which
/// this build environment cannot reach; 0.6 ships all its C sources.
pub struct OsqpQp {
    problem: osqp::Problem,
    p_colptr: Vec<usize>,
    p_rowval: Vec<usize>,
    variables: usize,
}

impl OsqpQp {
    /// Sets the backend up for `problem`.
    pub fn new(problem: &QpProblem) -> Result<Self> {
        use osqp::{CscMatrix as OsqpCsc, Problem, Settings};
        use std::borrow::Cow;
        let n = problem.variables;
        let (p_colptr, p_rowval) = upper_triangle_pattern(n);
        let p = OsqpCsc {
            nrows: n,
            ncols: n,
            indptr: Cow::Borrowed(&p_colptr),
            indices: Cow::Borrowed(&p_rowval),
            data: Cow::Borrowed(&problem.hessian_upper),
        };
        let a = &problem.constraints;
        let a = OsqpCsc {
            nrows: a.rows,
            ncols: a.cols,
            indptr: Cow::Borrowed(&a.col_ptr),
            indices: Cow::Borrowed(&a.row_indices),
            data: Cow::Borrowed(&a.values),
        };
        let settings = Settings::default()
            .verbose(false)
            .eps_abs(1e-7)
            .eps_rel(1e-7)
            .polish(true)
            .max_iter(4000)
            .warm_start(true);
        let solver = Problem::new(
            p,
            &problem.gradient,
            a,
            &problem.lower,
            &problem.upper,
            &settings,
        )
        .map_err(|e| numerical("OSQP set-up", e.to_string()))?;
        Ok(OsqpQp {
            problem: solver,
            p_colptr,
            p_rowval,
            variables: n,
        })
    }
}

impl QpSolver for OsqpQp {
    fn name(&self) -> &'static str {
        "osqp"
    }

    fn solve(
        &mut self,
        hessian_upper: &[f64],
        gradient: &[f64],
        lower: &[f64],
        upper: &[f64],
        x: &mut [f64],
    ) -> QpOutcome {
        use osqp::{CscMatrix as OsqpCsc, Status};
        use std::borrow::Cow;
        let p = OsqpCsc {
            nrows: self.variables,
            ncols: self.variables,
            indptr: Cow::Borrowed(&self.p_colptr),
            indices: Cow::Borrowed(&self.p_rowval),
            data: Cow::Borrowed(hessian_upper),
        };
        self.problem.update_P(p);
        self.problem.update_lin_cost(gradient);
        self.problem.update_bounds(lower, upper);
        let result = self.problem.solve();
        let iterations = result.iter();
        let (status, solution) = match &result {
            Status::Solved(s) => (QpStatus::Solved, Some(s.x())),
            Status::SolvedInaccurate(s) => (QpStatus::SolvedInaccurate, Some(s.x())),
            Status::MaxIterationsReached(_) | Status::TimeLimitReached(_) => {
                (QpStatus::IterationLimit, None)
            }
            Status::PrimalInfeasible(_) | Status::PrimalInfeasibleInaccurate(_) => {
                (QpStatus::Infeasible, None)
            }
            _ => (QpStatus::NumericalFailure, None),
        };
        if let Some(solution) = solution {
            if solution.len() == x.len() {
                x.copy_from_slice(solution);
            }
        }
        QpOutcome { status, iterations }
    }
}
