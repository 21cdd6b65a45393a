//! Unit tests of `mpc::constraints`: the matrix and its bounds at every
//! predicted sample against the plan simulated directly, and the rest.

use super::{
    constrained_steps, guard_position, CscMatrix, JointBounds, JointLimits, Model, MpcOptions,
};
use crate::model::{DhConvention, DhLink};

const T: f64 = 0.05;

/// A planar 2R arm: joint 0 within `[-1, 0.5]` rad at 2 rad/s, joint 1
/// within `[-2, 2]` rad without a speed limit.
fn arm() -> Model {
    let links = [
        DhLink::revolute(0.0, 0.4, 0.0)
            .with_limits(-1.0, 0.5)
            .with_velocity_limit(2.0),
        DhLink::revolute(0.0, 0.3, 0.0).with_limits(-2.0, 2.0),
    ];
    Model::from_dh("planar2", DhConvention::Standard, &links).unwrap()
}

fn options(horizon: usize, control_horizon: usize) -> MpcOptions {
    MpcOptions {
        horizon,
        control_horizon,
        sample_time: T,
        ..MpcOptions::default()
    }
}

/// The inputs `u(0..N)` and the joint positions at samples `1..=N` of the
/// plan `du` (eq 14 simulated directly: `u(k) = u(k-1) + du(k)` for
/// `k < M`, then held; `q(k+1) = q(k) + T u(k)`), one vector per sample.
fn simulate(
    q: &[f64],
    v_old: &[f64],
    du: &[f64],
    horizon: usize,
    control_horizon: usize,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let dof = q.len();
    let (mut position, mut u) = (q.to_vec(), v_old.to_vec());
    let (mut inputs, mut positions) = (Vec::new(), Vec::new());
    for k in 0..horizon {
        for j in 0..dof {
            if k < control_horizon {
                u[j] += du[k * dof + j];
            }
            position[j] += T * u[j];
        }
        inputs.push(u.clone());
        positions.push(position.clone());
    }
    (inputs, positions)
}

/// The joint positions at samples `1..=N` of the plan `du` ([`simulate`]).
fn predicted_positions(
    q: &[f64],
    v_old: &[f64],
    du: &[f64],
    horizon: usize,
    control_horizon: usize,
) -> Vec<Vec<f64>> {
    simulate(q, v_old, du, horizon, control_horizon).1
}

/// `A du` for the sparse `A`.
fn multiply(a: &CscMatrix, du: &[f64]) -> Vec<f64> {
    let mut value = vec![0.0; a.rows];
    for (c, &x) in du.iter().enumerate().take(a.cols) {
        for k in a.col_ptr[c]..a.col_ptr[c + 1] {
            value[a.row_indices[k]] += a.values[k] * x;
        }
    }
    value
}

/// Whether `du` meets every row of the QP's constraints at `q`, `v_old`.
fn rows_hold(
    bounds: &JointBounds,
    opts: &MpcOptions,
    q: &[f64],
    v_old: &[f64],
    du: &[f64],
) -> bool {
    let dof = q.len();
    let a = bounds.matrix(dof, opts.control_horizon, opts.sample_time);
    let mut lower = vec![0.0; a.rows];
    let mut upper = vec![0.0; a.rows];
    bounds.fill(q, v_old, opts, &mut lower, &mut upper);
    let value = multiply(&a, du);
    (0..a.rows).all(|r| value[r] >= lower[r] - 1e-12 && value[r] <= upper[r] + 1e-12)
}

/// The increments that give the joint velocities `u(0..N)` of joint
/// `joint` (the others keep `v_old`), or `None` where the sequence is
/// not held constant from `M - 1` on.
fn increments_for(
    velocities: &[f64],
    joint: usize,
    v_old: &[f64],
    control_horizon: usize,
) -> Option<Vec<f64>> {
    let dof = v_old.len();
    let held = velocities[control_horizon - 1];
    if velocities[control_horizon..].iter().any(|&u| u != held) {
        return None;
    }
    let mut du = vec![0.0; dof * control_horizon];
    let mut previous = v_old[joint];
    for (l, &u) in velocities[..control_horizon].iter().enumerate() {
        du[l * dof + joint] = u - previous;
        previous = u;
    }
    Some(du)
}

