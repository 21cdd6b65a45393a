//! Forward kinematics and Jacobians of many configurations in one call,
//! four at a time.
//!
//! A 6R chain's forward kinematics is a dependent chain of frame products:
//! on one configuration each step waits for the previous one. Across
//! configurations the steps are independent, so the kernels here take the
//! configurations four at a time, one per lane of an [`F64x4`] (structure
//! of arrays: every quantity of the chain is four values side by side, one
//! per configuration), and run the single call's steps (`frame.rs`, the
//! same source) on the four lanes at once. Where the processor has AVX2 and
//! FMA (detected at run time, as [`crate::dynamics::mass_matrix`] does) one
//! 256-bit instruction advances the four lanes, the multiply-adds fused,
//! the placements' coefficients kept in lanes (vector operands) and the
//! sine-cosine the fused one ([`crate::math::sin_cos_x4_fused`]); the
//! results then differ from the single call's in the last bits (the tests
//! bound them by 1e-14). Elsewhere the same code runs in 128-bit halves
//! and each configuration's result is the single call's, rounding for
//! rounding. Each block reads its rows of the input once and writes each
//! output row as a 4 x 4 transpose of the lanes.
//!
//! The caller owns every buffer: configurations in, poses or Jacobians out,
//! row-major (the layout of NumPy's `(N, dof)`, `(N, 4, 4)` and
//! `(N, 6, dof)` arrays), and a [`BatchData`] workspace made once. A call
//! allocates nothing.

use super::frame::Frame;
use super::JacobianFrame;
use crate::error::{Error, Result};
use crate::math::{sin_cos_x4_fused, F64x4, Lane, Lanes4, LANES};
use crate::model::{Model, PlacementForm};

/// Which instructions the kinematics kernels use (the single calls' chain,
/// through [`super::Data::with_instruction_set`], and the batched kernels).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum InstructionSet {
    /// AVX2 and FMA where the processor has them (detected at run time),
    /// the baseline otherwise.
    #[default]
    Detected,
    /// The target's baseline instructions (SSE2 on x86-64) everywhere: the
    /// reference the vector build is tested against.
    Baseline,
}

/// Workspace of the batched kernels, sized for one model: the lanes of one
/// block of four configurations. Create it once per model and thread.
#[derive(Clone, Debug)]
pub struct BatchData {
    dof: usize,
    instruction_set: InstructionSet,
    /// Chain joint positions, one per chain joint (coupled models).
    positions: Vec<F64x4>,
    /// One per chain joint: its placement and motion for the block.
    joints: Vec<LaneJoint>,
    /// The end effector's placement, coefficients in four lanes.
    end_form: PlacementForm<F64x4>,
    /// Each chain joint's axis (z column) and origin, for the Jacobian.
    axes: Vec<[F64x4; 3]>,
    origins: Vec<[F64x4; 3]>,
    /// Jacobian columns `[v; w]`, one per chain joint, then one per
    /// independent joint after the couplings.
    chain_columns: Vec<[F64x4; 6]>,
    columns: Vec<[F64x4; 6]>,
    /// One configuration's chain positions (coupled models).
    expanded: Vec<f64>,
}

/// A chain joint as the chain's loop reads it, all in one place (one
/// pointer to advance): its placement with every coefficient in four lanes
/// (rewritten by each call from the model; the products take them as
/// vector operands, no broadcast), and its motion for the current block.
#[derive(Clone, Debug)]
struct LaneJoint {
    form: PlacementForm<F64x4>,
    rotational: bool,
    /// The sine of the four positions (rotational), or the positions (m).
    first: F64x4,
    /// The cosine of the four positions (rotational).
    second: F64x4,
}

impl BatchData {
    /// A workspace for `model`, with the instructions detected at run time.
    pub fn new(model: &Model) -> Self {
        Self::with_instruction_set(model, InstructionSet::Detected)
    }

