//! The MPC planner (seed 000 secs 4-5): prediction matrices against direct
//! simulation, the structured condensation against the explicit matrices,
//! the QP against the closed-form unconstrained solution, limits, the
//! infeasibility handling and the option checks.

// Index loops mirror the equations (joint j, sample i) in these checks.
#![allow(clippy::needless_range_loop)]

use crate::common;

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{DMatrix, DVector, Pose, Vector3};
use armkit::mpc::prediction::{
    simulate_incremental_model, weighted_gram, Condensation, PredictionMatrices,
};
use armkit::mpc::qp::{
    upper_index, upper_triangle_len, QpOutcome, QpProblem, QpSolver, QpSolverKind, QpStatus,
};
use armkit::mpc::scenario::position_violation;
use armkit::mpc::{MpcOptions, MpcPlanner, ReachAid, StepStatus, TaskWeights, VelocityWeights};
use armkit::study::Seed000Example;
use armkit::Error;
use rand::Rng;

fn random_matrix(rows: usize, cols: usize, rng: &mut impl Rng) -> DMatrix<f64> {
    DMatrix::from_fn(rows, cols, |_, _| rng.gen_range(-1.0..1.0))
}

fn random_vector(len: usize, rng: &mut impl Rng) -> DVector<f64> {
    DVector::from_fn(len, |_, _| rng.gen_range(-1.0..1.0))
}

#[test]
fn prediction_matrices_match_direct_simulation_of_eq_14() {
    let mut rng = common::rng(1);
    for (nx, nu, p, n, m) in [
        (2, 1, 2, 4, 2),
        (3, 2, 2, 6, 1),
        (4, 3, 3, 5, 5),
        (6, 9, 6, 10, 3),
    ] {
        let a = DMatrix::identity(nx, nx) + 0.2 * random_matrix(nx, nx, &mut rng);
        let b = random_matrix(nx, nu, &mut rng);
        let c = random_matrix(p, nx, &mut rng);
        let pred = PredictionMatrices::new(&a, &b, &c, n, m).unwrap();
        assert_eq!(pred.s.shape(), (n * p, nx));
        assert_eq!(pred.g1.shape(), (n * p, n * nu));
        assert_eq!(pred.l.shape(), (n * nu, m * nu));
        for _ in 0..5 {
            let x0 = random_vector(nx, &mut rng);
            let v_old = random_vector(nu, &mut rng);
            let du = random_vector(m * nu, &mut rng);
            let y = pred.predict(&x0, &v_old, &du);
            let direct = simulate_incremental_model(&a, &b, &c, &x0, &v_old, &du, n);
            let scale = direct.amax().max(1.0);
            assert!(
                (&y - &direct).amax() < 1e-12 * scale,
                "nx={nx} nu={nu} N={n} M={m}: {:e}",
                (&y - &direct).amax()
            );
        }
    }
}

#[test]
fn prediction_matrices_of_the_gantry_model_match_simulation() {
    // Eq 13 on the flexible gantry: A = I, B = T J(q), C = position rows.
    let model = Seed000Example::model().unwrap();
    let mut data = Data::new(&model);
    let q = Seed000Example::LargeMove.start();
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let t = 0.05;
    let b = DMatrix::from_fn(6, 9, |r, c| t * j[(r, c)]);
    let a = DMatrix::identity(6, 6);
    let c = DMatrix::from_fn(3, 6, |r, col| if r == col { 1.0 } else { 0.0 });
    let mut rng = common::rng(2);
    let pred = PredictionMatrices::new(&a, &b, &c, 10, 5).unwrap();
    // G2 L block (i, l) = c(i, l) C B with c = max(i - l, 0).
    let gain = pred.increment_gain();
    let cb = &c * &b;
    for i in 1..=10 {
        for l in 0..5 {
            let block = gain.view(((i - 1) * 3, l * 9), (3, 9));
            let expected = &cb * (i.saturating_sub(l) as f64);
            assert!((block - expected).amax() < 1e-15);
        }
    }
    let x0 = random_vector(6, &mut rng);
    let v_old = random_vector(9, &mut rng);
    let du = random_vector(45, &mut rng);
    let y = pred.predict(&x0, &v_old, &du);
    let direct = simulate_incremental_model(&a, &b, &c, &x0, &v_old, &du, 10);
    assert!((y - direct).amax() < 1e-13);
}

