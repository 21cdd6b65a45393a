//! `armkit mpc`: model-predictive motion to a target pose (seed 000), run in
//! closed loop on a kinematic plant, written to CSV and SVG plots.
//!
//! * `armkit mpc --robot gantry9 --target "x,y,z,roll,pitch,yaw" [--start Q]
//!   [--horizon N] [--control-horizon M] [--dt T] [--weights position|pose|w1,..,w6]
//!   [--priorities R1,..,Rn] [--out DIR] [--json]`
//! * `armkit mpc --example 1|2|3|ex2-paper-weights|ex3-undamped|all [--out DIR] [--json]`:
//!   seed 000's examples on the flexible gantry, with their checks.
//!
//! `--out DIR` writes `mpc.csv` (time, joint positions and velocities,
//! end-effector pose, errors, step status) and the plots of seed 000's
//! Figs 7-9: `end_effector.svg` (a), `rotary_velocities.svg` (b),
//! `rotary_angles.svg` (c), `prismatic_velocities.svg` (d),
//! `prismatic_positions.svg` (e); a group the robot lacks is skipped.
//! The exit code is 3 when the run does not converge (or an example's check
//! fails).

use std::path::{Path, PathBuf};

use armkit::mpc::qp::QpSolverKind;
use armkit::mpc::scenario::{simulate_with, Seed000Example, SimulationOptions, Trajectory};
use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights, VelocityWeights};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::common::{
    parse_fixed_numbers, parse_joint_positions, parse_pose, print_json, CliError, CliResult,
    LimitPolicy, Outcome, RobotArgs,
};
use crate::plot::Figure;
use crate::report::{Animation, Check, Report, Table};

/// `armkit mpc` arguments.
#[derive(Args, Debug)]
pub struct MpcArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Target pose "x,y,z,roll,pitch,yaw" (m, rad; R = Rz(yaw) Ry(pitch) Rx(roll)).
    #[arg(
        long,
        value_name = "POSE",
        allow_hyphen_values = true,
        required_unless_present = "example"
    )]
    pub target: Option<String>,
    /// Start joint positions (default: the middle of every range); a start
    /// outside the limits is brought back in at half speed.
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub start: Option<String>,
    /// Prediction horizon N, samples.
    #[arg(long, default_value_t = 10)]
    pub horizon: usize,
    /// Control horizon M (1 <= M <= N), samples.
    #[arg(long, default_value_t = 1)]
    pub control_horizon: usize,
    /// Sample time T, s.
    #[arg(long, default_value_t = armkit::mpc::DEFAULT_SAMPLE_TIME)]
    pub dt: f64,
    /// Task weights Q: `position` (10 on x, y, z), `pose` (10 on all six),
    /// or six numbers for x, y, z, rx, ry, rz.
    #[arg(long, default_value = "pose", value_name = "position|pose|W1,..,W6")]
    pub weights: String,
    /// Terminal weight as a multiple of the task weights (seed 000: 200 / 10).
    #[arg(long, default_value_t = 20.0)]
    pub terminal_factor: f64,
    /// Increment weights R, one per joint (the joint priorities; default 1).
    #[arg(long, value_name = "R1,R2,...")]
    pub priorities: Option<String>,
    /// Velocity term W = FACTOR x R (damps self-motion; 0 = seed 000's eq 20 as printed).
    #[arg(long, default_value_t = 0.01, value_name = "FACTOR")]
    pub velocity_weight: f64,
    /// QP backend (default: OSQP when compiled in, else Clarabel).
    #[arg(long, value_enum)]
    pub solver: Option<SolverArg>,
    /// Most planner steps.
    #[arg(long, default_value_t = 2000)]
    pub max_steps: usize,
    /// Run seed 000's example(s) instead: 1, 2, 3, ex2-paper-weights, ex3-undamped or all.
    #[arg(long, value_name = "ID", conflicts_with_all = ["robot", "robot_file", "urdf", "target", "start"])]
    pub example: Option<String>,
    /// Directory for mpc.csv and the SVG plots (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print a JSON summary.
    #[arg(long)]
    pub json: bool,
}

