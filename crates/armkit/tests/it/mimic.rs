//! Mimic joints: the configuration holds the independent joints,
//! forward kinematics expands it, the Jacobian folds mimic columns into their
//! leaders' (checked against finite differences of FK and against `J0 M`),
//! limits bound leaders through the map, and IK, a trajectory and the MPC
//! on a chain with mimic joints keep every mimic joint within its own limits.
//! Bad input is an error naming the joint.

use crate::common::*;
use armkit::ik::{IkOptions, IkSolver};
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Matrix6xX, Pose};
use armkit::model::{CouplingLaw, JointKind, JointSpec, MimicJoint, ModelBuilder};
use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights};
use armkit::trajectory::JointState;
use armkit::trajectory::TrajectoryLimits;
use armkit::trajectory::{minimum_time, ProfileShape};
use armkit::urdf::{load, parse_str, ChainSelection};
use armkit::Model;

fn mimicbot_text() -> String {
    std::fs::read_to_string(data_path("urdf/mimicbot.urdf")).unwrap()
}

/// base -> fingertip: 6 arm joints, the knuckle, and two mimic joints.
fn finger() -> Model {
    load(
        data_path("urdf/mimicbot.urdf"),
        &ChainSelection::between("base", "fingertip"),
    )
    .unwrap()
}

/// base -> finger_b_tip: 6 arm joints and finger_b, which follows finger_a
/// (off the chain).
fn gripper() -> Model {
    load(
        data_path("urdf/mimicbot.urdf"),
        &ChainSelection::between("base", "finger_b_tip"),
    )
    .unwrap()
}

/// The same chain with every `<mimic>` removed: all joints independent.
fn expanded(tip: &str) -> Model {
    let text = mimicbot_text();
    let mut stripped = String::new();
    for line in text.lines() {
        if !line.trim_start().starts_with("<mimic") {
            stripped.push_str(line);
            stripped.push('\n');
        }
    }
    parse_str(&stripped, "stripped", &ChainSelection::between("base", tip)).unwrap()
}

fn names(joints: &[armkit::model::Joint]) -> Vec<&str> {
    joints.iter().map(|j| j.name.as_str()).collect()
}

#[test]
fn the_configuration_holds_the_independent_joints() {
    let finger = finger();
    assert_eq!(finger.dof(), 7);
    assert_eq!(finger.chain_joints().len(), 9);
    assert_eq!(
        names(finger.joints()),
        [
            "shoulder_pan",
            "shoulder_lift",
            "elbow",
            "wrist_1",
            "wrist_2",
            "wrist_3",
            "knuckle"
        ]
    );
    assert_eq!(
        names(&finger.chain_joints()[6..]),
        ["knuckle", "middle_joint", "distal_joint"]
    );
    // distal mimics middle mimics knuckle: resolved to the knuckle,
    // q_distal = -1.2 (0.8 q + 0.1) = -0.96 q - 0.12.
    let couplings = finger.couplings();
    assert_eq!(couplings.len(), 2);
    let law = |i: usize| match couplings[i].law {
        CouplingLaw::Mimic { multiplier, offset } => {
            (couplings[i].source, couplings[i].target, multiplier, offset)
        }
        CouplingLaw::Additive(_) => panic!("not a mimic"),
    };
    assert_eq!(law(0), (6, 7, 0.8, 0.1));
    let (source, target, m, o) = law(1);
    assert_eq!((source, target), (6, 8));
    assert!(
        (m + 0.96).abs() < 1e-15 && (o + 0.12).abs() < 1e-15,
        "{m} {o}"
    );

    let gripper = gripper();
    assert_eq!(gripper.dof(), 7);
    assert_eq!(gripper.joints()[6].name, "finger_a_joint");
    assert_eq!(gripper.joints()[6].kind, JointKind::Prismatic);
    assert_eq!(gripper.chain_joints()[6].name, "finger_b_joint");
    // The off-chain leader moves no body of the chain.
    assert!(gripper.joints()[6].inertia.is_none());
    assert!(gripper.chain_joints()[6].inertia.is_some());
}

