//! Free-floating space manipulator (seed 004, sec 1): validation, the
//! generalized Jacobian against finite differences of the simulation and
//! against the fixed-base Jacobian, momentum conservation of the simulation,
//! and resolved-rate tracking.
//!
//! Figures: `cargo test -p armkit --release --test it -- --nocapture space::`.

use crate::common;

use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::math::{Matrix3, Matrix6xX, Pose, Rotation3, Vector3, Vector6};
use armkit::robots::{space6r_base_body, space6r_free_floating};
use armkit::space::{
    center_of_mass, end_effector_pose, generalized_jacobian, momentum, step, track_pose_path,
    BaseBody, BaseMode, FreeFloatingModel, FreeFloatingState, SinusoidalJointMotion, SpaceData,
};
use armkit::tracking::{LeastSquares, TrackingOptions, TrackingStatus};
use armkit::trajectory::TimeFn;
use rand::Rng;

const MODES: [BaseMode; 2] = [BaseMode::AttitudeHeld, BaseMode::FreeFloating];

/// space6r on a base with a full (non-diagonal) inertia and an off-centre
/// centre of mass, so that every term of the free-floating formulas matters.
fn lopsided_model() -> FreeFloatingModel {
    let mut base = space6r_base_body();
    let turn = Rotation3::from_euler_angles(0.3, -0.2, 0.5).into_inner();
    base.inertia =
        turn * Matrix3::from_diagonal(&Vector3::new(40.0, 70.0, 90.0)) * turn.transpose();
    base.com = Vector3::new(0.05, -0.03, 0.02);
    base.mount = Pose::from_xyz_rpy([0.1, 0.0, 0.5], [0.0, 0.1, 0.2]);
    base.mass = 250.0;
    FreeFloatingModel::new(base, armkit::robots::space6r().unwrap()).unwrap()
}

/// The Stanford arm (RRPRRR: joint 3 prismatic) with made-up link masses and
/// full inertias on space6r's satellite: exercises the prismatic-joint terms.
fn stanford_model() -> FreeFloatingModel {
    let arm = armkit::robots::stanford().unwrap();
    let (convention, links) = arm.dh_table().unwrap();
    let links: Vec<_> = links
        .iter()
        .enumerate()
        .map(|(j, link)| {
            let k = j as f64;
            let turn = Rotation3::from_euler_angles(0.2 * k, -0.1, 0.3 * k).into_inner();
            let mut inertia = armkit::model::LinkInertia::point_mass(
                12.0 - k,
                Vector3::new(0.02 * k, -0.05, 0.1 - 0.03 * k),
            );
            inertia.inertia = turn
                * Matrix3::from_diagonal(&Vector3::new(0.3, 0.5, 0.6 + 0.1 * k))
                * turn.transpose();
            link.with_inertia(inertia)
        })
        .collect();
    let arm = armkit::Model::from_dh_with_transforms(
        "stanford-massive",
        convention,
        &links,
        *arm.base(),
        *arm.tool(),
    )
    .unwrap();
    FreeFloatingModel::new(space6r_base_body(), arm).unwrap()
}

fn random_state(model: &FreeFloatingModel, rng: &mut impl Rng) -> FreeFloatingState {
    let rpy = [
        rng.gen_range(-3.0..3.0),
        rng.gen_range(-1.5..1.5),
        rng.gen_range(-3.0..3.0),
    ];
    let xyz = [
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    ];
    FreeFloatingState::new(
        Pose::from_xyz_rpy(xyz, rpy),
        common::random_configuration(model.arm(), rng),
    )
}

/// Angle of a rotation matrix from its skew part: exact for small angles,
/// where `acos` of the trace loses half the digits.
fn rotation_angle(r: &Matrix3<f64>) -> f64 {
    let s = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    ) * 0.5;
    s.norm().atan2(0.5 * (r.trace() - 1.0))
}

fn base_twist(data: &SpaceData, q_dot: &[f64]) -> Vector6<f64> {
    let mut twist = Vector6::zeros();
    for (j, rate) in q_dot.iter().enumerate() {
        twist += data.base_jacobian().column(j) * *rate;
    }
    twist
}

/// Spoils one field of a valid base body.
type Spoiler = fn(&mut BaseBody);

