//! The dense active-set QP solver against Clarabel (the reference), on
//! random QPs of the MPC planner's shape, and its degenerate cases.
//!
//! The random QPs have the planner's structure: `n = M dof` increments, the
//! Hessian and gradient of eq 20 built by `Condensation` from a random
//! `Bt = T J` and random weights, the constraint matrix of eqs 17-19
//! (cumulative velocity rows, position rows at samples `1..M` and `N`), and
//! bounds around a random point with random widths, so that several
//! constraints are active. Both solvers must give the same minimiser (to
//! 1e-6) and the same active set. 10 000 QPs in release.

use crate::common;

use armkit::mpc::active_set::{ActiveSetQp, BoundSide};
use armkit::mpc::prediction::{increment_coefficient, weighted_gram, Condensation};
use armkit::mpc::qp::{upper_index, upper_triangle_len, CscMatrix, QpProblem, QpSolver, QpStatus};
use armkit::mpc::{ClarabelAccuracy, ClarabelQp};
use rand::Rng;

const HORIZON: usize = 10;
const SAMPLE_TIME: f64 = 0.05;

/// The planner's constraint matrix for `dof` joints, all limited (dense,
/// row-major): velocity rows `(l, j)` then position rows `(i, j)`.
fn mpc_constraints(dof: usize, m: usize) -> (usize, Vec<f64>) {
    let mut steps: Vec<usize> = (1..=m).collect();
    if HORIZON > m {
        steps.push(HORIZON);
    }
    let n = dof * m;
    let rows = m * dof + steps.len() * dof;
    let mut a = vec![0.0; rows * n];
    for l in 0..m {
        for j in 0..dof {
            for k in 0..=l {
                a[(l * dof + j) * n + k * dof + j] = 1.0;
            }
        }
    }
    for (s, &i) in steps.iter().enumerate() {
        for j in 0..dof {
            let row = m * dof + s * dof + j;
            for l in 0..m.min(i) {
                a[row * n + l * dof + j] = SAMPLE_TIME * increment_coefficient(i, l);
            }
        }
    }
    (rows, a)
}

struct Shape {
    dof: usize,
    m: usize,
    rows: usize,
    dense: Vec<f64>,
    condensation: Condensation,
    active_set: ActiveSetQp,
    clarabel: ClarabelQp,
}

impl Shape {
    fn new(dof: usize, m: usize) -> Self {
        let (rows, dense) = mpc_constraints(dof, m);
        let n = dof * m;
        let mut hessian = vec![0.0; upper_triangle_len(n)];
        for c in 0..n {
            hessian[upper_index(c, c)] = 1.0;
        }
        let problem = QpProblem::new(
            n,
            hessian,
            vec![0.0; n],
            CscMatrix::from_dense(rows, n, &dense),
            vec![-1.0; rows],
            vec![1.0; rows],
        )
        .unwrap();
        Shape {
            dof,
            m,
            rows,
            dense,
            condensation: Condensation::new(HORIZON, m).unwrap(),
            active_set: ActiveSetQp::new(&problem).unwrap(),
            clarabel: ClarabelQp::with_accuracy(&problem, ClarabelAccuracy::Reference).unwrap(),
        }
    }
}

