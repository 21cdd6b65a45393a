//! Seed 002's continuous path as a scenario report: the library's
//! [`ContinuousPathStudy`] run and formatted.

use armkit::study::{
    Check, ContinuousPathOutcome, ContinuousPathStudy, PathScope, PlannedPath, TorqueOutcome,
};
use armkit::trajectory::IkTask;
use armkit::trajectory::PathError;
use armkit::Model;

use super::line::LineArgs;
use super::output::{joint_figures, sample};
use crate::common::CliResult;
use crate::report::{Animation, Report, Table};

/// A continuous path as a report (a scenario's `[continuous_path]` table,
/// with the options of `armkit traj line`): the main run, with `scope`
/// paper seed 002's variants beside it and its claims, the torque check
/// when asked for, the joint motion, the arm moving. A line that cannot be
/// planned (a path point the IK cannot solve within the joint limits) is a
/// report with a failed check naming the point and the cause, and the line
/// that was asked for.
pub fn line_report(args: &LineArgs) -> CliResult<Report> {
    let model = args.robot.load()?;
    let study = args.study(&model)?;
    let dynamics = args.dynamics_model()?;
    let (start, goal) = study.end_poses(&model)?;
    let length = (goal.translation - start.translation).norm();
    let paper = study.scope.resolve(&model) == PathScope::Paper;
    let (title, method) = if paper {
        (
            format!("Seed 002: continuous path on {}", model.name()),
            "planned by seed 002's method (sec 3): IK at the n + 1 path points (nearest the previous \
             solution), joint rates by finite differences (eqs 23-24), one polynomial per segment in \
             normalized time (eq 25), and the adaptive segmentation of Fig 6 until the tolerance is met at the \
             check points; the paper's variants beside it, each labelled.",
        )
    } else {
        (
            format!("Continuous path on {}", model.name()),
            "planned by IK at the path points (nearest the previous solution), one polynomial per segment \
             with continuous joint positions and velocities, and segments halved until the tolerance is met \
             at the check points; graded on armkit's promises (tolerance, continuity, joint limits).",
        )
    };
    let description = format!("A straight line of {length:.3} m, {method}");
    let outcome = match study.outcome(&model, dynamics.as_ref()) {
        Ok(outcome) => outcome,
        Err(e @ armkit::Error::InvalidArgument { .. }) if e.to_string().contains("path point") => {
            return Ok(unplanned_report(
                &model,
                &study,
                &e,
                title,
                description,
                length,
            ));
        }
        Err(e) => return Err(e.into()),
    };
    let mut report = Report::from_study("continuous-path", title, description, outcome.report());
    report.tables = vec![plan_table(&outcome, length)];
    if paper {
        report.tables.push(variants_table(&outcome));
        report.tables.push(sweep_table(&outcome));
    }
    if let Some(torques) = &outcome.torques {
        report.tables.push(torque_table(torques));
    }
    let traj = &outcome.main.report.trajectory;
    let (times, states) = sample(traj, (traj.duration() / 400.0).max(1e-3))?;
    let configurations: Vec<Vec<f64>> = states.iter().map(|s| s.position.clone()).collect();
    report.figures.extend(
        joint_figures(&model, &times, &states)
            .into_iter()
            .map(|(stem, figure)| (stem.to_string(), figure)),
    );
    report.animation = Some(Animation::from_configurations(
        &model,
        &times,
        &configurations,
    )?);
    Ok(report)
}

/// The report of a line that could not be planned: the failed check with
/// the planner's cause (which path point, which joint or limit), the line
/// asked for, and the arm at the start.
fn unplanned_report(
    model: &Model,
    study: &ContinuousPathStudy,
    error: &armkit::Error,
    title: String,
    description: String,
    length: f64,
) -> Report {
    let reason = match error {
        armkit::Error::InvalidArgument { reason, .. } => reason.clone(),
        other => other.to_string(),
    };
    let mut report = Report::from_study(
        "continuous-path",
        title,
        description,
        armkit::study::StudyReport {
            checks: vec![Check::holds(
                "every path point is solved within the joint limits",
                false,
                reason,
            )],
            findings: Vec::new(),
            series: Vec::new(),
            notes: vec![
                "The line was not planned: the check above names the path point that failed and why. \
                 Nothing after that point was computed."
                    .to_string(),
            ],
        },
    );
    let mut table = Table::new("Plan", &["quantity", "value"]);
    let pose_text = |p: &armkit::math::Pose| {
        let (r, pi, y) = p.rpy();
        let t = p.translation;
        format!(
            "[{:.4}, {:.4}, {:.4}] m, rpy [{r:.4}, {pi:.4}, {y:.4}] rad",
            t.x, t.y, t.z
        )
    };
    let ends = study.end_poses(model).ok();
    let rows = [
        ("robot", model.name().to_string()),
        ("line length", format!("{length:.4} m")),
        ("start", ends.map_or("-".into(), |(s, _)| pose_text(&s))),
        ("goal", ends.map_or("-".into(), |(_, g)| pose_text(&g))),
        ("duration", format!("{} s", study.duration)),
        ("status", "not planned".to_string()),
    ];
    for (quantity, value) in rows {
        table.push(vec![quantity.to_string(), value]);
    }
    report.tables = vec![table];
    report.animation =
        Animation::from_configurations(model, &[0.0], std::slice::from_ref(&study.start)).ok();
    report
}

