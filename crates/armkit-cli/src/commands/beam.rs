//! `armkit beam`: seed 000's flexible gantry beam (sec 3.1).
//!
//! * `armkit beam table1 [--json]`: Table 1 (two equal loads on the 10 m
//!   beam): load positions, the paper's deflection under the loads, ours and
//!   the relative error. Exit code 3 when a case misses the paper's 4 %
//!   (possible with `--mass` or `--gravity` other than the paper's).
//! * `armkit beam error-along-beam --out DIR`: the end-effector position
//!   error that ignoring the deflection causes as gantry9's carriage travels
//!   its range `d2` in [0, 5] m (the rest of the arm fixed): `DIR/error_along_beam.csv`
//!   and `DIR/error_along_beam.svg`.

use std::path::{Path, PathBuf};

use armkit::beam::{
    CarriageDeflection, GantryBeam, PointLoad, SimplySupportedBeam, TwoCarriageBeam,
    SEED000_CARRIAGE_MASS, SEED000_GRAVITY, SEED000_TABLE1,
};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Vector3;
use armkit::robots;
use clap::{Args, Subcommand};
use plotters::prelude::*;

use crate::common::{
    clean_zero, parse_joint_positions, print_json, CliError, CliResult, LimitPolicy, Outcome,
};

/// The paper's tolerance between its theory and its simulation (Table 1).
const PAPER_TOLERANCE: f64 = 0.04;

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
    /// Number of carriage positions over d2's range (>= 2).
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

/// One computed row of Table 1.
struct Table1Row {
    label: &'static str,
    positions: [f64; 2],
    paper: f64,
    under_each: [f64; 2],
    midspan: f64,
}

impl Table1Row {
    fn relative_error(&self) -> f64 {
        (self.under_each[0] - self.paper) / self.paper
    }

    fn within_tolerance(&self) -> bool {
        self.relative_error().abs() < PAPER_TOLERANCE
    }
}

