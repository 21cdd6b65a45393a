//! Redundancy resolution: seed 001's partitioned form against the weighted
//! least norm, optimality, locking and priorities, energy weights, null-space
//! objectives, the tracking loop, and the four-way comparison on gantry9.

use crate::common;

use std::f64::consts::PI;

use armkit::ik::pose_error;
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::linalg::manipulability;
use armkit::math::{DMatrix, DVector, Matrix6xX, Pose, Vector3, Vector6};
use armkit::model::{DhConvention, DhLink, Model};
use armkit::redundancy::{
    best_partition, compare_distributions, energy_measure, gravity_torques, joint_torques,
    ComparisonCase, Damping, Distribution, DistributionOptions, Formulation, JointWeights, Load,
    Partition, PartitionedSolver, ResolvedRateTracker, SecondaryObjective, SolverOptions,
    TorqueFloor, WeightedLeastNorm, SEED000_PRIORITY_WEIGHTS,
};
use armkit::redundancy::{joint_limit_cost, joint_limit_gradient, SecondaryTask};
use armkit::tracking::{TrackingOptions, TrackingStatus};
use armkit::trajectory::{CartesianTrajectory, TimeLaw};
use rand::seq::SliceRandom;
use rand::Rng;

/// A random serial robot with `dof` joints (about one in five prismatic),
/// standard DH, lengths in [-0.5, 0.5] m, twists in [-pi, pi].
fn random_robot(dof: usize, rng: &mut impl Rng) -> Model {
    let links: Vec<DhLink> = (0..dof)
        .map(|_| {
            let a = rng.gen_range(-0.5..0.5);
            let alpha = rng.gen_range(-PI..PI);
            if rng.gen_bool(0.2) {
                DhLink::prismatic(rng.gen_range(-PI..PI), a, alpha).with_limits(-1.0, 1.0)
            } else {
                DhLink::revolute(rng.gen_range(-0.5..0.5), a, alpha)
            }
        })
        .collect();
    Model::from_dh("random", DhConvention::Standard, &links).unwrap()
}

/// Log-uniform random weights in [0.01, 100].
fn random_weights(dof: usize, rng: &mut impl Rng) -> JointWeights {
    let values: Vec<f64> = (0..dof)
        .map(|_| 10f64.powf(rng.gen_range(-2.0..2.0)))
        .collect();
    JointWeights::new(&values).unwrap()
}

fn random_twist(rng: &mut impl Rng) -> Vector6<f64> {
    Vector6::from_fn(|_, _| rng.gen_range(-1.0..1.0))
}

/// A random robot, configuration, Jacobian with a reasonably conditioned
/// 6-column block for a random partition.
struct Case {
    jacobian: Matrix6xX<f64>,
    weights: JointWeights,
    twist: Vector6<f64>,
    partition: Partition,
}

fn random_case(rng: &mut impl Rng) -> Case {
    loop {
        let dof = rng.gen_range(7..=10);
        let model = random_robot(dof, rng);
        let q = common::random_configuration(&model, rng);
        let mut data = Data::new(&model);
        let jacobian = jacobian(&model, &mut data, &q, JacobianFrame::World)
            .unwrap()
            .clone();
        let mut joints: Vec<usize> = (0..dof).collect();
        joints.shuffle(rng);
        let generalized = [
            joints[0], joints[1], joints[2], joints[3], joints[4], joints[5],
        ];
        let partition = Partition::new(dof, generalized).unwrap();
        let block = DMatrix::from_fn(6, 6, |r, c| jacobian[(r, partition.generalized()[c])]);
        let sv = block.singular_values();
        // Keep partitions whose block is invertible to a meaningful accuracy:
        // the test compares two solvers to 1e-9.
        if sv.min() > 1e-3 * sv.max() {
            return Case {
                jacobian,
                weights: random_weights(dof, rng),
                twist: random_twist(rng),
                partition,
            };
        }
    }
}

fn as_dvector(values: &[f64]) -> DVector<f64> {
    DVector::from_column_slice(values)
}

#[test]
fn partitioned_form_equals_weighted_least_norm_for_random_robots() {
    let mut rng = common::rng(5001);
    let mut worst: f64 = 0.0;
    for _ in 0..300 {
        let case = random_case(&mut rng);
        let dof = case.jacobian.ncols();
        let mut least_norm = WeightedLeastNorm::new(dof, SolverOptions::default()).unwrap();
        let mut partitioned = PartitionedSolver::new(dof, 1e10).unwrap();
        let a = least_norm
            .solve(&case.jacobian, &case.weights, &case.twist)
            .unwrap()
            .solved()
            .unwrap()
            .to_vec();
        let b = partitioned
            .solve(&case.jacobian, &case.weights, &case.twist, &case.partition)
            .unwrap()
            .to_vec();
        let scale = a.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        worst = worst.max(common::max_abs_difference(&a, &b) / scale);
        // Both meet the twist.
        let residual = (&case.jacobian * as_dvector(&b) - case.twist).amax();
        assert!(residual < 1e-10, "partitioned J q_dot - V = {residual:e}");
    }
    assert!(
        worst < 1e-9,
        "partitioned vs weighted least norm: {worst:e}"
    );
}

#[test]
fn unit_weights_give_the_pseudo_inverse() {
    let mut rng = common::rng(5002);
    for _ in 0..100 {
        let case = random_case(&mut rng);
        let dof = case.jacobian.ncols();
        let unit = JointWeights::uniform(dof);
        let j = DMatrix::from_fn(6, dof, |r, c| case.jacobian[(r, c)]);
        let pinv = j.clone().pseudo_inverse(1e-12).unwrap();
        let expected = &pinv * DVector::from_column_slice(case.twist.as_slice());
        let mut least_norm = WeightedLeastNorm::new(dof, SolverOptions::default()).unwrap();
        let mut partitioned = PartitionedSolver::new(dof, 1e10).unwrap();
        let a = least_norm
            .solve(&case.jacobian, &unit, &case.twist)
            .unwrap()
            .solved()
            .unwrap()
            .to_vec();
        let b = partitioned
            .solve(&case.jacobian, &unit, &case.twist, &case.partition)
            .unwrap()
            .to_vec();
        let scale = expected.amax().max(1.0);
        assert!(common::max_abs_difference(&a, expected.as_slice()) < 1e-9 * scale);
        assert!(common::max_abs_difference(&b, expected.as_slice()) < 1e-9 * scale);
    }
}

#[test]
fn weighted_solution_is_optimal_and_exact() {
    let mut rng = common::rng(5003);
    for _ in 0..200 {
        let case = random_case(&mut rng);
        let dof = case.jacobian.ncols();
        let mut solver = WeightedLeastNorm::new(dof, SolverOptions::default()).unwrap();
        let q_dot = solver
            .solve(&case.jacobian, &case.weights, &case.twist)
            .unwrap()
            .solved()
            .unwrap()
            .to_vec();
        let residual = (&case.jacobian * as_dvector(&q_dot) - case.twist).amax();
        assert!(residual < 1e-10, "J q_dot - V = {residual:e}");
        let projector = solver
            .null_space_projector(&case.jacobian, &case.weights)
            .unwrap()
            .solved()
            .unwrap()
            .clone();
        let jn = (&case.jacobian * &projector).amax();
        assert!(jn < 1e-10, "J N = {jn:e}");
        // N is a projector: N N = N.
        assert!((&projector * &projector - &projector).amax() < 1e-9);
        let best = case.weights.cost(&q_dot).unwrap();
        for _ in 0..10 {
            let delta = DVector::from_fn(dof, |_, _| rng.gen_range(-1.0..1.0));
            let motion = &projector * delta;
            let perturbed = as_dvector(&q_dot) + &motion;
            // Still a solution ...
            assert!((&case.jacobian * &perturbed - case.twist).amax() < 1e-9);
            // ... and dearer by exactly the cost of the null-space motion
            // (the cross term vanishes at the optimum).
            let cost = case.weights.cost(perturbed.as_slice()).unwrap();
            let extra = case.weights.cost(motion.as_slice()).unwrap();
            assert!(extra > 0.0 && cost > best, "{cost} <= {best}");
            assert!(
                (cost - best - extra).abs() < 1e-9 * cost.max(1.0),
                "cross term {}",
                cost - best - extra
            );
        }
    }
}

