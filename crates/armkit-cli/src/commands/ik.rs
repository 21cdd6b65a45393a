//! `armkit ik` (inverse kinematics of one pose) and `armkit bench-ik` (the
//! IK benchmark: success rate and solve times on random reachable targets).

use std::time::{Duration, Instant};

use armkit::ik::closed_form::{ClosedFormSolution, ClosedFormSolver, Fit};
use armkit::ik::{benchmark_targets, IkMethod, IkOptions, IkReport, IkSolver, IkStatus};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Pose;
use armkit::Model;
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};

use crate::common::{
    parse_fixed_numbers, parse_pose, print_json, CliError, CliResult, Outcome, RobotArgs,
};

/// `--solver` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// Newton-Raphson with the pseudo-inverse (seed 004, Fig 2).
    Nr,
    /// Damped least squares, Nakamura's adaptive damping.
    Dls,
    /// Levenberg-Marquardt, Sugihara's damping (default, fastest).
    Lm,
    /// Chiaverini's singularity-robust inverse with numerical filtering.
    Sri,
    /// Closed form: puma560-type arms (Pieper) and seed 002's arm4.
    ClosedForm,
}

impl SolverArg {
    fn name(self) -> &'static str {
        match self {
            SolverArg::Nr => "nr",
            SolverArg::Dls => "dls",
            SolverArg::Lm => "lm",
            SolverArg::Sri => "sri",
            SolverArg::ClosedForm => "closed-form",
        }
    }

    /// The numeric method, or `None` for the closed form.
    fn method(self) -> Option<IkMethod> {
        match self {
            SolverArg::ClosedForm => None,
            other => IkMethod::from_short_name(other.name()).ok(),
        }
    }
}