#[test]
fn prediction_rejects_bad_horizons_and_sizes() {
    let a = DMatrix::identity(2, 2);
    let b = DMatrix::zeros(2, 1);
    let c = DMatrix::identity(2, 2);
    let err = PredictionMatrices::new(&a, &b, &c, 3, 4).unwrap_err();
    assert!(err.to_string().contains("control_horizon"), "{err}");
    let err = PredictionMatrices::new(&a, &b, &c, 0, 0).unwrap_err();
    assert!(err.to_string().contains("horizon"), "{err}");
    let err = PredictionMatrices::new(&a, &DMatrix::zeros(3, 1), &c, 3, 1).unwrap_err();
    assert!(err.to_string().contains("b (rows)"), "{err}");
}

/// `H = (G2 L)' Q (G2 L) + R + (L' L) kron W`, `f = (G2 L)' Q E + L'(1 kron W v_old)`
/// from the explicit matrices, for `A = I`, `B = Bt`, `C = I6`.
#[allow(clippy::too_many_arguments)]
fn explicit_cost(
    bt: &DMatrix<f64>,
    n: usize,
    m: usize,
    tracking: &[f64; 6],
    terminal: &[f64; 6],
    r: &[f64],
    w: &[f64],
    error: &[f64; 6],
    v_old: &DVector<f64>,
) -> (DMatrix<f64>, DVector<f64>) {
    let nu = bt.ncols();
    let a = DMatrix::identity(6, 6);
    let c = DMatrix::identity(6, 6);
    let pred = PredictionMatrices::new(&a, bt, &c, n, m).unwrap();
    let theta = pred.increment_gain();
    let q = DMatrix::from_fn(6 * n, 6 * n, |r, col| {
        if r != col {
            0.0
        } else if r / 6 == n - 1 {
            terminal[r % 6]
        } else {
            tracking[r % 6]
        }
    });
    let rr = DMatrix::from_fn(m * nu, m * nu, |i, j| if i == j { r[i % nu] } else { 0.0 });
    let ww = DMatrix::from_fn(n * nu, n * nu, |i, j| if i == j { w[i % nu] } else { 0.0 });
    let h = theta.transpose() * &q * &theta + rr + pred.l.transpose() * &ww * &pred.l;
    // Free response minus the target: stacked a + i Bt v_old.
    let a0 = DVector::from_column_slice(error);
    let u_old = DVector::from_fn(n * nu, |i, _| v_old[i % nu]);
    let free = pred.s.clone() * &a0 + &pred.g1 * &u_old;
    let f = theta.transpose() * &q * free + pred.l.transpose() * &ww * &u_old;
    (h, f)
}

#[test]
fn condensation_equals_the_explicit_eq_20_cost() {
    let mut rng = common::rng(3);
    for (n, m, nu) in [(10, 1, 9), (10, 5, 9), (6, 6, 7), (4, 2, 3)] {
        let bt = random_matrix(6, nu, &mut rng) * 0.05;
        let tracking: [f64; 6] = std::array::from_fn(|_| rng.gen_range(0.0..10.0));
        let terminal: [f64; 6] = std::array::from_fn(|_| rng.gen_range(0.0..200.0));
        let r: Vec<f64> = (0..nu).map(|_| rng.gen_range(0.5..100.0)).collect();
        let w: Vec<f64> = (0..nu).map(|_| rng.gen_range(0.0..1.0)).collect();
        let error: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let v_old = random_vector(nu, &mut rng);
        let (h, f) = explicit_cost(&bt, n, m, &tracking, &terminal, &r, &w, &error, &v_old);

        let condensation = Condensation::new(n, m).unwrap();
        let bt_rows: Vec<f64> = (0..6)
            .flat_map(|row| (0..nu).map(move |col| (row, col)))
            .map(|(row, col)| bt[(row, col)])
            .collect();
        let mut gram_q = vec![0.0; nu * nu];
        let mut gram_n = vec![0.0; nu * nu];
        weighted_gram(&bt_rows, &tracking, &mut gram_q);
        weighted_gram(&bt_rows, &terminal, &mut gram_n);
        let mut upper = vec![0.0; upper_triangle_len(m * nu)];
        condensation.fill_hessian(&gram_q, &gram_n, &r, &w, &mut upper);
        let drift: [f64; 6] = std::array::from_fn(|row| (bt.row(row) * &v_old)[0]);
        let wv: Vec<f64> = (0..nu).map(|j| w[j] * v_old[j]).collect();
        let mut gradient = vec![0.0; m * nu];
        condensation.fill_gradient(
            &bt_rows,
            &error,
            &drift,
            &tracking,
            &terminal,
            &wv,
            &mut gradient,
        );
        let scale = h.amax();
        for col in 0..m * nu {
            for row in 0..=col {
                let got = upper[upper_index(row, col)];
                assert!(
                    (got - h[(row, col)]).abs() < 1e-12 * scale,
                    "N={n} M={m}: H[{row}][{col}] = {got} vs {}",
                    h[(row, col)]
                );
            }
        }
        let fscale = f.amax().max(1.0);
        for (i, g) in gradient.iter().enumerate() {
            assert!(
                (g - f[i]).abs() < 1e-12 * fscale,
                "f[{i}] = {g} vs {}",
                f[i]
            );
        }
    }
}