#[test]
fn locked_joints_do_not_move_and_huge_weights_approach_locking() {
    let mut rng = common::rng(5004);
    for _ in 0..50 {
        let case = random_case(&mut rng);
        let dof = case.jacobian.ncols();
        let extra = case.partition.extra().to_vec();
        let locked_joint = extra[0];
        let locked = case.weights.clone().with_locked(&[locked_joint]).unwrap();
        let mut huge = case.weights.clone();
        huge.set(locked_joint, 1e14).unwrap();
        let mut solver = WeightedLeastNorm::new(dof, SolverOptions::default()).unwrap();
        let with_lock = solver
            .solve(&case.jacobian, &locked, &case.twist)
            .unwrap()
            .solved()
            .unwrap()
            .to_vec();
        assert_eq!(with_lock[locked_joint], 0.0);
        assert!((&case.jacobian * as_dvector(&with_lock) - case.twist).amax() < 1e-10);
        let with_huge = solver
            .solve(&case.jacobian, &huge, &case.twist)
            .unwrap()
            .solved()
            .unwrap()
            .to_vec();
        let scale = with_lock.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        assert!(common::max_abs_difference(&with_lock, &with_huge) < 1e-6 * scale);
        // The partitioned form agrees (the locked joint is an extra joint).
        let mut partitioned = PartitionedSolver::new(dof, 1e10).unwrap();
        let p = partitioned
            .solve(&case.jacobian, &locked, &case.twist, &case.partition)
            .unwrap()
            .to_vec();
        assert!(common::max_abs_difference(&with_lock, &p) < 1e-9 * scale);
        // Seed 001's "lock the k extra joints": q_dot = G0 V on the block.
        let all_extra = case.weights.clone().with_locked(&extra).unwrap();
        let p = partitioned
            .solve(&case.jacobian, &all_extra, &case.twist, &case.partition)
            .unwrap()
            .to_vec();
        let block = DMatrix::from_fn(6, 6, |r, c| {
            case.jacobian[(r, case.partition.generalized()[c])]
        });
        let direct = block
            .lu()
            .solve(&DVector::from_column_slice(case.twist.as_slice()))
            .unwrap();
        for (m, &joint) in case.partition.generalized().iter().enumerate() {
            assert!((p[joint] - direct[m]).abs() < 1e-9 * direct.amax().max(1.0));
        }
        for &joint in &extra {
            assert_eq!(p[joint], 0.0);
        }
    }
}

#[test]
fn a_larger_weight_never_moves_a_joint_more() {
    // Seed 000: a large weight is a low priority. The optimal value is
    // concave in a_j with derivative q_dot_j^2, so |q_dot_j| cannot grow.
    let mut rng = common::rng(5005);
    for _ in 0..50 {
        let case = random_case(&mut rng);
        let dof = case.jacobian.ncols();
        let joint = rng.gen_range(0..dof);
        let mut solver = WeightedLeastNorm::new(dof, SolverOptions::default()).unwrap();
        let mut weights = case.weights.clone();
        let mut previous = f64::INFINITY;
        for exponent in -3..=6 {
            weights.set(joint, 10f64.powi(exponent)).unwrap();
            let v = solver
                .solve(&case.jacobian, &weights, &case.twist)
                .unwrap()
                .solved()
                .unwrap()[joint]
                .abs();
            assert!(v <= previous * (1.0 + 1e-9) + 1e-12, "{v} > {previous}");
            previous = v;
        }
    }
}

#[test]
fn priority_levels_reproduce_seed_000_weights() {
    let w = JointWeights::from_priority_levels(&[2, 1, 1, 0, 0, 0, 0, 0, 0], 10.0).unwrap();
    for (a, b) in w.values().iter().zip(SEED000_PRIORITY_WEIGHTS) {
        assert!((a - b).abs() < 1e-12);
    }
    let err = JointWeights::from_priority_levels(&[1, 0], 1.0).unwrap_err();
    assert_eq!(
        err.to_string(),
        "invalid argument `ratio`: must be finite and > 1, got 1"
    );
}

#[test]
fn damped_solution_solves_the_regularised_problem() {
    let mut rng = common::rng(5006);
    for _ in 0..50 {
        let case = random_case(&mut rng);
        let dof = case.jacobian.ncols();
        let lambda = 0.3;
        let options = SolverOptions {
            damping: Damping::Constant(lambda),
            ..SolverOptions::default()
        };
        let mut solver = WeightedLeastNorm::new(dof, options).unwrap();
        let q_dot = as_dvector(
            solver
                .solve(&case.jacobian, &case.weights, &case.twist)
                .unwrap()
                .solved()
                .unwrap(),
        );
        assert_eq!(solver.last_damping(), lambda);
        // Normal equations of min |J q - V|^2 + lambda^2 q' A q:
        // (J'J + lambda^2 A) q = J'V.
        let j = DMatrix::from_fn(6, dof, |r, c| case.jacobian[(r, c)]);
        let a = DMatrix::from_diagonal(&as_dvector(case.weights.values()));
        let v = DVector::from_column_slice(case.twist.as_slice());
        let lhs = (j.transpose() * &j + a * (lambda * lambda)) * &q_dot;
        let rhs = j.transpose() * v;
        assert!((lhs - &rhs).amax() < 1e-9 * rhs.amax().max(1.0));
    }
}

#[test]
fn damping_keeps_velocities_bounded_at_a_singularity() {
    // Panda stretched straight up (q = 0, just outside joint 4's range):
    // joints 1, 3 and 5 share one vertical axis, the Jacobian has rank 5.
    let model = armkit::robots::by_name("panda").unwrap();
    let mut data = Data::new(&model);
    let q = [0.0; 7];
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let twist = Vector6::new(0.0, 0.0, 0.1, 0.0, 0.0, 0.0); // straight up: out of reach
    let weights = JointWeights::uniform(7);
    let mut exact = WeightedLeastNorm::new(7, SolverOptions::default()).unwrap();
    let err = exact.solve(&j, &weights, &twist).unwrap().to_string();
    assert!(err.contains("singular"), "{err}");
    let adaptive = SolverOptions {
        damping: Damping::Adaptive {
            threshold: 0.05,
            max: 0.1,
        },
        ..SolverOptions::default()
    };
    let mut damped = WeightedLeastNorm::new(7, adaptive).unwrap();
    let q_dot = damped
        .solve(&j, &weights, &twist)
        .unwrap()
        .solved()
        .unwrap()
        .to_vec();
    assert!(damped.last_damping() > 0.09, "{}", damped.last_damping());
    assert!(q_dot.iter().all(|v| v.abs() < 10.0), "{q_dot:?}");
    // Away from singularities the adaptive damping is exactly zero.
    let q = [0.1, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7];
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let a = damped
        .solve(&j, &weights, &twist)
        .unwrap()
        .solved()
        .unwrap()
        .to_vec();
    assert_eq!(damped.last_damping(), 0.0);
    let b = exact
        .solve(&j, &weights, &twist)
        .unwrap()
        .solved()
        .unwrap()
        .to_vec();
    assert!(common::max_abs_difference(&a, &b) < 1e-14);
}

