//! RNEA and CRBA in body frames, ABA in the world frame, and what derives
//! from them (module documentation).

use super::spatial::{Motion, SpatialInertia};
use super::{check_not_overflowed, singular_mass_matrix, DynamicsData, MASS_MATRIX_THRESHOLD};
use crate::error::{check_finite_vector, Result};
use crate::math::{DMatrix, Matrix6, Vector3, Vector6};
use crate::model::Model;

/// Inverse dynamics by the recursive Newton-Euler algorithm (Featherstone,
/// table 5.1): the joint torques `tau = M(q) a + C(q, v) v + g(q)` (N m, or
/// N for prismatic joints) that give joint accelerations `a` at positions
/// `q` and velocities `v`, under the workspace's gravity.
///
/// Returns one torque per joint (also kept in [`DynamicsData::torques`]).
/// Errors: a slice of the wrong size or not finite, `data` made for another
/// model, a link without mass properties, an additive coupling curve
/// without a second derivative. A coupled model (mimic joints, the flexible
/// gantry) works in its independent joints (see the module documentation).
/// Allocates nothing.
pub fn rnea<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<&'d [f64]> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    check_finite_vector("joint_accelerations", a, model.dof())?;
    data.update_transforms(model, q)?;
    let gravity = data.gravity;
    data.chain_newton_euler(Some(v), Some(a), Some(&gravity))?;
    Ok(data.torques())
}

/// Gravity torques `g(q) = RNEA(q, 0, 0)` (N m or N): the torques that hold
/// the arm still against the workspace's gravity, equal to the gradient of
/// [`super::potential_energy`]. Errors as [`rnea`]. Allocates nothing.
pub fn gravity_torques<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
) -> Result<&'d [f64]> {
    data.update_transforms(model, q)?;
    let gravity = data.gravity;
    data.chain_newton_euler(None, None, Some(&gravity))?;
    Ok(data.torques())
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
    data.update_transforms(model, q)?;
    data.chain_newton_euler(Some(v), None, None)?;
    Ok(data.torques())
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
    data.update_transforms(model, q)?;
    let gravity = data.gravity;
    data.chain_newton_euler(Some(v), None, Some(&gravity))?;
    Ok(data.torques())
}

/// The two passes of the RNEA (Featherstone table 5.1) in body frames, on
/// the joint transforms of `update_transforms`, at chain velocities `v` and
/// accelerations `a`, into the chain torques `data.tau`; `gravity` `None`
/// leaves it out. Leaves each body's velocity in `data.velocities`.
pub(super) fn newton_euler(
    data: &mut DynamicsData,
    v: &[f64],
    a: &[f64],
    gravity: Option<&Vector3<f64>>,
) {
    let n = data.tau.len();
    if n == 0 {
        return;
    }
    let (v, a) = (&v[..n], &a[..n]);
    let transforms = &data.transforms[..n];
    let axes = &data.joint_axes[..n];
    let inertias = &data.local_inertias[..n];
    let forces = &mut data.forces[..n];
    let velocities = &mut data.velocities[..n];
    // Gravity as an upward acceleration of the base (Featherstone 5.3):
    // every body then feels it through its inertia. The first body moves
    // with S qd_0 alone (so v_0 x S qd_0 = 0) and accelerates with the base,
    // at rest: X_0 (0, -g) = (0, R_0' (-g)).
    let mut velocity = Motion::ZERO;
    let lifted = gravity.map_or(Vector3::zeros(), |g| transforms[0].rotation.tr_mul(&-g));
    let mut acceleration = Motion::new(Vector3::zeros(), lifted);
    for j in 0..n {
        let (transform, axis, body) = (&transforms[j], axes[j], &inertias[j]);
        let (qd, qdd) = (v[j], a[j]);
        // v_j = X_j v_{j-1} + S qd_j; a_j = X_j a_{j-1} + S qdd_j + v_j x S qd_j.
        if j > 0 {
            velocity = velocity.inverse_transformed(transform);
            acceleration = acceleration.inverse_transformed(transform);
            axis.add_rate(&mut velocity, qd);
            axis.add_velocity_product(&mut acceleration, &velocity, qd);
        } else {
            axis.add_rate(&mut velocity, qd);
        }
        axis.add_rate(&mut acceleration, qdd);
        velocities[j] = velocity;
        // f_j = I_j a_j + v_j x* I_j v_j.
        let momentum = body.apply(&velocity);
        forces[j] = body.apply(&acceleration) + velocity.cross_force(&momentum);
    }
    // Tip to base: tau_j = S' f_j, f_{j-1} += X_j* f_j.
    let tau = &mut data.tau[..n];
    let mut transmitted = forces[n - 1];
    tau[n - 1] = axes[n - 1].component(&transmitted);
    for j in (0..n - 1).rev() {
        transmitted = transmitted.transformed(&transforms[j + 1]) + forces[j];
        tau[j] = axes[j].component(&transmitted);
    }
}