#[test]
fn bad_mass_properties_are_named() {
    let arm = armkit::robots::space6r().unwrap();
    let cases: [(Spoiler, &str); 6] = [
        (
            |b| b.mass = -10.0,
            "field `mass`: must be finite and > 0 kg, got -10",
        ),
        (
            |b| b.mass = 0.0,
            "field `mass`: must be finite and > 0 kg, got 0",
        ),
        (|b| b.com.x = f64::NAN, "field `com`: must be finite"),
        (
            |b| b.inertia[(0, 1)] = 5.0,
            "field `inertia`: must be symmetric",
        ),
        (
            |b| b.inertia[(2, 2)] = -1.0,
            "field `inertia`: must be positive definite (smallest eigenvalue -1e0 kg m^2)",
        ),
        (
            |b| b.inertia[(1, 1)] = 0.0,
            "field `inertia`: must be positive definite (smallest eigenvalue 0e0 kg m^2)",
        ),
    ];
    for (spoil, expected) in cases {
        let mut base = space6r_base_body();
        spoil(&mut base);
        let message = FreeFloatingModel::new(base, arm.clone())
            .unwrap_err()
            .to_string();
        assert!(
            message.starts_with("invalid model `satellite`: base body, "),
            "{message}"
        );
        assert!(message.contains(expected), "{message}");
    }
    let mut base = space6r_base_body();
    base.mount.rotation[(0, 0)] = 2.0;
    let message = FreeFloatingModel::new(base, arm).unwrap_err().to_string();
    assert!(
        message.contains("field `mount`: rotation is not a proper rotation"),
        "{message}"
    );

    // An arm without mass properties: the link is named.
    let puma = armkit::robots::puma560().unwrap();
    let message = FreeFloatingModel::new(space6r_base_body(), puma)
        .unwrap_err()
        .to_string();
    assert_eq!(
        message,
        "invalid model: link 0 (`q1`), field `inertia`: no mass properties: a free-floating \
         system needs the mass, centre of mass and inertia of every link"
    );
}

#[test]
fn bad_arguments_are_named() {
    let model = space6r_free_floating().unwrap();
    let mut data = SpaceData::new(&model);
    let q = [0.1; 6];
    let mode = BaseMode::FreeFloating;
    let error = generalized_jacobian(&model, &mut data, &Pose::identity(), &q[..5], mode)
        .unwrap_err()
        .to_string();
    assert_eq!(error, "joint_positions: expected 6 values, got 5");
    let mut sheared = Pose::identity();
    sheared.rotation[(0, 1)] = 0.1;
    let error = generalized_jacobian(&model, &mut data, &sheared, &q, mode)
        .unwrap_err()
        .to_string();
    assert!(
        error.starts_with("invalid argument `base_pose`: rotation is not a proper"),
        "{error}"
    );
    let mut state = FreeFloatingState::new(Pose::identity(), q.to_vec());
    let error = step(
        &model,
        &mut data,
        &mut state,
        &[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0],
        0.1,
        mode,
    )
    .unwrap_err()
    .to_string();
    assert_eq!(error, "joint_rates[2] is not finite (NaN)");
    let error = step(&model, &mut data, &mut state, &[0.0; 6], -0.1, mode)
        .unwrap_err()
        .to_string();
    assert_eq!(
        error,
        "invalid argument `dt`: must be finite and >= 0 s, got -0.1"
    );
    let options = TrackingOptions {
        dt: 0.0,
        ..Default::default()
    };
    let error = track_pose_path(
        &model,
        &mut data,
        mode,
        &state,
        &TimeFn::new(1.0, |_| Pose::identity()).unwrap(),
        LeastSquares { damping: 0.0 },
        &options,
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        error,
        "invalid argument `dt`: must be finite and > 0 s, got 0"
    );
    // A workspace made for another model.
    let mut arm = armkit::model::ModelBuilder::new("one link");
    arm = arm.joint(
        armkit::model::JointSpec::revolute("a", -1.0, 1.0)
            .with_inertia(armkit::model::LinkInertia::point_mass(1.0, Vector3::x())),
    );
    let other = FreeFloatingModel::new(space6r_base_body(), arm.build().unwrap()).unwrap();
    let error = center_of_mass(&other, &mut data, &Pose::identity(), &[0.0])
        .unwrap_err()
        .to_string();
    assert_eq!(
        error,
        "data (workspace made for another model): expected 1 values, got 6"
    );
}