#[test]
fn mimic_limits_bound_the_leader_and_the_tighter_bound_wins() {
    let finger = finger();
    let knuckle = finger.joints()[6].limits;
    // own [-0.3, 1.6]; middle: 0.8 q + 0.1 in [-0.2, 1.2] -> q in
    // [-0.375, 1.375]; distal: -0.96 q - 0.12 in [-0.5, 0.9] -> q in
    // [-1.0625, 0.3958333].
    assert_eq!(knuckle.lower, -0.3);
    assert!(
        (knuckle.upper - 0.38 / 0.96).abs() < 1e-15,
        "{}",
        knuckle.upper
    );
    // Speeds: 3 own, 3 / 0.8 middle, 2 / 0.96 distal.
    assert!((knuckle.velocity.unwrap() - 2.0 / 0.96).abs() < 1e-15);
    let gripper = gripper();
    let finger_a = gripper.joints()[6].limits;
    // 0.75 q + 0.002 in [0, 0.03] -> q in [-0.00267, 0.0373]; own [0, 0.04].
    assert_eq!(finger_a.lower, 0.0);
    assert!((finger_a.upper - 0.028 / 0.75).abs() < 1e-15);
    assert_eq!(finger_a.velocity, Some(0.2));
    // At the leader's bounds every mimic joint is within its own limits,
    // exactly (the bounds are nudged inward past round-off).
    for model in [&finger, &gripper] {
        let mut chain = vec![0.0; model.chain_joints().len()];
        let (lower, upper) = model.position_limits();
        for q in [lower, upper] {
            let q: Vec<f64> = q
                .iter()
                .map(|v| if v.is_finite() { *v } else { 0.0 })
                .collect();
            model.chain_positions(&q, &mut chain).unwrap();
            for (joint, value) in model.chain_joints().iter().zip(&chain) {
                assert!(joint.limits.contains(*value), "{}: {value}", joint.name);
            }
        }
    }
}

#[test]
fn fk_expands_the_configuration_and_the_jacobian_is_j0_m() {
    let mut rng = rng(20);
    for (model, tip) in [(finger(), "fingertip"), (gripper(), "finger_b_tip")] {
        let full = expanded(tip);
        assert_eq!(full.dof(), model.chain_joints().len());
        let mut data = Data::new(&model);
        let mut full_data = Data::new(&full);
        let mut chain = vec![0.0; full.dof()];
        for _ in 0..100 {
            let q = random_configuration(&model, &mut rng);
            model.chain_positions(&q, &mut chain).unwrap();
            let pose = *forward_kinematics(&model, &mut data, &q).unwrap();
            assert_eq!(data.effective_positions(), chain.as_slice());
            let full_pose = *forward_kinematics(&full, &mut full_data, &chain).unwrap();
            assert_eq!(pose, full_pose, "{tip} {q:?}");
            // M = d q_chain / d q: one 1 per independent chain joint, the
            // multiplier in a mimic joint's row at its leader's column.
            let mut m = armkit::math::DMatrix::<f64>::zeros(full.dof(), model.dof());
            for (j, joint) in model.chain_joints().iter().enumerate() {
                match model.couplings().iter().find(|c| c.target == j) {
                    Some(c) => m[(j, c.source)] = c.law.offset_and_slope(0.0).1,
                    None => {
                        let i = model
                            .joints()
                            .iter()
                            .position(|k| k.name == joint.name)
                            .unwrap();
                        m[(j, i)] = 1.0;
                    }
                }
            }
            for frame in [JacobianFrame::World, JacobianFrame::EndEffector] {
                let j = jacobian(&model, &mut data, &q, frame).unwrap().clone();
                let j0 = jacobian(&full, &mut full_data, &chain, frame).unwrap();
                let expected: Matrix6xX<f64> = j0 * &m;
                assert!((&j - &expected).amax() < 1e-15, "{tip} {frame:?}");
            }
        }
    }
}

#[test]
fn the_mimic_jacobian_matches_finite_differences_of_fk_in_the_independent_joints() {
    let mut rng = rng(21);
    for model in [finger(), gripper()] {
        let mut data = Data::new(&model);
        let mut worst = 0.0f64;
        for _ in 0..100 {
            let q = random_configuration(&model, &mut rng);
            let analytic = jacobian(&model, &mut data, &q, JacobianFrame::World)
                .unwrap()
                .clone();
            let numeric = finite_difference_jacobian(&model, &q, 1e-6);
            worst = worst.max((&analytic - &numeric).amax());
        }
        assert!(worst < 1e-8, "{}: |J - J_fd| = {worst:e}", model.name());
    }
}