/// A random instance of `shape`: `(P upper, q, lower, upper)`.
fn random_instance(shape: &Shape, rng: &mut impl Rng) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let (dof, n) = (shape.dof, shape.dof * shape.m);
    let bt: Vec<f64> = (0..6 * dof)
        .map(|_| SAMPLE_TIME * rng.gen_range(-1.5..1.5))
        .collect();
    let weights: [f64; 6] = if rng.r#gen() {
        [10.0, 10.0, 10.0, 0.0, 0.0, 0.0]
    } else {
        [10.0; 6]
    };
    let terminal = weights.map(|w| 20.0 * w);
    let mut gram = vec![0.0; dof * dof];
    let mut gram_terminal = vec![0.0; dof * dof];
    weighted_gram(&bt, &weights, &mut gram);
    weighted_gram(&bt, &terminal, &mut gram_terminal);
    let r: Vec<f64> = (0..dof)
        .map(|_| 10f64.powf(rng.gen_range(-1.0..1.0)))
        .collect();
    let w: Vec<f64> = r.iter().map(|x| 0.01 * x).collect();
    let mut hessian = vec![0.0; upper_triangle_len(n)];
    shape
        .condensation
        .fill_hessian(&gram, &gram_terminal, &r, &w, &mut hessian);
    let error: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
    let drift: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-0.05..0.05));
    let wv: Vec<f64> = w.iter().map(|x| x * rng.gen_range(-1.0..1.0)).collect();
    let mut gradient = vec![0.0; n];
    shape
        .condensation
        .fill_gradient(&bt, &error, &drift, &weights, &terminal, &wv, &mut gradient);
    // Bounds around a random point, some of them narrow: the unconstrained
    // minimiser crosses several.
    let x0: Vec<f64> = (0..n).map(|_| rng.gen_range(-0.2..0.2)).collect();
    let mut lower = vec![0.0; shape.rows];
    let mut upper = vec![0.0; shape.rows];
    for i in 0..shape.rows {
        let v: f64 = (0..n).map(|c| shape.dense[i * n + c] * x0[c]).sum();
        lower[i] = v - rng.gen_range(0.0..0.3);
        upper[i] = v + rng.gen_range(0.0..0.3);
    }
    (hessian, gradient, lower, upper)
}

/// Margin for a weakly active row.
const WEAK: f64 = 1e-5;

/// True when a row outside the working set is within [`WEAK`] of a bound
/// at `x`, or a working-set multiplier is below it.
fn weakly_active(shape: &Shape, x: &[f64], lower: &[f64], upper: &[f64]) -> bool {
    let n = x.len();
    let working: Vec<usize> = shape.active_set.active_set().map(|(i, _)| i).collect();
    if shape
        .active_set
        .active_multipliers()
        .iter()
        .any(|&u| u < WEAK)
    {
        return true;
    }
    (0..shape.rows).any(|i| {
        let v: f64 = (0..n).map(|c| shape.dense[i * n + c] * x[c]).sum();
        !working.contains(&i) && (v - lower[i]).min(upper[i] - v) < WEAK
    })
}

/// Clarabel's active set: `(row, side)` where the side's multiplier is
/// larger than its slack in `x`.
fn clarabel_active_set(
    shape: &Shape,
    x: &[f64],
    lower: &[f64],
    upper: &[f64],
) -> Vec<(usize, BoundSide)> {
    let n = x.len();
    let (z_lower, z_upper) = shape.clarabel.bound_multipliers();
    assert_eq!(z_lower.len(), shape.rows);
    let mut rows = Vec::new();
    for i in 0..shape.rows {
        let v: f64 = (0..n).map(|c| shape.dense[i * n + c] * x[c]).sum();
        if z_lower[i] > v - lower[i] {
            rows.push((i, BoundSide::Lower));
        } else if z_upper[i] > upper[i] - v {
            rows.push((i, BoundSide::Upper));
        }
    }
    rows
}

/// The equality-constrained QP with the rows of `active` at their bounds,
/// solved exactly (KKT system, LU): `(x, multipliers)`, a multiplier >= 0
/// meaning the constraint pushes the right way.
fn polish(
    shape: &Shape,
    hessian: &[f64],
    gradient: &[f64],
    lower: &[f64],
    upper: &[f64],
    active: &[(usize, BoundSide)],
) -> (Vec<f64>, Vec<f64>) {
    use armkit::math::{DMatrix, DVector};
    let n = gradient.len();
    let k = active.len();
    let mut kkt = DMatrix::zeros(n + k, n + k);
    let mut rhs = DVector::zeros(n + k);
    for r in 0..n {
        for c in 0..n {
            kkt[(r, c)] = hessian[upper_index(r.min(c), r.max(c))];
        }
        rhs[r] = -gradient[r];
    }
    for (e, &(i, side)) in active.iter().enumerate() {
        let sign = match side {
            BoundSide::Lower => 1.0,
            BoundSide::Upper => -1.0,
        };
        for c in 0..n {
            let a = sign * shape.dense[i * n + c];
            kkt[(n + e, c)] = a;
            kkt[(c, n + e)] = -a;
        }
        rhs[n + e] = match side {
            BoundSide::Lower => lower[i],
            BoundSide::Upper => -upper[i],
        };
    }
    let solution = kkt
        .lu()
        .solve(&rhs)
        .expect("KKT system of an independent active set");
    (
        solution.rows(0, n).iter().copied().collect(),
        solution.rows(n, k).iter().copied().collect(),
    )
}

