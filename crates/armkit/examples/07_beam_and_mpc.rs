//! Example 07: seed 000's flexible gantry beam and its MPC planner.
//!
//! * Table 1: the deflection under two 400 kg carriages on a 10 m steel beam
//!   (E = 200 GPa, 0.2 m square section), against the paper's values.
//! * The 9-DOF gantry on that beam (`gantry9-flex`): how far the end effector
//!   sinks compared with a rigid beam, as the carriage moves along it.
//! * Seed 000's model-predictive planner (Example 1: horizon N = 10, control
//!   horizon M = 1, Q = 10 with terminal weight 200, priorities R of 100, 10
//!   and 1) driving the gantry to [4, 1, 6] m in closed loop; the prismatic
//!   joints should run at their 0.6 m/s limit and never beyond.
//!
//! Run: `cargo run --release --example 07_beam_and_mpc`

use armkit::beam::{TwoCarriageBeam, SEED000_TABLE1};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Matrix3, Pose, Vector3};
use armkit::model::JointKind;
use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights};
use armkit::study::{SEED000_PRIORITIES, SEED000_START};

fn main() -> Result<(), armkit::Error> {
    // Table 1 (g = 10 m/s^2 reproduces the printed values).
    let gantry_beam = TwoCarriageBeam::seed000();
    println!("Seed 000, Table 1: deflection under two 400 kg loads");
    for case in SEED000_TABLE1 {
        let [under_a, under_b] = gantry_beam.deflections(case.positions)?;
        println!(
            "  loads at {:?} m: {:.4} / {:.4} mm (paper {:.1} mm)",
            case.positions,
            1e3 * under_a,
            1e3 * under_b,
            1e3 * case.paper
        );
    }

    // The flexible gantry sinks by w(d2) where the rigid one does not.
    let rigid = armkit::robots::by_name("gantry9")?;
    let flexible = armkit::robots::by_name("gantry9-flex")?;
    let (mut rigid_data, mut flexible_data) = (Data::new(&rigid), Data::new(&flexible));
    let mut q = SEED000_START;
    println!("End-effector drop of gantry9-flex against gantry9 (rigid beam):");
    for d2 in [0.5, 1.5, 3.0, 5.0] {
        q[1] = d2;
        let a = forward_kinematics(&rigid, &mut rigid_data, &q)?.translation;
        let b = forward_kinematics(&flexible, &mut flexible_data, &q)?.translation;
        println!(
            "  d2 = {d2:.1} m: {:.3} mm lower (difference {:.3?} mm)",
            1e3 * (a.z - b.z),
            (1e3 * (b - a)).as_slice()
        );
    }

    // Seed 000, Example 1: position-only MPC to [4, 1, 6] m on the flexible gantry.
    let target = Pose::new(Matrix3::identity(), Vector3::new(4.0, 1.0, 6.0));
    let options = MpcOptions {
        horizon: 10,
        control_horizon: 1,
        task_weights: TaskWeights::position_only(10.0, 200.0),
        increment_weights: Some(SEED000_PRIORITIES.to_vec()),
        ..MpcOptions::default()
    };
    let dt = options.sample_time;
    let mut planner = MpcPlanner::new(&flexible, options)?;
    planner.set_target(&target)?;
    let prismatic: Vec<usize> = (0..flexible.dof())
        .filter(|&j| flexible.joints()[j].kind == JointKind::Prismatic)
        .collect();
    let mut q = SEED000_START.to_vec();
    let (mut steps, mut peak_prismatic, mut error) = (0, 0.0_f64, f64::INFINITY);
    let mut solve_time = std::time::Duration::ZERO;
    while steps < 2000 {
        let report = planner.step(&q)?;
        error = report.position_error;
        let fastest = report.velocity.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if error < 1e-4 && fastest < 1e-3 {
            break;
        }
        for &j in &prismatic {
            peak_prismatic = peak_prismatic.max(report.velocity[j].abs());
        }
        solve_time += report.solve_time;
        // The plant: each joint holds its commanded velocity for one sample.
        for (qj, vj) in q.iter_mut().zip(&report.velocity) {
            *qj += dt * vj;
        }
        steps += 1;
    }
    println!(
        "MPC to [4, 1, 6] m ({}, T = {dt} s): {steps} steps ({:.2} s of motion), final error {:.2e} m",
        planner.solver_name(),
        steps as f64 * dt,
        error
    );
    println!(
        "  peak prismatic speed {peak_prismatic:.4} m/s (limit {:.1} m/s); QP time {:.1} ms in all",
        planner.velocity_limits()[0],
        1e3 * solve_time.as_secs_f64()
    );
    flexible.check_limits(&q)?;
    Ok(())
}
