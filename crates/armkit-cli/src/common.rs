//! Argument parsing and output helpers shared by every command.

use std::fmt;
use std::path::PathBuf;

use armkit::math::{Matrix6xX, Pose};
use armkit::Model;
use clap::Args;

/// The error every command returns: one line, printed on stderr by `main`.
#[derive(Debug)]
pub struct CliError(pub String);

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<armkit::Error> for CliError {
    fn from(e: armkit::Error) -> Self {
        CliError(e.to_string())
    }
}

impl From<std::io::Error> for CliError {
    fn from(e: std::io::Error) -> Self {
        CliError(format!("I/O error: {e}"))
    }
}

impl From<serde_json::Error> for CliError {
    fn from(e: serde_json::Error) -> Self {
        CliError(format!("JSON error: {e}"))
    }
}

impl From<String> for CliError {
    fn from(e: String) -> Self {
        CliError(e)
    }
}

/// Result of a command.
pub type CliResult<T = ()> = Result<T, CliError>;

/// How a command ended, mapped to the process exit code by `main`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Done (exit code 0).
    Success,
    /// Ran, but the result does not meet its goal, e.g. IK did not converge
    /// (exit code 3); the best effort has been printed.
    NotConverged,
}

/// Which robot a command works on: a built-in, a DH description file, or a URDF.
#[derive(Args, Debug, Clone, Default)]
pub struct RobotArgs {
    /// Built-in robot (see `armkit robots`).
    #[arg(long, value_name = "NAME", conflicts_with_all = ["robot_file", "urdf"])]
    pub robot: Option<String>,
    /// DH description file (TOML or JSON; a whole reference JSON works too).
    #[arg(long, value_name = "PATH", conflicts_with = "urdf")]
    pub robot_file: Option<PathBuf>,
    /// URDF file.
    #[arg(long, value_name = "PATH")]
    pub urdf: Option<PathBuf>,
    /// URDF base link (default: the root link).
    #[arg(long, value_name = "LINK", requires = "urdf")]
    pub base: Option<String>,
    /// URDF tip link (default: the only leaf link).
    #[arg(long, value_name = "LINK", requires = "urdf")]
    pub tip: Option<String>,
}

impl RobotArgs {
    /// Loads the selected robot model.
    pub fn load(&self) -> CliResult<Model> {
        // clap does not enforce `requires = "urdf"` when --robot (which
        // conflicts with --urdf) is given, so check here.
        if self.urdf.is_none() && (self.base.is_some() || self.tip.is_some()) {
            return Err(CliError(
                "--base and --tip choose the chain of a URDF: they need --urdf PATH".into(),
            ));
        }
        if let Some(name) = &self.robot {
            return Ok(armkit::robots::by_name(name)?);
        }
        if let Some(path) = &self.robot_file {
            return Ok(armkit::description::load(path)?);
        }
        if let Some(path) = &self.urdf {
            return load_urdf(path, self.base.as_deref(), self.tip.as_deref());
        }
        Err(CliError(
            "no robot given: use --robot NAME, --robot-file PATH or --urdf PATH".into(),
        ))
    }
}

fn load_urdf(path: &std::path::Path, base: Option<&str>, tip: Option<&str>) -> CliResult<Model> {
    let selection = armkit::urdf::ChainSelection {
        base: base.map(str::to_string),
        tip: tip.map(str::to_string),
    };
    Ok(armkit::urdf::load(path, &selection)?)
}

/// A robot and one configuration: the arguments of `fk`, `jacobian`,
/// `dynamics` and `manipulability`.
#[derive(Args, Debug)]
pub struct ConfigurationArgs {
    #[command(flatten)]
    pub robot: RobotArgs,
    /// Joint positions, comma-separated (rad or m; `pi/2` and `90deg` work).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub q: String,
    /// Evaluate even when a joint is outside its limits.
    #[arg(long)]
    pub allow_out_of_limits: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

impl ConfigurationArgs {
    /// The robot and the joint positions, checked against its limits unless
    /// `--allow-out-of-limits` is given.
    pub fn load(&self) -> CliResult<(Model, Vec<f64>)> {
        let model = self.robot.load()?;
        let policy = LimitPolicy::from_flag(self.allow_out_of_limits);
        let q = parse_joint_positions(&self.q, &model, policy)?;
        Ok((model, q))
    }
}

/// Parses one number: a decimal (`0.5`, `-1e-3`), or a multiple of pi
/// (`pi`, `-pi/2`, `3*pi/4`, `2pi`), or degrees (`90deg`).
pub fn parse_number(token: &str) -> Result<f64, String> {
    let text = token.trim();
    let bad = || format!("`{text}` is not a number");
    let value = if let Some(degrees) = text.strip_suffix("deg") {
        degrees
            .trim()
            .parse::<f64>()
            .map_err(|_| bad())?
            .to_radians()
    } else if text.contains("pi") {
        parse_pi_multiple(text).ok_or_else(bad)?
    } else {
        text.parse::<f64>().map_err(|_| bad())?
    };
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("`{text}` is not a finite number"))
    }
}

