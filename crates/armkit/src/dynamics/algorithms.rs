//! RNEA, CRBA, ABA and what derives from them, in the world frame.

use super::spatial::{Force, Motion};
use super::DynamicsData;
use crate::error::{check_finite_vector, Error, Result};
use crate::math::{DMatrix, Matrix6, Vector3, Vector6};
use crate::model::Model;

/// Inverse dynamics by the recursive Newton-Euler algorithm (Featherstone,
/// table 5.1): the joint torques `tau = M(q) a + C(q, v) v + g(q)` (N m, or
/// N for prismatic joints) that give joint accelerations `a` at positions
/// `q` and velocities `v`, under the workspace's gravity.
///
/// Returns one torque per joint (also kept in [`DynamicsData::torques`]).
/// Errors: a slice of the wrong size or not finite, `data` made for another
/// model, a link without mass properties, a coupled model. Allocates nothing.
pub fn rnea<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<&'d [f64]> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    check_finite_vector("joint_accelerations", a, model.dof())?;
    data.update_bodies(model, q)?;
    let gravity = data.gravity;
    newton_euler(data, v, a, Some(&gravity));
    Ok(&data.tau)
}

/// Gravity torques `g(q) = RNEA(q, 0, 0)` (N m or N): the torques that hold
/// the arm still against the workspace's gravity, equal to the gradient of
/// [`super::potential_energy`]. Errors as [`rnea`]. Allocates nothing.
pub fn gravity_torques<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
) -> Result<&'d [f64]> {
    data.update_bodies(model, q)?;
    let gravity = data.gravity;
    let zeros = std::mem::take(&mut data.zeros);
    newton_euler(data, &zeros, &zeros, Some(&gravity));
    data.zeros = zeros;
    Ok(&data.tau)
}

/// Coriolis and centrifugal torques `C(q, v) v = RNEA(q, v, 0)` without
/// gravity (N m or N). Errors as [`rnea`]. Allocates nothing.
pub fn coriolis_torques<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
    v: &[f64],
) -> Result<&'d [f64]> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    data.update_bodies(model, q)?;
    let zeros = std::mem::take(&mut data.zeros);
    newton_euler(data, v, &zeros, None);
    data.zeros = zeros;
    Ok(&data.tau)
}

/// Non-linear effects `C(q, v) v + g(q) = RNEA(q, v, 0)` (N m or N), what
/// Pinocchio calls `nonLinearEffects`. Errors as [`rnea`]. Allocates nothing.
pub fn nonlinear_effects<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
    v: &[f64],
) -> Result<&'d [f64]> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    data.update_bodies(model, q)?;
    let gravity = data.gravity;
    let zeros = std::mem::take(&mut data.zeros);
    newton_euler(data, v, &zeros, Some(&gravity));
    data.zeros = zeros;
    Ok(&data.tau)
}

/// The two passes of the RNEA on bodies already placed by
/// `update_bodies`; `gravity` `None` leaves it out.
fn newton_euler(data: &mut DynamicsData, v: &[f64], a: &[f64], gravity: Option<&Vector3<f64>>) {
    // Gravity as an upward acceleration of the base (Featherstone 5.3):
    // every body then feels it through its inertia.
    let mut velocity = Motion::ZERO;
    let mut acceleration = Motion::new(Vector3::zeros(), gravity.map_or(Vector3::zeros(), |g| -g));
    for (((axis, body), force), (&qd, &qdd)) in data
        .axes
        .iter()
        .zip(&data.bodies)
        .zip(data.forces.iter_mut())
        .zip(v.iter().zip(a))
    {
        let joint_velocity = *axis * qd;
        velocity = velocity + joint_velocity;
        acceleration = acceleration + *axis * qdd + velocity.cross(&joint_velocity);
        let momentum = body.apply(&velocity);
        *force = body.apply(&acceleration) + velocity.cross_force(&momentum);
    }
    let mut transmitted = Force::ZERO;
    for ((axis, force), tau) in data
        .axes
        .iter()
        .zip(&data.forces)
        .zip(data.tau.iter_mut())
        .rev()
    {
        transmitted += *force;
        *tau = axis.dot(&transmitted);
    }
}

/// The joint-space inertia (mass) matrix `M(q)` by the composite rigid body
/// algorithm (Featherstone, table 6.2): n x n, symmetric positive definite,
/// kg m^2 (kg for two prismatic joints, kg m for mixed entries).
///
/// `M[i][j] = S_i' Ic_j S_j` for `i <= j`, with `Ic_j` the inertia of bodies
/// j..n-1 together (world frame). Also kept in [`DynamicsData::mass_matrix`].
/// Errors as [`rnea`]. Allocates nothing.
pub fn mass_matrix<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
) -> Result<&'d DMatrix<f64>> {
    data.update_bodies(model, q)?;
    composite_rigid_body(data);
    Ok(&data.mass_matrix)
}

fn composite_rigid_body(data: &mut DynamicsData) {
    let n = data.dof;
    let mut composite = super::spatial::SpatialInertia::ZERO;
    for (body, slot) in data.bodies.iter().zip(data.composite.iter_mut()).rev() {
        composite += *body;
        *slot = composite;
    }
    // Column j, rows 0..=j, of the column-major buffer: S_i' (Ic_j S_j).
    let m = data.mass_matrix.as_mut_slice();
    for (j, ((composite, axis), column)) in data
        .composite
        .iter()
        .zip(&data.axes)
        .zip(m.chunks_exact_mut(n))
        .enumerate()
    {
        let force = composite.apply(axis);
        for (value, axis_i) in column.iter_mut().zip(&data.axes[..=j]) {
            *value = axis_i.dot(&force);
        }
    }
    // The lower triangle mirrors the upper: M[j][i] = M[i][j].
    for i in 0..n {
        for j in i + 1..n {
            m[i * n + j] = m[j * n + i];
        }
    }
}

