//! `armkit singularity`: seed 004's straight-line pose path through a wrist
//! singularity, tracked four ways: plain resolved rate, seed 004's avoidance
//! (detection of the singular region, Newton-Raphson IK every k-th planned
//! pose, C2 cubic fit), damped least squares (Nakamura) and the
//! singularity-robust inverse (Chiaverini), singularity separation with a
//! damped reciprocal (the paper's reference [9]); and the avoidance for
//! several k (the error against k, seed 004 Figs 7-8).
//!
//! The command prints a table per method (peak joint rate, maximum and final
//! tracking error, time in the singular region, IK solves) and the singular
//! region(s); with `--out DIR` it writes the figures (SVG + CSV), a
//! `summary.csv`, `summary.json` and a `report.html`. The same report is a
//! scenario's `[singularity]` method ([`report`]).

use std::path::PathBuf;

use armkit::error::brief;
use armkit::math::Pose;
use armkit::singularity::{
    AvoidanceOptions, BaseKind, RegionPlan, SEED004_DIRECTION, SEED004_THROUGH,
};
use armkit::study::{AvoidanceOutcome, AvoidanceStudy, ThresholdRule};
use armkit::tracking::{Feedback, TrackingStatus, MAX_PERIODS};
use clap::{Args, ValueEnum};

use crate::common::{
    parse_fixed_numbers, parse_numbers, positive, print_json, CliError, CliResult, Outcome,
};
use crate::report::{format_value, join};

mod figures;
mod outputs;
mod page;
mod plant;
mod tables;

use outputs::{summary_json, write_outputs};
use page::build_report;
pub use page::report;
use plant::{load_plant, Plant};

/// Track a straight-line pose path through a wrist singularity (seed 004):
/// plain, avoidance, DLS, SRI and singularity separation (reference [9]).
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
    /// Misses of the sweep's parallel lines (m and rad, like --miss), each
    /// tracked by plain, the avoidance (first k) and the baselines.
    #[arg(
        long,
        value_name = "M1,M2,...",
        allow_hyphen_values = true,
        default_value = "-0.03,-0.01,-0.003,-0.001,0,0.001,0.003,0.01,0.03"
    )]
    pub miss_sweep: String,
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
    /// Default: seed 004's rule, the largest |det J| where plain tracking of
    /// the line through --through (no miss) steps a joint by more than the
    /// joint-step threshold (armkit::singularity::calibrate_determinant_threshold);
    /// the fitted 0.004 is then run beside it as a labelled comparison.
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub determinant_threshold: Option<f64>,
    /// A velocity-level step moving some joint by more than this in one
    /// control period is a jump (rad or m). Default: the library's.
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub joint_step_threshold: Option<f64>,
    /// Control period, s. Default: the library's (0.01 s).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// How the avoidance plans a singular region's knots: `joint` (all
    /// together, every step within the joint-step threshold), `greedy`
    /// (knot by knot, within it) or `exact` (seed 004's step 3 as printed:
    /// the Newton-Raphson knots, however fast the joints must move).
    #[arg(long, value_name = "joint|greedy|exact", default_value = "joint")]
    pub region_plan: String,
    /// Tracking feedback of every run: `next-pose` (seed 004, eqs 26-27:
    /// the twist to the pose due one period later) or `open-loop` (the
    /// path's twist alone, no error feedback).
    #[arg(long, value_name = "next-pose|open-loop", default_value = "next-pose")]
    pub feedback: String,
    /// Miss of the line on which seed 004's method also runs as printed
    /// (exact knots, no rate bound, eps_dq = --as-printed-eps-dq deg/s), m
    /// and rad; `none` skips it.
    #[arg(
        long,
        value_name = "M|none",
        default_value = "0.003",
        allow_hyphen_values = true
    )]
    pub as_printed_miss: String,
    /// eps_dq of the as-printed run, deg/s (seed 004 prints 5).
    #[arg(
        long,
        value_name = "DEG/S",
        default_value_t = 5.0,
        allow_hyphen_values = true
    )]
    pub as_printed_eps_dq: f64,
    /// Also run the avoidance for every k with open-loop tracking (Figs
    /// 7-8's explanation tested): `on` or `off`.
    #[arg(long, value_name = "on|off", default_value = "on")]
    pub open_loop_runs: String,
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

