//! Forward kinematics and the geometric Jacobian.
//!
//! Algorithms are free functions on an immutable [`Model`] and a mutable
//! [`Data`] workspace sized once by [`Data::new`]; after that they allocate
//! nothing. Poses are in the world frame (the frame in which the model's base
//! transform is given); Jacobian rows are `[vx, vy, vz, wx, wy, wz]`: the
//! linear velocity of the end-effector origin and the angular velocity.
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let mut data = Data::new(&model);
//! let q = [0.1, -1.2, 1.0, -0.5, 1.5, 0.3];
//! let pose = forward_kinematics(&model, &mut data, &q).unwrap();
//! assert!(pose.translation.norm() < 1.5);
//! let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
//! assert_eq!(j.shape(), (6, 6));
//! ```

mod batch;
mod frame;
mod link_frames;
mod measures;

pub use batch::{forward_kinematics_batch, jacobian_batch, BatchData, InstructionSet, POSE_VALUES};
pub use link_frames::link_frames;
pub use measures::{condition_number, manipulability, singular_values, smallest_singular_value};

use crate::error::{Error, Result};
use crate::math::{sin_cos_slice, Matrix6xX, Pose, Vector3};
use crate::model::{JointKind, Model, PlacementForm};
use frame::Frame;

/// The frame in whose axes a Jacobian is expressed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JacobianFrame {
    /// World axes, velocity of the end-effector origin: Robotics Toolbox
    /// `jacob0`, Pinocchio `LOCAL_WORLD_ALIGNED`.
    World,
    /// End-effector axes, velocity of its origin: Robotics Toolbox `jacobe`,
    /// Pinocchio `LOCAL`.
    EndEffector,
}

/// Workspace for the kinematics algorithms, sized for one model.
///
/// Holds the results of the last call: every joint frame, the end-effector
/// pose and the Jacobian. Create it once per model and thread.
#[derive(Clone, Debug)]
pub struct Data {
    dof: usize,
    instruction_set: InstructionSet,
    /// One per chain joint (mimic joints included).
    effective_positions: Vec<f64>,
    /// `(sin, cos)` of each effective joint position (used for rotational joints).
    joint_sin_cos: Vec<(f64, f64)>,
    joint_frames: Vec<Pose>,
    end_effector: Pose,
    jacobian: Matrix6xX<f64>,
    /// The chain's Jacobian `J0` (6 x chain joints) before `J = J0 M`; empty
    /// when the chain's joints are the configuration's (no mimic joint).
    chain_jacobian: Matrix6xX<f64>,
}

impl Data {
    /// A workspace for `model`, with the instructions detected at run time.
    pub fn new(model: &Model) -> Self {
        Self::with_instruction_set(model, InstructionSet::Detected)
    }

    /// A workspace for `model` whose calls use `instruction_set`
    /// ([`InstructionSet::Baseline`] forces the reference build, to compare
    /// it with the AVX2 + FMA one; both give the same bits).
    pub fn with_instruction_set(model: &Model, instruction_set: InstructionSet) -> Self {
        let dof = model.dof();
        let chain = model.chain_joints().len();
        let folded = if model.joint_map().is_identity() {
            0
        } else {
            chain
        };
        Data {
            dof,
            instruction_set,
            effective_positions: vec![0.0; chain],
            joint_sin_cos: vec![(0.0, 1.0); chain],
            joint_frames: vec![Pose::identity(); chain],
            end_effector: Pose::identity(),
            jacobian: Matrix6xX::zeros(dof),
            chain_jacobian: Matrix6xX::zeros(folded),
        }
    }

    /// The instructions this workspace's calls use.
    pub fn instruction_set(&self) -> InstructionSet {
        self.instruction_set
    }

    /// World pose of each chain joint's frame after its motion (one per
    /// [`Model::chain_joints`], mimic joints included), from the last
    /// forward kinematics: origin on the joint axis, z along the axis. For a
    /// modified-DH model these are the DH frames; for a standard-DH model,
    /// joint j's frame is DH frame j-1 turned by the joint.
    pub fn joint_frames(&self) -> &[Pose] {
        &self.joint_frames
    }

    /// World pose of the end-effector (tool) frame from the last forward kinematics.
    pub fn end_effector_pose(&self) -> &Pose {
        &self.end_effector
    }