/// `x' P x` for `P` given by its upper triangle.
fn quadratic(hessian: &[f64], x: &[f64]) -> f64 {
    let n = x.len();
    (0..n)
        .map(|r| {
            x[r] * (0..n)
                .map(|c| hessian[upper_index(r.min(c), r.max(c))] * x[c])
                .sum::<f64>()
        })
        .sum()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Largest violation of the KKT conditions at `x` with the active-set
/// solver's working set and multipliers: stationarity `P x + q = sum u n`,
/// feasibility, `u >= 0`.
fn kkt_residual(
    shape: &Shape,
    hessian: &[f64],
    gradient: &[f64],
    lower: &[f64],
    upper: &[f64],
    x: &[f64],
) -> f64 {
    let n = x.len();
    let mut residual: Vec<f64> = (0..n)
        .map(|r| {
            gradient[r]
                + (0..n)
                    .map(|c| hessian[upper_index(r.min(c), r.max(c))] * x[c])
                    .sum::<f64>()
        })
        .collect();
    let multipliers = shape.active_set.active_multipliers();
    for ((i, side), &u) in shape.active_set.active_set().zip(multipliers) {
        let sign = match side {
            BoundSide::Lower => 1.0,
            BoundSide::Upper => -1.0,
        };
        for (r, a) in residual.iter_mut().zip(&shape.dense[i * n..(i + 1) * n]) {
            *r -= u * sign * a;
        }
    }
    let mut worst = residual.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for i in 0..shape.rows {
        let v: f64 = (0..n).map(|c| shape.dense[i * n + c] * x[c]).sum();
        worst = worst.max(lower[i] - v).max(v - upper[i]);
    }
    worst
}

#[test]
fn active_set_matches_clarabel_on_random_qps_of_the_mpc_shape() {
    let count = if cfg!(debug_assertions) { 300 } else { 10_000 };
    let mut rng = common::rng(1616);
    let mut shapes: Vec<Shape> = [(6, 1), (7, 3), (9, 5), (9, 1), (6, 5), (7, 2)]
        .iter()
        .map(|&(dof, m)| Shape::new(dof, m))
        .collect();
    let (mut total_active, mut largest_gap, mut largest_raw_gap) = (0usize, 0.0f64, 0.0f64);
    let mut degenerate = 0usize;
    for k in 0..count {
        let s = k % shapes.len();
        let shape = &mut shapes[s];
        let n = shape.dof * shape.m;
        let (hessian, gradient, lower, upper) = random_instance(shape, &mut rng);
        let mut x = vec![0.0; n];
        let mut reference = vec![0.0; n];
        let outcome = shape
            .active_set
            .solve(&hessian, &gradient, &lower, &upper, &mut x);
        let reference_outcome =
            shape
                .clarabel
                .solve(&hessian, &gradient, &lower, &upper, &mut reference);
        assert_eq!(outcome.status, QpStatus::Solved, "QP {k}");
        assert_eq!(
            reference_outcome.status,
            QpStatus::Solved,
            "QP {k} (clarabel)"
        );
        // The same minimiser. An interior-point answer is least accurate
        // along the Hessian's flat directions (M = 5 makes P ill-conditioned):
        // Clarabel's raw x is within a few 1e-6 of the exact one. So the
        // reference is Clarabel's answer polished: its active set (the rows
        // within 1e-6 of a bound) solved exactly as equalities (the KKT
        // system), which must have non-negative multipliers. Both the raw
        // and the polished differences are reported. A row is active in
        // Clarabel's answer on the side whose multiplier exceeds its slack.
        let at_bounds = clarabel_active_set(shape, &reference, &lower, &upper);
        // A weakly active row (at its bound by coincidence with a zero
        // multiplier, or in the working set with a multiplier near 0) makes
        // the active set ambiguous: such instances are counted and compared
        // by their minimiser only.
        if weakly_active(shape, &x, &lower, &upper) {
            degenerate += 1;
            let raw_gap = x
                .iter()
                .zip(&reference)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                raw_gap <= 1e-5,
                "QP {k}: raw solutions differ by {raw_gap:.3e}"
            );
            assert!(kkt_residual(shape, &hessian, &gradient, &lower, &upper, &x) <= 1e-9);
            continue;
        }
        let (polished, polished_multipliers) =
            polish(shape, &hessian, &gradient, &lower, &upper, &at_bounds);
        assert!(
            polished_multipliers.iter().all(|&u| u >= -1e-9),
            "QP {k}: Clarabel's active set is not optimal: {:?} vs mine {:?}, polished multipliers {:?}, mine {:?}",
            at_bounds,
            shape.active_set.active_set().collect::<Vec<_>>(),
            polished_multipliers,
            shape.active_set.active_multipliers()
        );
        let raw_gap = x
            .iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        let gap = x
            .iter()
            .zip(&polished)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        largest_raw_gap = largest_raw_gap.max(raw_gap);
        largest_gap = largest_gap.max(gap);
        assert!(gap <= 1e-6, "QP {k}: solutions differ by {gap:.3e}");
        assert!(
            raw_gap <= 1e-5,
            "QP {k}: raw solutions differ by {raw_gap:.3e}"
        );
        let objective = quadratic(&hessian, &x) / 2.0 + dot(&gradient, &x);
        let reference_objective =
            quadratic(&hessian, &reference) / 2.0 + dot(&gradient, &reference);
        assert!(
            (objective - reference_objective).abs() <= 1e-6 * (1.0 + objective.abs()),
            "QP {k}: objectives {objective} and {reference_objective}"
        );
        // Same active set: the working set (constraints with a positive
        // multiplier) is exactly Clarabel's.
        let mut working: Vec<(usize, BoundSide)> = shape.active_set.active_set().collect();
        working.sort_by_key(|&(i, side)| (i, side as u8));
        assert_eq!(working, at_bounds, "QP {k}: active sets differ");
        assert!(shape
            .active_set
            .active_multipliers()
            .iter()
            .all(|&u| u > 0.0));
        // And the active-set answer meets the KKT conditions on its own.
        assert!(
            kkt_residual(shape, &hessian, &gradient, &lower, &upper, &x) <= 1e-9,
            "QP {k}: KKT"
        );
        total_active += working.len();
    }
    println!(
        "{count} random QPs: same minimiser (largest difference {largest_gap:.2e} to Clarabel's polished \
         answer, {largest_raw_gap:.2e} to its raw one), same active set; {:.1} active constraints on average; \
         {degenerate} with a weakly active row (minimiser compared only)",
        total_active as f64 / (count - degenerate) as f64
    );
    assert!(
        degenerate * 200 <= count,
        "{degenerate} degenerate instances"
    );
    // The instances do exercise the constraints.
    assert!(total_active as f64 / count as f64 > 2.0);
}

