//! The small quadratic-programming interface the MPC planner solves every
//! sample, and its backends (the dense active-set solver of
//! [`super::active_set`], Clarabel, and OSQP behind the `osqp` feature).
//!
//! The problem is
//!
//! ```text
//! minimise    1/2 x' P x + q' x
//! subject to  lower <= A x <= upper
//! ```
//!
//! with `P` dense symmetric positive definite (`n x n`, given by its upper
//! triangle column by column) and `A` sparse with a sparsity pattern fixed at
//! set-up. A backend is built once from a [`QpProblem`]; each sample then
//! overwrites `P`, `q` and the bounds in place and solves ([`QpSolver::solve`]),
//! without building a new problem. Another solver is added by implementing
//! [`QpSolver`] and handing it to [`super::MpcPlanner::with_solver`].
//!
//! ```
//! use armkit::mpc::qp::{ClarabelQp, CscMatrix, QpProblem, QpSolver, QpStatus};
//! // min 1/2 (x0^2 + x1^2) - x0 - x1  s.t.  x0 + x1 <= 1
//! let a = CscMatrix::from_dense(1, 2, &[1.0, 1.0]);
//! let problem = QpProblem::new(2, vec![1.0, 0.0, 1.0], vec![-1.0, -1.0], a, vec![-10.0], vec![1.0]).unwrap();
//! let mut solver = ClarabelQp::new(&problem).unwrap();
//! let mut x = [0.0; 2];
//! let outcome = solver.solve(&problem.hessian_upper, &problem.gradient, &problem.lower, &problem.upper, &mut x);
//! assert_eq!(outcome.status, QpStatus::Solved);
//! assert!((x[0] - 0.5).abs() < 1e-6 && (x[1] - 0.5).abs() < 1e-6);
//! ```

use crate::error::{Error, Result};

/// A sparse matrix in compressed sparse column form (`rows x cols`), with
/// 0-based row indices sorted within each column. Entries stored here are
/// structural: they stay in the pattern even when their value is zero.
#[derive(Clone, Debug, PartialEq)]
pub struct CscMatrix {
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub cols: usize,
    /// `cols + 1` offsets into `row_indices` / `values`.
    pub col_ptr: Vec<usize>,
    /// Row index of each stored entry.
    pub row_indices: Vec<usize>,
    /// Value of each stored entry.
    pub values: Vec<f64>,
}

impl CscMatrix {
    /// From a dense row-major `rows x cols` slice, keeping the non-zero entries.
    pub fn from_dense(rows: usize, cols: usize, row_major: &[f64]) -> Self {
        let mut matrix = CscMatrix {
            rows,
            cols,
            col_ptr: vec![0; cols + 1],
            row_indices: Vec::new(),
            values: Vec::new(),
        };
        for c in 0..cols {
            for r in 0..rows {
                let v = row_major.get(r * cols + c).copied().unwrap_or(0.0);
                if v != 0.0 {
                    matrix.row_indices.push(r);
                    matrix.values.push(v);
                }
            }
            matrix.col_ptr[c + 1] = matrix.row_indices.len();
        }
        matrix
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// The matrix times `x` (`cols` values), written into `out` (`rows` values).
    pub fn multiply(&self, x: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        for (c, xc) in x.iter().enumerate().take(self.cols) {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                if let Some(o) = out.get_mut(self.row_indices[k]) {
                    *o += self.values[k] * xc;
                }
            }
        }
    }

    fn check(&self) -> Result<()> {
        let bad = |reason: String| Error::invalid_argument("constraints", reason);
        if self.col_ptr.len() != self.cols + 1 || self.col_ptr.first() != Some(&0) {
            return Err(bad(format!(
                "column pointer must have {} entries starting at 0",
                self.cols + 1
            )));
        }
        if self.col_ptr.windows(2).any(|w| w[0] > w[1])
            || self.col_ptr[self.cols] != self.values.len()
            || self.row_indices.len() != self.values.len()
        {
            return Err(bad("column pointers do not match the stored entries".into()));
        }
        for c in 0..self.cols {
            let rows = &self.row_indices[self.col_ptr[c]..self.col_ptr[c + 1]];
            if rows.windows(2).any(|w| w[0] >= w[1]) || rows.iter().any(|&r| r >= self.rows) {
                return Err(bad(format!(
                    "column {c}: row indices must be increasing and below {}",
                    self.rows
                )));
            }
        }
        crate::error::check_finite("constraints.values", &self.values)
    }
}