#[test]
fn best_partition_is_the_best_conditioned_block() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let mut rng = common::rng(5007);
    for _ in 0..5 {
        let q = common::random_configuration(&model, &mut rng);
        let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
            .unwrap()
            .clone();
        let choice = best_partition(&j, None, 1e10).unwrap();
        // Brute force over the 84 blocks.
        let mut best = f64::INFINITY;
        for mask in 0u32..512 {
            if mask.count_ones() != 6 {
                continue;
            }
            let columns: Vec<usize> = (0..9).filter(|c| mask & (1 << c) != 0).collect();
            let block = DMatrix::from_fn(6, 6, |r, c| j[(r, columns[c])]);
            let sv = block.singular_values();
            best = best.min(sv.max() / sv.min());
        }
        assert!((choice.condition_number - best).abs() < 1e-9 * best);
        // With joints 0 and 4 locked, they are extra joints.
        let locked = JointWeights::uniform(9).with_locked(&[0, 4]).unwrap();
        let choice = best_partition(&j, Some(&locked), 1e10).unwrap();
        assert!(choice.partition.extra().contains(&0) && choice.partition.extra().contains(&4));
    }
}

#[test]
fn rank_deficient_jacobians_and_singular_blocks_are_clear_errors() {
    // Rank 5: the sixth row is a combination of the others.
    let mut rng = common::rng(5008);
    let mut j = Matrix6xX::from_fn(8, |_, _| rng.gen_range(-1.0..1.0));
    for c in 0..8 {
        j[(5, c)] = j[(0, c)] + 2.0 * j[(3, c)];
    }
    let err = best_partition(&j, None, 1e10).unwrap_err().to_string();
    assert!(
        err.starts_with("numerical failure in seed 001 partition: no nonsingular 6 x 6 block"),
        "{err}"
    );
    // A full-rank Jacobian with one singular block: columns 0 and 1 equal.
    let mut j = Matrix6xX::from_fn(8, |_, _| rng.gen_range(-1.0..1.0));
    for r in 0..6 {
        j[(r, 1)] = j[(r, 0)];
    }
    let partition = Partition::new(8, [0, 1, 2, 3, 4, 5]).unwrap();
    let mut solver = PartitionedSolver::new(8, 1e10).unwrap();
    let twist = Vector6::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let err = solver
        .solve(&j, &JointWeights::uniform(8), &twist, &partition)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("block G'0 (joints [0, 1, 2, 3, 4, 5]) is singular"),
        "{err}"
    );
    // best_partition avoids it.
    let choice = best_partition(&j, None, 1e10).unwrap();
    assert!(solver
        .solve(&j, &JointWeights::uniform(8), &twist, &choice.partition)
        .is_ok());
    // A locked generalized joint.
    let locked = JointWeights::uniform(8).with_locked(&[2]).unwrap();
    let err = solver
        .solve(
            &j,
            &locked,
            &twist,
            &Partition::new(8, [0, 2, 3, 4, 5, 6]).unwrap(),
        )
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("joint 2 is locked but is one of the generalized joints"),
        "{err}"
    );
    // Too many locked joints.
    let locked = JointWeights::uniform(8).with_locked(&[0, 1, 2]).unwrap();
    let err = best_partition(&j, Some(&locked), 1e10)
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "invalid argument `weights`: only 5 of 8 joints are unlocked; a 6-D twist needs at least 6"
    );
}

#[test]
fn bad_input_gets_clear_errors() {
    let message = |e: armkit::Error| e.to_string();
    assert_eq!(
        message(JointWeights::new(&[1.0, 0.0]).unwrap_err()),
        "invalid argument `weights`: weight of joint 1 must be finite and > 0, got 0"
    );
    assert_eq!(
        message(JointWeights::new(&[-2.0]).unwrap_err()),
        "invalid argument `weights`: weight of joint 0 must be finite and > 0, got -2"
    );
    assert_eq!(
        message(JointWeights::new(&[f64::NAN]).unwrap_err()),
        "invalid argument `weights`: weight of joint 0 must be finite and > 0, got NaN"
    );
    assert_eq!(
        message(JointWeights::uniform(3).lock(3).unwrap_err()),
        "invalid argument `joint`: index 3 is out of range for 3 joints (0-based)"
    );
    let mut solver = WeightedLeastNorm::new(7, SolverOptions::default()).unwrap();
    let j = Matrix6xX::from_fn(7, |r, c| if r == c { 1.0 } else { 0.1 });
    let twist = Vector6::new(0.1, 0.0, 0.0, 0.0, 0.0, 0.0);
    let w7 = JointWeights::uniform(7);
    assert_eq!(
        message(solver.solve(&Matrix6xX::zeros(6), &w7, &twist).unwrap_err()),
        "jacobian (columns): expected 7 values, got 6"
    );
    assert_eq!(
        message(
            solver
                .solve(&j, &JointWeights::uniform(6), &twist)
                .unwrap_err()
        ),
        "weights: expected 7 values, got 6"
    );
    let mut bad = j.clone();
    bad[(2, 3)] = f64::NAN;
    assert_eq!(
        message(solver.solve(&bad, &w7, &twist).unwrap_err()),
        "jacobian[20] is not finite (NaN)"
    );
    let nan_twist = Vector6::new(0.1, f64::INFINITY, 0.0, 0.0, 0.0, 0.0);
    assert_eq!(
        message(solver.solve(&j, &w7, &nan_twist).unwrap_err()),
        "twist[1] is not finite (inf)"
    );
    assert_eq!(
        message(solver.solve_toward(&j, &w7, &twist, &[0.0; 3]).unwrap_err()),
        "preferred: expected 7 values, got 3"
    );
    assert_eq!(
        message(
            WeightedLeastNorm::new(
                7,
                SolverOptions {
                    damping: Damping::Constant(-1.0),
                    ..SolverOptions::default()
                }
            )
            .unwrap_err()
        ),
        "invalid argument `damping.lambda`: must be finite and > 0, got -1"
    );
    assert_eq!(
        message(PartitionedSolver::new(5, 1e10).unwrap_err()),
        "invalid argument `dof`: seed 001's partition needs at least 6 joints, got 5"
    );
    assert_eq!(
        message(TorqueFloor::Relative(0.0).validate().unwrap_err()),
        "invalid argument `torque_floor`: relative fraction must be in (0, 1], got 0"
    );
    let model = armkit::robots::by_name("gantry9").unwrap();
    let options = DistributionOptions {
        tracking: TrackingOptions::proportional(0.01, 200.0),
        ..DistributionOptions::default()
    };
    let err = ResolvedRateTracker::new(
        &model,
        Distribution::Weights(JointWeights::uniform(9)),
        options,
    )
    .unwrap_err();
    assert!(message(err).contains("gain * time_step <= 1"));
    let err = ResolvedRateTracker::new(
        &model,
        Distribution::Weights(JointWeights::uniform(7)),
        DistributionOptions::default(),
    )
    .unwrap_err();
    assert_eq!(message(err), "weights: expected 9 values, got 7");
    let mut data = Data::new(&model);
    let load = Load::payload(f64::NAN);
    let mut tau = [0.0; 9];
    assert_eq!(
        message(joint_torques(&model, &mut data, &[0.0; 9], &load, &mut tau).unwrap_err()),
        "load.wrench[2] is not finite (NaN)"
    );
    assert_eq!(
        message(energy_measure(&[1.0, 2.0], &[1.0]).unwrap_err()),
        "torques: expected 2 values, got 1"
    );
    assert!(
        CartesianTrajectory::line(Pose::identity(), Pose::identity(), TimeLaw::Quintic, 0.0)
            .is_err()
    );
}

