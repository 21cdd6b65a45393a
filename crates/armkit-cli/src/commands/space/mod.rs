//! `armkit space`: free-floating space robots (seed 004): the generalized
//! Jacobian, a momentum-conserving simulation of a random joint motion, and
//! resolved-rate tracking of a straight-line pose path, and seed 004's
//! space-robot study.

use std::path::PathBuf;

use armkit::error::brief;
use armkit::math::{Pose, Vector3};
use armkit::robots::space6r_base_body;
use armkit::space::{generalized_jacobian, BaseBody, BaseMode, FreeFloatingModel, SpaceData};
use clap::{Args, Subcommand, ValueEnum};

use crate::common::{
    format_rows, jacobian_rows, parse_fixed_numbers, parse_joint_positions, parse_pose, pose_rows,
    positive, print_json, CliError, CliResult, LimitPolicy, Outcome, RobotArgs,
};

mod csv;
mod simulate;
mod study;
mod track;

pub use study::{report as study_report, SpaceStudyArgs};

/// Free-floating space robot: a base body carrying the arm, momentum zero.
#[derive(Args, Debug)]
pub struct SpaceArgs {
    #[command(subcommand)]
    pub command: SpaceCommand,
}

/// `armkit space` subcommands.
#[derive(Subcommand, Debug)]
pub enum SpaceCommand {
    /// The generalized Jacobian J* (rows vx vy vz wx wy wz of the end effector, inertial frame).
    Jacobian(SpaceJacobianArgs),
    /// Simulate a smooth random joint motion; CSV of base, centre of mass and momenta.
    Simulate(SimulateArgs),
    /// Resolved-rate tracking of a straight-line pose path with J* (trapezoidal speed).
    Track(TrackArgs),
    /// Seed 004's space-robot study: free-floating and attitude-held runs,
    /// centre of mass, momenta, J* against the simulation, the base motion.
    Study(SpaceStudyArgs),
}

/// `--base-mode` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BaseModeArg {
    /// Base attitude held by the attitude control (w0 = 0), linear momentum zero (seed 004).
    AttitudeHeld,
    /// Nothing acts on the base: linear and angular momentum zero (Umetani-Yoshida).
    #[value(alias = "free-floating")]
    Free,
}

impl From<BaseModeArg> for BaseMode {
    fn from(mode: BaseModeArg) -> Self {
        match mode {
            BaseModeArg::AttitudeHeld => BaseMode::AttitudeHeld,
            BaseModeArg::Free => BaseMode::FreeFloating,
        }
    }
}

/// The base body carrying the arm (space6r's satellite unless changed).
#[derive(Args, Debug, Clone, Default)]
pub struct BaseBodyArgs {
    /// Base body mass, kg (default: space6r's 400 kg satellite).
    #[arg(long, value_name = "KG", allow_hyphen_values = true)]
    pub base_mass: Option<String>,
    /// Base principal moments of inertia about its centre of mass, along the
    /// base frame's axes, kg m^2 (default: space6r's satellite, 66.67,81.33,81.33).
    #[arg(long, value_name = "IXX,IYY,IZZ", allow_hyphen_values = true)]
    pub base_inertia: Option<String>,
    /// Arm mount in the base frame, m and rad (R = Rz(yaw) Ry(pitch) Rx(roll);
    /// default: space6r's, 0,0,0.5,0,0,0).
    #[arg(long, value_name = "X,Y,Z,ROLL,PITCH,YAW", allow_hyphen_values = true)]
    pub base_mount: Option<String>,
}

impl BaseBodyArgs {
    /// The free-floating system: the arm (`--robot space6r` when none is
    /// given; every link needs mass properties) on this base body.
    pub fn system(&self, robot: &RobotArgs) -> CliResult<FreeFloatingModel> {
        let mut robot = robot.clone();
        if robot.robot.is_none() && robot.robot_file.is_none() && robot.urdf.is_none() {
            robot.robot = Some("space6r".into());
        }
        let arm = robot.load()?;
        let mut base: BaseBody = space6r_base_body();
        if let Some(text) = &self.base_mass {
            base.mass = parse_fixed_numbers(text, "--base-mass", 1)?[0];
        }
        if let Some(text) = &self.base_inertia {
            let moments = parse_fixed_numbers(text, "--base-inertia", 3)?;
            base.inertia =
                armkit::math::Matrix3::from_diagonal(&Vector3::from_column_slice(&moments));
        }
        if let Some(text) = &self.base_mount {
            base.mount = parse_pose(text, "--base-mount")?;
        }
        Ok(FreeFloatingModel::new(base, arm)?)
    }
}

/// The free-floating system: arm, base body, base mode and base pose.
#[derive(Args, Debug)]
pub struct SystemArgs {
    /// The arm (default: --robot space6r). Every link needs mass properties.
    #[command(flatten)]
    pub robot: RobotArgs,
    /// What the base does while the arm moves.
    #[arg(long, value_enum, default_value_t = BaseModeArg::AttitudeHeld)]
    pub base_mode: BaseModeArg,
    #[command(flatten)]
    pub body: BaseBodyArgs,
    /// Initial base pose in the inertial frame, m and rad.
    #[arg(
        long,
        value_name = "X,Y,Z,ROLL,PITCH,YAW",
        default_value = "0,0,0,0,0,0",
        allow_hyphen_values = true
    )]
    pub base_pose: String,
}

impl SystemArgs {
    /// Builds the model (space6r by default) and its base body.
    fn load(&self) -> CliResult<(FreeFloatingModel, Pose)> {
        let model = self.body.system(&self.robot)?;
        let pose = parse_pose(&self.base_pose, "--base-pose")?;
        Ok((model, pose))
    }
}