/// Number of entries in the upper triangle (diagonal included) of an `n x n`
/// matrix: the length of [`QpProblem::hessian_upper`].
pub fn upper_triangle_len(n: usize) -> usize {
    n * (n + 1) / 2
}

/// Index of entry `(row, col)`, `row <= col`, in the column-major upper
/// triangle: `col (col + 1) / 2 + row`.
#[inline]
pub fn upper_index(row: usize, col: usize) -> usize {
    col * (col + 1) / 2 + row
}

/// A QP `min 1/2 x'Px + q'x  s.t.  lower <= A x <= upper` as the backends
/// are set up from it.
#[derive(Clone, Debug)]
pub struct QpProblem {
    /// Number of variables `n`.
    pub variables: usize,
    /// Upper triangle of `P`, column-major (see [`upper_index`]): every entry
    /// is structural, so any symmetric `P` can be written later.
    pub hessian_upper: Vec<f64>,
    /// `q`, `n` values.
    pub gradient: Vec<f64>,
    /// `A` (`m x n`), pattern fixed from here on.
    pub constraints: CscMatrix,
    /// Lower bounds, `m` finite values.
    pub lower: Vec<f64>,
    /// Upper bounds, `m` finite values, `>= lower`.
    pub upper: Vec<f64>,
}

impl QpProblem {
    /// Checks the sizes, finiteness and `lower <= upper`.
    pub fn new(
        variables: usize,
        hessian_upper: Vec<f64>,
        gradient: Vec<f64>,
        constraints: CscMatrix,
        lower: Vec<f64>,
        upper: Vec<f64>,
    ) -> Result<Self> {
        use crate::error::check_finite_vector;
        if variables == 0 {
            return Err(Error::invalid_argument("variables", "must be at least 1"));
        }
        check_finite_vector(
            "hessian_upper",
            &hessian_upper,
            upper_triangle_len(variables),
        )?;
        check_finite_vector("gradient", &gradient, variables)?;
        if constraints.cols != variables {
            return Err(Error::DimensionMismatch {
                what: "constraints (columns)",
                expected: variables,
                got: constraints.cols,
            });
        }
        constraints.check()?;
        check_finite_vector("lower", &lower, constraints.rows)?;
        check_finite_vector("upper", &upper, constraints.rows)?;
        if let Some(i) = (0..lower.len()).find(|&i| lower[i] > upper[i]) {
            return Err(Error::invalid_argument(
                "lower",
                format!(
                    "row {i}: lower bound {} exceeds upper bound {}",
                    lower[i], upper[i]
                ),
            ));
        }
        Ok(QpProblem {
            variables,
            hessian_upper,
            gradient,
            constraints,
            lower,
            upper,
        })
    }

    /// Number of constraint rows `m`.
    pub fn constraint_rows(&self) -> usize {
        self.constraints.rows
    }
}

/// How a QP solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QpStatus {
    /// Solved to the backend's tolerances.
    Solved,
    /// Solved to reduced accuracy (Clarabel `AlmostSolved`, OSQP
    /// `SolvedInaccurate`): the solution is usable but may cross a bound by
    /// more than round-off.
    SolvedInaccurate,
    /// The constraints admit no solution (primal infeasibility certificate).
    Infeasible,
    /// Iteration or time limit reached without a solution.
    IterationLimit,
    /// The backend stopped on a numerical problem (or reported unboundedness,
    /// which a positive definite `P` rules out).
    NumericalFailure,
}

impl QpStatus {
    /// Lower-case name: `solved`, `solved-inaccurate`, `infeasible`,
    /// `iteration-limit`, `numerical-failure`.
    pub fn as_str(self) -> &'static str {
        match self {
            QpStatus::Solved => "solved",
            QpStatus::SolvedInaccurate => "solved-inaccurate",
            QpStatus::Infeasible => "infeasible",
            QpStatus::IterationLimit => "iteration-limit",
            QpStatus::NumericalFailure => "numerical-failure",
        }
    }

    /// True for [`QpStatus::Solved`] and [`QpStatus::SolvedInaccurate`].
    pub fn has_solution(self) -> bool {
        matches!(self, QpStatus::Solved | QpStatus::SolvedInaccurate)
    }
}