/// A plan whose joint 0 crosses its upper limit at one predicted sample
/// only, anywhere in the horizon (the limit binding mid-horizon), breaks
/// a constraint row; the same plan scaled to stay within the limit
/// meets them all. Every sample whose crossing a plan can isolate is
/// tried: `1..M-1` (a bump up and back), `M` when `M = N` (the last
/// input, held), and `N` when `N > M` (a slow drift from `M - 1` on).
#[test]
fn a_limit_crossed_at_any_single_sample_breaks_a_row() {
    let model = arm();
    let (upper, gap) = (0.5, 0.02);
    let v_old = [0.0, 0.1];
    let q = [upper - gap, 0.3];
    let mut tried = 0;
    for (n, m) in [(10, 10), (10, 5), (6, 1), (5, 4), (4, 4), (8, 2)] {
        let opts = options(n, m);
        let bounds = JointBounds::new(&model, None, n, m).unwrap();
        for s in 1..=n {
            for (scale, crosses) in [(1.01, true), (0.99, false)] {
                let h = scale * gap;
                let mut velocities = vec![0.0; n];
                if s < m {
                    // Up to the limit over sample s, back over s + 1
                    // (and on down, held, when s + 1 is the last input).
                    velocities[s - 1] = h / T;
                    let back = if s + 1 < m { s + 1..s + 1 } else { s..n };
                    velocities[s] = -h / T;
                    velocities[back].iter_mut().for_each(|u| *u = -h / T);
                } else if s == m && m == n {
                    velocities[s - 1] = h / T;
                } else if s == n {
                    let rate = h / ((n - m + 1) as f64 * T);
                    velocities[m - 1..].iter_mut().for_each(|u| *u = rate);
                } else {
                    continue;
                }
                let Some(du) = increments_for(&velocities, 0, &v_old, m) else {
                    continue;
                };
                let positions = predicted_positions(&q, &v_old, &du, n, m);
                let over: Vec<usize> = (1..=n).filter(|&i| positions[i - 1][0] > upper).collect();
                if crosses {
                    assert_eq!(over, vec![s], "N = {n}, M = {m}: {positions:?}");
                } else {
                    assert!(over.is_empty());
                }
                assert_eq!(
                    rows_hold(&bounds, &opts, &q, &v_old, &du),
                    !crosses,
                    "N = {n}, M = {m}: a plan reaching {:.4} rad at sample {s} only (limit {upper})",
                    positions[s - 1][0]
                );
                tried += 1;
            }
        }
    }
    // Each horizon pair's isolable samples, twice (crossing and not).
    assert_eq!(tried, 2 * (10 + 5 + 1 + 4 + 4 + 2));
}

/// The rows hold exactly when every predicted sample is within the
/// limits and every input within its speed limit: random plans near
/// the upper limit of joint 0, both horizons equal and not.
#[test]
fn the_rows_hold_exactly_when_every_sample_is_within_the_limits() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(37);
    let model = arm();
    let (mut feasible, mut infeasible, mut last_only) = (0, 0, 0);
    for (n, m) in [(10, 10), (10, 5), (6, 1), (5, 4), (4, 4)] {
        let opts = options(n, m);
        let bounds = JointBounds::new(&model, None, n, m).unwrap();
        for _ in 0..4000 {
            let q = [0.5 - rng.gen_range(0.0..0.05), rng.gen_range(-1.9..1.9)];
            let v_old = [rng.gen_range(-0.5..0.5), rng.gen_range(-0.5..0.5)];
            let du: Vec<f64> = (0..2 * m).map(|_| rng.gen_range(-0.3..0.3)).collect();
            let positions = predicted_positions(&q, &v_old, &du, n, m);
            let within_positions = positions
                .iter()
                .all(|p| p[0] >= -1.0 && p[0] <= 0.5 && p[1] >= -2.0 && p[1] <= 2.0);
            let mut u = v_old[0];
            let within_speed = (0..m).all(|l| {
                u += du[2 * l];
                u.abs() <= 2.0
            });
            let expected = within_positions && within_speed;
            if expected {
                feasible += 1;
            } else {
                infeasible += 1;
            }
            if within_speed
                && positions[..n - 1].iter().all(|p| p[0] <= 0.5)
                && positions[n - 1][0] > 0.5
            {
                last_only += 1;
            }
            assert_eq!(
                rows_hold(&bounds, &opts, &q, &v_old, &du),
                expected,
                "N = {n}, M = {m}, q {q:?}, v_old {v_old:?}, du {du:?}: {positions:?}"
            );
        }
    }
    // Both outcomes, and plans crossing at the last sample only, occur.
    assert!(
        feasible > 1000 && infeasible > 1000,
        "{feasible} {infeasible}"
    );
    assert!(last_only > 20, "{last_only}");
}

