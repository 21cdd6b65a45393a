//! Time stepping of a free-floating system under commanded joint rates.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::dynamics::{generalized_jacobian, update_kinematics};
use super::{BaseMode, FreeFloatingModel, FreeFloatingState, SpaceData};
use crate::error::{check_finite_vector, check_positive, Error, Result};
use crate::math::{skew, Matrix3, Vector3};

/// Advances `state` (base pose and joint positions) by `dt` seconds with the
/// joint rates `joint_rates` (rad/s or m/s) held constant, keeping the
/// momentum zero as `mode` says.
///
/// * Joints: `q += dt q_dot` (exact for constant rates).
/// * Base attitude: unchanged when [`BaseMode::AttitudeHeld`]; otherwise the
///   base's body-frame angular velocity `R0' B_w(q) q_dot` (a function of `q`
///   only, see the module docs) is integrated with the fourth-order Magnus
///   scheme at the two Gauss-Legendre nodes, through the exponential map.
/// * Base position: solved from the condition that the system's centre of
///   mass stays where it was (zero linear momentum is holonomic), not
///   integrated, so it cannot drift.
///
/// Afterwards `data` holds the kinematics of the new state
/// ([`SpaceData::end_effector_pose`], [`SpaceData::center_of_mass`]); call
/// [`generalized_jacobian`] for `J*` there. Joint limits are not checked.
/// Allocates nothing. Errors: `joint_rates` of
/// the wrong size or not finite, `dt` negative or not finite, and the errors
/// of [`generalized_jacobian`].
pub fn step(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    state: &mut FreeFloatingState,
    joint_rates: &[f64],
    dt: f64,
    mode: BaseMode,
) -> Result<()> {
    check_step_inputs(model, joint_rates, dt)?;
    update_kinematics(model, data, &state.base, &state.q)?;
    let com = data.com;
    if mode == BaseMode::FreeFloating {
        // 4th-order Magnus on R0' = R0 [w_b(t)]x: with w1, w2 the body rates at
        // t + (1/2 -+ sqrt(3)/6) dt, R0(t + dt) = R0 exp([W]x),
        // W = dt/2 (w1 + w2) + sqrt(3)/12 dt^2 (w1 x w2).
        let offset = 3f64.sqrt() / 6.0;
        let w1 = body_rate(model, data, state, joint_rates, (0.5 - offset) * dt)?;
        let w2 = body_rate(model, data, state, joint_rates, (0.5 + offset) * dt)?;
        let rotation_vector =
            (w1 + w2) * (0.5 * dt) + w1.cross(&w2) * (3f64.sqrt() / 12.0 * dt * dt);
        let turned = state.base.rotation * exp_so3(&rotation_vector);
        state.base.rotation = orthonormalize(&turned);
    }
    for (q, rate) in state.q.iter_mut().zip(joint_rates) {
        *q += rate * dt;
    }
    // P = 0: r_g is constant. Place the base so that it is.
    update_kinematics(model, data, &state.base, &state.q)?;
    let shift = com - data.com;
    state.base.translation += shift;
    // Leave the workspace describing the new state (centre of mass, tip pose).
    data.translate(&shift);
    Ok(())
}

/// Advances `state` by `dt` seconds with constant joint rates
/// `joint_rates`, the base moved by integrating its twist from the momentum
/// equations (seed 004, eqs 10-16: `v0 = -J_g q_dot` with `w0 = 0` when
/// the attitude is held; `w0 = B_w q_dot`, `v0 = (r_g - p0) x w0 - J_g q_dot`
/// when free-floating) with a classical fourth-order Runge-Kutta step
/// (rotation stages through the exponential map). Unlike [`step`], the
/// base is never re-placed from the centre of mass: whether the centre of
/// mass stays put and the momenta stay zero is then a property of the
/// integrated motion, checked against [`super::center_of_mass`] and
/// [`super::momentum`] (computed independently of the base Jacobian).
///
/// Afterwards `data` holds the base Jacobian at the last stage, not at the
/// new state. Allocates nothing. Errors as [`step`].
pub fn step_integrated(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    state: &mut FreeFloatingState,
    joint_rates: &[f64],
    dt: f64,
    mode: BaseMode,
) -> Result<()> {
    check_step_inputs(model, joint_rates, dt)?;
    let (p, r) = (state.base.translation, state.base.rotation);
    let k1 = base_twist(model, data, state, joint_rates, 0.0, &p, &r, mode)?;
    let stage = |k: &(Vector3<f64>, Vector3<f64>), h: f64| {
        (p + k.0 * h, orthonormalize(&(exp_so3(&(k.1 * h)) * r)))
    };
    let (p2, r2) = stage(&k1, 0.5 * dt);
    let k2 = base_twist(model, data, state, joint_rates, 0.5 * dt, &p2, &r2, mode)?;
    let (p3, r3) = stage(&k2, 0.5 * dt);
    let k3 = base_twist(model, data, state, joint_rates, 0.5 * dt, &p3, &r3, mode)?;
    let (p4, r4) = stage(&k3, dt);
    let k4 = base_twist(model, data, state, joint_rates, dt, &p4, &r4, mode)?;
    let v = (k1.0 + (k2.0 + k3.0) * 2.0 + k4.0) / 6.0;
    let w = (k1.1 + (k2.1 + k3.1) * 2.0 + k4.1) / 6.0;
    let (p_new, r_new) = stage(&(v, w), dt);
    state.base.translation = p_new;
    state.base.rotation = r_new;
    for (q, rate) in state.q.iter_mut().zip(joint_rates) {
        *q += rate * dt;
    }
    Ok(())
}

