//! `armkit mpc`: model-predictive motion to a target pose (seed 000), run in
//! closed loop on a kinematic plant, written to CSV and SVG plots.
//!
//! * `armkit mpc --robot gantry9 --target "x,y,z,roll,pitch,yaw" [--start Q]
//!   [--horizon N] [--control-horizon M] [--dt T] [--weights position|pose|w1,..,w6]
//!   [--priorities R1,..,Rn] [--priority-mode weighted|strict] [--out DIR] [--json]`
//! * `armkit mpc --example 1|2|3|ex1-rigid-model|ex1-link-error|ex2-paper-weights|ex2-strict|ex3-undamped|all [--out DIR] [--json]`:
//!   seed 000's examples on the flexible gantry, with their checks and the
//!   paper's claims as findings.
//!
//! Either runs on an exact plant (each joint follows its commanded velocity
//! exactly) unless `--prismatic-resolution M` / `--prismatic-deadband M/S`
//! give the prismatic actuators a finite precision (seed 000, Example 3:
//! with 0.001 Example 3 keeps oscillating while Example 2 settles).
//!
//! `--out DIR` writes `mpc.csv` (time, joint positions and velocities,
//! end-effector pose, errors, step status) and the plots of seed 000's
//! Figs 7-9: `end_effector.svg` (a), `rotary_velocities.svg` (b),
//! `rotary_angles.svg` (c), `prismatic_velocities.svg` (d),
//! `prismatic_positions.svg` (e); a group the robot lacks is skipped.
//! The exit code is 3 when the run does not converge (or an example's check
//! fails); the cause (unreachable, which joint limit, singularity, step
//! limit) is printed on stderr. `--json` adds the per-step QP solve times
//! (median, p99, max, us) and the solver used.

mod args;
mod report;
mod target;
mod target_report;

use std::path::PathBuf;