/// A pose `offset` m away from the pose at `q`, same orientation.
fn nearby_target(model: &armkit::Model, q: &[f64], offset: Vector3<f64>) -> Pose {
    let pose = *forward_kinematics(model, &mut Data::new(model), q).unwrap();
    Pose::new(pose.rotation, pose.translation + offset)
}

#[test]
fn without_active_constraints_the_qp_equals_the_closed_form_solution() {
    // A 2 mm move from the middle of the ranges: no limit is near.
    for name in ["gantry9", "panda"] {
        let model = armkit::robots::by_name(name).unwrap();
        let q = model.neutral_configuration();
        let target = nearby_target(&model, &q, Vector3::new(0.002, -0.001, 0.001));
        for &solver in QpSolverKind::available() {
            for (m, weights) in [
                (1, TaskWeights::position_only(10.0, 200.0)),
                (5, TaskWeights::full_pose(10.0, 200.0)),
            ] {
                let r: Vec<f64> = (0..model.dof()).map(|j| 1.0 + j as f64).collect();
                let options = MpcOptions {
                    control_horizon: m,
                    task_weights: weights,
                    increment_weights: Some(r.clone()),
                    solver,
                    // The closed form is seed 000's cost alone.
                    reach: ReachAid::Off,
                    ..MpcOptions::default()
                };
                let t = options.sample_time;
                let mut planner = MpcPlanner::new(&model, options).unwrap();
                planner.set_target(&target).unwrap();
                let v_old: Vec<f64> = (0..model.dof()).map(|j| 0.01 * (j as f64 - 3.0)).collect();
                planner.reset(&v_old).unwrap();
                let report = planner.step(&q).unwrap().clone();
                assert_eq!(report.status, StepStatus::Solved);

                // Closed form from the explicit matrices: dU = -H^-1 f.
                let mut data = Data::new(&model);
                let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
                    .unwrap()
                    .clone();
                let pose = *data.end_effector_pose();
                let bt = DMatrix::from_fn(6, model.dof(), |r, c| t * j[(r, c)]);
                let mut error = [0.0; 6];
                for k in 0..3 {
                    error[k] = pose.translation[k] - target.translation[k];
                }
                let w: Vec<f64> = r.iter().map(|x| 0.01 * x).collect();
                let v = DVector::from_vec(v_old.clone());
                let (h, f) = explicit_cost(
                    &bt,
                    10,
                    m,
                    &weights.tracking,
                    &weights.terminal,
                    &r,
                    &w,
                    &error,
                    &v,
                );
                let du = -h.cholesky().unwrap().solve(&f);
                let increments = planner.increments();
                let scale = du.amax();
                let worst = (0..du.len())
                    .map(|i| (increments[i] - du[i]).abs())
                    .fold(0.0, f64::max);
                assert!(
                    worst < 1e-5 * scale,
                    "{name} {} M={m}: |dU - closed form| = {worst:e} (scale {scale:e})",
                    solver.name()
                );
                for (k, u) in report.velocity.iter().enumerate() {
                    assert!((u - (v_old[k] + du[k])).abs() < 1e-5 * scale);
                }
            }
        }
    }
}