    /// A workspace for `model` that runs the kernels with `instruction_set`.
    pub fn with_instruction_set(model: &Model, instruction_set: InstructionSet) -> Self {
        let chain = model.chain_joints().len();
        let dof = model.dof();
        BatchData {
            dof,
            instruction_set,
            positions: vec![F64x4::default(); chain],
            joints: model
                .placement_forms()
                .iter()
                .zip(model.chain_kinds())
                .map(|(form, kind)| LaneJoint {
                    form: form.map(F64x4::splat),
                    rotational: kind.is_rotational(),
                    first: F64x4::default(),
                    second: F64x4::default(),
                })
                .collect(),
            end_form: model.end_effector_form().map(F64x4::splat),
            axes: vec![[F64x4::default(); 3]; chain],
            origins: vec![[F64x4::default(); 3]; chain],
            chain_columns: vec![[F64x4::default(); 6]; chain],
            columns: vec![[F64x4::default(); 6]; dof],
            expanded: vec![0.0; chain],
        }
    }

    /// The instructions this workspace's calls use.
    pub fn instruction_set(&self) -> InstructionSet {
        self.instruction_set
    }
}

/// Values per configuration of [`forward_kinematics_batch`]'s output: a
/// row-major 4 x 4 homogeneous transform.
pub const POSE_VALUES: usize = 16;

/// Forward kinematics of `q.len() / dof` configurations: `q` row-major,
/// configuration `k`'s joint `j` (rad or m, one per independent joint) at
/// `q[k * dof + j]`; writes configuration `k`'s end-effector pose in the
/// world frame as a row-major homogeneous 4 x 4 transform (m) at
/// `poses[16 k..16 k + 16]`. Each pose is [`super::forward_kinematics`]'s.
///
/// Errors (nothing is written then): `q`'s length not a multiple of dof,
/// `poses` not 16 values per configuration, a value of `q` not finite (the
/// message names its configuration and joint), `data` made for another
/// model, a pose that overflows to a non-finite value. Allocates nothing.
pub fn forward_kinematics_batch(
    model: &Model,
    data: &mut BatchData,
    q: &[f64],
    poses: &mut [f64],
) -> Result<()> {
    let count = check_batch(model, data, q, poses.len(), POSE_VALUES, "poses")?;
    run(model, data, q, count, Output::Poses(poses))
}

/// Geometric Jacobians (6 x dof, rows `[vx, vy, vz, wx, wy, wz]`, axes of
/// `frame`) of `q.len() / dof` configurations (`q` as in
/// [`forward_kinematics_batch`]): configuration `k`'s Jacobian row-major at
/// `jacobians[6 dof k..6 dof (k + 1)]`, each [`super::jacobian`]'s, the
/// couplings folded in. Errors as [`forward_kinematics_batch`] (`jacobians`
/// must hold 6 dof values per configuration). Allocates nothing.
pub fn jacobian_batch(
    model: &Model,
    data: &mut BatchData,
    q: &[f64],
    frame: JacobianFrame,
    jacobians: &mut [f64],
) -> Result<()> {
    let width = 6 * model.dof();
    let count = check_batch(model, data, q, jacobians.len(), width, "jacobians")?;
    run(model, data, q, count, Output::Jacobians(jacobians, frame))
}

/// What a batched call writes.
enum Output<'a> {
    Poses(&'a mut [f64]),
    Jacobians(&'a mut [f64], JacobianFrame),
}

/// Sizes (the kernels check finiteness); returns the number of configurations.
fn check_batch(
    model: &Model,
    data: &BatchData,
    q: &[f64],
    output: usize,
    width: usize,
    output_name: &'static str,
) -> Result<usize> {
    let dof = model.dof();
    if data.dof != dof || data.positions.len() != model.chain_joints().len() {
        return Err(Error::DimensionMismatch {
            what: "data (workspace made for another model)",
            expected: dof,
            got: data.dof,
        });
    }
    if q.len() % dof != 0 {
        return Err(Error::invalid_argument(
            "q",
            format!(
                "must hold {dof} values per configuration (row-major), got {} values",
                q.len()
            ),
        ));
    }
    let count = q.len() / dof;
    if output != count * width {
        return Err(Error::DimensionMismatch {
            what: output_name,
            expected: count * width,
            got: output,
        });
    }
    Ok(count)
}

/// Runs the kernel with the workspace's instructions.
fn run(model: &Model, data: &mut BatchData, q: &[f64], count: usize, output: Output) -> Result<()> {
    #[cfg(target_arch = "x86_64")]
    if data.instruction_set == InstructionSet::Detected
        && std::arch::is_x86_feature_detected!("avx2")
        && std::arch::is_x86_feature_detected!("fma")
    {
        // SAFETY: the function needs only the two features detected above.
        return unsafe { kernel_avx2_fma(model, data, q, count, output) };
    }
    kernel::<F64x4>(model, data, q, count, output)
}

/// [`kernel`] compiled for AVX2 and FMA on the AVX register lanes
/// (`math::Avx4`, whose values exist only here and in the other kernels
/// entered after the detection): every lane operation one 256-bit
/// instruction, the frame's multiply-adds fused.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn kernel_avx2_fma(
    model: &Model,
    data: &mut BatchData,
    q: &[f64],
    count: usize,
    output: Output,
) -> Result<()> {
    kernel::<crate::math::Avx4>(model, data, q, count, output)
}