fn parse_pi_multiple(text: &str) -> Option<f64> {
    let (sign, rest) = match text.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, text.strip_prefix('+').unwrap_or(text)),
    };
    let (numerator, denominator) = match rest.split_once('/') {
        Some((n, d)) => (n, d.trim().parse::<f64>().ok()?),
        None => (rest, 1.0),
    };
    let factor = numerator
        .trim()
        .strip_suffix("pi")?
        .trim()
        .trim_end_matches('*')
        .trim();
    let factor = if factor.is_empty() {
        1.0
    } else {
        factor.parse::<f64>().ok()?
    };
    Some(sign * factor * std::f64::consts::PI / denominator)
}

/// Parses a comma-separated list of numbers; `what` names it in errors.
pub fn parse_numbers(text: &str, what: &str) -> CliResult<Vec<f64>> {
    if text.trim().is_empty() {
        return Err(CliError(format!("{what}: no values given")));
    }
    text.split(',')
        .enumerate()
        .map(|(i, token)| {
            parse_number(token).map_err(|e| CliError(format!("{what}: value {}: {e}", i + 1)))
        })
        .collect()
}

/// Parses exactly `count` comma-separated numbers.
pub fn parse_fixed_numbers(text: &str, what: &str, count: usize) -> CliResult<Vec<f64>> {
    let values = parse_numbers(text, what)?;
    if values.len() != count {
        return Err(CliError(format!(
            "{what}: expected {count} values, got {}",
            values.len()
        )));
    }
    Ok(values)
}

/// Parses joint positions for `model` (one per joint) and, unless
/// `allow_out_of_limits`, checks them against the limits.
pub fn parse_joint_positions(
    text: &str,
    model: &Model,
    limits: LimitPolicy,
) -> CliResult<Vec<f64>> {
    let q = parse_fixed_numbers(text, "--q", model.dof())?;
    if limits == LimitPolicy::Enforce {
        model.check_limits(&q).map_err(|e| {
            CliError(format!(
                "{e} (pass --allow-out-of-limits to evaluate anyway)"
            ))
        })?;
    }
    Ok(q)
}

/// Whether joint positions outside the limits are accepted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitPolicy {
    /// Outside the limits is an error.
    Enforce,
    /// Outside the limits is accepted.
    Allow,
}

impl LimitPolicy {
    /// From the `--allow-out-of-limits` flag.
    pub fn from_flag(allow_out_of_limits: bool) -> Self {
        if allow_out_of_limits {
            LimitPolicy::Allow
        } else {
            LimitPolicy::Enforce
        }
    }
}

/// Parses `"x,y,z,roll,pitch,yaw"` (m, rad; `R = Rz(yaw) Ry(pitch) Rx(roll)`).
pub fn parse_pose(text: &str, what: &str) -> CliResult<Pose> {
    let v = parse_fixed_numbers(text, what, 6)?;
    Ok(Pose::from_xyz_rpy([v[0], v[1], v[2]], [v[3], v[4], v[5]]))
}

/// Row-major rows of a pose, for JSON.
pub fn pose_rows(pose: &Pose) -> Vec<Vec<f64>> {
    pose.to_rows().iter().map(|r| r.to_vec()).collect()
}

/// Row-major rows of a 6 x n Jacobian, for JSON.
pub fn jacobian_rows(j: &Matrix6xX<f64>) -> Vec<Vec<f64>> {
    (0..6).map(|r| j.row(r).iter().copied().collect()).collect()
}

/// Formats rows of numbers as an aligned text table.
pub fn format_rows(rows: &[Vec<f64>]) -> String {
    rows.iter()
        .map(|row| {
            let cells: Vec<String> = row
                .iter()
                .map(|v| {
                    // A value of 11 characters or more (-100 and beyond)
                    // fills its column: a space keeps it from running into
                    // the one before.
                    let cell = format!("{:>11.6}", clean_zero(*v));
                    if cell.starts_with(' ') {
                        cell
                    } else {
                        format!(" {cell}")
                    }
                })
                .collect();
            format!("  [{} ]", cells.join(""))
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Turns -0.0 and round-off dust (|v| < 5e-13) into 0.0 so tables do not print `-0.000000`.
pub fn clean_zero(v: f64) -> f64 {
    if v.abs() < 5e-13 {
        0.0
    } else {
        v
    }
}

/// Prints a JSON value on stdout.
pub fn print_json(value: &serde_json::Value) -> CliResult {
    println!("{}", serde_json::to_string_pretty(value)?);
    Ok(())
}

/// Lets every option of `command` and of its subcommands take a value that
/// starts with `-`, so that `--damping -1` reaches the option's own check
/// ("must be > 0") instead of clap's "unexpected argument '-1'", and
/// `--q -0.5,1` works without `=`. Positional arguments are left alone so
/// that a flag after them is still a flag.
pub fn accept_hyphen_values(command: clap::Command) -> clap::Command {
    let names: Vec<String> = command
        .get_subcommands()
        .map(|sub| sub.get_name().to_string())
        .collect();
    let mut command = command.mut_args(|arg| {
        if arg.is_positional() || !arg.get_action().takes_values() {
            arg
        } else {
            arg.allow_hyphen_values(true)
        }
    });
    for name in names {
        command = command.mut_subcommand(name, accept_hyphen_values);
    }
    command
}

/// `value` when finite and > 0; else an error naming `option`.
pub fn positive(option: &str, value: f64) -> CliResult<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CliError(format!(
            "{option}: must be finite and > 0, got {}",
            armkit::error::brief(value)
        )))
    }
}