/// `--solver` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// Clarabel (interior point, pure Rust).
    Clarabel,
    /// OSQP (ADMM; needs armkit's `osqp` feature).
    Osqp,
}

impl From<SolverArg> for QpSolverKind {
    fn from(s: SolverArg) -> Self {
        match s {
            SolverArg::Clarabel => QpSolverKind::Clarabel,
            SolverArg::Osqp => QpSolverKind::Osqp,
        }
    }
}

/// Runs `armkit mpc`.
pub fn run(args: &MpcArgs) -> CliResult<Outcome> {
    match &args.example {
        Some(id) => run_examples(args, id),
        None => run_target(args),
    }
}

fn task_weights(text: &str, terminal_factor: f64) -> CliResult<TaskWeights> {
    let tracking: [f64; 6] = match text.trim() {
        "position" => [10.0, 10.0, 10.0, 0.0, 0.0, 0.0],
        "pose" => [10.0; 6],
        other => {
            let v = parse_fixed_numbers(other, "--weights", 6)?;
            [v[0], v[1], v[2], v[3], v[4], v[5]]
        }
    };
    if !(terminal_factor.is_finite() && terminal_factor >= 0.0) {
        return Err(CliError(format!(
            "--terminal-factor: must be finite and >= 0, got {terminal_factor}"
        )));
    }
    Ok(TaskWeights {
        tracking,
        terminal: tracking.map(|w| w * terminal_factor),
    })
}

