//! `armkit ik` (inverse kinematics of one pose) and `armkit bench-ik` (the
//! IK benchmark: success rate and solve times on random reachable targets).

mod analytic;
mod bench;
mod report;

pub use bench::{preempted, run_bench, thread_cpu_time, BenchIkArgs};

use std::time::Duration;

use armkit::ik::analytic::Representatives;
use armkit::ik::{AutoSolver, IkMethod, IkOptions, IkReport, IkSolver, ReachBound, SolverName};
use armkit::math::Pose;
use armkit::Model;
use clap::{Args, ValueEnum};

use crate::common::{
    parse_fixed_numbers, parse_pose, print_json, CliError, CliResult, Outcome, RobotArgs,
};
use report::{describe_report, outcome, report_json};

/// `--solver` values: the library's [`SolverName`] vocabulary, the same
/// names as Python's `solver=` (a test checks the two lists agree).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// The analytic solver where the arm's class allows (all solutions, the
    /// nearest returned), otherwise Levenberg-Marquardt (default).
    Auto,
    /// Every solution by subproblem decomposition or elimination (spherical
    /// wrist, UR family, general 6R arms, 7-DOF by a redundancy parameter;
    /// seed 002's arm4).
    #[value(alias = "closed-form", alias = "closed_form")]
    Analytic,
    /// Levenberg-Marquardt, Sugihara's damping.
    Lm,
    /// Newton-Raphson with the pseudo-inverse (seed 004, Fig 2).
    Nr,
    /// Damped least squares, Nakamura's adaptive damping.
    Dls,
    /// Chiaverini's singularity-robust inverse with numerical filtering.
    Sri,
}

impl SolverArg {
    /// The library's name of the solver.
    pub fn solver(self) -> SolverName {
        match self {
            SolverArg::Auto => SolverName::Auto,
            SolverArg::Analytic => SolverName::Analytic,
            SolverArg::Lm => SolverName::Lm,
            SolverArg::Nr => SolverName::Nr,
            SolverArg::Dls => SolverName::Dls,
            SolverArg::Sri => SolverName::Sri,
        }
    }

    fn name(self) -> &'static str {
        self.solver().as_str()
    }

    /// The numeric method (Levenberg-Marquardt for auto and the analytic
    /// solver's best effort).
    fn method(self) -> IkMethod {
        self.solver().method()
    }
}

/// `--representatives` values (the library's [`Representatives`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum RepresentativesArg {
    /// Each distinct solution once, its 2 pi multiple nearest the start
    /// (default).
    #[default]
    Nearest,
    /// Every 2 pi multiple of each joint angle within the joint limits.
    Every,
}

impl RepresentativesArg {
    /// The library's choice.
    pub fn representatives(self) -> Representatives {
        match self {
            RepresentativesArg::Nearest => Representatives::Nearest,
            RepresentativesArg::Every => Representatives::Every,
        }
    }
}

/// Largest `--sweep` accepted: the parameter values of one run.
pub const MAX_SWEEP: usize = 100_000;

/// Largest `--budget-ms` accepted: one hour per solve, ms.
pub const MAX_BUDGET_MS: f64 = 3.6e6;