impl std::fmt::Display for QpStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Result of one [`QpSolver::solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QpOutcome {
    /// How it ended.
    pub status: QpStatus,
    /// Iterations the backend took.
    pub iterations: u32,
}

/// A QP backend, built once and updated in place every sample.
pub trait QpSolver: Send {
    /// Short name for reports, e.g. `"clarabel"`.
    fn name(&self) -> &'static str;

    /// Overwrites `P` (its upper triangle, same layout as
    /// [`QpProblem::hessian_upper`]), `q` and the bounds of the problem the
    /// backend was built from, solves, and writes the solution into `x`
    /// (`n` values; left unchanged unless the status has a solution).
    ///
    /// The slices must have the set-up sizes (the planner guarantees it).
    fn solve(
        &mut self,
        hessian_upper: &[f64],
        gradient: &[f64],
        lower: &[f64],
        upper: &[f64],
        x: &mut [f64],
    ) -> QpOutcome;

    /// How many solves so far were answered by a fallback backend (0 for a
    /// backend without one).
    fn fallback_solves(&self) -> usize {
        0
    }
}

/// Which QP backend the planner builds.
///
/// Measured on this problem (gantry9, `N = 10`; `benches/mpc.rs`): the
/// dense active-set solver ([`super::active_set`]) is the fastest at the
/// planner's sizes and needs no C code, so it is the default, with Clarabel
/// as its fallback; Clarabel alone is the reference; OSQP needs the `osqp`
/// feature (and cmake).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum QpSolverKind {
    /// The dense Goldfarb-Idnani active-set solver written for the planner
    /// ([`super::active_set::ActiveSetQp`]), exact up to round-off, with
    /// Clarabel as its fallback when it cannot solve a problem. The default.
    #[default]
    ActiveSet,
    /// Clarabel 0.11 (interior point, pure Rust): accurate to 1e-8, no warm
    /// start; 10-17 iterations per MPC step.
    Clarabel,
    /// OSQP 0.6 (ADMM + polishing, C library, warm-started from the previous
    /// step). Needs the crate feature `osqp` (and `cmake` to build its C code).
    Osqp,
}

impl QpSolverKind {
    /// Every backend this build offers.
    pub fn available() -> &'static [QpSolverKind] {
        #[cfg(feature = "osqp")]
        {
            &[
                QpSolverKind::ActiveSet,
                QpSolverKind::Clarabel,
                QpSolverKind::Osqp,
            ]
        }
        #[cfg(not(feature = "osqp"))]
        {
            &[QpSolverKind::ActiveSet, QpSolverKind::Clarabel]
        }
    }

    /// Lower-case name (`active-set`, `clarabel`, `osqp`).
    pub fn name(self) -> &'static str {
        match self {
            QpSolverKind::ActiveSet => "active-set",
            QpSolverKind::Clarabel => "clarabel",
            QpSolverKind::Osqp => "osqp",
        }
    }

    /// Same as [`QpSolverKind::name`].
    pub fn as_str(self) -> &'static str {
        self.name()
    }

    /// Builds the backend for `problem`. Errors when the backend was not
    /// compiled in or rejects the problem.
    pub fn build(self, problem: &QpProblem) -> Result<Box<dyn QpSolver>> {
        match self {
            QpSolverKind::ActiveSet => Ok(Box::new(super::active_set::ActiveSetQp::with_fallback(
                problem,
            )?)),
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

impl std::fmt::Display for QpSolverKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

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

fn numerical(context: &str, reason: String) -> Error {
    Error::Numerical {
        context: context.into(),
        reason,
    }
}

/// Column-major pattern of a dense upper triangle: `(col_ptr, row_indices)`.
fn upper_triangle_pattern(n: usize) -> (Vec<usize>, Vec<usize>) {
    let mut colptr = Vec::with_capacity(n + 1);
    let mut rowval = Vec::with_capacity(upper_triangle_len(n));
    colptr.push(0);
    for c in 0..n {
        rowval.extend(0..=c);
        colptr.push(rowval.len());
    }
    (colptr, rowval)
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

/// The OSQP backend (OSQP 0.6.3 through the `osqp` crate; feature `osqp`).
///
/// Tolerances 1e-7 absolute and relative, solution polishing on (it turns
/// ADMM's 1e-7 into an active-set accurate answer), warm start from the
/// previous sample's primal and dual solution. OSQP's own `osqp 1.x` crate
/// could not be used: its build script downloads QDLDL from GitHub, which
/// this build environment cannot reach; 0.6 ships all its C sources.
#[cfg(feature = "osqp")]
pub struct OsqpQp {
    problem: osqp::Problem,
    p_colptr: Vec<usize>,
    p_rowval: Vec<usize>,
    variables: usize,
}

#[cfg(feature = "osqp")]
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

#[cfg(feature = "osqp")]
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
