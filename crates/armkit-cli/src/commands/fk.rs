//! `armkit fk` and `armkit jacobian`: forward kinematics and the geometric Jacobian.

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::Pose;
use clap::{Args, ValueEnum};

use crate::common::{
    format_rows, jacobian_rows, pose_rows, print_json, CliResult, ConfigurationArgs, Outcome,
};

/// Forward kinematics: the end-effector pose in the world frame.
#[derive(Args, Debug)]
pub struct FkArgs {
    #[command(flatten)]
    pub config: ConfigurationArgs,
}

/// The geometric Jacobian, rows [vx vy vz wx wy wz].
#[derive(Args, Debug)]
pub struct JacobianArgs {
    #[command(flatten)]
    pub config: ConfigurationArgs,
    /// Axes the Jacobian is expressed in.
    #[arg(long, value_enum, default_value_t = FrameArg::World)]
    pub frame: FrameArg,
}

/// `--frame` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum FrameArg {
    /// World (base) axes, like RTB jacob0.
    World,
    /// End-effector axes, like RTB jacobe.
    EndEffector,
}

/// Runs `armkit fk`.
pub fn run_fk(args: &FkArgs) -> CliResult<Outcome> {
    let (model, q) = args.config.load()?;
    let mut data = Data::new(&model);
    let pose = *forward_kinematics(&model, &mut data, &q)?;
    if args.config.json {
        let (roll, pitch, yaw) = pose.rpy();
        print_json(&serde_json::json!({
            "robot": model.name(),
            "q": q,
            "pose": pose_rows(&pose),
            "position": pose.translation.as_slice(),
            "rpy": [roll, pitch, yaw],
        }))?;
    } else {
        print!("{}", describe_pose(model.name(), &pose));
    }
    Ok(Outcome::Success)
}

/// The text form of an end-effector pose: matrix, position and roll-pitch-yaw.
pub fn describe_pose(robot: &str, pose: &Pose) -> String {
    let (roll, pitch, yaw) = pose.rpy();
    let p = pose.translation;
    format!(
        "{robot}: end-effector pose in the world frame (m)\n{}\nposition (m): {:.6} {:.6} {:.6}\nroll pitch yaw (rad, R = Rz(yaw) Ry(pitch) Rx(roll)): {:.6} {:.6} {:.6}\n",
        format_rows(&pose_rows(pose)),
        p.x,
        p.y,
        p.z,
        roll,
        pitch,
        yaw
    )
}

/// Runs `armkit jacobian`.
pub fn run_jacobian(args: &JacobianArgs) -> CliResult<Outcome> {
    let (model, q) = args.config.load()?;
    let mut data = Data::new(&model);
    let frame = match args.frame {
        FrameArg::World => JacobianFrame::World,
        FrameArg::EndEffector => JacobianFrame::EndEffector,
    };
    let j = jacobian(&model, &mut data, &q, frame)?;
    let rows = jacobian_rows(j);
    if args.config.json {
        print_json(&serde_json::json!({"robot": model.name(), "q": q, "jacobian": rows}))?;
    } else {
        println!(
            "{}: geometric Jacobian (6 x {}), rows vx vy vz wx wy wz, {:?} axes",
            model.name(),
            model.dof(),
            args.frame
        );
        println!("{}", format_rows(&rows));
    }
    Ok(Outcome::Success)
}