/// The base twist `(v0, w0)` (inertial frame, m/s and rad/s) that the
/// momentum equations give at base `(p, r)` and joint positions
/// `q + tau q_dot`, under rates `q_dot`.
#[allow(clippy::too_many_arguments)]
fn base_twist(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    state: &FreeFloatingState,
    joint_rates: &[f64],
    tau: f64,
    p: &Vector3<f64>,
    r: &Matrix3<f64>,
    mode: BaseMode,
) -> Result<(Vector3<f64>, Vector3<f64>)> {
    let mut q_node = std::mem::take(&mut data.q_node);
    for ((node, q), rate) in q_node.iter_mut().zip(&state.q).zip(joint_rates) {
        *node = q + rate * tau;
    }
    let base = crate::math::Pose::new(*r, *p);
    let result = generalized_jacobian(model, data, &base, &q_node, mode).map(|_| ());
    data.q_node = q_node;
    result?;
    let (mut v, mut w) = (Vector3::zeros(), Vector3::zeros());
    for (j, rate) in joint_rates.iter().enumerate() {
        v += data.base_jacobian.fixed_view::<3, 1>(0, j) * *rate;
        w += data.base_jacobian.fixed_view::<3, 1>(3, j) * *rate;
    }
    Ok((v, w))
}

/// The base's body-frame angular velocity (rad/s) at joint positions
/// `q + tau q_dot` under rates `q_dot`: `R0' B_w q_dot`. The world-frame
/// `B_w` turns with the base, so the product depends on `q` only.
fn body_rate(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    state: &FreeFloatingState,
    joint_rates: &[f64],
    tau: f64,
) -> Result<Vector3<f64>> {
    // Borrow the workspace's buffer for the node's joint positions (no allocation).
    let mut q_node = std::mem::take(&mut data.q_node);
    for ((node, q), rate) in q_node.iter_mut().zip(&state.q).zip(joint_rates) {
        *node = q + rate * tau;
    }
    let result =
        generalized_jacobian(model, data, &state.base, &q_node, BaseMode::FreeFloating).map(|_| ());
    data.q_node = q_node;
    result?;
    let mut w_world = Vector3::zeros();
    for (j, rate) in joint_rates.iter().enumerate() {
        w_world += data.base_jacobian.fixed_view::<3, 1>(3, j) * *rate;
    }
    Ok(state.base.rotation.transpose() * w_world)
}

/// `exp([v]x)` by Rodrigues' formula, written with `2 sin^2(a/2)` to keep
/// full precision for small angles.
fn exp_so3(v: &Vector3<f64>) -> Matrix3<f64> {
    let angle = v.norm();
    let k = skew(v);
    if angle < 1e-8 {
        // Series to second order: the next term is O(angle^3) < 1e-24.
        return Matrix3::identity() + k + k * k * 0.5;
    }
    let half = 0.5 * angle;
    let a = angle.sin() / angle;
    let b = 2.0 * (half.sin() / angle).powi(2);
    Matrix3::identity() + k * a + k * k * b
}

/// One Newton step of the polar decomposition, `R (3 I - R'R) / 2`: removes
/// the round-off that products of rotations accumulate (quadratically).
fn orthonormalize(r: &Matrix3<f64>) -> Matrix3<f64> {
    r * (Matrix3::identity() * 3.0 - r.transpose() * r) * 0.5
}

/// A smooth pseudo-random joint motion: each joint follows a sum of three
/// sinusoids, `q_j(t) = q0_j + sum_k a_jk (sin(w_jk t + phi_jk) - sin phi_jk)`,
/// so `q(0) = q0`. For simulation tests and demos.
#[derive(Clone, Debug, PartialEq)]
pub struct SinusoidalJointMotion {
    /// Per joint, three (amplitude rad or m, angular frequency rad/s, phase rad).
    terms: Vec<[(f64, f64, f64); 3]>,
}