/// Tolerances shared by `ik` and `bench-ik`.
#[derive(Args, Debug)]
pub struct ToleranceArgs {
    /// Position tolerance, m.
    #[arg(long, default_value_t = 1e-6)]
    pub position_tolerance: f64,
    /// Orientation tolerance, rad.
    #[arg(long, default_value_t = 1e-6)]
    pub orientation_tolerance: f64,
    /// Time budget per solve, ms, in (0, 3.6e6] (one hour).
    #[arg(long, default_value_t = 5.0)]
    pub budget_ms: f64,
    /// Seed of the solver's random restarts.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

impl ToleranceArgs {
    fn options(&self, method: IkMethod) -> CliResult<IkOptions> {
        // One hour bounds a single solve; the checked conversion keeps a
        // value Duration cannot hold an error rather than a panic.
        let budget =
            (self.budget_ms.is_finite() && self.budget_ms > 0.0 && self.budget_ms <= MAX_BUDGET_MS)
                .then(|| Duration::try_from_secs_f64(self.budget_ms * 1e-3).ok())
                .flatten()
                .ok_or_else(|| {
                    CliError(format!(
                        "--budget-ms: must be > 0 and <= {MAX_BUDGET_MS:e} ms (one hour), got {:e}",
                        self.budget_ms
                    ))
                })?;
        let options = IkOptions {
            method,
            position_tolerance: self.position_tolerance,
            orientation_tolerance: self.orientation_tolerance,
            time_budget: Some(budget),
            seed: self.seed,
            ..IkOptions::default()
        };
        options.validate()?;
        Ok(options)
    }
}

/// The redundancy parameter of a 7-DOF arm (analytic solver).
#[derive(Args, Debug, Default)]
pub struct RedundancyArgs {
    /// Hold this joint (1-based) and solve the other six analytically
    /// (default for 7-DOF arms that are not spherical-shoulder-elbow-wrist:
    /// the first joint, last first, that leaves a solvable class).
    #[arg(long, value_name = "JOINT")]
    pub fixed_joint: Option<usize>,
    /// The redundancy parameter: the elbow angle (rad) of a
    /// spherical-shoulder-elbow-wrist arm, or the held joint's value
    /// (default: the start configuration's).
    #[arg(long, value_name = "VALUE", allow_hyphen_values = true)]
    pub parameter: Option<f64>,
    /// Sweep the parameter over N values (the elbow angle's circle, or the
    /// held joint's range) and list the solutions of all of them; N in
    /// 1..=100000.
    #[arg(long, value_name = "N")]
    pub sweep: Option<usize>,
    /// How the analytic solver solves 6R arms without a closed form:
    /// `elimination` (the only route: algebraic elimination, tens of
    /// microseconds). `1d` and `2d` (retired searches) are errors.
    #[arg(long, value_enum, default_value_t = SearchArg::Elimination)]
    pub search: SearchArg,
}

/// Why a retired `--search` value is refused.
const RETIRED: &str = "retired (the searches are gone: every 6R arm without a closed form is solved by elimination, the default; arms elimination does not take need a numeric solver, e.g. --solver lm); expected `elimination`";

/// `--search` values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum SearchArg {
    /// Closed forms, elimination for the rest (default).
    #[default]
    #[value(name = "elimination")]
    Elimination,
    /// Retired (the 1-D searches; elimination solves those arms): an error
    /// naming the value.
    #[value(name = "1d", hide = true)]
    OneD,
    /// Retired (the 2-D search; elimination solves general 6R arms): an
    /// error naming the value.
    #[value(name = "2d", hide = true)]
    TwoD,
}

impl SearchArg {
    /// The value as written on the command line.
    pub fn name(self) -> &'static str {
        match self {
            SearchArg::Elimination => "elimination",
            SearchArg::OneD => "1d",
            SearchArg::TwoD => "2d",
        }
    }

    /// Errors: a retired value (named).
    pub fn check(self) -> CliResult<()> {
        match self {
            SearchArg::Elimination => Ok(()),
            SearchArg::OneD | SearchArg::TwoD => {
                Err(CliError(format!("--search {}: {RETIRED}", self.name())))
            }
        }
    }
}