fn table1_rows(load: LoadArgs) -> CliResult<Vec<Table1Row>> {
    let force = armkit::beam::weight(load.mass, load.gravity)?;
    let gantry = TwoCarriageBeam::new(SimplySupportedBeam::seed000(), [force, force])?;
    SEED000_TABLE1
        .iter()
        .map(|case| {
            let loads = [
                PointLoad::new(case.positions[0], force),
                PointLoad::new(case.positions[1], force),
            ];
            Ok(Table1Row {
                label: case.label,
                positions: case.positions,
                paper: case.paper,
                under_each: gantry.deflections(case.positions)?,
                midspan: gantry.beam.deflection(0.5 * gantry.beam.length(), &loads)?,
            })
        })
        .collect()
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
                    "relative_error": r.relative_error(),
                    "within_paper_tolerance": r.within_tolerance(),
                    "mass_kg": args.load.mass,
                    "gravity": args.load.gravity,
                })
            })
            .collect();
        print_json(&serde_json::Value::Array(list))?;
    } else {
        print!("{}", table1_text(&rows, args.load));
    }
    Ok(if rows.iter().all(Table1Row::within_tolerance) {
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
    let verdict = if rows.iter().all(Table1Row::within_tolerance) {
        "every case is within the paper's 4 %"
    } else {
        "NOT every case is within the paper's 4 %"
    };
    out + &format!("\n{verdict}\n")
}

/// One sample of the sweep: carriage position and what the rigid model misses.
struct ErrorSample {
    d2: f64,
    deflection: f64,
    error: Vector3<f64>,
    two_arm_deflection: f64,
}

fn error_along_beam(args: &ErrorAlongBeamArgs) -> CliResult<Vec<ErrorSample>> {
    if args.samples < 2 {
        return Err(CliError(format!(
            "--samples: expected at least 2, got {}",
            args.samples
        )));
    }
    let beam = SimplySupportedBeam::seed000();
    let carriage = CarriageDeflection::from_mass(beam, args.load.mass, args.load.gravity)?;
    let rigid = robots::gantry9_with_beam(&GantryBeam::Rigid)?;
    let flex = robots::gantry9_with_beam(&GantryBeam::Flexible(carriage))?;
    let two_arm = TwoCarriageBeam::new(beam, [carriage.force, carriage.force])?;
    let mut q = match &args.q {
        Some(text) => parse_joint_positions(text, &rigid, LimitPolicy::Enforce)?,
        None => rigid.neutral_configuration(),
    };
    let limits = rigid.joints()[1].limits;
    let (mut rigid_data, mut flex_data) = (Data::new(&rigid), Data::new(&flex));
    (0..args.samples)
        .map(|k| {
            let d2 =
                limits.lower + (limits.upper - limits.lower) * k as f64 / (args.samples - 1) as f64;
            q[1] = d2;
            let truth = forward_kinematics(&flex, &mut flex_data, &q)?.translation;
            let assumed = forward_kinematics(&rigid, &mut rigid_data, &q)?.translation;
            // The second arm of the two-arm gantry mirrored about mid-span.
            let mirror = beam.length() - d2;
            Ok(ErrorSample {
                d2,
                deflection: carriage.deflection_and_slope(d2).0,
                error: truth - assumed,
                two_arm_deflection: two_arm.deflections([d2, mirror])?[0],
            })
        })
        .collect()
}

fn run_error_along_beam(args: &ErrorAlongBeamArgs) -> CliResult<Outcome> {
    let samples = error_along_beam(args)?;
    std::fs::create_dir_all(&args.out)?;
    let csv_path = args.out.join("error_along_beam.csv");
    let svg_path = args.out.join("error_along_beam.svg");
    let mut csv = String::from(
        "d2_m,deflection_m,error_x_m,error_y_m,error_z_m,error_norm_m,deflection_two_arm_mirrored_m\n",
    );
    for s in &samples {
        csv += &format!(
            "{},{},{},{},{},{},{}\n",
            s.d2,
            s.deflection,
            s.error.x,
            s.error.y,
            s.error.z,
            s.error.norm(),
            s.two_arm_deflection
        );
    }
    std::fs::write(&csv_path, csv)?;
    let x: Vec<f64> = samples.iter().map(|s| s.d2).collect();
    let millimetres = |f: fn(&ErrorSample) -> f64| samples.iter().map(|s| 1e3 * f(s)).collect();
    write_line_plot(
        &svg_path,
        "End-effector error of a rigid-beam model (gantry9, seed 000 beam)",
        "carriage position d2 (m)",
        "error (mm)",
        &x,
        &[
            ("|error|, one arm", millimetres(|s| s.error.norm())),
            (
                "deflection with a second arm at L - d2",
                millimetres(|s| s.two_arm_deflection),
            ),
        ],
    )?;
    let worst = samples
        .iter()
        .max_by(|a, b| a.error.norm().total_cmp(&b.error.norm()))
        .ok_or_else(|| CliError("no samples".into()))?;
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

/// Writes an SVG line chart of `series` (name, ordinates) against `x`.
fn write_line_plot(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x: &[f64],
    series: &[(&str, Vec<f64>)],
) -> CliResult {
    let plot_error = |e: &dyn std::fmt::Display| CliError(format!("{}: plot: {e}", path.display()));
    let (x_min, x_max) = bounds(x.iter().copied());
    let (y_min, y_max) = bounds(series.iter().flat_map(|(_, y)| y.iter().copied()));
    let y_pad = 0.05 * (y_max - y_min).max(1e-9);
    let root = SVGBackend::new(path, (800, 500)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x_min..x_max, (y_min - y_pad)..(y_max + y_pad))
        .map_err(|e| plot_error(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()
        .map_err(|e| plot_error(&e))?;
    for (k, (name, y)) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(
                x.iter().copied().zip(y.iter().copied()),
                color.stroke_width(2),
            ))
            .map_err(|e| plot_error(&e))?
            .label(*name)
            .legend(move |(px, py)| {
                PathElement::new([(px, py), (px + 18, py)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|e| plot_error(&e))?;
    root.present().map_err(|e| plot_error(&e))?;
    Ok(())
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}