    /// The Jacobian from the last call to [`jacobian`] (6 x dof).
    pub fn jacobian(&self) -> &Matrix6xX<f64> {
        &self.jacobian
    }

    /// Joint positions the chain was evaluated at, one per chain joint, after
    /// the couplings (mimic joints from their leaders, the gantry's
    /// `d3' = d3 + w(d2)`); equal to `q` for uncoupled models.
    pub fn effective_positions(&self) -> &[f64] {
        &self.effective_positions
    }

    #[inline]
    fn check_model(&self, model: &Model) -> Result<()> {
        if self.dof != model.dof() || self.joint_frames.len() != model.chain_joints().len() {
            return Err(Error::DimensionMismatch {
                what: "data (workspace made for another model)",
                expected: model.dof(),
                got: self.dof,
            });
        }
        Ok(())
    }
}

/// Forward kinematics: every joint frame and the end-effector pose, in the
/// world frame, for joint positions `q` (rad or m, one per independent
/// joint; the couplings give the chain's other joints).
///
/// Returns the end-effector pose. Errors: `q` of the wrong size or not
/// finite, `data` made for another model, or a pose that overflows to an
/// infinity or NaN (link lengths or prismatic positions near `f64::MAX`).
/// Limits are not checked here (see [`Model::check_limits`]). Allocates
/// nothing (on success).
pub fn forward_kinematics<'d>(model: &Model, data: &'d mut Data, q: &[f64]) -> Result<&'d Pose> {
    data.check_model(model)?;
    model.check_joint_positions(q)?;
    model.joint_map().expand(q, &mut data.effective_positions);
    let mut frame = evaluate_chain(model, data);
    frame.place(model.end_effector_form());
    data.end_effector = frame.to_pose();
    check_pose_is_finite(&data.end_effector)?;
    Ok(&data.end_effector)
}

/// The chain's trigonometry and product ([`chain_kernel`]) in the build the
/// workspace's [`InstructionSet`] and the processor allow: with AVX2 and FMA
/// (detected at run time, as the batched kernels and the mass matrix do)
/// the six to nine sine-cosine pairs of a chain go four to a 256-bit
/// register (`math::Avx4`) and every product is a three-operand
/// instruction; the results are the baseline build's, bit for bit (no
/// operation is fused: the sine-cosine fuses nothing, and Rust never
/// contracts the chain's `f64` products).
fn evaluate_chain(model: &Model, data: &mut Data) -> Frame<f64> {
    #[cfg(target_arch = "x86_64")]
    if data.instruction_set == InstructionSet::Detected
        && std::arch::is_x86_feature_detected!("avx2")
        && std::arch::is_x86_feature_detected!("fma")
    {
        // SAFETY: the function needs only the two features detected above.
        return unsafe { chain_avx2_fma(model, data) };
    }
    chain_baseline(model, data)
}

/// [`chain_kernel`] in the target's baseline instructions. Kept out of
/// line on purpose: compiled on its own, the loop keeps the frame in
/// registers whatever the caller inlines around it.
#[inline(never)]
fn chain_baseline(model: &Model, data: &mut Data) -> Frame<f64> {
    sin_cos_slice(&data.effective_positions, &mut data.joint_sin_cos);
    chain_kernel(model, data)
}

/// [`chain_kernel`] compiled for AVX2 and FMA, the sine-cosine four joints
/// per AVX register (the module `math::lanes_avx`'s values exist only in
/// functions entered after the detection, as this one).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn chain_avx2_fma(model: &Model, data: &mut Data) -> Frame<f64> {
    crate::math::sin_cos_slice_x4::<crate::math::Avx4>(
        &data.effective_positions,
        &mut data.joint_sin_cos,
    );
    chain_kernel(model, data)
}

/// The chain's product from the sine-cosine of every chain joint (computed
/// before, all at once: the calls are independent, so the processor
/// overlaps them, where inside the chain each would wait for the previous
/// frame product); returns the last joint's frame.
#[inline(always)]
fn chain_kernel(model: &Model, data: &mut Data) -> Frame<f64> {
    chain_frames(
        model.placement_forms(),
        model.chain_kinds(),
        &data.joint_sin_cos,
        &data.effective_positions,
        &mut data.joint_frames,
    )
}