#[test]
fn planned_joint_positions_respect_the_limits_at_every_predicted_sample() {
    // A far target on the gantry with M = 5: the QP's whole plan, not just
    // the applied input, keeps every joint within its limits for all N samples.
    let model = Seed000Example::model().unwrap();
    let example = Seed000Example::LargeMove;
    for &solver in QpSolverKind::available() {
        let options = MpcOptions {
            control_horizon: 5,
            solver,
            ..example.options()
        };
        let (n, m, t) = (
            options.horizon,
            options.control_horizon,
            options.sample_time,
        );
        let mut planner = MpcPlanner::new(&model, options).unwrap();
        planner.set_target(&example.target()).unwrap();
        let (lower, upper) = {
            let (l, u) = planner.position_limits();
            (l.to_vec(), u.to_vec())
        };
        let vmax = planner.velocity_limits().to_vec();
        let mut q = example.start();
        let mut worst_position: f64 = 0.0;
        let mut worst_velocity: f64 = 0.0;
        for _ in 0..150 {
            let v_old = planner.previous_velocity().to_vec();
            let report = planner.step(&q).unwrap().clone();
            assert!(report.status.is_ok(), "{:?}", report.status);
            let du = planner.increments().to_vec();
            let mut u = v_old.clone();
            let mut qp = q.clone();
            for i in 0..n {
                if i < m {
                    for j in 0..9 {
                        u[j] += du[i * 9 + j];
                    }
                }
                for j in 0..9 {
                    worst_velocity = worst_velocity.max(u[j].abs() - vmax[j]);
                    qp[j] += t * u[j];
                }
                worst_position = worst_position.max(position_violation(&qp, &lower, &upper));
            }
            for j in 0..9 {
                q[j] += t * report.velocity[j];
            }
        }
        // The QP's tolerance (1e-7 OSQP, 1e-8 Clarabel) on the plan; the
        // applied input is exact (checked by the examples' summaries).
        assert!(
            worst_position < 1e-6,
            "{}: {worst_position:e}",
            solver.name()
        );
        assert!(
            worst_velocity < 1e-6,
            "{}: {worst_velocity:e}",
            solver.name()
        );
    }
}