/// Storage lanes to computing lanes. Loops, not `from_fn` or `map`: a
/// closure the compiler leaves out of line runs without the AVX kernel's
/// target features (see `frame.rs`), which halved the kernel's speed.
#[inline(always)]
fn load<L: Lanes4, const N: usize>(values: &[F64x4; N]) -> [L; N] {
    let mut out = [L::splat(0.0); N];
    for (lane, value) in out.iter_mut().zip(values) {
        *lane = L::from_array(value.0);
    }
    out
}

/// Computing lanes to storage lanes (a loop, as [`load`]).
#[inline(always)]
fn store<L: Lanes4, const N: usize>(values: &[L; N]) -> [F64x4; N] {
    let mut out = [F64x4::default(); N];
    for (stored, value) in out.iter_mut().zip(values) {
        *stored = F64x4(value.to_array());
    }
    out
}

/// The blocks of four configurations, base to tip on each, computed on
/// lanes `L` (the workspace keeps them as [`F64x4`]); the last block
/// repeats its last configuration in the lanes beyond `count` (computed,
/// not written). Each block reads its rows of `q` once (four rows side by
/// side, a joint's four values one lane load), takes every joint's
/// sine-cosine ([`sin_cos_x4_fused`]), runs the chain with the frame in
/// registers and writes each pose row as one 4 x 4 transpose.
#[inline(always)]
fn kernel<L: Lanes4>(
    model: &Model,
    data: &mut BatchData,
    q: &[f64],
    count: usize,
    mut output: Output,
) -> Result<()> {
    let dof = data.dof;
    if !all_finite::<L>(q) {
        return Err(non_finite_error(q, dof));
    }
    let map = model.joint_map();
    let identity = map.is_identity() && map.additive().is_empty();
    let sources = model.placement_forms().iter().zip(model.chain_kinds());
    for (joint, (form, kind)) in data.joints.iter_mut().zip(sources) {
        joint.form = form.map(F64x4::splat);
        joint.rotational = kind.is_rotational();
    }
    data.end_form = model.end_effector_form().map(F64x4::splat);
    let kinds = model.chain_kinds();
    let keep_joints = matches!(output, Output::Jacobians(..));
    let mut start = 0;
    while start < count {
        let lanes = LANES.min(count - start);
        let mut q_rows: [&[f64]; LANES] = [&[]; LANES];
        for (l, rows) in q_rows.iter_mut().enumerate() {
            let row = start + l.min(lanes - 1);
            *rows = &q[row * dof..(row + 1) * dof];
        }
        if identity {
            let joints = data
                .joints
                .iter_mut()
                .zip(q_rows[0].iter().zip(q_rows[1]))
                .zip(q_rows[2].iter().zip(q_rows[3]));
            for ((joint, (&a, &b)), (&c, &d)) in joints {
                set_motion(joint, L::from_array([a, b, c, d]));
            }
        } else {
            for (l, row) in q_rows.iter().enumerate() {
                map.expand(row, &mut data.expanded);
                for (position, &value) in data.positions.iter_mut().zip(&data.expanded) {
                    position.0[l] = value;
                }
            }
            for (joint, position) in data.joints.iter_mut().zip(&data.positions) {
                set_motion(joint, L::from_array(position.0));
            }
        }
        let frame = if keep_joints {
            chain::<L, true>(data)
        } else {
            chain::<L, false>(data)
        };
        check_finite_lanes(&frame.t, start, lanes)?;
        match &mut output {
            Output::Poses(poses) => write_poses(&frame, &mut poses[start * POSE_VALUES..], lanes),
            Output::Jacobians(jacobians, jacobian_frame) => {
                chain_columns::<L>(data, kinds, &frame.t);
                // Uncoupled: the chain's columns are the result.
                let columns = if identity {
                    &mut data.chain_columns
                } else {
                    map.fold_lane_columns(&q_rows, &data.chain_columns, &mut data.columns);
                    &mut data.columns
                };
                if *jacobian_frame == JacobianFrame::EndEffector {
                    for column in columns.iter_mut() {
                        *column = store(&to_end_effector_axes(&frame, &load(column)));
                    }
                }
                write_jacobians::<L>(columns, &mut jacobians[start * 6 * dof..], lanes);
            }
        }
        start += lanes;
    }
    Ok(())
}

