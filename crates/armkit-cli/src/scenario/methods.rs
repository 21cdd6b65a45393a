//! The methods a scenario can run. A method table holds the options of the
//! matching `armkit` command (`payload = 50` is `--payload 50`): every
//! command option works in a scenario, with the same defaults and the same
//! checks, and a scenario never drifts from the command line.

use std::collections::BTreeMap;

use clap::{Args, FromArgMatches};
use toml::Spanned;

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
    /// `[mpc]`: one of seed 000's MPC examples (`example = "ex1"`); options of `armkit mpc`.
    Mpc(Box<mpc::MpcArgs>),
    /// `[redundancy]`: one motion distributed four ways; options of `armkit redundancy`.
    Redundancy(Box<redundancy::RedundancyArgs>),
    /// `[continuous_path]`: seed 002's continuous path; options of `armkit traj line`.
    ContinuousPath(Box<traj::LineArgs>),
    /// `[singularity]`: seed 004's line through a wrist singularity tracked
    /// four ways; options of `armkit singularity`.
    Singularity(Box<singularity::SingularityArgs>),
    Space(Box<space::SpaceStudyArgs>),
}

/// The method tables a scenario file may hold (exactly one is given).
pub const METHOD_TABLES: &str =
    "[beam], [mpc], [redundancy], [continuous_path], [singularity], [space]";

impl Method {
    /// Parses the one method table given, with the robot's arguments
    /// (`--robot NAME` ...) appended, as the command would.
    pub fn parse(
        tables: Vec<(&'static str, Option<Spanned<OptionTable>>)>,
        robot_argv: &[(String, String, std::ops::Range<usize>)],
        locator: &Locator,
    ) -> CliResult<Method> {
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
        let parsed = ParsedTable::new(&table, robot_argv, locator)?;
        Ok(match name {
            "beam" => Method::Beam(parsed.args(name, locator)?),
            "mpc" => Method::Mpc(Box::new(parsed.args(name, locator)?)),
            "redundancy" => Method::Redundancy(Box::new(parsed.args(name, locator)?)),
            "singularity" => Method::Singularity(Box::new(parsed.args(name, locator)?)),
            "space" => Method::Space(Box::new(parsed.args(name, locator)?)),
            _ => Method::ContinuousPath(Box::new(parsed.args(name, locator)?)),
        })
    }

    /// Runs the method and returns its report.
    pub fn run(&self) -> CliResult<Report> {
        match self {
            Method::Beam(args) => beam::study_report(args),
            Method::Mpc(args) => mpc::example_report(args),
            Method::Redundancy(args) => redundancy::report(args),
            Method::ContinuousPath(args) => traj::line_report(args),
            Method::Singularity(args) => singularity::report(args),
            Method::Space(args) => space::study_report(args),
        }
    }
}

/// A method table turned into command-line words, with the location of
/// each option for error messages.
struct ParsedTable {
    argv: Vec<String>,
    /// (`--option`, span of its key) for every option, robot options included.
    spans: Vec<(String, std::ops::Range<usize>)>,
    table_span: std::ops::Range<usize>,
}

impl ParsedTable {
    fn new(
        table: &Spanned<OptionTable>,
        robot_argv: &[(String, String, std::ops::Range<usize>)],
        locator: &Locator,
    ) -> CliResult<Self> {
        let mut argv = Vec::new();
        let mut spans = Vec::new();
        for (key, value) in table.get_ref() {
            let flag = format!("--{}", key.get_ref().replace('_', "-"));
            match value.get_ref() {
                toml::Value::Boolean(true) => argv.push(flag.clone()),
                toml::Value::Boolean(false) => {}
                other => {
                    argv.push(flag.clone());
                    argv.push(option_value(other).map_err(|why| locator.error(value.span(), why))?);
                }
            }
            spans.push((flag, key.span()));
        }
        for (flag, value, span) in robot_argv {
            argv.push(flag.clone());
            argv.push(value.clone());
            spans.push((flag.clone(), span.clone()));
        }
        Ok(ParsedTable {
            argv,
            spans,
            table_span: table.span(),
        })
    }

    /// Parses the words as the command `name` parses its options.
    fn args<A: Args + FromArgMatches>(
        &self,
        name: &'static str,
        locator: &Locator,
    ) -> CliResult<A> {
        let command = accept_hyphen_values(A::augment_args(
            clap::Command::new(name).no_binary_name(true),
        ));
        let error = |e: clap::Error| {
            let text = e.to_string();
            let first = text
                .lines()
                .next()
                .unwrap_or("")
                .trim_start_matches("error: ")
                .to_string();
            // Point at the option the message names, else at the table.
            let span = self
                .spans
                .iter()
                .filter(|(flag, _)| {
                    first.contains(&format!("'{flag}")) || first.contains(&format!("{flag} "))
                })
                .map(|(_, span)| span.clone())
                .next()
                .unwrap_or_else(|| self.table_span.clone());
            locator.error(span, format!("[{name}]: {first}"))
        };
        let matches = command.try_get_matches_from(&self.argv).map_err(error)?;
        A::from_arg_matches(&matches).map_err(error)
    }
}

/// A TOML value as the command-line word for it: numbers and strings as
/// they are, arrays joined by commas.
fn option_value(value: &toml::Value) -> Result<String, String> {
    match value {
        toml::Value::String(s) => Ok(s.clone()),
        toml::Value::Integer(i) => Ok(i.to_string()),
        toml::Value::Float(f) => Ok(f.to_string()),
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