/// Arguments of `armkit space jacobian`.
#[derive(Args, Debug)]
pub struct SpaceJacobianArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    /// Joint positions, comma-separated (rad or m; `pi/2` and `90deg` work).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub q: String,
    /// Evaluate even when a joint is outside its limits.
    #[arg(long)]
    pub allow_out_of_limits: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `armkit space simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    /// Initial joint positions (default: space6r's 0.3,0.8,-0.6,0.4,0.9,-0.3,
    /// other arms' mid-range configuration).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Simulated time, s.
    #[arg(long, default_value_t = 60.0)]
    pub duration: f64,
    /// Step, s.
    #[arg(long, default_value_t = 0.01)]
    pub dt: f64,
    /// Seed of the random joint motion.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Amplitude of each joint's excursion, rad (or m).
    #[arg(long, default_value_t = 0.5)]
    pub amplitude: f64,
    /// Highest angular frequency of the joint motion, rad/s.
    #[arg(long, default_value_t = 0.5)]
    pub max_frequency: f64,
    /// CSV file to write (one row per step).
    #[arg(long, value_name = "PATH")]
    pub output: Option<PathBuf>,
    /// Directory for SVG plots (created if missing): com_drift.svg,
    /// momentum.svg, base_position.svg, base_attitude.svg.
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `armkit space track`.
#[derive(Args, Debug)]
pub struct TrackArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    /// Initial joint positions (default as for `simulate`).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Goal end-effector pose in the inertial frame, m and rad.
    #[arg(long, value_name = "X,Y,Z,ROLL,PITCH,YAW", allow_hyphen_values = true)]
    pub goal: String,
    /// Duration of the motion, s (seed 004: 20 s).
    #[arg(long, default_value_t = 20.0)]
    pub duration: f64,
    /// Acceleration (and deceleration) time of the trapezoidal speed profile, s
    /// (seed 004: 4 s).
    #[arg(long, default_value_t = 4.0)]
    pub accel_time: f64,
    /// Control period, s.
    #[arg(long, default_value_t = 0.01)]
    pub dt: f64,
    /// Damping of the least-squares inverse of J* (0: plain inverse).
    #[arg(long, default_value_t = 0.0)]
    pub damping: f64,
    /// CSV file to write (one row per control period).
    #[arg(long, value_name = "PATH")]
    pub output: Option<PathBuf>,
    /// Directory for SVG plots (created if missing): tracking_error.svg,
    /// joint_rates.svg.
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `armkit space`.
pub fn run(args: &SpaceArgs) -> CliResult<Outcome> {
    match &args.command {
        SpaceCommand::Jacobian(a) => run_jacobian(a),
        SpaceCommand::Simulate(a) => simulate::run_simulate(a),
        SpaceCommand::Track(a) => track::run_track(a),
        SpaceCommand::Study(a) => study::run(a),
    }
}

fn run_jacobian(args: &SpaceJacobianArgs) -> CliResult<Outcome> {
    let (model, base) = args.system.load()?;
    let q = parse_joint_positions(
        &args.q,
        model.arm(),
        LimitPolicy::from_flag(args.allow_out_of_limits),
    )?;
    let mode = BaseMode::from(args.system.base_mode);
    let mut data = SpaceData::new(&model);
    let rows = jacobian_rows(generalized_jacobian(&model, &mut data, &base, &q, mode)?);
    let base_rows = jacobian_rows(data.base_jacobian());
    let tip = *data.end_effector_pose();
    let com = *data.center_of_mass();
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.arm().name(),
            "base_mode": format!("{mode:?}"),
            "q": q,
            "base_pose": pose_rows(&base),
            "generalized_jacobian": rows,
            "base_jacobian": base_rows,
            "end_effector": pose_rows(&tip),
            "center_of_mass": com.as_slice(),
            "total_mass": model.total_mass(),
        }))?;
    } else {
        println!(
            "{} on a {} kg base ({mode:?}): generalized Jacobian J* (6 x {}), rows vx vy vz wx wy wz, inertial frame",
            model.arm().name(),
            model.base().mass,
            model.dof()
        );
        println!("{}", format_rows(&rows));
        println!("base twist per joint rate [v0; w0] (base frame origin, inertial frame):");
        println!("{}", format_rows(&base_rows));
        println!(
            "centre of mass (m): {:.6} {:.6} {:.6}; total mass {:.3} kg",
            com.x,
            com.y,
            com.z,
            model.total_mass()
        );
    }
    Ok(Outcome::Success)
}

/// Initial joint positions: given, or a well-conditioned default for space6r,
/// or the arm's mid-range configuration.
fn initial_q(text: Option<&str>, model: &FreeFloatingModel) -> CliResult<Vec<f64>> {
    match text {
        Some(text) => parse_joint_positions(text, model.arm(), LimitPolicy::Enforce),
        None if model.arm().name() == "space6r" => Ok(vec![0.3, 0.8, -0.6, 0.4, 0.9, -0.3]),
        None => Ok(model.arm().neutral_configuration()),
    }
}

/// Number of steps of `dt` in `duration`, after checking both.
fn step_count(duration: f64, dt: f64) -> CliResult<usize> {
    for (name, value) in [("--duration", duration), ("--dt", dt)] {
        positive(name, value)?;
    }
    let steps = (duration / dt - 1e-9).ceil().max(1.0);
    if steps > 1e7 {
        return Err(CliError(format!(
            "--duration / --dt = {} steps: at most 1e7",
            brief(steps)
        )));
    }
    Ok(steps as usize)
}