/// Potential energy of the links, `-sum m g . c` (J).
fn potential_energy(model: &Model, q: &[f64], gravity: &Vector3<f64>) -> f64 {
    let mut data = Data::new(model);
    forward_kinematics(model, &mut data, q).unwrap();
    model
        .joints()
        .iter()
        .zip(data.joint_frames())
        .map(|(joint, frame)| {
            let inertia = joint.inertia.unwrap();
            -inertia.mass * gravity.dot(&frame.transform_point(&inertia.com))
        })
        .sum()
}

#[test]
fn gravity_torques_are_the_gradient_of_the_potential_energy() {
    let gravity = Vector3::new(0.0, 0.0, -9.81);
    let mut rng = common::rng(5009);
    for name in ["gantry9", "gantry9-flex", "space6r"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut data = Data::new(&model);
        let mut tau = vec![0.0; model.dof()];
        for _ in 0..5 {
            let q = common::random_configuration(&model, &mut rng);
            gravity_torques(&model, &mut data, &q, &gravity, &mut tau).unwrap();
            for i in 0..model.dof() {
                // The potential energy is ~2e5 J (the beam at 6 m): a step
                // of 1e-4 keeps round-off (~1e-7) and truncation below 1e-6.
                let h = 1e-4;
                let mut plus = q.clone();
                let mut minus = q.clone();
                plus[i] += h;
                minus[i] -= h;
                let fd = (potential_energy(&model, &plus, &gravity)
                    - potential_energy(&model, &minus, &gravity))
                    / (2.0 * h);
                assert!(
                    (fd - tau[i]).abs() < 1e-5 * tau[i].abs().max(1.0),
                    "{name} joint {i}: {} vs {fd}",
                    tau[i]
                );
            }
        }
    }
    // No masses: a clear error naming the link.
    let puma = armkit::robots::by_name("puma560").unwrap();
    let mut data = Data::new(&puma);
    let mut tau = [0.0; 6];
    let err = gravity_torques(&puma, &mut data, &[0.0; 6], &gravity, &mut tau).unwrap_err();
    assert!(err
        .to_string()
        .contains("model `puma560` has no mass properties for link 0 (`q1`)"));
}

#[test]
fn gantry9_holding_torques_match_a_hand_count() {
    // The ram is vertical at every configuration: it holds everything below
    // the carriage (ram 150 kg + arm 150 kg) and the 50 N payload; the rail
    // and beam joints are horizontal and the arm's first axis is vertical,
    // so their torques are zero.
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let load = Load::payload(50.0).with_seed001_gravity();
    let mut tau = [0.0; 9];
    let mut rng = common::rng(5010);
    for _ in 0..10 {
        let q = common::random_configuration(&model, &mut rng);
        joint_torques(&model, &mut data, &q, &load, &mut tau).unwrap();
        // z3 points down: holding up means a negative force along it.
        assert!((tau[2] + 300.0 * 9.81 + 50.0).abs() < 1e-9, "{}", tau[2]);
        assert!(tau[0].abs() < 1e-9 && tau[1].abs() < 1e-9 && tau[3].abs() < 1e-9);
        // Wrench part alone: tau = J' w.
        let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
            .unwrap()
            .clone();
        joint_torques(&model, &mut data, &q, &Load::payload(50.0), &mut tau).unwrap();
        let expected = j.transpose() * Vector6::new(0.0, 0.0, 50.0, 0.0, 0.0, 0.0);
        assert!(common::max_abs_difference(&tau, expected.as_slice()) < 1e-12);
    }
}

#[test]
fn zero_torques_are_floored_never_divided_by() {
    let torques = [0.0, 0.0, -3000.0, 0.0, 600.0, 50.0, 0.2, 9.0, 0.0];
    // Default: 5 % of the largest torque, 150 N or N m.
    assert_eq!(TorqueFloor::default(), TorqueFloor::Relative(0.05));
    let w = JointWeights::from_torques(&torques, TorqueFloor::default()).unwrap();
    for (j, expected) in [
        22500.0, 22500.0, 9e6, 22500.0, 360000.0, 22500.0, 22500.0, 22500.0, 22500.0,
    ]
    .iter()
    .enumerate()
    {
        assert!(
            (w.values()[j] - expected).abs() < 1e-9 * expected,
            "joint {j}"
        );
    }
    let w = JointWeights::from_torques(&torques, TorqueFloor::Relative(1e-3)).unwrap();
    assert!((w.values()[0] - 9.0).abs() < 1e-12); // floor 3
    assert!((w.values()[6] - 9.0).abs() < 1e-12); // |0.2| < 3
    assert!((w.values()[7] - 81.0).abs() < 1e-12); // |9| > 3: tau^2
    assert!(w.inverse().iter().all(|v| v.is_finite() && *v > 0.0));
    let w = JointWeights::from_torques(&torques, TorqueFloor::Absolute(0.5)).unwrap();
    assert_eq!(w.values()[0], 0.25);
    assert_eq!(w.values()[6], 0.25);
    let err = JointWeights::from_torques(&[0.0; 9], TorqueFloor::default()).unwrap_err();
    assert!(err.to_string().starts_with(
        "invalid argument `torques`: every joint torque is zero: seed 001's energy measure (eq 9)"
    ));
    let w = JointWeights::from_torques(&[0.0; 3], TorqueFloor::Absolute(2.0)).unwrap();
    assert_eq!(w.values(), &[4.0, 4.0, 4.0]);
}