/// The chain's product, base to tip: joint j's frame is the previous one
/// times its placement (multiplied in its form, `model::PlacementForm`),
/// turned by its angle (rotational: two columns mixed) or moved along its
/// z axis (prismatic); written into `frames`, the last one returned. One
/// pass over slices of equal length (the caller's `check_model`), without
/// indices or bounds checks; the steps are the batched kernels' (`frame.rs`).
#[inline(always)]
fn chain_frames(
    forms: &[PlacementForm],
    kinds: &[JointKind],
    sin_cos: &[(f64, f64)],
    positions: &[f64],
    frames: &mut [Pose],
) -> Frame<f64> {
    let joints = forms
        .iter()
        .zip(kinds)
        .zip(sin_cos)
        .zip(positions)
        .zip(frames.iter_mut());
    let mut frame = Frame::<f64>::identity();
    for ((((form, kind), &(s, c)), &position), joint_frame) in joints {
        frame.place(form);
        if kind.is_rotational() {
            frame.rotate_about_z(s, c);
        } else {
            frame.translate_along_z(position);
        }
        *joint_frame = frame.to_pose();
    }
    frame
}

/// Finite inputs can still overflow (lengths near `f64::MAX`); a non-finite
/// pose is an error rather than a result. Only the translation can
/// overflow: rotations are products of orthonormal factors with entries in
/// [-1, 1]; every joint frame feeds the end effector's translation (an
/// infinity stays infinite or becomes NaN), so checking it covers the chain
/// and the Jacobian.
fn check_pose_is_finite(pose: &Pose) -> Result<()> {
    if pose.translation.iter().all(|v| v.is_finite()) {
        return Ok(());
    }
    Err(Error::Numerical {
        context: "forward kinematics".into(),
        reason: "the end-effector pose overflowed to a non-finite value (link lengths or joint positions too large)".into(),
    })
}

/// Forward kinematics, then the geometric Jacobian (6 x dof) of the
/// end-effector frame, rows `[v; w]`, in the axes of `frame`.
///
/// Column j is `[z_j x (p_e - p_j); z_j]` for a rotational joint and
/// `[z_j; 0]` for a prismatic one (`z_j`, `p_j` the joint's axis and origin,
/// `p_e` the end-effector origin), for each chain joint; the couplings then
/// fold these into one column per independent joint, `J = J0 M` with
/// `M = d q_chain / d q` (a mimic joint's column times its multiplier added
/// to its leader's; seed 000, eq 10 for the beam). Allocates nothing.
pub fn jacobian<'d>(
    model: &Model,
    data: &'d mut Data,
    q: &[f64],
    frame: JacobianFrame,
) -> Result<&'d Matrix6xX<f64>> {
    forward_kinematics(model, data, q)?;
    let end = data.end_effector.translation;
    let map = model.joint_map();
    // Without mimic joints the chain's columns are the result, written
    // straight into it (the additive couplings then fold in place).
    let chain_jacobian = if map.is_identity() {
        &mut data.jacobian
    } else {
        &mut data.chain_jacobian
    };
    let joints = data
        .joint_frames
        .iter()
        .zip(model.chain_kinds())
        .zip(chain_jacobian.column_iter_mut());
    for ((joint_frame, kind), mut column) in joints {
        let axis: Vector3<f64> = joint_frame.rotation.column(2).into_owned();
        if kind.is_rotational() {
            let linear = axis.cross(&(end - joint_frame.translation));
            column.fixed_rows_mut::<3>(0).copy_from(&linear);
            column.fixed_rows_mut::<3>(3).copy_from(&axis);
        } else {
            column.fixed_rows_mut::<3>(0).copy_from(&axis);
            column.fixed_rows_mut::<3>(3).fill(0.0);
        }
    }
    map.fold_jacobian(q, &data.chain_jacobian, &mut data.jacobian);
    if frame == JacobianFrame::EndEffector {
        let rt = data.end_effector.rotation.transpose();
        for mut column in data.jacobian.column_iter_mut() {
            let linear = rt * column.fixed_rows::<3>(0);
            let angular = rt * column.fixed_rows::<3>(3);
            column.fixed_rows_mut::<3>(0).copy_from(&linear);
            column.fixed_rows_mut::<3>(3).copy_from(&angular);
        }
    }
    Ok(&data.jacobian)
}