fn error_text(error: &PathError, task: IkTask) -> String {
    match task {
        IkTask::Position => format!("{:.3e} m", error.position),
        IkTask::Pose => format!("{:.3e} m, {:.3e} rad", error.position, error.orientation),
    }
}

fn plan_table(outcome: &ContinuousPathOutcome, length: f64) -> Table {
    let main = &outcome.main;
    let mut table = Table::new("Plan", &["quantity", "value"]);
    for (quantity, value) in [
        ("robot", outcome.robot.clone()),
        ("line length", format!("{length:.4} m")),
        (
            "task",
            match outcome.task {
                IkTask::Position => "position".to_string(),
                IkTask::Pose => "full pose".to_string(),
            },
        ),
        ("orientation law", main.label.clone()),
        ("IK", outcome.ik_method.to_string()),
        (
            "segments chosen",
            main.report.trajectory.segment_count().to_string(),
        ),
        ("plan-and-check passes", main.report.passes.to_string()),
        ("IK solves", main.report.ik_solves.to_string()),
        (
            "planning time",
            format!("{:.3} ms", main.planning.as_secs_f64() * 1e3),
        ),
        (
            "error at check points",
            format!(
                "{:.3e} m, {:.3e} rad",
                main.report.checked_error.position, main.report.checked_error.orientation
            ),
        ),
        (
            "error at 100 points per segment",
            format!(
                "{:.3e} m, {:.3e} rad",
                main.interior.position, main.interior.orientation
            ),
        ),
    ] {
        table.push(vec![quantity.to_string(), value]);
    }
    table
}

fn run_row(run: &PlannedPath, task: IkTask) -> Vec<String> {
    vec![
        run.label.clone(),
        run.report.trajectory.segment_count().to_string(),
        run.report.status.to_string(),
        error_text(&run.report.checked_error, task),
        error_text(&run.interior, task),
        String::new(),
    ]
}

fn variants_table(outcome: &ContinuousPathOutcome) -> Table {
    let mut table = Table::new(
        "Seed 002's variants (each labelled; the main run first)",
        &[
            "run",
            "segments",
            "status",
            "error at check points",
            "error at 100 points per segment",
            "rate amplification",
        ],
    );
    let task = outcome.task;
    table.push(run_row(&outcome.main, task));
    for run in [&outcome.other_orientation, &outcome.midpoint_only]
        .into_iter()
        .flatten()
    {
        table.push(run_row(run, task));
    }
    for run in &outcome.cubic_quintic {
        table.push(vec![
            "cubic segments, quintic last (fixed n)".into(),
            run.segments.to_string(),
            run.status.to_string(),
            String::new(),
            error_text(&run.interior, task),
            format!("{:.3e}", run.amplification),
        ]);
    }
    table
}

fn sweep_table(outcome: &ContinuousPathOutcome) -> Table {
    let mut table = Table::new(
        "Error against the number of segments (fixed n, the main run's scheme)",
        &[
            "segments",
            "error at the midpoints",
            "error at 100 points per segment",
        ],
    );
    for row in &outcome.sweep {
        table.push(vec![
            row.segments.to_string(),
            error_text(&row.midpoint, outcome.task),
            error_text(&row.interior, outcome.task),
        ]);
    }
    table
}

fn torque_table(torques: &TorqueOutcome) -> Table {
    let scaling = &torques.scaling;
    let mut table = Table::new(
        format!(
            "Joint torques on {} (played in {:.3} s; uniform slow-down x{:.4} to {:.3} s)",
            torques.dynamics_robot,
            torques.planned_duration / torques.speed_up,
            scaling.factor,
            scaling.trajectory.duration()
        ),
        &[
            "joint",
            "peak |tau| as played",
            "at",
            "limit",
            "peak / limit",
            "peak after slow-down",
        ],
    );
    for (before, after) in scaling.before.peaks.iter().zip(&scaling.after.peaks) {
        table.push(vec![
            before.name.clone(),
            format!("{:.3}", before.peak),
            format!("{:.3} s", before.time),
            before.limit.map_or("none".into(), |l| format!("{l:.1}")),
            before.ratio().map_or("-".into(), |r| format!("{r:.3}")),
            format!("{:.3}", after.peak),
        ]);
    }
    table
}
