//! A small dense QP solver for the planner: the dual active-set method of
//! Goldfarb and Idnani (1983), written for problems of the MPC's size (tens
//! of variables, up to a few hundred two-sided constraint rows).
//!
//! The method starts from the unconstrained minimiser `x = -P^-1 q` (which
//! is dual feasible) and adds the most violated constraint one at a time,
//! dropping a constraint whose multiplier would turn negative, until every
//! constraint holds: each step keeps the current point the optimum of the
//! constraints in the working set. It needs `P` positive definite (the
//! planner's `P` has the increment weights `R > 0` on its diagonal); a `P`
//! that is not (a zero row, say) is reported as
//! [`QpStatus::NumericalFailure`], and [`ActiveSetQp`] then falls back to
//! Clarabel when built with [`ActiveSetQp::with_fallback`].
//!
//! Factorisations kept: `P = L L'` (Cholesky), `J = L^-T Q` and the upper
//! triangular `R` of `J' N = [R; 0]`, `N` the normals of the working set;
//! adding or dropping a constraint updates them with Givens rotations
//! (`O(n^2)`), so a solve with `k` changes of the working set costs
//! `O(n^3 / 2 + k n^2)`. Every buffer is sized at set-up: a solve allocates
//! nothing.
//!
//! ```
//! use armkit::mpc::active_set::ActiveSetQp;
//! use armkit::mpc::qp::{CscMatrix, QpProblem, QpSolver, QpStatus};
//! // min 1/2 (x0^2 + x1^2) - x0 - x1  s.t.  x0 + x1 <= 1
//! let a = CscMatrix::from_dense(1, 2, &[1.0, 1.0]);
//! let problem = QpProblem::new(2, vec![1.0, 0.0, 1.0], vec![-1.0, -1.0], a, vec![-10.0], vec![1.0]).unwrap();
//! let mut solver = ActiveSetQp::new(&problem).unwrap();
//! let mut x = [0.0; 2];
//! let outcome = solver.solve(&problem.hessian_upper, &problem.gradient, &problem.lower, &problem.upper, &mut x);
//! assert_eq!(outcome.status, QpStatus::Solved);
//! assert!((x[0] - 0.5).abs() < 1e-12 && (x[1] - 0.5).abs() < 1e-12);
//! assert_eq!(solver.active_set().collect::<Vec<_>>(), vec![(0, armkit::mpc::active_set::BoundSide::Upper)]);
//! ```

use super::clarabel_qp::ClarabelQp;
use super::qp::{upper_index, QpOutcome, QpProblem, QpSolver, QpStatus};
use crate::error::Result;

/// Which side of a two-sided row `lower <= a'x <= upper` is active.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoundSide {
    /// `a'x = lower`.
    Lower,
    /// `a'x = upper`.
    Upper,
}

impl BoundSide {
    /// `lower` or `upper`.
    pub fn as_str(self) -> &'static str {
        match self {
            BoundSide::Lower => "lower",
            BoundSide::Upper => "upper",
        }
    }
}

impl std::fmt::Display for BoundSide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A constraint is taken as violated when `a'x` is beyond its bound by more
/// than this times `1 + |bound|`.
pub const FEASIBILITY_TOLERANCE: f64 = 1e-10;

/// The Goldfarb-Idnani dual active-set backend, optionally with Clarabel as
/// the fallback for the problems it cannot solve (see the module doc).
pub struct ActiveSetQp {
    n: usize,
    m: usize,
    /// Constraint rows, compressed by row: `row_ptr` (m + 1), `cols`, `vals`.
    row_ptr: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
    /// Cholesky factor `L` (n x n, column-major, lower triangle used).
    chol: Vec<f64>,
    /// `J` (n x n, column-major).
    j: Vec<f64>,
    /// `R` (n x n, column-major, upper triangle used).
    r: Vec<f64>,
    /// Working set: constraint `k` (row `k mod m`, `k < m` lower side).
    active: Vec<usize>,
    /// Multipliers of the working set (>= 0).
    multipliers: Vec<f64>,
    x: Vec<f64>,
    d: Vec<f64>,
    z: Vec<f64>,
    step: Vec<f64>,
    normal: Vec<f64>,
    /// Indices of the non-zero entries of `normal`.
    normal_support: Vec<usize>,
    row_values: Vec<f64>,
    max_iterations: u32,
    fallback: Option<Box<ClarabelQp>>,
    last_used_fallback: bool,
    fallback_count: usize,
}

