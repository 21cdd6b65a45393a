//! `armkit redundancy`: one Cartesian motion distributed four ways among a
//! redundant robot's joints (seeds 000 and 001): minimum norm, energy-optimal
//! for a payload, joint priorities, and with joints locked so that six remain
//! (the paper's baseline; on gantry9 also the rail and beam alone, a labelled
//! extra). Prints seed 001's energy measure F (eq 9, integrated over the
//! motion) under the load's static torques and, for robots with masses, under
//! the full dynamics, and each joint's travel; writes the samples and the
//! summary as CSV and SVG plots.

use std::path::PathBuf;

use armkit::redundancy::TorqueModel;
use armkit::study::{DistributionOutcome, DistributionStudy, FormulationKind, SecondaryKind};
use armkit::Model;
use clap::{Args, ValueEnum};

use crate::common::{
    parse_fixed_numbers, parse_joint_positions, parse_numbers, print_json, CliError, CliResult,
    LimitPolicy, Outcome, RobotArgs,
};
use crate::report::join;

mod output;

pub use output::report;
use output::{summary_table, write_outputs};

/// Distribute one straight-line motion four ways (minimum norm, energy-optimal,
/// priorities, locked joints) and compare seed 001's energy measure.
#[derive(Args, Debug)]
pub struct RedundancyArgs {
    /// The robot (default: the built-in gantry9).
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Start joint positions, comma-separated (rad or m). Default: gantry9
    /// 3,2.5,1,0.3,0.4,-0.5,0.2,0.8,0.1; other robots: mid-range.
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub q0: Option<String>,
    /// End-effector displacement in the world frame, m. Default: gantry9
    /// 0.4,0.3,-0.3; other robots 0.1,0.1,-0.1.
    #[arg(long = "move", value_name = "DX,DY,DZ", allow_hyphen_values = true)]
    pub displacement: Option<String>,
    /// End-effector rotation (world-frame rotation vector, rad) over the motion.
    #[arg(
        long,
        value_name = "RX,RY,RZ",
        default_value = "0,0,0",
        allow_hyphen_values = true
    )]
    pub rotate: String,
    /// Duration of the motion, s (quintic timing: starts and ends at rest).
    #[arg(long, default_value_t = 4.0)]
    pub duration: f64,
    /// Durations of the sweep, s, comma-separated, or `none`: the
    /// energy-optimal run and the baseline repeated at each (F under static
    /// and dynamic torques, the crossover, the moderate speed). Default: the
    /// duration times 0.5, 0.75, 1, 1.5, 2, 3, 4. Robots with masses only.
    #[arg(long, value_name = "T1,T2,...")]
    pub durations: Option<String>,
    /// Payload weight held at the end effector, N (seed 001's load).
    #[arg(long, default_value_t = 50.0)]
    pub payload: f64,
    /// Ignore the links' own weight (by default it counts when the robot has
    /// mass properties).
    #[arg(long)]
    pub no_gravity: bool,
    /// Priority weights, one per joint (large = low priority). Default:
    /// seed 000's 100,10,10,1,1,1,1,1,1 for 9 joints; 10 for prismatic and 1
    /// for rotational joints otherwise.
    #[arg(long, value_name = "W1,W2,...")]
    pub priorities: Option<String>,
    /// Joints to lock, 1-based, comma-separated. Default: seed 001's
    /// baseline, the first n - 6 joints so that six remain (1,2,3, the
    /// gantry's axes, on gantry9). gantry9 also runs `locked-variant`, the
    /// rail and beam (1,2) alone locked, as a labelled extra.
    #[arg(long, value_name = "J1,J2,...")]
    pub lock: Option<String>,
    /// Zero-torque floor of the energy weights, as a fraction of the largest
    /// torque: a_i = max(|tau_i|, f max|tau|)^2.
    #[arg(long, default_value_t = 0.05)]
    pub torque_floor: f64,
    /// Control period, s.
    #[arg(long, default_value_t = 0.01)]
    pub dt: f64,
    /// Position feedback gain, 1/s.
    #[arg(long, default_value_t = 10.0)]
    pub gain: f64,
    /// Constant damping lambda of the weighted least norm (default: exact).
    #[arg(long)]
    pub damping: Option<f64>,
    /// Null-space objective, in the same weighted metric.
    #[arg(long, value_enum, default_value_t = SecondaryArg::None)]
    pub secondary: SecondaryArg,
    /// Gain of the null-space objective.
    #[arg(long, default_value_t = 1.0)]
    pub secondary_gain: f64,
    /// Solver: weighted least norm, or seed 001's partitioned form
    /// (best-conditioned partition at every step).
    #[arg(long, value_enum, default_value_t = FormulationArg::LeastNorm)]
    pub formulation: FormulationArg,
    /// Output directory for CSV and SVG files (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out/redundancy")]
    pub out: PathBuf,
    /// Print the summary as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// `--secondary` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SecondaryArg {
    /// None.
    None,
    /// Joint-limit avoidance (Liegeois).
    JointLimits,
    /// Manipulability ascent.
    Manipulability,
}