/// Inverse kinematics of one pose: every solution for the analytic solver,
/// the solver's report for the numeric methods and auto. Exit code 3 when
/// the target is not reached (the best effort is printed, the reason on stderr).
#[derive(Args, Debug)]
pub struct IkArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Target pose "x,y,z,roll,pitch,yaw" in the world frame (m, rad;
    /// R = Rz(yaw) Ry(pitch) Rx(roll), as in URDF). Required unless --explain.
    #[arg(long, value_name = "X,Y,Z,R,P,Y", allow_hyphen_values = true)]
    pub pose: Option<String>,
    /// Start configuration, one value per joint (default: mid-range).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub start: Option<String>,
    /// Solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Auto)]
    pub solver: SolverArg,
    /// Which 2 pi multiples of the analytic solutions' joint angles are
    /// listed (--solver analytic): `nearest` (default: each distinct
    /// solution once) or `every` (each multiple within the joint limits).
    #[arg(long, value_enum)]
    pub representatives: Option<RepresentativesArg>,
    /// Print the arm's joint axes (lines at zero configuration), which
    /// consecutive axes intersect or are parallel, and its analytic class.
    #[arg(long)]
    pub explain: bool,
    #[command(flatten)]
    pub redundancy: RedundancyArgs,
    #[command(flatten)]
    pub tolerances: ToleranceArgs,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `armkit ik`.
pub fn run(args: &IkArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    if args.explain {
        analytic::explain(&model, &args.redundancy, args.json && args.pose.is_none())?;
    }
    let Some(pose) = &args.pose else {
        if args.explain {
            return Ok(Outcome::Success);
        }
        return Err(CliError("--pose: required unless --explain".into()));
    };
    let target = parse_pose(pose, "--pose")?;
    let start = match &args.start {
        Some(text) => parse_fixed_numbers(text, "--start", model.dof())?,
        None => model.neutral_configuration(),
    };
    let options = args.tolerances.options(args.solver.method())?;
    check_analytic_flags(args)?;
    match args.solver {
        SolverArg::Analytic => analytic::run(args, &model, &target, &start, options),
        SolverArg::Auto => {
            let mut solver = AutoSolver::new(&model, options)?;
            let solved = solver.solve(&target, &start)?;
            let class = solver.class().map(|c| c.as_str()).unwrap_or("none");
            if args.json {
                let mut json = report_json(model.name(), "auto", &solved.report);
                json["route"] = solved.route.as_str().into();
                json["class"] = class.into();
                print_json(&json)?;
            } else {
                let label = format!("auto: {}, class {class}", solved.route);
                print!("{}", describe_report(model.name(), &label, &solved.report));
            }
            explain_failure(&model, &target, &solved.report, &options);
            Ok(outcome(solved.report.status))
        }
        _ => {
            let mut solver = IkSolver::new(&model, options)?;
            let report = solver.solve(&target, &start)?;
            if args.json {
                print_json(&report_json(model.name(), args.solver.name(), &report))?;
            } else {
                print!(
                    "{}",
                    describe_report(model.name(), args.solver.name(), &report)
                );
            }
            explain_failure(&model, &target, &report, &options);
            Ok(outcome(report.status))
        }
    }
}

/// The analytic solver's flags are refused with another solver, which
/// would ignore them (the message names the flag given and the solver).
fn check_analytic_flags(args: &IkArgs) -> CliResult<()> {
    if args.solver == SolverArg::Analytic {
        return Ok(());
    }
    let r = &args.redundancy;
    let given = [
        ("--fixed-joint", r.fixed_joint.is_some()),
        ("--parameter", r.parameter.is_some()),
        ("--sweep", r.sweep.is_some()),
        ("--search", r.search != SearchArg::default()),
        ("--representatives", args.representatives.is_some()),
    ];
    match given.iter().find(|(_, given)| *given) {
        Some((flag, _)) => Err(CliError(format!(
            "{flag}: only with --solver analytic (the {} solver does not take it)",
            args.solver.name()
        ))),
        None => Ok(()),
    }
}

/// One line on stderr saying why a solve did not converge (nothing when it did).
fn explain_failure(model: &Model, target: &Pose, report: &IkReport, options: &IkOptions) {
    if report.converged() {
        return;
    }
    eprintln!("{}", failure_reason(model, target, report, options));
}

/// Why `report` did not converge, in one line.
pub(crate) fn failure_reason(
    model: &Model,
    target: &Pose,
    report: &IkReport,
    options: &IkOptions,
) -> String {
    let reach = ReachBound::of_model(model);
    if reach.excludes(target) {
        return format!(
            "ik: unreachable: the target is {:.4} m from the first joint axis, beyond the arm's reach of {:.4} m (sum of its link lengths); not attempted",
            reach.distance(target),
            reach.radius()
        );
    }
    format!(
        "ik: not converged: best position error {:.3e} m, orientation error {:.3e} rad (tolerances {:e} m, {:e} rad) after {} iterations and {} restarts in {:.1} us",
        report.position_error,
        report.orientation_error,
        options.position_tolerance,
        options.orientation_tolerance,
        report.iterations,
        report.restarts,
        report.elapsed.as_secs_f64() * 1e6
    )
}
