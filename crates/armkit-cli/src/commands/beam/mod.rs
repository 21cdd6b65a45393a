//! `armkit beam`: seed 000's flexible gantry beam (sec 3.1).
//!
//! * `armkit beam table1 [--json]`: Table 1 (two equal loads on the 10 m
//!   beam): load positions, the paper's deflection under the loads, ours,
//!   ours at mid-span and the relative error. Exit code 3 when a case does
//!   not round to the printed digits (as with `--gravity 9.81`: the paper
//!   used 10).
//! * `armkit beam error-along-beam --out DIR`: the end-effector position
//!   error that ignoring the deflection causes as gantry9's carriage travels
//!   its range `d2` in [0, 5] m (the rest of the arm fixed): `DIR/error_along_beam.csv`
//!   and `DIR/error_along_beam.svg`.

use std::path::PathBuf;

use armkit::beam::{
    CarriageDeflection, GantryBeam, SimplySupportedBeam, SEED000_CARRIAGE_MASS, SEED000_GRAVITY,
};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::robots;
use armkit::study::{BeamTableStudy, Table1Row};
use clap::{Args, Subcommand};

use crate::common::{clean_zero, print_json, CliResult, Outcome};
use crate::report::{write_atomic, Animation, Check, Report, Table};

mod sweep;

pub use sweep::error_along_beam_figure;
use sweep::{error_along_beam, error_along_beam_csv, worst_sample, ErrorSample};

/// Seed 000's flexible gantry beam: Table 1 and the error of a rigid model.
#[derive(Args, Debug)]
pub struct BeamArgs {
    #[command(subcommand)]
    pub command: BeamCommand,
}

/// `armkit beam` subcommands.
#[derive(Subcommand, Debug)]
pub enum BeamCommand {
    /// Seed 000's Table 1: deflection under two equal loads, paper vs ours.
    Table1(Table1Args),
    /// End-effector error caused by ignoring the deflection along the beam (CSV + SVG).
    ErrorAlongBeam(ErrorAlongBeamArgs),
}

/// The load shared by both subcommands: mass per carriage and gravity.
#[derive(Args, Debug, Clone, Copy)]
pub struct LoadArgs {
    /// Mass hanging from each carriage, kg (seed 000: 400).
    #[arg(long, default_value_t = SEED000_CARRIAGE_MASS, value_name = "KG")]
    pub mass: f64,
    /// Gravitational acceleration, m/s^2 (10 reproduces Table 1; 9.80665 is standard).
    #[arg(long, default_value_t = SEED000_GRAVITY, value_name = "M/S^2")]
    pub gravity: f64,
}

/// The options of the beam study (`[beam]` in a scenario file).
#[derive(Args, Debug)]
pub struct BeamStudyArgs {
    #[command(flatten)]
    pub load: LoadArgs,
    /// Number of carriage positions in the rigid-model error sweep (2..=100000).
    #[arg(long, default_value_t = 51)]
    pub samples: usize,
}

/// `armkit beam table1`.
#[derive(Args, Debug)]
pub struct Table1Args {
    #[command(flatten)]
    pub load: LoadArgs,
    /// Print a JSON list of cases (`paper` and `computed` in metres).
    #[arg(long)]
    pub json: bool,
}