/// The joint-space inertia (mass) matrix `M(q)` by the composite rigid body
/// algorithm (Featherstone, table 6.2): n x n, symmetric positive definite,
/// kg m^2 (kg for two prismatic joints, kg m for mixed entries).
///
/// `M[i][j] = S_i' Ic_j S_j` for `i <= j`, with `Ic_j` the inertia of bodies
/// j..n-1 together (each in its own joint frame, carried to frame `i`).
/// Also kept in [`DynamicsData::mass_matrix`]. Errors as [`rnea`].
/// Allocates nothing.
pub fn mass_matrix<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
) -> Result<&'d DMatrix<f64>> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the function needs only the two features detected above.
        unsafe { mass_matrix_avx2_fma(model, data, q) }?;
        return Ok(&data.mass_matrix);
    }
    mass_matrix_kernel(model, data, q)?;
    Ok(&data.mass_matrix)
}

/// [`mass_matrix`]'s work, inlined into both of its builds.
#[inline(always)]
fn mass_matrix_kernel(model: &Model, data: &mut DynamicsData, q: &[f64]) -> Result<()> {
    data.update_transforms(model, q)?;
    joint_space_inertia(data);
    check_not_overflowed("mass matrix", data.mass_matrix.as_slice())
}

/// [`mass_matrix_kernel`] compiled for AVX2 and FMA, which [`mass_matrix`]
/// runs where the processor has them (detected at run time, once, then
/// cached by the standard library). The three-operand vector instructions
/// and fused multiply-adds take the CRBA from 3.3k to 2.8k instructions on
/// the UR5, the margin its 2x-Pinocchio target needed (Pinocchio is built
/// for the native processor); the results agree with the baseline build to
/// rounding (a fused multiply-add rounds once). The RNEA and the ABA meet
/// their targets without it and stay baseline, bit for bit the same on
/// every processor.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn mass_matrix_avx2_fma(model: &Model, data: &mut DynamicsData, q: &[f64]) -> Result<()> {
    mass_matrix_kernel(model, data, q)
}

/// The mass matrix at the joint transforms of `update_transforms` into
/// `data.mass_matrix`: the CRBA, folded `M' H_c M` for a coupled model.
#[inline(always)] // into `mass_matrix_avx2_fma`
fn joint_space_inertia(data: &mut DynamicsData) {
    // Checked before `take` so that an uncoupled call moves nothing.
    let coupled = if data.coupled.is_some() {
        data.coupled.take()
    } else {
        None
    };
    match coupled {
        None => {
            let mut m = std::mem::take(&mut data.mass_matrix);
            composite_rigid_body(data, &mut m);
            data.mass_matrix = m;
        }
        Some(mut coupled) => {
            // M' H_c M, H_c the chain's mass matrix (plain loops: nalgebra's
            // gemm packs into heap buffers).
            composite_rigid_body(data, &mut coupled.chain_mass_matrix);
            let (h, map, product) = (
                &coupled.chain_mass_matrix,
                &coupled.map,
                &mut coupled.product,
            );
            let chain = h.nrows();
            for k in 0..map.ncols() {
                for i in 0..chain {
                    product[(i, k)] = (0..chain).map(|j| h[(i, j)] * map[(j, k)]).sum();
                }
            }
            for k in 0..map.ncols() {
                for i in 0..map.ncols() {
                    data.mass_matrix[(i, k)] =
                        (0..chain).map(|j| map[(j, i)] * product[(j, k)]).sum();
                }
            }
            data.coupled = Some(coupled);
        }
    }
}