/// With two speed-limited joints (2 and 3 rad/s, positions far from
/// their limits), an input of either joint beyond its speed limit at any
/// single control sample `l < M`, of either sign, breaks a row, and the
/// same plan 1 % within the limit meets every row (eq 17: each joint's
/// velocity rows at every control sample, none sharing another's bounds).
#[test]
fn a_speed_limit_crossed_by_either_joint_at_any_input_breaks_a_row() {
    let model = arm();
    let limits = [
        JointLimits {
            velocity: Some(2.0),
            ..JointLimits::position(-10.0, 10.0)
        },
        JointLimits {
            velocity: Some(3.0),
            ..JointLimits::position(-10.0, 10.0)
        },
    ];
    let (q, v_old) = ([0.0, 0.0], [0.0, 0.0]);
    let mut tried = 0;
    for (n, m) in [(10, 10), (10, 5), (6, 1), (5, 4)] {
        let opts = options(n, m);
        let bounds = JointBounds::new(&model, Some(&limits), n, m).unwrap();
        assert_eq!(bounds.velocity_rows, vec![0, 1]);
        for (joint, limit) in limits.iter().enumerate() {
            let speed = limit.velocity.unwrap();
            for l in 0..m {
                for sign in [1.0, -1.0] {
                    for (scale, crosses) in [(1.01, true), (0.99, false)] {
                        let mut velocities = vec![0.0; n];
                        let end = if l + 1 == m { n } else { l + 1 };
                        velocities[l..end]
                            .iter_mut()
                            .for_each(|u| *u = sign * scale * speed);
                        let du = increments_for(&velocities, joint, &v_old, m).unwrap();
                        assert_eq!(
                            rows_hold(&bounds, &opts, &q, &v_old, &du),
                            !crosses,
                            "N = {n}, M = {m}: joint {joint} at {:.3} rad/s over input {l} only (limit {speed})",
                            sign * scale * speed
                        );
                        tried += 1;
                    }
                }
            }
        }
    }
    assert_eq!(tried, 2 * 2 * 2 * (10 + 5 + 1 + 4));
}

/// Four joints with asymmetric limits, each a different case: joint 0
/// within `[-0.4, 0.9]` rad at 1.5 rad/s; joint 1 below 0.7 rad only, at
/// 2.5 rad/s; joint 2 above -1.3 rad only, no speed limit; joint 3 free in
/// position at 0.8 rad/s. Velocity rows for joints 0, 1 and 3, position
/// rows for joints 0, 1 and 2.
fn mixed_limits() -> [JointLimits; 4] {
    [
        JointLimits {
            velocity: Some(1.5),
            ..JointLimits::position(-0.4, 0.9)
        },
        JointLimits {
            velocity: Some(2.5),
            ..JointLimits::position(f64::NEG_INFINITY, 0.7)
        },
        JointLimits::position(-1.3, f64::INFINITY),
        JointLimits {
            velocity: Some(0.8),
            ..JointLimits::UNLIMITED
        },
    ]
}

/// A planar 4R arm (its own limits are replaced by [`mixed_limits`]).
fn arm4() -> Model {
    let links = [
        DhLink::revolute(0.0, 0.4, 0.0),
        DhLink::revolute(0.0, 0.3, 0.0),
        DhLink::revolute(0.0, 0.2, 0.0),
        DhLink::revolute(0.0, 0.1, 0.0),
    ];
    Model::from_dh("planar4", DhConvention::Standard, &links).unwrap()
}

/// Horizon pairs `(N, M)`: equal, `N = M + 1`, `N > M` with `M` 1 to 5.
const HORIZONS: [(usize, usize); 6] = [(6, 6), (9, 3), (5, 1), (7, 2), (4, 3), (12, 5)];