use armkit::mpc::scenario::{simulate_on_plant, MpcRun, SimulationOptions};
use armkit::mpc::{diagnose_run, ActuatorPrecision, MpcOptions, MpcPlanner, PlantModel, ReachAid};
use armkit::study::Seed000Example;
use armkit::Model;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::common::{print_json, CliError, CliResult, Outcome, RobotArgs};
pub use args::{PriorityArg, ReachArg, SolverArg};
pub use report::example_report;
use report::{
    files_json, print_files, print_summary, print_tolerances, summary_json, tolerances_json,
    write_outputs,
};
pub(crate) use target::{target_setup, TargetSetup};
pub use target_report::target_report;

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
    /// Prediction horizon N, samples (not with --example: the examples run
    /// the paper's N = 10).
    #[arg(long, default_value_t = 10, conflicts_with = "example")]
    pub horizon: usize,
    /// Control horizon M (1 <= M <= N), samples.
    #[arg(long, default_value_t = 1)]
    pub control_horizon: usize,
    /// Sample time T, s (not with --example: the examples run at their own T).
    #[arg(long, default_value_t = armkit::mpc::DEFAULT_SAMPLE_TIME, conflicts_with = "example")]
    pub dt: f64,
    /// Task weights Q: `position` (10 on x, y, z), `pose` (10 on all six),
    /// or six numbers for x, y, z, rx, ry, rz.
    #[arg(
        long,
        default_value = "pose",
        value_name = "position|pose|W1,..,W6",
        conflicts_with = "example"
    )]
    pub weights: String,
    /// Terminal weight as a multiple of the task weights (seed 000: 200 / 10).
    #[arg(long, default_value_t = 20.0, conflicts_with = "example")]
    pub terminal_factor: f64,
    /// Increment weights R, one per joint (the joint priorities; default 1).
    #[arg(long, value_name = "R1,R2,...", conflicts_with = "example")]
    pub priorities: Option<String>,
    /// How the priorities act: `weighted` (one cost, eq 20) or `strict`
    /// (joints with equal R form a level, smallest R first; each level's QP
    /// holds the levels above at their optimum).
    #[arg(long, value_enum, default_value_t = PriorityArg::Weighted, conflicts_with = "example")]
    pub priority_mode: PriorityArg,
    /// Velocity term W = FACTOR x R (damps self-motion; 0 = seed 000's eq 20 as printed).
    #[arg(
        long,
        default_value_t = 0.01,
        value_name = "FACTOR",
        conflicts_with = "example"
    )]
    pub velocity_weight: f64,
    /// QP backend (default: active-set, with Clarabel as its fallback).
    #[arg(long, value_enum)]
    pub solver: Option<SolverArg>,
    /// Help out of local minima: `goal-posture` (IK goal posture pulled
    /// toward, re-planned when stalled) or `off` (seed 000's plain planner).
    /// Default: goal-posture for --target runs; seed 000's examples run off.
    #[arg(long, value_enum)]
    pub reach: Option<ReachArg>,
    /// Plan with the robot's model but move a built-in robot of the same
    /// joints (model mismatch, e.g. `--robot gantry9 --plant-robot
    /// gantry9-flex`: the planner ignores the beam's deflection).
    #[arg(long, value_name = "NAME", conflicts_with = "example")]
    pub plant_robot: Option<String>,
    /// Plan with every DH length of the robot (and its tool offset) scaled
    /// by 1 + FRACTION while the plant keeps the true lengths (model
    /// mismatch; 0.05 = 5 % too long).
    #[arg(
        long,
        value_name = "FRACTION",
        allow_hyphen_values = true,
        conflicts_with = "example"
    )]
    pub link_length_error: Option<f64>,
    /// Most planner steps.
    #[arg(long, default_value_t = 2000)]
    pub max_steps: usize,
    /// Converged when the position error is below this, m (default 1e-4;
    /// seed 000's examples: their own).
    #[arg(long, value_name = "M")]
    pub position_tolerance: Option<f64>,
    /// ... and the orientation error below this, rad, when orientation is
    /// tracked (default 1e-3).
    #[arg(long, value_name = "RAD")]
    pub orientation_tolerance: Option<f64>,
    /// ... and every joint speed below this, m/s or rad/s (default 1e-3).
    #[arg(long, value_name = "RATE")]
    pub velocity_tolerance: Option<f64>,
    /// Position resolution of the prismatic actuators, m: each rests only on
    /// multiples of it from its start (0 = exact).
    #[arg(long, default_value_t = 0.0, value_name = "M")]
    pub prismatic_resolution: f64,
    /// Velocity deadband of the prismatic actuators, m/s: slower commands do
    /// not move them (0 = none).
    #[arg(long, default_value_t = 0.0, value_name = "M/S")]
    pub prismatic_deadband: f64,
    /// Run seed 000's example(s) instead: 1, 2, 3, ex1-rigid-model, ex1-link-error, ex2-paper-weights, ex2-strict,
    /// ex3-undamped or all.
    /// Each runs its own start, horizon, T, weights and priorities: the
    /// flags that would change them are refused with it.
    #[arg(long, value_name = "ID", conflicts_with_all = ["robot", "robot_file", "urdf", "target", "start"])]
    pub example: Option<String>,
    /// Directory for mpc.csv and the SVG plots (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print a JSON summary.
    #[arg(long)]
    pub json: bool,
}

impl MpcArgs {
    /// Applies `--solver`, `--reach` and `--control-horizon` to `options`.
    fn apply(&self, options: &mut MpcOptions) {
        if let Some(solver) = self.solver {
            options.solver = solver.into();
        }
        match self.reach {
            Some(ReachArg::Off) => options.reach = ReachAid::Off,
            Some(ReachArg::GoalPosture) if options.reach == ReachAid::Off => {
                options.reach = ReachAid::default()
            }
            _ => {}
        }
        options.control_horizon = self.control_horizon;
    }

    /// The plant of `--prismatic-resolution` and `--prismatic-deadband`
    /// (exact when both are 0). Errors name the flag.
    fn plant(&self) -> CliResult<PlantModel> {
        for (flag, value) in [
            ("--prismatic-resolution", self.prismatic_resolution),
            ("--prismatic-deadband", self.prismatic_deadband),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(CliError(format!(
                    "{flag}: must be finite and >= 0, got {value}"
                )));
            }
        }
        let prismatic = ActuatorPrecision {
            position_resolution: self.prismatic_resolution,
            deadband: self.prismatic_deadband,
            ..ActuatorPrecision::EXACT
        };
        Ok(PlantModel::of_actuators(
            prismatic,
            ActuatorPrecision::EXACT,
        )?)
    }

    /// The example's simulation settings on the flags' plant.
    fn example_simulation(&self, example: Seed000Example) -> CliResult<SimulationOptions> {
        self.with_tolerances(SimulationOptions {
            plant: self.plant()?,
            ..example.simulation()
        })
    }
}

