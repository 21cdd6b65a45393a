//! Strict (lexicographic) joint priorities for the planner: a sequence of
//! QPs, one per priority level, each over its own level's variables with
//! the higher levels' optimum held fixed (seed 000, sec 4.4, read as a
//! strict priority: the rotary joints first, then the beam joints and the
//! rail only for what remains).
//!
//! Level `l` minimises the planner's whole cost over its own variables
//! `x_l`, with the levels above fixed at their optimum (equality
//! constraints `x_h = x_h*`) and the levels below at zero increments (they
//! have not been given anything yet). The equality constraints are
//! eliminated by substitution, which is exact: with `x_F` fixed,
//!
//! ```text
//! minimise    1/2 x_l' P_ll x_l + (q_l + P_lF x_F)' x_l
//! subject to  lower - A_F x_F <= A_l x_l <= upper - A_F x_F
//! ```
//!
//! over the rows of `A` that touch `x_l` (rows that touch no variable of the
//! level are left to the level that owns them). Each level's QP is solved
//! by the backend [`QpSolverKind`] names (the active-set solver by
//! default), built once at set-up, so a solve allocates nothing.
//!
//! ```
//! use armkit::mpc::lexicographic::LexicographicQp;
//! use armkit::mpc::qp::{CscMatrix, QpProblem, QpSolver, QpSolverKind, QpStatus};
//! // min 1/2 |x|^2 + 1/2 (x0 + x1 - 2)^2: the joint optimum shares the
//! // move (2/3 each); with x0 first, x0 takes what it can alone and x1
//! // only what remains.
//! let hessian = vec![2.0, 1.0, 2.0];
//! let gradient = vec![-2.0, -2.0];
//! let a = CscMatrix::from_dense(2, 2, &[1.0, 0.0, 0.0, 1.0]);
//! let problem = QpProblem::new(2, hessian.clone(), gradient.clone(), a, vec![-5.0; 2], vec![5.0; 2]).unwrap();
//! let mut qp = LexicographicQp::new(&problem, &[vec![0], vec![1]], QpSolverKind::ActiveSet).unwrap();
//! let mut x = [0.0; 2];
//! let outcome = qp.solve(&hessian, &gradient, &problem.lower, &problem.upper, &mut x);
//! assert_eq!(outcome.status, QpStatus::Solved);
//! // Level 1: x0 minimises with x1 = 0: 2 x0 - 2 = 0, x0 = 1.
//! // Level 2: x1 minimises with x0 = 1: 2 x1 + 1 - 2 = 0, x1 = 1/2.
//! assert!((x[0] - 1.0).abs() < 1e-12 && (x[1] - 0.5).abs() < 1e-12);
//! ```

use crate::error::{Error, Result};

use super::qp::{
    upper_index, upper_triangle_len, CscMatrix, QpOutcome, QpProblem, QpSolver, QpSolverKind,
    QpStatus,
};

/// One priority level: its variables, the rows that touch them, its backend
/// and its workspaces.
struct Level {
    variables: Vec<usize>,
    rows: Vec<usize>,
    solver: Box<dyn QpSolver>,
    hessian: Vec<f64>,
    gradient: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    x: Vec<f64>,
}

/// A [`QpSolver`] that solves the levels of a strict priority one after
/// another (see the module doc).
pub struct LexicographicQp {
    levels: Vec<Level>,
    constraints: CscMatrix,
    /// `A x` for the levels solved so far, one per constraint row.
    fixed_rows: Vec<f64>,
    kind: QpSolverKind,
}