/// `|actual - expected|` within `1e-10` relative to `expected` (or both
/// the same infinity).
fn assert_close(actual: f64, expected: f64, what: &str) {
    let ok = if expected.is_infinite() {
        actual == expected
    } else {
        (actual - expected).abs() <= 1e-10 * (1.0 + expected.abs())
    };
    assert!(ok, "{what}: {actual} instead of {expected}");
}

/// The dense rows of `a`, checking its compressed-column structure: a
/// pointer per column and one more, no entry stored twice, no stored zero
/// (the sparse backends' work grows with the stored entries).
fn dense(a: &CscMatrix) -> Vec<Vec<f64>> {
    assert_eq!(a.col_ptr.len(), a.cols + 1);
    assert_eq!(a.col_ptr[0], 0);
    assert_eq!(a.col_ptr[a.cols], a.values.len());
    assert_eq!(a.row_indices.len(), a.values.len());
    let mut out = vec![vec![0.0; a.cols]; a.rows];
    for (c, span) in a.col_ptr.windows(2).enumerate() {
        assert!(span[0] <= span[1]);
        for k in span[0]..span[1] {
            let r = a.row_indices[k];
            assert!(r < a.rows, "row {r} of {} in column {c}", a.rows);
            assert_ne!(a.values[k], 0.0, "a stored zero at row {r}, column {c}");
            assert_eq!(out[r][c], 0.0, "row {r} stored twice in column {c}");
            out[r][c] = a.values[k];
        }
    }
    out
}

/// The constrained samples are `1..=M` and `N` (once, when `N > M`).
#[test]
fn the_constrained_samples_are_every_control_sample_and_the_last() {
    let cases: [(usize, usize, &[usize]); 7] = [
        (6, 6, &[1, 2, 3, 4, 5, 6]),
        (9, 3, &[1, 2, 3, 9]),
        (5, 1, &[1, 5]),
        (4, 3, &[1, 2, 3, 4]),
        (1, 1, &[1]),
        (3, 2, &[1, 2, 3]),
        (12, 5, &[1, 2, 3, 4, 5, 12]),
    ];
    for (n, m, expected) in cases {
        assert_eq!(constrained_steps(n, m), expected, "N = {n}, M = {m}");
        let bounds = JointBounds::new(&arm4(), Some(&mixed_limits()), n, m).unwrap();
        assert_eq!(bounds.position_steps, expected, "N = {n}, M = {m}");
        assert_eq!(bounds.velocity_rows, vec![0, 1, 3]);
        assert_eq!(bounds.position_rows, vec![0, 1, 2]);
    }
}

/// Each column of the constraint matrix (increment `du(l)` of joint `j`)
/// holds, in the velocity row of each speed-limited joint at each control
/// sample `0..M`, the input that increment adds there, and in the position
/// row of each position-limited joint at each constrained sample, the
/// position it adds there: the plan `du = e_c` simulated from rest at
/// zero. Rows: `M` per speed-limited joint, one per constrained sample per
/// position-limited joint; columns `M dof`.
#[test]
fn each_column_of_the_matrix_is_its_increments_inputs_and_positions() {
    let model = arm4();
    let dof = 4;
    for (n, m) in HORIZONS {
        let bounds = JointBounds::new(&model, Some(&mixed_limits()), n, m).unwrap();
        let a = bounds.matrix(dof, m, T);
        let steps = &bounds.position_steps;
        assert_eq!(
            (a.rows, a.cols),
            (3 * m + 3 * steps.len(), dof * m),
            "N = {n}, M = {m}"
        );
        let a = dense(&a);
        for c in 0..dof * m {
            let mut du = vec![0.0; dof * m];
            du[c] = 1.0;
            let (inputs, positions) = simulate(&[0.0; 4], &[0.0; 4], &du, n, m);
            let mut expected = Vec::new();
            for input in &inputs[..m] {
                expected.extend([0, 1, 3].map(|j| input[j]));
            }
            for &i in steps {
                expected.extend([0, 1, 2].map(|j| positions[i - 1][j]));
            }
            assert_eq!(expected.len(), a.len());
            for (r, e) in expected.iter().enumerate() {
                assert_close(
                    a[r][c],
                    *e,
                    &format!("N = {n}, M = {m}, row {r}, column {c}"),
                );
            }
        }
    }
}

