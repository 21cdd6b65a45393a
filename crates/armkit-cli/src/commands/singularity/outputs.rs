//! The files and the JSON summary of `armkit singularity`.

use std::path::Path;

use super::tables::table_runs;
use super::{BaseArg, SingularityArgs, Study};
use crate::common::{CliError, CliResult};
use crate::report::{write_atomic, Report};

/// Writes the report's files into `dir` and `summary.csv`; returns the paths.
pub(super) fn write_outputs(dir: &Path, study: &Study, report: &Report) -> CliResult<Vec<String>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError(format!("{}: cannot create: {e}", dir.display())))?;
    let absolute = dir
        .canonicalize()
        .map_err(|e| CliError(format!("{}: {e}", dir.display())))?;
    let (Some(parent), Some(name)) = (absolute.parent(), absolute.file_name()) else {
        return Err(CliError(format!(
            "--out {}: give a folder other than the root",
            dir.display()
        )));
    };
    let mut named = report.clone();
    named.name = name.to_string_lossy().to_string();
    named.write(parent)?;
    let mut files: Vec<String> = report
        .figures
        .iter()
        .flat_map(|(stem, _)| [format!("{stem}.csv"), format!("{stem}.svg")])
        .chain(["summary.json".to_string(), "report.html".to_string()])
        .map(|f| dir.join(f).display().to_string())
        .collect();
    let summary = dir.join("summary.csv");
    write_atomic(&summary, summary_csv(study).as_bytes())?;
    files.push(summary.display().to_string());
    Ok(files)
}

/// `summary.csv`: one row per method of the table.
fn summary_csv(study: &Study) -> String {
    let mut out = "method,status,peak_joint_rate,max_position_error_m,max_orientation_error_rad,\
                   final_position_error_m,final_orientation_error_rad,time_in_singular_region_s,\
                   mean_region_position_error_m,mean_region_orientation_error_rad,ik_solves\n"
        .to_string();
    for run in table_runs(study) {
        let s = &run.summary;
        out += &format!(
            "{},{},{},{},{},{},{},{},{},{},{}\n",
            run.method.label(),
            run.status,
            s.peak_joint_rate,
            s.max_position_error,
            s.max_orientation_error,
            s.final_position_error,
            s.final_orientation_error,
            s.time_in_singular_region,
            s.mean_region_position_error,
            s.mean_region_orientation_error,
            s.ik_solves
        );
    }
    out
}

/// The `--json` summary (checks and files are added by the caller).
pub(super) fn summary_json(study: &Study, args: &SingularityArgs) -> serde_json::Value {
    let goal = &study.outcome.line.goal;
    let (roll, pitch, yaw) = goal.rpy();
    let mut value = serde_json::json!({
        "robot": study.plant.arm().name(),
        "base": match study.base { BaseArg::Fixed => "fixed", BaseArg::AttitudeHeld => "attitude-held" },
        "through": study.through,
        "direction": study.direction,
        "miss": args.miss,
        "start": study.outcome.line.start,
        "goal_xyz_rpy": [goal.translation.x, goal.translation.y, goal.translation.z, roll, pitch, yaw],
        "duration": args.duration,
        "accel_time": args.accel_time,
        "dt": study.outcome.options.tracking.dt,
        "determinant_threshold": study.outcome.options.detection.determinant_threshold,
        "joint_step_threshold": study.outcome.options.detection.joint_step_threshold,
        "k": study.outcome.ks,
        "threshold_rule": study.outcome.threshold.as_str(),
        "miss_sweep": study.outcome.sweep.lines.iter().map(|l| serde_json::json!({
            "miss": l.miss,
            "least_squares_knots": l.bounded_knots,
            "joint_planned_regions": l.joint_planned_regions,
            "floor": l.floor.map(|f| serde_json::json!({
                "time": f.time,
                "position": f.position,
                "orientation": f.orientation,
                "pose_error": f.norm,
            })),
            "methods": l.methods().iter().map(|(name, s)| serde_json::json!({
                "method": name,
                "peak_joint_rate": s.peak_joint_rate,
                "max_position_error": s.max_position_error,
                "max_orientation_error": s.max_orientation_error,
                "max_pose_error": s.max_pose_error,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "methods": table_runs(study).iter().map(|r| serde_json::json!({
            "method": r.method.label(),
            "status": r.status.to_string(),
            "peak_joint_rate": r.summary.peak_joint_rate,
            "max_position_error": r.summary.max_position_error,
            "max_orientation_error": r.summary.max_orientation_error,
            "final_position_error": r.summary.final_position_error,
            "final_orientation_error": r.summary.final_orientation_error,
            "time_in_singular_region": r.summary.time_in_singular_region,
            "mean_region_position_error": r.summary.mean_region_position_error,
            "mean_region_orientation_error": r.summary.mean_region_orientation_error,
            "ik_solves": r.summary.ik_solves,
            "min_determinant": r.determinant.iter().copied().fold(f64::INFINITY, f64::min),
            "regions": r.regions.iter().map(|g| serde_json::json!({
                "start_time": g.start_time,
                "end_time": g.end_time,
                "trigger": g.trigger.as_str(),
                "knots": g.knot_times.len(),
                "ik_solves": g.ik_solves,
                "ik_failures": g.ik_failures,
                "bounded_knots": g.bounded_knots,
                "plan": g.plan.as_str(),
                "greedy_max_error": g.greedy_max_error,
                "cone_programs": g.cone_programs,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    });
    let outcome = &study.outcome;
    value["region_plan"] = outcome.options.region_plan.as_str().into();
    value["feedback"] = outcome.options.tracking.feedback.as_str().into();
    value["as_printed"] = outcome.as_printed.as_ref().map(as_printed_json).into();
    value["open_loop"] = outcome
        .open_loop
        .iter()
        .map(|r| {
            serde_json::json!({
                "method": r.method.label(),
                "status": r.status.to_string(),
                "max_position_error": r.summary.max_position_error,
                "mean_region_position_error": r.summary.mean_region_position_error,
                "mean_region_orientation_error": r.summary.mean_region_orientation_error,
            })
        })
        .collect::<Vec<_>>()
        .into();
    value
}

/// The as-printed line's figures in the `--json` summary.
fn as_printed_json(a: &armkit::study::AsPrintedLine) -> serde_json::Value {
    let methods: Vec<serde_json::Value> = std::iter::once(("plain".to_string(), &a.plain.summary))
        .chain(a.k_sweep.iter().map(|r| (r.method.label(), &r.summary)))
        .chain([
            ("dls".to_string(), &a.damped_least_squares),
            ("sri".to_string(), &a.singularity_robust),
            (armkit::singularity::SEPARATION.to_string(), &a.separation),
        ])
        .map(|(name, s)| {
            serde_json::json!({
                "method": name,
                "peak_joint_rate": s.peak_joint_rate,
                "max_position_error": s.max_position_error,
                "max_orientation_error": s.max_orientation_error,
                "mean_region_position_error": s.mean_region_position_error,
            })
        })
        .collect();
    serde_json::json!({
        "miss": a.miss,
        "eps_dq_deg_per_s": a.eps_dq_deg_per_s,
        "joint_step_threshold": a.options.detection.joint_step_threshold,
        "determinant_threshold": a.options.detection.determinant_threshold,
        "threshold_rule": a.threshold.as_str(),
        "methods": methods,
    })
}