impl LexicographicQp {
    /// Sets the levels up for `problem`: `levels[l]` lists the variables of
    /// level `l` (highest priority first); every variable in exactly one
    /// level. Each level's backend is `kind`'s, built for its sub-problem.
    ///
    /// Errors: a variable out of range, in two levels or in none; an empty
    /// level; a backend that rejects a sub-problem.
    pub fn new(problem: &QpProblem, levels: &[Vec<usize>], kind: QpSolverKind) -> Result<Self> {
        let n = problem.variables;
        let mut owner = vec![usize::MAX; n];
        for (l, variables) in levels.iter().enumerate() {
            if variables.is_empty() {
                return Err(Error::invalid_argument(
                    "priority levels",
                    format!("level {l} has no variable"),
                ));
            }
            for &v in variables {
                match owner.get(v) {
                    None => {
                        return Err(Error::invalid_argument(
                            "priority levels",
                            format!("variable {v} out of range (the QP has {n})"),
                        ))
                    }
                    Some(&o) if o != usize::MAX => {
                        return Err(Error::invalid_argument(
                            "priority levels",
                            format!("variable {v} is in levels {o} and {l}"),
                        ))
                    }
                    Some(_) => owner[v] = l,
                }
            }
        }
        if let Some(v) = owner.iter().position(|&o| o == usize::MAX) {
            return Err(Error::invalid_argument(
                "priority levels",
                format!("variable {v} is in no level"),
            ));
        }
        let a = &problem.constraints;
        let built = levels
            .iter()
            .map(|variables| {
                let (sub, rows) = sub_problem(problem, variables)?;
                Ok(Level {
                    solver: kind.build(&sub)?,
                    rows,
                    hessian: sub.hessian_upper.clone(),
                    gradient: sub.gradient.clone(),
                    lower: sub.lower.clone(),
                    upper: sub.upper.clone(),
                    x: vec![0.0; variables.len()],
                    variables: variables.clone(),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(LexicographicQp {
            levels: built,
            constraints: a.clone(),
            fixed_rows: vec![0.0; a.rows],
            kind,
        })
    }

    /// The backend each level is solved with.
    pub fn kind(&self) -> QpSolverKind {
        self.kind
    }

    /// Number of levels.
    pub fn levels(&self) -> usize {
        self.levels.len()
    }
}

/// The rows of `a` with an entry in one of `variables`, increasing.
fn touched_rows(a: &CscMatrix, variables: &[usize]) -> Vec<usize> {
    let mut rows: Vec<usize> = variables
        .iter()
        .flat_map(|&c| {
            a.row_indices[a.col_ptr[c]..a.col_ptr[c + 1]]
                .iter()
                .copied()
        })
        .collect();
    rows.sort_unstable();
    rows.dedup();
    rows
}

/// The level's QP at set-up (`problem`'s data restricted to `variables` and
/// the rows they touch; the data is rewritten every solve), and its rows.
fn sub_problem(problem: &QpProblem, variables: &[usize]) -> Result<(QpProblem, Vec<usize>)> {
    let a = &problem.constraints;
    let rows = touched_rows(a, variables);
    let mut dense = vec![0.0; rows.len() * variables.len()];
    for (c, &v) in variables.iter().enumerate() {
        for k in a.col_ptr[v]..a.col_ptr[v + 1] {
            if let Ok(r) = rows.binary_search(&a.row_indices[k]) {
                dense[r * variables.len() + c] = a.values[k];
            }
        }
    }
    let mut hessian = vec![0.0; upper_triangle_len(variables.len())];
    fill_hessian(&problem.hessian_upper, variables, &mut hessian);
    let sub = QpProblem::new(
        variables.len(),
        hessian,
        variables.iter().map(|&v| problem.gradient[v]).collect(),
        CscMatrix::from_dense(rows.len(), variables.len(), &dense),
        rows.iter().map(|&r| problem.lower[r]).collect(),
        rows.iter().map(|&r| problem.upper[r]).collect(),
    )?;
    Ok((sub, rows))
}

/// `P(i, k)` of a symmetric matrix stored as its upper triangle.
#[inline]
fn entry(hessian_upper: &[f64], i: usize, k: usize) -> f64 {
    hessian_upper[upper_index(i.min(k), i.max(k))]
}

/// `P_ll`, the level's block, as an upper triangle.
fn fill_hessian(hessian_upper: &[f64], variables: &[usize], out: &mut [f64]) {
    for (b, &vb) in variables.iter().enumerate() {
        for (a, &va) in variables.iter().enumerate().take(b + 1) {
            out[upper_index(a, b)] = entry(hessian_upper, va, vb);
        }
    }
}

impl QpSolver for LexicographicQp {
    fn name(&self) -> &'static str {
        match self.kind {
            QpSolverKind::ActiveSet => "active-set (strict priority)",
            QpSolverKind::Clarabel => "clarabel (strict priority)",
            QpSolverKind::Osqp => "osqp (strict priority)",
        }
    }

    fn fallback_solves(&self) -> usize {
        self.levels.iter().map(|l| l.solver.fallback_solves()).sum()
    }

    /// Solves the levels in order; `x` holds every level's optimum. On a
    /// level's failure `x` holds the levels solved so far (zero below) and
    /// the failing level's status is returned.
    fn solve(
        &mut self,
        hessian_upper: &[f64],
        gradient: &[f64],
        lower: &[f64],
        upper: &[f64],
        x: &mut [f64],
    ) -> QpOutcome {
        let n = self.constraints.cols;
        if hessian_upper.len() != upper_triangle_len(n)
            || gradient.len() != n
            || lower.len() != self.constraints.rows
            || upper.len() != self.constraints.rows
            || x.len() != n
        {
            return QpOutcome {
                status: QpStatus::NumericalFailure,
                iterations: 0,
            };
        }
        x.iter_mut().for_each(|v| *v = 0.0);
        let mut result = QpOutcome {
            status: QpStatus::Solved,
            iterations: 0,
        };
        for level in &mut self.levels {
            // The fixed levels' share of every row (this level's entries of
            // `x` are still zero).
            self.constraints.multiply(x, &mut self.fixed_rows);
            for (i, &r) in level.rows.iter().enumerate() {
                level.lower[i] = lower[r] - self.fixed_rows[r];
                level.upper[i] = upper[r] - self.fixed_rows[r];
            }
            for (i, &v) in level.variables.iter().enumerate() {
                level.gradient[i] = gradient[v]
                    + (0..n)
                        .map(|k| entry(hessian_upper, v, k) * x[k])
                        .sum::<f64>();
            }
            fill_hessian(hessian_upper, &level.variables, &mut level.hessian);
            let outcome = level.solver.solve(
                &level.hessian,
                &level.gradient,
                &level.lower,
                &level.upper,
                &mut level.x,
            );
            result.iterations += outcome.iterations;
            if !outcome.status.has_solution() {
                result.status = outcome.status;
                return result;
            }
            if outcome.status == QpStatus::SolvedInaccurate {
                result.status = QpStatus::SolvedInaccurate;
            }
            for (i, &v) in level.variables.iter().enumerate() {
                x[v] = level.x[i];
            }
        }
        result
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mpc::ClarabelQp;

    /// A random strictly convex QP with box rows and one coupling row.
    fn problem(seed: u64) -> QpProblem {
        let n = 5;
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let g: Vec<f64> = (0..n * n).map(|_| next()).collect();
        let mut hessian = vec![0.0; upper_triangle_len(n)];
        for b in 0..n {
            for a in 0..=b {
                let dot: f64 = (0..n).map(|k| g[k * n + a] * g[k * n + b]).sum();
                hessian[upper_index(a, b)] = dot + if a == b { 0.5 } else { 0.0 };
            }
        }
        let gradient: Vec<f64> = (0..n).map(|_| 3.0 * next()).collect();
        let mut dense = vec![0.0; (n + 1) * n];
        for i in 0..n {
            dense[i * n + i] = 1.0;
        }
        dense[n * n] = 1.0;
        dense[n * n + 3] = 1.0;
        let a = CscMatrix::from_dense(n + 1, n, &dense);
        let mut lower = vec![-0.4; n + 1];
        let mut upper = vec![0.4; n + 1];
        lower[n] = -0.3;
        upper[n] = 0.3;
        QpProblem::new(n, hessian, gradient, a, lower, upper).unwrap()
    }

    /// The same problem with the variables `fixed` held at `values` by
    /// equality rows (`lower = upper`), solved by Clarabel on the full
    /// problem: the definition the substitution must meet.
    fn clarabel_with_equalities(problem: &QpProblem, fixed: &[usize], values: &[f64]) -> Vec<f64> {
        let n = problem.variables;
        let m = problem.constraints.rows;
        let mut dense = vec![0.0; (m + fixed.len()) * n];
        let a = &problem.constraints;
        for c in 0..n {
            for k in a.col_ptr[c]..a.col_ptr[c + 1] {
                dense[a.row_indices[k] * n + c] = a.values[k];
            }
        }
        let mut lower = problem.lower.clone();
        let mut upper = problem.upper.clone();
        for (i, &v) in fixed.iter().enumerate() {
            dense[(m + i) * n + v] = 1.0;
            lower.push(values[v]);
            upper.push(values[v]);
        }
        let full = QpProblem::new(
            n,
            problem.hessian_upper.clone(),
            problem.gradient.clone(),
            CscMatrix::from_dense(m + fixed.len(), n, &dense),
            lower,
            upper,
        )
        .unwrap();
        let mut clarabel = ClarabelQp::new(&full).unwrap();
        let mut x = vec![0.0; n];
        let outcome = clarabel.solve(
            &full.hessian_upper,
            &full.gradient,
            &full.lower,
            &full.upper,
            &mut x,
        );
        assert!(outcome.status.has_solution(), "{outcome:?}");
        x
    }

    #[test]
    fn each_level_is_the_clarabel_optimum_with_the_levels_above_as_equalities() {
        let levels = [vec![1, 4], vec![0, 3], vec![2]];
        for seed in 0..20 {
            let p = problem(seed);
            let mut qp = LexicographicQp::new(&p, &levels, QpSolverKind::ActiveSet).unwrap();
            let mut x = vec![0.0; 5];
            let outcome = qp.solve(&p.hessian_upper, &p.gradient, &p.lower, &p.upper, &mut x);
            assert_eq!(outcome.status, QpStatus::Solved, "seed {seed}");
            // Level l's answer: Clarabel on the full problem with the
            // levels above fixed at x and the levels below fixed at 0.
            for l in 0..levels.len() {
                let mut reference = x.clone();
                for below in &levels[l + 1..] {
                    for &v in below {
                        reference[v] = 0.0;
                    }
                }
                let fixed: Vec<usize> = (0..5).filter(|v| !levels[l].contains(v)).collect();
                let clarabel = clarabel_with_equalities(&p, &fixed, &reference);
                for &v in &levels[l] {
                    assert!(
                        (clarabel[v] - x[v]).abs() < 1e-6,
                        "seed {seed}, level {l}, variable {v}: clarabel {} vs active set {}",
                        clarabel[v],
                        x[v]
                    );
                }
            }
            // And the whole sequence on Clarabel agrees.
            let mut on_clarabel =
                LexicographicQp::new(&p, &levels, QpSolverKind::Clarabel).unwrap();
            let mut y = vec![0.0; 5];
            on_clarabel.solve(&p.hessian_upper, &p.gradient, &p.lower, &p.upper, &mut y);
            for v in 0..5 {
                assert!((x[v] - y[v]).abs() < 1e-6, "seed {seed}, variable {v}");
            }
        }
    }

    #[test]
    fn one_level_is_the_plain_qp() {
        let p = problem(7);
        let mut strict =
            LexicographicQp::new(&p, &[vec![0, 1, 2, 3, 4]], QpSolverKind::ActiveSet).unwrap();
        let mut plain = QpSolverKind::ActiveSet.build(&p).unwrap();
        let (mut x, mut y) = (vec![0.0; 5], vec![0.0; 5]);
        strict.solve(&p.hessian_upper, &p.gradient, &p.lower, &p.upper, &mut x);
        plain.solve(&p.hessian_upper, &p.gradient, &p.lower, &p.upper, &mut y);
        assert_eq!(x, y);
    }

    #[test]
    fn bad_levels_are_refused_by_name() {
        let p = problem(1);
        for (levels, text) in [
            (vec![vec![0, 1], vec![2, 3]], "variable 4 is in no level"),
            (
                vec![vec![0, 1, 2], vec![2, 3, 4]],
                "variable 2 is in levels 0 and 1",
            ),
            (vec![vec![0, 1, 2, 3, 4, 9]], "variable 9 out of range"),
            (vec![vec![0, 1, 2, 3, 4], vec![]], "level 1 has no variable"),
        ] {
            let error = LexicographicQp::new(&p, &levels, QpSolverKind::ActiveSet)
                .err()
                .unwrap()
                .to_string();
            assert!(error.contains(text), "{error}");
        }
    }
}
