//! `armkit traj`: joint-space profiles and Cartesian lines, sampled to CSV
//! and plotted to SVG.
//!
//! * `armkit traj joint --robot panda --from Q0 --to QF [--profile quintic]
//!   [--duration T [--accel-time TA]]`: a point-to-point profile (minimum
//!   time under the robot's limits when no duration is given).
//! * `armkit traj line --robot panda --from Q0 (--to-pose X,Y,Z,R,P,Y |
//!   --to-q Q1) [--duration T] [--law quintic]`: a straight Cartesian line
//!   from the pose of Q0, followed with seed 002's continuous-path method
//!   (IK at the knots, polynomial segments, adaptive segmentation to
//!   `--tolerance`). Exit code 3 when the tolerance is not met.
//!
//! The CSV has a header row: `t`, `q1..qn`, `qd1..qdn`, `qdd1..qddn`, then
//! the end-effector pose `x, y, z` (m) and `roll, pitch, yaw` (rad, world
//! frame). `--plots DIR` writes `positions.svg`, `velocities.svg` and
//! `accelerations.svg`.

use std::path::PathBuf;

use armkit::kinematics::{forward_kinematics, Data};
use armkit::study::{
    BoundaryKind, ContinuousPathStudy, IkKind, LawKind, OrientationKind, PathGoal, SchemeKind,
    TaskKind, TorqueStudy,
};
use armkit::trajectory::PathStatus;
use armkit::trajectory::{self, ProfileShape};
use armkit::trajectory::{check_limits, peak_rates, LimitKind, TrajectoryLimits};
use armkit::trajectory::{JointState, Trajectory};
use armkit::Model;
use clap::{Args, Subcommand, ValueEnum};

use crate::common::{
    parse_fixed_numbers, parse_joint_positions, parse_pose, print_json, CliError, CliResult,
    LimitPolicy, Outcome, RobotArgs,
};
use crate::plot::Figure;
use crate::report::{Animation, Report, Table};

mod line;
mod line_report;
mod output;

use line::run_line;
pub use line::{
    BoundaryArg, DynamicsArg, IkArg, LawArg, LineArgs, OrientationArg, SchemeArg, TaskArg,
};
pub use line_report::line_report;
use output::sample;
pub use output::{joint_figures, write_outputs};

/// `armkit traj` arguments.
#[derive(Args, Debug)]
pub struct TrajArgs {
    #[command(subcommand)]
    pub command: TrajCommand,
}

/// The trajectory kinds.
#[derive(Subcommand, Debug)]
pub enum TrajCommand {
    /// Joint-space point-to-point profile between two configurations.
    Joint(JointArgs),
    /// Straight Cartesian line, followed by seed 002's continuous-path method.
    Line(LineArgs),
}

/// Where and how densely the trajectory is written.
#[derive(Args, Debug, Clone)]
pub struct OutputArgs {
    /// Sampling period of the CSV and plots, s.
    #[arg(
        long,
        default_value_t = 0.01,
        value_name = "S",
        allow_hyphen_values = true
    )]
    pub dt: f64,
    /// CSV file: t, q, qd, qdd, end-effector x y z roll pitch yaw.
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Directory for SVG plots (created if missing): positions.svg,
    /// velocities.svg, accelerations.svg.
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// `--profile` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ProfileArg {
    /// Cubic polynomial, rest to rest.
    Cubic,
    /// Quintic polynomial, rest to rest.
    Quintic,
    /// Trapezoidal velocity (needs --accel-time with --duration).
    Trapezoidal,
}

impl From<ProfileArg> for ProfileShape {
    fn from(p: ProfileArg) -> Self {
        match p {
            ProfileArg::Cubic => ProfileShape::Cubic,
            ProfileArg::Quintic => ProfileShape::Quintic,
            ProfileArg::Trapezoidal => ProfileShape::Trapezoidal,
        }
    }
}

/// `armkit traj joint`.
#[derive(Args, Debug)]
pub struct JointArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Start configuration, comma-separated (rad or m; `pi/2`, `90deg` work).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub from: String,
    /// Goal configuration.
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub to: String,
    /// Profile shape.
    #[arg(long, value_enum, default_value_t = ProfileArg::Quintic)]
    pub profile: ProfileArg,
    /// Duration, s. Without it: the minimum time under the robot's velocity
    /// and acceleration limits.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub duration: Option<f64>,
    /// Acceleration (and deceleration) time of the trapezoid, s (with --duration).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub accel_time: Option<f64>,
    /// Accept configurations outside the joint limits.
    #[arg(long)]
    pub allow_out_of_limits: bool,
    #[command(flatten)]
    pub output: OutputArgs,
    #[command(flatten)]
    pub torques: super::traj_torques::TorqueArgs,
}

/// Runs `armkit traj`.
pub fn run(args: &TrajArgs) -> CliResult<Outcome> {
    match &args.command {
        TrajCommand::Joint(a) => run_joint(a),
        TrajCommand::Line(a) => run_line(a),
    }
}

fn run_joint(args: &JointArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let policy = LimitPolicy::from_flag(args.allow_out_of_limits);
    let q0 = parse_joint_positions(&args.from, &model, policy).map_err(|e| rename(e, "--from"))?;
    let qf = parse_joint_positions(&args.to, &model, policy).map_err(|e| rename(e, "--to"))?;
    let shape = ProfileShape::from(args.profile);
    let limits = TrajectoryLimits::from_model(&model);
    let traj = match args.duration {
        Some(duration) => trajectory::rest_to_rest(shape, &q0, &qf, duration, args.accel_time)?,
        None => {
            if args.accel_time.is_some() {
                return Err(CliError(
                    "--accel-time needs --duration (without it the profile is minimum-time)".into(),
                ));
            }
            trajectory::minimum_time(shape, &q0, &qf, &limits).map_err(|e| {
                CliError(format!(
                    "{e} (the robot's limits; give --duration to plan without them)"
                ))
            })?
        }
    };
    let (traj, torques) = super::traj_torques::check(&model, traj, &args.torques, &args.output)?;
    let mut summary = summarize(&model, &traj, &limits)?;
    summary["torques"] = torques.json();
    summary["profile"] = serde_json::json!(format!("{:?}", args.profile).to_lowercase());
    summary["minimum_time"] = serde_json::json!(args.duration.is_none());
    let files = write_outputs(&model, &traj, &args.output)?;
    summary["files"] = serde_json::json!(files);
    report_summary(&summary, args.output.json)?;
    torques.print(args.output.json);
    Ok(Outcome::Success)
}

/// Puts the option's name in a message from `parse_joint_positions` (which says `--q`).
fn rename(error: CliError, option: &str) -> CliError {
    CliError(error.0.replacen("--q", option, 1))
}

/// Duration, segments, peak rates and limit violations, as JSON.
fn summarize(
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
fn report_summary(summary: &serde_json::Value, json: bool) -> CliResult {
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
