//! `armkit redundancy`: one Cartesian motion distributed four ways among a
//! redundant robot's joints (seeds 000 and 001): minimum norm, energy-optimal
//! for a payload, joint priorities, and with joints locked. Prints seed 001's
//! energy measure F (eq 9, integrated over the motion) and each joint's
//! travel; writes the samples and the summary as CSV and SVG plots.

use std::path::{Path, PathBuf};

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Pose, Vector3};
use armkit::redundancy::{
    compare_distributions, ComparisonCase, ComparisonResult, Damping, DistributionOptions,
    Formulation, JointWeights, Load, SecondaryObjective, TorqueFloor, SEED000_PRIORITY_WEIGHTS,
};
use armkit::tracking::{TrackingOptions, TrackingStatus};
use armkit::trajectory::{CartesianTrajectory, TimeLaw};
use armkit::Model;
use clap::{Args, ValueEnum};

use crate::common::{
    parse_fixed_numbers, parse_joint_positions, parse_numbers, print_json, CliError, CliResult,
    LimitPolicy, Outcome, RobotArgs,
};
use crate::plot::Figure;
use crate::report::{Animation, Check, Report, Table};

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
    /// Joints to lock, 1-based, comma-separated. Default: 1,2 (the gantry's
    /// rail and beam axes) for 9 joints, 1 otherwise.
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

const GANTRY_START: [f64; 9] = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];

/// One motion distributed four ways, with everything the outputs need.
pub struct Study {
    model: Model,
    q0: Vec<f64>,
    displacement: Vec<f64>,
    rotation: Vec<f64>,
    gravity: bool,
    priorities: JointWeights,
    locked: Vec<usize>,
    heading: String,
    results: Vec<ComparisonResult>,
}

impl Study {
    /// Name of the distribution with the lowest energy measure F.
    fn lowest(&self) -> String {
        self.results
            .iter()
            .min_by(|a, b| a.summary.energy.total_cmp(&b.summary.energy))
            .map(|r| r.name.clone())
            .unwrap_or_default()
    }

    fn all_completed(&self) -> bool {
        self.results
            .iter()
            .all(|r| r.report.status == TrackingStatus::Completed)
    }
}