/// Tolerances shared by `ik` and `bench-ik`.
#[derive(Args, Debug)]
pub struct ToleranceArgs {
    /// Position tolerance, m.
    #[arg(long, default_value_t = 1e-6)]
    pub position_tolerance: f64,
    /// Orientation tolerance, rad.
    #[arg(long, default_value_t = 1e-6)]
    pub orientation_tolerance: f64,
    /// Time budget per solve, ms.
    #[arg(long, default_value_t = 5.0)]
    pub budget_ms: f64,
    /// Seed of the solver's random restarts.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

impl ToleranceArgs {
    fn options(&self, method: IkMethod) -> CliResult<IkOptions> {
        if !(self.budget_ms.is_finite() && self.budget_ms > 0.0) {
            return Err(CliError(format!(
                "--budget-ms: must be > 0, got {}",
                self.budget_ms
            )));
        }
        let options = IkOptions {
            method,
            position_tolerance: self.position_tolerance,
            orientation_tolerance: self.orientation_tolerance,
            time_budget: Some(Duration::from_secs_f64(self.budget_ms * 1e-3)),
            seed: self.seed,
            ..IkOptions::default()
        };
        options.validate()?;
        Ok(options)
    }
}

/// Inverse kinematics of one pose: every solution for the closed form, the
/// solver's report for the numeric methods. Exit code 3 when the target is
/// not reached (the best effort is printed).
#[derive(Args, Debug)]
pub struct IkArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Target pose "x,y,z,roll,pitch,yaw" in the world frame (m, rad;
    /// R = Rz(yaw) Ry(pitch) Rx(roll), as in URDF).
    #[arg(long, value_name = "X,Y,Z,R,P,Y", allow_hyphen_values = true)]
    pub pose: String,
    /// Start configuration, one value per joint (default: mid-range).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub start: Option<String>,
    /// Solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Lm)]
    pub solver: SolverArg,
    #[command(flatten)]
    pub tolerances: ToleranceArgs,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `armkit ik`.
pub fn run(args: &IkArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let target = parse_pose(&args.pose, "--pose")?;
    let start = match &args.start {
        Some(text) => parse_fixed_numbers(text, "--start", model.dof())?,
        None => model.neutral_configuration(),
    };
    let lm = IkMethod::LevenbergMarquardt(Default::default());
    let options = args
        .tolerances
        .options(args.solver.method().unwrap_or(lm))?;
    let mut solver = IkSolver::new(&model, options)?;
    match args.solver {
        SolverArg::ClosedForm => {
            let closed = ClosedFormSolver::new(&model)?;
            let solutions = closed.solve(&target, &start)?;
            // The nearest solution; with none, the numeric best effort.
            let best_effort = match solutions.first() {
                Some(s) => s.q.clone(),
                None => solver.solve(&target, &start)?.q,
            };
            let status = match solutions.first() {
                Some(s) if s.fit == Fit::Exact => IkStatus::Converged,
                _ => IkStatus::NotConverged,
            };
            let mut data = Data::new(&model);
            let (position_error, orientation_error) =
                errors(&model, &mut data, &best_effort, &target)?;
            if args.json {
                print_json(&serde_json::json!({
                    "robot": model.name(),
                    "solver": "closed-form",
                    "method": closed.description(),
                    "status": status.as_str(),
                    "q": best_effort,
                    "position_error": position_error,
                    "orientation_error": orientation_error,
                    "solutions": solutions.iter().map(|s| s.q.clone()).collect::<Vec<_>>(),
                    "solution_fits": solutions.iter().map(fit_json).collect::<Vec<_>>(),
                }))?;
            } else {
                print!(
                    "{}",
                    describe_closed_form(&model, closed.description(), &solutions, status)
                );
                if solutions.is_empty() {
                    println!(
                        "best effort (numeric, lm): q = {}\nposition error {:.3e} m, orientation error {:.3e} rad",
                        format_q(&best_effort),
                        position_error,
                        orientation_error
                    );
                }
            }
            Ok(outcome(status))
        }
        _ => {
            let report = solver.solve(&target, &start)?;
            if args.json {
                print_json(&report_json(model.name(), args.solver.name(), &report))?;
            } else {
                print!(
                    "{}",
                    describe_report(model.name(), args.solver.name(), &report)
                );
            }
            Ok(outcome(report.status))
        }
    }
}

fn outcome(status: IkStatus) -> Outcome {
    match status {
        IkStatus::Converged => Outcome::Success,
        IkStatus::NotConverged => Outcome::NotConverged,
    }
}

fn fit_json(s: &ClosedFormSolution) -> serde_json::Value {
    serde_json::json!({
        "fit": match s.fit { Fit::Exact => "exact", Fit::Approximate => "approximate" },
        "position_error": s.position_error,
        "orientation_error": s.orientation_error,
    })
}

fn report_json(robot: &str, solver: &str, report: &IkReport) -> serde_json::Value {
    serde_json::json!({
        "robot": robot,
        "solver": solver,
        "status": report.status.as_str(),
        "q": report.q,
        "position_error": report.position_error,
        "orientation_error": report.orientation_error,
        "iterations": report.iterations,
        "restarts": report.restarts,
        "elapsed_us": report.elapsed.as_secs_f64() * 1e6,
    })
}

fn format_q(q: &[f64]) -> String {
    q.iter()
        .map(|v| format!("{:.9}", crate::common::clean_zero(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

fn describe_report(robot: &str, solver: &str, report: &IkReport) -> String {
    format!(
        "{robot}: inverse kinematics ({solver})\nstatus: {}\nq (rad or m): {}\nposition error: {:.3e} m, orientation error: {:.3e} rad\niterations: {}, restarts: {}, time: {:.1} us\n",
        report.status.as_str(),
        format_q(&report.q),
        report.position_error,
        report.orientation_error,
        report.iterations,
        report.restarts,
        report.elapsed.as_secs_f64() * 1e6
    )
}

fn describe_closed_form(
    model: &Model,
    method: &str,
    solutions: &[ClosedFormSolution],
    status: IkStatus,
) -> String {
    let mut text = format!(
        "{}: closed-form inverse kinematics ({method})\nstatus: {}\n{} solution(s) within the joint limits, nearest the start first:\n",
        model.name(),
        status.as_str(),
        solutions.len()
    );
    for (i, s) in solutions.iter().enumerate() {
        let fit = match s.fit {
            Fit::Exact => "exact",
            Fit::Approximate => "approximate",
        };
        text.push_str(&format!(
            "  {}: [{}]  {fit}, position error {:.1e} m, orientation error {:.1e} rad\n",
            i + 1,
            format_q(&s.q),
            s.position_error,
            s.orientation_error
        ));
    }
    text
}

fn errors(model: &Model, data: &mut Data, q: &[f64], target: &Pose) -> CliResult<(f64, f64)> {
    let pose = forward_kinematics(model, data, q)?;
    let e = armkit::ik::pose_error(target, pose);
    Ok((e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm()))
}

/// The IK benchmark (TRAC-IK's protocol): random reachable targets (FK of
/// uniform random configurations within the limits, fixed seed), every solve
/// from the mid-range configuration, a success verified independently by
/// FK and the joint limits. Prints robot, solver, success rate and the mean,
/// median and 99th percentile of the solve time (over all targets).
#[derive(Args, Debug)]
pub struct BenchIkArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Number of targets.
    #[arg(long, default_value_t = 10000)]
    pub targets: usize,
    /// Solvers, comma-separated.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "lm")]
    pub solver: Vec<SolverArg>,
    /// Seed of the random targets.
    #[arg(long, default_value_t = 42)]
    pub target_seed: u64,
    #[command(flatten)]
    pub tolerances: ToleranceArgs,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// One row of the benchmark table.
#[derive(Clone, Debug)]
struct BenchRow {
    robot: String,
    solver: &'static str,
    targets: usize,
    successes: usize,
    times_us: Vec<f64>,
    mean_iterations: f64,
}

impl BenchRow {
    fn percentile(&self, p: f64) -> f64 {
        let mut sorted = self.times_us.clone();
        sorted.sort_by(f64::total_cmp);
        let index = ((p / 100.0) * (sorted.len() - 1) as f64).round() as usize;
        sorted[index.min(sorted.len() - 1)]
    }

    fn mean(&self) -> f64 {
        self.times_us.iter().sum::<f64>() / self.times_us.len() as f64
    }

    fn success_rate(&self) -> f64 {
        100.0 * self.successes as f64 / self.targets as f64
    }
}

/// Runs `armkit bench-ik`.
pub fn run_bench(args: &BenchIkArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let targets = benchmark_targets(&model, args.targets, args.target_seed)?;
    let start = model.neutral_configuration();
    let mut rows = Vec::new();
    for solver in &args.solver {
        rows.push(bench_solver(
            &model,
            &targets,
            &start,
            *solver,
            &args.tolerances,
        )?);
    }
    if args.json {
        let rows: Vec<serde_json::Value> = rows
            .iter()
            .map(|r| {
                serde_json::json!({
                    "robot": r.robot,
                    "solver": r.solver,
                    "targets": r.targets,
                    "success_rate": r.success_rate() / 100.0,
                    "mean_us": r.mean(),
                    "median_us": r.percentile(50.0),
                    "p99_us": r.percentile(99.0),
                    "max_us": r.percentile(100.0),
                    "mean_iterations": r.mean_iterations,
                })
            })
            .collect();
        print_json(&serde_json::json!({
            "protocol": "targets = FK of uniform random q within limits; start = mid-range; success = converged and verified by FK within the tolerances and within the limits",
            "target_seed": args.target_seed,
            "position_tolerance": args.tolerances.position_tolerance,
            "orientation_tolerance": args.tolerances.orientation_tolerance,
            "budget_ms": args.tolerances.budget_ms,
            "rows": rows,
        }))?;
    } else {
        println!(
            "IK benchmark: {} random reachable targets (seed {}), start = mid-range, tolerance {:e} m / {:e} rad, budget {} ms",
            args.targets,
            args.target_seed,
            args.tolerances.position_tolerance,
            args.tolerances.orientation_tolerance,
            args.tolerances.budget_ms
        );
        println!(
            "| robot | solver | success | mean (us) | median (us) | p99 (us) | max (us) | mean iterations |"
        );
        println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
        for r in &rows {
            println!(
                "| {} | {} | {:.2} % ({}/{}) | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
                r.robot,
                r.solver,
                r.success_rate(),
                r.successes,
                r.targets,
                r.mean(),
                r.percentile(50.0),
                r.percentile(99.0),
                r.percentile(100.0),
                r.mean_iterations
            );
        }
    }
    Ok(Outcome::Success)
}

fn bench_solver(
    model: &Model,
    targets: &[(Vec<f64>, Pose)],
    start: &[f64],
    solver: SolverArg,
    tolerances: &ToleranceArgs,
) -> CliResult<BenchRow> {
    let lm = IkMethod::LevenbergMarquardt(Default::default());
    let options = tolerances.options(solver.method().unwrap_or(lm))?;
    let mut numeric = IkSolver::new(model, options)?;
    let closed = match solver {
        SolverArg::ClosedForm => Some(ClosedFormSolver::new(model)?),
        _ => None,
    };
    let progress = ProgressBar::new(targets.len() as u64);
    progress.set_style(
        ProgressStyle::with_template("{prefix} [{bar:40}] {pos}/{len} {elapsed_precise} eta {eta}")
            .map_err(|e| CliError(format!("progress bar: {e}")))?
            .progress_chars("=> "),
    );
    progress.set_prefix(format!("{} {}", model.name(), solver.name()));
    let mut data = Data::new(model);
    let mut times_us = Vec::with_capacity(targets.len());
    let mut successes = 0;
    let mut iterations = 0usize;
    for (i, (_, target)) in targets.iter().enumerate() {
        let began = Instant::now();
        let q = match &closed {
            Some(c) => c
                .solve(target, start)?
                .into_iter()
                .find(|s| s.fit == Fit::Exact)
                .map(|s| s.q),
            None => {
                let report = numeric.solve(target, start)?;
                iterations += report.iterations;
                (report.status == IkStatus::Converged).then_some(report.q)
            }
        };
        times_us.push(began.elapsed().as_secs_f64() * 1e6);
        if let Some(q) = q {
            // Independent check: FK within the tolerances, limits respected.
            let (p, o) = errors(model, &mut data, &q, target)?;
            if p <= tolerances.position_tolerance
                && o <= tolerances.orientation_tolerance
                && model.check_limits(&q).is_ok()
            {
                successes += 1;
            }
        }
        if i % 64 == 0 {
            progress.set_position(i as u64);
        }
    }
    progress.finish_and_clear();
    Ok(BenchRow {
        robot: model.name().to_string(),
        solver: solver.name(),
        targets: targets.len(),
        successes,
        times_us,
        mean_iterations: iterations as f64 / targets.len() as f64,
    })
}
