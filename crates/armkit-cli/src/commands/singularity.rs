//! `armkit singularity`: seed 004's straight-line pose path through a wrist
//! singularity, tracked four ways: plain resolved rate, seed 004's avoidance
//! (detection of the singular region, Newton-Raphson IK every k-th planned
//! pose, C2 cubic fit), damped least squares (Nakamura) and the
//! singularity-robust inverse (Chiaverini); and the avoidance for several k
//! (the error against k, seed 004 Figs 7-8).
//!
//! The command prints a table per method (peak joint rate, maximum and final
//! tracking error, time in the singular region, IK solves) and the singular
//! region(s); with `--out DIR` it writes the figures (SVG + CSV), a
//! `summary.csv`, `summary.json` and a `report.html`. The same report is a
//! scenario's `[singularity]` method ([`report`]).

use std::path::{Path, PathBuf};

use armkit::math::{Pose, Vector3};
use armkit::singularity::{
    line_through, AvoidanceOptions, Baselines, Comparison, DetectionOptions, LineThrough,
    Manipulator, MethodRun, PathTracker, SEED004_DIRECTION, SEED004_THROUGH,
};
use armkit::space::FreeFloatingModel;
use armkit::tracking::{TrackingOptions, TrackingStatus};
use armkit::Model;
use clap::{Args, ValueEnum};

use crate::common::{
    parse_fixed_numbers, parse_numbers, print_json, CliError, CliResult, Outcome, RobotArgs,
};
use crate::plot::Figure;
use crate::report::{write_atomic, Animation, Check, Report, Table};

/// Track a straight-line pose path through a wrist singularity (seed 004):
/// plain, avoidance, damped least squares and singularity-robust inverse.
///
/// Exit code 3 when an avoidance or damped run stops before the end of the
/// path (plain tracking stopping at an exactly singular Jacobian is a
/// result, shown in the table).
#[derive(Args, Debug)]
pub struct SingularityArgs {
    /// What the arm stands on: a fixed base, or seed 004's free-floating
    /// satellite with its attitude held (the generalized Jacobian J*; the
    /// arm is then space6r).
    #[arg(long, value_enum, default_value_t = BaseArg::AttitudeHeld)]
    pub base: BaseArg,
    /// Built-in arm for a fixed base (default: space6r). Other arms need
    /// --through and --direction.
    #[arg(long, value_name = "NAME", conflicts_with = "robot_file")]
    pub robot: Option<String>,
    /// DH description file of the arm, for a fixed base.
    #[arg(long, value_name = "PATH")]
    pub robot_file: Option<PathBuf>,
    /// The configuration the line passes through at mid-path (rad or m; one
    /// per joint): singular, or nearly, e.g. q5 = 0 on a PUMA-type wrist.
    /// Default for space6r: 0.4,1.2,-0.5,0.6,0,-0.3 (q5 = 0: the wrist
    /// singularity).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub through: Option<String>,
    /// Joint displacement whose end-effector motion (J(through) times it,
    /// to first order) is the whole line, centred on --through. Default for
    /// space6r: 0.5,-0.3,0.4,0,0.8,0 (q5 moves: the line crosses q5 = 0).
    #[arg(long, value_name = "DQ1,DQ2,...", allow_hyphen_values = true)]
    pub direction: Option<String>,
    /// Offset of the line from the singular pose, along the direction the
    /// Jacobian loses there (m and rad); 0 passes through it.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub miss: f64,
    /// Duration of the motion, s (seed 004: 20 s).
    #[arg(long, default_value_t = 20.0, allow_hyphen_values = true)]
    pub duration: f64,
    /// Acceleration and deceleration time of the trapezoidal speed profile,
    /// s, in (0, duration / 2] (seed 004: 4 s).
    #[arg(long, default_value_t = 4.0, allow_hyphen_values = true)]
    pub accel_time: f64,
    /// Knot strides k of the avoidance method (IK every k-th planned pose
    /// of the singular region), integers >= 1; the first is the one compared
    /// with the baselines.
    #[arg(long, value_name = "K1,K2,...", default_value = "1,5,10")]
    pub k: String,
    /// |det J| below which the motion is singular (m^3 for a 6R arm).
    /// Default: the library's (armkit::singularity::DetectionOptions).
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub determinant_threshold: Option<f64>,
    /// A velocity-level step moving some joint by more than this in one
    /// control period is a jump (rad or m). Default: the library's.
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub joint_step_threshold: Option<f64>,
    /// Control period, s. Default: the library's (0.01 s).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Output directory for the CSV and SVG files, summary.json and
    /// report.html (created if missing). Without it, nothing is written.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the summary as JSON instead of tables.
    #[arg(long)]
    pub json: bool,
}

