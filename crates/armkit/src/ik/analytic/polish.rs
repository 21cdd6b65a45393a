//! A root of elimination made a solution: the chain's pose
//! at a configuration, its error to the target, and a few damped
//! Gauss-Newton (Levenberg-Marquardt) steps on the full 6-D pose error of
//! the chain's product of exponentials (position error, m, and the rotation
//! vector of `R_T R'`, rad) where the root misses by more than the
//! rounding.

use super::chain::Chain;
use super::subproblems::rotation;
use super::EXACT_TOLERANCE;
use crate::math::{wrap_angle, Matrix6, Pose, Vector3, Vector6};

/// How far a root may miss and how hard it is polished: a root `q` whose
/// pose misses the target by more than `keep` (m and rad) is dropped; one
/// missing by more than [`POLISHED`] is polished by at most `iterations`
/// steps of [`polish`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settle {
    pub keep: f64,
    pub iterations: usize,
}

/// Norm of the 6-D pose error (m and rad) at which a polish stops.
pub(crate) const CONVERGED: f64 = 1e-13;

/// Pose error (m and rad) above which a root is polished.
pub(crate) const POLISHED: f64 = 1e-12;

/// A root `q` (chain order) as a solution for `target`, per `settle`: the
/// polished configuration kept only if it errs less; with whether it is
/// exact (within [`EXACT_TOLERANCE`]).
pub(crate) fn settle_root_within(
    chain: &Chain,
    home: &Pose,
    mut q: [f64; 6],
    target: &Pose,
    settle: Settle,
) -> Option<([f64; 6], bool)> {
    let error = pose_gap(chain, home, &q, target);
    if error > settle.keep {
        return None;
    }
    if error > POLISHED {
        if let Some(p) = polish(chain, home, q, target, settle.iterations) {
            if pose_gap(chain, home, &p, target) < error {
                q = p.map(wrap_angle);
            }
        }
    }
    Some((q, pose_gap(chain, home, &q, target) <= EXACT_TOLERANCE))
}

/// `E1(q1) ... E6(q6) home` of a chain of rotation joints (m, rad).
pub(crate) fn chain_pose(chain: &Chain, home: &Pose, q: &[f64; 6]) -> Pose {
    let (c, h) = (&chain.c, &chain.h);
    let mut pose = Pose::identity();
    for k in 0..6 {
        let r = rotation(&h[k], q[k]);
        pose = pose * Pose::new(r, c[k] - r * c[k]);
    }
    pose * *home
}

/// The largest of the position (m) and rotation-matrix (Frobenius) errors
/// of [`chain_pose`] at `q` against `target`.
fn pose_gap(chain: &Chain, home: &Pose, q: &[f64; 6], target: &Pose) -> f64 {
    let pose = chain_pose(chain, home, q);
    let position = (pose.translation - target.translation).norm();
    let orientation = (pose.rotation - target.rotation).norm();
    position.max(orientation)
}

/// Levenberg-Marquardt on the chain's 6-D pose error from `q` to
/// `target` (at most `iterations` steps, stopping below [`CONVERGED`]); the
/// configuration if it ends within 1e-8 (a candidate; exact only within
/// 1e-10).
fn polish(
    chain: &Chain,
    home: &Pose,
    mut q: [f64; 6],
    target: &Pose,
    iterations: usize,
) -> Option<[f64; 6]> {
    let (mut error, mut jacobian) = error_and_jacobian(chain, home, &q, target);
    let mut norm = error.norm();
    let mut damping = 1e-6;
    for _ in 0..iterations {
        if norm <= CONVERGED {
            break;
        }
        let normal = jacobian.transpose() * jacobian + Matrix6::identity() * damping;
        let step = normal.cholesky()?.solve(&(jacobian.transpose() * error));
        let mut trial = q;
        for (value, delta) in trial.iter_mut().zip(step.iter()) {
            *value += delta;
        }
        let (e, j) = error_and_jacobian(chain, home, &trial, target);
        let n = e.norm();
        if n < norm {
            (q, error, jacobian, norm) = (trial, e, j, n);
            damping = (damping * 0.1).max(1e-12);
        } else {
            damping *= 10.0;
            if damping > 1e3 {
                return None;
            }
        }
    }
    (norm <= 1e-8).then_some(q)
}

/// The 6-D error `[p_T - p; w]` at `q` (`w` the vector of the skew part of
/// `R_T R'`, `sin` of the angle times the axis: accurate for small errors,
/// where an arccosine loses half the digits) and its Jacobian (world
/// frame, `d error / d q = -J`, returned as `J`).
fn error_and_jacobian(
    chain: &Chain,
    home: &Pose,
    q: &[f64; 6],
    target: &Pose,
) -> (Vector6<f64>, Matrix6<f64>) {
    let (c, h) = (&chain.c, &chain.h);
    let mut pose = Pose::identity();
    let mut axes = [Vector3::zeros(); 6];
    let mut points = [Vector3::zeros(); 6];
    for k in 0..6 {
        axes[k] = pose.rotation * h[k];
        points[k] = pose.transform_point(&c[k]);
        let r = rotation(&h[k], q[k]);
        pose = pose * Pose::new(r, c[k] - r * c[k]);
    }
    let pose = pose * *home;
    let r = target.rotation * pose.rotation.transpose();
    let rotation_error = Vector3::new(
        0.5 * (r[(2, 1)] - r[(1, 2)]),
        0.5 * (r[(0, 2)] - r[(2, 0)]),
        0.5 * (r[(1, 0)] - r[(0, 1)]),
    );
    let mut error = Vector6::zeros();
    error
        .fixed_rows_mut::<3>(0)
        .copy_from(&(target.translation - pose.translation));
    error.fixed_rows_mut::<3>(3).copy_from(&rotation_error);
    let mut jacobian = Matrix6::zeros();
    for k in 0..6 {
        let linear = axes[k].cross(&(pose.translation - points[k]));
        jacobian.fixed_view_mut::<3, 1>(0, k).copy_from(&linear);
        jacobian.fixed_view_mut::<3, 1>(3, k).copy_from(&axes[k]);
    }
    (error, jacobian)
}