/// The base twist that `generalized_jacobian` implies has zero linear momentum
/// (both modes) and zero angular momentum (free mode), summed body by body.
#[test]
fn base_twist_conserves_momentum() {
    for model in [lopsided_model(), stanford_model()] {
        let mut data = SpaceData::new(&model);
        let mut rng = common::rng(41);
        let mut worst = [0.0f64; 2];
        for _ in 0..50 {
            let state = random_state(&model, &mut rng);
            let q_dot: Vec<f64> = (0..6).map(|_| rng.gen_range(-0.5..0.5)).collect();
            for (m, mode) in MODES.into_iter().enumerate() {
                generalized_jacobian(&model, &mut data, &state.base, &state.q, mode).unwrap();
                let twist = base_twist(&data, &q_dot);
                let p = momentum(&model, &mut data, &state.base, &state.q, &twist, &q_dot).unwrap();
                // Scale: the momentum of the arm moving on a held base.
                let held = momentum(
                    &model,
                    &mut data,
                    &state.base,
                    &state.q,
                    &Vector6::zeros(),
                    &q_dot,
                )
                .unwrap();
                let linear = p.linear.norm() / held.linear.norm();
                assert!(linear < 1e-13, "{mode:?}: relative |P| = {linear:e}");
                if mode == BaseMode::FreeFloating {
                    let angular = p.angular.norm() / held.angular.norm();
                    assert!(angular < 1e-13, "relative |L| = {angular:e}");
                    worst[m] = worst[m].max(angular);
                } else {
                    // Holding the attitude takes a torque: L is not zero.
                    assert!(p.angular.norm() > 1e-3 * held.angular.norm());
                    worst[m] = worst[m].max(linear);
                }
            }
        }
        println!(
            "{}: relative |P| (attitude held) {:.1e}, relative |L| (free) {:.1e}",
            model.arm().name(),
            worst[0],
            worst[1]
        );
    }
}

/// Central differences of the simulated end-effector motion: from a state,
/// step by +h and by -h with one joint at unit rate.
fn simulated_jacobian(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    state: &FreeFloatingState,
    mode: BaseMode,
    h: f64,
) -> Matrix6xX<f64> {
    let mut fd = Matrix6xX::zeros(model.dof());
    for j in 0..model.dof() {
        let mut rates = vec![0.0; model.dof()];
        rates[j] = 1.0;
        let mut plus = state.clone();
        step(model, data, &mut plus, &rates, h, mode).unwrap();
        let tp = *data.end_effector_pose();
        rates[j] = -1.0;
        let mut minus = state.clone();
        step(model, data, &mut minus, &rates, h, mode).unwrap();
        let tm = *data.end_effector_pose();
        let linear = (tp.translation - tm.translation) / (2.0 * h);
        let relative = tp.rotation * tm.rotation.transpose();
        let skew = (relative - relative.transpose()) * 0.5;
        let angular = Vector3::new(skew[(2, 1)], skew[(0, 2)], skew[(1, 0)]) / (2.0 * h);
        fd.fixed_view_mut::<3, 1>(0, j).copy_from(&linear);
        fd.fixed_view_mut::<3, 1>(3, j).copy_from(&angular);
    }
    fd
}