/// A joint's motion for the block from its four positions: their
/// sine-cosine ([`sin_cos_x4_fused`]) or, prismatic, the positions.
#[inline(always)]
fn set_motion<L: Lanes4>(joint: &mut LaneJoint, position: L) {
    if joint.rotational {
        let (s, c) = sin_cos_x4_fused(position);
        joint.first = F64x4(s.to_array());
        joint.second = F64x4(c.to_array());
    } else {
        joint.first = F64x4(position.to_array());
    }
}

/// The block's end-effector frame, base to tip; with `KEEP`, each joint's
/// axis and origin into the workspace (the Jacobian).
#[inline(always)]
fn chain<L: Lanes4, const KEEP: bool>(data: &mut BatchData) -> Frame<L> {
    let mut frame = Frame::<L>::identity();
    if KEEP {
        let joints = data
            .joints
            .iter()
            .zip(data.axes.iter_mut().zip(data.origins.iter_mut()));
        for (joint, (axis, origin)) in joints {
            joint_step(joint, &mut frame);
            *axis = store(&frame.z);
            *origin = store(&frame.t);
        }
    } else {
        for joint in &data.joints {
            joint_step(joint, &mut frame);
        }
    }
    frame.place(&data.end_form);
    frame
}

/// The frame through one joint: its placement, then its motion.
#[inline(always)]
fn joint_step<L: Lanes4>(joint: &LaneJoint, frame: &mut Frame<L>) {
    frame.place(&joint.form);
    if joint.rotational {
        frame.rotate_about_z(L::from_array(joint.first.0), L::from_array(joint.second.0));
    } else {
        frame.translate_along_z(L::from_array(joint.first.0));
    }
}

/// Whether every value of `q` is finite: `v * 0` is zero for a finite `v`
/// and NaN otherwise, summed four lanes at a time in two chains (one fused
/// multiply-add per four values on the AVX lanes).
#[inline(always)]
fn all_finite<L: Lanes4>(q: &[f64]) -> bool {
    let zero = L::splat(0.0);
    let (mut even, mut odd) = (zero, zero);
    let mut pairs = q.chunks_exact(2 * LANES);
    for pair in &mut pairs {
        let (a, b) = pair.split_at(LANES);
        even = L::from_array([a[0], a[1], a[2], a[3]]).mul_add(zero, even);
        odd = L::from_array([b[0], b[1], b[2], b[3]]).mul_add(zero, odd);
    }
    (even + odd).all_below(f64::INFINITY) && pairs.remainder().iter().all(|v| v.is_finite())
}

/// The error naming `q`'s first value that is not finite.
#[cold]
fn non_finite_error(q: &[f64], dof: usize) -> Error {
    let at = q.iter().position(|v| !v.is_finite()).unwrap_or(0);
    Error::invalid_argument(
        "q",
        format!(
            "configuration {} (0-based), joint {}: must be finite, got {}",
            at / dof,
            at % dof,
            q[at]
        ),
    )
}

/// The chain's Jacobian columns from the stored axes and origins:
/// `[z_j x (p_e - p_j); z_j]` (rotational) or `[z_j; 0]` (prismatic), as
/// [`super::jacobian`].
#[inline(always)]
fn chain_columns<L: Lanes4>(data: &mut BatchData, kinds: &[crate::model::JointKind], end: &[L; 3]) {
    let zero = L::splat(0.0);
    let joints = data
        .chain_columns
        .iter_mut()
        .zip(kinds)
        .zip(data.axes.iter().zip(&data.origins));
    for ((column, kind), (z, p)) in joints {
        let z = load::<L, 3>(z);
        *column = store(&if kind.is_rotational() {
            let p = load::<L, 3>(p);
            let d = [end[0] - p[0], end[1] - p[1], end[2] - p[2]];
            let v = cross(&z, &d);
            [v[0], v[1], v[2], z[0], z[1], z[2]]
        } else {
            [z[0], z[1], z[2], zero, zero, zero]
        });
    }
}

