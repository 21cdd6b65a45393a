//! `armkit space`: free-floating space robots (seed 004): the generalized
//! Jacobian, a momentum-conserving simulation of a random joint motion, and
//! resolved-rate tracking of a straight-line pose path.

use std::fmt::Write as _;
use std::path::PathBuf;

use armkit::math::{Pose, Rotation3, Vector3, Vector6};
use armkit::space::{
    center_of_mass, generalized_jacobian, momentum, space6r_base_body, step, track_pose_path,
    BaseBody, BaseMode, FreeFloatingModel, FreeFloatingState, SinusoidalJointMotion, SpaceData,
};
use armkit::tracking::{LeastSquares, TimedPath, TrackingOptions, TrackingStatus};
use armkit::trajectory::{CartesianTrajectory, TimeLaw};
use clap::{Args, Subcommand, ValueEnum};

use crate::plot::Figure;

use crate::common::{
    format_rows, jacobian_rows, parse_fixed_numbers, parse_joint_positions, parse_pose, pose_rows,
    print_json, CliError, CliResult, LimitPolicy, Outcome, RobotArgs,
};

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

/// The free-floating system: arm, base body, base mode and base pose.
#[derive(Args, Debug)]
pub struct SystemArgs {
    /// The arm (default: --robot space6r). Every link needs mass properties.
    #[command(flatten)]
    pub robot: RobotArgs,
    /// What the base does while the arm moves.
    #[arg(long, value_enum, default_value_t = BaseModeArg::AttitudeHeld)]
    pub base_mode: BaseModeArg,
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
        let mut robot = self.robot.clone();
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
        let model = FreeFloatingModel::new(base, arm)?;
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
        SpaceCommand::Simulate(a) => run_simulate(a),
        SpaceCommand::Track(a) => run_track(a),
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
        if !(value.is_finite() && value > 0.0) {
            return Err(CliError(format!(
                "{name}: must be finite and > 0 s, got {value}"
            )));
        }
    }
    let steps = (duration / dt - 1e-9).ceil().max(1.0);
    if steps > 1e7 {
        return Err(CliError(format!(
            "--duration / --dt = {steps} steps: at most 1e7"
        )));
    }
    Ok(steps as usize)
}

/// `x,y,z,roll,pitch,yaw` CSV cells of a pose.
fn pose_cells(pose: &Pose) -> String {
    let (roll, pitch, yaw) = pose.rpy();
    let p = pose.translation;
    format!("{},{},{},{roll},{pitch},{yaw}", p.x, p.y, p.z)
}

fn pose_header(prefix: &str) -> String {
    ["x", "y", "z", "roll", "pitch", "yaw"]
        .map(|c| format!("{prefix}_{c}"))
        .join(",")
}