/// The inverse of the mass matrix, `M(q)^-1` (n x n), by a Cholesky
/// factorization of [`mass_matrix`] done in place. Errors as [`rnea`], and
/// [`Error::Numerical`] if `M` is not positive definite (a body without
/// inertia about its own joint axis). Allocates nothing.
pub fn mass_matrix_inverse<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
) -> Result<&'d DMatrix<f64>> {
    mass_matrix(model, data, q)?;
    let n = data.dof;
    // Lower Cholesky factor L (M = L L') into the inverse's buffer.
    let l = &mut data.mass_matrix_inverse;
    l.copy_from(&data.mass_matrix);
    for j in 0..n {
        let mut diagonal = l[(j, j)];
        for k in 0..j {
            diagonal -= l[(j, k)] * l[(j, k)];
        }
        if !(diagonal > 0.0 && diagonal.is_finite()) {
            return Err(Error::Numerical {
                context: "mass matrix inverse".into(),
                reason: format!(
                    "the mass matrix is not positive definite at joint {j} (`{}`): the bodies it moves have no inertia about its axis",
                    model.joints()[j].name
                ),
            });
        }
        let diagonal = diagonal.sqrt();
        l[(j, j)] = diagonal;
        for i in j + 1..n {
            let mut value = l[(i, j)];
            for k in 0..j {
                value -= l[(i, k)] * l[(j, k)];
            }
            l[(i, j)] = value / diagonal;
        }
    }
    // L^-1 in place (lower triangular), then M^-1 = L^-T L^-1.
    for j in 0..n {
        l[(j, j)] = 1.0 / l[(j, j)];
        for i in j + 1..n {
            let mut sum = 0.0;
            for k in j..i {
                sum -= l[(i, k)] * l[(k, j)];
            }
            l[(i, j)] = sum / l[(i, i)];
        }
    }
    for i in 0..n {
        for j in 0..=i {
            // (L^-T L^-1)[i][j] = sum_k Linv[k][i] Linv[k][j], k >= max(i, j) = i.
            let mut sum = 0.0;
            for k in i..n {
                sum += l[(k, i)] * l[(k, j)];
            }
            // Row i >= j: store in the upper triangle first (not read again).
            l[(j, i)] = sum;
        }
    }
    for i in 0..n {
        for j in 0..i {
            l[(i, j)] = l[(j, i)];
        }
    }
    Ok(&data.mass_matrix_inverse)
}

/// Forward dynamics by the articulated-body algorithm (Featherstone, table
/// 7.1), O(n): the joint accelerations `ddq = M(q)^-1 (tau - C(q, v) v - g(q))`
/// (rad/s^2 or m/s^2) that torques `tau` (N m or N) give at positions `q` and
/// velocities `v`, under the workspace's gravity.
///
/// Returns one acceleration per joint (also kept in
/// [`DynamicsData::accelerations`]). Errors as [`rnea`], and
/// [`Error::Numerical`] if a joint's articulated inertia about its axis is not
/// positive (bodies without inertia about that axis). Allocates nothing.
pub fn aba<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<&'d [f64]> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    check_finite_vector("joint_torques", tau, model.dof())?;
    data.update_bodies(model, q)?;
    // Pass 1: velocities and velocity-product accelerations c_j = v_j x S_j qd_j.
    let mut velocity = Motion::ZERO;
    for (((axis, &qd), slot), c) in data
        .axes
        .iter()
        .zip(v)
        .zip(data.velocities.iter_mut())
        .zip(data.accelerations.iter_mut())
    {
        let joint_velocity = *axis * qd;
        velocity = velocity + joint_velocity;
        *slot = velocity;
        *c = velocity.cross(&joint_velocity);
    }
    // Pass 2, tip to base: the articulated inertia IA and bias force pA of
    // bodies j..n-1, projected through joint j and handed to the parent. In
    // the world frame the parent adds them without a transform, so one
    // running pair suffices.
    let mut articulated = Matrix6::zeros();
    let mut bias = Vector6::zeros();
    for j in (0..data.dof).rev() {
        let body = &data.bodies[j];
        let velocity = data.velocities[j];
        articulated += body.to_matrix();
        bias += velocity.cross_force(&body.apply(&velocity)).to_vector();
        let s = data.axes[j].to_vector();
        let u_column = articulated * s;
        let d = s.dot(&u_column);
        if !(d > 0.0 && d.is_finite()) {
            return Err(Error::Numerical {
                context: "forward dynamics (ABA)".into(),
                reason: format!(
                    "the articulated inertia about joint {j} (`{}`) is {d:e}: the bodies it moves have no inertia about its axis",
                    model.joints()[j].name
                ),
            });
        }
        let u = tau[j] - s.dot(&bias);
        data.u_columns[j] = u_column;
        data.d_values[j] = d;
        data.u_values[j] = u;
        let inverse_d = 1.0 / d;
        articulated -= u_column * (u_column.transpose() * inverse_d);
        bias += articulated * data.accelerations[j].to_vector() + u_column * (u * inverse_d);
    }
    // Pass 3, base to tip: accelerations, gravity as an upward base acceleration.
    let mut acceleration = Motion::new(Vector3::zeros(), -data.gravity).to_vector();
    for j in 0..data.dof {
        acceleration += data.accelerations[j].to_vector();
        let qdd = (data.u_values[j] - data.u_columns[j].dot(&acceleration)) / data.d_values[j];
        acceleration += data.axes[j].to_vector() * qdd;
        data.ddq[j] = qdd;
    }
    Ok(&data.ddq)
}