#[test]
fn ik_on_the_finger_chain_is_verified_by_fk_and_keeps_mimic_limits() {
    let model = finger();
    let mut data = Data::new(&model);
    let mut rng = rng(22);
    let mut solver = IkSolver::new(&model, IkOptions::default()).unwrap();
    let mut chain = vec![0.0; model.chain_joints().len()];
    let mut converged = 0;
    for _ in 0..20 {
        let goal_q = random_configuration(&model, &mut rng);
        let target = *forward_kinematics(&model, &mut data, &goal_q).unwrap();
        let start = model.neutral_configuration();
        let report = solver.solve(&target, &start).unwrap();
        if !report.converged() {
            continue;
        }
        converged += 1;
        let reached = *forward_kinematics(&model, &mut data, &report.q).unwrap();
        assert!((reached.translation - target.translation).norm() < 1e-6);
        assert!(armkit::ik::orientation_error(&reached.rotation, &target.rotation).norm() < 1e-6);
        model.check_limits(&report.q).unwrap();
        model.chain_positions(&report.q, &mut chain).unwrap();
        for (joint, value) in model.chain_joints().iter().zip(&chain) {
            assert!(joint.limits.contains(*value), "{}: {value}", joint.name);
        }
    }
    assert!(converged >= 18, "{converged} of 20 converged");
}

/// Every mimic joint's position within its own limits along `positions`.
fn assert_mimic_joints_within_limits(model: &Model, positions: &[f64], context: &str) {
    let mut chain = vec![0.0; model.chain_joints().len()];
    model.chain_positions(positions, &mut chain).unwrap();
    for (joint, value) in model.chain_joints().iter().zip(&chain) {
        assert!(
            joint.limits.contains(*value),
            "{context}: {} at {value} outside [{}, {}]",
            joint.name,
            joint.limits.lower,
            joint.limits.upper
        );
    }
}

#[test]
fn a_trajectory_between_limit_configurations_keeps_mimic_joints_within_their_limits() {
    let model = finger();
    let limits = TrajectoryLimits::from_model(&model);
    let (lower, upper) = model.position_limits();
    let clip = |v: f64| v.clamp(-3.0, 3.0);
    // From every joint at its lower bound to every joint at its upper bound:
    // the knuckle sweeps its whole (tightened) range.
    let q0: Vec<f64> = lower.iter().map(|v| clip(*v)).collect();
    let qf: Vec<f64> = upper.iter().map(|v| clip(*v)).collect();
    for shape in [ProfileShape::Cubic, ProfileShape::Quintic] {
        let trajectory = minimum_time(shape, &q0, &qf, &limits).unwrap();
        let mut state = JointState::new(vec![0.0; 7], vec![0.0; 7], vec![0.0; 7]);
        let mut chain_speeds = vec![0.0; model.chain_joints().len()];
        for k in 0..=400 {
            let t = trajectory.start_time() + trajectory.duration() * k as f64 / 400.0;
            trajectory.sample_into(t, &mut state).unwrap();
            assert_mimic_joints_within_limits(
                &model,
                &state.position,
                &format!("{shape:?} t = {t}"),
            );
            // Velocities map with the multipliers: within each mimic
            // joint's own speed limit too.
            model
                .chain_positions(&state.velocity, &mut chain_speeds)
                .unwrap();
            for c in model.couplings() {
                let (_, multiplier) = c.law.offset_and_slope(0.0);
                let speed = (multiplier * state.velocity[c.source]).abs();
                let joint = &model.chain_joints()[c.target];
                assert!(
                    speed <= joint.limits.velocity.unwrap() * (1.0 + 1e-12),
                    "{}: {speed}",
                    joint.name
                );
            }
        }
    }
}

