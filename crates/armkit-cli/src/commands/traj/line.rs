//! `armkit traj line`: seed 002's continuous path along a Cartesian line.

use armkit::study::{
    BoundaryKind, ContinuousPathStudy, IkKind, LawKind, OrientationKind, PathGoal, PathScope,
    SchemeKind, TaskKind, TorqueStudy,
};
use armkit::trajectory::{PathStatus, TrajectoryLimits};
use armkit::Model;
use clap::{Args, ValueEnum};

use super::output::{write_outputs, OutputArgs};
use super::summary::{rename, report_summary, summarize};
use super::torques::{self, TorqueArgs};
use crate::common::{
    parse_fixed_numbers, parse_joint_positions, parse_pose, CliError, CliResult, LimitPolicy,
    Outcome, RobotArgs,
};

/// `--law` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LawArg {
    /// Quintic from rest to rest.
    Quintic,
    /// Trapezoidal speed (with --accel-time, default a quarter of the duration).
    Trapezoidal,
    /// Constant speed.
    Linear,
}

/// `--orientation` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OrientationArg {
    /// Slerp between the end orientations, in step with the position.
    Slerp,
    /// Seed 002 eqs 20-22: roll, pitch and yaw linear in time.
    RpyLinear,
}

/// `--boundary` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BoundaryArg {
    /// Joints at rest at both ends (for rest-to-rest laws).
    Rest,
    /// End rates by finite differences of the knots (seed 002, eqs 23-24).
    FiniteDifference,
}

/// `--task` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TaskArg {
    /// Position only for robots with fewer than 6 joints (arm4), else the full pose.
    Auto,
    /// Position and orientation.
    Pose,
    /// Position only (the tolerance is on the position).
    Position,
}

/// `--scheme` values (seed 002's polynomial schemes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SchemeArg {
    /// Quartic first and last, cubic middles, via velocities by eq 23 (C1).
    QuarticCubic,
    /// As quartic-cubic with central-difference via velocities (not in the seed).
    QuarticCubicCentral,
    /// Cubic segments and a quintic last one (C2; unstable with many segments).
    CubicQuintic,
}

/// `--ik` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IkArg {
    /// Closed form if the robot has one (arm4, PUMA-type), else numeric.
    Auto,
    /// Numeric (Levenberg-Marquardt from the previous knot).
    Numeric,
}

/// `--scope` values: what a report grades.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ScopeArg {
    /// Seed 002's paper on its 4-DOF arm, armkit's promises on any other robot.
    Auto,
    /// Seed 002: its variants beside the main run, and its claims.
    Paper,
    /// armkit's promises only (tolerance, continuity, joint limits, torques).
    Armkit,
}