/// Runs `armkit mpc`.
pub fn run(args: &MpcArgs) -> CliResult<Outcome> {
    match &args.example {
        Some(id) => run_examples(args, id),
        None => run_target(args),
    }
}

fn run_target(args: &MpcArgs) -> CliResult<Outcome> {
    let TargetSetup {
        model,
        target,
        start,
        mut planner,
        plant_model,
        simulation,
    } = target_setup(args)?;
    let run = run_with_progress(
        &mut planner,
        plant_model.as_ref(),
        &start,
        &target,
        &simulation,
        model.name(),
    )?;
    let final_q = run.samples.last().map(|s| s.q.clone()).unwrap_or_default();
    let status = diagnose_run(&planner, &final_q, run.summary.converged)?;
    let files = match &args.out {
        Some(dir) => write_outputs(dir, &run, model.name(), &model)?,
        None => Vec::new(),
    };
    let summary = &run.summary;
    if args.json {
        let mut value = summary_json(&run, &planner);
        value["robot"] = model.name().into();
        value["status"] = status.as_str().into();
        value["status_detail"] = status.to_string().into();
        value["final_q"] = final_q.into();
        value["files"] = files_json(&files);
        value["tolerances"] = tolerances_json(&simulation);
        print_json(&value)?;
    } else {
        println!(
            "{}: MPC to ({:.4}, {:.4}, {:.4}) m, N = {}, M = {}, T = {} s, {}",
            model.name(),
            target.translation.x,
            target.translation.y,
            target.translation.z,
            args.horizon,
            args.control_horizon,
            args.dt,
            planner.solver_name()
        );
        print_summary(&run, &planner);
        print_tolerances(&simulation);
        print_files(&files);
    }
    if !status.is_converged() {
        eprintln!("armkit mpc: not converged: {status}");
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
        args.apply(&mut options);
        let planner_model = example.planner_model()?;
        let mut planner = MpcPlanner::new(planner_model.as_ref().unwrap_or(&model), options)?;
        let simulation = args.example_simulation(example)?;
        let run = run_with_progress(
            &mut planner,
            planner_model.as_ref().map(|_| &model),
            &example.start(),
            &example.target(),
            &simulation,
            example.id(),
        )?;
        let checks = example.checks(&run);
        let findings = example.findings(&run)?;
        all_passed &= checks.iter().all(|c| c.passed);
        let files = match &args.out {
            Some(dir) => write_outputs(&dir.join(example.id()), &run, example.title(), &model)?,
            None => Vec::new(),
        };
        if args.json {
            let mut value = summary_json(&run, &planner);
            value["id"] = example.id().into();
            value["title"] = example.title().into();
            value["checks"] = checks
                .iter()
                .map(
                    |c| serde_json::json!({"name": c.name, "passed": c.passed, "detail": c.detail}),
                )
                .collect::<Vec<_>>()
                .into();
            value["findings"] = findings
                .iter()
                .map(|f| serde_json::json!({"claim": f.claim, "measured": f.measured, "status": f.status.as_str()}))
                .collect::<Vec<_>>()
                .into();
            value["files"] = files_json(&files);
            value["tolerances"] = tolerances_json(&simulation);
            reports.push(value);
        } else {
            println!(
                "{} [{}, {}]",
                example.title(),
                example.id(),
                planner.solver_name()
            );
            print_summary(&run, &planner);
            print_tolerances(&simulation);
            for check in &checks {
                println!(
                    "  [{}] {}: {}",
                    if check.passed { "pass" } else { "FAIL" },
                    check.name,
                    check.detail
                );
            }
            for finding in &findings {
                println!("  paper: {finding}");
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
    planner: &mut MpcPlanner,
    plant_model: Option<&Model>,
    start: &[f64],
    target: &armkit::math::Pose,
    simulation: &SimulationOptions,
    label: &str,
) -> CliResult<MpcRun> {
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
    let run = simulate_on_plant(planner, plant_model, start, target, simulation, |step| {
        if step % 50 == 0 {
            progress.set_position(step as u64);
        }
    });
    progress.finish_and_clear();
    Ok(run?)
}
