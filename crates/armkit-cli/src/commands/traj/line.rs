//! `armkit traj line`: seed 002's continuous path along a Cartesian line.

use super::*;

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
    #[command(flatten)]
    pub output: OutputArgs,
}

/// Plans the line the arguments describe with seed 002's continuous-path method.
pub fn plan_line(args: &LineArgs) -> CliResult<LineStudy> {
    let model = args.robot.load()?;
    let policy = LimitPolicy::from_flag(args.allow_out_of_limits);
    let q0 = parse_joint_positions(&args.from, &model, policy).map_err(|e| rename(e, "--from"))?;
    let mut data = Data::new(&model);
    let start = *forward_kinematics(&model, &mut data, &q0)?;
    let goal = match (&args.to_pose, &args.to_q) {
        (Some(text), _) => parse_pose(text, "--to-pose")?,
        (None, Some(text)) => {
            let q1 =
                parse_joint_positions(text, &model, policy).map_err(|e| rename(e, "--to-q"))?;
            *forward_kinematics(&model, &mut data, &q1)?
        }
        (None, None) => return Err(CliError("give --to-pose or --to-q".into())),
    };
    let law = match args.law {
        LawArg::Quintic => TimeLaw::Quintic,
        LawArg::Linear => TimeLaw::Linear,
        LawArg::Trapezoidal => TimeLaw::Trapezoidal {
            acceleration_time: args.accel_time.unwrap_or(0.25 * args.duration),
        },
    };
    if args.accel_time.is_some() && args.law != LawArg::Trapezoidal {
        return Err(CliError("--accel-time is for --law trapezoidal".into()));
    }
    let orientation = match args.orientation {
        OrientationArg::Slerp => OrientationLaw::FollowPath,
        OrientationArg::RpyLinear => OrientationLaw::RpyLinearInTime,
    };
    let path = CartesianTrajectory::new(LinePath::new(start, goal)?, law.timing(args.duration)?)?
        .with_orientation_law(orientation);
    let task = match args.task {
        TaskArg::Pose => IkTask::Pose,
        TaskArg::Position => IkTask::Position,
        TaskArg::Auto if model.dof() < 6 => IkTask::Position,
        TaskArg::Auto => IkTask::Pose,
    };
    let tolerance = match task {
        IkTask::Position => PathTolerance::Position(args.tolerance),
        IkTask::Pose => PathTolerance::Pose {
            position: args.tolerance,
            orientation: args.orientation_tolerance,
        },
    };
    let options = ContinuousPathOptions {
        scheme: match args.scheme {
            SchemeArg::QuarticCubic => {
                SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference)
            }
            SchemeArg::QuarticCubicCentral => {
                SegmentScheme::QuarticCubicQuartic(ViaVelocity::CentralDifference)
            }
            SchemeArg::CubicQuintic => SegmentScheme::CubicQuinticLast,
        },
        segmentation: match args.segments {
            Some(n) => Segmentation::Fixed(n),
            None => Segmentation::Adaptive {
                initial: 4.min(args.max_segments),
                max: args.max_segments,
            },
        },
        tolerance,
        checks_per_segment: args.checks,
        ..Default::default()
    };
    let (mut ik, method): (Box<dyn PathIk>, &str) = match args.ik {
        IkArg::Auto => path_ik_for(&model, task)?,
        IkArg::Numeric => (
            Box::new(NumericPathIk::for_path(&model, task)?),
            "numeric (Levenberg-Marquardt from the previous knot)",
        ),
    };
    let clock = std::time::Instant::now();
    let report = plan_continuous_path(&model, &path, &mut *ik, &q0, &options)?;
    let planning = clock.elapsed();
    let interior = measure_path_error(&model, &report.trajectory, &path, 100)?;
    Ok(LineStudy {
        model,
        start,
        goal,
        task,
        tolerance,
        method,
        report,
        planning,
        interior,
    })
}

/// A planned continuous path and the figures measured on it.
pub struct LineStudy {
    pub(super) model: Model,
    pub(super) start: armkit::math::Pose,
    pub(super) goal: armkit::math::Pose,
    pub(super) task: IkTask,
    pub(super) tolerance: PathTolerance,
    pub(super) method: &'static str,
    pub(super) report: armkit::trajectory::ContinuousPathReport,
    pub(super) planning: std::time::Duration,
    pub(super) interior: armkit::trajectory::PathError,
}

pub(super) fn run_line(args: &LineArgs) -> CliResult<Outcome> {
    let LineStudy {
        model,
        start,
        goal,
        report,
        planning,
        interior,
        method,
        ..
    } = plan_line(args)?;

    let limits = TrajectoryLimits::from_model(&model);
    let mut summary = summarize(&model, &report.trajectory, &limits)?;
    let met = report.status == PathStatus::ToleranceMet;
    summary["profile"] = serde_json::json!("cartesian line");
    summary["status"] = serde_json::json!(report.status.as_str());
    summary["ik"] = serde_json::json!(method);
    summary["length_m"] = serde_json::json!((goal.translation - start.translation).norm());
    summary["checked_error_m"] = serde_json::json!(report.checked_error.position);
    summary["checked_error_rad"] = serde_json::json!(report.checked_error.orientation);
    summary["error_100_points_m"] = serde_json::json!(interior.position);
    summary["error_100_points_rad"] = serde_json::json!(interior.orientation);
    summary["planning_ms"] = serde_json::json!(planning.as_secs_f64() * 1e3);
    summary["ik_solves"] = serde_json::json!(report.ik_solves);
    let files = write_outputs(&model, &report.trajectory, &args.output)?;
    summary["files"] = serde_json::json!(files);
    report_summary(&summary, args.output.json)?;
    Ok(if met {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}
