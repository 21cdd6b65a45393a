//! A method table's keys and the command's flags they stand for, so that
//! every message about an option (clap's while parsing, the command's or the
//! library's while running) names the key as the file spells it
//! (`to_pose`, not `--to-pose`) and points at the line that sets it.

use std::ops::Range;

use clap::error::{ContextKind, ContextValue, ErrorKind};

use super::Locator;
use crate::common::CliError;

/// Flags that come from the `[robot]` table, with the key they stand for.
const ROBOT_KEYS: &[(&str, &str)] = &[
    ("--robot", "builtin"),
    ("--robot-file", "file"),
    ("--urdf", "urdf"),
    ("--base", "base"),
    ("--tip", "tip"),
];

/// Keys a scenario accepts but that only matter on the command line (where
/// output goes, JSON); left out of the list of keys a table takes.
const COMMAND_LINE_ONLY: &[&str] = &["out", "json", "csv", "plots", "output"];

/// One option given in the file.
#[derive(Clone, Debug)]
struct Given {
    /// `--to-pose`.
    flag: String,
    /// `to_pose`, or `[robot] builtin` for the robot's options.
    key: String,
    /// Where the key is.
    span: Range<usize>,
}

/// The keys of one method table (and of `[robot]`), located.
#[derive(Clone, Debug)]
pub struct KeyMap {
    /// The table's name (`mpc`).
    pub table: &'static str,
    table_span: Range<usize>,
    given: Vec<Given>,
    /// Every long flag the command knows, without `--`, longest first (so
    /// that `--to-pose` is matched before `--to`).
    known: Vec<String>,
    /// The keys the table takes, for "unknown key" messages.
    accepted: Vec<String>,
    /// Each flag's help line, for "missing key" messages.
    help: Vec<(String, String)>,
    /// Where `[robot]` is, for errors of the robot's model.
    robot_span: Option<Range<usize>>,
}

impl KeyMap {
    /// An empty map for `table`; `command` is the command's clap definition.
    pub fn new(table: &'static str, table_span: Range<usize>, command: &clap::Command) -> Self {
        let mut known: Vec<String> = command
            .get_arguments()
            .filter_map(|a| a.get_long().map(str::to_string))
            .collect();
        known.sort_by_key(|name| std::cmp::Reverse(name.len()));
        let robot_flags = robot_flags(command);
        let mut accepted: Vec<String> = command
            .get_arguments()
            .filter_map(|a| a.get_long())
            .filter(|name| {
                *name != "help"
                    && !COMMAND_LINE_ONLY.contains(name)
                    && !robot_flags.contains(&format!("--{name}"))
            })
            .map(|name| name.replace('-', "_"))
            .collect();
        accepted.sort();
        let help = command
            .get_arguments()
            .filter_map(|a| {
                let help = a.get_help()?.to_string();
                Some((format!("--{}", a.get_long()?), help))
            })
            .collect();
        KeyMap {
            table,
            table_span,
            given: Vec::new(),
            known,
            accepted,
            help,
            robot_span: None,
        }
    }

    /// Records a key of the method table (`to_pose` for `--to-pose`).
    pub fn add_table_key(&mut self, flag: &str, span: Range<usize>) {
        let key = flag.trim_start_matches("--").replace('-', "_");
        self.given.push(Given {
            flag: flag.to_string(),
            key: format!("`{key}`"),
            span,
        });
    }

    /// Records where `[robot]` is.
    pub fn set_robot_span(&mut self, span: Range<usize>) {
        self.robot_span = Some(span);
    }

    /// Records a flag that `[robot]` supplies.
    pub fn add_robot_key(&mut self, flag: &str, span: Range<usize>) {
        let key = ROBOT_KEYS
            .iter()
            .find(|(f, _)| *f == flag)
            .map_or(flag, |(_, k)| k);
        self.given.push(Given {
            flag: flag.to_string(),
            key: format!("[robot] `{key}`"),
            span,
        });
    }

    /// The key written for `flag` (`--to-pose` -> `` `to_pose` ``, a robot
    /// flag -> `` [robot] `builtin` ``).
    fn key_for(&self, flag: &str) -> String {
        match self.given.iter().find(|g| g.flag == flag) {
            Some(given) => given.key.clone(),
            None => format!("`{}`", flag.trim_start_matches("--").replace('-', "_")),
        }
    }

