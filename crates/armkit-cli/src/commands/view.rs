//! `armkit view`: one HTML file showing the robot in 3-D (three.js, inlined:
//! the file opens offline from anywhere), at one configuration or moving
//! along a trajectory CSV. Opens nothing by itself.

use std::path::{Path, PathBuf};

use armkit::model::Model;
use armkit_view::{chain_scene, standalone_page, urdf_scene, Scene, UrdfSource};
use clap::Args;

use crate::common::{parse_joint_positions, CliError, CliResult, LimitPolicy, Outcome, RobotArgs};

/// The robot in 3-D, written as one self-contained HTML file.
#[derive(Args, Debug)]
pub struct ViewArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Joint positions, comma-separated (rad or m; `pi/2` and `90deg` work);
    /// default: the middle of each joint's range.
    #[arg(
        long,
        value_name = "Q1,Q2,...",
        allow_hyphen_values = true,
        conflicts_with = "trajectory"
    )]
    pub q: Option<String>,
    /// A motion: CSV with a header, a `t` column (s) and one column per
    /// joint, named `q1`, `q2`, ... (as `armkit traj --csv` writes) or by
    /// the joints' names.
    #[arg(long, value_name = "FILE.csv")]
    pub trajectory: Option<PathBuf>,
    /// Folder holding the packages that `package://` mesh paths name
    /// (repeatable); the URDF's own folder and those above it are searched too.
    #[arg(long, value_name = "DIR")]
    pub package_path: Vec<PathBuf>,
    /// The HTML file to write.
    #[arg(long, value_name = "FILE.html", default_value = "armkit-view.html")]
    pub out: PathBuf,
}

/// Runs `armkit view`.
pub fn run(args: &ViewArgs) -> CliResult<Outcome> {
    let model = args.robot.load()?;
    let (times, configurations) = match (&args.q, &args.trajectory) {
        (_, Some(path)) => read_trajectory(path, &model)?,
        (Some(q), None) => (
            vec![0.0],
            vec![parse_joint_positions(q, &model, LimitPolicy::Enforce)?],
        ),
        (None, None) => (vec![0.0], vec![model.neutral_configuration()]),
    };
    let scene = scene(
        &args.robot,
        &args.package_path,
        &model,
        &times,
        &configurations,
    )?;
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    crate::report::write_atomic(&args.out, standalone_page(&scene).as_bytes())
        .map_err(|e| CliError(format!("--out {}: cannot write: {e}", args.out.display())))?;
    println!(
        "wrote {} ({} links, {} frames, {} meshes)",
        args.out.display(),
        scene.links.len(),
        scene.times.len(),
        scene.meshes.len()
    );
    Ok(Outcome::Success)
}

/// The scene of the selected robot: a URDF's own visuals, or the chain
/// drawn from its joint frames.
pub fn scene(
    robot: &RobotArgs,
    package_paths: &[PathBuf],
    model: &Model,
    times: &[f64],
    configurations: &[Vec<f64>],
) -> CliResult<Scene> {
    match &robot.urdf {
        Some(path) => {
            let source = UrdfSource {
                path: path.clone(),
                selection: armkit::urdf::ChainSelection {
                    base: robot.base.clone(),
                    tip: robot.tip.clone(),
                },
                package_paths: package_paths.to_vec(),
            };
            urdf_scene(&source, model, times, configurations).map_err(CliError)
        }
        None => Ok(chain_scene(model, times, configurations)?),
    }
}

/// Reads a trajectory CSV: times and one configuration per row.
pub fn read_trajectory(path: &Path, model: &Model) -> CliResult<(Vec<f64>, Vec<Vec<f64>>)> {
    let fail = |reason: String| CliError(format!("--trajectory {}: {reason}", path.display()));
    let text = std::fs::read_to_string(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, header) = lines.next().ok_or_else(|| fail("empty file".into()))?;
    let header: Vec<&str> = header.split(',').map(str::trim).collect();
    let column = |name: &str| header.iter().position(|h| *h == name);
    let t_column = column("t").ok_or_else(|| fail("no `t` column in the header".into()))?;
    let joint_columns = model
        .joints()
        .iter()
        .enumerate()
        .map(|(j, joint)| {
            column(&format!("q{}", j + 1))
                .or_else(|| column(&joint.name))
                .ok_or_else(|| {
                    fail(format!(
                        "no column for joint {} (`q{}` or `{}`)",
                        j + 1,
                        j + 1,
                        joint.name
                    ))
                })
        })
        .collect::<CliResult<Vec<usize>>>()?;
    let mut times = Vec::new();
    let mut configurations = Vec::new();
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        let cell = |c: usize| -> CliResult<f64> {
            let text = cells.get(c).ok_or_else(|| {
                fail(format!("line {}: missing column `{}`", line + 1, header[c]))
            })?;
            crate::common::parse_number(text)
                .map_err(|e| fail(format!("line {}, column `{}`: {e}", line + 1, header[c])))
        };
        let t = cell(t_column)?;
        if times.last().is_some_and(|&last| t < last) {
            return Err(fail(format!("line {}: `t` goes back in time", line + 1)));
        }
        times.push(t);
        configurations.push(
            joint_columns
                .iter()
                .map(|&c| cell(c))
                .collect::<CliResult<Vec<f64>>>()?,
        );
    }
    if times.is_empty() {
        return Err(fail("no rows after the header".into()));
    }
    Ok((times, configurations))
}