#[test]
fn eq17_from_torques_matches_the_weighted_form_and_its_floor_limit() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let load = Load::payload(50.0).with_seed001_gravity();
    let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    let mut tau = [0.0; 9];
    joint_torques(&model, &mut data, &q, &load, &mut tau).unwrap();
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let twist = Vector6::new(0.1, 0.075, -0.075, 0.0, 0.0, 0.0);
    let choice = best_partition(&j, None, 1e10).unwrap();
    let mut partitioned = PartitionedSolver::new(9, 1e10).unwrap();
    // Eq 17 as printed, with the raw torques (three of them are zero).
    let raw = partitioned
        .solve_energy_optimal(&j, &tau, &twist, &choice.partition)
        .unwrap()
        .to_vec();
    assert!((&j * as_dvector(&raw) - twist).amax() < 1e-10);
    // The weighted least norm with floored weights converges to it as the
    // floor goes to zero, and its energy measure to eq 17's minimum. The
    // unfloored optimum is nearly degenerate here (joints 1, 2, 4, 9 carry
    // no torque and 7 almost none: counter-rotating the two near-vertical
    // axes 4 and 7 while the rail and beam compensate costs almost nothing),
    // so it asks for joint rates of ~17 rad/s for a 0.1 m/s twist; a floor
    // of 1e-3 already keeps them below 1 rad/s at under 1 % in F.
    let f_raw = energy_measure(&raw, &tau).unwrap();
    let raw_size = raw.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(raw_size > 10.0, "{raw_size}");
    let mut solver = WeightedLeastNorm::new(9, SolverOptions::default()).unwrap();
    let mut previous_gap = f64::INFINITY;
    let mut previous_f = f64::INFINITY;
    for fraction in [1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
        let w = JointWeights::from_torques(&tau, TorqueFloor::Relative(fraction)).unwrap();
        let floored = solver
            .solve(&j, &w, &twist)
            .unwrap()
            .solved()
            .unwrap()
            .to_vec();
        let gap = common::max_abs_difference(&floored, &raw);
        let f = energy_measure(&floored, &tau).unwrap();
        assert!(
            gap < previous_gap,
            "floor {fraction}: {gap} >= {previous_gap}"
        );
        assert!(
            f <= previous_f && f >= f_raw * (1.0 - 1e-8),
            "floor {fraction}: F {f}"
        );
        if fraction == 1e-3 {
            assert!(floored.iter().all(|v| v.abs() < 1.0), "{floored:?}");
            assert!(f < 1.01 * f_raw);
        }
        previous_gap = gap;
        previous_f = f;
    }
    assert!(previous_gap < 1e-3 * raw_size, "{previous_gap}");
    assert!((previous_f - f_raw).abs() < 1e-8 * f_raw);
    // With every torque non-zero, eq 17 and eq 19 with A = T^2 coincide.
    let nonzero: Vec<f64> = tau.iter().map(|t| t + 5.0).collect();
    let eq17 = partitioned
        .solve_energy_optimal(&j, &nonzero, &twist, &choice.partition)
        .unwrap()
        .to_vec();
    let w = JointWeights::new(&nonzero.iter().map(|t| t * t).collect::<Vec<_>>()).unwrap();
    let eq19 = solver
        .solve(&j, &w, &twist)
        .unwrap()
        .solved()
        .unwrap()
        .to_vec();
    assert!(common::max_abs_difference(&eq17, &eq19) < 1e-9);
}

#[test]
fn joint_limit_and_manipulability_gradients_match_finite_differences() {
    let model = armkit::robots::by_name("panda").unwrap();
    let mut rng = common::rng(5011);
    let mut data = Data::new(&model);
    let manipulability_at = |q: &[f64], data: &mut Data| {
        manipulability(jacobian(&model, data, q, JacobianFrame::World).unwrap())
    };
    let mut task = SecondaryTask::new(
        &model,
        SecondaryObjective::Manipulability {
            gain: 1.0,
            step: 1e-6,
        },
    )
    .unwrap();
    let mut gradient = [0.0; 7];
    for _ in 0..5 {
        let q = common::random_configuration(&model, &mut rng);
        joint_limit_gradient(&model, &q, &mut gradient).unwrap();
        let direction = task.direction(&model, &q).unwrap().to_vec();
        for i in 0..7 {
            let h = 1e-5;
            let mut plus = q.clone();
            let mut minus = q.clone();
            plus[i] += h;
            minus[i] -= h;
            let fd = (joint_limit_cost(&model, &plus).unwrap()
                - joint_limit_cost(&model, &minus).unwrap())
                / (2.0 * h);
            assert!((fd - gradient[i]).abs() < 1e-8, "{fd} vs {}", gradient[i]);
            let fd = (manipulability_at(&plus, &mut data) - manipulability_at(&minus, &mut data))
                / (2.0 * h);
            assert!((fd - direction[i]).abs() < 1e-6, "{fd} vs {}", direction[i]);
        }
    }
    // Manipulability agrees with the kinematics module's (SVD) measure.
    let q = [0.1, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7];
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
    let expected = armkit::kinematics::manipulability(j);
    assert!((manipulability(j) - expected).abs() < 1e-12);
}

/// Tracking accuracy of the loop with its defaults (dt = 0.01 s, K = 10/s)
/// on these moves: 1 mm and 1 mrad. A proportional loop alone would lag by
/// about the path speed over K (0.1 m/s / 10/s = 1e-2 m); the feedforward
/// twist removes most of that.
const TRACKING_TOLERANCE: f64 = 1e-3;

fn gantry_start() -> [f64; 9] {
    [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1]
}

fn line_from(
    model: &Model,
    q0: &[f64],
    shift: Vector3<f64>,
    turn: f64,
    duration: f64,
) -> CartesianTrajectory {
    let mut data = Data::new(model);
    let start = *forward_kinematics(model, &mut data, q0).unwrap();
    let goal = Pose::from_translation(shift) * start * Pose::rot_z(turn);
    CartesianTrajectory::line(start, goal, TimeLaw::Quintic, duration).unwrap()
}

/// Velocity and position limits hold at every sample.
fn assert_limits_respected(model: &Model, samples: &[armkit::tracking::TrackingSample]) {
    for sample in samples {
        for (j, joint) in model.joints().iter().enumerate() {
            let limits = joint.limits;
            assert!(
                sample.q[j] >= limits.lower && sample.q[j] <= limits.upper,
                "joint {j} at {} outside [{}, {}] at t = {}",
                sample.q[j],
                limits.lower,
                limits.upper,
                sample.time
            );
            if let Some(v) = limits.velocity {
                assert!(sample.joint_rates[j].abs() <= v * (1.0 + 1e-12));
            }
        }
    }
}

#[test]
fn tracking_follows_lines_on_gantry9_and_panda_with_every_method() {
    let gantry = armkit::robots::by_name("gantry9").unwrap();
    let q0 = gantry_start();
    let path = line_from(&gantry, &q0, Vector3::new(0.4, 0.3, -0.3), 0.3, 4.0);
    let load = Load::payload(50.0).with_seed001_gravity();
    let distributions = [
        Distribution::Weights(JointWeights::uniform(9)),
        Distribution::Weights(JointWeights::new(&SEED000_PRIORITY_WEIGHTS).unwrap()),
        Distribution::Energy {
            load,
            floor: TorqueFloor::default(),
        },
    ];
    let secondaries = [
        SecondaryObjective::None,
        SecondaryObjective::JointLimits { gain: 0.5 },
        SecondaryObjective::Manipulability {
            gain: 0.5,
            step: 1e-6,
        },
    ];
    for distribution in &distributions {
        for secondary in secondaries {
            let options = DistributionOptions {
                secondary,
                ..DistributionOptions::default()
            };
            let mut tracker =
                ResolvedRateTracker::new(&gantry, distribution.clone(), options).unwrap();
            let report = tracker.run(&gantry, &q0, &path).unwrap();
            assert_eq!(report.status, TrackingStatus::Completed);
            assert!(report.max_position_error < TRACKING_TOLERANCE);
            assert!(report.final_position_error < TRACKING_TOLERANCE);
            assert!(report.final_orientation_error < TRACKING_TOLERANCE);
            assert_limits_respected(&gantry, &report.samples);
        }
    }
    // Panda, minimum norm and the partitioned form give the same motion.
    let panda = armkit::robots::by_name("panda").unwrap();
    let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let path = line_from(&panda, &q0, Vector3::new(0.15, 0.1, -0.1), -0.4, 2.0);
    let run = |formulation: Formulation| {
        let options = DistributionOptions {
            formulation,
            ..DistributionOptions::default()
        };
        let mut tracker = ResolvedRateTracker::new(
            &panda,
            Distribution::Weights(JointWeights::uniform(7)),
            options,
        )
        .unwrap();
        tracker.run(&panda, &q0, &path).unwrap()
    };
    let a = run(Formulation::WeightedLeastNorm);
    let b = run(Formulation::Partitioned(None));
    assert_eq!(a.status, TrackingStatus::Completed);
    assert!(a.max_position_error < TRACKING_TOLERANCE);
    assert!(a.final_position_error < TRACKING_TOLERANCE);
    assert!(a.final_orientation_error < TRACKING_TOLERANCE);
    assert_limits_respected(&panda, &a.samples);
    let last_a = &a.samples.last().unwrap().q;
    let last_b = &b.samples.last().unwrap().q;
    assert!(common::max_abs_difference(last_a, last_b) < 1e-9);
}