fn joint_header(prefix: &str, dof: usize) -> String {
    (1..=dof)
        .map(|j| format!("{prefix}{j}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn number_cells(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// Writes each figure as `DIR/NAME.svg` (800 x 450 px).
fn write_plots(dir: &std::path::Path, figures: &[(&str, Figure)]) -> CliResult {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError(format!("{}: cannot create: {e}", dir.display())))?;
    for (name, figure) in figures {
        let path = dir.join(format!("{name}.svg"));
        let svg = figure
            .to_svg(800, 450)
            .map_err(|e| CliError(format!("{}: plot: {e}", path.display())))?;
        write_csv(&path, &svg)?;
    }
    Ok(())
}

fn write_csv(path: &std::path::Path, text: &str) -> CliResult {
    std::fs::write(path, text)
        .map_err(|e| CliError(format!("{}: cannot write: {e}", path.display())))
}

/// The base twist that `J*` implies for joint rates `rates` (call after
/// `generalized_jacobian`).
fn base_twist(data: &SpaceData, rates: &[f64]) -> Vector6<f64> {
    let mut twist = Vector6::zeros();
    for (j, rate) in rates.iter().enumerate() {
        twist += data.base_jacobian().column(j) * *rate;
    }
    twist
}

/// Twist of the base between two states `2 dt` apart (central difference).
fn differenced_base_twist(before: &Pose, after: &Pose, dt: f64) -> Vector6<f64> {
    let v = (after.translation - before.translation) / (2.0 * dt);
    let w = Rotation3::from_matrix_unchecked(after.rotation * before.rotation.transpose())
        .scaled_axis()
        / (2.0 * dt);
    Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z)
}

fn run_simulate(args: &SimulateArgs) -> CliResult<Outcome> {
    let (model, base) = args.system.load()?;
    let mode = BaseMode::from(args.system.base_mode);
    let q0 = initial_q(args.q.as_deref(), &model)?;
    let steps = step_count(args.duration, args.dt)?;
    let dt = args.duration / steps as f64;
    let n = model.dof();
    let motion = SinusoidalJointMotion::random(n, args.seed, args.amplitude, args.max_frequency)?;
    let mut data = SpaceData::new(&model);
    let mut states = Vec::with_capacity(steps + 1);
    let mut state = FreeFloatingState::new(base, q0);
    let com0 = center_of_mass(&model, &mut data, &state.base, &state.q)?;
    states.push(state.clone());
    let mut rates = vec![0.0; n];
    for k in 0..steps {
        // Rates at the middle of the step (zero-order hold).
        motion.rates((k as f64 + 0.5) * dt, &mut rates);
        step(&model, &mut data, &mut state, &rates, dt, mode)?;
        states.push(state.clone());
    }
    let mut csv = format!(
        "t,{},{},{},com_x,com_y,com_z,com_drift,{},linear_momentum,angular_momentum,linear_momentum_fd,angular_momentum_fd\n",
        joint_header("q", n),
        joint_header("qd", n),
        pose_header("base"),
        pose_header("ee"),
    );
    let (mut com_drift, mut worst_p, mut worst_l, mut worst_p_fd, mut worst_l_fd) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    // Plot series: time, COM drift, |P| and |L| by differences, base pose.
    let mut series: [Vec<f64>; 10] = Default::default();
    for (k, s) in states.iter().enumerate() {
        let t = k as f64 * dt;
        motion.rates(t, &mut rates);
        // Momentum with the base twist J* implies for the instantaneous rates.
        generalized_jacobian(&model, &mut data, &s.base, &s.q, mode)?;
        let twist = base_twist(&data, &rates);
        let com = *data.center_of_mass();
        let tip = *data.end_effector_pose();
        let p = momentum(&model, &mut data, &s.base, &s.q, &twist, &rates)?;
        // Momentum of the simulated motion itself, by central differences.
        let fd = if k > 0 && k < steps {
            let (before, after) = (&states[k - 1], &states[k + 1]);
            let q_dot: Vec<f64> = (0..n)
                .map(|j| (after.q[j] - before.q[j]) / (2.0 * dt))
                .collect();
            let twist = differenced_base_twist(&before.base, &after.base, dt);
            Some(momentum(&model, &mut data, &s.base, &s.q, &twist, &q_dot)?)
        } else {
            None
        };
        let drift = (com - com0).norm();
        com_drift = com_drift.max(drift);
        let (roll, pitch, yaw) = s.base.rpy();
        let p_base = s.base.translation - base.translation;
        let (p_fd, l_fd) = fd.map_or((f64::NAN, f64::NAN), |m| {
            (m.linear.norm(), m.angular.norm())
        });
        for (column, value) in series.iter_mut().zip([
            t, drift, p_fd, l_fd, p_base.x, p_base.y, p_base.z, roll, pitch, yaw,
        ]) {
            column.push(value);
        }
        worst_p = worst_p.max(p.linear.norm());
        worst_l = worst_l.max(p.angular.norm());
        let fd_cells = match fd {
            Some(m) => {
                worst_p_fd = worst_p_fd.max(m.linear.norm());
                worst_l_fd = worst_l_fd.max(m.angular.norm());
                format!("{},{}", m.linear.norm(), m.angular.norm())
            }
            None => ",".into(),
        };
        let _ = writeln!(
            csv,
            "{t},{},{},{},{},{},{},{drift},{},{},{},{fd_cells}",
            number_cells(&s.q),
            number_cells(&rates),
            pose_cells(&s.base),
            com.x,
            com.y,
            com.z,
            pose_cells(&tip),
            p.linear.norm(),
            p.angular.norm(),
        );
    }
    let last = &states[steps];
    let travel = (last.base.translation - base.translation).norm();
    let turn =
        Rotation3::from_matrix_unchecked(last.base.rotation * base.rotation.transpose()).angle();
    if let Some(path) = &args.output {
        write_csv(path, &csv)?;
    }
    if let Some(dir) = &args.plots {
        let [t, drift, p_fd, l_fd, x, y, z, roll, pitch, yaw] = series;
        let title = format!("{} ({mode:?}, dt = {dt} s)", model.arm().name());
        write_plots(
            dir,
            &[
                (
                    "com_drift",
                    Figure::new(
                        format!("Centre-of-mass drift, {title}"),
                        "t (s)",
                        "|r_g(t) - r_g(0)| (m)",
                        t.clone(),
                    )
                    .with_series("COM drift", drift),
                ),
                (
                    "momentum",
                    Figure::new(
                        format!("Momentum of the simulated motion (central differences), {title}"),
                        "t (s)",
                        "|P| (kg m/s), |L| (kg m^2/s)",
                        t.clone(),
                    )
                    .with_series("|P|", p_fd)
                    .with_series("|L| about the COM", l_fd),
                ),
                (
                    "base_position",
                    Figure::new(
                        format!("Base displacement, {title}"),
                        "t (s)",
                        "m",
                        t.clone(),
                    )
                    .with_series("x", x)
                    .with_series("y", y)
                    .with_series("z", z),
                ),
                (
                    "base_attitude",
                    Figure::new(format!("Base attitude, {title}"), "t (s)", "rad", t)
                        .with_series("roll", roll)
                        .with_series("pitch", pitch)
                        .with_series("yaw", yaw),
                ),
            ],
        )?;
    }
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.arm().name(),
            "base_mode": format!("{mode:?}"),
            "steps": steps,
            "dt": dt,
            "max_com_drift": com_drift,
            "max_linear_momentum": worst_p,
            "max_angular_momentum": worst_l,
            "max_linear_momentum_fd": worst_p_fd,
            "max_angular_momentum_fd": worst_l_fd,
            "base_travel": travel,
            "base_rotation": turn,
        }))?;
    } else {
        println!(
            "{} on a {} kg base ({mode:?}): {steps} steps of {dt} s",
            model.arm().name(),
            model.base().mass
        );
        println!("max centre-of-mass drift: {com_drift:.3e} m");
        println!(
            "max |P|, |L| with the base twist J* implies: {worst_p:.3e} kg m/s, {worst_l:.3e} kg m^2/s"
        );
        println!(
            "max |P|, |L| of the simulated motion (central differences, O(dt^2)): {worst_p_fd:.3e} kg m/s, {worst_l_fd:.3e} kg m^2/s"
        );
        println!("base moved {travel:.6} m and turned {turn:.6} rad");
        if let Some(path) = &args.output {
            println!("wrote {}", path.display());
        }
    }
    Ok(Outcome::Success)
}

