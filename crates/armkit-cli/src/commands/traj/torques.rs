//! `armkit traj joint|line --torques` / `--fit-torque-limits`: the joint
//! torques along the trajectory (inverse dynamics, gravity along -z) against
//! the motors' limits, the uniform slow-down that meets them, and
//! `torques.svg`.

use armkit::trajectory::{
    peak_rates, scale_to_torque_limits, torque_profile, TorqueCheckOptions, TorqueReport,
    TorqueStatus, Trajectory, TrajectoryLimits,
};
use armkit::Model;
use clap::Args;

use super::output::OutputArgs;
use crate::common::{parse_fixed_numbers, CliResult, Outcome};
use crate::plot::Figure;

/// The torque options of `armkit traj joint`.
#[derive(Args, Debug, Clone, Default)]
pub struct TorqueArgs {
    /// Report each joint's peak torque (inverse dynamics, gravity (0,0,-9.81);
    /// needs link masses) against its limit; with --plots also torques.svg.
    #[arg(long)]
    pub torques: bool,
    /// Slow the trajectory down uniformly until every torque is within its
    /// limit (implies --torques).
    #[arg(long)]
    pub fit_torque_limits: bool,
    /// Torque limits, N m or N, one per joint (default: the model's effort limits).
    #[arg(long, value_name = "T1,T2,...", allow_hyphen_values = true)]
    pub torque_limits: Option<String>,
}

/// What the torque check found: JSON for the summary, text lines, files.
#[derive(Default)]
pub struct TorqueSummary {
    json: serde_json::Value,
    text: Vec<String>,
    /// The limits asked for are not met (exit 3), and why.
    unmet: Option<String>,
}

impl TorqueSummary {
    /// The summary's `torques` entry (`null` when no check was asked for).
    pub fn json(&self) -> serde_json::Value {
        self.json.clone()
    }

    /// Prints the text lines (nothing in JSON mode: the summary holds them),
    /// and on stderr why the limits are not met when they are not.
    pub fn print(&self, json: bool) {
        if !json {
            for line in &self.text {
                println!("{line}");
            }
        }
        if let Some(reason) = &self.unmet {
            eprintln!("{reason}");
        }
    }

    /// Success, or not converged (exit 3) when `--fit-torque-limits` could
    /// not meet the limits.
    pub fn outcome(&self) -> Outcome {
        if self.unmet.is_some() {
            Outcome::NotConverged
        } else {
            Outcome::Success
        }
    }
}

/// Checks (and with `--fit-torque-limits` rescales) `traj`; returns the
/// trajectory to write and the summary. Writes `torques.svg` into `--plots`.
pub fn check(
    model: &Model,
    traj: Trajectory,
    args: &TorqueArgs,
    output: &OutputArgs,
) -> CliResult<(Trajectory, TorqueSummary)> {
    if args.torque_limits.is_some() && !(args.torques || args.fit_torque_limits) {
        return Err("--torque-limits needs --torques or --fit-torque-limits"
            .to_string()
            .into());
    }
    if !(args.torques || args.fit_torque_limits) {
        return Ok((traj, TorqueSummary::default()));
    }
    let limits = args
        .torque_limits
        .as_ref()
        .map(|t| parse_fixed_numbers(t, "--torque-limits", model.dof()))
        .transpose()?;
    let options = TorqueCheckOptions {
        limits,
        ..Default::default()
    };
    let (traj, factor, report) = if args.fit_torque_limits {
        let scaled = scale_to_torque_limits(model, &traj, &options)?;
        (scaled.trajectory, Some(scaled.factor), scaled.after)
    } else {
        let report = torque_profile(model, &traj, &options)?;
        (traj, None, report)
    };
    let mut summary = describe(&report, factor);
    if factor.is_some() && summary.unmet.is_none() {
        // The fit slows the path for the torques; a joint still faster than
        // its velocity limit makes "within-limits" untrue for the run.
        if let Some(reason) = velocity_excess(model, &traj) {
            summary.text.push(format!("warning: {reason}"));
            summary.json["status"] = serde_json::json!("exceeds-velocity-limits");
            summary.unmet = Some(reason);
        }
    }
    if let Some(dir) = &output.plots {
        std::fs::create_dir_all(dir)?;
        let path = dir.join("torques.svg");
        let svg = torque_figure(model.name(), &report)
            .to_svg(800, 450)
            .map_err(|e| format!("{}: plot: {e}", path.display()))?;
        std::fs::write(&path, svg).map_err(|e| format!("{}: {e}", path.display()))?;
        summary.text.push(format!("wrote {}", path.display()));
        summary.json["plot"] = serde_json::json!(path.display().to_string());
    }
    Ok((traj, summary))
}