impl SinusoidalJointMotion {
    /// A motion for `dof` joints drawn from `seed`: each joint's three
    /// amplitudes sum to `amplitude` (rad or m, > 0), frequencies are uniform
    /// in `[0.2, 1] x max_frequency` (rad/s, > 0), phases uniform in `[0, 2 pi)`.
    pub fn random(dof: usize, seed: u64, amplitude: f64, max_frequency: f64) -> Result<Self> {
        for (name, value) in [("amplitude", amplitude), ("max_frequency", max_frequency)] {
            check_positive(name, value)?;
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let terms = (0..dof)
            .map(|_| {
                let weights: [f64; 3] = [
                    rng.gen_range(0.2..1.0),
                    rng.gen_range(0.2..1.0),
                    rng.gen_range(0.2..1.0),
                ];
                let total: f64 = weights.iter().sum();
                weights.map(|w| {
                    (
                        amplitude * w / total,
                        max_frequency * rng.gen_range(0.2..=1.0),
                        rng.gen_range(0.0..std::f64::consts::TAU),
                    )
                })
            })
            .collect();
        Ok(SinusoidalJointMotion { terms })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.terms.len()
    }

    /// Joint rates at time `t` (s) into `rates` (one per joint; extra entries
    /// are left alone).
    pub fn rates(&self, t: f64, rates: &mut [f64]) {
        for (rate, terms) in rates.iter_mut().zip(&self.terms) {
            *rate = terms
                .iter()
                .map(|(a, w, phi)| a * w * (w * t + phi).cos())
                .sum();
        }
    }

    /// Joint positions at time `t` (s) starting from `q0` at `t = 0`, into
    /// `positions` (one per joint).
    pub fn positions(&self, q0: &[f64], t: f64, positions: &mut [f64]) {
        for ((q, start), terms) in positions.iter_mut().zip(q0).zip(&self.terms) {
            *q = start
                + terms
                    .iter()
                    .map(|(a, w, phi)| a * ((w * t + phi).sin() - phi.sin()))
                    .sum::<f64>();
        }
    }
}

/// The inputs of one step, checked alike by [`step`] and [`step_integrated`]:
/// `joint_rates` (rad/s or m/s, one per joint) finite and of the arm's size,
/// `dt` (s) finite and non-negative.
fn check_step_inputs(model: &FreeFloatingModel, joint_rates: &[f64], dt: f64) -> Result<()> {
    check_finite_vector("joint_rates", joint_rates, model.dof())?;
    if !(dt.is_finite() && dt >= 0.0) {
        return Err(Error::invalid_argument(
            "dt",
            format!("must be finite and >= 0 s, got {dt}"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_so3_is_a_rotation_about_the_vector() {
        for v in [
            Vector3::new(0.3, -0.2, 0.9),
            Vector3::new(1e-9, 2e-9, 0.0),
            Vector3::new(0.0, 0.0, 3.0),
        ] {
            let r = exp_so3(&v);
            assert!((r.transpose() * r - Matrix3::identity()).amax() < 1e-15);
            assert!((r * v - v).norm() < 1e-15);
            let expected = nalgebra::Rotation3::from_scaled_axis(v).into_inner();
            assert!((r - expected).amax() < 1e-15);
        }
    }

    #[test]
    fn orthonormalize_removes_small_errors() {
        let mut r = exp_so3(&Vector3::new(0.4, 0.1, -0.7));
        r[(0, 1)] += 1e-7;
        let fixed = orthonormalize(&r);
        assert!((fixed.transpose() * fixed - Matrix3::identity()).amax() < 1e-13);
    }

    #[test]
    fn sinusoidal_motion_rates_are_the_derivative_of_positions() {
        let motion = SinusoidalJointMotion::random(3, 7, 0.5, 1.0).unwrap();
        let q0 = [0.1, 0.2, 0.3];
        let (mut qp, mut qm, mut rates, mut start) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
        motion.positions(&q0, 0.0, &mut start);
        assert_eq!(start, q0);
        let (t, h) = (2.3, 1e-5);
        motion.positions(&q0, t + h, &mut qp);
        motion.positions(&q0, t - h, &mut qm);
        motion.rates(t, &mut rates);
        for j in 0..3 {
            assert!(((qp[j] - qm[j]) / (2.0 * h) - rates[j]).abs() < 1e-9);
        }
        assert!(SinusoidalJointMotion::random(3, 7, -1.0, 1.0)
            .unwrap_err()
            .to_string()
            .contains("amplitude"));
    }
}