fn run_track(args: &TrackArgs) -> CliResult<Outcome> {
    let (model, base) = args.system.load()?;
    let mode = BaseMode::from(args.system.base_mode);
    let q0 = initial_q(args.q.as_deref(), &model)?;
    let goal = parse_pose(&args.goal, "--goal")?;
    step_count(args.duration, args.dt)?;
    if !(args.accel_time.is_finite()
        && args.accel_time >= 0.0
        && 2.0 * args.accel_time <= args.duration)
    {
        return Err(CliError(format!(
            "--accel-time: must be in [0, duration / 2] = [0, {}] s, got {}",
            args.duration / 2.0,
            args.accel_time
        )));
    }
    let mut data = SpaceData::new(&model);
    let initial = FreeFloatingState::new(base, q0);
    generalized_jacobian(&model, &mut data, &initial.base, &initial.q, mode)?;
    let start = *data.end_effector_pose();
    let (duration, accel) = (args.duration, args.accel_time);
    // Seed 004's trapezoidal speed along the line (constant speed without
    // an acceleration phase).
    let law = if accel > 0.0 {
        TimeLaw::Trapezoidal {
            acceleration_time: accel,
        }
    } else {
        TimeLaw::Linear
    };
    let path = CartesianTrajectory::line(start, goal, law, duration)?;
    let options = TrackingOptions {
        dt: args.dt,
        ..TrackingOptions::default()
    };
    let damping = LeastSquares {
        damping: args.damping,
    };
    let report = track_pose_path(&model, &mut data, mode, &initial, &path, damping, &options)?;
    let n = model.dof();
    if let Some(output) = &args.output {
        let mut csv = format!(
            "t,{},{},{},{},{},position_error,orientation_error\n",
            joint_header("q", n),
            joint_header("qd", n),
            pose_header("base"),
            pose_header("ee"),
            pose_header("goal"),
        );
        for s in &report.samples {
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{}",
                s.time,
                number_cells(&s.q),
                number_cells(&s.joint_rates),
                pose_cells(&s.base),
                pose_cells(&s.end_effector),
                pose_cells(&path.pose(s.time)),
                s.position_error,
                s.orientation_error
            );
        }
        write_csv(output, &csv)?;
    }
    if let Some(dir) = &args.plots {
        let t: Vec<f64> = report.samples.iter().map(|s| s.time).collect();
        let title = format!("{} ({mode:?}, dt = {} s)", model.arm().name(), args.dt);
        let mut rates = Figure::new(format!("Joint rates, {title}"), "t (s)", "rad/s", t.clone());
        for j in 0..n {
            rates = rates.with_series(
                format!("q{}", j + 1),
                report.samples.iter().map(|s| s.joint_rates[j]).collect(),
            );
        }
        let errors = Figure::new(format!("Tracking error, {title}"), "t (s)", "m, rad", t)
            .with_series(
                "position (m)",
                report.samples.iter().map(|s| s.position_error).collect(),
            )
            .with_series(
                "orientation (rad)",
                report.samples.iter().map(|s| s.orientation_error).collect(),
            );
        write_plots(dir, &[("tracking_error", errors), ("joint_rates", rates)])?;
    }
    let max_rate = report
        .samples
        .iter()
        .flat_map(|s| s.joint_rates.iter())
        .fold(0.0f64, |m, r| m.max(r.abs()));
    let status = report.status.to_string();
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.arm().name(),
            "base_mode": format!("{mode:?}"),
            "status": status,
            "samples": report.samples.len(),
            "max_position_error": report.max_position_error,
            "max_orientation_error": report.max_orientation_error,
            "max_joint_rate": max_rate,
            "final_q": report.samples.last().map(|s| s.q.clone()),
        }))?;
    } else {
        println!(
            "{} on a {} kg base ({mode:?}): tracking {duration} s, {status}",
            model.arm().name(),
            model.base().mass
        );
        println!(
            "max position error {:.3e} m, max orientation error {:.3e} rad, max |joint rate| {max_rate:.4} rad/s",
            report.max_position_error, report.max_orientation_error
        );
        if let Some(path) = &args.output {
            println!("wrote {}", path.display());
        }
    }
    Ok(match report.status {
        TrackingStatus::Completed => Outcome::Success,
        _ => Outcome::NotConverged,
    })
}