#[test]
fn an_mpc_run_never_moves_a_mimic_joint_past_its_limits() {
    // The finger alone (palm to fingertip): one independent joint, the
    // knuckle, and its two mimic joints. The target is the fingertip where
    // knuckle = 1.0 would put it on a finger without mimic limits, past the
    // bound (0.396) the distal joint sets: the planner must press against
    // that bound and stop there.
    let model = load(
        data_path("urdf/mimicbot.urdf"),
        &ChainSelection::between("palm", "fingertip"),
    )
    .unwrap();
    assert_eq!(model.dof(), 1);
    let text = mimicbot_text()
        .replace("<mimic", "<!-- mimic")
        .replace("multiplier=\"0.8\" offset=\"0.1\"/>", "-->")
        .replace("multiplier=\"-1.2\"/>", "-->")
        .replace("offset=\"0.002\"/>", "-->");
    let full = parse_str(
        &text,
        "stripped",
        &ChainSelection::between("palm", "fingertip"),
    )
    .unwrap();
    assert_eq!(full.dof(), 3);
    let mut far = vec![0.0; 3];
    model.chain_positions(&[1.0], &mut far).unwrap();
    let target = *forward_kinematics(&full, &mut Data::new(&full), &far).unwrap();
    let options = MpcOptions {
        task_weights: TaskWeights::position_only(10.0, 200.0),
        ..MpcOptions::default()
    };
    let sample_time = options.sample_time;
    let mut planner = MpcPlanner::new(&model, options).unwrap();
    planner.set_target(&target).unwrap();
    let mut q = vec![0.0];
    let upper = model.joints()[0].limits.upper;
    let mut first_at_bound = None;
    for step in 0..200 {
        let report = planner.step(&q).unwrap();
        assert!(report.status.is_ok(), "step {step}: {:?}", report.status);
        q[0] += sample_time * report.velocity[0];
        assert_mimic_joints_within_limits(&model, &q, &format!("step {step}"));
        if first_at_bound.is_none() && upper - q[0] < 1e-9 {
            first_at_bound = Some(step);
        }
    }
    // The knuckle reached the bound its distal joint sets and stayed there.
    assert!(
        first_at_bound.is_some(),
        "knuckle at {} (bound {upper})",
        q[0]
    );
    assert!(upper - q[0] < 1e-9, "knuckle at {}", q[0]);
}

fn parse_error(text: &str, selection: &ChainSelection) -> String {
    parse_str(text, "test.urdf", selection)
        .unwrap_err()
        .to_string()
}

fn two_revolute(second_mimic: &str, extra: &str) -> String {
    format!(
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><link name=\"d\"/>\n\
         <joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/></joint>\n\
         <joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/>{second_mimic}</joint>\n\
         {extra}</robot>"
    )
}

#[test]
fn bad_mimic_joints_are_errors_naming_the_joint() {
    let chain = ChainSelection::between("a", "c");
    // Leader missing.
    assert_eq!(
        parse_error(&two_revolute("<mimic joint=\"ghost\"/>", ""), &chain),
        "test.urdf: joint `j2` (line 3): <mimic joint=\"ghost\">: the file has no joint named `ghost` (a mimic joint follows an existing joint)"
    );
    // Non-finite multiplier and offset.
    let text = parse_error(
        &two_revolute("<mimic joint=\"j1\" multiplier=\"inf\"/>", ""),
        &chain,
    );
    assert!(
        text.contains("mimic joint `j2`: the multiplier must be finite, got inf"),
        "{text}"
    );
    let text = parse_error(
        &two_revolute("<mimic joint=\"j1\" offset=\"nan\"/>", ""),
        &chain,
    );
    assert!(
        text.contains("mimic joint `j2`: the offset must be finite, got NaN"),
        "{text}"
    );
    // A cycle: j2 -> j3 -> j4 -> j3, j3 and j4 off the chain.
    let extra = "<link name=\"e\"/><link name=\"f\"/>\
        <joint name=\"j3\" type=\"revolute\"><parent link=\"a\"/><child link=\"e\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/><mimic joint=\"j4\"/></joint>\
        <joint name=\"j4\" type=\"revolute\"><parent link=\"a\"/><child link=\"f\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/><mimic joint=\"j3\"/></joint>";
    let text = parse_error(&two_revolute("<mimic joint=\"j3\"/>", extra), &chain);
    assert!(
        text.contains("mimic joint `j2`: the mimic joints form a cycle (`j3` -> `j4` -> `j3`)"),
        "{text}"
    );
    // A joint that mimics itself.
    let text = parse_error(&two_revolute("<mimic joint=\"j2\"/>", ""), &chain);
    assert!(text.contains("form a cycle (`j2` -> `j2`)"), "{text}");
    // A fixed leader.
    let extra = "<link name=\"e\"/><joint name=\"weld\" type=\"fixed\"><parent link=\"a\"/><child link=\"e\"/></joint>";
    let text = parse_error(&two_revolute("<mimic joint=\"weld\"/>", extra), &chain);
    assert!(
        text.contains("joint `j2` (line 3) mimics joint `weld` (line 4), which is fixed"),
        "{text}"
    );
    // Limits that leave the leader no range: j2 = j1 + 3 within [-1, 1].
    let text = parse_error(
        &two_revolute("<mimic joint=\"j1\" offset=\"3\"/>", ""),
        &chain,
    );
    assert!(
        text.contains("the limits of the mimic joints `j2` leave their leader `j1`"),
        "{text}"
    );
}

