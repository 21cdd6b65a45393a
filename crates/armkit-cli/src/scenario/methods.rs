//! The methods a scenario can run. A method table holds the options of the
//! matching `armkit` command (`payload = 50` is `--payload 50`): every
//! command option works in a scenario, with the same defaults and the same
//! checks, and a scenario never drifts from the command line.

use std::collections::BTreeMap;

use clap::{Args, FromArgMatches};
use toml::Spanned;

use super::keys::KeyMap;
use super::Locator;
use crate::commands::{beam, mpc, redundancy, singularity, space, traj};
use crate::common::{accept_hyphen_values, CliError, CliResult};
use crate::report::Report;

/// A method table as written: option name -> value, both located.
pub type OptionTable = BTreeMap<Spanned<String>, Spanned<toml::Value>>;

/// A scenario's method, with its options parsed as the command parses them.
#[derive(Debug)]
pub enum Method {
    /// `[beam]`: seed 000's beam (Table 1, rigid-model error); options of
    /// [`beam::BeamStudyArgs`].
    Beam(beam::BeamStudyArgs),
    /// `[mpc]`: the MPC on the `[robot]` to `target` (options of `armkit
    /// mpc --target`), or one of seed 000's examples (`example = "ex1"`).
    Mpc(Box<mpc::MpcArgs>),
    /// `[redundancy]`: one motion distributed four ways; options of `armkit redundancy`.
    Redundancy(Box<redundancy::RedundancyArgs>),
    /// `[continuous_path]`: seed 002's continuous path; options of `armkit traj line`.
    ContinuousPath(Box<traj::LineArgs>),
    /// `[singularity]`: seed 004's line through a wrist singularity tracked
    /// four ways; options of `armkit singularity`.
    Singularity(Box<singularity::SingularityArgs>),
    /// `[space]`: seed 004's free-floating space robot; options of `armkit space study`.
    Space(Box<space::SpaceStudyArgs>),
}

/// The method tables a scenario file may hold (exactly one is given).
pub const METHOD_TABLES: &str =
    "[beam], [mpc], [redundancy], [continuous_path], [singularity], [space]";

/// The robot's command-line words: (`--robot`, value, span of the key).
pub type RobotWords = [(String, String, std::ops::Range<usize>)];