/// `--base` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BaseArg {
    /// A fixed base: the arm's world frame is the inertial frame.
    Fixed,
    /// Seed 004's satellite, attitude held, linear momentum zero.
    AttitudeHeld,
}

impl BaseArg {
    fn text(self) -> &'static str {
        match self {
            BaseArg::Fixed => "fixed base",
            BaseArg::AttitudeHeld => "free-floating base, attitude held",
        }
    }
}

/// Largest `k` accepted (a stride longer than any sensible path).
const MAX_K: f64 = 1e6;

/// Largest number of control periods per run (each run keeps every sample
/// of every joint, for several runs).
const MAX_STEPS: f64 = 1e6;

/// The arm, and the free-floating system when the base is held.
enum Plant {
    Fixed(Box<Model>),
    Held(Box<FreeFloatingModel>),
}

impl Plant {
    fn arm(&self) -> &Model {
        match self {
            Plant::Fixed(model) => model,
            Plant::Held(system) => system.arm(),
        }
    }

    fn manipulator(&self, base: Pose) -> Manipulator<'_> {
        match self {
            Plant::Fixed(model) => Manipulator::FixedBase(model),
            Plant::Held(system) => Manipulator::AttitudeHeld { system, base },
        }
    }
}

/// The line, the runs, and what the outputs need.
pub struct Study {
    plant: Plant,
    base: BaseArg,
    through: Vec<f64>,
    direction: Vec<f64>,
    line: LineThrough,
    ks: Vec<usize>,
    options: AvoidanceOptions,
    heading: String,
    comparison: Comparison,
}

