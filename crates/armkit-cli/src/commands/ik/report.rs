//! Text and JSON forms of IK results, shared by `ik` and `bench-ik`.

use armkit::ik::closed_form::Fit;
use armkit::ik::{IkReport, IkStatus};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Pose;
use armkit::Model;

use crate::common::{CliResult, Outcome};

/// Exit outcome of a status.
pub(super) fn outcome(status: IkStatus) -> Outcome {
    match status {
        IkStatus::Converged => Outcome::Success,
        IkStatus::NotConverged => Outcome::NotConverged,
    }
}

/// One entry of `solution_fits`.
pub(super) fn fit_json(fit: Fit, position_error: f64, orientation_error: f64) -> serde_json::Value {
    serde_json::json!({
        "fit": fit.as_str(),
        "position_error": position_error,
        "orientation_error": orientation_error,
    })
}

/// The JSON of a numeric (or auto) report.
pub(super) fn report_json(robot: &str, solver: &str, report: &IkReport) -> serde_json::Value {
    serde_json::json!({
        "robot": robot,
        "solver": solver,
        "status": report.status.as_str(),
        "q": report.q,
        "position_error": report.position_error,
        "orientation_error": report.orientation_error,
        "iterations": report.iterations,
        "restarts": report.restarts,
        "elapsed_us": report.elapsed.as_secs_f64() * 1e6,
    })
}

/// Joint values, 9 decimals, comma-separated.
pub(super) fn format_q(q: &[f64]) -> String {
    q.iter()
        .map(|v| format!("{:.9}", crate::common::clean_zero(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The text of a numeric (or auto) report.
pub(super) fn describe_report(robot: &str, solver: &str, report: &IkReport) -> String {
    format!(
        "{robot}: inverse kinematics ({solver})\nstatus: {}\nq (rad or m): {}\nposition error: {:.3e} m, orientation error: {:.3e} rad\niterations: {}, restarts: {}, time: {:.1} us\n",
        report.status,
        format_q(&report.q),
        report.position_error,
        report.orientation_error,
        report.iterations,
        report.restarts,
        report.elapsed.as_secs_f64() * 1e6
    )
}

/// Position and orientation error of `FK(q)` from `target`.
pub(super) fn errors(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    target: &Pose,
) -> CliResult<(f64, f64)> {
    let pose = forward_kinematics(model, data, q)?;
    let e = armkit::ik::pose_error(target, pose);
    Ok((e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm()))
}