impl Method {
    /// Parses the one method table given, with the robot's arguments
    /// (`--robot NAME` ...) appended, as the command would; returns the
    /// method and where each of its keys is (for messages while it runs).
    pub fn parse(
        tables: Vec<(&'static str, Option<Spanned<OptionTable>>)>,
        robot: Option<(&RobotWords, std::ops::Range<usize>)>,
        locator: &Locator,
    ) -> CliResult<(Method, KeyMap)> {
        let mut given = tables
            .into_iter()
            .filter_map(|(name, table)| table.map(|t| (name, t)));
        let (name, table) = given.next().ok_or_else(|| {
            locator.error(
                0..0,
                format!("no method table: expected exactly one of {METHOD_TABLES}"),
            )
        })?;
        if let Some((_, second)) = given.next() {
            return Err(locator.error(
                second.span(),
                format!("a second method table: expected exactly one of {METHOD_TABLES}"),
            ));
        }
        needs_robot(name, &table, robot.is_some(), locator)?;
        Ok(match name {
            "beam" => {
                let (args, keys) = parse_table(name, &table, robot.clone(), locator)?;
                (Method::Beam(args), keys)
            }
            "mpc" => {
                let (args, keys) = parse_table(name, &table, robot.clone(), locator)?;
                (Method::Mpc(Box::new(args)), keys)
            }
            "redundancy" => {
                let (args, keys) = parse_table(name, &table, robot.clone(), locator)?;
                (Method::Redundancy(Box::new(args)), keys)
            }
            "singularity" => {
                let (args, keys) = parse_table(name, &table, robot.clone(), locator)?;
                (Method::Singularity(Box::new(args)), keys)
            }
            "space" => {
                let (args, keys) = parse_table(name, &table, robot.clone(), locator)?;
                (Method::Space(Box::new(args)), keys)
            }
            _ => {
                let (args, keys) = parse_table(name, &table, robot.clone(), locator)?;
                (Method::ContinuousPath(Box::new(args)), keys)
            }
        })
    }

    /// Runs the method and returns its report.
    pub fn run(&self) -> CliResult<Report> {
        match self {
            Method::Beam(args) => beam::study_report(args),
            Method::Mpc(args) if args.example.is_some() => mpc::example_report(args),
            Method::Mpc(args) => mpc::target_report(args),
            Method::Redundancy(args) => redundancy::report(args),
            Method::ContinuousPath(args) => traj::line_report(args),
            Method::Singularity(args) => singularity::report(args),
            Method::Space(args) => space::study_report(args),
        }
    }
}

/// The tables that run on the user's robot and have no default one: `[mpc]`
/// without `example`, `[continuous_path]`. Their commands would say "no
/// robot given: use --robot"; a scenario says which table is missing.
fn needs_robot(
    name: &str,
    table: &Spanned<OptionTable>,
    has_robot: bool,
    locator: &Locator,
) -> CliResult {
    if has_robot {
        return Ok(());
    }
    let has_key = |key: &str| table.get_ref().keys().any(|k| k.get_ref() == key);
    let why = match name {
        "mpc" if !has_key("example") => {
            "[mpc] runs the MPC on your robot to `target`: add a [robot] table (`builtin`, \
             `file` or `urdf`), or give `example` to run one of seed 000's examples (ex1, ex2, \
             ex3, ex1-rigid-model, ex1-link-error, ex2-paper-weights, ex2-strict, ex3-undamped)"
        }
        "continuous_path" => {
            "[continuous_path] plans a line for your robot: add a [robot] table (`builtin`, \
             `file` or `urdf`)"
        }
        _ => return Ok(()),
    };
    Err(locator.error(table.span(), why))
}

/// Parses a method table (with the robot's words appended) as the command
/// `name` parses its options.
fn parse_table<A: Args + FromArgMatches>(
    name: &'static str,
    table: &Spanned<OptionTable>,
    robot: Option<(&RobotWords, std::ops::Range<usize>)>,
    locator: &Locator,
) -> CliResult<(A, KeyMap)> {
    let command = accept_hyphen_values(A::augment_args(
        clap::Command::new(name).no_binary_name(true),
    ));
    let mut keys = KeyMap::new(name, table.span(), &command);
    let mut argv = Vec::new();
    for (key, value) in table.get_ref() {
        let long = key.get_ref().replace('_', "-");
        let flag = format!("--{long}");
        // An on/off switch takes true/false, an option a value: a boolean
        // for an option would become a bare flag that takes the next key's
        // words as its value.
        let switch = command
            .get_arguments()
            .find(|a| a.get_long() == Some(long.as_str()))
            .map(|a| !a.get_action().takes_values());
        let mismatch = |expected: &str| {
            locator.error(
                value.span(),
                format!("[{name}] `{}`: {expected}", key.get_ref()),
            )
        };
        match value.get_ref() {
            toml::Value::Boolean(_) if switch == Some(false) => {
                return Err(mismatch(
                    "expected a value (a number, a string or a list), got a boolean",
                ));
            }
            toml::Value::Boolean(true) => argv.push(flag.clone()),
            toml::Value::Boolean(false) => {}
            _ if switch == Some(true) => {
                return Err(mismatch("an on/off switch: expected true or false"));
            }
            other => {
                argv.push(flag.clone());
                argv.push(option_value(other).map_err(|why| {
                    locator.error(value.span(), format!("[{name}] `{}`: {why}", key.get_ref()))
                })?);
            }
        }
        keys.add_table_key(&flag, key.span());
    }
    if let Some((words, robot_span)) = robot {
        keys.set_robot_span(robot_span);
        for (flag, value, span) in words {
            argv.push(flag.clone());
            argv.push(value.clone());
            keys.add_robot_key(flag, span.clone());
        }
    }
    let matches = command
        .try_get_matches_from(&argv)
        .map_err(|e| keys.clap_error(locator, &e))?;
    let args = A::from_arg_matches(&matches).map_err(|e| keys.clap_error(locator, &e))?;
    Ok((args, keys))
}

/// A TOML value as the command-line word for it: numbers and strings as
/// they are, arrays joined by commas.
fn option_value(value: &toml::Value) -> Result<String, String> {
    match value {
        toml::Value::String(s) => Ok(s.clone()),
        toml::Value::Integer(i) => Ok(i.to_string()),
        // Briefly (1e300, not 301 digits): the same value, parsed back.
        toml::Value::Float(f) => Ok(armkit::error::brief(*f)),
        toml::Value::Array(items) => items
            .iter()
            .map(|item| match item {
                toml::Value::Array(_) | toml::Value::Table(_) => {
                    Err("expected a number, a string or a list of them".to_string())
                }
                other => option_value(other),
            })
            .collect::<Result<Vec<_>, _>>()
            .map(|words| words.join(",")),
        toml::Value::Boolean(_) => Ok(String::new()),
        toml::Value::Datetime(_) | toml::Value::Table(_) => {
            Err("expected a number, a string, true/false or a list".to_string())
        }
    }
}

impl From<clap::Error> for CliError {
    fn from(e: clap::Error) -> Self {
        CliError(e.to_string().lines().next().unwrap_or("").to_string())
    }
}
