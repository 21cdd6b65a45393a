//! The output options of `armkit traj`, and its sampling, CSV and figures.

use std::path::PathBuf;

use armkit::kinematics::{forward_kinematics, Data};
use armkit::trajectory::{JointState, Trajectory};
use armkit::Model;
use clap::Args;

use crate::common::{positive, CliError, CliResult};
use crate::plot::Figure;

/// Where and how densely the trajectory is written.
#[derive(Args, Debug, Clone)]
pub struct OutputArgs {
    /// Sampling period of the CSV and plots, s.
    #[arg(
        long,
        default_value_t = 0.01,
        value_name = "S",
        allow_hyphen_values = true
    )]
    pub dt: f64,
    /// CSV file: t, q, qd, qdd, end-effector x y z roll pitch yaw.
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Directory for SVG plots (created if missing): positions.svg,
    /// velocities.svg, accelerations.svg.
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// The trajectory sampled every `dt` (and at its end): times and states.
pub(super) fn sample(traj: &Trajectory, dt: f64) -> CliResult<(Vec<f64>, Vec<JointState>)> {
    positive("--dt", dt)?;
    let steps = (traj.duration() / dt).ceil() as usize;
    if steps > 10_000_000 {
        return Err(CliError(format!(
            "--dt: {dt} s gives {steps} samples; use a larger step"
        )));
    }
    let times: Vec<f64> = (0..=steps)
        .map(|k| traj.start_time() + (k as f64 * dt).min(traj.duration()))
        .collect();
    let states = times
        .iter()
        .map(|&t| traj.sample(t))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((times, states))
}

/// Writes the CSV and the plots that `output` asks for; returns the paths written.
pub fn write_outputs(
    model: &Model,
    traj: &Trajectory,
    output: &OutputArgs,
) -> CliResult<Vec<String>> {
    let (times, states) = sample(traj, output.dt)?;
    let mut written = Vec::new();
    if let Some(path) = &output.csv {
        crate::report::write_text(path, &trajectory_csv(model, &times, &states)?)?;
        written.push(path.display().to_string());
    }
    if let Some(dir) = &output.plots {
        std::fs::create_dir_all(dir)
            .map_err(|e| CliError(format!("{}: cannot create: {e}", dir.display())))?;
        for (name, figure) in joint_figures(model, &times, &states) {
            let path = dir.join(format!("{name}.svg"));
            let svg = figure
                .to_svg(800, 450)
                .map_err(|e| CliError(format!("{}: plot: {e}", path.display())))?;
            crate::report::write_text(&path, &svg)?;
            written.push(path.display().to_string());
        }
    }
    Ok(written)
}

/// CSV text: header, then one row per sample with the end-effector pose from FK.
fn trajectory_csv(model: &Model, times: &[f64], states: &[JointState]) -> CliResult<String> {
    let dof = model.dof();
    let joint_columns = |prefix: &'static str| (1..=dof).map(move |j| format!("{prefix}{j}"));
    let header: Vec<String> = std::iter::once("t".to_string())
        .chain(joint_columns("q"))
        .chain(joint_columns("qd"))
        .chain(joint_columns("qdd"))
        .chain(["x", "y", "z", "roll", "pitch", "yaw"].map(String::from))
        .collect();
    let mut out = header.join(",");
    out.push('\n');
    let mut data = Data::new(model);
    for (t, s) in times.iter().zip(states) {
        let pose = forward_kinematics(model, &mut data, &s.position)?;
        let (roll, pitch, yaw) = pose.rpy();
        let p = pose.translation;
        let row: Vec<String> = std::iter::once(*t)
            .chain(s.position.iter().copied())
            .chain(s.velocity.iter().copied())
            .chain(s.acceleration.iter().copied())
            .chain([p.x, p.y, p.z, roll, pitch, yaw])
            .map(|v| v.to_string())
            .collect();
        out += &row.join(",");
        out.push('\n');
    }
    Ok(out)
}

/// Joint positions, velocities and accelerations against time: three
/// figures named `positions`, `velocities`, `accelerations`, one series per
/// joint, each with its joint's limits as dashed lines (position bounds,
/// +- the velocity and acceleration limits, where the model has them).
pub fn joint_figures(
    model: &Model,
    times: &[f64],
    states: &[JointState],
) -> Vec<(&'static str, Figure)> {
    let dof = states.first().map_or(0, JointState::dof);
    type Field = fn(&JointState) -> &Vec<f64>;
    type Bounds = fn(&armkit::model::JointLimits) -> [f64; 2];
    let quantities: [(&'static str, &str, &str, Field, Bounds); 3] = [
        (
            "positions",
            "joint positions",
            "q (rad or m)",
            |s| &s.position,
            |l| [l.lower, l.upper],
        ),
        (
            "velocities",
            "joint velocities",
            "qd (rad/s or m/s)",
            |s| &s.velocity,
            |l| l.velocity.map_or([f64::INFINITY; 2], |v| [-v, v]),
        ),
        (
            "accelerations",
            "joint accelerations",
            "qdd (rad/s^2 or m/s^2)",
            |s| &s.acceleration,
            |l| l.acceleration.map_or([f64::INFINITY; 2], |a| [-a, a]),
        ),
    ];
    let joints = model.joints();
    quantities
        .into_iter()
        .map(|(name, title, y_label, field, bounds)| {
            let mut figure = Figure::new(
                format!("{}: {title}", model.name()),
                "t (s)",
                y_label,
                times.to_vec(),
            );
            for j in 0..dof {
                let label = format!("joint {}", j + 1);
                figure =
                    figure.with_series(label.clone(), states.iter().map(|s| field(s)[j]).collect());
                if let Some(joint) = joints.get(j) {
                    for bound in bounds(&joint.limits) {
                        figure = figure.with_limit(label.clone(), bound);
                    }
                }
            }
            (name, figure)
        })
        .collect()
}
