//! Kinematics of the free-floating system: centre of mass, end-effector pose,
//! the generalized Jacobian and the momenta (seed 004, eqs 3-17).

use super::{check_pose, BaseMode, FreeFloatingModel, SpaceData};
use crate::dynamics::spatial::{Motion, SpatialInertia};
use crate::dynamics::JointAxis;
use crate::error::{check_finite_vector, Error, Result};
use crate::kinematics::forward_kinematics;
use crate::math::{skew, Matrix3, Matrix6xX, Pose, Vector3, Vector6};
use crate::model::LinkInertia;

/// Forward kinematics of every body at `(base, q)`: joint origins and axes,
/// link centres of mass and orientations, the system's centre of mass and the
/// end-effector pose, all in the inertial frame (seed 004, eqs 9-10).
pub(super) fn update_kinematics(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    base: &Pose,
    q: &[f64],
) -> Result<()> {
    data.check_model(model)?;
    check_pose(base).map_err(|reason| Error::invalid_argument("base_pose", reason))?;
    forward_kinematics(&model.arm, &mut data.arm, q)?;
    let mount = base * &model.base.mount;
    data.base_pose = *base;
    data.base_com = base.transform_point(&model.base.com);
    let mut first_moment = data.base_com * model.base.mass;
    for (i, frame) in data.arm.joint_frames().iter().enumerate() {
        let world = &mount * frame;
        let link = &model.links[i];
        data.joint_origins[i] = world.translation;
        data.joint_axes[i] = world.rotation.column(2).into_owned();
        data.link_coms[i] = world.transform_point(&link.com);
        data.link_rotations[i] = world.rotation;
        first_moment += data.link_coms[i] * link.mass;
    }
    data.end_effector = &mount * data.arm.end_effector_pose();
    data.com = first_moment / model.total_mass;
    Ok(())
}

/// The system's centre of mass `r_g = sum m_i r_i / M` (seed 004, eq 10), m,
/// inertial frame, with the base at `base` (pose of the base frame in the
/// inertial frame) and the joints at `q`. Allocates nothing.
pub fn center_of_mass(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    base: &Pose,
    q: &[f64],
) -> Result<Vector3<f64>> {
    update_kinematics(model, data, base, q)?;
    Ok(data.com)
}

/// End-effector pose in the inertial frame with the base at `base` and the
/// joints at `q`. Allocates nothing.
pub fn end_effector_pose(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    base: &Pose,
    q: &[f64],
) -> Result<Pose> {
    update_kinematics(model, data, base, q)?;
    Ok(data.end_effector)
}

/// The generalized Jacobian `J*` (6 x n): `[v_e; w_e] = J* q_dot`, the
/// end-effector origin's linear velocity (m/s) and angular velocity (rad/s)
/// in the inertial frame, for the base at `base` (base frame in the inertial
/// frame), joints at `q` and zero momentum as `mode` says.
///
/// See the module documentation for the derivation. Also fills
/// [`SpaceData::base_jacobian`] (the base twist per joint rate) and
/// [`SpaceData::com_jacobian`]. Joint limits are not checked. Allocates nothing.
///
/// Errors: `q` of the wrong size or not finite, a base pose that is not a
/// proper rigid transform, or `data` made for another model.
pub fn generalized_jacobian<'d>(
    model: &FreeFloatingModel,
    data: &'d mut SpaceData,
    base: &Pose,
    q: &[f64],
    mode: BaseMode,
) -> Result<&'d Matrix6xX<f64>> {
    update_kinematics(model, data, base, q)?;
    attitude_held_jacobian(model, data);
    if mode == BaseMode::FreeFloating {
        add_base_rotation(model, data)?;
    }
    Ok(&data.jacobian)
}