/// `armkit traj line`.
#[derive(Args, Debug)]
pub struct LineArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Start configuration (the line starts at its end-effector pose).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub from: String,
    /// Goal pose: x,y,z (m), roll,pitch,yaw (rad; R = Rz(yaw) Ry(pitch) Rx(roll)).
    #[arg(
        long,
        value_name = "X,Y,Z,R,P,Y",
        allow_hyphen_values = true,
        conflicts_with = "to_q",
        required_unless_present = "to_q"
    )]
    pub to_pose: Option<String>,
    /// Goal configuration: the line ends at its end-effector pose.
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub to_q: Option<String>,
    /// Duration, s.
    #[arg(
        long,
        default_value_t = 2.0,
        value_name = "S",
        allow_hyphen_values = true
    )]
    pub duration: f64,
    /// Timing law along the line.
    #[arg(long, value_enum, default_value_t = LawArg::Quintic)]
    pub law: LawArg,
    /// Acceleration time of the trapezoidal law, s (default: duration / 4).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub accel_time: Option<f64>,
    /// How the orientation moves.
    #[arg(long, value_enum, default_value_t = OrientationArg::Slerp)]
    pub orientation: OrientationArg,
    /// Joint rates at both ends.
    #[arg(long, value_enum, default_value_t = BoundaryArg::Rest)]
    pub boundary: BoundaryArg,
    /// What the tolerance and the IK cover.
    #[arg(long, value_enum, default_value_t = TaskArg::Auto)]
    pub task: TaskArg,
    /// Position tolerance, m.
    #[arg(
        long,
        default_value_t = 1e-4,
        value_name = "M",
        allow_hyphen_values = true
    )]
    pub tolerance: f64,
    /// Orientation tolerance, rad (with the full-pose task).
    #[arg(
        long,
        default_value_t = 1e-3,
        value_name = "RAD",
        allow_hyphen_values = true
    )]
    pub orientation_tolerance: f64,
    /// Polynomial scheme.
    #[arg(long, value_enum, default_value_t = SchemeArg::QuarticCubic)]
    pub scheme: SchemeArg,
    /// Check points per segment (1: the seed's midpoint only).
    #[arg(long, default_value_t = 3, value_name = "N")]
    pub checks: usize,
    /// Fixed number of segments instead of the adaptive segmentation.
    #[arg(long, value_name = "N")]
    pub segments: Option<usize>,
    /// Largest number of segments of the adaptive segmentation.
    #[arg(long, default_value_t = 4096, value_name = "N")]
    pub max_segments: usize,
    /// Which IK.
    #[arg(long, value_enum, default_value_t = IkArg::Auto)]
    pub ik: IkArg,
    /// Accept configurations outside the joint limits.
    #[arg(long)]
    pub allow_out_of_limits: bool,
    /// Report only (a scenario's [continuous_path]): the segment counts of
    /// the error-against-segments sweep.
    #[arg(long, value_name = "N,N,...", value_delimiter = ',', default_values_t = [2, 4, 8, 16, 32, 64])]
    pub sweep_segments: Vec<usize>,
    /// Report only: the segment counts at which the cubic-quintic scheme is shown.
    #[arg(long, value_name = "N,N,...", value_delimiter = ',', default_values_t = [4, 8, 16])]
    pub cubic_quintic_segments: Vec<usize>,
    /// Report only: what the report grades.
    #[arg(long, value_enum, default_value_t = ScopeArg::Auto)]
    pub scope: ScopeArg,
    #[command(flatten)]
    pub torques: TorqueArgs,
    /// Play the planned motion this many times faster before the torque
    /// check (which then slows it down to the limits): how fast can the path run?
    #[arg(
        long,
        default_value_t = 1.0,
        value_name = "X",
        allow_hyphen_values = true
    )]
    pub speed_up: f64,
    /// Whose mass properties and effort limits the torque check uses.
    #[arg(long, value_enum, default_value_t = DynamicsArg::Robot)]
    pub dynamics: DynamicsArg,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// `--dynamics` values: whose mass properties and effort limits the torque
/// check uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DynamicsArg {
    /// The planning robot's own (it must have mass properties).
    Robot,
    /// Franka's Panda from example-robot-data's panda.urdf (panda_link0 to
    /// panda_link8, built into armkit): inertias and the effort limits 87 /
    /// 12 N m; for --robot panda, whose joints it shares (checked).
    PandaUrdf,
}

/// The Panda URDF behind `--dynamics panda-urdf` (tests/data/urdf).
const PANDA_URDF: &str = include_str!("../../../../../tests/data/urdf/panda.urdf");

