//! `armkit robots`: the built-in robots.

use clap::Args;

use crate::common::{print_json, CliResult, Outcome};

/// Lists the built-in robots with their DOF and a one-line description.
#[derive(Args, Debug)]
pub struct RobotsArgs {
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `armkit robots`.
pub fn run(args: &RobotsArgs) -> CliResult<Outcome> {
    if args.json {
        let list: Vec<_> = armkit::robots::BUILTIN
            .iter()
            .map(
                |r| serde_json::json!({"name": r.name, "dof": r.dof, "description": r.description, "frames": r.frames}),
            )
            .collect();
        print_json(&serde_json::Value::Array(list))?;
    } else {
        print!("{}", table());
    }
    Ok(Outcome::Success)
}

/// The text table of built-in robots.
pub fn table() -> String {
    let width = armkit::robots::names().map(str::len).max().unwrap_or(5);
    let mut out = format!("{:<width$} {:>3}  {}\n", "robot", "dof", "description");
    for r in armkit::robots::BUILTIN {
        out += &format!("{:<width$} {:>3}  {}\n", r.name, r.dof, r.description);
        out += &format!("{:<width$}      frames: {}\n", "", r.frames);
    }
    out
}