/// The bounds of every row, through what the rows mean: for random plans
/// from random states within the limits, each velocity row's slack to its
/// bounds is the input's slack to the joint's speed limit at that control
/// sample, and each position row's slack is the predicted position's slack
/// to the joint's limits at that constrained sample. An unbounded side is
/// bounded `i T min(vmax, 1000) + 1` from the joint's position at sample
/// `i`: beyond its reach (joint 1 below, at 2.5 rad/s; joint 2 above,
/// with no speed limit).
#[test]
fn every_rows_slack_is_the_predicted_inputs_or_positions_slack_to_its_limit() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(41);
    let model = arm4();
    let speed = [1.5, 2.5, f64::INFINITY, 0.8];
    for (n, m) in HORIZONS {
        let opts = options(n, m);
        let bounds = JointBounds::new(&model, Some(&mixed_limits()), n, m).unwrap();
        let a = bounds.matrix(4, m, T);
        let mut lower = vec![f64::NAN; a.rows];
        let mut upper = vec![f64::NAN; a.rows];
        for _ in 0..20 {
            let q = [
                rng.gen_range(-0.4..0.9),
                rng.gen_range(-3.0..0.7),
                rng.gen_range(-1.3..4.0),
                rng.gen_range(-5.0..5.0),
            ];
            let v_old = [
                rng.gen_range(-1.5..1.5),
                rng.gen_range(-2.5..2.5),
                rng.gen_range(-4.0..4.0),
                rng.gen_range(-0.8..0.8),
            ];
            let du: Vec<f64> = (0..4 * m).map(|_| rng.gen_range(-1.0..1.0)).collect();
            assert!(!bounds.fill(&q, &v_old, &opts, &mut lower, &mut upper));
            let value = multiply(&a, &du);
            let (inputs, positions) = simulate(&q, &v_old, &du, n, m);
            let mut row = 0;
            for (l, input) in inputs[..m].iter().enumerate() {
                for j in [0, 1, 3] {
                    let what = format!("N = {n}, M = {m}: speed of joint {j} at input {l}");
                    assert_close(value[row] - lower[row], input[j] + speed[j], &what);
                    assert_close(upper[row] - value[row], speed[j] - input[j], &what);
                    row += 1;
                }
            }
            for &i in &bounds.position_steps {
                let it = i as f64 * T;
                let limits = [
                    (-0.4, 0.9),
                    (q[1] - (it * 2.5 + 1.0), 0.7),
                    (-1.3, q[2] + (it * 1000.0 + 1.0)),
                ];
                for (j, (lo, hi)) in limits.into_iter().enumerate() {
                    let p = positions[i - 1][j];
                    let what = format!("N = {n}, M = {m}: position of joint {j} at sample {i}");
                    assert_close(value[row] - lower[row], p - lo, &what);
                    assert_close(upper[row] - value[row], hi - p, &what);
                    row += 1;
                }
            }
            assert_eq!(row, a.rows);
        }
    }
}