/// `min 1/2 x'Px + q'x` over two variables with the rows of `a` (row-major).
fn small_problem(
    hessian_upper: Vec<f64>,
    gradient: Vec<f64>,
    a: &[f64],
    lower: Vec<f64>,
    upper: Vec<f64>,
) -> QpProblem {
    let rows = lower.len();
    QpProblem::new(
        2,
        hessian_upper,
        gradient,
        CscMatrix::from_dense(rows, 2, a),
        lower,
        upper,
    )
    .unwrap()
}

#[test]
fn infeasible_bounds_are_reported_as_infeasible() {
    // x0 >= 1 and x0 <= 0 on two rows: each row is fine, together they
    // admit nothing.
    let problem = small_problem(
        vec![1.0, 0.0, 1.0],
        vec![0.0, 0.0],
        &[1.0, 0.0, 1.0, 0.0],
        vec![1.0, -5.0],
        vec![5.0, 0.0],
    );
    let mut solver = ActiveSetQp::with_fallback(&problem).unwrap();
    let mut x = [7.0, 7.0];
    let outcome = solver.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Infeasible);
    assert!(!solver.last_used_fallback());
    assert_eq!(x, [7.0, 7.0], "x is left alone without a solution");
    // A row whose own bounds cross (lower > upper, given at solve time).
    let outcome = solver.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &[2.0, -5.0],
        &[1.0, 5.0],
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Infeasible);
    // Clarabel agrees on the first.
    let mut clarabel = ClarabelQp::new(&problem).unwrap();
    let outcome = clarabel.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Infeasible);
}

