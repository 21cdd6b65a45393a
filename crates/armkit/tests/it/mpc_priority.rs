//! The planner's strict (lexicographic) priority mode (seed 000, sec 4.4
//! read as a strict priority): levels from the increment weights, one
//! level equal to the weighted planner, and the same runs on the
//! active-set solver and on Clarabel.

use armkit::mpc::qp::QpSolverKind;
use armkit::mpc::scenario::{simulate, SimulationOptions};
use armkit::mpc::PriorityMode;
use armkit::study::Seed000Example;

#[test]
fn levels_follow_the_increment_weights_smallest_first() {
    assert_eq!(
        PriorityMode::Strict.joint_levels(&[100.0, 10.0, 10.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]),
        [2, 1, 1, 0, 0, 0, 0, 0, 0]
    );
    assert_eq!(PriorityMode::Weighted.joint_levels(&[100.0, 1.0]), [0, 0]);
}

#[test]
fn strict_with_one_level_is_the_weighted_planner() {
    let model = Seed000Example::model().unwrap();
    let example = Seed000Example::EqualWeights;
    let run = |priority| {
        simulate(
            &model,
            armkit::mpc::MpcOptions {
                priority,
                ..example.options()
            },
            &example.start(),
            &example.target(),
            &SimulationOptions {
                max_steps: 200,
                ..SimulationOptions::default()
            },
        )
        .unwrap()
    };
    let (strict, weighted) = (run(PriorityMode::Strict), run(PriorityMode::Weighted));
    for (a, b) in strict.samples.iter().zip(&weighted.samples) {
        assert_eq!(a.q, b.q);
    }
}

/// Seed 000's Example 2 with the strict priority, on the active-set solver
/// and on Clarabel: the same motion (Clarabel's 1e-8 accuracy over the run).
#[test]
fn strict_example_2_is_the_same_on_clarabel() {
    let model = Seed000Example::model().unwrap();
    let example = Seed000Example::SmallMoveStrict;
    let run = |solver| {
        simulate(
            &model,
            armkit::mpc::MpcOptions {
                solver,
                ..example.options()
            },
            &example.start(),
            &example.target(),
            &example.simulation(),
        )
        .unwrap()
    };
    let (active, clarabel) = (run(QpSolverKind::ActiveSet), run(QpSolverKind::Clarabel));
    assert!(active.summary.converged && clarabel.summary.converged);
    for j in 0..model.dof() {
        let (a, c) = (active.travel(j), clarabel.travel(j));
        assert!((a - c).abs() < 1e-4, "joint {j}: travel {a} vs {c}");
    }
    // Strict levels change the motion: the beam joint d2 moves (the rotary
    // level, weighted by its own R, leaves part of each step's error).
    let weighted = Seed000Example::SmallMovePaperWeights.run().unwrap();
    assert!((active.travel(1) - weighted.travel(1)).abs() > 1e-2);
}

/// Seed 000 eq 14 and sec 4.5 under a model error: the rigid-beam planner
/// on the bending plant and the planner with links 5 % too long both end
/// within the tolerance of the target on the plant, though their own
/// models put the hand millimetres to centimetres away.
#[test]
fn model_mismatch_leaves_no_static_error() {
    use armkit::kinematics::{forward_kinematics, Data};
    for (example, least_offset) in [
        (Seed000Example::LargeMoveRigidModel, 1e-3),
        (Seed000Example::LargeMoveLinkError, 1e-2),
    ] {
        let run = example.run().unwrap();
        assert!(run.summary.converged, "{}", example.id());
        assert!(run.summary.final_position_error <= 1e-4, "{}", example.id());
        let q = &run.samples.last().unwrap().q;
        let planner = example.planner_model().unwrap().unwrap();
        let plant = Seed000Example::model().unwrap();
        let hand = |m: &armkit::Model| {
            forward_kinematics(m, &mut Data::new(m), q)
                .unwrap()
                .translation
        };
        let offset = (hand(&planner) - hand(&plant)).norm();
        assert!(offset > least_offset, "{}: offset {offset}", example.id());
    }
    let error = armkit::mpc::scenario::simulate_on_plant(
        armkit::mpc::MpcPlanner::new(&Seed000Example::model().unwrap(), Default::default())
            .unwrap(),
        Some(&armkit::robots::by_name("panda").unwrap()),
        &Seed000Example::LargeMove.start(),
        &Seed000Example::LargeMove.target(),
        &SimulationOptions::default(),
        |_| {},
    )
    .err()
    .unwrap()
    .to_string();
    assert!(error.contains("plant model"), "{error}");
    let urdf_like =
        armkit::mpc::with_link_length_error(&Seed000Example::model().unwrap(), f64::NAN)
            .err()
            .unwrap()
            .to_string();
    assert!(urdf_like.contains("link_length_error"), "{urdf_like}");
}