/// `J* = [J_v - J_g; J_w]` and `[v0; w0] = [-J_g; 0] q_dot` (seed 004, eqs
/// 16-17): the fixed-base Jacobian `J_m` (eq 6) minus the centre-of-mass
/// Jacobian `J_g = J_Tw / M` (eqs 13-14), built from suffix sums over the
/// links beyond each joint.
fn attitude_held_jacobian(model: &FreeFloatingModel, data: &mut SpaceData) {
    let end = data.end_effector.translation;
    let total = model.total_mass;
    let mut mass_beyond = 0.0;
    let mut moment_beyond = Vector3::zeros();
    for j in (0..data.dof).rev() {
        let link = &model.links[j];
        mass_beyond += link.mass;
        moment_beyond += data.link_coms[j] * link.mass;
        let axis = data.joint_axes[j];
        let origin = data.joint_origins[j];
        let (linear, angular, com_rate) = if model.arm.joints()[j].kind.is_rotational() {
            // sum_{i >= j} m_i k_j x (r_i - p_j) / M
            let com_rate = axis.cross(&(moment_beyond - origin * mass_beyond)) / total;
            (axis.cross(&(end - origin)), axis, com_rate)
        } else {
            (axis, Vector3::zeros(), axis * (mass_beyond / total))
        };
        data.com_jacobian.set_column(j, &com_rate);
        let mut column = data.jacobian.column_mut(j);
        column
            .fixed_rows_mut::<3>(0)
            .copy_from(&(linear - com_rate));
        column.fixed_rows_mut::<3>(3).copy_from(&angular);
        let mut base_column = data.base_jacobian.column_mut(j);
        base_column.fixed_rows_mut::<3>(0).copy_from(&(-com_rate));
        base_column.fixed_rows_mut::<3>(3).fill(0.0);
    }
}

/// Inertia of one body about the system's centre of mass, inertial axes:
/// `I - m [d]x [d]x` with `d = r - r_g` (parallel-axis theorem).
fn inertia_about(
    rotation: &Matrix3<f64>,
    local: &Matrix3<f64>,
    mass: f64,
    d: &Vector3<f64>,
) -> Matrix3<f64> {
    let s = skew(d);
    rotation * local * rotation.transpose() - s * s * mass
}

/// Adds the base rotation of the fully free case (Umetani-Yoshida): with
/// `L = H_w w0 + H_wq q_dot = 0`, `w0 = B_w q_dot`, `B_w = -H_w^-1 H_wq`, and
/// `J*` gains `[w0 x (p_e - r_g); w0]` per unit rate.
fn add_base_rotation(model: &FreeFloatingModel, data: &mut SpaceData) -> Result<()> {
    let com = data.com;
    let end = data.end_effector.translation;
    let base_origin = data.base_pose.translation;
    // Suffix sums S_j = sum_{i >= j} (I_i - m_i [d_i]x^2), s_j = sum_{i >= j} m_i d_i.
    let mut inertia_beyond = Matrix3::zeros();
    let mut moment_beyond = Vector3::zeros();
    for j in (0..data.dof).rev() {
        let link = &model.links[j];
        let d = data.link_coms[j] - com;
        inertia_beyond += inertia_about(&data.link_rotations[j], &link.inertia, link.mass, &d);
        moment_beyond += d * link.mass;
        let axis = data.joint_axes[j];
        let h = if model.arm.joints()[j].kind.is_rotational() {
            inertia_beyond * axis + moment_beyond.cross(&axis.cross(&(com - data.joint_origins[j])))
        } else {
            moment_beyond.cross(&axis)
        };
        data.momentum_jacobian.set_column(j, &h);
    }
    let base = &model.base;
    let d0 = data.base_com - com;
    data.system_inertia =
        inertia_beyond + inertia_about(&data.base_pose.rotation, &base.inertia, base.mass, &d0);
    // H_w is the inertia of the whole system about its centre of mass: positive
    // definite because the base's inertia is (checked by BaseBody::validate).
    let cholesky = data
        .system_inertia
        .cholesky()
        .ok_or_else(|| Error::Numerical {
            context: "free-floating generalized Jacobian".into(),
            reason: "the system's inertia about its centre of mass is not positive definite".into(),
        })?;
    for j in 0..data.dof {
        let h: Vector3<f64> = data.momentum_jacobian.column(j).into_owned();
        let w0 = -cholesky.solve(&h);
        let mut column = data.jacobian.column_mut(j);
        let linear = column.fixed_rows::<3>(0) + w0.cross(&(end - com));
        column.fixed_rows_mut::<3>(0).copy_from(&linear);
        let angular = column.fixed_rows::<3>(3) + w0;
        column.fixed_rows_mut::<3>(3).copy_from(&angular);
        // P = 0: v0 = (r_g - p0) x w0 - J_g q_dot.
        let mut base_column = data.base_jacobian.column_mut(j);
        let v0 = base_column.fixed_rows::<3>(0) + (com - base_origin).cross(&w0);
        base_column.fixed_rows_mut::<3>(0).copy_from(&v0);
        base_column.fixed_rows_mut::<3>(3).copy_from(&w0);
    }
    Ok(())
}