/// `|N A^-1 grad H|`: the joint-limit gradient projected on the null space.
fn projected_limit_gradient(model: &Model, q: &[f64]) -> f64 {
    let mut data = Data::new(model);
    let j = jacobian(model, &mut data, q, JacobianFrame::World)
        .unwrap()
        .clone();
    let weights = JointWeights::uniform(model.dof());
    let mut solver = WeightedLeastNorm::new(model.dof(), SolverOptions::default()).unwrap();
    let projector = solver
        .null_space_projector(&j, &weights)
        .unwrap()
        .solved()
        .unwrap()
        .clone();
    let mut gradient = vec![0.0; model.dof()];
    joint_limit_gradient(model, q, &mut gradient).unwrap();
    (projector * as_dvector(&gradient)).norm()
}

#[test]
fn null_space_objectives_improve_without_disturbing_the_task() {
    let panda = armkit::robots::by_name("panda").unwrap();
    // Joint 1 near its lower limit, joint 7 near its upper one.
    let q0 = [-2.4, -0.3, 0.0, -2.2, 0.0, 2.0, 2.5];
    let run = |secondary: SecondaryObjective, path: &CartesianTrajectory| {
        let options = DistributionOptions {
            secondary,
            ..DistributionOptions::default()
        };
        let mut tracker = ResolvedRateTracker::new(
            &panda,
            Distribution::Weights(JointWeights::uniform(7)),
            options,
        )
        .unwrap();
        let report = tracker.run(&panda, &q0, path).unwrap();
        assert_eq!(report.status, TrackingStatus::Completed);
        assert!(report.max_position_error < TRACKING_TOLERANCE);
        assert!(report.max_orientation_error < TRACKING_TOLERANCE);
        report
    };
    let cost = |q: &[f64]| joint_limit_cost(&panda, q).unwrap();
    // Holding the end effector still, the self-motion (one-dimensional for
    // a 7-joint arm) descends the joint-limit cost monotonically to a point
    // where its projected gradient vanishes.
    let hold = line_from(&panda, &q0, Vector3::zeros(), 0.0, 5.0);
    let report = run(SecondaryObjective::JointLimits { gain: 50.0 }, &hold);
    let costs: Vec<f64> = report.samples.iter().map(|s| cost(&s.q)).collect();
    assert!(costs.windows(2).all(|w| w[1] <= w[0] + 1e-12));
    let last = &report.samples.last().unwrap().q;
    assert!(costs[costs.len() - 1] < 0.95 * costs[0], "{costs:?}");
    let (start, end) = (
        projected_limit_gradient(&panda, &q0),
        projected_limit_gradient(&panda, last),
    );
    assert!(end < 1e-2 * start, "projected gradient {start} -> {end}");
    // Moving, it ends farther from the limits than without it.
    let path = line_from(&panda, &q0, Vector3::new(0.0, 0.1, 0.0), 0.0, 3.0);
    let final_q = |r: armkit::tracking::TrackingReport| r.samples.last().unwrap().q.clone();
    let plain = final_q(run(SecondaryObjective::None, &path));
    let limits = final_q(run(SecondaryObjective::JointLimits { gain: 10.0 }, &path));
    assert!(
        cost(&limits) < cost(&plain),
        "{} vs {}",
        cost(&limits),
        cost(&plain)
    );
    // Manipulability: the 7-joint arm's one-dimensional self-motion barely
    // changes it (about 2 % at best from typical poses); the gantry's
    // three-dimensional one does. Holding still, w climbs monotonically.
    let gantry = armkit::robots::by_name("gantry9").unwrap();
    let q0 = gantry_start();
    let mut data = Data::new(&gantry);
    let mut w =
        |q: &[f64]| manipulability(jacobian(&gantry, &mut data, q, JacobianFrame::World).unwrap());
    let run = |secondary: SecondaryObjective, path: &CartesianTrajectory| {
        let options = DistributionOptions {
            secondary,
            ..DistributionOptions::default()
        };
        let mut tracker = ResolvedRateTracker::new(
            &gantry,
            Distribution::Weights(JointWeights::uniform(9)),
            options,
        )
        .unwrap();
        let report = tracker.run(&gantry, &q0, path).unwrap();
        assert_eq!(report.status, TrackingStatus::Completed);
        assert!(report.max_position_error < TRACKING_TOLERANCE);
        assert!(report.max_orientation_error < TRACKING_TOLERANCE);
        assert_limits_respected(&gantry, &report.samples);
        report
    };
    let ascent = SecondaryObjective::Manipulability {
        gain: 1.0,
        step: 1e-6,
    };
    let hold = line_from(&gantry, &q0, Vector3::zeros(), 0.0, 5.0);
    let report = run(ascent, &hold);
    let values: Vec<f64> = report.samples.iter().map(|s| w(&s.q)).collect();
    assert!(values.windows(2).all(|p| p[1] >= p[0] - 1e-12));
    assert!(values[values.len() - 1] > 1.2 * values[0], "{values:?}");
    let path = line_from(&gantry, &q0, Vector3::new(0.4, 0.3, -0.3), 0.0, 4.0);
    let plain = final_q(run(SecondaryObjective::None, &path));
    let climbed = final_q(run(ascent, &path));
    let (w_plain, w_climbed) = (w(&plain), w(&climbed));
    assert!(w_climbed > 1.1 * w_plain, "{w_climbed} vs {w_plain}");
}

#[test]
fn velocity_limits_scale_and_position_limits_lock_or_stop() {
    // Fast: a 2 m move along the rails in 1 s (peak 3.75 m/s with the
    // quintic timing) is beyond gantry9's velocity limits whatever the
    // weights; the run is slowed down uniformly, some joint runs exactly at
    // its limit, none beyond.
    let gantry = armkit::robots::by_name("gantry9").unwrap();
    let q0 = gantry_start();
    let path = line_from(&gantry, &q0, Vector3::new(2.0, 0.0, 0.0), 0.0, 1.0);
    let mut tracker = ResolvedRateTracker::new(
        &gantry,
        Distribution::Weights(JointWeights::new(&SEED000_PRIORITY_WEIGHTS).unwrap()),
        DistributionOptions::default(),
    )
    .unwrap();
    let report = tracker.run(&gantry, &q0, &path).unwrap();
    assert!(
        report.velocity_scaled_steps > 10,
        "{}",
        report.velocity_scaled_steps
    );
    let at_limit = report.samples.iter().any(|s| {
        s.joint_rates
            .iter()
            .zip(gantry.joints())
            .any(|(v, joint)| (v.abs() - joint.limits.velocity.unwrap()).abs() < 1e-9)
    });
    assert!(at_limit);
    assert_limits_respected(&gantry, &report.samples);

    // The tool rolls +1 rad about its axis from q9 = 6.0 (limit 6.28):
    // with all nine joints free, q9 locks at its limit and the others take
    // over the roll.
    let mut q0 = gantry_start();
    q0[8] = 6.0;
    let roll = line_from(&gantry, &q0, Vector3::zeros(), 1.0, 2.0);
    let run = |weights: JointWeights| {
        let mut tracker = ResolvedRateTracker::new(
            &gantry,
            Distribution::Weights(weights),
            DistributionOptions::default(),
        )
        .unwrap();
        tracker.run(&gantry, &q0, &roll).unwrap()
    };
    let report = run(JointWeights::uniform(9));
    assert_eq!(report.status, TrackingStatus::Completed);
    assert!(
        report.limit_locked_steps > 10,
        "{}",
        report.limit_locked_steps
    );
    assert!(report.final_orientation_error < TRACKING_TOLERANCE);
    assert_limits_respected(&gantry, &report.samples);
    // With the gantry's three axes locked the arm alone has six joints:
    // once q9 locks, five remain for a 6-D twist and the motion stops
    // just short of the limit.
    let report = run(JointWeights::uniform(9).with_locked(&[0, 1, 2]).unwrap());
    match report.status {
        TrackingStatus::StoppedAtJointLimit { joint, time } => {
            assert_eq!(joint, 8);
            assert!(time > 0.1 && time < 2.0, "{time}");
        }
        other => panic!("expected a stop at q9's limit, got {other:?}"),
    }
    let last = report.samples.last().unwrap();
    let q9_limit = gantry.joints()[8].limits.upper;
    assert!(
        last.q[8] <= q9_limit && last.q[8] > q9_limit - 0.01,
        "{}",
        last.q[8]
    );
    assert_limits_respected(&gantry, &report.samples);
}