/// Runs `armkit singularity`.
pub fn run(args: &SingularityArgs) -> CliResult<Outcome> {
    let study = study(args)?;
    let report = build_report(&study)?;
    let files = match &args.out {
        Some(dir) => write_outputs(dir, &study, &report)?,
        None => Vec::new(),
    };
    if args.json {
        let mut value = summary_json(&study, args);
        value["checks"] = report.summary_json()["checks"].clone();
        value["files"] = serde_json::json!(files);
        print_json(&value)?;
    } else {
        print!("{}", report.to_text());
        if !files.is_empty() {
            println!("wrote {}", files.join(", "));
        }
    }
    let completed = study
        .comparison
        .methods()
        .into_iter()
        .chain(&study.comparison.k_sweep)
        .filter(|r| r.method != armkit::singularity::Method::Plain)
        .all(|r| r.status == TrackingStatus::Completed);
    Ok(if completed {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

/// Checks the arguments, builds the line and runs every method.
pub fn study(args: &SingularityArgs) -> CliResult<Study> {
    let ks = parse_ks(&args.k)?;
    let defaults = AvoidanceOptions::default();
    let detection = DetectionOptions {
        determinant_threshold: positive(
            "--determinant-threshold",
            args.determinant_threshold
                .unwrap_or(defaults.detection.determinant_threshold),
        )?,
        joint_step_threshold: positive(
            "--joint-step-threshold",
            args.joint_step_threshold
                .unwrap_or(defaults.detection.joint_step_threshold),
        )?,
    };
    let options = AvoidanceOptions {
        tracking: TrackingOptions {
            dt: positive("--dt", args.dt.unwrap_or(defaults.tracking.dt))?,
            ..defaults.tracking
        },
        detection,
        ..defaults
    };
    let duration = positive("--duration", args.duration)?;
    if !(args.accel_time > 0.0 && 2.0 * args.accel_time <= duration) {
        return Err(CliError(format!(
            "--accel-time: must be in (0, duration / 2] = (0, {}] s, got {}",
            duration / 2.0,
            args.accel_time
        )));
    }
    if options.tracking.dt > duration {
        return Err(CliError(format!(
            "--dt: must be at most the duration ({duration} s), got {}",
            options.tracking.dt
        )));
    }
    let steps = (duration / options.tracking.dt).ceil();
    if steps > MAX_STEPS {
        return Err(CliError(format!(
            "--duration / --dt = {steps:.0} control periods: at most {MAX_STEPS:.0} \
             (every run records every period)"
        )));
    }
    if !args.miss.is_finite() {
        return Err(CliError(format!(
            "--miss: must be a finite number, got {}",
            args.miss
        )));
    }
    let plant = load_plant(args)?;
    let arm = plant.arm();
    let space6r = arm.name() == "space6r";
    let joint_values = |text: &Option<String>, option: &str, default: &[f64]| match text {
        Some(text) => parse_fixed_numbers(text, option, arm.dof()),
        None if space6r => Ok(default.to_vec()),
        None => Err(CliError(format!(
            "{option}: no default for {}: give --through (a configuration at the singularity) \
             and --direction (a joint motion crossing it)",
            arm.name()
        ))),
    };
    let through = joint_values(&args.through, "--through", &SEED004_THROUGH)?;
    let direction = joint_values(&args.direction, "--direction", &SEED004_DIRECTION)?;
    let line = line_through(
        &plant.manipulator(Pose::identity()),
        &through,
        &direction,
        args.miss,
    )
    .map_err(|e| CliError(format!("the line (--through, --direction, --miss): {e}")))?;
    let task = line.task(duration, args.accel_time);
    let tracker = PathTracker::new(plant.manipulator(line.base), task, options)
        .map_err(|e| CliError(format!("the line (--through, --direction, --miss): {e}")))?;
    let comparison = tracker.compare(&Baselines::for_detection(&options.detection), &ks)?;
    let (closest, closest_time) = comparison
        .plain
        .determinant
        .iter()
        .zip(&comparison.plain.time)
        .fold((f64::INFINITY, 0.0), |best, (d, t)| {
            if *d < best.0 {
                (*d, *t)
            } else {
                best
            }
        });
    let heading = format!(
        "{} on a {}: a straight line through q = ({}) at mid-path, {} s with {} s acceleration and \
         deceleration (trapezoidal speed), dt {} s; smallest |det J| along the plain run {} at \
         t = {:.2} s; singular where |det J| < {} or a joint would step more than {} per period",
        arm.name(),
        args.base.text(),
        join(&through),
        duration,
        args.accel_time,
        options.tracking.dt,
        short(closest),
        closest_time,
        short(options.detection.determinant_threshold),
        short(options.detection.joint_step_threshold),
    );
    Ok(Study {
        base: args.base,
        through,
        direction,
        line,
        ks,
        options,
        heading,
        comparison,
        plant,
    })
}

/// The arm, and the satellite when the base is held.
fn load_plant(args: &SingularityArgs) -> CliResult<Plant> {
    match args.base {
        BaseArg::Fixed => {
            let robot = RobotArgs {
                robot: args.robot.clone(),
                robot_file: args.robot_file.clone(),
                ..RobotArgs::default()
            };
            if robot.robot.is_none() && robot.robot_file.is_none() {
                return Ok(Plant::Fixed(Box::new(armkit::robots::space6r()?)));
            }
            Ok(Plant::Fixed(Box::new(robot.load()?)))
        }
        BaseArg::AttitudeHeld => {
            let named_other = args.robot.as_deref().is_some_and(|r| r != "space6r");
            if named_other || args.robot_file.is_some() {
                return Err(CliError(
                    "--base attitude-held: the free-floating system is seed 004's space6r on its \
                     satellite; other arms work with --base fixed"
                        .into(),
                ));
            }
            Ok(Plant::Held(Box::new(
                armkit::space::space6r_free_floating()?
            )))
        }
    }
}

/// `--k`: integers >= 1.
fn parse_ks(text: &str) -> CliResult<Vec<usize>> {
    parse_numbers(text, "--k")?
        .into_iter()
        .enumerate()
        .map(|(i, k)| {
            if k.fract() == 0.0 && (1.0..=MAX_K).contains(&k) {
                Ok(k as usize)
            } else {
                Err(CliError(format!(
                    "--k: value {}: k must be an integer in 1..={MAX_K} (IK every k-th planned \
                     pose of the singular region), got {k}",
                    i + 1
                )))
            }
        })
        .collect()
}

/// `value` when finite and > 0; else an error naming `option`.
fn positive(option: &str, value: f64) -> CliResult<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CliError(format!(
            "{option}: must be a finite number > 0, got {value}"
        )))
    }
}

