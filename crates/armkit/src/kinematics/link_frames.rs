//! The world pose of every link frame along the chain (Pinocchio's `oMi`
//! after `forwardKinematics`, the Robotics Toolbox's `fkine_all`).

use super::{forward_kinematics, Data};
use crate::error::{Error, Result};
use crate::math::Pose;
use crate::model::Model;

/// Forward kinematics of every link frame: `frames[j]` is the world pose of
/// the frame of the link chain joint j moves ([`Model::link_frame_offsets`]:
/// a URDF's child link frame, a DH table's frame j), one per
/// [`Model::chain_joints`] (mimic joints included), named by
/// [`Model::chain_joints`]' `name`. Returns the end-effector pose, as
/// [`forward_kinematics`] does. Allocates nothing.
///
/// Errors: `q` of the wrong length or not finite, `frames` not of length
/// `model.chain_joints().len()`.
///
/// ```
/// use armkit::kinematics::{link_frames, Data};
/// use armkit::math::Pose;
/// let model = armkit::robots::by_name("ur5").unwrap();
/// let mut data = Data::new(&model);
/// let mut frames = vec![Pose::identity(); model.chain_joints().len()];
/// let tip = link_frames(&model, &mut data, &[0.0; 6], &mut frames).unwrap();
/// // DH frame 6 of the UR5 is its flange, the end effector (no tool).
/// assert!((frames[5].translation - tip.translation).norm() < 1e-15);
/// ```
pub fn link_frames(model: &Model, data: &mut Data, q: &[f64], frames: &mut [Pose]) -> Result<Pose> {
    let count = model.chain_joints().len();
    if frames.len() != count {
        return Err(Error::invalid_argument(
            "frames",
            format!(
                "expected {count} frames (one per chain joint), got {}",
                frames.len()
            ),
        ));
    }
    let tip = *forward_kinematics(model, data, q)?;
    for ((frame, joint), offset) in frames
        .iter_mut()
        .zip(data.joint_frames())
        .zip(model.link_frame_offsets())
    {
        *frame = *joint * *offset;
    }
    Ok(tip)
}