#[test]
fn pose_error_is_position_difference_and_rotation_vector() {
    let a = Pose::from_xyz_rpy([0.1, 0.2, 0.3], [0.3, -0.2, 1.0]);
    for angle in [0.0, 1e-9, 0.5, 2.0, PI - 1e-7, PI] {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        let turn =
            armkit::math::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
        let b = Pose::new(turn.into_inner() * a.rotation, a.translation + Vector3::x());
        let e = pose_error(&b, &a);
        assert!((e.fixed_rows::<3>(0) - Vector3::x()).norm() < 1e-15);
        let w: Vector3<f64> = e.fixed_rows::<3>(3).into_owned();
        assert!((w.norm() - angle).abs() < 1e-9, "{angle}: {}", w.norm());
        if angle > 1e-6 && angle < PI - 1e-6 {
            assert!((w - axis * angle).norm() < 1e-9);
        }
    }
}

#[test]
fn four_way_comparison_on_gantry9() {
    // One Cartesian motion (0.4, 0.3, -0.3) m in 4 s, orientation held,
    // distributed four ways; seed 001's energy measure F for a 50 N payload
    // plus the links' weight.
    let model = armkit::robots::by_name("gantry9").unwrap();
    let q0 = gantry_start();
    let path = line_from(&model, &q0, Vector3::new(0.4, 0.3, -0.3), 0.0, 4.0);
    let load = Load::payload(50.0).with_seed001_gravity();
    let cases = ComparisonCase::four_way(
        9,
        load,
        TorqueFloor::default(),
        JointWeights::new(&SEED000_PRIORITY_WEIGHTS).unwrap(),
        // Seed 001's baseline: joints locked so that six remain.
        &[0, 1, 2],
    )
    .unwrap();
    let results = compare_distributions(
        &model,
        &q0,
        &path,
        &load,
        &cases,
        &DistributionOptions::default(),
    )
    .unwrap();
    println!("distribution      F (W^2 s)   travel d1..d3 (m), q4..q9 (rad)");
    for r in &results {
        let travel: Vec<String> = r.summary.travel.iter().map(|t| format!("{t:.3}")).collect();
        println!(
            "{:15} {:11.4e}   {}",
            r.name,
            r.summary.energy,
            travel.join(" ")
        );
        assert_eq!(r.report.status, TrackingStatus::Completed);
        assert_eq!(r.report.velocity_scaled_steps, 0, "{}: slowed down", r.name);
        assert!(r.report.max_position_error < TRACKING_TOLERANCE);
        assert!(r.report.final_position_error < TRACKING_TOLERANCE);
        assert_limits_respected(&model, &r.report.samples);
    }
    let energy = |name: &str| {
        results
            .iter()
            .find(|r| r.name == name)
            .unwrap()
            .summary
            .energy
    };
    for other in ["minimum-norm", "priorities", "locked"] {
        assert!(
            energy("energy-optimal") < energy(other),
            "energy-optimal {} >= {other} {}",
            energy("energy-optimal"),
            energy(other)
        );
    }
    let travel = |name: &str| {
        results
            .iter()
            .find(|r| r.name == name)
            .unwrap()
            .summary
            .travel
            .clone()
    };
    // Locked joints do not move; priorities move the rail least.
    assert_eq!(&travel("locked")[..3], &[0.0, 0.0, 0.0]);
    assert!(travel("priorities")[0] < 0.2 * travel("minimum-norm")[0]);
    // Energy-optimal avoids lifting the 300 kg below the carriage.
    assert!(travel("energy-optimal")[2] < 0.3 * travel("minimum-norm")[2]);
}

#[test]
fn the_torque_floor_regularises_free_self_motion() {
    // Panda (no link masses) holding a 50 N payload: joints 1 and 3 carry no
    // torque and nearly share an axis. With a 1e-3 floor the energy-optimal
    // run spins them at their velocity limit and lags; with the default 5 %
    // floor it is smooth, and still spends less F than the minimum norm.
    let panda = armkit::robots::by_name("panda").unwrap();
    let q0 = panda.neutral_configuration();
    let path = line_from(&panda, &q0, Vector3::new(0.1, 0.1, -0.1), 0.0, 2.0);
    let load = Load::payload(50.0);
    let run = |floor: TorqueFloor| {
        let cases = [
            ComparisonCase {
                name: "minimum-norm".into(),
                distribution: Distribution::Weights(JointWeights::uniform(7)),
            },
            ComparisonCase {
                name: "energy-optimal".into(),
                distribution: Distribution::Energy { load, floor },
            },
        ];
        compare_distributions(
            &panda,
            &q0,
            &path,
            &load,
            &cases,
            &DistributionOptions::default(),
        )
        .unwrap()
    };
    let fastest = |r: &armkit::redundancy::ComparisonResult| {
        r.report
            .samples
            .iter()
            .flat_map(|s| s.joint_rates.iter())
            .fold(0.0_f64, |m, v| m.max(v.abs()))
    };
    let tiny = run(TorqueFloor::Relative(1e-3));
    assert!(tiny[1].report.velocity_scaled_steps > 100);
    assert!(tiny[1].report.max_position_error > 0.05);
    assert!((fastest(&tiny[1]) - 2.175).abs() < 1e-9);
    let default = run(TorqueFloor::default());
    assert_eq!(default[1].report.velocity_scaled_steps, 0);
    assert!(default[1].report.max_position_error < TRACKING_TOLERANCE);
    assert!(fastest(&default[1]) < 0.5, "{}", fastest(&default[1]));
    assert!(default[1].summary.energy < default[0].summary.energy);
}