#[test]
fn generalized_jacobian_matches_finite_differences_of_the_simulation() {
    for model in [
        space6r_free_floating().unwrap(),
        lopsided_model(),
        stanford_model(),
    ] {
        let mut data = SpaceData::new(&model);
        let mut rng = common::rng(7);
        for mode in MODES {
            let mut worst: f64 = 0.0;
            let mut base_effect: f64 = 0.0;
            for _ in 0..20 {
                let state = random_state(&model, &mut rng);
                let fd = simulated_jacobian(&model, &mut data, &state, mode, 1e-5);
                let j_star = generalized_jacobian(&model, &mut data, &state.base, &state.q, mode)
                    .unwrap()
                    .clone();
                worst = worst.max((&j_star - &fd).amax());
                // The base's reaction is far from negligible: J* is not J_m.
                let mut arm_data = Data::new(model.arm());
                let fixed = jacobian(model.arm(), &mut arm_data, &state.q, JacobianFrame::World)
                    .unwrap()
                    .clone();
                let mut fixed_world = fixed.clone();
                let turn = state.base.rotation * model.base().mount.rotation;
                for (mut c, f) in fixed_world.column_iter_mut().zip(fixed.column_iter()) {
                    let v = turn * f.fixed_rows::<3>(0);
                    let w = turn * f.fixed_rows::<3>(3);
                    c.fixed_rows_mut::<3>(0).copy_from(&v);
                    c.fixed_rows_mut::<3>(3).copy_from(&w);
                }
                base_effect = base_effect.max((&j_star - &fixed_world).amax());
            }
            println!(
                "{} {mode:?}, base {} kg: max |J* - FD(simulation)| = {worst:.2e}, max |J* - J_fixed| = {base_effect:.3}",
                model.arm().name(),
                model.base().mass
            );
            assert!(worst < 1e-8, "{mode:?}: {worst:e}");
            assert!(base_effect > 0.05, "{mode:?}: {base_effect}");
        }
    }
}

#[test]
fn generalized_jacobian_tends_to_the_fixed_base_jacobian() {
    let arm = armkit::robots::space6r().unwrap();
    let mut arm_data = Data::new(&arm);
    let q = [0.4, 0.9, -0.7, 0.3, 0.8, -0.5];
    let fixed = jacobian(&arm, &mut arm_data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    for mode in MODES {
        let mut previous = f64::NAN;
        for k in 0..=8 {
            let scale = 10f64.powi(k);
            let mut base = space6r_base_body();
            base.mass *= scale;
            base.inertia *= scale;
            let model = FreeFloatingModel::new(base, arm.clone()).unwrap();
            let mut data = SpaceData::new(&model);
            // Base frame = inertial frame, mount = Tz(0.5): same axes as the arm's world.
            let j_star =
                generalized_jacobian(&model, &mut data, &Pose::identity(), &q, mode).unwrap();
            let error = (j_star - &fixed).amax();
            println!(
                "{mode:?}: base mass {:.0e} kg: max |J* - J_fixed| = {error:.3e}, x mass = {:.3e}",
                model.base().mass,
                error * model.base().mass
            );
            if k >= 4 {
                // O(1 / m0) once the base dominates (from 4e6 kg): ten times
                // the mass, a tenth of the difference.
                let ratio = previous / error;
                assert!((ratio - 10.0).abs() < 0.2, "{mode:?}: ratio {ratio}");
            }
            previous = error;
        }
        assert!(previous < 1e-7, "{mode:?}: {previous:e}");
    }
}

/// The states of a simulated random joint motion (`steps + 1` of them, `dt`
/// apart) and the largest distance of the centre of mass, recomputed from
/// scratch after every step, from where it started.
fn simulate_random_motion(
    model: &FreeFloatingModel,
    mode: BaseMode,
    start: &FreeFloatingState,
    dt: f64,
    steps: usize,
) -> (Vec<FreeFloatingState>, f64) {
    let mut data = SpaceData::new(model);
    let motion = SinusoidalJointMotion::random(6, 3, 0.8, 0.8).unwrap();
    let mut state = start.clone();
    let com = center_of_mass(model, &mut data, &state.base, &state.q).unwrap();
    let mut rates = [0.0; 6];
    let mut history = Vec::with_capacity(steps + 1);
    let mut com_drift: f64 = 0.0;
    history.push(state.clone());
    for k in 0..steps {
        motion.rates((k as f64 + 0.5) * dt, &mut rates);
        step(model, &mut data, &mut state, &rates, dt, mode).unwrap();
        let now = center_of_mass(model, &mut data, &state.base, &state.q).unwrap();
        com_drift = com_drift.max((now - com).norm());
        history.push(state.clone());
    }
    (history, com_drift)
}

/// Momentum of a simulated motion itself, from central differences of the
/// recorded states (every `stride`-th sample): the largest |P| and |L|, and
/// the largest |P| and |L| the same joint motion has with the base held still
/// (the scale).
fn differenced_momentum(
    model: &FreeFloatingModel,
    history: &[FreeFloatingState],
    dt: f64,
    stride: usize,
) -> [f64; 4] {
    let mut data = SpaceData::new(model);
    let mut worst = [0.0f64; 4];
    for k in (1..history.len() - 1).step_by(stride) {
        let (before, here, after) = (&history[k - 1], &history[k], &history[k + 1]);
        let q_dot: Vec<f64> = (0..6)
            .map(|j| (after.q[j] - before.q[j]) / (2.0 * dt))
            .collect();
        let relative = after.base.rotation * before.base.rotation.transpose();
        let w = Rotation3::from_matrix_unchecked(relative).scaled_axis() / (2.0 * dt);
        let v = (after.base.translation - before.base.translation) / (2.0 * dt);
        let twist = Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z);
        let moving = momentum(model, &mut data, &here.base, &here.q, &twist, &q_dot).unwrap();
        let held = momentum(
            model,
            &mut data,
            &here.base,
            &here.q,
            &Vector6::zeros(),
            &q_dot,
        )
        .unwrap();
        for (w, value) in worst.iter_mut().zip([
            moving.linear.norm(),
            moving.angular.norm(),
            held.linear.norm(),
            held.angular.norm(),
        ]) {
            *w = w.max(value);
        }
    }
    worst
}

