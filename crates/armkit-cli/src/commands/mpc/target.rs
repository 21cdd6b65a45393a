//! The set-up of an `armkit mpc --target` run from its flags (robot,
//! target, start, planner, simulation options), shared by the command and a
//! scenario's `[mpc]` table without `example`.

use armkit::mpc::scenario::SimulationOptions;
use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights, VelocityWeights, MAX_SAMPLE_TIME};

use super::MpcArgs;
use crate::common::{
    parse_fixed_numbers, parse_joint_positions, parse_pose, positive, CliError, CliResult,
    LimitPolicy,
};

fn task_weights(text: &str, terminal_factor: f64) -> CliResult<TaskWeights> {
    let tracking: [f64; 6] = match text.trim() {
        "position" => [10.0, 10.0, 10.0, 0.0, 0.0, 0.0],
        "pose" => [10.0; 6],
        other => {
            let v = parse_fixed_numbers(other, "--weights", 6)?;
            [v[0], v[1], v[2], v[3], v[4], v[5]]
        }
    };
    if !(terminal_factor.is_finite() && terminal_factor >= 0.0) {
        return Err(CliError(format!(
            "--terminal-factor: must be finite and >= 0, got {terminal_factor}"
        )));
    }
    Ok(TaskWeights {
        tracking,
        terminal: tracking.map(|w| w * terminal_factor),
    })
}

/// The MPC of a `--target` run, set up from the flags: the robot, the
/// target, the start, the planner and the simulation options (shared by the
/// command and a scenario's `[mpc]` table without `example`).
pub(crate) struct TargetSetup {
    pub model: armkit::Model,
    pub target: armkit::math::Pose,
    pub start: Vec<f64>,
    pub planner: MpcPlanner,
    /// The robot the run moves when it is not the planner's model
    /// (`--plant-robot`, or the true robot under `--link-length-error`).
    pub plant_model: Option<armkit::Model>,
    pub simulation: SimulationOptions,
}

/// Parses the flags of a `--target` run and builds its planner.
pub(crate) fn target_setup(args: &MpcArgs) -> CliResult<TargetSetup> {
    let model = args.robot.load()?;
    let target_text = args
        .target
        .as_deref()
        .ok_or_else(|| CliError("--target is required (or --example)".into()))?;
    let target = parse_pose(target_text, "--target")?;
    let start = match &args.start {
        Some(text) => parse_joint_positions(text, &model, LimitPolicy::Allow)?,
        None => model.neutral_configuration(),
    };
    let priorities = match &args.priorities {
        Some(text) => Some(parse_fixed_numbers(text, "--priorities", model.dof())?),
        None => None,
    };
    if !(args.dt.is_finite() && args.dt > 0.0 && args.dt <= MAX_SAMPLE_TIME) {
        return Err(CliError(format!(
            "--dt: must be > 0 and <= {MAX_SAMPLE_TIME} s, got {} s",
            armkit::error::brief(args.dt)
        )));
    }
    let mut options = MpcOptions {
        horizon: args.horizon,
        sample_time: args.dt,
        task_weights: task_weights(&args.weights, args.terminal_factor)?,
        increment_weights: priorities,
        priority: args.priority_mode.into(),
        velocity_weights: VelocityWeights::Proportional(args.velocity_weight),
        ..MpcOptions::default()
    };
    args.apply(&mut options);
    let simulation = args.with_tolerances(SimulationOptions {
        max_steps: args.max_steps,
        plant: args.plant()?,
        ..SimulationOptions::default()
    })?;
    let (planner_model, plant_model) = mismatch(args, &model)?;
    let planner = MpcPlanner::new(planner_model.as_ref().unwrap_or(&model), options)?;
    Ok(TargetSetup {
        model,
        target,
        start,
        planner,
        plant_model,
        simulation,
    })
}

impl MpcArgs {
    /// `simulation` with the tolerances the flags set (each finite and > 0).
    pub(crate) fn with_tolerances(
        &self,
        mut simulation: SimulationOptions,
    ) -> CliResult<SimulationOptions> {
        for (flag, value, field) in [
            (
                "--position-tolerance",
                self.position_tolerance,
                &mut simulation.position_tolerance,
            ),
            (
                "--orientation-tolerance",
                self.orientation_tolerance,
                &mut simulation.orientation_tolerance,
            ),
            (
                "--velocity-tolerance",
                self.velocity_tolerance,
                &mut simulation.velocity_tolerance,
            ),
        ] {
            if let Some(value) = value {
                *field = positive(flag, value)?;
            }
        }
        Ok(simulation)
    }
}

/// The planner's model when it is not the robot's (`--link-length-error`)
/// and the plant's when it is not the planner's (`--plant-robot`, or the
/// true robot under a link-length error).
fn mismatch(
    args: &MpcArgs,
    model: &armkit::Model,
) -> CliResult<(Option<armkit::Model>, Option<armkit::Model>)> {
    let planner_model = match args.link_length_error {
        Some(e) if !(e.is_finite() && e > -1.0) => {
            return Err(CliError(format!(
                "--link-length-error: must be finite and > -1, got {e}"
            )))
        }
        Some(e) => Some(armkit::mpc::with_link_length_error(model, e)?),
        None => None,
    };
    let plant_model = match &args.plant_robot {
        Some(name) => {
            let plant = armkit::robots::by_name(name)?;
            if plant.dof() != model.dof() {
                return Err(CliError(format!(
                    "--plant-robot: {name} has {} joints, the planner's robot {}",
                    plant.dof(),
                    model.dof()
                )));
            }
            Some(plant)
        }
        None => planner_model.as_ref().map(|_| model.clone()),
    };
    Ok((planner_model, plant_model))
}