/// The chain's mass matrix (chain joints x chain joints) into `out`, by the
/// CRBA in body frames (Featherstone table 6.2), in one pass from the tip to
/// the base.
///
/// At level `i` the composite inertia `Ic_i = I_i + X_{i+1}* Ic_{i+1}` and the
/// columns `F_k = Ic_k S_k` of the bodies beyond (`k > i`) are carried
/// together through the one transform `X_{i+1}` into frame `i`, where row `i`
/// reads their `S_i` components; then `F_i = Ic_i S_i` joins them. The base
/// level needs no frame-0 quantity but `S_0`'s products: with `s = X_1 S_0`
/// (`S_0` seen from frame 1), `M[0][k] = s . F_k` and
/// `M[0][0] = S_0' I_0 S_0 + s' Ic_1 s`.
#[inline(always)] // into `mass_matrix_avx2_fma`
fn composite_rigid_body(data: &mut DynamicsData, out: &mut DMatrix<f64>) {
    let n = data.local_inertias.len();
    if n == 0 {
        return;
    }
    let m = &mut out.as_mut_slice()[..n * n];
    let transforms = &data.transforms[..n];
    let axes = &data.joint_axes[..n];
    let inertias = &data.local_inertias[..n];
    let columns = &mut data.forces[..n];
    let mut composite = inertias[n - 1];
    columns[n - 1] = axes[n - 1].inertia_column(&composite);
    m[n * n - 1] = axes[n - 1].component(&columns[n - 1]);
    for i in (1..n - 1).rev() {
        let (transform, axis) = (&transforms[i + 1], axes[i]);
        composite = inertias[i] + composite.transformed(transform);
        for k in i + 1..n {
            let column = columns[k].transformed(transform);
            columns[k] = column;
            let value = axis.component(&column);
            m[k * n + i] = value;
            m[i * n + k] = value;
        }
        columns[i] = axis.inertia_column(&composite);
        m[i * n + i] = axis.component(&columns[i]);
    }
    let base = axes[0].component(&axes[0].inertia_column(&inertias[0]));
    if n == 1 {
        m[0] = base;
        return;
    }
    let s = axes[0].in_child_frame(&transforms[1]);
    for k in 1..n {
        let value = s.dot(&columns[k]);
        m[k * n] = value;
        m[k] = value;
    }
    m[0] = base + s.dot(&composite.apply(&s));
}