/// Why the fitted `traj` breaks the model's velocity limits (the joint with
/// the largest peak / limit ratio, and the duration at which every joint
/// meets its limit), or `None` when it keeps them.
fn velocity_excess(model: &Model, traj: &Trajectory) -> Option<String> {
    let limits = TrajectoryLimits::from_model(model).velocity;
    let peaks = peak_rates(traj).velocity;
    let (joint, ratio) = peaks
        .iter()
        .zip(&limits)
        .map(|(peak, limit)| peak / limit)
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (j, r)| if r > best.1 { (j, r) } else { best },
        );
    let over = peaks.iter().zip(&limits).filter(|(p, l)| p > l).count();
    (ratio > 1.0).then(|| {
        format!(
            "velocity limits not met: {over} of {} joints exceed their limit, joint {} ({}) by \
             {ratio:.2}x (peak {:.4}, limit {:.4}); the fit slows the path for the torques only: \
             a duration of {:.4} s or more keeps every velocity limit",
            peaks.len(),
            joint + 1,
            model.joints()[joint].name,
            peaks[joint],
            limits[joint],
            traj.duration() * ratio
        )
    })
}

fn describe(report: &TorqueReport, factor: Option<f64>) -> TorqueSummary {
    let mut text = Vec::new();
    if let Some(k) = factor {
        text.push(format!(
            "torque limits: slowed down by a factor {k:.6} (duration {:.6} s)",
            report.times.last().unwrap_or(&0.0) - report.times.first().unwrap_or(&0.0)
        ));
    }
    text.push(format!(
        "joint torques ({} samples, gravity 9.81 m/s^2 along -z): {}",
        report.times.len(),
        report.status
    ));
    let peaks: Vec<serde_json::Value> = report
        .peaks
        .iter()
        .map(|p| {
            let limit = p.limit.map_or("no limit".to_string(), |l| {
                format!("limit {l:.3} ({:.1} %)", 100.0 * p.peak / l)
            });
            text.push(format!(
                "  {}: peak |tau| {:.3} at {:.4} s, {limit}",
                p.name, p.peak, p.time
            ));
            serde_json::json!({"joint": p.name, "peak": p.peak, "time_s": p.time, "limit": p.limit, "ratio": p.ratio()})
        })
        .collect();
    if report.status == TorqueStatus::GravityExceedsLimits {
        text.push(
            "warning: gravity alone exceeds a torque limit on this path: no timing can meet it"
                .into(),
        );
    }
    // A fit promises limits met; a plain `--torques` check reports peaks.
    let unmet = match report.status {
        TorqueStatus::GravityExceedsLimits => Some(
            "torque limits not met: gravity alone exceeds a limit on this path, no timing can meet it"
                .to_string(),
        ),
        TorqueStatus::ExceedsLimits => Some("torque limits not met: a joint exceeds its limit".to_string()),
        _ => None,
    }
    .filter(|_| factor.is_some());
    TorqueSummary {
        unmet,
        json: serde_json::json!({
            "status": report.status.as_str(),
            "time_scaling_factor": factor,
            "peaks": peaks,
        }),
        text,
    }
}

fn torque_figure(robot: &str, report: &TorqueReport) -> Figure {
    let mut figure = Figure::new(
        format!("{robot}: joint torques (inverse dynamics)"),
        "t (s)",
        "tau (N m or N)",
        report.times.clone(),
    );
    for (j, peak) in report.peaks.iter().enumerate() {
        figure = figure.with_series(
            format!("joint {} ({})", j + 1, peak.name),
            report.torques.iter().map(|tau| tau[j]).collect(),
        );
    }
    figure
}
