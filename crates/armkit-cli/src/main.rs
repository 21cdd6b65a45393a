//! `armkit`: the command-line tool.

mod commands;
#[allow(dead_code)] // wired into the commands as they land
mod plot;
#[allow(dead_code)] // wired into `run` and `demo` as the scenarios land
mod report;
mod common;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use common::{CliResult, Outcome};

/// Kinematics, redundancy resolution, trajectories and MPC for robot manipulators.
#[derive(Parser, Debug)]
#[command(name = "armkit", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run the seed scenarios and write the report into out/.
    Demo(commands::demo::DemoArgs),
    /// List the built-in robots.
    Robots(commands::robots::RobotsArgs),
    /// Forward kinematics: the end-effector pose.
    Fk(commands::fk::FkArgs),
    /// The geometric Jacobian.
    Jacobian(commands::fk::JacobianArgs),
    /// Seed 000's flexible gantry beam: Table 1, error of a rigid model.
    Beam(commands::beam::BeamArgs),
    /// Free-floating space robot (seed 004): generalized Jacobian, simulation, tracking.
    Space(commands::space::SpaceArgs),
}

fn run(command: &Command) -> CliResult<Outcome> {
    match command {
        Command::Demo(args) => commands::demo::run(args),
        Command::Robots(args) => commands::robots::run(args),
        Command::Fk(args) => commands::fk::run_fk(args),
        Command::Jacobian(args) => commands::fk::run_jacobian(args),
        Command::Beam(args) => commands::beam::run(args),
        Command::Space(args) => commands::space::run(args),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(&cli.command) {
        Ok(Outcome::Success) => ExitCode::SUCCESS,
        Ok(Outcome::NotConverged) => ExitCode::from(3),
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
