//! The arm `armkit singularity` runs on: a fixed-base model, or seed 004's
//! space6r on its satellite with the attitude held.

use armkit::math::Pose;
use armkit::singularity::Manipulator;
use armkit::space::FreeFloatingModel;
use armkit::Model;

use super::{BaseArg, SingularityArgs};
use crate::common::{CliError, CliResult, RobotArgs};

/// The arm, and the free-floating system when the base is held.
pub(super) enum Plant {
    Fixed(Box<Model>),
    Held(Box<FreeFloatingModel>),
}

impl Plant {
    pub(super) fn arm(&self) -> &Model {
        match self {
            Plant::Fixed(model) => model,
            Plant::Held(system) => system.arm(),
        }
    }

    pub(super) fn manipulator(&self, base: Pose) -> Manipulator<'_> {
        match self {
            Plant::Fixed(model) => Manipulator::FixedBase(model),
            Plant::Held(system) => Manipulator::AttitudeHeld { system, base },
        }
    }
}

/// The arm, and the satellite when the base is held.
pub(super) fn load_plant(args: &SingularityArgs) -> CliResult<Plant> {
    match args.base {
        BaseArg::Fixed => {
            let robot = RobotArgs {
                robot: args.robot.clone(),
                robot_file: args.robot_file.clone(),
                ..RobotArgs::default()
            };
            if robot.robot.is_none() && robot.robot_file.is_none() {
                return Ok(Plant::Fixed(Box::new(armkit::robots::space6r()?)));
            }
            Ok(Plant::Fixed(Box::new(robot.load()?)))
        }
        BaseArg::AttitudeHeld => {
            let named_other = args.robot.as_deref().is_some_and(|r| r != "space6r");
            if named_other || args.robot_file.is_some() {
                return Err(CliError(
                    "--base attitude-held: the free-floating system is seed 004's space6r on its \
                     satellite; other arms work with --base fixed"
                        .into(),
                ));
            }
            Ok(Plant::Held(Box::new(
                armkit::robots::space6r_free_floating()?,
            )))
        }
    }
}