#[test]
fn duplicate_constraints_give_the_single_constraint_answer() {
    // min 1/2 |x|^2 - x0 - x1 s.t. x0 + x1 <= 1, twice: x = (0.5, 0.5), one
    // copy in the working set.
    let problem = small_problem(
        vec![1.0, 0.0, 1.0],
        vec![-1.0, -1.0],
        &[1.0, 1.0, 1.0, 1.0],
        vec![-10.0, -10.0],
        vec![1.0, 1.0],
    );
    let mut solver = ActiveSetQp::new(&problem).unwrap();
    let mut x = [0.0; 2];
    let outcome = solver.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Solved);
    assert!(
        (x[0] - 0.5).abs() < 1e-12 && (x[1] - 0.5).abs() < 1e-12,
        "{x:?}"
    );
    assert_eq!(solver.active_set().count(), 1);
    // The same row with a tighter bound second: the tighter one is the
    // active one, the looser one leaves the working set.
    let outcome = solver.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &[-10.0, -10.0],
        &[1.0, 0.5],
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Solved);
    assert!(
        (x[0] - 0.25).abs() < 1e-12 && (x[1] - 0.25).abs() < 1e-12,
        "{x:?}"
    );
    assert_eq!(
        solver.active_set().collect::<Vec<_>>(),
        vec![(1, BoundSide::Upper)]
    );
}

#[test]
fn a_zero_hessian_row_is_a_numerical_failure_that_the_fallback_solves() {
    // P = diag(1, 0): x1 has no curvature; q = (-1, 1) and x1 >= -2 bound
    // it: the minimiser is (1, -2).
    let problem = small_problem(
        vec![1.0, 0.0, 0.0],
        vec![-1.0, 1.0],
        &[1.0, 0.0, 0.0, 1.0],
        vec![-10.0, -2.0],
        vec![10.0, 10.0],
    );
    let mut plain = ActiveSetQp::new(&problem).unwrap();
    let mut x = [0.0; 2];
    let outcome = plain.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::NumericalFailure);
    assert_eq!(x, [0.0, 0.0]);
    let mut with_fallback = ActiveSetQp::with_fallback(&problem).unwrap();
    let outcome = with_fallback.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert!(outcome.status.has_solution(), "{:?}", outcome.status);
    assert!(with_fallback.last_used_fallback());
    assert_eq!(with_fallback.fallback_solves(), 1);
    assert!(
        (x[0] - 1.0).abs() < 1e-6 && (x[1] + 2.0).abs() < 1e-6,
        "{x:?}"
    );
}

#[test]
fn wrong_sizes_are_a_failure_not_a_panic() {
    let problem = small_problem(
        vec![1.0, 0.0, 1.0],
        vec![0.0, 0.0],
        &[1.0, 0.0],
        vec![-1.0],
        vec![1.0],
    );
    let mut solver = ActiveSetQp::new(&problem).unwrap();
    let mut x = [0.0; 3];
    let outcome = solver.solve(&[1.0, 0.0, 1.0], &[0.0, 0.0], &[-1.0], &[1.0], &mut x);
    assert_eq!(outcome.status, QpStatus::NumericalFailure);
}

/// How far `x` with the working set `working` and its `multipliers` is
/// from meeting the KKT conditions of `min 1/2 x'Px + q'x` subject to
/// `lower <= A x <= upper` (`A` dense, row-major), each judged on its own:
/// stationarity `P x + q = sum u s a` (`s = +1` on a lower side, `-1` on
/// an upper side), primal feasibility, every working-set row at its bound
/// (complementarity: rows outside it have a zero multiplier), `u >= 0`.
#[allow(clippy::too_many_arguments)]
fn kkt_violation(
    hessian: &[f64],
    gradient: &[f64],
    a: &[f64],
    lower: &[f64],
    upper: &[f64],
    x: &[f64],
    working: &[(usize, BoundSide)],
    multipliers: &[f64],
) -> [f64; 4] {
    let n = x.len();
    let row = |i: usize| dot(&a[i * n..(i + 1) * n], x);
    let mut residual: Vec<f64> = (0..n)
        .map(|r| {
            gradient[r]
                + (0..n)
                    .map(|c| hessian[upper_index(r.min(c), r.max(c))] * x[c])
                    .sum::<f64>()
        })
        .collect();
    let mut at_bound: f64 = 0.0;
    assert_eq!(working.len(), multipliers.len());
    for (&(i, side), &u) in working.iter().zip(multipliers) {
        let (sign, bound) = match side {
            BoundSide::Lower => (1.0, lower[i]),
            BoundSide::Upper => (-1.0, upper[i]),
        };
        for (r, ai) in residual.iter_mut().zip(&a[i * n..(i + 1) * n]) {
            *r -= u * sign * ai;
        }
        at_bound = at_bound.max((row(i) - bound).abs());
    }
    let stationarity = residual.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let infeasibility = (0..lower.len()).fold(0.0f64, |m, i| {
        m.max(lower[i] - row(i)).max(row(i) - upper[i])
    });
    let negative = multipliers.iter().fold(0.0f64, |m, &u| m.max(-u));
    [stationarity, infeasibility, at_bound, negative]
}

