//! The summary that `armkit traj joint` and `armkit traj line` print: the
//! duration, peak rates and limit violations, as JSON or as text.

use armkit::trajectory::{check_limits, peak_rates, LimitKind, Trajectory, TrajectoryLimits};
use armkit::Model;

use crate::common::{print_json, CliError, CliResult};

/// Puts the option's name in a message from `parse_joint_positions` (which says `--q`).
pub(super) fn rename(error: CliError, option: &str) -> CliError {
    CliError(error.0.replacen("--q", option, 1))
}

/// Duration, segments, peak rates and limit violations, as JSON.
pub(super) fn summarize(
    model: &Model,
    traj: &Trajectory,
    limits: &TrajectoryLimits,
) -> CliResult<serde_json::Value> {
    let peaks = peak_rates(traj);
    let violations: Vec<serde_json::Value> = check_limits(traj, limits)?
        .iter()
        .map(|v| {
            serde_json::json!({
                "joint": v.joint + 1,
                "kind": match v.kind {
                    LimitKind::Position => "position",
                    LimitKind::Velocity => "velocity",
                    LimitKind::Acceleration => "acceleration",
                },
                "from_s": v.start_time,
                "to_s": v.end_time,
                "peak": v.peak_value,
                "peak_time_s": v.peak_time,
                "bound": v.bound,
            })
        })
        .collect();
    Ok(serde_json::json!({
        "robot": model.name(),
        "duration_s": traj.duration(),
        "segments": traj.segment_count(),
        "peak_velocity": peaks.velocity,
        "peak_acceleration": peaks.acceleration,
        "limit_violations": violations,
    }))
}

/// Prints the summary as JSON or as text.
pub(super) fn report_summary(summary: &serde_json::Value, json: bool) -> CliResult {
    if json {
        return print_json(summary);
    }
    let numbers = |key: &str| -> String {
        summary[key]
            .as_array()
            .map(|a| {
                a.iter()
                    .map(|v| format!("{:.4}", v.as_f64().unwrap_or(f64::NAN)))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .unwrap_or_default()
    };
    println!(
        "{}: {} trajectory, {:.6} s, {} segment(s)",
        summary["robot"].as_str().unwrap_or("?"),
        summary["profile"].as_str().unwrap_or("?"),
        summary["duration_s"].as_f64().unwrap_or(f64::NAN),
        summary["segments"]
    );
    for (key, value) in summary.as_object().into_iter().flatten() {
        if let Some(v) = value
            .as_f64()
            .filter(|_| key.ends_with("_m") || key.ends_with("_rad") || key.ends_with("_ms"))
        {
            println!("{key}: {v:.6e}");
        } else if matches!(key.as_str(), "status" | "ik" | "ik_solves") {
            println!(
                "{key}: {}",
                value.as_str().map_or(value.to_string(), String::from)
            );
        }
    }
    println!("peak |qd|: {}", numbers("peak_velocity"));
    println!("peak |qdd|: {}", numbers("peak_acceleration"));
    let violations = summary["limit_violations"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    if violations.is_empty() {
        println!("within the robot's position, velocity and acceleration limits");
    }
    for v in violations {
        println!(
            "warning: joint {} exceeds its {} limit {} from {:.4} s to {:.4} s (peak {:.6} at {:.4} s)",
            v["joint"],
            v["kind"].as_str().unwrap_or("?"),
            v["bound"],
            v["from_s"].as_f64().unwrap_or(f64::NAN),
            v["to_s"].as_f64().unwrap_or(f64::NAN),
            v["peak"].as_f64().unwrap_or(f64::NAN),
            v["peak_time_s"].as_f64().unwrap_or(f64::NAN)
        );
    }
    for file in summary["files"].as_array().into_iter().flatten() {
        println!("wrote {}", file.as_str().unwrap_or("?"));
    }
    Ok(())
}