/// A joint outside its limits may not move further out and must come
/// back at `recovery_speed` of its speed limit: its bound on the side it
/// is past is relaxed, at each constrained sample `i`, to where it gets
/// returning at that speed, and never beyond the limit (the relaxed bound
/// meets the limit mid-horizon); its other side keeps its limit, and a
/// joint with no speed limit keeps its limits (it may return at once).
#[test]
fn a_joint_outside_its_limits_must_return_at_the_recovery_speed() {
    let limits = [
        JointLimits {
            velocity: Some(1.5),
            ..JointLimits::position(-0.4, 0.9)
        },
        JointLimits {
            velocity: Some(2.5),
            ..JointLimits::position(-0.6, 0.7)
        },
        JointLimits::position(-1.3, 2.0),
        JointLimits {
            velocity: Some(0.8),
            ..JointLimits::UNLIMITED
        },
    ];
    // Recovery at 0.4 of the speed limit: joint 0, 0.3 rad above, returns
    // 0.03 rad a sample (back at sample 10); joint 1, 0.35 rad below,
    // 0.05 rad a sample (back at sample 7); joint 2, 0.3 rad below, has no
    // speed limit.
    let q = [1.2, -0.95, -1.6, 0.0];
    let v_old = [0.1, -0.2, 0.3, 0.0];
    let (mut relaxed, mut at_limit) = (0, 0);
    for (n, m) in [(12, 12), (14, 4), (9, 9), (20, 12), (6, 1)] {
        let opts = MpcOptions {
            recovery_speed: 0.4,
            ..options(n, m)
        };
        let bounds = JointBounds::new(&arm4(), Some(&limits), n, m).unwrap();
        let a = bounds.matrix(4, m, T);
        let mut lower = vec![f64::NAN; a.rows];
        let mut upper = vec![f64::NAN; a.rows];
        assert!(bounds.fill(&q, &v_old, &opts, &mut lower, &mut upper));
        // With the inputs held (`du = 0`) each row is 0 and the position
        // is where the joint drifts.
        let drift = predicted_positions(&q, &v_old, &vec![0.0; 4 * m], n, m);
        let offset = 3 * m;
        for (s, &i) in bounds.position_steps.iter().enumerate() {
            let it = i as f64 * T;
            let expected = [
                (-0.4, (1.2 - it * 0.4 * 1.5).max(0.9)),
                ((-0.95 + it * 0.4 * 2.5).min(-0.6), 0.7),
                (-1.3, 2.0),
            ];
            if expected[0].1 > 0.9 {
                relaxed += 1;
            } else {
                at_limit += 1;
            }
            for (j, (lo, hi)) in expected.into_iter().enumerate() {
                let row = offset + 3 * s + j;
                let what = format!("N = {n}, M = {m}: joint {j} at sample {i}");
                assert_close(lower[row] + drift[i - 1][j], lo, &what);
                assert_close(upper[row] + drift[i - 1][j], hi, &what);
            }
        }
    }
    assert!(relaxed > 10 && at_limit > 5, "{relaxed} {at_limit}");
}

/// `fill` says whether a joint is outside its limits: past either limit,
/// by a nanometre, each joint alone; exactly at a limit is within.
#[test]
fn fill_reports_a_joint_past_either_limit_and_not_one_at_it() {
    let (n, m) = (5, 2);
    let opts = options(n, m);
    let bounds = JointBounds::new(&arm4(), Some(&mixed_limits()), n, m).unwrap();
    let rows = bounds.matrix(4, m, T).rows;
    let (mut lower, mut upper) = (vec![0.0; rows], vec![0.0; rows]);
    let v_old = [0.0; 4];
    let cases = [
        ([0.9, 0.7, -1.3, 0.0], false),
        ([-0.4, 0.7, -1.3, 0.0], false),
        ([0.2, -1e6, 1e6, 1e6], false),
        ([0.9 + 1e-9, 0.0, 0.0, 0.0], true),
        ([-0.4 - 1e-9, 0.0, 0.0, 0.0], true),
        ([0.0, 0.7 + 1e-9, 0.0, 0.0], true),
        ([0.0, 0.0, -1.3 - 1e-9, 0.0], true),
    ];
    for (q, outside) in cases {
        assert_eq!(
            bounds.fill(&q, &v_old, &opts, &mut lower, &mut upper),
            outside,
            "{q:?}"
        );
    }
}