impl ActiveSetQp {
    /// Sets the solver up for `problem`'s sizes and constraint matrix (this
    /// allocates; solves do not). No fallback: a failure is reported as it is.
    pub fn new(problem: &QpProblem) -> Result<Self> {
        let n = problem.variables;
        let a = &problem.constraints;
        let m = a.rows;
        // CSC -> CSR.
        let mut counts = vec![0usize; m + 1];
        for &r in &a.row_indices {
            counts[r + 1] += 1;
        }
        for i in 0..m {
            counts[i + 1] += counts[i];
        }
        let row_ptr = counts.clone();
        let mut next = counts;
        let mut cols = vec![0; a.nnz()];
        let mut vals = vec![0.0; a.nnz()];
        for c in 0..a.cols {
            for k in a.col_ptr[c]..a.col_ptr[c + 1] {
                let r = a.row_indices[k];
                cols[next[r]] = c;
                vals[next[r]] = a.values[k];
                next[r] += 1;
            }
        }
        Ok(ActiveSetQp {
            n,
            m,
            row_ptr,
            cols,
            vals,
            chol: vec![0.0; n * n],
            j: vec![0.0; n * n],
            r: vec![0.0; n * n],
            active: Vec::with_capacity(n),
            multipliers: Vec::with_capacity(n),
            x: vec![0.0; n],
            d: vec![0.0; n],
            z: vec![0.0; n],
            step: vec![0.0; n],
            normal: vec![0.0; n],
            normal_support: Vec::with_capacity(n),
            row_values: vec![0.0; m],
            max_iterations: (4 * (n + 2 * m) + 20) as u32,
            fallback: None,
            last_used_fallback: false,
            fallback_count: 0,
        })
    }

    /// As [`ActiveSetQp::new`], with Clarabel built for the same problem and
    /// used whenever the active-set method does not end with a solution (a
    /// `P` that is not positive definite, an iteration limit, round-off
    /// trouble); an infeasibility it proves is reported without a fallback.
    pub fn with_fallback(problem: &QpProblem) -> Result<Self> {
        let mut solver = Self::new(problem)?;
        solver.fallback = Some(Box::new(ClarabelQp::new(problem)?));
        Ok(solver)
    }

    /// True when the last solve was answered by the Clarabel fallback.
    pub fn last_used_fallback(&self) -> bool {
        self.last_used_fallback
    }

