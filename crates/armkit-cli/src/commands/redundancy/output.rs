//! The table, files, figures and report of `armkit redundancy`.

use std::path::Path;

use armkit::redundancy::ComparisonResult;
use armkit::redundancy::TorqueModel;
use armkit::study::DistributionOutcome;
use armkit::Model;

use super::{study, RedundancyArgs};
use crate::common::{CliError, CliResult};
use crate::plot::Figure;
use crate::report::{Animation, Report, Table};
use armkit::study::{TorqueEnergies, DISTRIBUTION_NOTE, MODERATE_SPEED_MARGIN, VARIANT_NAME};

/// F under dynamic torques of the run named `name`, if computed.
fn dynamic_energy(energies: &[TorqueEnergies], name: &str) -> Option<f64> {
    energies
        .iter()
        .find(|e| e.name == name)
        .map(|e| e.dynamic_energy)
}

/// The text table: one row per distribution (F under dynamic torques when
/// `energies` has them).
pub(super) fn summary_table(
    model: &Model,
    results: &[ComparisonResult],
    energies: &[TorqueEnergies],
) -> String {
    let mut out = format!(
        "{:<15} {:>12} {:>12} {:>10}",
        "distribution", "F (W^2 s)", "F dyn", "max err"
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
        let dynamic = dynamic_energy(energies, &r.name).map_or("-".into(), |f| format!("{f:.4e}"));
        out += &format!(
            "{:<15} {:>12.4e} {:>12} {:>10.2e}",
            r.name, r.summary.energy, dynamic, r.report.max_position_error
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
pub(super) fn write_outputs(
    dir: &Path,
    model: &Model,
    results: &[ComparisonResult],
    energies: &[TorqueEnergies],
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
        "distribution,status,energy_W2s,energy_dynamic_W2s,max_position_error_m,final_position_error_m,\
         final_orientation_error_rad,velocity_scaled_steps,limit_locked_steps,{}\n",
        names
            .iter()
            .map(|n| format!("travel_{n}"))
            .collect::<Vec<_>>()
            .join(",")
    );
    for r in results {
        summary += &format!(
            "{},{},{},{},{},{},{},{},{},{}\n",
            r.name,
            r.report.status.to_string().replace(',', ";"),
            r.summary.energy,
            dynamic_energy(energies, &r.name).map_or(String::new(), |f| f.to_string()),
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
pub(super) fn figures(model: &Model, results: &[ComparisonResult]) -> Vec<(String, Figure)> {
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
    let results = &study.outcome.results;
    let energy_optimal = study
        .outcome
        .result("energy-optimal")
        .ok_or_else(|| CliError("no energy-optimal run".into()))?;
    let checks = study.outcome.checks()?;
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
    for r in results {
        let mut row = vec![label(&r.name), format!("{:.4e}", r.summary.energy)];
        row.extend(r.summary.travel.iter().map(|t| format!("{t:.3}")));
        table.push(row);
    }
    let mut tables = vec![table];
    if let Some(torques) = torque_table(&study.outcome) {
        tables.push(torques);
    }
    if let Some(sweep) = sweep_table(&study.outcome) {
        tables.push(sweep);
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
             seed 000's joint priorities; locked: the paper's baseline, joints {} locked so that six remain{}. \
             F is measured under the load's static torques (the paper's) and, for robots with masses, under the \
             full inverse dynamics of each run. The animation shows the energy-optimal run.",
            study.heading,
            one_based(&study.outcome.settings.locked),
            if study.outcome.settings.variant_locked.is_empty() {
                String::new()
            } else {
                format!(
                    "; {VARIANT_NAME}: a labelled extra, not the paper's baseline, joints {} locked",
                    one_based(&study.outcome.settings.variant_locked)
                )
            }
        ),
        checks,
        findings: study.outcome.findings(),
        tables,
        figures: figures(&study.model, results),
        notes: vec![DISTRIBUTION_NOTE.into()],
        animation: Some(Animation::from_configurations(&study.model, &times, &configurations)?),
    })
}

/// 1-based joint numbers, comma-separated.
fn one_based(joints: &[usize]) -> String {
    joints
        .iter()
        .map(|j| (j + 1).to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// A run's name as a table shows it: the baseline and the extra labelled.
fn label(name: &str) -> String {
    match name {
        "locked" => "locked (paper's baseline)".into(),
        VARIANT_NAME => format!("{VARIANT_NAME} (extra)"),
        other => other.into(),
    }
}

/// Seed 001's F under static and dynamic torques, one row per run, with
/// each run's margin over the winner; `None` without dynamics.
fn torque_table(outcome: &DistributionOutcome) -> Option<Table> {
    if outcome.torque_energies.is_empty() {
        return None;
    }
    let best = |model: TorqueModel| outcome.ranking(model).first().map(|(_, f)| *f);
    let (best_static, best_dynamic) = (best(TorqueModel::Static)?, best(TorqueModel::Dynamic)?);
    let title = format!(
        "F under static and dynamic torques (W^2 s): static, {}; dynamic, {}",
        outcome.winner(TorqueModel::Static)?,
        outcome.winner(TorqueModel::Dynamic)?
    );
    let mut table = Table::new(
        title,
        &[
            "distribution",
            "F static",
            "vs lowest static",
            "F dynamic",
            "vs lowest dynamic",
            "dynamic / static",
        ],
    );
    for e in &outcome.torque_energies {
        table.push(vec![
            label(&e.name),
            format!("{:.4e}", e.static_energy),
            format!("{:+.1} %", 100.0 * (e.static_energy / best_static - 1.0)),
            format!("{:.4e}", e.dynamic_energy),
            format!("{:+.1} %", 100.0 * (e.dynamic_energy / best_dynamic - 1.0)),
            format!(
                "{:+.2} %",
                100.0 * (e.dynamic_energy / e.static_energy - 1.0)
            ),
        ]);
    }
    Some(table)
}

/// The duration sweep (seed 001's energy claim against the move's speed),
/// one row per duration; `None` without a sweep.
fn sweep_table(outcome: &DistributionOutcome) -> Option<Table> {
    let sweep = outcome.sweep.as_ref()?;
    let title = format!(
        "Duration sweep: energy-optimal against the paper's baseline (F in W^2 s); crossover \
         under dynamic torques: {}; moderate speed (inertia within {:.0} % of F): {}",
        sweep
            .crossover()
            .map_or("none in the sweep".into(), |t| format!("{t:.2} s")),
        100.0 * MODERATE_SPEED_MARGIN,
        sweep
            .moderate()
            .map_or("none in the sweep".into(), |p| format!(
                "from {} s",
                p.duration
            )),
    );
    let mut table = Table::new(
        title,
        &[
            "duration (s)",
            "F static, energy-optimal",
            "F static, baseline",
            "F dynamic, energy-optimal",
            "F dynamic, baseline",
            "margin static",
            "margin dynamic",
            "inertia share",
        ],
    );
    for p in &sweep.points {
        table.push(vec![
            format!("{}", p.duration),
            format!("{:.4e}", p.optimal_static),
            format!("{:.4e}", p.baseline_static),
            format!("{:.4e}", p.optimal_dynamic),
            format!("{:.4e}", p.baseline_dynamic),
            format!("{:+.1} %", p.margin(TorqueModel::Static)),
            format!("{:+.1} %", p.margin(TorqueModel::Dynamic)),
            format!("{:.1} %", 100.0 * p.inertia_share()),
        ]);
    }
    Some(table)
}