/// The interval of inputs one sample may apply, with asymmetric limits:
/// the speed limit far from the position limits, cut by the distance to a
/// near limit over `T`; outside a limit, only a return or holding still,
/// still cut by the opposite limit over a long sample; no bound but the
/// distance for a joint with no speed limit. `applied` clamps the planned
/// input into it and never lands past a limit.
#[test]
fn the_step_interval_is_the_speed_limit_cut_by_the_distance_to_each_limit() {
    let bounds = JointBounds::new(&arm4(), Some(&mixed_limits()), 5, 2).unwrap();
    let inf = f64::INFINITY;
    let cases = [
        // (joint, position, sample time, interval)
        (0, 0.0, T, (-1.5, 1.5)),
        (0, 0.88, T, (-1.5, 0.4)),
        (0, -0.39, T, (-0.2, 1.5)),
        (0, 0.9, T, (-1.5, 0.0)),
        (0, -0.4, T, (0.0, 1.5)),
        (0, 1.2, T, (-1.5, 0.0)),
        (0, 1.2, 2.0, (-0.8, 0.0)),
        (0, -0.5, T, (0.0, 1.5)),
        (0, -0.5, 2.0, (0.0, 0.7)),
        (0, 0.2, 2.0, (-0.3, 0.35)),
        (1, 0.69, T, (-2.5, 0.2)),
        (1, -50.0, T, (-2.5, 2.5)),
        (1, 0.8, T, (-2.5, 0.0)),
        (2, 0.0, T, (-26.0, inf)),
        (2, -1.29, T, (-0.2, inf)),
        (2, -1.5, T, (0.0, inf)),
        (3, 7.0, T, (-0.8, 0.8)),
    ];
    for (j, qj, t, (lo, hi)) in cases {
        let (a, b) = bounds.step_interval(j, qj, t);
        let what = format!("joint {j} at {qj} rad, T = {t}");
        assert_close(a, lo, &what);
        assert_close(b, hi, &what);
    }
    let applied = [
        // (joint, position, planned, applied)
        (0, 0.0, 0.37, 0.37),
        (0, 0.0, -0.37, -0.37),
        (0, 0.0, 2.0, 1.5),
        (0, 0.0, -9.0, -1.5),
        (0, 0.88, 1.0, 0.4),
        (0, -0.39, -1.0, -0.2),
        (0, 1.2, 0.5, 0.0),
        (0, 1.2, -0.7, -0.7),
        (0, -0.5, -0.7, 0.0),
        (2, -1.29, -3.0, -0.2),
        (2, 0.0, 40.0, 40.0),
        (3, 7.0, -1.0, -0.8),
    ];
    for (j, qj, planned, expected) in applied {
        let u = bounds.applied(j, qj, planned, T);
        assert_close(
            u,
            expected,
            &format!("joint {j} at {qj} rad planned {planned}"),
        );
        let (lower, upper) = (bounds.lower[j], bounds.upper[j]);
        if (lower..=upper).contains(&qj) {
            assert!(
                (lower..=upper).contains(&(qj + T * u)),
                "joint {j}: {qj} + T {u}"
            );
        }
    }
}

/// The guard leaves an input alone unless it lands past a limit the joint
/// is within (a joint outside may move on: the interval handles it), and
/// otherwise shrinks it by the rounding error only: on a grid of
/// positions and sample times the input `(limit - q) / T` of the clamp
/// overshoots the limit in floating point many times, and the guarded
/// input never does, within 1e-12 of it; one landing on the limit exactly
/// is left as it is.
#[test]
fn the_guard_stops_the_clamps_rounding_overshoot_and_nothing_else() {
    let (lower, upper) = (-0.4, 0.9);
    let inside = [(0.1, 0.37), (0.1, -0.37), (0.9, 0.0), (-0.4, 0.0)];
    let outside = [(1.2, 1.0), (1.2, -3.0), (-0.5, -1.0), (-0.5, 3.0)];
    for (q, u) in inside.into_iter().chain(outside) {
        assert_eq!(guard_position(q, u, T, lower, upper), u, "q {q}, u {u}");
    }
    // An input past a limit by more than rounding is brought onto it.
    for (q, u, limit) in [(0.0, 40.0, upper), (0.3, -20.0, lower)] {
        let next = q + T * guard_position(q, u, T, lower, upper);
        assert!((lower..=upper).contains(&next) && (next - limit).abs() < 1e-12);
    }
    let (mut over_upper, mut under_lower, mut on_limit) = (0, 0, 0);
    for t in [0.05, 0.01, 0.003, 0.1, 0.2, 0.7] {
        for step in 0..2000 {
            let q = lower + (upper - lower) * (step as f64 + 0.5) / 2000.0;
            for (limit, count) in [(upper, &mut over_upper), (lower, &mut under_lower)] {
                let exact = &mut on_limit;
                let u = (limit - q) / t;
                let past = |x: f64| {
                    if limit == upper {
                        x > upper
                    } else {
                        x < lower
                    }
                };
                if past(q + t * u) {
                    *count += 1;
                }
                let guarded = guard_position(q, u, t, lower, upper);
                if q + t * u == limit {
                    // On the limit exactly is within: left alone.
                    *exact += 1;
                    assert_eq!(guarded, u, "q {q}, T {t}");
                }
                assert!(!past(q + t * guarded), "q {q}, T {t}: {u} -> {guarded}");
                assert!(
                    (guarded - u).abs() <= 1e-12 * (1.0 + u.abs()),
                    "q {q}, T {t}: {u} -> {guarded}"
                );
            }
        }
    }
    assert!(
        over_upper > 100 && under_lower > 100,
        "{over_upper} {under_lower}"
    );
}