/// `--formulation` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum FormulationArg {
    /// Weighted least norm.
    LeastNorm,
    /// Seed 001's partition into 6 generalized and k extra joints.
    Partitioned,
}

/// One motion distributed four ways (the library's [`DistributionStudy`]),
/// with everything the outputs need.
pub struct Study {
    model: Model,
    rotation: Vec<f64>,
    heading: String,
    outcome: DistributionOutcome,
}

/// Runs `armkit redundancy`.
pub fn run(args: &RedundancyArgs) -> CliResult<Outcome> {
    let study = study(args)?;
    let results = &study.outcome.results;
    let energies = &study.outcome.torque_energies;
    let files = write_outputs(&args.out, &study.model, results, energies)?;
    let (model, rotation, heading) = (&study.model, &study.rotation, &study.heading);
    let settings = &study.outcome.settings;
    let (q0, displacement, gravity) = (&settings.start, &settings.displacement, settings.gravity);
    let (priorities, locked) = (&settings.priorities, &settings.locked);
    let lowest = study.outcome.lowest();
    let dynamic = |name: &str| {
        study
            .outcome
            .torque_energies
            .iter()
            .find(|e| e.name == name)
            .map(|e| e.dynamic_energy)
    };
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.name(),
            "q0": q0,
            "move": displacement,
            "rotate": rotation,
            "duration": args.duration,
            "payload": args.payload,
            "gravity": gravity,
            "priorities": priorities.values(),
            "locked": locked.iter().map(|j| j + 1).collect::<Vec<_>>(),
            "locked_variant": settings.variant_locked.iter().map(|j| j + 1).collect::<Vec<_>>(),
            "lowest_energy": lowest,
            "lowest_energy_dynamic": study.outcome.ranking(TorqueModel::Dynamic).first().map(|(n, _)| n.clone()),
            "distributions": results.iter().map(|r| serde_json::json!({
                "name": r.name,
                "status": r.report.status.to_string(),
                "energy": r.summary.energy,
                "energy_dynamic": dynamic(&r.name),
                "travel": r.summary.travel,
                "max_position_error": r.report.max_position_error,
                "final_position_error": r.report.final_position_error,
                "final_orientation_error": r.report.final_orientation_error,
                "velocity_scaled_steps": r.report.velocity_scaled_steps,
                "limit_locked_steps": r.report.limit_locked_steps,
            })).collect::<Vec<_>>(),
            "sweep": study.outcome.sweep.as_ref().map(|sweep| serde_json::json!({
                "crossover_s": sweep.crossover(),
                "moderate_s": sweep.moderate().map(|p| p.duration),
                "points": sweep.points.iter().map(|p| serde_json::json!({
                    "duration": p.duration,
                    "energy_optimal_static": p.optimal_static,
                    "baseline_static": p.baseline_static,
                    "energy_optimal_dynamic": p.optimal_dynamic,
                    "baseline_dynamic": p.baseline_dynamic,
                    "margin_dynamic_percent": p.margin(TorqueModel::Dynamic),
                })).collect::<Vec<_>>(),
            })),
            "files": files,
        }))?;
    } else {
        println!("{heading}");
        println!(
            "priorities {}; locked joints {}",
            join(priorities.values(), 0),
            locked
                .iter()
                .map(|j| (j + 1).to_string())
                .collect::<Vec<_>>()
                .join(",")
        );
        print!("{}", summary_table(model, results, energies));
        println!("lowest F (seed 001, eq 9): {lowest}");
        for torque_model in [TorqueModel::Static, TorqueModel::Dynamic] {
            if let Some(winner) = study.outcome.winner(torque_model) {
                println!("{torque_model} torques: {winner}");
            }
        }
        if lowest != "energy-optimal" {
            println!(
                "note: the energy-optimal distribution minimises F at each instant for the \
                 commanded twist; over a whole motion the paths in joint space differ, and \
                 velocity scaling or joint limits change the timing"
            );
        }
        println!("wrote {}", files.join(", "));
    }
    Ok(if study.outcome.all_completed() {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

/// Plans the four distributions the arguments describe: the flags parsed
/// (with the command's messages), then the library's study.
pub fn study(args: &RedundancyArgs) -> CliResult<Study> {
    let model = load_robot(&args.robot)?;
    let dof = model.dof();
    if dof <= 6 {
        return Err(CliError(format!(
            "{}: {dof} joints; redundancy needs more than 6",
            model.name()
        )));
    }
    let three = |text: &str, option: &str| -> CliResult<[f64; 3]> {
        let v = parse_fixed_numbers(text, option, 3)?;
        Ok([v[0], v[1], v[2]])
    };
    let library = DistributionStudy {
        start: match &args.q0 {
            Some(text) => Some(parse_joint_positions(text, &model, LimitPolicy::Enforce)?),
            None => None,
        },
        displacement: match &args.displacement {
            Some(text) => Some(three(text, "--move")?),
            None => None,
        },
        rotation: three(&args.rotate, "--rotate")?,
        duration: args.duration,
        durations: match args.durations.as_deref().map(str::trim) {
            Some(text) if text.eq_ignore_ascii_case("none") => Some(Vec::new()),
            Some(text) => Some(parse_durations(text)?),
            None => None,
        },
        payload: args.payload,
        link_weights: !args.no_gravity,
        priorities: match &args.priorities {
            Some(text) => Some(parse_fixed_numbers(text, "--priorities", dof)?),
            None => None,
        },
        locked: match &args.lock {
            Some(text) => Some(parse_joint_list(text, dof)?),
            None => None,
        },
        // The labelled extra: the robot's default (gantry9: rail and beam).
        variant_locked: None,
        torque_floor: args.torque_floor,
        dt: args.dt,
        gain: args.gain,
        damping: args.damping,
        secondary: match args.secondary {
            SecondaryArg::None => SecondaryKind::None,
            SecondaryArg::JointLimits => SecondaryKind::JointLimits,
            SecondaryArg::Manipulability => SecondaryKind::Manipulability,
        },
        secondary_gain: args.secondary_gain,
        formulation: match args.formulation {
            FormulationArg::LeastNorm => FormulationKind::LeastNorm,
            FormulationArg::Partitioned => FormulationKind::Partitioned,
        },
    };
    let outcome = library.compare(&model)?;
    let settings = &outcome.settings;
    let heading = format!(
        "{}: move ({}) m, rotate ({}) rad in {} s; load: {} N payload{}; dt {} s, gain {} 1/s",
        model.name(),
        join(&settings.displacement, 3),
        join(&library.rotation, 3),
        args.duration,
        args.payload,
        if settings.gravity {
            " + link weights (g = 9.81 m/s^2)"
        } else if model.has_inertias() {
            " (link weights ignored)"
        } else {
            " (no link masses in this model)"
        },
        args.dt,
        args.gain
    );
    Ok(Study {
        model,
        rotation: library.rotation.to_vec(),
        heading,
        outcome,
    })
}

/// The selected robot, gantry9 when none is given.
fn load_robot(robot: &RobotArgs) -> CliResult<Model> {
    if robot.robot.is_none() && robot.robot_file.is_none() && robot.urdf.is_none() {
        return Ok(armkit::robots::by_name("gantry9")?);
    }
    robot.load()
}

/// Parses `--durations`: positive durations, s.
fn parse_durations(text: &str) -> CliResult<Vec<f64>> {
    let durations = parse_numbers(text, "--durations")?;
    // parse_numbers has refused NaN and infinities.
    match durations.iter().find(|&&d| d <= 0.0) {
        Some(bad) => Err(CliError(format!(
            "--durations: every duration must be > 0 s, got {bad}"
        ))),
        None => Ok(durations),
    }
}

/// Parses 1-based joint numbers into 0-based indices.
fn parse_joint_list(text: &str, dof: usize) -> CliResult<Vec<usize>> {
    if text.trim().eq_ignore_ascii_case("none") {
        return Ok(Vec::new());
    }
    let locked = parse_numbers(text, "--lock")?
        .into_iter()
        .map(|v| {
            if v.fract() == 0.0 && v >= 1.0 && v <= dof as f64 {
                Ok(v as usize - 1)
            } else {
                Err(CliError(format!(
                    "--lock: joint {v} is not a joint number in 1..={dof}"
                )))
            }
        })
        .collect::<CliResult<Vec<usize>>>()?;
    // The move is a 6-D pose change: fewer than six free joints cannot
    // follow it, and a run of them would only stop at its first step.
    let mut distinct = locked.clone();
    distinct.sort_unstable();
    distinct.dedup();
    let free = dof - distinct.len();
    if free < 6 {
        return Err(CliError(format!(
            "--lock: leaves {free} of {dof} joints free; the pose move needs at least 6"
        )));
    }
    Ok(locked)
}