#[inline(always)]
fn cross<L: Lane>(a: &[L; 3], b: &[L; 3]) -> [L; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A column `[v; w]` in the end-effector's axes: `[R' v; R' w]`.
#[inline(always)]
fn to_end_effector_axes<L: Lane>(frame: &Frame<L>, column: &[L; 6]) -> [L; 6] {
    let dot = |axis: &[L; 3], v: &[L]| axis[2].mul_add(v[2], axis[0].mul_add(v[0], axis[1] * v[1]));
    let (v, w) = column.split_at(3);
    [
        dot(&frame.x, v),
        dot(&frame.y, v),
        dot(&frame.z, v),
        dot(&frame.x, w),
        dot(&frame.y, w),
        dot(&frame.z, w),
    ]
}

/// As the single call's check: only the translation can overflow. The
/// lanes beyond the batch repeat its last configuration, so all four are
/// checked; the error names the first lane that overflowed.
#[inline(always)]
fn check_finite_lanes<L: Lanes4>(t: &[L; 3], start: usize, lanes: usize) -> Result<()> {
    if t.iter().all(|v| v.all_below(f64::INFINITY)) {
        return Ok(());
    }
    let t: [[f64; 4]; 3] = std::array::from_fn(|i| t[i].to_array());
    let lane = (0..lanes)
        .find(|&l| !t.iter().all(|v| v[l].is_finite()))
        .unwrap_or(0);
    Err(Error::Numerical {
        context: format!("forward kinematics of configuration {}", start + lane),
        reason: "the end-effector pose overflowed to a non-finite value (link lengths or joint positions too large)".into(),
    })
}

/// Scatter: lane l's pose into `out[16 l..16 l + 16]`, row-major 4 x 4.
/// Row i of every lane's pose is `(x_i, y_i, z_i, t_i)`: one transpose of
/// those four values gives the four lanes' rows, each one store.
#[inline(always)]
fn write_poses<L: Lanes4>(frame: &Frame<L>, out: &mut [f64], lanes: usize) {
    let mut rows = [[L::splat(0.0); LANES]; 3];
    for (i, row) in rows.iter_mut().enumerate() {
        *row = L::transpose([frame.x[i], frame.y[i], frame.z[i], frame.t[i]]);
    }
    for (pose, l) in out.chunks_exact_mut(POSE_VALUES).zip(0..LANES).take(lanes) {
        for (i, row) in rows.iter().enumerate() {
            pose[4 * i..4 * i + 4].copy_from_slice(&row[l].to_array());
        }
        pose[12..].copy_from_slice(&[0.0, 0.0, 0.0, 1.0]);
    }
}

/// Scatter: lane l's 6 x dof Jacobian, row-major, into `out`. Row r of a
/// lane's Jacobian is its columns' r-th values: four columns at a time, one
/// transpose gives four consecutive values of the row for each lane.
#[inline(always)]
fn write_jacobians<L: Lanes4>(columns: &[[F64x4; 6]], out: &mut [f64], lanes: usize) {
    let dof = columns.len();
    for (g, group) in columns.chunks(LANES).enumerate() {
        let first = g * LANES;
        for r in 0..6 {
            let mut values = [L::splat(0.0); LANES];
            for (value, column) in values.iter_mut().zip(group) {
                *value = L::from_array(column[r].0);
            }
            let lane_values = L::transpose(values);
            let at = r * dof + first;
            for (jacobian, l) in out.chunks_exact_mut(6 * dof).zip(0..LANES).take(lanes) {
                let values = lane_values[l].to_array();
                if let Some(slot) = jacobian
                    .get_mut(at..at + LANES)
                    .filter(|_| group.len() == LANES)
                {
                    slot.copy_from_slice(&values);
                } else {
                    for (slot, &value) in jacobian[at..at + group.len()].iter_mut().zip(&values) {
                        *slot = value;
                    }
                }
            }
        }
    }
}