/// The active-set solver's own answer checked by the KKT conditions alone
/// (no reference solver): random dense QPs of 2 to 12 variables with up to
/// three times as many random rows, bounds around a random feasible point,
/// many of them active. The conditions are sufficient for the convex QP's
/// minimiser, so a wrong multiplier or a wrong working set fails here.
#[test]
fn active_set_multipliers_and_working_set_meet_the_kkt_conditions() {
    let mut rng = common::rng(37);
    let count = if cfg!(debug_assertions) { 300 } else { 3000 };
    let (mut active_total, mut dropped_possible) = (0usize, 0usize);
    for k in 0..count {
        let n = rng.gen_range(2..=12);
        let rows = rng.gen_range(1..=3 * n);
        let m: Vec<f64> = (0..n * n).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mut hessian = vec![0.0; upper_triangle_len(n)];
        for r in 0..n {
            for c in r..n {
                let v: f64 = (0..n).map(|k| m[r * n + k] * m[c * n + k]).sum();
                hessian[upper_index(r, c)] = v + if r == c { 0.1 } else { 0.0 };
            }
        }
        let gradient: Vec<f64> = (0..n).map(|_| rng.gen_range(-5.0..5.0)).collect();
        let a: Vec<f64> = (0..rows * n)
            .map(|_| {
                if rng.gen_bool(0.3) {
                    0.0
                } else {
                    rng.gen_range(-1.0..1.0)
                }
            })
            .collect();
        let x0: Vec<f64> = (0..n).map(|_| rng.gen_range(-0.5..0.5)).collect();
        let (mut lower, mut upper) = (vec![0.0; rows], vec![0.0; rows]);
        for i in 0..rows {
            let v = dot(&a[i * n..(i + 1) * n], &x0);
            lower[i] = v - rng.gen_range(0.0..0.5);
            upper[i] = v + rng.gen_range(0.0..0.5);
        }
        let problem = QpProblem::new(
            n,
            hessian.clone(),
            gradient.clone(),
            CscMatrix::from_dense(rows, n, &a),
            lower.clone(),
            upper.clone(),
        )
        .unwrap();
        let mut solver = ActiveSetQp::new(&problem).unwrap();
        let mut x = vec![0.0; n];
        let outcome = solver.solve(&hessian, &gradient, &lower, &upper, &mut x);
        assert_eq!(outcome.status, QpStatus::Solved, "QP {k}");
        let working: Vec<(usize, BoundSide)> = solver.active_set().collect();
        let multipliers = solver.active_multipliers().to_vec();
        let [stationarity, infeasibility, at_bound, negative] = kkt_violation(
            &hessian,
            &gradient,
            &a,
            &lower,
            &upper,
            &x,
            &working,
            &multipliers,
        );
        let scale = 1.0 + gradient.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            stationarity <= 1e-9 * scale,
            "QP {k}: stationarity {stationarity:e}, working set {working:?}, multipliers {multipliers:?}"
        );
        assert!(
            infeasibility <= 1e-9,
            "QP {k}: infeasible by {infeasibility:e}"
        );
        assert!(
            at_bound <= 1e-9,
            "QP {k}: a working-set row off its bound by {at_bound:e}"
        );
        assert!(negative == 0.0, "QP {k}: multipliers {multipliers:?}");
        // One side of a row at most, each row once.
        let mut seen: Vec<usize> = working.iter().map(|&(i, _)| i).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), working.len(), "QP {k}: {working:?}");
        active_total += working.len();
        if working.len() >= 2 {
            dropped_possible += 1;
        }
    }
    // The instances exercise the working set.
    assert!(active_total as f64 / count as f64 > 1.5, "{active_total}");
    assert!(dropped_possible * 4 > count, "{dropped_possible}");
}