fn random_motion_start() -> FreeFloatingState {
    FreeFloatingState::new(
        Pose::from_xyz_rpy([0.2, -0.1, 0.3], [0.1, 0.2, 0.3]),
        vec![0.3, 0.6, -0.9, 0.4, 0.7, -0.2],
    )
}

/// Long random joint motion (100 s, 5000 steps): the centre of mass stays
/// put, the attitude is held exactly in the held mode, and the simulated
/// motion (differentiated numerically) has zero linear momentum, and zero
/// angular momentum in the free mode.
#[test]
fn long_random_motion_keeps_the_centre_of_mass_and_zero_momentum() {
    let model = lopsided_model();
    let start = random_motion_start();
    let (dt, steps) = (0.02, 5_000);
    for mode in MODES {
        let (history, com_drift) = simulate_random_motion(&model, mode, &start, dt, steps);
        let state = history.last().unwrap();
        let base_travel = (state.base.translation - start.base.translation).norm();
        let turn = rotation_angle(&(state.base.rotation * start.base.rotation.transpose()));
        let [p, l, held_p, held_l] = differenced_momentum(&model, &history, dt, 25);
        println!(
            "{mode:?}: {steps} steps of {dt} s: COM drift {com_drift:.2e} m, base moved {base_travel:.3} m \
             and turned {turn:.3} rad; momentum of the simulated motion (central differences): \
             |P| max {p:.2e} kg m/s (held base: {held_p:.2e}), |L| max {l:.2e} kg m^2/s \
             (held base: {held_l:.2e})"
        );
        assert!(com_drift < 1e-9, "{mode:?}: COM drift {com_drift:e}");
        assert!(base_travel > 0.01);
        assert!(p < 1e-3 * held_p, "{p:e} vs {held_p:e}");
        match mode {
            BaseMode::AttitudeHeld => assert_eq!(state.base.rotation, start.base.rotation),
            BaseMode::FreeFloating => {
                assert!(turn > 0.01);
                assert!(l < 1e-3 * held_l, "{l:e} vs {held_l:e}");
                let r = state.base.rotation;
                assert!((r.transpose() * r - Matrix3::identity()).amax() < 1e-14);
            }
        }
    }
}

/// What is left of |L| in the free mode is the error of the central
/// differences used to measure it, not a drift of the simulation: halving
/// the step divides it by about 4 (second order), over the same 20 s motion.
#[test]
fn residual_angular_momentum_is_differentiation_error() {
    let model = lopsided_model();
    let start = random_motion_start();
    let mut residuals = Vec::new();
    for (dt, steps) in [(0.04, 500), (0.02, 1000), (0.01, 2000)] {
        let (history, _) =
            simulate_random_motion(&model, BaseMode::FreeFloating, &start, dt, steps);
        let [_, l, _, held_l] = differenced_momentum(&model, &history, dt, 1);
        println!(
            "dt = {dt} s: max |L| {l:.3e} kg m^2/s, relative {:.3e}",
            l / held_l
        );
        residuals.push(l);
    }
    for pair in residuals.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!(ratio > 3.5 && ratio < 4.5, "ratio {ratio}");
    }
}