fn join(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| format!("{v:.3}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A number in 4 significant digits.
fn short(v: f64) -> String {
    crate::report::format_value(v)
}

/// The runs of the table: plain, avoidance (first k), dls, sri, then the
/// other k of the sweep.
fn table_runs(study: &Study) -> Vec<&MethodRun> {
    let c = &study.comparison;
    let mut runs: Vec<&MethodRun> = c.methods().to_vec();
    runs.extend(c.k_sweep.iter().filter(|r| r.method != c.avoidance.method));
    runs
}

/// Table 1: one row per method.
fn methods_table(study: &Study) -> Table {
    let mut table = Table::new(
        "Tracking the line: one row per method (errors from the planned pose)",
        &[
            "method",
            "peak joint rate (rad/s)",
            "max position error (m)",
            "max orientation error (rad)",
            "final position error (m)",
            "final orientation error (rad)",
            "time in singular region (s)",
            "IK solves",
            "status",
        ],
    );
    for run in table_runs(study) {
        let s = &run.summary;
        table.push(vec![
            run.method.label(),
            format!("{:.4}", s.peak_joint_rate),
            format!("{:.3e}", s.max_position_error),
            format!("{:.3e}", s.max_orientation_error),
            format!("{:.3e}", s.final_position_error),
            format!("{:.3e}", s.final_orientation_error),
            format!("{:.2}", s.time_in_singular_region),
            s.ik_solves.to_string(),
            run.status.to_string(),
        ]);
    }
    table
}

/// Table 2: the singular regions the avoidance method planned through.
fn regions_table(study: &Study) -> Table {
    let mut table = Table::new(
        "Singular regions planned through by the avoidance method",
        &[
            "method",
            "start (s)",
            "end (s)",
            "trigger",
            "knots",
            "IK solves",
            "IK failures",
            "dropped knots",
            "max knot error (m, rad)",
        ],
    );
    for run in &study.comparison.k_sweep {
        for region in &run.regions {
            table.push(vec![
                run.method.label(),
                format!("{:.2}", region.start_time),
                format!("{:.2}", region.end_time),
                region.trigger.as_str().to_string(),
                region.knot_times.len().to_string(),
                region.ik_solves.to_string(),
                region.ik_failures.to_string(),
                region.dropped_knots.to_string(),
                format!(
                    "{:.1e}, {:.1e}",
                    region.max_knot_error.0, region.max_knot_error.1
                ),
            ]);
        }
    }
    table
}

/// Table 3: the error against k (seed 004 Figs 7-8).
fn k_table(study: &Study) -> Table {
    let mut table = Table::new(
        "Avoidance: tracking error against the knot stride k (seed 004, Figs 7-8)",
        &[
            "k",
            "IK solves",
            "max position error (m)",
            "max orientation error (rad)",
            "mean position error in region (m)",
            "mean orientation error in region (rad)",
        ],
    );
    for (k, run) in study.ks.iter().zip(&study.comparison.k_sweep) {
        let s = &run.summary;
        table.push(vec![
            k.to_string(),
            s.ik_solves.to_string(),
            format!("{:.3e}", s.max_position_error),
            format!("{:.3e}", s.max_orientation_error),
            format!("{:.3e}", s.mean_region_position_error),
            format!("{:.3e}", s.mean_region_orientation_error),
        ]);
    }
    table
}

/// True when `values` never decrease (`Rising`) or never increase (`Falling`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Trend {
    Rising,
    Falling,
}

fn follows(values: &[f64], trend: Trend) -> bool {
    values.windows(2).all(|w| match trend {
        Trend::Rising => w[1] >= w[0],
        Trend::Falling => w[1] <= w[0],
    })
}

/// The checks: plain's peak at least 10 times avoidance's, avoidance's final
/// pose error at most 1e-6, a region detected, every damped or avoiding run
/// completes, fewer IK solves for larger k.
fn checks(study: &Study) -> Vec<Check> {
    let c = &study.comparison;
    let avoidance = &c.avoidance;
    let label = avoidance.method.label();
    let mut checks = vec![
        Check::at_least(
            format!("peak joint rate: plain / {label}"),
            c.plain.summary.peak_joint_rate / avoidance.summary.peak_joint_rate,
            10.0,
            "",
        ),
        Check::at_most(
            format!("{label}: final position error"),
            avoidance.summary.final_position_error,
            1e-6,
            "m",
        ),
        Check::at_most(
            format!("{label}: final orientation error"),
            avoidance.summary.final_orientation_error,
            1e-6,
            "rad",
        ),
        Check::holds(
            format!("{label}: the singular region is detected and planned through"),
            !avoidance.regions.is_empty(),
            avoidance
                .regions
                .iter()
                .map(|r| {
                    format!(
                        "t = {:.2} to {:.2} s (trigger: {}), {} IK solves",
                        r.start_time,
                        r.end_time,
                        r.trigger.as_str(),
                        r.ik_solves
                    )
                })
                .collect::<Vec<_>>()
                .join("; "),
        ),
    ];
    for run in [&c.damped_least_squares, &c.singularity_robust]
        .into_iter()
        .chain(&c.k_sweep)
    {
        checks.push(Check::holds(
            format!("{}: the run completes the path", run.method.label()),
            run.status == TrackingStatus::Completed,
            run.status.to_string(),
        ));
    }
    if c.k_sweep.len() > 1 {
        let solves: Vec<f64> = c
            .k_sweep
            .iter()
            .map(|r| r.summary.ik_solves as f64)
            .collect();
        checks.push(Check::holds(
            "avoidance: fewer IK solves as k grows",
            sorted_ks(study) && follows(&solves, Trend::Falling),
            sweep_detail(study, |r| r.summary.ik_solves.to_string()),
        ));
    }
    checks
}

fn sorted_ks(study: &Study) -> bool {
    study.ks.windows(2).all(|w| w[0] < w[1])
}

/// `k=1: x, k=5: y, ...`.
fn sweep_detail(study: &Study, value: impl Fn(&MethodRun) -> String) -> String {
    study
        .ks
        .iter()
        .zip(&study.comparison.k_sweep)
        .map(|(k, r)| format!("k={k}: {}", value(r)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The error-against-k trade-off in words, as measured.
fn trade_off_note(study: &Study) -> String {
    let c = &study.comparison;
    let position: Vec<f64> = c
        .k_sweep
        .iter()
        .map(|r| r.summary.max_position_error)
        .collect();
    let orientation: Vec<f64> = c
        .k_sweep
        .iter()
        .map(|r| r.summary.max_orientation_error)
        .collect();
    let rising = sorted_ks(study)
        && follows(&position, Trend::Rising)
        && follows(&orientation, Trend::Rising);
    let verdict = if c.k_sweep.len() < 2 {
        "Give several k (--k 1,5,10) to see the trade-off".to_string()
    } else if rising {
        "The error grows with k while the IK solves fall: the trade-off seed 004 describes \
         (fewer solves, looser tracking between the knots)"
            .to_string()
    } else {
        "The error does not grow monotonically with k here: between knots the C2 cubic fit \
         follows the path closely, so the knot spacing matters less than the knots' own \
         accuracy and where they fall in the region"
            .to_string()
    };
    format!(
        "Error against k (max position / orientation error): {}. {verdict}.",
        sweep_detail(study, |r| format!(
            "{:.2e} m / {:.2e} rad, {} IK solves",
            r.summary.max_position_error, r.summary.max_orientation_error, r.summary.ik_solves
        ))
    )
}

/// Samples where `|det J|` is below the threshold.
fn singular_mask(run: &MethodRun, threshold: f64) -> Vec<bool> {
    run.determinant
        .iter()
        .map(|d| d.is_nan() || *d < threshold)
        .collect()
}

/// The figures: joint rates per method (Figs 5-6) with the singular region
/// marked, position and orientation error against time for each k (Figs
/// 7-8), and |det J| against time.
fn figures(study: &Study) -> Vec<(String, Figure)> {
    let c = &study.comparison;
    let arm = study.plant.arm();
    let threshold = study.options.detection.determinant_threshold;
    let mut figures = Vec::new();
    for (stem, run) in [
        ("joint_rates_plain", &c.plain),
        ("joint_rates_avoidance", &c.avoidance),
        ("joint_rates_dls", &c.damped_least_squares),
        ("joint_rates_sri", &c.singularity_robust),
    ] {
        let mut figure = Figure::new(
            format!(
                "{}: joint rates ({}, {})",
                run.method.label(),
                arm.name(),
                study.base.text()
            ),
            "t (s)",
            "joint rate (rad/s)",
            run.time.clone(),
        );
        for (joint, rates) in arm.joints().iter().zip(&run.joint_rates) {
            figure = figure.with_series(joint.name.clone(), rates.clone());
        }
        // The region as a box as tall as the largest rate (plotters has no
        // shading in our Figure; the CSV column is 0 outside the region).
        let height = run.summary.peak_joint_rate;
        let marker = singular_mask(run, threshold)
            .into_iter()
            .map(|s| if s { height } else { 0.0 })
            .collect();
        figure = figure.with_series("singular region (|det J| < threshold)", marker);
        figures.push((stem.to_string(), figure));
    }
    let x = c
        .k_sweep
        .first()
        .map(|r| r.time.clone())
        .unwrap_or_default();
    // In micrometres and microradians: the errors are far below the plot
    // axis' resolution in metres and radians.
    let micro = |v: &[f64]| v.iter().map(|e| e * 1e6).collect::<Vec<f64>>();
    let mut position = Figure::new(
        "Avoidance: position error against time for each k (seed 004, Fig 7)",
        "t (s)",
        "position error (µm)",
        x.clone(),
    );
    let mut orientation = Figure::new(
        "Avoidance: orientation error against time for each k (seed 004, Fig 8)",
        "t (s)",
        "orientation error (µrad)",
        x,
    );
    for (k, run) in study.ks.iter().zip(&c.k_sweep) {
        position = position.with_series(format!("k={k} (µm)"), micro(&run.position_error));
        orientation =
            orientation.with_series(format!("k={k} (µrad)"), micro(&run.orientation_error));
    }
    figures.push(("position_error_k".into(), position));
    figures.push(("orientation_error_k".into(), orientation));
    let mut determinant = Figure::new(
        format!(
            "|det J| along the path ({}, {})",
            arm.name(),
            study.base.text()
        ),
        "t (s)",
        "|det J| (m^3)",
        c.plain.time.clone(),
    );
    for run in c.methods() {
        determinant = determinant.with_series(run.method.label(), run.determinant.clone());
    }
    determinant = determinant.with_series("threshold", vec![threshold; c.plain.time.len()]);
    figures.push(("determinant".into(), determinant));
    figures
}

/// The avoidance run's motion, base included on a held system.
fn animation(study: &Study) -> CliResult<Animation> {
    let run = &study.comparison.avoidance;
    let arm = study.plant.arm();
    let configurations: Vec<Vec<f64>> = (0..run.time.len())
        .map(|i| run.joint_positions.iter().map(|q| q[i]).collect())
        .collect();
    let mut animation = Animation::from_configurations(arm, &run.time, &configurations)?;
    if let Plant::Held(system) = &study.plant {
        // The arm's frame is the base's mount frame; the base keeps its
        // attitude and moves with the arm (zero linear momentum).
        let mount = system.base().mount;
        for (frame, base) in animation.frames.iter_mut().zip(&run.base_position) {
            let base = Pose::new(study.line.base.rotation, Vector3::from(*base));
            let world = base * mount;
            for p in frame.iter_mut() {
                let q = world.rotation * Vector3::from(*p) + world.translation;
                *p = [q.x, q.y, q.z];
            }
        }
    }
    Ok(animation)
}

/// The comparison as a report (a scenario's `[singularity]` table, and the
/// command's `--out`).
pub fn report(args: &SingularityArgs) -> CliResult<Report> {
    build_report(&study(args)?)
}

fn build_report(study: &Study) -> CliResult<Report> {
    let avoidance = study.comparison.avoidance.method.label();
    Ok(Report {
        name: "singularity".into(),
        title: format!(
            "Singularity avoidance along a straight line on {} (seed 004)",
            study.plant.arm().name()
        ),
        description: format!(
            "{}. Methods: plain resolved rate (J^-1 of the commanded twist, seed 004 eq 28); seed 004's \
             avoidance (the singular region detected by the determinant and joint-step tests, Newton-Raphson \
             IK of every k-th planned pose inside it, warm-started, and the C2 piecewise cubic of eqs 33-42 \
             through the solutions; tracking resumes after); damped least squares with Nakamura's adaptive \
             damping; Chiaverini's singularity-robust inverse with numerical filtering. The animation shows \
             {avoidance}.",
            study.heading
        ),
        checks: checks(study),
        tables: vec![methods_table(study), regions_table(study), k_table(study)],
        figures: figures(study),
        notes: vec![
            trade_off_note(study),
            format!(
                "The line: the straight pose line whose midpoint is the pose at q = ({}) and whose \
                 extent is the end-effector motion of the joint displacement ({}) there \
                 (armkit::singularity::line_through); the start configuration is found by \
                 continuation from the midpoint, so it lies on the branch through the singularity.",
                join(&study.through),
                join(&study.direction)
            ),
            "Time in the singular region counts the control periods whose start state has |det J| \
             below the threshold, for each method as it crossed the region. The joint-rate plots mark \
             that region with a box as tall as the largest rate."
                .into(),
        ],
        animation: Some(animation(study)?),
    })
}

/// Writes the report's files into `dir` and `summary.csv`; returns the paths.
fn write_outputs(dir: &Path, study: &Study, report: &Report) -> CliResult<Vec<String>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError(format!("{}: cannot create: {e}", dir.display())))?;
    let absolute = dir
        .canonicalize()
        .map_err(|e| CliError(format!("{}: {e}", dir.display())))?;
    let (Some(parent), Some(name)) = (absolute.parent(), absolute.file_name()) else {
        return Err(CliError(format!(
            "--out {}: give a folder other than the root",
            dir.display()
        )));
    };
    let mut named = report.clone();
    named.name = name.to_string_lossy().to_string();
    named.write(parent)?;
    let mut files: Vec<String> = report
        .figures
        .iter()
        .flat_map(|(stem, _)| [format!("{stem}.csv"), format!("{stem}.svg")])
        .chain(["summary.json".to_string(), "report.html".to_string()])
        .map(|f| dir.join(f).display().to_string())
        .collect();
    let summary = dir.join("summary.csv");
    write_atomic(&summary, summary_csv(study).as_bytes())?;
    files.push(summary.display().to_string());
    Ok(files)
}

/// `summary.csv`: one row per method of the table.
fn summary_csv(study: &Study) -> String {
    let mut out = "method,status,peak_joint_rate,max_position_error_m,max_orientation_error_rad,\
                   final_position_error_m,final_orientation_error_rad,time_in_singular_region_s,\
                   mean_region_position_error_m,mean_region_orientation_error_rad,ik_solves\n"
        .to_string();
    for run in table_runs(study) {
        let s = &run.summary;
        out += &format!(
            "{},{},{},{},{},{},{},{},{},{},{}\n",
            run.method.label(),
            run.status,
            s.peak_joint_rate,
            s.max_position_error,
            s.max_orientation_error,
            s.final_position_error,
            s.final_orientation_error,
            s.time_in_singular_region,
            s.mean_region_position_error,
            s.mean_region_orientation_error,
            s.ik_solves
        );
    }
    out
}

/// The `--json` summary (checks and files are added by the caller).
fn summary_json(study: &Study, args: &SingularityArgs) -> serde_json::Value {
    let goal = &study.line.goal;
    let (roll, pitch, yaw) = goal.rpy();
    serde_json::json!({
        "robot": study.plant.arm().name(),
        "base": match study.base { BaseArg::Fixed => "fixed", BaseArg::AttitudeHeld => "attitude-held" },
        "through": study.through,
        "direction": study.direction,
        "miss": args.miss,
        "start": study.line.start,
        "goal_xyz_rpy": [goal.translation.x, goal.translation.y, goal.translation.z, roll, pitch, yaw],
        "duration": args.duration,
        "accel_time": args.accel_time,
        "dt": study.options.tracking.dt,
        "determinant_threshold": study.options.detection.determinant_threshold,
        "joint_step_threshold": study.options.detection.joint_step_threshold,
        "k": study.ks,
        "methods": table_runs(study).iter().map(|r| serde_json::json!({
            "method": r.method.label(),
            "status": r.status.to_string(),
            "peak_joint_rate": r.summary.peak_joint_rate,
            "max_position_error": r.summary.max_position_error,
            "max_orientation_error": r.summary.max_orientation_error,
            "final_position_error": r.summary.final_position_error,
            "final_orientation_error": r.summary.final_orientation_error,
            "time_in_singular_region": r.summary.time_in_singular_region,
            "mean_region_position_error": r.summary.mean_region_position_error,
            "mean_region_orientation_error": r.summary.mean_region_orientation_error,
            "ik_solves": r.summary.ik_solves,
            "min_determinant": r.determinant.iter().copied().fold(f64::INFINITY, f64::min),
            "regions": r.regions.iter().map(|g| serde_json::json!({
                "start_time": g.start_time,
                "end_time": g.end_time,
                "trigger": g.trigger.as_str(),
                "knots": g.knot_times.len(),
                "ik_solves": g.ik_solves,
                "ik_failures": g.ik_failures,
                "dropped_knots": g.dropped_knots,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}