/// A planar 2R arm whose first joint is stopped by its upper limit on the
/// way to the target: every plan the QP makes, at every step, keeps that
/// joint within the limit at every one of the `N` predicted samples, with
/// the control horizon shorter than the horizon and equal to it, while the
/// limit binds in the middle of the horizon (reached at a later sample
/// than the first).
#[test]
fn plans_stay_within_a_limit_that_binds_mid_horizon_at_every_sample() {
    use armkit::model::{DhConvention, DhLink};
    let upper = 0.5;
    let links = [
        DhLink::revolute(0.0, 0.4, 0.0)
            .with_limits(-1.0, upper)
            .with_velocity_limit(1.0),
        DhLink::revolute(0.0, 0.3, 0.0)
            .with_limits(-2.5, 2.5)
            .with_velocity_limit(1.0),
    ];
    let model = armkit::Model::from_dh("planar2", DhConvention::Standard, &links).unwrap();
    let mut data = Data::new(&model);
    let target = *forward_kinematics(&model, &mut data, &[1.1, 0.6]).unwrap();
    for &solver in QpSolverKind::available() {
        for control_horizon in [4, 10] {
            let options = MpcOptions {
                horizon: 10,
                control_horizon,
                task_weights: TaskWeights::position_only(10.0, 200.0),
                reach: ReachAid::Off,
                solver,
                ..MpcOptions::default()
            };
            let (n, m, t) = (
                options.horizon,
                options.control_horizon,
                options.sample_time,
            );
            let mut planner = MpcPlanner::new(&model, options).unwrap();
            planner.set_target(&target).unwrap();
            let mut q = vec![-0.2, 0.3];
            let (mut worst, mut mid_horizon): (f64, usize) = (f64::NEG_INFINITY, 0);
            let mut stops = 0;
            for step in 0..80 {
                let v_old = planner.previous_velocity().to_vec();
                let report = planner.step(&q).unwrap().clone();
                if !report.status.is_ok() {
                    // Clarabel can stop on a numerical failure with the joint
                    // at its limit (a controlled stop, reported); the
                    // planner's own active-set solver must not.
                    assert_ne!(
                        solver,
                        QpSolverKind::ActiveSet,
                        "M = {m}, step {step}: {:?}, q {q:?}",
                        report.status
                    );
                    stops += 1;
                }
                let du = planner.increments().to_vec();
                let (mut u, mut position) = (v_old.clone(), q.clone());
                let mut predicted = Vec::with_capacity(n);
                for i in 0..n {
                    for j in 0..2 {
                        if i < m {
                            u[j] += du[i * 2 + j];
                        }
                        position[j] += t * u[j];
                    }
                    predicted.push(position[0]);
                }
                let highest = predicted.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                worst = worst.max(highest - upper);
                if predicted[0] < upper - 1e-3 && highest > upper - 1e-6 {
                    mid_horizon += 1;
                }
                for j in 0..2 {
                    q[j] += t * report.velocity[j];
                }
            }
            assert!(
                worst <= 1e-6,
                "{} M = {m}: a plan crosses the limit by {worst:e} rad",
                solver.name()
            );
            assert!(
                mid_horizon >= 2,
                "{} M = {m}: the limit never binds mid-horizon",
                solver.name()
            );
            assert!(
                (q[0] - upper).abs() < 1e-3,
                "{} M = {m}: {q:?}",
                solver.name()
            );
            println!(
                "{} M = {m}: {mid_horizon} plans reach the limit mid-horizon, {stops} stopped step(s)",
                solver.name()
            );
        }
    }
}

#[test]
fn seed000_examples_meet_their_checks() {
    for example in Seed000Example::ALL {
        let run = example.run().unwrap();
        for check in example.checks(&run) {
            assert!(
                check.passed,
                "{}: `{}` failed: {}",
                example.title(),
                check.name,
                check.detail
            );
        }
        assert_eq!(run.summary.max_velocity_violation, 0.0);
        assert_eq!(run.summary.max_position_violation, 0.0);
    }
}

#[test]
fn a_start_outside_the_limits_recovers_without_going_further_out() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    // The paper's own start: d1 = -1 is below its lower limit 0; and q5 =
    // pi/2 is above our 1.22.
    let mut q = vec![
        -1.0,
        2.0,
        0.0,
        0.0,
        std::f64::consts::FRAC_PI_2,
        0.0,
        0.0,
        0.0,
        0.0,
    ];
    let target = nearby_target(&model, &model.neutral_configuration(), Vector3::zeros());
    let options = MpcOptions {
        task_weights: TaskWeights::position_only(10.0, 200.0),
        ..MpcOptions::default()
    };
    let t = options.sample_time;
    let mut planner = MpcPlanner::new(&model, options).unwrap();
    planner.set_target(&target).unwrap();
    let (lower, upper) = {
        let (l, u) = planner.position_limits();
        (l.to_vec(), u.to_vec())
    };
    let mut violation = position_violation(&q, &lower, &upper);
    let mut recovering_steps = 0;
    for step in 0..400 {
        let report = planner.step(&q).unwrap().clone();
        let was_outside = position_violation(&q, &lower, &upper) > 0.0;
        if was_outside {
            assert_eq!(report.status, StepStatus::Recovering, "step {step}");
            recovering_steps += 1;
        } else {
            assert!(report.status.is_ok());
        }
        for j in 0..9 {
            q[j] += t * report.velocity[j];
        }
        let now = position_violation(&q, &lower, &upper);
        assert!(
            now <= violation + 1e-15,
            "step {step}: {violation} -> {now}"
        );
        violation = now;
    }
    assert_eq!(violation, 0.0);
    // d1 comes back from -1 m at least at the recovery speed (half its
    // 0.6 m/s limit: 67 steps) and at most at the limit (34 steps).
    assert!((33..=67).contains(&recovering_steps), "{recovering_steps}");
}