fn run_target(args: &MpcArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let target_text = args
        .target
        .as_deref()
        .ok_or_else(|| CliError("--target is required (or --example)".into()))?;
    let target = parse_pose(target_text, "--target")?;
    let start = match &args.start {
        Some(text) => parse_joint_positions(text, &model, LimitPolicy::Allow)?,
        None => model.neutral_configuration(),
    };
    let priorities = match &args.priorities {
        Some(text) => Some(parse_fixed_numbers(text, "--priorities", model.dof())?),
        None => None,
    };
    let options = MpcOptions {
        horizon: args.horizon,
        control_horizon: args.control_horizon,
        sample_time: args.dt,
        task_weights: task_weights(&args.weights, args.terminal_factor)?,
        increment_weights: priorities,
        velocity_weights: VelocityWeights::Proportional(args.velocity_weight),
        solver: args.solver.map_or_else(QpSolverKind::default, Into::into),
        ..MpcOptions::default()
    };
    let simulation = SimulationOptions {
        max_steps: args.max_steps,
        ..SimulationOptions::default()
    };
    let planner = MpcPlanner::new(&model, options)?;
    let solver = planner.solver_name();
    let run = run_with_progress(planner, &start, &target, &simulation, model.name())?;
    let files = match &args.out {
        Some(dir) => write_outputs(dir, &run, model.name())?,
        None => Vec::new(),
    };
    let summary = &run.summary;
    if args.json {
        let mut value = summary_json(&run);
        value["robot"] = model.name().into();
        value["solver"] = solver.into();
        value["final_q"] = run
            .samples
            .last()
            .map(|s| s.q.clone())
            .unwrap_or_default()
            .into();
        value["files"] = files_json(&files);
        print_json(&value)?;
    } else {
        println!(
            "{}: MPC to ({:.4}, {:.4}, {:.4}) m, N = {}, M = {}, T = {} s, {solver}",
            model.name(),
            target.translation.x,
            target.translation.y,
            target.translation.z,
            args.horizon,
            args.control_horizon,
            args.dt
        );
        print_summary(&run);
        print_files(&files);
    }
    Ok(if summary.converged {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

fn run_examples(args: &MpcArgs, id: &str) -> CliResult<Outcome> {
    let examples: Vec<Seed000Example> = if id.trim().eq_ignore_ascii_case("all") {
        Seed000Example::ALL.to_vec()
    } else {
        vec![Seed000Example::from_id(id)?]
    };
    let model = Seed000Example::model()?;
    let mut all_passed = true;
    let mut reports = Vec::new();
    for example in examples {
        let mut options = example.options();
        if let Some(solver) = args.solver {
            options.solver = solver.into();
        }
        let planner = MpcPlanner::new(&model, options)?;
        let solver = planner.solver_name();
        let run = run_with_progress(
            planner,
            &example.start(),
            &example.target(),
            &example.simulation(),
            example.id(),
        )?;
        let checks = example.checks(&run);
        all_passed &= checks.iter().all(|c| c.passed);
        let files = match &args.out {
            Some(dir) => write_outputs(&dir.join(example.id()), &run, example.title())?,
            None => Vec::new(),
        };
        if args.json {
            let mut value = summary_json(&run);
            value["id"] = example.id().into();
            value["title"] = example.title().into();
            value["solver"] = solver.into();
            value["checks"] = checks
                .iter()
                .map(
                    |c| serde_json::json!({"name": c.name, "passed": c.passed, "detail": c.detail}),
                )
                .collect::<Vec<_>>()
                .into();
            value["files"] = files_json(&files);
            reports.push(value);
        } else {
            println!("{} [{}, {solver}]", example.title(), example.id());
            print_summary(&run);
            for check in &checks {
                println!(
                    "  [{}] {}: {}",
                    if check.passed { "pass" } else { "FAIL" },
                    check.name,
                    check.detail
                );
            }
            print_files(&files);
            println!();
        }
    }
    if args.json {
        print_json(&serde_json::json!({ "robot": model.name(), "examples": reports }))?;
    }
    Ok(if all_passed {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

fn run_with_progress(
    planner: MpcPlanner,
    start: &[f64],
    target: &armkit::math::Pose,
    simulation: &SimulationOptions,
    label: &str,
) -> CliResult<Trajectory> {
    let progress = ProgressBar::with_draw_target(
        Some(simulation.max_steps as u64),
        ProgressDrawTarget::stderr(),
    );
    progress.set_style(
        ProgressStyle::with_template("{prefix} [{bar:40}] step {pos}/{len} {elapsed_precise}")
            .map_err(|e| CliError(format!("progress bar: {e}")))?
            .progress_chars("=> "),
    );
    progress.set_prefix(label.to_string());
    let run = simulate_with(planner, start, target, simulation, |step| {
        if step % 50 == 0 {
            progress.set_position(step as u64);
        }
    });
    progress.finish_and_clear();
    Ok(run?)
}

fn summary_json(run: &Trajectory) -> serde_json::Value {
    let s = &run.summary;
    serde_json::json!({
        "converged": s.converged,
        "final_position_error": s.final_position_error,
        "final_orientation_error": s.final_orientation_error,
        "tracks_orientation": run.tracks_orientation,
        "steps": s.steps,
        "sample_time": run.sample_time,
        "max_velocity_violation": s.max_velocity_violation,
        "max_position_violation": s.max_position_violation,
        "non_solved_steps": s.non_solved_steps,
        "max_prediction_error": s.max_prediction_error,
    })
}

fn files_json(files: &[PathBuf]) -> serde_json::Value {
    files
        .iter()
        .map(|f| f.display().to_string())
        .collect::<Vec<_>>()
        .into()
}

fn print_summary(run: &Trajectory) {
    let s = &run.summary;
    let orientation = if run.tracks_orientation {
        format!("orientation error {:.3e} rad", s.final_orientation_error)
    } else {
        "orientation not tracked".to_string()
    };
    println!(
        "  {} after {} steps ({:.2} s): position error {:.3e} m, {orientation}",
        if s.converged {
            "converged"
        } else {
            "NOT converged"
        },
        s.steps,
        s.steps as f64 * run.sample_time,
        s.final_position_error,
    );
    println!(
        "  limits: max velocity violation {:.3e}, max position violation {:.3e}; {} steps not plainly solved",
        s.max_velocity_violation, s.max_position_violation, s.non_solved_steps
    );
}

fn print_files(files: &[PathBuf]) {
    if !files.is_empty() {
        println!(
            "  wrote {}",
            files
                .iter()
                .map(|f| f.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
}

/// Writes `mpc.csv` and the plots of Figs 7-9 into `dir`; returns the paths.
fn write_outputs(dir: &Path, run: &Trajectory, title: &str) -> CliResult<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError(format!("{}: cannot create directory: {e}", dir.display())))?;
    let mut files = Vec::new();
    let csv = dir.join("mpc.csv");
    write_file(&csv, &run.to_csv())?;
    files.push(csv);
    for (name, figure) in figures(run, title) {
        let path = dir.join(format!("{name}.svg"));
        let svg = figure
            .to_svg(900, 500)
            .map_err(|e| CliError(format!("{}: plot failed: {e}", path.display())))?;
        write_file(&path, &svg)?;
        files.push(path);
    }
    Ok(files)
}

fn write_file(path: &Path, text: &str) -> CliResult {
    std::fs::write(path, text)
        .map_err(|e| CliError(format!("{}: cannot write: {e}", path.display())))
}

/// What a joint panel plots.
#[derive(Clone, Copy)]
enum Quantity {
    Velocity,
    Position,
}

/// The panels of seed 000's Figs 7-9: (a) end-effector coordinates, (b)
/// rotary joint velocities, (c) rotary joint angles, (d) prismatic joint
/// velocities, (e) prismatic joint positions.
fn figures(run: &Trajectory, title: &str) -> Vec<(&'static str, Figure)> {
    let t: Vec<f64> = run.samples.iter().map(|s| s.time).collect();
    let mut end_effector = Figure::new(
        format!("{title}: (a) end-effector position"),
        "t (s)",
        "m",
        t.clone(),
    );
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        end_effector =
            end_effector.with_series(*axis, run.samples.iter().map(|s| s.position[k]).collect());
    }
    let mut figures = vec![("end_effector", end_effector)];
    let groups = [
        (
            run.rotary_joints(),
            [
                (
                    "rotary_velocities",
                    "(b) rotary joint velocities",
                    "rad/s",
                    Quantity::Velocity,
                ),
                (
                    "rotary_angles",
                    "(c) rotary joint angles",
                    "rad",
                    Quantity::Position,
                ),
            ],
        ),
        (
            run.prismatic_joints(),
            [
                (
                    "prismatic_velocities",
                    "(d) prismatic joint velocities",
                    "m/s",
                    Quantity::Velocity,
                ),
                (
                    "prismatic_positions",
                    "(e) prismatic joint positions",
                    "m",
                    Quantity::Position,
                ),
            ],
        ),
    ];
    for (joints, panels) in groups {
        if joints.is_empty() {
            continue;
        }
        for (name, caption, unit, quantity) in panels {
            let mut figure = Figure::new(format!("{title}: {caption}"), "t (s)", unit, t.clone());
            for &j in &joints {
                let values = run
                    .samples
                    .iter()
                    .map(|s| match quantity {
                        Quantity::Velocity => s.velocity[j],
                        Quantity::Position => s.q[j],
                    })
                    .collect();
                figure = figure.with_series(run.joint_names[j].clone(), values);
            }
            figures.push((name, figure));
        }
    }
    figures
}

/// One of seed 000's examples as a report (a scenario's `[mpc]` table with
/// `example = "ex1"`, `"ex2"`, `"ex3"`, `"ex2-paper-weights"` or
/// `"ex3-undamped"`): the paper's claims as checks, Figs 7-9 as figures, the
/// gantry moving.
pub fn example_report(args: &MpcArgs) -> CliResult<Report> {
    let id = args.example.as_deref().ok_or_else(|| {
        CliError(
            "[mpc] in a scenario runs one of seed 000's examples: give example = \"ex1\" \
             (or ex2, ex3, ex2-paper-weights, ex3-undamped)"
                .into(),
        )
    })?;
    let example = Seed000Example::from_id(id)?;
    let model = Seed000Example::model()?;
    let mut options = example.options();
    if let Some(solver) = args.solver {
        options.solver = solver.into();
    }
    let planner = MpcPlanner::new(&model, options)?;
    let solver = planner.solver_name();
    let run = simulate_with(
        planner,
        &example.start(),
        &example.target(),
        &example.simulation(),
        |_| {},
    )?;
    let checks = example
        .checks(&run)
        .into_iter()
        .map(|c| Check::holds(c.name, c.passed, c.detail))
        .collect();
    let times: Vec<f64> = run.samples.iter().map(|s| s.time).collect();
    let configurations: Vec<Vec<f64>> = run.samples.iter().map(|s| s.q.clone()).collect();
    let mut table = Table::new(
        "Joint motion",
        &["joint", "travel", "peak |velocity|", "velocity limit"],
    );
    for (j, joint) in model.joints().iter().enumerate() {
        let unit = if joint.kind.is_rotational() {
            "rad"
        } else {
            "m"
        };
        table.push(vec![
            run.joint_names[j].clone(),
            format!("{:.4} {unit}", run.travel(j)),
            format!("{:.4} {unit}/s", run.peak_speed(j)),
            joint
                .limits
                .velocity
                .map_or("-".into(), |v| format!("{v:.4} {unit}/s")),
        ]);
    }
    let target = example.target().translation;
    Ok(Report {
        name: example.id().into(),
        title: format!("Seed 000, {}", example.title()),
        description: format!(
            "The 9-DOF gantry with its flexible beam (gantry9-flex) moves its hand from [2.00, 2.38, 5.00] m \
             to [{}, {}, {}] m under seed 000's incremental MPC (eqs 13-21): N = 10, M = 1, T = {} s, \
             Q = 10 with terminal weight 200 on position, joint priorities R = {:?}, velocity limits of eq 23 \
             and position limits of eq 24 as QP constraints, re-linearised (J = J0 M) every sample; QP solver {solver}. \
             {} steps, final position error {:.2e} m.",
            target.x,
            target.y,
            target.z,
            run.sample_time,
            example.increment_weights(),
            run.summary.steps,
            run.summary.final_position_error
        ),
        checks,
        tables: vec![table],
        figures: figures(&run, example.id())
            .into_iter()
            .map(|(stem, figure)| (stem.to_string(), figure))
            .collect(),
        notes: mpc_notes(example),
        animation: Some(Animation::from_configurations(&model, &times, &configurations)?),
    })
}

/// What differs from the paper in each example, and why.
fn mpc_notes(example: Seed000Example) -> Vec<String> {
    let mut notes = vec![
        "The paper's start q0 = [-1, 2, 0, 0, pi/2, 0, 0, 0, 0] violates its own limits (d1 >= 0, q5 <= 1.22); we start at \
         [2.0, 0.89, 0.76, pi/2, 0.5, 0.5, 0, 0.5, 0], inside every limit, which puts our gantry's hand at the paper's \
         X0 = [2, 2.38, 5]. T is not printed: 0.05 s. Eq 20 gets a small velocity term W = 0.01 R: without it nothing \
         penalises a constant self-motion of a redundant arm and the joints never settle (see ex3-undamped)."
            .to_string(),
    ];
    match example {
        Seed000Example::SmallMove => notes.push(
            "Not as printed: with the paper's priorities 100/10/1 the beam joints travel 226 mm (d2) and 36 mm (d3) \
             (ex2-paper-weights). Quadratic weights only scale a joint's share of the motion, never to zero; priorities \
             1e5/1e4/1 keep the prismatic joints below 1 mm. No single weight set gives both Example 1's saturated \
             prismatic joints and Example 2's still ones."
                .to_string(),
        ),
        Seed000Example::EqualWeights => notes.push(
            "The paper reports oscillation with every R = 10. Ours converges without oscillating because of the velocity \
             term; with eq 20 as printed (ex3-undamped) the hand reaches the target but the rotary joints keep drifting \
             along the self-motion, which matches the paper's 'rotary joints diverge'."
                .to_string(),
        ),
        _ => {}
    }
    notes
}