/// Linear and angular momentum of the whole system.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Momentum {
    /// Linear momentum `P = sum m_i v_i`, kg m/s, inertial frame.
    pub linear: Vector3<f64>,
    /// Angular momentum about the system's centre of mass,
    /// `L = sum I_i w_i + m_i (r_i - r_g) x v_i`, kg m^2/s, inertial frame.
    pub angular: Vector3<f64>,
}

/// Momentum of the system at `(base, q)` moving with base twist
/// `base_twist = [v0; w0]` (velocity of the base frame's origin, m/s, and
/// angular velocity, rad/s, inertial frame) and joint rates `q_dot`.
///
/// Computed body by body from each body's spatial velocity (seed 004, eqs 3
/// and 7) with the rigid-body algebra of [`crate::dynamics::spatial`]: the
/// base moves with `V_0 = (w0, v0 - w0 x p0)` about the inertial origin,
/// body i with `V_i = V_{i-1} + S_i q_dot_i` (`S_i` its joint's motion
/// subspace), and the system's spatial momentum `sum I_i V_i` holds `P` and
/// the angular momentum about the origin, moved to `r_g` at the end. This is
/// independent of the suffix sums of [`generalized_jacobian`]: a check of
/// `J*` and of simulated motions. O(n); allocates nothing.
pub fn momentum(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    base: &Pose,
    q: &[f64],
    base_twist: &Vector6<f64>,
    q_dot: &[f64],
) -> Result<Momentum> {
    check_finite_vector("joint_rates", q_dot, model.dof())?;
    crate::error::check_finite("base_twist", base_twist.as_slice())?;
    update_kinematics(model, data, base, q)?;
    let v0: Vector3<f64> = base_twist.fixed_rows::<3>(0).into_owned();
    let w0: Vector3<f64> = base_twist.fixed_rows::<3>(3).into_owned();
    let body = &model.base;
    let base_link = LinkInertia {
        mass: body.mass,
        com: body.com,
        inertia: body.inertia,
    };
    // Spatial velocities about the inertial origin: the linear part is the
    // velocity of the body point passing through the origin.
    let mut velocity = Motion::new(w0, v0 - w0.cross(&data.base_pose.translation));
    let mut total = SpatialInertia::from_link(&base_link, &data.base_pose).apply(&velocity);
    for (i, (link, &rate)) in model.links.iter().zip(q_dot).enumerate() {
        let frame = Pose::new(data.link_rotations[i], data.joint_origins[i]);
        let axis = JointAxis::of(model.arm.joints()[i].kind).in_frame(&frame);
        velocity = velocity + axis * rate;
        total += SpatialInertia::from_link(link, &frame).apply(&velocity);
    }
    // Force part: P; moment part: the angular momentum about the inertial
    // origin, shifted to r_g.
    let linear = total.force;
    let angular = total.moment - data.com.cross(&linear);
    Ok(Momentum { linear, angular })
}