/// A backend that always fails, to check the controlled stop.
struct FailingSolver(QpStatus);

impl QpSolver for FailingSolver {
    fn name(&self) -> &'static str {
        "failing"
    }
    fn solve(&mut self, _: &[f64], _: &[f64], _: &[f64], _: &[f64], x: &mut [f64]) -> QpOutcome {
        x.iter_mut().for_each(|v| *v = f64::NAN);
        QpOutcome {
            status: self.0,
            iterations: 7,
        }
    }
}

#[test]
fn a_solver_failure_stops_the_robot_and_says_so() {
    let model = armkit::robots::by_name("ur5").unwrap();
    for status in [
        QpStatus::Infeasible,
        QpStatus::IterationLimit,
        QpStatus::NumericalFailure,
    ] {
        let mut planner = MpcPlanner::with_solver(&model, MpcOptions::default(), |_| {
            Ok(Box::new(FailingSolver(status)))
        })
        .unwrap();
        assert_eq!(planner.solver_name(), "failing");
        planner.reset(&[0.5; 6]).unwrap();
        let report = planner.step(&model.neutral_configuration()).unwrap();
        assert_eq!(report.status, StepStatus::Stopped(status));
        assert!(!report.status.is_ok());
        assert_eq!(report.velocity, vec![0.0; 6]);
        assert!((report.limit_correction - 0.0).abs() < 1e-15);
        assert!(planner.increments().iter().all(|&v| v == 0.0));
    }
    // A "solved" answer with NaN in it is a numerical failure too.
    let mut planner = MpcPlanner::with_solver(&model, MpcOptions::default(), |_| {
        Ok(Box::new(FailingSolver(QpStatus::Solved)))
    })
    .unwrap();
    let report = planner.step(&model.neutral_configuration()).unwrap();
    assert_eq!(
        report.status,
        StepStatus::Stopped(QpStatus::NumericalFailure)
    );
}

#[test]
fn a_failure_outside_the_limits_still_moves_back_in() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut planner = MpcPlanner::with_solver(&model, MpcOptions::default(), |_| {
        Ok(Box::new(FailingSolver(QpStatus::Infeasible)))
    })
    .unwrap();
    let mut q = model.neutral_configuration();
    q[2] = 3.3; // elbow limit is pi
    let report = planner.step(&q).unwrap();
    assert_eq!(report.status, StepStatus::Stopped(QpStatus::Infeasible));
    assert!(report.velocity[2] <= 0.0);
    assert!(report
        .velocity
        .iter()
        .enumerate()
        .all(|(j, v)| j == 2 || *v == 0.0));
}

#[test]
fn limits_are_respected_exactly_even_when_the_plan_pushes_on_them() {
    // A target 3 m beyond the rail's end: d1 runs into its 9 m limit at full
    // speed and stays on it, never past; the arm stretches towards the target.
    let model = armkit::robots::by_name("gantry9").unwrap();
    let q0 = vec![7.0, 2.5, 1.0, 0.0, 0.3, 0.3, 0.0, 0.5, 0.0];
    let target = Pose::from_translation(Vector3::new(12.0, 2.5, 4.0));
    for &solver in QpSolverKind::available() {
        for m in [1, 4] {
            let options = MpcOptions {
                solver,
                control_horizon: m,
                task_weights: TaskWeights::position_only(10.0, 200.0),
                ..MpcOptions::default()
            };
            let run = armkit::mpc::scenario::simulate(
                &model,
                options,
                &q0,
                &target,
                &armkit::mpc::scenario::SimulationOptions {
                    max_steps: 200,
                    ..Default::default()
                },
            )
            .unwrap();
            let name = solver.name();
            assert!(!run.summary.converged);
            assert_eq!(run.summary.max_position_violation, 0.0, "{name} M={m}");
            assert_eq!(run.summary.max_velocity_violation, 0.0, "{name} M={m}");
            assert!((run.peak_speed(0) - 0.6).abs() < 1e-9, "{name} M={m}");
            let last = &run.samples.last().unwrap().q;
            // Clarabel, an interior-point method, stops 1e-7 short of the bound.
            assert!(
                (last[0] - 9.0).abs() < 1e-6,
                "{name} M={m}: d1 = {}",
                last[0]
            );
        }
    }
}