/// Runs `armkit redundancy`.
pub fn run(args: &RedundancyArgs) -> CliResult<Outcome> {
    let study = study(args)?;
    let files = write_outputs(&args.out, &study.model, &study.results)?;
    let Study {
        model,
        q0,
        displacement,
        rotation,
        gravity,
        priorities,
        locked,
        heading,
        results,
    } = &study;
    let lowest = study.lowest();
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
            "lowest_energy": lowest,
            "distributions": results.iter().map(|r| serde_json::json!({
                "name": r.name,
                "status": r.report.status.to_string(),
                "energy": r.summary.energy,
                "travel": r.summary.travel,
                "max_position_error": r.report.max_position_error,
                "final_position_error": r.report.final_position_error,
                "final_orientation_error": r.report.final_orientation_error,
                "velocity_scaled_steps": r.report.velocity_scaled_steps,
                "limit_locked_steps": r.report.limit_locked_steps,
            })).collect::<Vec<_>>(),
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
        print!("{}", summary_table(model, results));
        println!("lowest F (seed 001, eq 9): {lowest}");
        if lowest != "energy-optimal" {
            println!(
                "note: the energy-optimal distribution minimises F at each instant for the \
                 commanded twist; over a whole motion the paths in joint space differ, and \
                 velocity scaling or joint limits change the timing"
            );
        }
        println!("wrote {}", files.join(", "));
    }
    Ok(if study.all_completed() {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

/// Plans the four distributions the arguments describe.
pub fn study(args: &RedundancyArgs) -> CliResult<Study> {
    let model = load_robot(&args.robot)?;
    let dof = model.dof();
    if dof <= 6 {
        return Err(CliError(format!(
            "{}: {dof} joints; redundancy needs more than 6",
            model.name()
        )));
    }
    let gantry = dof == 9 && model.name().starts_with("gantry9");
    let q0 = match &args.q0 {
        Some(text) => parse_joint_positions(text, &model, LimitPolicy::Enforce)?,
        None if gantry => GANTRY_START.to_vec(),
        None => model.neutral_configuration(),
    };
    let displacement = match &args.displacement {
        Some(text) => parse_fixed_numbers(text, "--move", 3)?,
        None if gantry => vec![0.4, 0.3, -0.3],
        None => vec![0.1, 0.1, -0.1],
    };
    let rotation = parse_fixed_numbers(&args.rotate, "--rotate", 3)?;
    let priorities = match &args.priorities {
        Some(text) => JointWeights::new(&parse_fixed_numbers(text, "--priorities", dof)?)?,
        None if dof == 9 => JointWeights::new(&SEED000_PRIORITY_WEIGHTS)?,
        None => JointWeights::new(
            &model
                .joints()
                .iter()
                .map(|j| if j.kind.is_rotational() { 1.0 } else { 10.0 })
                .collect::<Vec<_>>(),
        )?,
    };
    let locked = match &args.lock {
        Some(text) => parse_joint_list(text, dof)?,
        None if dof == 9 => vec![0, 1],
        None => vec![0],
    };
    let gravity = !args.no_gravity && model.has_inertias();
    let mut load = Load::payload(args.payload);
    if gravity {
        load = load.with_standard_gravity();
    }
    let options = DistributionOptions {
        tracking: TrackingOptions::proportional(args.dt, args.gain),
        damping: args.damping.map_or(Damping::None, Damping::Constant),
        secondary: match args.secondary {
            SecondaryArg::None => SecondaryObjective::None,
            SecondaryArg::JointLimits => SecondaryObjective::JointLimits {
                gain: args.secondary_gain,
            },
            SecondaryArg::Manipulability => SecondaryObjective::Manipulability {
                gain: args.secondary_gain,
                step: 1e-6,
            },
        },
        formulation: match args.formulation {
            FormulationArg::LeastNorm => Formulation::WeightedLeastNorm,
            FormulationArg::Partitioned => Formulation::Partitioned(None),
        },
    };
    let mut data = Data::new(&model);
    let start = *forward_kinematics(&model, &mut data, &q0)?;
    let turn = armkit::math::Rotation3::from_scaled_axis(Vector3::from_column_slice(&rotation));
    let goal = Pose::new(
        turn.into_inner() * start.rotation,
        start.translation + Vector3::from_column_slice(&displacement),
    );
    let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, args.duration)?;
    let cases = ComparisonCase::four_way(
        dof,
        load,
        TorqueFloor::Relative(args.torque_floor),
        priorities.clone(),
        &locked,
    )?;
    let results = compare_distributions(&model, &q0, &path, &load, &cases, &options)?;
    let heading = format!(
        "{}: move ({}) m, rotate ({}) rad in {} s; load: {} N payload{}; dt {} s, gain {} 1/s",
        model.name(),
        join(&displacement, 3),
        join(&rotation, 3),
        args.duration,
        args.payload,
        if gravity {
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
        q0,
        displacement,
        rotation,
        gravity,
        priorities,
        locked,
        heading,
        results,
    })
}

/// The selected robot, gantry9 when none is given.
fn load_robot(robot: &RobotArgs) -> CliResult<Model> {
    if robot.robot.is_none() && robot.robot_file.is_none() && robot.urdf.is_none() {
        return Ok(armkit::robots::by_name("gantry9")?);
    }
    robot.load()
}

/// Parses 1-based joint numbers into 0-based indices.
fn parse_joint_list(text: &str, dof: usize) -> CliResult<Vec<usize>> {
    if text.trim().eq_ignore_ascii_case("none") {
        return Ok(Vec::new());
    }
    parse_numbers(text, "--lock")?
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
        .collect()
}

fn join(values: &[f64], decimals: usize) -> String {
    values
        .iter()
        .map(|v| format!("{v:.decimals$}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The text table: one row per distribution.
fn summary_table(model: &Model, results: &[ComparisonResult]) -> String {
    let mut out = format!(
        "{:<15} {:>12} {:>10}",
        "distribution", "F (W^2 s)", "max err"
    );
    for joint in model.joints() {
        let unit = if joint.kind.is_rotational() {
            "rad"
        } else {
            "m"
        };
        out += &format!(" {:>9}", format!("{} {unit}", joint.name));
    }
    out += "  status\n";
    for r in results {
        out += &format!(
            "{:<15} {:>12.4e} {:>10.2e}",
            r.name, r.summary.energy, r.report.max_position_error
        );
        for t in &r.summary.travel {
            out += &format!(" {t:>9.4}");
        }
        out += &format!("  {}\n", r.report.status);
    }
    out
}

/// Writes summary.csv, samples.csv and the SVG plots into `dir`; returns
/// the paths written.
fn write_outputs(
    dir: &Path,
    model: &Model,
    results: &[ComparisonResult],
) -> CliResult<Vec<String>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError(format!("{}: cannot create: {e}", dir.display())))?;
    let names: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
    let mut written = Vec::new();
    let mut write = |name: &str, text: &str| -> CliResult {
        let path = dir.join(name);
        std::fs::write(&path, text)
            .map_err(|e| CliError(format!("{}: cannot write: {e}", path.display())))?;
        written.push(path.display().to_string());
        Ok(())
    };

    let mut summary = format!(
        "distribution,status,energy_W2s,max_position_error_m,final_position_error_m,\
         final_orientation_error_rad,velocity_scaled_steps,limit_locked_steps,{}\n",
        names
            .iter()
            .map(|n| format!("travel_{n}"))
            .collect::<Vec<_>>()
            .join(",")
    );
    for r in results {
        summary += &format!(
            "{},{},{},{},{},{},{},{},{}\n",
            r.name,
            r.report.status.to_string().replace(',', ";"),
            r.summary.energy,
            r.report.max_position_error,
            r.report.final_position_error,
            r.report.final_orientation_error,
            r.report.velocity_scaled_steps,
            r.report.limit_locked_steps,
            cells(&r.summary.travel)
        );
    }
    write("summary.csv", &summary)?;

    let mut samples = format!(
        "distribution,time_s,{},{},energy_rate_W2,position_error_m,orientation_error_rad,velocity_scale\n",
        names.join(","),
        names
            .iter()
            .map(|n| format!("{n}_dot"))
            .collect::<Vec<_>>()
            .join(",")
    );
    for r in results {
        for (sample, f) in r.report.samples.iter().zip(&r.summary.measure) {
            samples += &format!(
                "{},{},{},{},{},{},{},{}\n",
                r.name,
                sample.time,
                cells(&sample.q),
                cells(&sample.joint_rates),
                f,
                sample.position_error,
                sample.orientation_error,
                sample.velocity_scale
            );
        }
    }
    write("samples.csv", &samples)?;

    let figures = figures(model, results);
    for (name, figure) in &figures {
        let svg = figure
            .to_svg(800, 450)
            .map_err(|e| CliError(format!("{name}.svg: plot: {e}")))?;
        write(&format!("{name}.svg"), &svg)?;
    }
    Ok(written)
}

fn cells(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// The plots: F(t), its integral, each joint's travel, and each
/// distribution's joint motion.
fn figures(model: &Model, results: &[ComparisonResult]) -> Vec<(String, Figure)> {
    let names: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
    // Plots: F(t) and its integral for each distribution on one time axis
    // (the runs share the time grid unless one stopped early).
    let longest = results
        .iter()
        .max_by_key(|r| r.report.samples.len())
        .map(|r| {
            r.report
                .samples
                .iter()
                .map(|s| s.time)
                .collect::<Vec<f64>>()
        })
        .unwrap_or_default();
    let mut rate = Figure::new(
        "Seed 001 energy measure F = sum (q_dot_i tau_i)^2",
        "t (s)",
        "F (W^2)",
        longest.clone(),
    );
    let mut cumulative = Figure::new(
        "Integral of F over the motion",
        "t (s)",
        "integral F dt (W^2 s)",
        longest,
    );
    let mut travel = Figure::new(
        "Joint travel (m for prismatic, rad for rotational joints)",
        "joint",
        "travel",
        (1..=model.dof()).map(|j| j as f64).collect(),
    );
    for r in results {
        rate = rate.with_series(r.name.clone(), r.summary.measure.clone());
        let mut total = 0.0;
        let mut integral = vec![0.0];
        for (k, f) in r.summary.measure.iter().enumerate() {
            if let Some(next) = r.report.samples.get(k + 1) {
                total += f * (next.time - r.report.samples[k].time);
                integral.push(total);
            }
        }
        cumulative = cumulative.with_series(r.name.clone(), integral);
        travel = travel.with_series(r.name.clone(), r.summary.travel.clone());
    }
    let mut figures = vec![
        ("energy_rate".to_string(), rate),
        ("energy_cumulative".to_string(), cumulative),
        ("travel".to_string(), travel),
    ];
    for r in results {
        let times = r.report.samples.iter().map(|s| s.time).collect();
        let mut joints = Figure::new(
            format!("{}: joint motion q - q0 ({})", r.name, model.name()),
            "t (s)",
            "q - q0 (m or rad)",
            times,
        );
        for (j, name) in names.iter().enumerate() {
            let q0 = r.report.samples.first().map_or(0.0, |s| s.q[j]);
            joints = joints.with_series(
                name.to_string(),
                r.report.samples.iter().map(|s| s.q[j] - q0).collect(),
            );
        }
        figures.push((format!("joints_{}", r.name), joints));
    }
    figures
}

/// The four-way comparison as a report (a scenario's `[redundancy]` table):
/// seed 001's energy measure F per distribution, each joint's travel, the
/// checks that every run tracked the path and that the energy-optimal
/// distribution has the lowest F.
pub fn report(args: &RedundancyArgs) -> CliResult<Report> {
    let study = study(args)?;
    let by_name = |name: &str| study.results.iter().find(|r| r.name == name);
    let energy_optimal =
        by_name("energy-optimal").ok_or_else(|| CliError("no energy-optimal run".into()))?;
    let others_min = study
        .results
        .iter()
        .filter(|r| r.name != "energy-optimal")
        .map(|r| r.summary.energy)
        .fold(f64::INFINITY, f64::min);
    let mut checks = vec![Check::at_most(
        "F of the energy-optimal distribution / lowest F of the others",
        energy_optimal.summary.energy / others_min,
        1.0,
        "",
    )];
    for r in &study.results {
        checks.push(Check::holds(
            format!("{}: the run completes the path", r.name),
            r.report.status == TrackingStatus::Completed,
            r.report.status.to_string(),
        ));
        checks.push(Check::at_most(
            format!("{}: largest tracking error", r.name),
            r.report.max_position_error,
            1e-3,
            "m",
        ));
    }
    let names: Vec<String> = study
        .model
        .joints()
        .iter()
        .map(|j| j.name.clone())
        .collect();
    let mut header: Vec<&str> = vec!["distribution", "F (W^2 s)"];
    header.extend(names.iter().map(String::as_str));
    let mut table = Table::new(
        "Energy measure F (seed 001, eq 9, integrated over the motion) and joint travel (m or rad)",
        &header,
    );
    for r in &study.results {
        let mut row = vec![r.name.clone(), format!("{:.4e}", r.summary.energy)];
        row.extend(r.summary.travel.iter().map(|t| format!("{t:.3}")));
        table.push(row);
    }
    let samples = &energy_optimal.report.samples;
    let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let configurations: Vec<Vec<f64>> = samples.iter().map(|s| s.q.clone()).collect();
    Ok(Report {
        name: "redundancy".into(),
        title: format!("Redundancy resolution on {}", study.model.name()),
        description: format!(
            "{} Distributions: minimum norm (all weights 1, the pseudo-inverse); energy-optimal (seed 001, eq 17 \
             in its weighted least-norm form, weights = squared joint torques for the load, recomputed every step); \
             seed 000's joint priorities; two joints locked. The animation shows the energy-optimal run.",
            study.heading
        ),
        checks,
        tables: vec![table],
        figures: figures(&study.model, &study.results),
        notes: vec![
            "A zero torque would make a joint free of cost: the energy weights are floored at 5 % of the largest \
             torque (a_i = max(|tau_i|, 0.05 max|tau|)^2). Seed 001's eq 17 minimises F at each instant, not over \
             the whole motion. Locking a joint is an infinite weight (the paper says zero)."
                .into(),
        ],
        animation: Some(Animation::from_configurations(&study.model, &times, &configurations)?),
    })
}