    /// `message` with every flag of the command (`'--mass <KG>'`,
    /// `--to-pose`) replaced by its key, and the span of the first key the
    /// file gives that the message names (else the table's header).
    fn translate(&self, message: &str) -> (String, Range<usize>) {
        let mut out = String::with_capacity(message.len());
        let mut span = None;
        let mut rest = message;
        while let Some(at) = rest.find("--") {
            let (before, from) = rest.split_at(at);
            let boundary = before
                .chars()
                .last()
                .is_none_or(|c| c == ' ' || c == '\'' || c == '(' || c == '`' || c == ',');
            let name = self
                .known
                .iter()
                .find(|name| {
                    from[2..].starts_with(name.as_str())
                        && !from[2 + name.len()..]
                            .starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-')
                })
                .filter(|_| boundary);
            let Some(name) = name else {
                out.push_str(before);
                out.push_str("--");
                rest = &from[2..];
                continue;
            };
            let flag = format!("--{name}");
            let mut after = &from[flag.len()..];
            // clap writes `'--mass <KG>'`: drop the value name and the quotes.
            if let Some(value) = after.strip_prefix(" <") {
                if let Some(end) = value.find('>') {
                    after = &value[end + 1..];
                }
            }
            let quoted = before.ends_with('\'') && after.starts_with('\'');
            out.push_str(if quoted {
                &before[..before.len() - 1]
            } else {
                before
            });
            if quoted {
                after = &after[1..];
            }
            out.push_str(&self.key_for(&flag));
            if span.is_none() {
                span = self
                    .given
                    .iter()
                    .find(|g| g.flag == flag)
                    .map(|g| g.span.clone());
            }
            rest = after;
        }
        out.push_str(rest);
        // Library messages name a field as `name`: locate those too.
        let span = span.or_else(|| {
            self.given
                .iter()
                .find(|g| g.key.starts_with('`') && out.contains(&g.key))
                .map(|g| g.span.clone())
        });
        // An error of the robot's model (no mass properties, ...) is the robot's.
        let span = span.or_else(|| {
            out.starts_with("invalid model")
                .then(|| self.robot_span.clone())
                .flatten()
        });
        (out, span.unwrap_or_else(|| self.table_span.clone()))
    }

    /// A message from running the method, located at the key it names (or
    /// the table) and spelt with the file's keys.
    pub fn locate(&self, locator: &Locator, message: &str) -> CliError {
        let (text, span) = self.translate(message);
        locator.error(span, format!("[{}]: {text}", self.table))
    }

    /// clap's error while parsing the table, in the file's terms.
    pub fn clap_error(&self, locator: &Locator, error: &clap::Error) -> CliError {
        let invalid: Vec<String> = match error.get(ContextKind::InvalidArg) {
            Some(ContextValue::String(s)) => vec![s.clone()],
            Some(ContextValue::Strings(v)) => v.clone(),
            _ => Vec::new(),
        };
        let flag_of = |arg: &str| arg.split(' ').next().unwrap_or("").to_string();
        match error.kind() {
            ErrorKind::UnknownArgument => {
                let flag = invalid.first().map(|a| flag_of(a)).unwrap_or_default();
                if let Some(robot) = self.given.iter().find(|g| {
                    g.flag == flag && g.key.starts_with("[robot]") && !self.known_flag(&flag)
                }) {
                    return locator.error(robot.span.clone(), self.robot_refused(&robot.key));
                }
                let span = self
                    .given
                    .iter()
                    .find(|g| g.flag == flag)
                    .map_or_else(|| self.table_span.clone(), |g| g.span.clone());
                locator.error(
                    span,
                    format!(
                        "[{}]: unknown key `{}`; the keys of [{}] are: {}",
                        self.table,
                        flag.trim_start_matches("--").replace('-', "_"),
                        self.table,
                        self.accepted.join(", ")
                    ),
                )
            }
            ErrorKind::MissingRequiredArgument => {
                let keys: Vec<String> = invalid
                    .iter()
                    .map(|a| {
                        let flag = flag_of(a);
                        match self.help.iter().find(|(f, _)| *f == flag) {
                            Some((_, help)) => format!("{} ({help})", self.key_for(&flag)),
                            None => self.key_for(&flag),
                        }
                    })
                    .collect();
                locator.error(
                    self.table_span.clone(),
                    format!("[{}]: missing {}", self.table, keys.join(", ")),
                )
            }
            _ => {
                let first = error.to_string();
                let first = first
                    .lines()
                    .next()
                    .unwrap_or("")
                    .trim_start_matches("error: ")
                    .to_string();
                self.locate(locator, &first)
            }
        }
    }

    fn known_flag(&self, flag: &str) -> bool {
        self.known.iter().any(|k| format!("--{k}") == flag)
    }

    /// Why the table refuses a `[robot]` key.
    fn robot_refused(&self, key: &str) -> String {
        match self.table {
            "beam" => "[beam] takes no [robot]: it runs seed 000's own gantry beam (remove the \
                       [robot] table)"
                .to_string(),
            "singularity" => "[singularity] takes [robot] `builtin` or `file` (a DH description): \
                              `armkit singularity` has no URDF input"
                .to_string(),
            table => format!("[{table}] takes no {key}"),
        }
    }
}

/// The flags of `command` that `[robot]` supplies.
fn robot_flags(command: &clap::Command) -> Vec<String> {
    let has = |name: &str| command.get_arguments().any(|a| a.get_long() == Some(name));
    ROBOT_KEYS
        .iter()
        .map(|(flag, _)| *flag)
        // `--base` and `--tip` are the URDF's only where the command takes a URDF
        // (singularity's `--base` is fixed/attitude-held).
        .filter(|flag| !matches!(*flag, "--base" | "--tip") || has("urdf"))
        .filter(|flag| has(flag.trim_start_matches("--")))
        .map(str::to_string)
        .collect()
}
