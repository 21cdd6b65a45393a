//! Whole commands (`armkit dynamics`, `armkit ik`) run on a command line
//! built from the bytes: a robot, then options with values at the edges of
//! their checks. clap parses the line as the `armkit` binary does and the
//! command runs; an `Err` (a parse error or the command's own refusal) is
//! fine, a panic is a crash.

use std::path::PathBuf;

use armkit_cli::commands::{dynamics, ik};
use clap::Parser;

/// The robots a command line may name: built-ins with and without mass
/// properties, URDFs with a singular mass matrix (al5d), mimic joints and a
/// tip chosen by name.
const ROBOTS: &[&[&str]] = &[
    &["--robot", "ur5"],
    &["--robot", "panda"],
    &["--robot", "space6r"],
    &["--robot", "gantry9-flex"],
    &["--robot", "arm4"],
    &["--robot", "no-such-robot"],
    &["--urdf", "tests/data/urdf/ur5.urdf", "--tip", "ee_link"],
    &["--urdf", "tests/data/urdf/al5d.urdf"],
    &[
        "--urdf",
        "tests/data/urdf/mimicbot.urdf",
        "--tip",
        "fingertip",
    ],
    &[
        "--urdf",
        "tests/data/urdf/panda.urdf",
        "--tip",
        "panda_link8",
    ],
];

/// Number tokens: nine ordinary values first (a list of up to nine of them is
/// a plausible configuration), then the edges of the parsers and the checks.
const NUMBER_TOKENS: &[&str] = &[
    "0.25", "0.5", "-0.5", "0", "1", "-1", "pi/2", "-90deg", "2", "nan", "inf", "-inf", "1e300",
    "-1e300", "1e-300", "3.0e8", "",
];

/// A number list from one byte: its length (0 to 9 values) from the low
/// digit, the first token from the rest, the following tokens in order.
fn number_list(byte: u8) -> String {
    let count = usize::from(byte % 10);
    let first = usize::from(byte / 10);
    (0..count)
        .map(|i| NUMBER_TOKENS[(first + i) % NUMBER_TOKENS.len()])
        .collect::<Vec<_>>()
        .join(",")
}

/// Scalar values for the options that take one number or a count; the legal
/// ones stay small, so that no input asks for a long run by right (a budget
/// of an hour is legal, and not a bug).
const SCALARS: &[&str] = &[
    "0",
    "1",
    "2",
    "7",
    "-1",
    "0.5",
    "nan",
    "inf",
    "1e300",
    "1e-300",
    "100000000000",
    "18446744073709551615",
    "abc",
    "",
];

/// How an option's value is built from its byte.
#[derive(Clone, Copy)]
enum Value {
    /// A comma-separated number list.
    List,
    /// One of [`SCALARS`].
    Scalar,
    /// One of the given words.
    Word(&'static [&'static str]),
    /// A flag without a value.
    Flag,
}

const DYNAMICS_OPTIONS: &[(&str, Value)] = &[
    ("--q", Value::List),
    ("--v", Value::List),
    ("--a", Value::List),
    ("--tau", Value::List),
    ("--gravity", Value::List),
    ("--allow-out-of-limits", Value::Flag),
    ("--json", Value::Flag),
];

const IK_OPTIONS: &[(&str, Value)] = &[
    ("--pose", Value::List),
    ("--start", Value::List),
    (
        "--solver",
        Value::Word(&[
            "auto",
            "nr",
            "dls",
            "lm",
            "sri",
            "analytic",
            "closed-form",
            "x",
        ]),
    ),
    ("--explain", Value::Flag),
    ("--fixed-joint", Value::Scalar),
    ("--parameter", Value::Scalar),
    ("--sweep", Value::Scalar),
    ("--search", Value::Word(&["elimination", "1d", "2d", "x"])),
    ("--position-tolerance", Value::Scalar),
    ("--orientation-tolerance", Value::Scalar),
    (
        "--budget-ms",
        Value::Word(&["0", "1", "0.5", "-1", "nan", "1e300"]),
    ),
    ("--seed", Value::Scalar),
    ("--json", Value::Flag),
];

/// The command line `armkit <command> <robot> <options...>` the bytes
/// describe: the first byte picks the robot, then a byte pair per option
/// (which option, its value). An option may repeat: clap's refusal of a
/// repeated option is part of what is checked.
fn command_line(command: &str, options: &[(&str, Value)], data: &[u8]) -> Option<Vec<String>> {
    let [robot, rest @ ..] = data else {
        return None;
    };
    let mut line = vec!["armkit".to_string(), command.to_string()];
    line.extend(
        ROBOTS[usize::from(*robot) % ROBOTS.len()]
            .iter()
            .map(|word| repository_path(word)),
    );
    for pair in rest.chunks_exact(2) {
        let (name, value) = options[usize::from(pair[0]) % options.len()];
        let byte = pair[1];
        let value = match value {
            Value::List => Some(number_list(byte)),
            Value::Scalar => Some(SCALARS[usize::from(byte) % SCALARS.len()].to_string()),
            Value::Word(words) => Some(words[usize::from(byte) % words.len()].to_string()),
            Value::Flag => None,
        };
        match value {
            // `--opt=value` keeps a value that starts with '-' a value.
            Some(value) => line.push(format!("{name}={value}")),
            None => line.push(name.to_string()),
        }
    }
    Some(line)
}

/// A path under the repository, found from this crate's folder (`fuzz/` when
/// fuzzing, `crates/armkit-cli/` in the corpus replay); other words as given.
fn repository_path(word: &str) -> String {
    if !word.starts_with("tests/") {
        return word.to_string();
    }
    let mut folder = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    while !folder.join(word).exists() && folder.pop() {}
    folder.join(word).to_string_lossy().into_owned()
}

#[derive(Parser)]
struct DynamicsLine {
    #[command(subcommand)]
    command: DynamicsCommand,
}

#[derive(clap::Subcommand)]
enum DynamicsCommand {
    Dynamics(dynamics::DynamicsArgs),
}

#[derive(Parser)]
struct IkLine {
    #[command(subcommand)]
    command: IkCommand,
}

#[derive(clap::Subcommand)]
enum IkCommand {
    Ik(ik::IkArgs),
}

/// Parses `line` as clap would for the `armkit` binary, or `None` when clap
/// refuses it (a refusal is fine).
fn parse<T: Parser>(line: &[String]) -> Option<T> {
    T::try_parse_from(line).ok()
}

/// `armkit dynamics` on a command line built from the bytes.
pub fn dynamics_command(data: &[u8]) {
    let Some(line) = command_line("dynamics", DYNAMICS_OPTIONS, data) else {
        return;
    };
    if let Some(DynamicsLine {
        command: DynamicsCommand::Dynamics(args),
    }) = parse(&line)
    {
        let _ = dynamics::run(&args);
    }
}

/// `armkit ik` on a command line built from the bytes (the analytic
/// solver's options among the rest).
pub fn ik_command(data: &[u8]) {
    let Some(line) = command_line("ik", IK_OPTIONS, data) else {
        return;
    };
    if let Some(IkLine {
        command: IkCommand::Ik(args),
    }) = parse(&line)
    {
        let _ = ik::run(&args);
    }
}
