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
