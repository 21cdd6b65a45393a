//! `armkit fk` and `armkit jacobian`: forward kinematics and the geometric Jacobian.

use armkit::kinematics::{forward_kinematics, jacobian, link_frames, Data, JacobianFrame};
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
    /// Also the pose of every link frame along the chain, named by its joint
    /// (a URDF's child link frame, Pinocchio's oMi; a DH table's frame j).
    #[arg(long)]
    pub all_frames: bool,
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
    let mut frames = Vec::new();
    if args.all_frames {
        frames = vec![Pose::identity(); model.chain_joints().len()];
        link_frames(&model, &mut data, &q, &mut frames)?;
    }
    let names = model.chain_joints().iter().map(|j| j.name.as_str());
    if args.config.json {
        let mut value = pose_json(&pose);
        value["robot"] = model.name().into();
        value["q"] = q.clone().into();
        if args.all_frames {
            value["frames"] = names
                .zip(&frames)
                .map(|(name, frame)| {
                    let mut entry = pose_json(frame);
                    entry["name"] = name.into();
                    entry
                })
                .collect();
        }
        print_json(&value)?;
    } else {
        print!("{}", describe_pose(model.name(), &pose));
        if args.all_frames {
            println!(
                "link frames in the world frame, one per joint (position m, roll pitch yaw rad):"
            );
            let width = names.clone().map(str::len).max().unwrap_or(0);
            for (name, frame) in names.zip(&frames) {
                let (roll, pitch, yaw) = frame.rpy();
                let p = frame.translation;
                println!(
                    "  {name:width$}  {:>10.6} {:>10.6} {:>10.6}   {:>9.6} {:>9.6} {:>9.6}",
                    p.x, p.y, p.z, roll, pitch, yaw
                );
            }
        }
    }
    Ok(Outcome::Success)
}

/// A pose as JSON: `pose` (4x4 rows), `position`, `rpy`.
fn pose_json(pose: &Pose) -> serde_json::Value {
    let (roll, pitch, yaw) = pose.rpy();
    serde_json::json!({
        "pose": pose_rows(pose),
        "position": pose.translation.as_slice(),
        "rpy": [roll, pitch, yaw],
    })
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
