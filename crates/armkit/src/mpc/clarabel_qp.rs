//! The Clarabel backend of the planner's QP ([`super::qp`]): Clarabel 0.11,
//! an interior-point solver in pure Rust, with the planner's settings or a
//! reference accuracy.

use super::qp::{numerical, upper_triangle_pattern, QpOutcome, QpProblem, QpSolver, QpStatus};
use crate::error::Result;

/// Clarabel's accuracy settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClarabelAccuracy {
    /// Gap and feasibility tolerances 1e-8 (Clarabel's defaults), no
    /// iterative refinement: the planner's backend.
    Planner,
    /// Tolerances 1e-12 (kt ratio 1e-10) and iterative refinement: the reference the
    /// active-set solver is checked against.
    Reference,
}

impl ClarabelAccuracy {
    fn tolerance(self) -> f64 {
        match self {
            ClarabelAccuracy::Planner => 1e-8,
            ClarabelAccuracy::Reference => 1e-12,
        }
    }

    fn ktratio_tolerance(self) -> f64 {
        match self {
            ClarabelAccuracy::Planner => 1e-6,
            ClarabelAccuracy::Reference => 1e-10,
        }
    }
}

/// The Clarabel backend: `lower <= A x <= upper` becomes `[A; -A] x + s =
/// [upper; -lower]`, `s >= 0` (Clarabel's non-negative cone). Presolve and
/// zero-dropping are off so that the problem data can be updated in place.
pub struct ClarabelQp {
    solver: clarabel::solver::DefaultSolver<f64>,
    // Clarabel's update functions take `&Vec` (its slice impls are unusable
    // through them: `[T]` is unsized), so the data is copied into these first.
    p: Vec<f64>,
    q: Vec<f64>,
    /// `[upper; -lower]`, rewritten every solve.
    b: Vec<f64>,
}

impl ClarabelQp {
    /// Sets the backend up for `problem` (this allocates; solves do not),
    /// with the planner's settings: Clarabel's default tolerances (1e-8),
    /// no iterative refinement.
    pub fn new(problem: &QpProblem) -> Result<Self> {
        Self::with_accuracy(problem, ClarabelAccuracy::Planner)
    }

    /// As [`ClarabelQp::new`] with the given accuracy settings.
    pub fn with_accuracy(problem: &QpProblem, accuracy: ClarabelAccuracy) -> Result<Self> {
        use clarabel::algebra::CscMatrix as ClarabelCsc;
        use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, SupportedConeT};
        let n = problem.variables;
        let (p_colptr, p_rowval) = upper_triangle_pattern(n);
        let p = ClarabelCsc::new(n, n, p_colptr, p_rowval, problem.hessian_upper.clone());
        let a = &problem.constraints;
        let m = a.rows;
        // [A; -A]: column c holds A's entries, then the same rows shifted by m, negated.
        let mut colptr = Vec::with_capacity(n + 1);
        let mut rowval = Vec::with_capacity(2 * a.nnz());
        let mut nzval = Vec::with_capacity(2 * a.nnz());
        colptr.push(0);
        for c in 0..n {
            let range = a.col_ptr[c]..a.col_ptr[c + 1];
            for k in range.clone() {
                rowval.push(a.row_indices[k]);
                nzval.push(a.values[k]);
            }
            for k in range {
                rowval.push(a.row_indices[k] + m);
                nzval.push(-a.values[k]);
            }
            colptr.push(rowval.len());
        }
        let stacked = ClarabelCsc::new(2 * m, n, colptr, rowval, nzval);
        let mut b = vec![0.0; 2 * m];
        fill_stacked_bounds(&problem.lower, &problem.upper, &mut b);
        let cones = [SupportedConeT::NonnegativeConeT(2 * m)];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .presolve_enable(false)
            .input_sparse_dropzeros(false)
            .max_iter(100)
            // Iterative refinement of the KKT solves costs ~30 % of the
            // solve on this small, well-regularised problem; the closed-form
            // and limit tests pass without it.
            .iterative_refinement_enable(accuracy == ClarabelAccuracy::Reference)
            .tol_gap_abs(accuracy.tolerance())
            .tol_gap_rel(accuracy.tolerance())
            .tol_feas(accuracy.tolerance())
            .tol_ktratio(accuracy.ktratio_tolerance())
            .build()
            .map_err(|e| numerical("Clarabel settings", e.to_string()))?;
        let solver = DefaultSolver::new(&p, &problem.gradient, &stacked, &b, &cones, settings)
            .map_err(|e| numerical("Clarabel set-up", e.to_string()))?;
        if !solver.is_data_update_allowed() {
            return Err(numerical(
                "Clarabel set-up",
                "the solver does not allow in-place data updates".into(),
            ));
        }
        Ok(ClarabelQp {
            solver,
            p: problem.hessian_upper.clone(),
            q: problem.gradient.clone(),
            b,
        })
    }
}

impl ClarabelQp {
    /// The multipliers of the last solve's rows, `(lower side, upper side)`
    /// (`m` values each, >= 0): a row is active on the side whose
    /// multiplier exceeds its slack (complementarity), the classification
    /// the active-set solver is checked against.
    pub fn bound_multipliers(&self) -> (&[f64], &[f64]) {
        let z = &self.solver.solution.z;
        let m = self.b.len() / 2;
        if z.len() == 2 * m {
            (&z[m..], &z[..m])
        } else {
            (&[], &[])
        }
    }
}

fn fill_stacked_bounds(lower: &[f64], upper: &[f64], b: &mut [f64]) {
    let m = lower.len();
    b[..m].copy_from_slice(upper);
    for (dst, l) in b[m..].iter_mut().zip(lower) {
        *dst = -l;
    }
}

impl QpSolver for ClarabelQp {
    fn name(&self) -> &'static str {
        "clarabel"
    }

    fn solve(
        &mut self,
        hessian_upper: &[f64],
        gradient: &[f64],
        lower: &[f64],
        upper: &[f64],
        x: &mut [f64],
    ) -> QpOutcome {
        use clarabel::solver::{IPSolver, SolverStatus};
        if hessian_upper.len() != self.p.len()
            || gradient.len() != self.q.len()
            || 2 * lower.len() != self.b.len()
            || lower.len() != upper.len()
        {
            return QpOutcome {
                status: QpStatus::NumericalFailure,
                iterations: 0,
            };
        }
        self.p.copy_from_slice(hessian_upper);
        self.q.copy_from_slice(gradient);
        fill_stacked_bounds(lower, upper, &mut self.b);
        let updated = self
            .solver
            .update_P(&self.p)
            .and_then(|_| self.solver.update_q(&self.q))
            .and_then(|_| self.solver.update_b(&self.b));
        if updated.is_err() {
            return QpOutcome {
                status: QpStatus::NumericalFailure,
                iterations: 0,
            };
        }
        self.solver.solve();
        let solution = &self.solver.solution;
        let status = match solution.status {
            SolverStatus::Solved => QpStatus::Solved,
            SolverStatus::AlmostSolved => QpStatus::SolvedInaccurate,
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                QpStatus::Infeasible
            }
            SolverStatus::MaxIterations | SolverStatus::MaxTime => QpStatus::IterationLimit,
            _ => QpStatus::NumericalFailure,
        };
        if status.has_solution() && solution.x.len() == x.len() {
            x.copy_from_slice(&solution.x);
        }
        QpOutcome {
            status,
            iterations: solution.iterations,
        }
    }
}
