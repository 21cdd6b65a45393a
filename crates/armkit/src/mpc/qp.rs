//! The small quadratic-programming interface the MPC planner solves every
//! sample: the problem, the outcome and the [`QpSolver`] trait its backends
//! implement (the dense active-set solver of [`super::active_set`],
//! [`super::ClarabelQp`], and `OsqpQp` behind the `osqp` feature).
//! This file knows no backend; [`QpSolverKind::build`] (in `solver.rs`)
//! builds the one a [`QpSolverKind`] names.
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
//! use armkit::mpc::qp::{CscMatrix, QpProblem, QpSolver, QpStatus};
//! use armkit::mpc::ClarabelQp;
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
}

impl std::fmt::Display for QpSolverKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// An [`Error::Numerical`] of a backend's `context`.
pub(super) fn numerical(context: &str, reason: String) -> Error {
    Error::Numerical {
        context: context.into(),
        reason,
    }
}

/// Column-major pattern of a dense upper triangle: `(col_ptr, row_indices)`.
pub(super) fn upper_triangle_pattern(n: usize) -> (Vec<usize>, Vec<usize>) {
    let mut colptr = Vec::with_capacity(n + 1);
    let mut rowval = Vec::with_capacity(upper_triangle_len(n));
    colptr.push(0);
    for c in 0..n {
        rowval.extend(0..=c);
        colptr.push(rowval.len());
    }
    (colptr, rowval)
}