    /// The working set of the last solve: `(row, side)` of every active
    /// constraint, in the order they were added.
    pub fn active_set(&self) -> impl Iterator<Item = (usize, BoundSide)> + '_ {
        self.active.iter().map(move |&k| {
            if k < self.m {
                (k, BoundSide::Lower)
            } else {
                (k - self.m, BoundSide::Upper)
            }
        })
    }

    /// The multipliers of [`ActiveSetQp::active_set`] (>= 0), same order.
    pub fn active_multipliers(&self) -> &[f64] {
        &self.multipliers
    }

    /// Writes the constraint normal of `k` (`+a_i` for a lower side, `-a_i`
    /// for an upper side) into `self.normal` and returns the bound it has
    /// to reach from above, `normal'x >= bound`.
    fn load_normal(&mut self, k: usize, lower: &[f64], upper: &[f64]) -> f64 {
        let (row, sign, bound) = if k < self.m {
            (k, 1.0, lower[k])
        } else {
            (k - self.m, -1.0, -upper[k - self.m])
        };
        self.normal.iter_mut().for_each(|v| *v = 0.0);
        self.normal_support.clear();
        for p in self.row_ptr[row]..self.row_ptr[row + 1] {
            let c = self.cols[p];
            if self.normal[c] == 0.0 {
                self.normal_support.push(c);
            }
            self.normal[c] += sign * self.vals[p];
        }
        bound
    }

    /// `P = L L'` and `J = L^-T`; false when `P` is not positive definite.
    fn factorise(&mut self, hessian_upper: &[f64]) -> bool {
        let n = self.n;
        let l = &mut self.chol;
        for c in 0..n {
            for r in c..n {
                // P[r][c] = P[c][r], stored in the upper triangle at (c, r).
                let mut v = hessian_upper[upper_index(c, r)];
                for k in 0..c {
                    v -= l[r + n * k] * l[c + n * k];
                }
                if r == c {
                    if v.is_nan() || v <= 1e-14 * (1.0 + hessian_upper[upper_index(c, c)].abs()) {
                        return false;
                    }
                    l[c + n * c] = v.sqrt();
                } else {
                    l[r + n * c] = v / l[c + n * c];
                }
            }
        }
        // J = L^-T: column c of J is row c of L^-1; solve L' j_c = e_c
        // column by column (J upper triangular).
        let j = &mut self.j;
        j.iter_mut().for_each(|v| *v = 0.0);
        for c in 0..n {
            // Solve L' y = e_c for y (upper triangular system), y[k] = 0 for k > c.
            for row in (0..=c).rev() {
                let mut v = if row == c { 1.0 } else { 0.0 };
                for k in row + 1..=c {
                    v -= l[k + n * row] * j[k + n * c];
                }
                j[row + n * c] = v / l[row + n * row];
            }
        }
        true
    }

    fn givens(a: f64, b: f64) -> (f64, f64, f64) {
        let h = a.hypot(b);
        if h == 0.0 {
            (1.0, 0.0, 0.0)
        } else {
            (a / h, b / h, h)
        }
    }

    /// Rotates columns `c0`, `c0 + 1` of `J`.
    fn rotate_j(&mut self, c0: usize, c: f64, s: f64) {
        let n = self.n;
        let (left, right) = self.j.split_at_mut(n * (c0 + 1));
        let a_col = &mut left[n * c0..];
        let b_col = &mut right[..n];
        for (a, b) in a_col.iter_mut().zip(b_col.iter_mut()) {
            let (va, vb) = (*a, *b);
            *a = c * va + s * vb;
            *b = -s * va + c * vb;
        }
    }

    /// Adds the constraint whose `d = J' normal` is in `self.d` to the
    /// working set. Returns false if it is linearly dependent on it.
    fn add_constraint(&mut self, k: usize, multiplier: f64) -> bool {
        let n = self.n;
        let q = self.active.len();
        for col in (q + 1..n).rev() {
            if self.d[col] == 0.0 {
                continue;
            }
            let (c, s, h) = Self::givens(self.d[col - 1], self.d[col]);
            self.d[col - 1] = h;
            self.d[col] = 0.0;
            self.rotate_j(col - 1, c, s);
        }
        let scale = self.d[..=q.min(n - 1)]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        if q >= n || self.d[q].abs() <= 1e-13 * scale.max(1e-300) {
            return false;
        }
        for row in 0..=q {
            self.r[row + n * q] = self.d[row];
        }
        self.active.push(k);
        self.multipliers.push(multiplier);
        true
    }

    /// Drops the working-set member at position `l`.
    fn drop_constraint(&mut self, l: usize) {
        let n = self.n;
        let q = self.active.len();
        self.active.remove(l);
        self.multipliers.remove(l);
        // Shift R's columns l+1..q left, then restore the triangle.
        for col in l..q - 1 {
            for row in 0..=col + 1 {
                self.r[row + n * col] = self.r[row + n * (col + 1)];
            }
        }
        for row in 0..n {
            self.r[row + n * (q - 1)] = 0.0;
        }
        for jdx in l..q - 1 {
            let (c, s, h) = Self::givens(self.r[jdx + n * jdx], self.r[jdx + 1 + n * jdx]);
            self.r[jdx + n * jdx] = h;
            self.r[jdx + 1 + n * jdx] = 0.0;
            for col in jdx + 1..q - 1 {
                let (a, b) = (self.r[jdx + n * col], self.r[jdx + 1 + n * col]);
                self.r[jdx + n * col] = c * a + s * b;
                self.r[jdx + 1 + n * col] = -s * a + c * b;
            }
            self.rotate_j(jdx, c, s);
        }
    }

    /// The Goldfarb-Idnani iteration; the solution is in `self.x`.
    fn solve_dual(
        &mut self,
        hessian_upper: &[f64],
        gradient: &[f64],
        lower: &[f64],
        upper: &[f64],
    ) -> QpOutcome {
        let n = self.n;
        let m = self.m;
        let fail = |status| QpOutcome {
            status,
            iterations: 0,
        };
        self.active.clear();
        self.multipliers.clear();
        if (0..m).any(|i| lower[i].is_nan() || upper[i].is_nan() || lower[i] > upper[i]) {
            return fail(QpStatus::Infeasible);
        }
        if !self.factorise(hessian_upper) {
            return fail(QpStatus::NumericalFailure);
        }
        // x = -J J' q.
        for c in 0..n {
            self.d[c] = (0..=c).map(|k| self.j[k + n * c] * gradient[k]).sum();
        }
        for row in 0..n {
            self.x[row] = -(row..n)
                .map(|c| self.j[row + n * c] * self.d[c])
                .sum::<f64>();
        }
        let mut iterations = 0u32;
        loop {
            // Step 1: the most violated constraint.
            for i in 0..m {
                self.row_values[i] = (self.row_ptr[i]..self.row_ptr[i + 1])
                    .map(|p| self.vals[p] * self.x[self.cols[p]])
                    .sum();
            }
            let mut worst = 0.0;
            let mut chosen = None;
            for i in 0..m {
                let v = self.row_values[i];
                let below = (v - lower[i]) / (1.0 + lower[i].abs());
                let above = (upper[i] - v) / (1.0 + upper[i].abs());
                if below < worst && below < -FEASIBILITY_TOLERANCE {
                    worst = below;
                    chosen = Some(i);
                }
                if above < worst && above < -FEASIBILITY_TOLERANCE {
                    worst = above;
                    chosen = Some(i + m);
                }
            }
            let Some(p) = chosen else {
                return QpOutcome {
                    status: QpStatus::Solved,
                    iterations,
                };
            };
            let bound = self.load_normal(p, lower, upper);
            let mut added_multiplier = 0.0;
            // Step 2: move towards p until it is satisfied.
            loop {
                iterations += 1;
                if iterations > self.max_iterations {
                    return QpOutcome {
                        status: QpStatus::IterationLimit,
                        iterations,
                    };
                }
                let q = self.active.len();
                for c in 0..n {
                    let column = &self.j[n * c..n * (c + 1)];
                    self.d[c] = self
                        .normal_support
                        .iter()
                        .map(|&k| column[k] * self.normal[k])
                        .sum();
                }
                // Primal direction z = J2 d2, dual direction r = R^-1 d1.
                self.z.iter_mut().for_each(|v| *v = 0.0);
                for c in q..n {
                    let dc = self.d[c];
                    if dc != 0.0 {
                        for row in 0..n {
                            self.z[row] += self.j[row + n * c] * dc;
                        }
                    }
                }
                for row in (0..q).rev() {
                    let mut v = self.d[row];
                    for c in row + 1..q {
                        v -= self.r[row + n * c] * self.step[c];
                    }
                    self.step[row] = v / self.r[row + n * row];
                }
                let mut partial = f64::INFINITY;
                let mut leaving = None;
                for l in 0..q {
                    if self.step[l] > 0.0 {
                        let ratio = self.multipliers[l] / self.step[l];
                        if ratio < partial {
                            partial = ratio;
                            leaving = Some(l);
                        }
                    }
                }
                let z_normal: f64 = self.z.iter().zip(&self.normal).map(|(a, b)| a * b).sum();
                let z_norm: f64 = self.z.iter().map(|v| v * v).sum::<f64>().sqrt();
                let normal_norm: f64 = self.normal.iter().map(|v| v * v).sum::<f64>().sqrt();
                let slack: f64 = self
                    .normal
                    .iter()
                    .zip(&self.x)
                    .map(|(a, b)| a * b)
                    .sum::<f64>()
                    - bound;
                let full = if z_norm <= 1e-12 * normal_norm || z_normal <= 0.0 {
                    f64::INFINITY
                } else {
                    (-slack / z_normal).max(0.0)
                };
                let t = partial.min(full);
                if !t.is_finite() {
                    return QpOutcome {
                        status: QpStatus::Infeasible,
                        iterations,
                    };
                }
                for l in 0..q {
                    self.multipliers[l] = (self.multipliers[l] - t * self.step[l]).max(0.0);
                }
                added_multiplier += t;
                if full.is_finite() {
                    for (xi, zi) in self.x.iter_mut().zip(&self.z) {
                        *xi += t * zi;
                    }
                }
                if t == full {
                    if !self.add_constraint(p, added_multiplier) {
                        return QpOutcome {
                            status: QpStatus::NumericalFailure,
                            iterations,
                        };
                    }
                    break;
                }
                if let Some(l) = leaving {
                    self.drop_constraint(l);
                }
            }
        }
    }
}