/// The line, the runs ([`AvoidanceOutcome`]), and what the outputs need.
pub struct Study {
    plant: Plant,
    base: BaseArg,
    through: Vec<f64>,
    direction: Vec<f64>,
    heading: String,
    outcome: AvoidanceOutcome,
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
        let summary = report.summary_json();
        value["checks"] = summary["checks"].clone();
        value["findings"] = summary["findings"].clone();
        value["files"] = serde_json::json!(files);
        print_json(&value)?;
    } else {
        print!("{}", report.to_text());
        if !files.is_empty() {
            println!("wrote {}", files.join(", "));
        }
    }
    let completed = study
        .outcome
        .comparison
        .methods()
        .into_iter()
        .chain(&study.outcome.comparison.k_sweep)
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
    let threshold = match args.determinant_threshold {
        Some(value) => ThresholdRule::Given(positive("--determinant-threshold", value)?),
        None => ThresholdRule::Calibrated,
    };
    let joint_step_threshold = positive(
        "--joint-step-threshold",
        args.joint_step_threshold
            .unwrap_or(defaults.detection.joint_step_threshold),
    )?;
    let dt = positive("--dt", args.dt.unwrap_or(defaults.tracking.dt))?;
    let miss_sweep = parse_numbers(&args.miss_sweep, "--miss-sweep")?;
    if let Some(bad) = miss_sweep.iter().find(|m| !m.is_finite()) {
        return Err(CliError(format!(
            "--miss-sweep: every miss must be a finite number (m and rad), got {bad}"
        )));
    }
    let duration = positive("--duration", args.duration)?;
    if !(args.accel_time > 0.0 && 2.0 * args.accel_time <= duration) {
        return Err(CliError(format!(
            "--accel-time: must be in (0, duration / 2] = (0, {}] s, got {}",
            duration / 2.0,
            args.accel_time
        )));
    }
    if dt > duration {
        return Err(CliError(format!(
            "--dt: must be at most the duration ({duration} s), got {dt}"
        )));
    }
    let steps = (duration / dt).ceil();
    if steps > MAX_PERIODS as f64 {
        return Err(CliError(format!(
            "--duration / --dt = {} control periods: at most {MAX_PERIODS} \
             (every run records every period)",
            brief(steps)
        )));
    }
    if !args.miss.is_finite() {
        return Err(CliError(format!(
            "--miss: must be a finite number, got {}",
            args.miss
        )));
    }
    let region_plan: RegionPlan = args
        .region_plan
        .parse()
        .map_err(|e| CliError(format!("--region-plan: {e}")))?;
    let feedback: Feedback = args
        .feedback
        .parse()
        .map_err(|e| CliError(format!("--feedback: {e}")))?;
    let as_printed_miss = match args.as_printed_miss.trim() {
        "none" => None,
        text => Some(
            text.parse::<f64>()
                .ok()
                .filter(|m| m.is_finite())
                .ok_or_else(|| {
                    CliError(format!(
                        "--as-printed-miss: a finite number (m and rad) or `none`, got \"{text}\""
                    ))
                })?,
        ),
    };
    let as_printed_eps_dq = positive("--as-printed-eps-dq", args.as_printed_eps_dq)?;
    let open_loop = match args.open_loop_runs.as_str() {
        "on" => true,
        "off" => false,
        other => {
            return Err(CliError(format!(
                "--open-loop-runs: `on` or `off`, got \"{other}\""
            )))
        }
    };
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
    // The library's study (armkit::study::AvoidanceStudy) with the flags'
    // values; the checks and notes are its own.
    let library = AvoidanceStudy {
        base: match args.base {
            BaseArg::Fixed => BaseKind::Fixed,
            BaseArg::AttitudeHeld => BaseKind::AttitudeHeld,
        },
        through: through.clone(),
        direction: direction.clone(),
        miss: args.miss,
        miss_sweep,
        duration,
        acceleration_time: args.accel_time,
        ks,
        threshold,
        joint_step_threshold,
        dt,
        as_printed_miss,
        as_printed_eps_dq,
        open_loop,
        region_plan,
        feedback,
        ..AvoidanceStudy::default()
    };
    let outcome = library
        .compare(plant.manipulator(Pose::identity()))
        .map_err(|e| CliError(format!("the line (--through, --direction, --miss): {e}")))?;
    let options = outcome.options;
    let comparison = &outcome.comparison;
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
         t = {:.2} s; singular where |det J| < {} ({}) or a joint would step more than {} per \
         period; region plan {}, feedback {}",
        arm.name(),
        args.base.text(),
        join(&through, 3),
        duration,
        args.accel_time,
        options.tracking.dt,
        format_value(closest),
        closest_time,
        format_value(options.detection.determinant_threshold),
        outcome.threshold,
        format_value(options.detection.joint_step_threshold),
        options.region_plan,
        options.tracking.feedback,
    );
    Ok(Study {
        base: args.base,
        through,
        direction,
        heading,
        outcome,
        plant,
    })
}

/// `--k`: integers >= 1.
fn parse_ks(text: &str) -> CliResult<Vec<usize>> {
    parse_numbers(text, "--k")?
        .into_iter()
        .enumerate()
        .map(|(i, k)| {
            if k.fract() == 0.0 && (1.0..=MAX_PERIODS as f64).contains(&k) {
                Ok(k as usize)
            } else {
                Err(CliError(format!(
                    "--k: value {}: k must be an integer in 1..={MAX_PERIODS} (IK every k-th planned \
                     pose of the singular region), got {}",
                    i + 1,
                    brief(k)
                )))
            }
        })
        .collect()
}
