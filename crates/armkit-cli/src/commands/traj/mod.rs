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

use armkit::trajectory::{self, ProfileShape, TrajectoryLimits};
use clap::{Args, Subcommand, ValueEnum};

use crate::common::{parse_joint_positions, CliError, CliResult, LimitPolicy, Outcome, RobotArgs};

mod line;
mod line_report;
mod output;
mod summary;
mod torques;

use line::run_line;
pub use line::{
    BoundaryArg, DynamicsArg, IkArg, LawArg, LineArgs, OrientationArg, SchemeArg, TaskArg,
};
pub use line_report::line_report;
pub use output::{joint_figures, write_outputs, OutputArgs};
use summary::{rename, report_summary, summarize};
pub use torques::TorqueArgs;

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
    pub torques: TorqueArgs,
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
    let (traj, torques) = torques::check(&model, traj, &args.torques, &args.output)?;
    let mut summary = summarize(&model, &traj, &limits)?;
    summary["torques"] = torques.json();
    summary["profile"] = serde_json::json!(format!("{:?}", args.profile).to_lowercase());
    summary["minimum_time"] = serde_json::json!(args.duration.is_none());
    let files = write_outputs(&model, &traj, &args.output)?;
    summary["files"] = serde_json::json!(files);
    report_summary(&summary, args.output.json)?;
    torques.print(args.output.json);
    Ok(torques.outcome())
}