impl LineArgs {
    /// The library study these flags describe, on `model`.
    pub fn study(&self, model: &Model) -> CliResult<ContinuousPathStudy> {
        let policy = LimitPolicy::from_flag(self.allow_out_of_limits);
        let start =
            parse_joint_positions(&self.from, model, policy).map_err(|e| rename(e, "--from"))?;
        let goal = match (&self.to_pose, &self.to_q) {
            (Some(text), _) => {
                let pose = parse_pose(text, "--to-pose")?;
                let (r, p, y) = pose.rpy();
                let t = pose.translation;
                PathGoal::Pose([t.x, t.y, t.z, r, p, y])
            }
            (None, Some(text)) => PathGoal::Configuration(
                parse_joint_positions(text, model, policy).map_err(|e| rename(e, "--to-q"))?,
            ),
            (None, None) => return Err(CliError("give --to-pose or --to-q".into())),
        };
        if self.accel_time.is_some() && self.law != LawArg::Trapezoidal {
            return Err(CliError("--accel-time is for --law trapezoidal".into()));
        }
        let checked = self.torques.torques || self.torques.fit_torque_limits;
        if !(self.speed_up.is_finite() && self.speed_up > 0.0) {
            return Err(CliError(format!(
                "--speed-up: must be finite and > 0, got {}",
                self.speed_up
            )));
        }
        if self.speed_up != 1.0 && !checked {
            return Err(CliError(
                "--speed-up needs --torques or --fit-torque-limits".into(),
            ));
        }
        let torques = (self.torques.torques || self.torques.fit_torque_limits).then(|| {
            self.torques
                .torque_limits
                .as_ref()
                .map(|t| parse_fixed_numbers(t, "--torque-limits", model.dof()))
                .transpose()
                .map(|limits| TorqueStudy {
                    limits,
                    speed_up: self.speed_up,
                    ..TorqueStudy::default()
                })
        });
        Ok(ContinuousPathStudy {
            robot: model.name().to_string(),
            start,
            goal,
            duration: self.duration,
            law: match self.law {
                LawArg::Quintic => LawKind::Quintic,
                LawArg::Trapezoidal => LawKind::Trapezoidal,
                LawArg::Linear => LawKind::Linear,
            },
            acceleration_time: self.accel_time,
            orientation: match self.orientation {
                OrientationArg::Slerp => OrientationKind::Slerp,
                OrientationArg::RpyLinear => OrientationKind::RpyLinear,
            },
            boundary: match self.boundary {
                BoundaryArg::Rest => BoundaryKind::Rest,
                BoundaryArg::FiniteDifference => BoundaryKind::FiniteDifference,
            },
            task: match self.task {
                TaskArg::Auto => TaskKind::Auto,
                TaskArg::Pose => TaskKind::Pose,
                TaskArg::Position => TaskKind::Position,
            },
            tolerance: self.tolerance,
            orientation_tolerance: self.orientation_tolerance,
            scheme: match self.scheme {
                SchemeArg::QuarticCubic => SchemeKind::QuarticCubic,
                SchemeArg::QuarticCubicCentral => SchemeKind::QuarticCubicCentral,
                SchemeArg::CubicQuintic => SchemeKind::CubicQuintic,
            },
            checks_per_segment: self.checks,
            segments: self.segments,
            max_segments: self.max_segments,
            ik: match self.ik {
                IkArg::Auto => IkKind::Auto,
                IkArg::Numeric => IkKind::Numeric,
            },
            segment_sweep: self.sweep_segments.clone(),
            cubic_quintic_segments: self.cubic_quintic_segments.clone(),
            torques: torques.transpose()?,
            scope: match self.scope {
                ScopeArg::Auto => PathScope::Auto,
                ScopeArg::Paper => PathScope::Paper,
                ScopeArg::Armkit => PathScope::Armkit,
            },
        })
    }

    /// The model the torque check runs on, when it is not the robot itself.
    pub fn dynamics_model(&self) -> CliResult<Option<Model>> {
        if self.dynamics != DynamicsArg::Robot
            && !(self.torques.torques || self.torques.fit_torque_limits)
        {
            return Err(CliError(
                "--dynamics needs --torques or --fit-torque-limits".into(),
            ));
        }
        Ok(match self.dynamics {
            DynamicsArg::Robot => None,
            DynamicsArg::PandaUrdf => Some(armkit::urdf::parse_str(
                PANDA_URDF,
                "panda.urdf (built in)",
                &armkit::urdf::ChainSelection::between("panda_link0", "panda_link8"),
            )?),
        })
    }
}

pub(super) fn run_line(args: &LineArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let study = args.study(&model)?;
    let dynamics = args.dynamics_model()?;
    let (planned, method) = study.plan(&model)?;
    let (start, goal) = study.end_poses(&model)?;
    let report = planned.report;
    let (trajectory, torques) = torques::check(
        dynamics.as_ref().unwrap_or(&model),
        report.trajectory.time_scaled(1.0 / args.speed_up)?,
        &args.torques,
        &args.output,
    )?;
    let limits = TrajectoryLimits::from_model(&model);
    let mut summary = summarize(&model, &trajectory, &limits)?;
    summary["torques"] = torques.json();
    summary["profile"] = serde_json::json!("cartesian line");
    summary["status"] = serde_json::json!(report.status.as_str());
    summary["ik"] = serde_json::json!(method);
    summary["length_m"] = serde_json::json!((goal.translation - start.translation).norm());
    summary["checked_error_m"] = serde_json::json!(report.checked_error.position);
    summary["checked_error_rad"] = serde_json::json!(report.checked_error.orientation);
    summary["error_100_points_m"] = serde_json::json!(planned.interior.position);
    summary["error_100_points_rad"] = serde_json::json!(planned.interior.orientation);
    summary["planning_ms"] = serde_json::json!(planned.planning.as_secs_f64() * 1e3);
    summary["ik_solves"] = serde_json::json!(report.ik_solves);
    let files = write_outputs(&model, &trajectory, &args.output)?;
    summary["files"] = serde_json::json!(files);
    report_summary(&summary, args.output.json)?;
    torques.print(args.output.json);
    Ok(if report.status == PathStatus::ToleranceMet {
        torques.outcome()
    } else {
        Outcome::NotConverged
    })
}