#[test]
fn bad_options_are_rejected_with_their_name() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let cases: Vec<(MpcOptions, &str)> = vec![
        (
            MpcOptions {
                control_horizon: 11,
                ..MpcOptions::default()
            },
            "control_horizon",
        ),
        (
            MpcOptions {
                sample_time: 0.0,
                ..MpcOptions::default()
            },
            "sample_time",
        ),
        (
            MpcOptions {
                task_weights: TaskWeights::position_only(0.0, 0.0),
                ..MpcOptions::default()
            },
            "nothing to track",
        ),
        (
            MpcOptions {
                increment_weights: Some(vec![1.0, 1.0, 0.0, 1.0, 1.0, 1.0]),
                ..MpcOptions::default()
            },
            "increment_weights",
        ),
        (
            MpcOptions {
                increment_weights: Some(vec![1.0; 5]),
                ..MpcOptions::default()
            },
            "increment_weights: expected 6 values, got 5",
        ),
        (
            MpcOptions {
                velocity_weights: VelocityWeights::Proportional(-1.0),
                ..MpcOptions::default()
            },
            "velocity_weights",
        ),
        (
            MpcOptions {
                joint_limits: Some(
                    (0..6)
                        .map(|j| armkit::model::JointLimits {
                            velocity: Some(if j == 2 { f64::NAN } else { 1.0 }),
                            ..armkit::model::JointLimits::position(-3.0, 3.0)
                        })
                        .collect(),
                ),
                ..MpcOptions::default()
            },
            "joint 2: velocity limit must be finite and > 0, got NaN",
        ),
        (
            MpcOptions {
                joint_limits: Some(
                    [1.0, 1.0, -1.0, 1.0, 1.0, 1.0]
                        .iter()
                        .map(|&upper| armkit::model::JointLimits::position(0.0, upper))
                        .collect(),
                ),
                ..MpcOptions::default()
            },
            "joint 2: contradictory position limits [0, -1]",
        ),
        (
            MpcOptions {
                recovery_speed: 1.5,
                ..MpcOptions::default()
            },
            "recovery_speed",
        ),
    ];
    for (options, expected) in cases {
        let err = match MpcPlanner::new(&model, options) {
            Ok(_) => panic!("accepted options that should fail with `{expected}`"),
            Err(e) => e,
        };
        assert!(
            err.to_string().contains(expected),
            "`{err}` lacks `{expected}`"
        );
    }
    let mut planner = MpcPlanner::new(&model, MpcOptions::default()).unwrap();
    let err = planner.step(&[0.0; 5]).unwrap_err();
    assert!(
        matches!(err, Error::DimensionMismatch { got: 5, .. }),
        "{err}"
    );
    let err = planner
        .step(&[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0])
        .unwrap_err();
    assert!(err.to_string().contains("joint_positions[2]"), "{err}");
    let err = planner.reset(&[0.0; 7]).unwrap_err();
    assert!(err.to_string().contains("velocity"), "{err}");
}

#[test]
fn qp_problem_checks_its_input() {
    let a = armkit::mpc::qp::CscMatrix::from_dense(1, 2, &[1.0, 1.0]);
    let err = QpProblem::new(
        2,
        vec![1.0; 3],
        vec![0.0; 2],
        a.clone(),
        vec![1.0],
        vec![0.0],
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .contains("lower bound 1 exceeds upper bound 0"),
        "{err}"
    );
    let err = QpProblem::new(2, vec![1.0; 2], vec![0.0; 2], a, vec![0.0], vec![1.0]).unwrap_err();
    assert!(err.to_string().contains("hessian_upper"), "{err}");
}

