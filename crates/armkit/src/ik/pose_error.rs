//! The pose error that drives every numeric IK solver (seed 004, eqs 20-28).
//!
//! Seed 004 writes the error between the current end-effector pose
//! `(p_r, R_r)` and the goal `(p_f, R_f)` as the position difference
//! `dp = p_f - p_r` (eq 26) and the Euler axis `k` and angle `phi` of the
//! rotation that takes `R_r` onto `R_f` (eq 27): `R_f = Rot(k, phi) R_r`, so
//! `Rot(k, phi) = R_f R_r'`, a rotation expressed in the world frame. Stacked
//! as `e = [dp; k phi]` (metres, radians) it is the twist, in world axes, that
//! would carry the current pose onto the goal in unit time, which is why
//! `J dq = e` with the world-frame geometric Jacobian is the Newton step
//! (eq 28). The extraction of the paper lost the formulas; these are derived.
//!
//! ```
//! use armkit::ik::{pose_error, rotation_log};
//! use armkit::math::Pose;
//! let current = Pose::from_xyz_rpy([0.1, 0.2, 0.3], [0.0, 0.0, 0.0]);
//! let goal = Pose::from_xyz_rpy([0.1, 0.2, 0.5], [0.0, 0.0, 0.4]);
//! let e = pose_error(&goal, &current);
//! assert!((e[2] - 0.2).abs() < 1e-15); // 0.2 m up
//! assert!((e[5] - 0.4).abs() < 1e-15); // 0.4 rad about world z
//! assert!(rotation_log(&goal.rotation).norm() - 0.4 < 1e-15);
//! ```

use crate::math::{rotation_log, Matrix3, Pose, Vector3, Vector6};

/// The orientation error of seed 004 (eq 27): the rotation vector `k phi`
/// (rad, world axes) of `R_goal R_current'`, the rotation that carries the
/// current orientation onto the goal.
pub fn orientation_error(goal: &Matrix3<f64>, current: &Matrix3<f64>) -> Vector3<f64> {
    rotation_log(&(goal * current.transpose()))
}

/// The pose error of seed 004 (eqs 26-27): `[p_goal - p_current; k phi]`,
/// metres then radians, world axes (rows ordered like the Jacobian's,
/// `[vx, vy, vz, wx, wy, wz]`).
pub fn pose_error(goal: &Pose, current: &Pose) -> Vector6<f64> {
    let dp = goal.translation - current.translation;
    let dr = orientation_error(&goal.rotation, &current.rotation);
    Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z)
}

/// The size of a pose error restricted to the task components with a
/// non-zero weight: `(position error in m, orientation error in rad)`, each
/// the Euclidean norm of its three active components.
///
/// `weights` are the six task weights `[x, y, z, rx, ry, rz]` of
/// [`crate::ik::IkOptions::task_weights`]; a zero weight masks a component.
pub fn masked_error_norms(error: &Vector6<f64>, weights: &[f64; 6]) -> (f64, f64) {
    let mut position = 0.0;
    let mut orientation = 0.0;
    for i in 0..3 {
        if weights[i] > 0.0 {
            position += error[i] * error[i];
        }
        if weights[i + 3] > 0.0 {
            orientation += error[i + 3] * error[i + 3];
        }
    }
    (position.sqrt(), orientation.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Unit};

    fn rotation(axis: Vector3<f64>, angle: f64) -> Matrix3<f64> {
        Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle).into_inner()
    }

    #[test]
    fn log_inverts_exp_over_the_whole_range() {
        let axes = [
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.3, -0.4, 0.5),
            Vector3::new(-0.1, 0.9, 0.2),
            Vector3::new(0.0, 0.0, -1.0),
        ];
        for axis in axes {
            let k = axis.normalize();
            for angle in [
                0.0,
                1e-12,
                1e-6,
                0.3,
                1.5,
                2.0,
                2.5,
                3.0,
                std::f64::consts::PI - 1e-7,
                std::f64::consts::PI - 1e-12,
            ] {
                let log = rotation_log(&rotation(k, angle));
                let expected = k * angle;
                assert!(
                    (log - expected).norm() < 1e-14 * angle.max(1.0) + 1e-15,
                    "axis {k:?} angle {angle}: {log:?}"
                );
            }
        }
    }

    #[test]
    fn log_of_a_half_turn_has_angle_pi() {
        let r = rotation(Vector3::new(1.0, 2.0, 2.0), std::f64::consts::PI);
        let log = rotation_log(&r);
        assert!((log.norm() - std::f64::consts::PI).abs() < 1e-14);
        let k = log.normalize();
        let expected = Vector3::new(1.0, 2.0, 2.0) / 3.0;
        assert!((k - expected).norm() < 1e-12 || (k + expected).norm() < 1e-12);
    }

    #[test]
    fn pose_error_is_the_world_twist_to_the_goal() {
        // Small motion: J dq = e to first order means the goal is
        // exp([w]) R_current with w the orientation error.
        let current = Pose::from_xyz_rpy([0.4, -0.2, 0.9], [0.3, -0.5, 1.1]);
        let w = Vector3::new(1e-4, -2e-4, 3e-4);
        let goal = Pose::new(
            rotation(w, w.norm()) * current.rotation,
            current.translation + Vector3::new(1e-3, 0.0, -2e-3),
        );
        let e = pose_error(&goal, &current);
        assert!((e.fixed_rows::<3>(3) - w).norm() < 1e-15);
        assert!((e.fixed_rows::<3>(0) - Vector3::new(1e-3, 0.0, -2e-3)).norm() < 1e-15);
    }

    #[test]
    fn masked_norms_ignore_zero_weights() {
        let e = Vector6::new(3.0, 4.0, 12.0, 1.0, 2.0, 2.0);
        let (p, o) = masked_error_norms(&e, &[1.0; 6]);
        assert!((p - 13.0).abs() < 1e-15 && (o - 3.0).abs() < 1e-15);
        let (p, o) = masked_error_norms(&e, &[1.0, 1.0, 0.0, 0.0, 0.0, 0.0]);
        assert!((p - 5.0).abs() < 1e-15 && o == 0.0);
    }
}