/// The same KKT check on the MPC planner's QP shape (the instances the
/// comparison with Clarabel uses), without the reference solver.
#[test]
fn active_set_meets_the_kkt_conditions_on_the_mpc_shape() {
    let count = if cfg!(debug_assertions) { 200 } else { 2000 };
    let mut rng = common::rng(3737);
    let mut shapes: Vec<Shape> = [(6, 1), (7, 3), (9, 5), (6, 5), (7, 2)]
        .iter()
        .map(|&(dof, m)| Shape::new(dof, m))
        .collect();
    for k in 0..count {
        let s = k % shapes.len();
        let shape = &mut shapes[s];
        let (hessian, gradient, lower, upper) = random_instance(shape, &mut rng);
        let mut x = vec![0.0; shape.dof * shape.m];
        let outcome = shape
            .active_set
            .solve(&hessian, &gradient, &lower, &upper, &mut x);
        assert_eq!(outcome.status, QpStatus::Solved, "QP {k}");
        let working: Vec<(usize, BoundSide)> = shape.active_set.active_set().collect();
        let multipliers = shape.active_set.active_multipliers().to_vec();
        let [stationarity, infeasibility, at_bound, negative] = kkt_violation(
            &hessian,
            &gradient,
            &shape.dense,
            &lower,
            &upper,
            &x,
            &working,
            &multipliers,
        );
        assert!(
            stationarity <= 1e-9 && infeasibility <= 1e-9 && at_bound <= 1e-9 && negative == 0.0,
            "QP {k}: stationarity {stationarity:e}, infeasibility {infeasibility:e}, \
             off the bound {at_bound:e}, multipliers {multipliers:?}"
        );
    }
}

/// Known multipliers: `min 1/2 |x|^2 + x0 + 2 x1` with `x0 >= 0` and
/// `x1 >= -1` active (lower sides): `x = (0, -1)`, `u = (1, 1)`; with
/// `x0 + x1 <= 1` on `min 1/2 |x|^2 - 2 x0 - 2 x1` (upper side): `x = (0.5,
/// 0.5)`, `u = 1.5`.
#[test]
fn multipliers_of_small_problems_are_the_known_ones() {
    let problem = small_problem(
        vec![1.0, 0.0, 1.0],
        vec![1.0, 2.0],
        &[1.0, 0.0, 0.0, 1.0],
        vec![0.0, -1.0],
        vec![10.0, 10.0],
    );
    let mut solver = ActiveSetQp::new(&problem).unwrap();
    let mut x = [0.0; 2];
    let outcome = solver.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Solved);
    assert!(x[0].abs() < 1e-14 && (x[1] + 1.0).abs() < 1e-14, "{x:?}");
    let mut pairs: Vec<((usize, BoundSide), f64)> = solver
        .active_set()
        .zip(solver.active_multipliers().iter().copied())
        .collect();
    pairs.sort_by_key(|p| p.0 .0);
    assert_eq!(pairs.len(), 2, "{pairs:?}");
    for (((row, side), u), expected_row) in pairs.into_iter().zip([0, 1]) {
        assert_eq!((row, side), (expected_row, BoundSide::Lower));
        assert!((u - 1.0).abs() < 1e-14, "row {row}: {u}");
    }
    let problem = small_problem(
        vec![1.0, 0.0, 1.0],
        vec![-2.0, -2.0],
        &[1.0, 1.0],
        vec![-10.0],
        vec![1.0],
    );
    let mut solver = ActiveSetQp::new(&problem).unwrap();
    let outcome = solver.solve(
        &problem.hessian_upper,
        &problem.gradient,
        &problem.lower,
        &problem.upper,
        &mut x,
    );
    assert_eq!(outcome.status, QpStatus::Solved);
    assert!(
        (x[0] - 0.5).abs() < 1e-14 && (x[1] - 0.5).abs() < 1e-14,
        "{x:?}"
    );
    assert_eq!(
        solver.active_set().collect::<Vec<_>>(),
        vec![(0, BoundSide::Upper)]
    );
    assert!((solver.active_multipliers()[0] - 1.5).abs() < 1e-14);
}
