//! A user's MPC run as a report: a scenario's `[mpc]` table with the
//! `[robot]` and `target` (the options of `armkit mpc --target`).

use armkit::kinematics::{forward_kinematics, Data};
use armkit::mpc::diagnose_run;
use armkit::mpc::scenario::{simulate_on_plant, MpcRun};
use armkit::Model;

use super::report::figures;
use super::{target_setup, MpcArgs, TargetSetup};
use crate::common::CliResult;
use crate::report::{join, Animation, Check, Report, Table};

/// The MPC to `target` on the user's robot as a report. Checks are what
/// armkit promises for any robot (no seed-paper claims): the run converges
/// (at the target within the simulation's tolerances and at rest), the
/// final position and orientation errors are within those tolerances, and
/// no joint velocity or position limit is crossed. Figures as seed 000's
/// Figs 7-9 (a group the robot lacks is skipped), the arm moving.
pub fn target_report(args: &MpcArgs) -> CliResult<Report> {
    let TargetSetup {
        model,
        target,
        start,
        mut planner,
        plant_model,
        simulation,
    } = target_setup(args)?;
    let solver = planner.solver_name();
    let run = simulate_on_plant(
        &mut planner,
        plant_model.as_ref(),
        &start,
        &target,
        &simulation,
        |_| {},
    )?;
    let final_q = run.samples.last().map(|s| s.q.clone()).unwrap_or_default();
    let status = diagnose_run(&planner, &final_q, run.summary.converged)?;
    let summary = &run.summary;
    let mut checks = vec![
        Check::holds(
            format!(
                "converges: at the target ({} m{}) and at rest ({})",
                simulation.position_tolerance,
                if run.tracks_orientation {
                    format!(", {} rad", simulation.orientation_tolerance)
                } else {
                    String::new()
                },
                simulation.velocity_tolerance
            ),
            status.is_converged(),
            format!(
                "{status} after {} steps ({:.2} s)",
                summary.steps,
                summary.steps as f64 * run.sample_time
            ),
        ),
        Check::at_most(
            "final position error",
            summary.final_position_error,
            simulation.position_tolerance,
            "m",
        ),
    ];
    if run.tracks_orientation {
        checks.push(Check::at_most(
            "final orientation error",
            summary.final_orientation_error,
            simulation.orientation_tolerance,
            "rad",
        ));
    }
    checks.push(Check::at_most(
        "largest excess over a joint velocity limit",
        summary.max_velocity_violation,
        0.0,
        "m/s or rad/s",
    ));
    checks.push(Check::at_most(
        "largest excess over a joint position limit (the start included)",
        summary.max_position_violation,
        0.0,
        "m or rad",
    ));
    let mut data = Data::new(&model);
    let from = forward_kinematics(&model, &mut data, &start)?.translation;
    let (roll, pitch, yaw) = target.rpy();
    let times: Vec<f64> = run.samples.iter().map(|s| s.time).collect();
    let configurations: Vec<Vec<f64>> = run.samples.iter().map(|s| s.q.clone()).collect();
    let options = planner.options();
    Ok(Report {
        name: "mpc".into(),
        title: format!("MPC to a target pose on {}", model.name()),
        description: format!(
            "{} moves its end effector from ({}) m to the target ({}) m, roll-pitch-yaw ({}) rad, under \
             seed 000's incremental MPC (eqs 13-21): N = {}, M = {}, T = {} s, {}, velocity and position \
             limits as QP constraints, re-linearised every sample; QP solver {solver}. Start q = ({}).",
            model.name(),
            join(from.as_slice(), 3),
            join(target.translation.as_slice(), 3),
            join(&[roll, pitch, yaw], 3),
            options.horizon,
            options.control_horizon,
            options.sample_time,
            if run.tracks_orientation {
                "position and orientation tracked"
            } else {
                "position tracked"
            },
            join(&start, 3),
        ),
        checks,
        findings: Vec::new(),
        tables: vec![joint_table(&model, &run, &start, &final_q)],
        figures: figures(&run, model.name(), &model)
            .into_iter()
            .map(|(stem, figure)| (stem.to_string(), figure))
            .collect(),
        notes: Vec::new(),
        animation: Some(
            Animation::from_configurations(&model, &times, &configurations)?
                .with_target(&target.translation),
        ),
    })
}

/// Each joint's start, end, travel and peak speed against its limits.
fn joint_table(model: &Model, run: &MpcRun, start: &[f64], end: &[f64]) -> Table {
    let mut table = Table::new(
        "Joints (m for prismatic, rad for rotational joints)",
        &[
            "joint",
            "start",
            "end",
            "range",
            "travel",
            "peak |velocity|",
            "velocity limit",
        ],
    );
    for (j, joint) in model.joints().iter().enumerate() {
        let limits = &joint.limits;
        table.push(vec![
            joint.name.clone(),
            format!("{:.4}", start[j]),
            format!("{:.4}", end.get(j).copied().unwrap_or(f64::NAN)),
            format!("[{:.3}, {:.3}]", limits.lower, limits.upper),
            format!("{:.4}", run.travel(j)),
            format!("{:.4}", run.peak_speed(j)),
            limits.velocity.map_or("-".into(), |v| format!("{v:.4}")),
        ]);
    }
    table
}