#[test]
fn the_measured_pose_feeds_the_prediction_back() {
    // A pose measurement that differs from the model (an unmodelled 5 mm
    // sag) shows as the prediction error, and the planner corrects for it.
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut q = Seed000Example::SmallMove.start();
    let target = Seed000Example::SmallMove.target();
    let options = MpcOptions {
        task_weights: TaskWeights::position_only(10.0, 200.0),
        ..MpcOptions::default()
    };
    let t = options.sample_time;
    let mut planner = MpcPlanner::new(&model, options).unwrap();
    planner.set_target(&target).unwrap();
    let sag = Vector3::new(0.0, 0.0, -0.005);
    let mut data = Data::new(&model);
    let mut last_error = f64::NAN;
    for step in 0..200 {
        let mut measured = *forward_kinematics(&model, &mut data, &q).unwrap();
        measured.translation += sag;
        let report = planner
            .step_with_measured_pose(&q, &measured)
            .unwrap()
            .clone();
        if step == 0 {
            assert_eq!(report.prediction_error, 0.0);
        }
        last_error = report.position_error;
        for j in 0..9 {
            q[j] += t * report.velocity[j];
        }
    }
    // The measured hand (model + sag) is at the target.
    assert!(last_error < 1e-4, "{last_error}");
    let model_pose = *forward_kinematics(&model, &mut data, &q).unwrap();
    assert!(((model_pose.translation + sag) - target.translation).norm() < 1e-4);
}

#[test]
fn a_target_beyond_a_joint_limit_is_reported_with_that_joint() {
    // The UR5's base joint narrowed to +-0.3 rad; the target lies 1.2 rad
    // round: the run stops against the base joint's upper limit and says so.
    use armkit::mpc::active_set::BoundSide;
    use armkit::mpc::scenario::{simulate_with, SimulationOptions};
    use armkit::mpc::{diagnose_run, RunStatus};
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut limits: Vec<armkit::model::JointLimits> =
        model.joints().iter().map(|j| j.limits).collect();
    limits[0].lower = -0.3;
    limits[0].upper = 0.3;
    let start = vec![0.0, -1.2, 1.4, -0.5, 1.2, 0.4];
    let mut goal = start.clone();
    goal[0] = 1.2;
    let target = *forward_kinematics(&model, &mut Data::new(&model), &goal).unwrap();
    for reach in [ReachAid::Off, ReachAid::default()] {
        let options = MpcOptions {
            task_weights: TaskWeights::position_only(10.0, 200.0),
            joint_limits: Some(limits.clone()),
            reach: reach.clone(),
            ..MpcOptions::default()
        };
        let mut planner = MpcPlanner::new(&model, options).unwrap();
        let simulation = SimulationOptions {
            max_steps: 400,
            ..SimulationOptions::default()
        };
        let run = simulate_with(&mut planner, &start, &target, &simulation, |_| {}).unwrap();
        assert!(!run.summary.converged);
        assert_eq!(run.summary.max_position_violation, 0.0);
        let last = &run.samples.last().unwrap().q;
        let status = diagnose_run(&planner, last, false).unwrap();
        assert_eq!(
            status,
            RunStatus::JointLimit {
                joint: 0,
                name: model.joints()[0].name.clone(),
                side: BoundSide::Upper
            },
            "reach {reach}: {status}"
        );
        assert_eq!(status.as_str(), "joint-limit");
        assert!(
            status.to_string().contains("upper limit of joint 0"),
            "{status}"
        );
        // And a converged run says so.
        assert_eq!(
            diagnose_run(&planner, last, true).unwrap(),
            RunStatus::Converged
        );
    }
}

#[test]
fn every_status_has_a_name_and_a_display() {
    use armkit::mpc::qp::QpStatus;
    assert_eq!(StepStatus::Solved.as_str(), "solved");
    assert_eq!(StepStatus::Clamped.to_string(), "clamped");
    assert_eq!(StepStatus::Recovering.to_string(), "recovering");
    assert_eq!(
        StepStatus::Stopped(QpStatus::Infeasible).to_string(),
        "stopped (infeasible)"
    );
    assert_eq!(
        StepStatus::Stopped(QpStatus::IterationLimit).as_str(),
        "stopped"
    );
    assert_eq!(QpStatus::SolvedInaccurate.to_string(), "solved-inaccurate");
    assert_eq!(QpStatus::NumericalFailure.as_str(), "numerical-failure");
    assert_eq!(ReachAid::Off.to_string(), "off");
    assert_eq!(ReachAid::default().as_str(), "goal-posture");
    assert_eq!(
        armkit::mpc::qp::QpSolverKind::ActiveSet.to_string(),
        "active-set"
    );
}
