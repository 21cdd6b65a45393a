//! `armkit`: the command-line tool.

use std::process::ExitCode;

use armkit_cli::commands;
use armkit_cli::common::{accept_hyphen_values, CliResult, Outcome};
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

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
    Demo(commands::run::DemoArgs),
    /// Run one scenario file and write its report.
    Run(commands::run::RunArgs),
    /// List the built-in robots.
    Robots(commands::robots::RobotsArgs),
    /// A robot's chain: its joints, which mimic which, and the limits.
    Info(commands::info::InfoArgs),
    /// Forward kinematics: the end-effector pose.
    Fk(commands::fk::FkArgs),
    /// The geometric Jacobian.
    Jacobian(commands::fk::JacobianArgs),
    /// Rigid-body dynamics at one state: tau (RNEA), mass matrix, gravity and Coriolis torques, ddq (ABA) with --tau.
    Dynamics(commands::dynamics::DynamicsArgs),
    /// Inverse kinematics of one pose (numeric or closed form).
    Ik(commands::ik::IkArgs),
    /// IK benchmark: success rate and solve times on random reachable targets.
    BenchIk(commands::ik::BenchIkArgs),
    /// Seed 000's flexible gantry beam: Table 1, error of a rigid model.
    Beam(commands::beam::BeamArgs),
    /// Free-floating space robot (seed 004): generalized Jacobian, simulation, tracking.
    Space(commands::space::SpaceArgs),
    /// Redundancy resolution (seeds 000, 001): one motion distributed four ways, energy measure F.
    Redundancy(commands::redundancy::RedundancyArgs),
    /// Trajectories: joint-space profiles and Cartesian lines (seed 002), CSV and SVG plots.
    Traj(commands::traj::TrajArgs),
    /// Model-predictive motion to a target pose with joint limits (seed 000), CSV and SVG plots.
    Mpc(commands::mpc::MpcArgs),
    /// Singular values, singularity kind (wrist, elbow, shoulder) and manipulability ellipsoids at one configuration.
    Manipulability(commands::manipulability::ManipulabilityArgs),
    /// Reachability and capability map: position cells x tool orientations, by IK or FK sampling; .npz and SVG.
    Reach(commands::reach::ReachArgs),
    /// Singularity avoidance along a straight line (seed 004): plain, avoidance, DLS, SRI; tables, CSV and SVG.
    Singularity(commands::singularity::SingularityArgs),
    /// The robot in 3-D (at one configuration or along a trajectory CSV), one offline HTML file.
    View(commands::view::ViewArgs),
}

fn run(command: &Command) -> CliResult<Outcome> {
    match command {
        Command::Demo(args) => commands::run::demo(args),
        Command::Run(args) => commands::run::run(args),
        Command::Robots(args) => commands::robots::run(args),
        Command::Info(args) => commands::info::run(args),
        Command::Fk(args) => commands::fk::run_fk(args),
        Command::Jacobian(args) => commands::fk::run_jacobian(args),
        Command::Dynamics(args) => commands::dynamics::run(args),
        Command::Ik(args) => commands::ik::run(args),
        Command::BenchIk(args) => commands::ik::run_bench(args),
        Command::Beam(args) => commands::beam::run(args),
        Command::Space(args) => commands::space::run(args),
        Command::Redundancy(args) => commands::redundancy::run(args),
        Command::Traj(args) => commands::traj::run(args),
        Command::Mpc(args) => commands::mpc::run(args),
        Command::Manipulability(args) => commands::manipulability::run(args),
        Command::Reach(args) => commands::reach::run(args),
        Command::Singularity(args) => commands::singularity::run(args),
        Command::View(args) => commands::view::run(args),
    }
}

/// Rust ignores SIGPIPE, so a write to a closed pipe (`armkit ... | head`)
/// returns an error and `println!` panics. A command-line tool should end
/// quietly there, like other Unix tools: restore the default action.
#[cfg(unix)]
fn restore_default_sigpipe() {
    unsafe extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    const SIGPIPE: i32 = 13; // the same on Linux, macOS and the BSDs
    const SIG_DFL: usize = 0;
    // SAFETY: the C library's `signal` with a valid signal number and the
    // default disposition, called first in `main` before any thread starts.
    unsafe {
        signal(SIGPIPE, SIG_DFL);
    }
}

#[cfg(not(unix))]
fn restore_default_sigpipe() {}

fn main() -> ExitCode {
    restore_default_sigpipe();
    let matches = accept_hyphen_values(Cli::command()).get_matches();
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(cli) => cli,
        Err(error) => error.exit(),
    };
    match run(&cli.command) {
        Ok(Outcome::Success) => ExitCode::SUCCESS,
        Ok(Outcome::NotConverged) => ExitCode::from(3),
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
