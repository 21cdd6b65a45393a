//! `armkit bench-ik`: the IK benchmark.

use std::time::{Duration, Instant};

use armkit::ik::analytic::Representatives;
use armkit::ik::{benchmark_targets, AutoSolver, IkSolver, IkStatus};
use armkit::kinematics::Data;
use armkit::math::Pose;
use armkit::Model;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use super::analytic::route;
use super::report::errors;
use super::{RedundancyArgs, SolverArg, ToleranceArgs};
use crate::common::{print_json, CliError, CliResult, Outcome, RobotArgs};

/// The IK benchmark (TRAC-IK's protocol): random reachable targets (FK of
/// uniform random configurations within the limits, fixed seed), every solve
/// from the mid-range configuration, a success verified independently by
/// FK and the joint limits. Prints robot, solver, success rate and the mean,
/// median and 99th percentile of the solve time (over all targets). The
/// solvers' budget is wall-clock: a failed solve that reached it while its
/// thread had the processor for less than half of that time was preempted
/// by the machine, and runs again (up to three times, counted in the last
/// column) before it counts as a failure.
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
    /// The analytic solver's redundancy parameter and searches (as in
    /// `armkit ik`; `--sweep` is not taken here).
    #[command(flatten)]
    pub redundancy: RedundancyArgs,
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
    /// Failed solves run again because the machine preempted them (see
    /// [`preempted`]).
    preempted: usize,
}

/// Times one solve preempted by the machine is run again before it counts
/// as a failure.
const PREEMPTION_RETRIES: usize = 3;

/// The calling thread's CPU time, or `None` where the platform has no
/// per-thread clock.
#[cfg(unix)]
pub fn thread_cpu_time() -> Option<Duration> {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec into `now`, which lives for
    // the call; CLOCK_THREAD_CPUTIME_ID needs no other argument.
    let status = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut now) };
    (status == 0).then(|| Duration::new(now.tv_sec as u64, now.tv_nsec as u32))
}

#[cfg(not(unix))]
pub fn thread_cpu_time() -> Option<Duration> {
    None
}

/// Whether a failed solve was the machine's doing: its wall-clock time
/// reached the budget while its thread ran for less than half of it (the
/// solver's budget is wall-clock; a loaded machine cuts a solve short that
/// a quiet one finishes).
pub fn preempted(wall: Duration, cpu: Option<Duration>, budget_ms: f64) -> bool {
    let budget = Duration::from_secs_f64(budget_ms * 1e-3);
    cpu.is_some_and(|cpu| wall >= budget && cpu.as_secs_f64() < 0.5 * wall.as_secs_f64())
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

/// The analytic solver's options are refused where they would be ignored:
/// `--sweep` (the benchmark times one parameter value) and any of them
/// without `--solver analytic`.
fn check_redundancy_args(args: &BenchIkArgs) -> CliResult<()> {
    let r = &args.redundancy;
    if r.sweep.is_some() {
        return Err(CliError(
            "--sweep: not taken by bench-ik (it times one parameter value; use --parameter)".into(),
        ));
    }
    let given = r.fixed_joint.is_some()
        || r.parameter.is_some()
        || r.search != RedundancyArgs::default().search;
    if given && !args.solver.contains(&SolverArg::Analytic) {
        return Err(CliError(
            "--fixed-joint / --parameter / --search: only with --solver analytic".into(),
        ));
    }
    Ok(())
}

/// Runs `armkit bench-ik`.
pub fn run_bench(args: &BenchIkArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    check_redundancy_args(args)?;
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
            &args.redundancy,
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
                    "preempted_retries": r.preempted,
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
            "| robot | solver | success | mean (us) | median (us) | p99 (us) | max (us) | mean iterations | preempted, run again |"
        );
        println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
        for r in &rows {
            println!(
                "| {} | {} | {:.2} % ({}/{}) | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {} |",
                r.robot,
                r.solver,
                r.success_rate(),
                r.successes,
                r.targets,
                r.mean(),
                r.percentile(50.0),
                r.percentile(99.0),
                r.percentile(100.0),
                r.mean_iterations,
                r.preempted
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
    redundancy: &RedundancyArgs,
) -> CliResult<BenchRow> {
    let options = tolerances.options(solver.method())?;
    let mut numeric = IkSolver::new(model, options)?;
    let mut auto = match solver {
        SolverArg::Auto => Some(AutoSolver::new(model, options)?),
        _ => None,
    };
    let mut analytic = match solver {
        // The nearest exact solution is timed: one representative each.
        SolverArg::Analytic => Some(route(model, redundancy, Representatives::Nearest, start)?),
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
    let mut preemptions = 0;
    for (i, (_, target)) in targets.iter().enumerate() {
        for attempt in 0..=PREEMPTION_RETRIES {
            let cpu_before = thread_cpu_time();
            let began = Instant::now();
            let (q, solve_iterations) = if let Some(route) = analytic.as_mut() {
                (route.nearest_exact(target, start)?, 0)
            } else {
                let report = match auto.as_mut() {
                    Some(auto) => auto.solve(target, start)?.report,
                    None => numeric.solve(target, start)?,
                };
                let converged = report.status == IkStatus::Converged;
                (converged.then_some(report.q), report.iterations)
            };
            let wall = began.elapsed();
            let cpu = thread_cpu_time()
                .zip(cpu_before)
                .map(|(after, before)| after.saturating_sub(before));
            // Independent check: FK within the tolerances, limits respected.
            let solved = match q {
                Some(q) => {
                    let (p, o) = errors(model, &mut data, &q, target)?;
                    p <= tolerances.position_tolerance
                        && o <= tolerances.orientation_tolerance
                        && model.check_limits(&q).is_ok()
                }
                None => false,
            };
            let retry = !solved
                && attempt < PREEMPTION_RETRIES
                && preempted(wall, cpu, tolerances.budget_ms);
            if retry {
                preemptions += 1;
                continue;
            }
            times_us.push(wall.as_secs_f64() * 1e6);
            iterations += solve_iterations;
            successes += usize::from(solved);
            break;
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
        preempted: preemptions,
    })
}