#[test]
fn the_builder_checks_mimic_declarations() {
    let base = || {
        ModelBuilder::new("m")
            .joint(JointSpec::revolute("a", -1.0, 1.0))
            .joint(JointSpec::prismatic("b", 0.0, 0.1).with_origin(Pose::trans_x(0.1)))
    };
    let err = |builder: ModelBuilder| builder.build().unwrap_err().to_string();
    assert!(
        err(base().mimic(MimicJoint::new("zz", "a", 1.0, 0.0))).contains(
            "mimic joint `zz`: declared as a mimic joint, but the model has no joint of that name"
        )
    );
    assert!(err(base().mimic(MimicJoint::new("b", "a", f64::NAN, 0.0)))
        .contains("mimic joint `b`: the multiplier must be finite"));
    assert!(err(base()
        .mimic(MimicJoint::new("b", "a", 1.0, 0.0))
        .mimic(MimicJoint::new("b", "a", 2.0, 0.0)))
    .contains("declared as a mimic joint twice"));
    assert!(err(base().mimic(MimicJoint::new("b", "a", 0.0, 0.5)))
        .contains("multiplier 0 holds it at its offset 0.5, outside its limits [0, 0.1]"));
    // A continuous leader bounded through its follower stops wrapping.
    let model = ModelBuilder::new("m")
        .joint(JointSpec::continuous("spin"))
        .joint(JointSpec::revolute("follow", -1.0, 1.0).with_origin(Pose::trans_x(0.1)))
        .mimic(MimicJoint::new("follow", "spin", -2.0, 0.0))
        .build()
        .unwrap();
    assert_eq!(model.joints()[0].kind, JointKind::Revolute);
    assert_eq!(model.position_limits(), (vec![-0.5], vec![0.5]));
    // A mimic coupling cannot be added to a built model, and an additive
    // coupling cannot drive a mimic joint.
    let coupling = armkit::model::JointCoupling {
        source: 0,
        target: 1,
        law: CouplingLaw::Mimic {
            multiplier: 1.0,
            offset: 0.0,
        },
    };
    assert!(model
        .with_coupling(Some(coupling))
        .unwrap_err()
        .to_string()
        .contains("declared with ModelBuilder::mimic"));
}

#[test]
fn chain_forces_fold_onto_the_leaders() {
    // tau = M' tau0: the power tau0 . dq_chain equals tau . dq.
    let model = finger();
    let mut rng = rng(23);
    let q = random_configuration(&model, &mut rng);
    let tau0: Vec<f64> = (0..9).map(|i| 0.3 * i as f64 - 1.0).collect();
    let mut tau = vec![0.0; 7];
    model.fold_chain_forces(&q, &tau0, &mut tau).unwrap();
    let dq: Vec<f64> = (0..7).map(|i| 0.1 + 0.05 * i as f64).collect();
    // q_chain is affine in q here: dq_chain = M dq.
    let mut a = vec![0.0; 9];
    let mut b = vec![0.0; 9];
    let shifted: Vec<f64> = q.iter().zip(&dq).map(|(x, d)| x + d).collect();
    model.chain_positions(&q, &mut a).unwrap();
    model.chain_positions(&shifted, &mut b).unwrap();
    let power0: f64 = tau0
        .iter()
        .zip(a.iter().zip(&b))
        .map(|(t, (x, y))| t * (y - x))
        .sum();
    let power: f64 = tau.iter().zip(&dq).map(|(t, d)| t * d).sum();
    assert!((power0 - power).abs() < 1e-12, "{power0} vs {power}");
    assert!(model.fold_chain_forces(&q, &tau0[..8], &mut tau).is_err());
}

#[test]
fn gravity_torques_refuse_mimic_joints_rather_than_mispair_frames() {
    let model = finger();
    let mut data = Data::new(&model);
    let q = model.neutral_configuration();
    let mut torques = vec![0.0; model.dof()];
    let err = armkit::redundancy::gravity_torques(
        &model,
        &mut data,
        &q,
        &armkit::math::Vector3::new(0.0, 0.0, -9.81),
        &mut torques,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("mimic joints"), "{err}");
}
