//! `armkit demo`: the main job. For now, the built-in robots and one FK.

use armkit::kinematics::{forward_kinematics, Data};
use clap::Args;

use crate::commands::{fk::describe_pose, robots::table};
use crate::common::{CliResult, Outcome};

/// Runs the shipped scenarios and writes the report.
#[derive(Args, Debug)]
pub struct DemoArgs {}

/// Runs `armkit demo`.
pub fn run(_args: &DemoArgs) -> CliResult<Outcome> {
    print!("{}", table());
    let model = armkit::robots::by_name("gantry9")?;
    let q = model.neutral_configuration();
    let mut data = Data::new(&model);
    let pose = *forward_kinematics(&model, &mut data, &q)?;
    println!("\nmid-range configuration q = {q:.3?}");
    print!("{}", describe_pose(model.name(), &pose));
    Ok(Outcome::Success)
}