/// `armkit beam error-along-beam`.
#[derive(Args, Debug)]
pub struct ErrorAlongBeamArgs {
    /// Directory for error_along_beam.csv and error_along_beam.svg (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    #[command(flatten)]
    pub load: LoadArgs,
    /// Number of carriage positions over d2's range (2..=100000).
    #[arg(long, default_value_t = 51)]
    pub samples: usize,
    /// gantry9 joint positions (9 values; d2 is swept). Default: mid-range.
    #[arg(long, value_name = "Q1,...,Q9", allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `armkit beam`.
pub fn run(args: &BeamArgs) -> CliResult<Outcome> {
    match &args.command {
        BeamCommand::Table1(args) => run_table1(args),
        BeamCommand::ErrorAlongBeam(args) => run_error_along_beam(args),
    }
}

/// The library's Table 1 study for the load flags.
fn table1_study(load: LoadArgs) -> BeamTableStudy {
    BeamTableStudy {
        mass: load.mass,
        gravity: load.gravity,
    }
}

/// Table 1's rows from the library's study for the load flags.
fn table1_rows(load: LoadArgs) -> CliResult<Vec<Table1Row>> {
    Ok(table1_study(load).rows()?)
}

fn run_table1(args: &Table1Args) -> CliResult<Outcome> {
    let rows = table1_rows(args.load)?;
    if args.json {
        let list: Vec<_> = rows
            .iter()
            .map(|r| {
                serde_json::json!({
                    "case": r.label,
                    "loads_m": r.positions,
                    "paper": r.paper,
                    "computed": r.under_each[0],
                    "computed_under_each": r.under_each,
                    "midspan": r.midspan,
                    "largest": r.largest,
                    "largest_at_m": r.largest_at,
                    "paper_simulation": r.simulation,
                    "relative_error": r.relative_error(),
                    "rounds_to_printed": r.rounds_to_printed(),
                    "mass_kg": args.load.mass,
                    "gravity": args.load.gravity,
                })
            })
            .collect();
        print_json(&serde_json::Value::Array(list))?;
    } else {
        print!("{}", table1_text(&rows, args.load));
    }
    Ok(if rows.iter().all(Table1Row::rounds_to_printed) {
        Outcome::Success
    } else {
        Outcome::NotConverged
    })
}

fn table1_text(rows: &[Table1Row], load: LoadArgs) -> String {
    let mut out = format!(
        "Seed 000, Table 1: deflection under the loads (E = 200 GPa, L = 10 m, square 0.2 m,\n\
         two loads of {} kg, g = {} m/s^2), downward, m\n\n",
        load.mass, load.gravity
    );
    out += &format!(
        "{:<14} {:<12} {:>9} {:>10} {:>10} {:>9}\n",
        "case", "loads (m)", "paper", "ours", "mid-span", "error"
    );
    for r in rows {
        out += &format!(
            "{:<14} {:<12} {:>9.4} {:>10.6} {:>10.6} {:>8.2}%\n",
            r.label,
            format!("{}, {}", r.positions[0], r.positions[1]),
            r.paper,
            r.under_each[0],
            r.midspan,
            100.0 * clean_zero(r.relative_error())
        );
    }
    let verdict = if rows.iter().all(Table1Row::rounds_to_printed) {
        "every case rounds to the printed digits"
    } else {
        "NOT every case rounds to the printed digits"
    };
    let largest = rows
        .iter()
        .map(|r| format!("{:.3} m", r.largest_at))
        .collect::<Vec<_>>()
        .join(", ");
    let where_ = if rows.iter().all(|r| (r.largest_at - 5.0).abs() < 1e-9) {
        "mid-span, not under the loads as the paper's Fig 5 text says"
    } else {
        "not at mid-span"
    };
    out + &format!("\n{verdict}\nlargest deflection along the span at {largest}: {where_}\n")
}

fn run_error_along_beam(args: &ErrorAlongBeamArgs) -> CliResult<Outcome> {
    let samples = error_along_beam(args.load, args.samples, args.q.as_deref())?;
    std::fs::create_dir_all(&args.out)?;
    let csv_path = args.out.join("error_along_beam.csv");
    let svg_path = args.out.join("error_along_beam.svg");
    let figure = error_along_beam_figure(&samples);
    write_atomic(&csv_path, error_along_beam_csv(&samples).as_bytes())?;
    write_atomic(&svg_path, figure.to_svg(800, 500)?.as_bytes())?;
    let worst = worst_sample(&samples)?;
    if args.json {
        print_json(&serde_json::json!({
            "csv": csv_path.display().to_string(),
            "svg": svg_path.display().to_string(),
            "samples": samples.len(),
            "max_error_m": worst.error.norm(),
            "max_error_at_d2_m": worst.d2,
            "mass_kg": args.load.mass,
            "gravity": args.load.gravity,
        }))?;
    } else {
        println!(
            "largest end-effector error {:.4} mm at d2 = {} m ({} kg, g = {} m/s^2)\nwrote {}\nwrote {}",
            1e3 * worst.error.norm(),
            worst.d2,
            args.load.mass,
            args.load.gravity,
            csv_path.display(),
            svg_path.display()
        );
    }
    Ok(Outcome::Success)
}

/// The beam study of a scenario file: [`report`] with its options.
pub fn study_report(args: &BeamStudyArgs) -> CliResult<Report> {
    report(args.load, args.samples)
}

/// Seed 000's beam as a report: Table 1 (paper vs ours: each case rounds
/// to the printed digits; the largest deflection at mid-span; the paper's
/// claims as findings), and the error a rigid model makes along the beam.
pub fn report(load: LoadArgs, samples: usize) -> CliResult<Report> {
    let study = table1_study(load).run()?;
    let rows = table1_rows(load)?;
    let mut table = Table::new(
        format!(
            "Table 1: deflection under the loads, {} kg each, g = {} m/s^2",
            load.mass, load.gravity
        ),
        &[
            "case",
            "loads (m)",
            "paper (m)",
            "ours (m)",
            "mid-span (m)",
            "largest (m), at",
            "error",
        ],
    );
    let mut checks = study.checks;
    for r in &rows {
        table.push(vec![
            r.label.to_string(),
            format!("{}, {}", r.positions[0], r.positions[1]),
            format!("{}", r.paper),
            format!("{:.6}", r.under_each[0]),
            format!("{:.6}", r.midspan),
            format!("{:.6}, {:.3} m", r.largest, r.largest_at),
            format!("{:.2} %", 100.0 * clean_zero(r.relative_error())),
        ]);
    }
    let along = error_along_beam(load, samples, None)?;
    let worst = worst_sample(&along)?;
    let carriage =
        CarriageDeflection::from_mass(SimplySupportedBeam::seed000(), load.mass, load.gravity)?;
    let flex = robots::gantry9_with_beam(&GantryBeam::Flexible(carriage))?;
    let coupled_jacobian_error = coupled_jacobian_error(&flex)?;
    checks.push(Check::at_least(
        "largest end-effector error of a rigid model along the beam",
        1e3 * worst.error.norm(),
        1.0,
        "mm",
    ));
    checks.push(Check::at_most(
        "coupled Jacobian J0 M vs central differences of the deflected FK",
        coupled_jacobian_error,
        1e-7,
        "",
    ));
    Ok(Report {
        name: "seed000-beam".into(),
        title: "Seed 000, sec 3.1: the gantry's flexible beam (Table 1)".into(),
        description: "A simply supported 10 m steel beam (E = 200 GPa, square 0.2 m section) carries the arm's carriage. Its deflection w(d2) lowers the vertical joint (d3' = d3 + w(d2), eq 4 corrected) and couples the Jacobian (J = J0 M, eqs 8-10 corrected). Table 1's two-load cases are recomputed from eq 1 by superposition (eqs 2-3 derived; the printed ones are garbled).".into(),
        checks,
        findings: study.findings,
        tables: vec![table],
        figures: vec![("error_along_beam".into(), error_along_beam_figure(&along))],
        notes: vec![
            format!("Table 1 is reproduced with g = {SEED000_GRAVITY} m/s^2 (only g in [9.948, 10.089) rounds to all three printed values); the printed values are the deflection under the loads, not at mid-span, and case a=3.3, b=3.3 means 3.3 m from each end. For these symmetric loads the beam bends most at mid-span, not under the loads as the paper's text on Fig 5 says."),
            "Errata: eq 3 swaps P1 and P2; eq 4 prints d2 - for d3 +; the printed eq 8 misses 2 P d2^3 / (3 E I L).".into(),
            format!("Largest error of a rigid model: {:.3} mm at d2 = {} m, straight down.", 1e3 * worst.error.norm(), worst.d2),
        ],
        animation: Some(carriage_sweep_animation(&flex, carriage, &along)?),
    })
}

/// The flexible gantry at its mid-range configuration while the carriage
/// travels the sweep's positions (one frame per position, 0.1 s apart).
fn carriage_sweep_animation(
    flex: &armkit::Model,
    carriage: CarriageDeflection,
    samples: &[ErrorSample],
) -> CliResult<Animation> {
    let mut q = flex.neutral_configuration();
    let configurations: Vec<Vec<f64>> = samples
        .iter()
        .map(|s| {
            q[1] = s.d2;
            q.clone()
        })
        .collect();
    let times: Vec<f64> = (0..samples.len()).map(|k| 0.1 * k as f64).collect();
    let mut animation = Animation::from_configurations(flex, &times, &configurations)?;
    animation.beam = Some(bent_beam(carriage, &configurations)?);
    Ok(animation)
}

/// The beam's deflection is millimetres on a 10 m span: drawn this many
/// times larger (stated on the page, on a toggle).
const BEAM_MAGNIFICATION: f64 = 200.0;

/// The beam's centre line at each configuration: the carriage joint's
/// origin of the rigid gantry at 41 positions along the span (the straight
/// beam), lowered along the vertical joint's axis by the deflection there
/// under the carriage's load at its position (seed 000 eq 1; the arm hangs
/// at the deflection under the load, `d3' = d3 + w(d2)`).
fn bent_beam(
    carriage: CarriageDeflection,
    configurations: &[Vec<f64>],
) -> CliResult<armkit_view::BeamLine> {
    let rigid = robots::gantry9()?;
    let mut data = Data::new(&rigid);
    let length = carriage.beam.length();
    let mut samples = Vec::new();
    let mut straight = Vec::new();
    for q in configurations {
        let load = armkit::beam::PointLoad::new(q[1], carriage.force);
        let (mut bent, mut line) = (Vec::new(), Vec::new());
        for i in 0..=40 {
            let x = length * i as f64 / 40.0;
            let mut at = q.clone();
            at[1] = x;
            forward_kinematics(&rigid, &mut data, &at)?;
            let frames = data.joint_frames();
            let origin = frames[1].translation;
            let down = frames[2].rotation.column(2).into_owned();
            let p = origin + down * carriage.beam.deflection_due_to(x, load)?;
            line.push([origin.x, origin.y, origin.z]);
            bent.push([p.x, p.y, p.z]);
        }
        samples.push(bent);
        straight.push(line);
    }
    Ok(armkit_view::BeamLine {
        magnification: BEAM_MAGNIFICATION,
        samples,
        straight,
    })
}

/// Largest entry of |J0 M - J_fd| over a few configurations of the flexible gantry.
fn coupled_jacobian_error(flex: &armkit::Model) -> CliResult<f64> {
    let mut data = Data::new(flex);
    let mut worst: f64 = 0.0;
    for k in 0..5 {
        let mut q = flex.neutral_configuration();
        q[1] = 0.5 + 0.9 * k as f64;
        let analytic = armkit::jacobian(flex, &mut data, &q, armkit::JacobianFrame::World)?.clone();
        let h = 1e-6;
        for j in 0..flex.dof() {
            let (mut plus, mut minus) = (q.clone(), q.clone());
            plus[j] += h;
            minus[j] -= h;
            let p = forward_kinematics(flex, &mut data, &plus)?.translation;
            let m = forward_kinematics(flex, &mut data, &minus)?.translation;
            let column = (p - m) / (2.0 * h);
            for r in 0..3 {
                worst = worst.max((analytic[(r, j)] - column[r]).abs());
            }
        }
    }
    Ok(worst)
}