/// The free-floating attitude integrator is fourth order: with constant joint
/// rates (so that every step size follows the same joint path), halving the
/// step divides the attitude error by about 16.
#[test]
fn free_floating_attitude_integration_is_fourth_order() {
    let model = lopsided_model();
    let mut data = SpaceData::new(&model);
    let rates = [0.8, -0.6, 1.0, 1.2, -1.0, 0.8];
    let start = FreeFloatingState::new(Pose::identity(), vec![0.3, 0.6, -0.9, 0.4, 0.7, -0.2]);
    let duration = 2.0;
    let run = |data: &mut SpaceData, steps: usize| {
        let mut state = start.clone();
        for _ in 0..steps {
            step(
                &model,
                data,
                &mut state,
                &rates,
                duration / steps as f64,
                BaseMode::FreeFloating,
            )
            .unwrap();
        }
        state
    };
    let reference = run(&mut data, 1280);
    let mut errors = Vec::new();
    for steps in [5, 10, 20, 40] {
        let state = run(&mut data, steps);
        let error = rotation_angle(&(state.base.rotation * reference.base.rotation.transpose()));
        let position = (state.base.translation - reference.base.translation).norm();
        println!(
            "dt = {:.4} s: attitude error {error:.3e} rad, base position error {position:.3e} m",
            duration / steps as f64
        );
        errors.push(error);
    }
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!(ratio > 13.0 && ratio < 19.0, "order ratio {ratio}");
    }
    let total_turn = rotation_angle(&reference.base.rotation);
    assert!(total_turn > 0.05, "{total_turn}");
}

/// Resolved-rate tracking with `J*` follows a straight-line pose path while
/// the base drifts; the error left by each period is second order in the
/// period (halving `dt` divides it by about 4).
#[test]
fn resolved_rate_tracking_follows_a_straight_line() {
    let model = space6r_free_floating().unwrap();
    let mut data = SpaceData::new(&model);
    let q0 = vec![0.3, 0.8, -0.6, 0.4, 0.9, -0.3];
    for mode in MODES {
        let initial = FreeFloatingState::new(Pose::identity(), q0.clone());
        let start = end_effector_pose(&model, &mut data, &initial.base, &initial.q).unwrap();
        let shift = Vector3::new(0.15, -0.10, 0.08);
        let turn = Vector3::new(0.0, 0.2, 0.3);
        let duration = 8.0;
        let path = |t: f64| {
            let tau = (t / duration).clamp(0.0, 1.0);
            let s = tau * tau * (3.0 - 2.0 * tau);
            Pose::new(
                Rotation3::from_scaled_axis(turn * s).into_inner() * start.rotation,
                start.translation + shift * s,
            )
        };
        let mut errors = Vec::new();
        for dt in [0.01, 0.005] {
            let options = TrackingOptions {
                dt,
                ..Default::default()
            };
            let report = track_pose_path(
                &model,
                &mut data,
                mode,
                &initial,
                &TimeFn::new(duration, path).unwrap(),
                LeastSquares { damping: 0.0 },
                &options,
            )
            .unwrap();
            assert_eq!(report.status, TrackingStatus::Completed);
            assert_eq!(report.samples.len(), (duration / dt).round() as usize + 1);
            let last = report.samples.last().unwrap();
            let base_motion = last.base.translation.norm();
            println!(
                "{mode:?}, dt = {dt} s: max position error {:.2e} m, max orientation error {:.2e} rad, base moved {:.4} m",
                report.max_position_error, report.max_orientation_error, base_motion
            );
            assert!(base_motion > 0.005, "{base_motion}");
            assert!((last.end_effector.translation - path(duration).translation).norm() < 1e-4);
            errors.push(report.max_position_error.max(report.max_orientation_error));
        }
        assert!(errors[0] < 1e-4, "{mode:?}: {errors:?}");
        let ratio = errors[0] / errors[1];
        assert!(ratio > 3.0 && ratio < 5.0, "{mode:?}: ratio {ratio}");
    }
}