/// The lower Cholesky factor `L` of `data.mass_matrix` (`M = L L'`) into
/// `data.mass_matrix_inverse`'s buffer (lower triangle). Error: `M`
/// numerically singular (a pivot `L_jj^2` at or below
/// [`MASS_MATRIX_THRESHOLD`] times `M`'s largest diagonal entry), naming the
/// joint; `context` says what was being computed.
fn cholesky_factor(model: &Model, data: &mut DynamicsData, context: &str) -> Result<()> {
    let n = data.dof;
    let l = &mut data.mass_matrix_inverse;
    l.copy_from(&data.mass_matrix);
    let largest = (0..n).map(|j| l[(j, j)]).fold(0.0, f64::max);
    for j in 0..n {
        let mut diagonal = l[(j, j)];
        for k in 0..j {
            diagonal -= l[(j, k)] * l[(j, k)];
        }
        if !(diagonal > MASS_MATRIX_THRESHOLD * largest && diagonal.is_finite()) {
            return Err(singular_mass_matrix(model, context, j, diagonal, largest));
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
    Ok(())
}

/// The inverse of the mass matrix, `M(q)^-1` (n x n), by a Cholesky
/// factorization of [`mass_matrix`] done in place. Errors as [`rnea`], and
/// [`crate::Error::Numerical`] if `M` is numerically singular (see
/// [`MASS_MATRIX_THRESHOLD`]; a body without inertia about its own joint
/// axis). Allocates nothing.
pub fn mass_matrix_inverse<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
) -> Result<&'d DMatrix<f64>> {
    mass_matrix(model, data, q)?;
    let n = data.dof;
    cholesky_factor(model, data, "mass matrix inverse")?;
    let l = &mut data.mass_matrix_inverse;
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
/// For a coupled model (mimic joints, the flexible gantry) the chain is
/// constrained, and the O(n) recursion does not hold: `(M' H_c M) ddq =
/// tau - M'(C + g)` is solved by a Cholesky factorization instead, O(n^3)
/// (module documentation).
///
/// Returns one acceleration per joint (also kept in
/// [`DynamicsData::accelerations`]). Errors as [`rnea`], and
/// [`crate::Error::Numerical`] if `M(q)` is numerically singular: a joint's
/// articulated inertia about its axis at or below [`MASS_MATRIX_THRESHOLD`]
/// times `M`'s largest diagonal entry (bodies without inertia about that
/// axis), at any configuration. Allocates nothing.
pub fn aba<'d>(
    model: &Model,
    data: &'d mut DynamicsData,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<&'d [f64]> {
    check_finite_vector("joint_velocities", v, model.dof())?;
    check_finite_vector("joint_torques", tau, model.dof())?;
    data.update_transforms(model, q)?;
    if data.coupled.is_some() {
        coupled_forward_dynamics(model, data, v, tau)?;
        check_not_overflowed("forward dynamics", &data.ddq)?;
        return Ok(&data.ddq);
    }
    data.update_world_bodies();
    // Pass 1: velocities and velocity-product accelerations c_j = v_j x S_j qd_j.
    let mut velocity = Motion::ZERO;
    for (((axis, &qd), slot), c) in data
        .world_axes
        .iter()
        .zip(v)
        .zip(data.world_velocities.iter_mut())
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
    // The composite inertia of bodies j..n-1 gives M's diagonal entry
    // S_j' Ic_j S_j, the scale the pivots D_j are judged against.
    let mut composite = SpatialInertia::ZERO;
    let mut largest_diagonal = 0.0_f64;
    for j in (0..data.dof).rev() {
        let body = &data.world_inertias[j];
        let velocity = data.world_velocities[j];
        articulated += body.to_matrix();
        composite += *body;
        let axis = &data.world_axes[j];
        largest_diagonal = largest_diagonal.max(axis.dot(&composite.apply(axis)));
        bias += velocity.cross_force(&body.apply(&velocity)).to_vector();
        let s = axis.to_vector();
        let u_column = articulated * s;
        let d = s.dot(&u_column);
        let u = tau[j] - s.dot(&bias);
        data.u_columns[j] = u_column;
        data.d_values[j] = d;
        data.u_values[j] = u;
        let inverse_d = 1.0 / d;
        articulated -= u_column * (u_column.transpose() * inverse_d);
        bias += articulated * data.accelerations[j].to_vector() + u_column * (u * inverse_d);
    }
    // Judged once every diagonal entry is known; the first pivot from the tip
    // that fails is the one that makes the rest meaningless.
    let tolerance = MASS_MATRIX_THRESHOLD * largest_diagonal;
    if let Some(j) = (0..data.dof)
        .rev()
        .find(|&j| !(data.d_values[j] > tolerance && data.d_values[j].is_finite()))
    {
        return Err(singular_mass_matrix(
            model,
            "forward dynamics (ABA)",
            j,
            data.d_values[j],
            largest_diagonal,
        ));
    }
    // Pass 3, base to tip: accelerations, gravity as an upward base acceleration.
    let mut acceleration = Motion::new(Vector3::zeros(), -data.gravity).to_vector();
    for j in 0..data.dof {
        acceleration += data.accelerations[j].to_vector();
        let qdd = (data.u_values[j] - data.u_columns[j].dot(&acceleration)) / data.d_values[j];
        acceleration += data.world_axes[j].to_vector() * qdd;
        data.ddq[j] = qdd;
    }
    check_not_overflowed("forward dynamics", &data.ddq)?;
    Ok(&data.ddq)
}

/// Forward dynamics of a coupled model (after `update_transforms`):
/// `(M' H_c M) ddq = tau - M'(C + g)` by a Cholesky factorization, O(n^3)
/// (the articulated-body recursion holds for unconstrained chains only),
/// into `data.ddq`.
fn coupled_forward_dynamics(
    model: &Model,
    data: &mut DynamicsData,
    v: &[f64],
    tau: &[f64],
) -> Result<()> {
    let gravity = data.gravity;
    data.chain_newton_euler(Some(v), None, Some(&gravity))?;
    joint_space_inertia(data);
    cholesky_factor(model, data, "forward dynamics")?;
    let n = data.dof;
    let l = &data.mass_matrix_inverse;
    let ddq = &mut data.ddq;
    let bias = match &data.coupled {
        Some(coupled) => &coupled.torques,
        None => &data.tau,
    };
    for ((x, &t), &bias) in ddq.iter_mut().zip(tau).zip(bias) {
        *x = t - bias;
    }
    // L y = rhs, then L' ddq = y, in place.
    for i in 0..n {
        let mut value = ddq[i];
        for k in 0..i {
            value -= l[(i, k)] * ddq[k];
        }
        ddq[i] = value / l[(i, i)];
    }
    for i in (0..n).rev() {
        let mut value = ddq[i];
        for k in i + 1..n {
            value -= l[(k, i)] * ddq[k];
        }
        ddq[i] = value / l[(i, i)];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The processor-specific build of the CRBA (what `mass_matrix` runs
    /// where AVX2 and FMA exist) and the baseline build agree to rounding.
    #[test]
    fn both_builds_of_the_mass_matrix_agree() {
        // space6r: a built-in arm with mass properties.
        let model = crate::robots::by_name("space6r").unwrap();
        let mut fast = DynamicsData::new(&model).unwrap();
        let mut baseline = DynamicsData::new(&model).unwrap();
        for k in 0..50 {
            let q: Vec<f64> = (0..6)
                .map(|j| ((k * 6 + j) as f64 * 0.7).sin() * 3.0)
                .collect();
            let m = mass_matrix(&model, &mut fast, &q).unwrap().clone();
            mass_matrix_kernel(&model, &mut baseline, &q).unwrap();
            let scale = m.amax();
            assert!((m - &baseline.mass_matrix).amax() <= 1e-14 * scale);
        }
    }
}
