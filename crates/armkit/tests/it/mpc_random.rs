//! Random reachable targets on panda, iiwa14 (URDF), ur5 and gantry9-flex,
//! started from the mid-range configuration: the planner (with its default
//! goal posture) reaches at least 99 % of them, never crosses a joint
//! position or velocity limit, and every run that does not converge carries
//! a status naming its cause.
//!
//! Each target is the pose of a random configuration within the limits (so
//! it is reachable); targets alternate between position-only and full-pose
//! tracking (1e-4 m; full pose also 1e-4 rad). 10 targets per robot in the
//! normal (release) suite; the 1000-target run (same seeds) is `#[ignore]`d:
//! `cargo test -p armkit --release --test it -- --ignored --nocapture mpc_random::`.
//! The plain planner ([`ReachAid::Off`]) is run beside it for comparison.

use crate::common;

use armkit::kinematics::{forward_kinematics, Data};
use armkit::mpc::scenario::{simulate_with, SimulationOptions};
use armkit::mpc::{diagnose_run, MpcOptions, MpcPlanner, ReachAid, RunStatus, TaskWeights};
use armkit::Model;

struct Outcome {
    status: RunStatus,
    position_error: f64,
    orientation_error: Option<f64>,
    steps: usize,
}

fn robots() -> Vec<(Model, u64)> {
    let selection = armkit::urdf::ChainSelection::between("base_link", "tool0");
    vec![
        (armkit::robots::by_name("panda").unwrap(), 8),
        (
            armkit::urdf::load(common::data_path("urdf/iiwa14.urdf"), &selection).unwrap(),
            14,
        ),
        (armkit::robots::by_name("ur5").unwrap(), 5),
        (armkit::robots::gantry9_flex().unwrap(), 7),
    ]
}

/// Runs `count` random targets on `model` from its mid-range configuration;
/// asserts no limit is ever crossed and returns the outcomes.
fn random_targets(model: &Model, count: usize, seed: u64, reach: &ReachAid) -> Vec<Outcome> {
    let mut rng = common::rng(seed);
    let mut data = Data::new(model);
    let simulation = SimulationOptions {
        max_steps: 2000,
        position_tolerance: 1e-4,
        orientation_tolerance: 1e-4,
        ..SimulationOptions::default()
    };
    let start = model.neutral_configuration();
    (0..count)
        .map(|k| {
            let goal = common::random_configuration(model, &mut rng);
            let target = *forward_kinematics(model, &mut data, &goal).unwrap();
            let full_pose = k % 2 == 1;
            let options = MpcOptions {
                task_weights: if full_pose {
                    TaskWeights::full_pose(10.0, 200.0)
                } else {
                    TaskWeights::position_only(10.0, 200.0)
                },
                reach: reach.clone(),
                ..MpcOptions::default()
            };
            let mut planner = MpcPlanner::new(model, options).unwrap();
            let run = simulate_with(&mut planner, &start, &target, &simulation, |_| {}).unwrap();
            assert_eq!(
                run.summary.max_velocity_violation,
                0.0,
                "{} target {k}: velocity limit crossed",
                model.name()
            );
            assert_eq!(
                run.summary.max_position_violation,
                0.0,
                "{} target {k}: position limit crossed",
                model.name()
            );
            let last = &run.samples.last().unwrap().q;
            let status = diagnose_run(&planner, last, run.summary.converged).unwrap();
            assert_eq!(status.is_converged(), run.summary.converged);
            Outcome {
                status,
                position_error: run.summary.final_position_error,
                orientation_error: full_pose.then_some(run.summary.final_orientation_error),
                steps: run.summary.steps,
            }
        })
        .collect()
}

/// Prints the outcome and checks it: at least `min_converged` of the runs
/// converge, each within its tolerances, and every other one has a cause.
fn report(name: &str, reach: &ReachAid, outcomes: &[Outcome], min_converged: f64) {
    let n = outcomes.len();
    let converged: Vec<&Outcome> = outcomes
        .iter()
        .filter(|o| o.status.is_converged())
        .collect();
    let mut steps: Vec<usize> = converged.iter().map(|o| o.steps).collect();
    steps.sort();
    println!(
        "{name} (reach {reach}): {n} random reachable targets from mid-range, {} converged ({:.1} %), \
         0 limit crossings, median steps {}",
        converged.len(),
        100.0 * converged.len() as f64 / n as f64,
        steps.get(steps.len() / 2).copied().unwrap_or(0)
    );
    for (k, o) in outcomes.iter().enumerate() {
        if !o.status.is_converged() {
            println!("  target {k}: {}", o.status);
            // A cause, not a bare "not converged".
            assert!(!o.status.to_string().is_empty());
        }
    }
    for o in &converged {
        assert!(o.position_error <= 1e-4, "{}", o.position_error);
        if let Some(e) = o.orientation_error {
            assert!(e <= 1e-4, "{e}");
        }
    }
    assert!(
        converged.len() as f64 >= min_converged * n as f64,
        "{name}: only {} of {n} converged",
        converged.len()
    );
}

fn suite_size() -> usize {
    if cfg!(debug_assertions) {
        2
    } else {
        10
    }
}

#[test]
fn random_targets_from_mid_range_are_reached_without_crossing_a_limit() {
    let reach = ReachAid::default();
    for (model, seed) in robots() {
        let outcomes = random_targets(&model, suite_size(), seed, &reach);
        report(model.name(), &reach, &outcomes, 0.99);
    }
}

#[test]
#[ignore = "1000 targets per robot, with and without the goal posture: minutes in release"]
fn thousand_random_targets_per_robot() {
    for (model, seed) in robots() {
        let reach = ReachAid::default();
        let outcomes = random_targets(&model, 1000, seed, &reach);
        report(model.name(), &reach, &outcomes, 0.99);
    }
}

#[test]
#[ignore = "the plain planner on the same 1000 targets, for comparison (no convergence bound)"]
fn thousand_random_targets_per_robot_plain_planner() {
    for (model, seed) in robots() {
        let outcomes = random_targets(&model, 1000, seed, &ReachAid::Off);
        report(model.name(), &ReachAid::Off, &outcomes, 0.0);
    }
}