#[test]
fn zero_generalized_weights_lock_the_extra_joints_along_the_motion() {
    // Seed 001, sec 3, last sentence: locking joints is a zero weight. In
    // eq 19, A_Q = 0 leaves A_p phi_dot = 0: the extra joints stay still and
    // the six generalized joints realise the twist alone (eq 8), which is the
    // infinite-weight lock of the weighted least norm.
    let model = armkit::robots::by_name("gantry9").unwrap();
    let q0 = gantry_start();
    let path = line_from(&model, &q0, Vector3::new(0.4, 0.3, -0.3), 0.0, 4.0);
    let locked = JointWeights::uniform(9).with_locked(&[0, 1, 2]).unwrap();
    let mut tracker = ResolvedRateTracker::new(
        &model,
        Distribution::Weights(locked),
        DistributionOptions::default(),
    )
    .unwrap();
    let run = tracker.run(&model, &q0, &path).unwrap();
    assert_eq!(run.status, TrackingStatus::Completed);
    let partition = Partition::new(9, [3, 4, 5, 6, 7, 8]).unwrap();
    let mut solver = PartitionedSolver::new(9, 1e10).unwrap();
    let paper_lock = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let slight = [1.0, 1.0, 1.0, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3];
    let mut data = Data::new(&model);
    let (mut largest_rate, mut largest_difference, mut moving) = (0.0_f64, 0.0_f64, 0.0_f64);
    for sample in &run.samples {
        let j = jacobian(&model, &mut data, &sample.q, JacobianFrame::World)
            .unwrap()
            .clone();
        let twist = Vector6::from_column_slice((&j * as_dvector(&sample.joint_rates)).as_slice());
        let q_dot = solver
            .solve_with_paper_weights(&j, &paper_lock, &twist, &partition)
            .unwrap()
            .to_vec();
        // The extra joints: exactly zero.
        assert_eq!(&q_dot[..3], &[0.0, 0.0, 0.0], "t = {}", sample.time);
        // The twist is met, and the rates are the locked run's.
        assert!((&j * as_dvector(&q_dot) - twist).norm() < 1e-12);
        largest_difference =
            largest_difference.max(common::max_abs_difference(&q_dot, &sample.joint_rates));
        largest_rate = largest_rate.max(sample.joint_rates.iter().fold(0.0, |m, v| m.max(v.abs())));
        // A_Q small but not zero: the extra joints move.
        let q_dot = solver
            .solve_with_paper_weights(&j, &slight, &twist, &partition)
            .unwrap();
        moving = moving.max(q_dot[..3].iter().fold(0.0, |m, v| m.max(v.abs())));
    }
    assert!(largest_rate > 0.1, "{largest_rate}");
    assert!(largest_difference < 1e-12, "{largest_difference}");
    assert!(moving > 1e-4, "{moving}");
    // Weights the paper's form cannot use.
    let j = jacobian(&model, &mut data, &q0, JacobianFrame::World)
        .unwrap()
        .clone();
    let twist = Vector6::new(0.1, 0.0, 0.0, 0.0, 0.0, 0.0);
    let mut bad = paper_lock;
    bad[1] = 0.0; // A_Q = 0 and a zero A_p entry: the cost cannot choose
    let err = solver
        .solve_with_paper_weights(&j, &bad, &twist, &partition)
        .unwrap_err()
        .to_string();
    assert!(err.contains("singular"), "{err}");
    bad[1] = -1.0;
    let err = solver
        .solve_with_paper_weights(&j, &bad, &twist, &partition)
        .unwrap_err()
        .to_string();
    assert!(err.contains("weight of joint 1 must be >= 0"), "{err}");
    bad[1] = f64::INFINITY;
    let err = solver
        .solve_with_paper_weights(&j, &bad, &twist, &partition)
        .unwrap_err()
        .to_string();
    assert!(err.contains("weights"), "{err}");
    let err = solver
        .solve_with_paper_weights(&j, &[1.0; 8], &twist, &partition)
        .unwrap_err()
        .to_string();
    assert!(err.contains("weights"), "{err}");
}

#[test]
fn distribution_study_uses_the_papers_baseline_and_compares_torque_models() {
    use armkit::redundancy::TorqueModel;
    use armkit::study::{DistributionStudy, FindingStatus, VARIANT_NAME};
    let model = armkit::robots::by_name("gantry9").unwrap();
    let outcome = DistributionStudy::default().compare(&model).unwrap();
    // The paper's baseline: three joints locked, six remain; the two-joint
    // lock only as the labelled extra.
    assert_eq!(outcome.settings.locked, vec![0, 1, 2]);
    assert_eq!(outcome.settings.variant_locked, vec![0, 1]);
    let names: Vec<&str> = outcome.results.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "minimum-norm",
            "energy-optimal",
            "priorities",
            "locked",
            VARIANT_NAME
        ]
    );
    let energy = |name: &str| outcome.result(name).unwrap().summary.energy;
    assert_eq!(
        &outcome.result("locked").unwrap().summary.travel[..3],
        &[0.0; 3]
    );
    assert_eq!(
        &outcome.result(VARIANT_NAME).unwrap().summary.travel[..2],
        &[0.0; 2]
    );
    assert!(outcome.result(VARIANT_NAME).unwrap().summary.travel[2] > 0.1);
    // Against the paper's baseline the gain is modest; against the two-joint
    // lock it is large.
    let baseline_gain = 1.0 - energy("energy-optimal") / energy("locked");
    let variant_gain = 1.0 - energy("energy-optimal") / energy(VARIANT_NAME);
    assert!(
        baseline_gain > 0.0 && baseline_gain < 0.5,
        "{baseline_gain}"
    );
    assert!(variant_gain > 0.5, "{variant_gain}");
    // Static F by the dynamics module equals the study's F; the dynamic one
    // differs.
    assert_eq!(outcome.torque_energies.len(), 5);
    for (r, e) in outcome.results.iter().zip(&outcome.torque_energies) {
        assert_eq!(r.name, e.name);
        assert!((e.static_energy - r.summary.energy).abs() < 1e-9 * r.summary.energy);
        assert!(e.dynamic_energy > 0.0 && e.dynamic_energy != e.static_energy);
    }
    let ranked = outcome.ranking(TorqueModel::Dynamic);
    assert!(ranked.windows(2).all(|w| w[0].1 <= w[1].1));
    let winner = outcome.winner(TorqueModel::Static).unwrap();
    assert!(winner.starts_with("energy-optimal"), "{winner}");
    // The zero-weight lock along the baseline run.
    let lock = outcome.zero_weight_lock.as_ref().unwrap();
    assert_eq!(lock.extra, vec![0, 1, 2]);
    assert_eq!(lock.max_extra_rate, 0.0);
    assert!(lock.max_rate_difference < 1e-12 * lock.max_rate.max(1.0));
    // Findings: the static claim and the lock reproduced; the dynamic one
    // stated either way with its figures; then the duration sweep's
    // crossover and moderate speed, F at each instant and unit weights
    // (tests/it/seed001_claims.rs judges those four).
    let findings = outcome.findings();
    assert_eq!(findings.len(), 7);
    assert_eq!(findings[0].status, FindingStatus::Reproduced);
    assert!(findings[0]
        .measured
        .contains("joints 1,2,3 locked, 6 remain"));
    assert!(findings[1]
        .measured
        .starts_with("dynamic torques: energy-optimal F = "));
    let dynamic_wins = ranked[0].0 == "energy-optimal";
    assert_eq!(
        findings[1].status == FindingStatus::Reproduced,
        dynamic_wins,
        "{}",
        findings[1]
    );
    assert_eq!(findings[2].status, FindingStatus::Reproduced);
    let checks = outcome.checks().unwrap();
    assert!(checks.iter().all(|c| c.passed()), "{checks:#?}");
    for finding in &findings {
        println!("{finding}");
    }
    for check in &checks {
        println!("{check}");
    }
}