impl QpSolver for ActiveSetQp {
    fn name(&self) -> &'static str {
        "active-set"
    }

    fn fallback_solves(&self) -> usize {
        self.fallback_count
    }

    fn solve(
        &mut self,
        hessian_upper: &[f64],
        gradient: &[f64],
        lower: &[f64],
        upper: &[f64],
        x: &mut [f64],
    ) -> QpOutcome {
        self.last_used_fallback = false;
        let n = self.n;
        if hessian_upper.len() != n * (n + 1) / 2
            || gradient.len() != n
            || lower.len() != self.m
            || upper.len() != self.m
            || x.len() != n
        {
            return QpOutcome {
                status: QpStatus::NumericalFailure,
                iterations: 0,
            };
        }
        let outcome = self.solve_dual(hessian_upper, gradient, lower, upper);
        if outcome.status.has_solution() {
            if self.x.iter().all(|v| v.is_finite()) {
                x.copy_from_slice(&self.x);
                return outcome;
            }
        } else if outcome.status == QpStatus::Infeasible {
            return outcome;
        }
        match &mut self.fallback {
            Some(clarabel) => {
                self.last_used_fallback = true;
                self.fallback_count += 1;
                self.active.clear();
                self.multipliers.clear();
                let fallback = clarabel.solve(hessian_upper, gradient, lower, upper, x);
                QpOutcome {
                    status: fallback.status,
                    iterations: outcome.iterations + fallback.iterations,
                }
            }
            None => QpOutcome {
                status: if outcome.status.has_solution() {
                    QpStatus::NumericalFailure
                } else {
                    outcome.status
                },
                iterations: outcome.iterations,
            },
        }
    }
}
