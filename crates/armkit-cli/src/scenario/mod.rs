//! Scenario files: which robot, which method with which options, and what to
//! check; `armkit run FILE.toml` turns one into a report, `armkit demo` runs
//! the shipped ones.
//!
//! ```toml
//! name = "seed000-beam"            # folder under the output directory
//! title = "Seed 000: the flexible beam"
//! description = "..."              # optional
//!
//! [robot]                          # optional for methods that fix their robot
//! builtin = "gantry9"              # or file = "robot.toml", or urdf = "x.urdf" (+ base, tip)
//!
//! [beam]                           # exactly one method table
//! mass = 400.0
//! ```
//!
//! Errors name the file, the line and the column, and say what was expected.

mod keys;
mod methods;

use std::path::{Path, PathBuf};

use armkit::description::{line_and_column, toml_error_line};
use serde::Deserialize;
use toml::Spanned;

use crate::common::{CliError, CliResult};
use crate::report::Report;

use keys::KeyMap;
pub use methods::Method;
use methods::OptionTable;

/// Where the robot comes from.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotSpec {
    builtin: Option<Spanned<String>>,
    file: Option<Spanned<String>>,
    urdf: Option<Spanned<String>>,
    base: Option<Spanned<String>>,
    tip: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenarioFile {
    name: Spanned<String>,
    /// Optional: a scenario without one is titled by its name.
    title: Option<String>,
    #[serde(default)]
    description: String,
    robot: Option<Spanned<RobotSpec>>,
    // The method tables: exactly one is present (see `methods`).
    beam: Option<Spanned<OptionTable>>,
    mpc: Option<Spanned<OptionTable>>,
    redundancy: Option<Spanned<OptionTable>>,
    continuous_path: Option<Spanned<OptionTable>>,
    singularity: Option<Spanned<OptionTable>>,
    space: Option<Spanned<OptionTable>>,
}

/// A parsed, validated scenario.
#[derive(Debug)]
pub struct Scenario {
    /// Output folder name.
    pub name: String,
    /// Title (the file's `title`, else its `name`).
    pub title: String,
    /// Description shown in the report.
    pub description: String,
    /// The method and its options (the robot among them).
    pub method: Method,
    /// Where each option is, for the messages of a run.
    keys: KeyMap,
    /// The file's name and text, for the messages of a run.
    source_name: String,
    text: String,
}

/// Locates byte offsets of one file in error messages.
pub struct Locator<'a> {
    source_name: &'a str,
    text: &'a str,
}

impl Locator<'_> {
    /// `file: line L, column C: message` for a span's start.
    pub fn error(&self, span: std::ops::Range<usize>, message: impl std::fmt::Display) -> CliError {
        let (line, column) = line_and_column(self.text, span.start);
        CliError(format!(
            "{}: line {line}, column {column}: {message}",
            self.source_name
        ))
    }
}

/// Reads and validates a scenario file.
pub fn load(path: &Path) -> CliResult<Scenario> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError(format!("{}: cannot read the file: {e}", path.display())))?;
    let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse(&text, &path.display().to_string(), &base_dir)
}

/// Parses scenario text; relative paths inside it are taken from `base_dir`.
pub fn parse(text: &str, source_name: &str, base_dir: &Path) -> CliResult<Scenario> {
    let file: ScenarioFile = toml::from_str(text)
        .map_err(|e| CliError(format!("{source_name}: {}", toml_error_line(text, &e))))?;
    let locator = Locator { source_name, text };
    let name = file.name.get_ref();
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
    {
        return Err(locator.error(
            file.name.span(),
            format!("`name` must be letters, digits, `-` or `_` (it names the output folder), got {name:?}"),
        ));
    }
    let robot_words = match &file.robot {
        Some(spec) => Some((robot_arguments(spec, &locator, base_dir)?, spec.span())),
        None => None,
    };
    let tables = vec![
        ("beam", file.beam),
        ("mpc", file.mpc),
        ("redundancy", file.redundancy),
        ("continuous_path", file.continuous_path),
        ("singularity", file.singularity),
        ("space", file.space),
    ];
    let robot = robot_words
        .as_ref()
        .map(|(words, span)| (words.as_slice(), span.clone()));
    let (method, keys) = Method::parse(tables, robot, &locator)?;
    Ok(Scenario {
        name: name.clone(),
        title: file.title.unwrap_or_else(|| name.clone()),
        description: file.description,
        method,
        keys,
        source_name: source_name.to_string(),
        text: text.to_string(),
    })
}

/// Loads the robot (so that a bad one is reported at its line) and returns
/// the command-line words that select it: `--robot NAME`, `--robot-file
/// PATH` or `--urdf PATH [--base LINK] [--tip LINK]`, paths taken from the
/// scenario's folder.
fn robot_arguments(
    spec: &Spanned<RobotSpec>,
    locator: &Locator,
    base_dir: &Path,
) -> CliResult<Vec<(String, String, std::ops::Range<usize>)>> {
    let robot = spec.get_ref();
    let resolve = |p: &Spanned<String>| -> PathBuf { base_dir.join(p.get_ref()) };
    let word =
        |flag: &str, value: String, span: std::ops::Range<usize>| (flag.to_string(), value, span);
    if robot.urdf.is_none() {
        if let Some(link) = robot.base.as_ref().or(robot.tip.as_ref()) {
            return Err(locator.error(
                link.span(),
                "[robot] `base` and `tip` choose the chain of a URDF: they need `urdf`",
            ));
        }
    }
    match (&robot.builtin, &robot.file, &robot.urdf) {
        (Some(name), None, None) => {
            armkit::robots::by_name(name.get_ref()).map_err(|e| locator.error(name.span(), e))?;
            Ok(vec![word("--robot", name.get_ref().clone(), name.span())])
        }
        (None, Some(file), None) => {
            armkit::description::load(resolve(file)).map_err(|e| locator.error(file.span(), e))?;
            Ok(vec![word(
                "--robot-file",
                resolve(file).display().to_string(),
                file.span(),
            )])
        }
        (None, None, Some(urdf)) => {
            let selection = armkit::urdf::ChainSelection {
                base: robot.base.as_ref().map(|b| b.get_ref().clone()),
                tip: robot.tip.as_ref().map(|t| t.get_ref().clone()),
            };
            armkit::urdf::load(resolve(urdf), &selection)
                .map_err(|e| locator.error(urdf.span(), e))?;
            let mut words = vec![word(
                "--urdf",
                resolve(urdf).display().to_string(),
                urdf.span(),
            )];
            for (flag, value) in [("--base", &robot.base), ("--tip", &robot.tip)] {
                if let Some(v) = value {
                    words.push(word(flag, v.get_ref().clone(), v.span()));
                }
            }
            Ok(words)
        }
        _ => Err(locator.error(
            spec.span(),
            "[robot] needs exactly one of `builtin`, `file` or `urdf`",
        )),
    }
}

impl Scenario {
    /// Runs the method and returns its report, named and titled by the
    /// scenario. An error names the file, the line of the key it is about
    /// (or of the method table) and the key as the file spells it.
    pub fn run(&self) -> CliResult<Report> {
        let locator = Locator {
            source_name: &self.source_name,
            text: &self.text,
        };
        let mut report = self
            .method
            .run()
            .map_err(|e| self.keys.locate(&locator, &e.0))?;
        report.name = self.name.clone();
        report.title = self.title.clone();
        if !self.description.is_empty() {
            report.description = self.description.clone();
        }
        Ok(report)
    }
}
