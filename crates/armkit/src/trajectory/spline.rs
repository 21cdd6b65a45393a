//! The clamped C2 cubic spline through joint-space via points at given times.
//!
//! One cubic per interval; positions, velocities and accelerations are
//! continuous at every via point, the acceleration is linear on each interval
//! (seed 004's fitting, eqs 33-42), and the velocities at both ends are given
//! ("clamped"). This is the spline seed 004's singularity avoidance fits to
//! the joint angles of its warm-started IK solves.
//!
//! Unknowns are the velocities `v_i` at the interior via points. With
//! `h_i = t_{i+1} - t_i` and slopes `d_i = (q_{i+1} - q_i) / h_i`, equal
//! accelerations on both sides of via point `i` (each interval a cubic
//! Hermite) give the symmetric, strictly diagonally dominant tridiagonal system
//! `v_{i-1} / h_{i-1} + 2 (1/h_{i-1} + 1/h_i) v_i + v_{i+1} / h_i
//!  = 3 (d_{i-1} / h_{i-1} + d_i / h_i)`,
//! solved by the Thomas algorithm (stable without pivoting) for all joints at once.
//!
//! ```
//! use armkit::trajectory::clamped_cubic_spline;
//! let times = [0.0, 1.0, 2.5, 4.0];
//! let points = [vec![0.0, 1.0], vec![0.5, 0.8], vec![1.2, 0.2], vec![1.0, 0.0]];
//! let spline = clamped_cubic_spline(&times, &points, &[0.0, 0.0], &[0.0, 0.0]).unwrap();
//! let at = spline.sample(2.5).unwrap();
//! assert!((at.position[0] - 1.2).abs() < 1e-12);
//! let [dq, dv, da] = spline.knot_discontinuities();
//! assert!(dq < 1e-12 && dv < 1e-12 && da < 1e-9);
//! ```

use super::poly;
use super::Trajectory;
use crate::error::{check_finite, check_finite_vector, Error, Result};

/// The clamped cubic spline through `positions[i]` at `times[i]` (s,
/// strictly increasing, at least 2), with joint velocities `start_velocity`
/// at the first time and `end_velocity` at the last (rad/s or m/s).
///
/// The trajectory runs from `times[0]` to the last time. Every position
/// vector must have the same length (the number of joints). With two points
/// it is the cubic Hermite segment.
///
/// Errors: fewer than 2 points, times not strictly increasing or not finite,
/// mismatched sizes, non-finite values.
pub fn clamped_cubic_spline<P: AsRef<[f64]>>(
    times: &[f64],
    positions: &[P],
    start_velocity: &[f64],
    end_velocity: &[f64],
) -> Result<Trajectory> {
    let dof = check_via_points(times, positions)?;
    check_finite_vector("start_velocity", start_velocity, dof)?;
    check_finite_vector("end_velocity", end_velocity, dof)?;
    let m = times.len() - 1;
    let h: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    // velocities[i * dof + j]: velocity of joint j at via point i.
    let mut velocities = vec![0.0; (m + 1) * dof];
    velocities[..dof].copy_from_slice(start_velocity);
    velocities[m * dof..].copy_from_slice(end_velocity);
    if m >= 2 {
        // Thomas algorithm on the interior unknowns 1..m-1; the sub- and
        // super-diagonals are 1/h_{i-1} and 1/h_i.
        let mut diagonal = vec![0.0; m];
        let mut rhs = vec![0.0; (m + 1) * dof];
        for i in 1..m {
            diagonal[i] = 2.0 * (1.0 / h[i - 1] + 1.0 / h[i]);
            let q_prev = positions[i - 1].as_ref();
            let q = positions[i].as_ref();
            let q_next = positions[i + 1].as_ref();
            for j in 0..dof {
                let d_prev = (q[j] - q_prev[j]) / h[i - 1];
                let d_next = (q_next[j] - q[j]) / h[i];
                rhs[i * dof + j] = 3.0 * (d_prev / h[i - 1] + d_next / h[i]);
            }
        }
        for j in 0..dof {
            rhs[dof + j] -= start_velocity[j] / h[0];
            rhs[(m - 1) * dof + j] -= end_velocity[j] / h[m - 1];
        }
        for i in 2..m {
            let w = (1.0 / h[i - 1]) / diagonal[i - 1];
            diagonal[i] -= w / h[i - 1];
            for j in 0..dof {
                rhs[i * dof + j] -= w * rhs[(i - 1) * dof + j];
            }
        }
        for i in (1..m).rev() {
            for j in 0..dof {
                let next = if i + 1 < m {
                    velocities[(i + 1) * dof + j] / h[i]
                } else {
                    0.0
                };
                velocities[i * dof + j] = (rhs[i * dof + j] - next) / diagonal[i];
            }
        }
    }
    let mut coefficients = Vec::with_capacity(m * dof);
    for i in 0..m {
        let (q0, q1) = (positions[i].as_ref(), positions[i + 1].as_ref());
        for j in 0..dof {
            coefficients.push(poly::cubic_hermite(
                q0[j],
                velocities[i * dof + j] * h[i],
                q1[j],
                velocities[(i + 1) * dof + j] * h[i],
            ));
        }
    }
    Trajectory::from_polynomials(times.to_vec(), dof, coefficients)
}

/// Checks via points (at least 2, strictly increasing finite times, equal
/// non-zero sizes, finite values) and returns the number of joints.
pub(crate) fn check_via_points<P: AsRef<[f64]>>(times: &[f64], positions: &[P]) -> Result<usize> {
    if times.len() < 2 {
        return Err(Error::invalid_argument(
            "times",
            format!("need at least 2 via points, got {}", times.len()),
        ));
    }
    if positions.len() != times.len() {
        return Err(Error::DimensionMismatch {
            what: "positions (one per time)",
            expected: times.len(),
            got: positions.len(),
        });
    }
    check_finite("times", times)?;
    if let Some(i) = times.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::invalid_argument(
            "times",
            format!(
                "must be strictly increasing: times[{}] = {} is not after times[{i}] = {}",
                i + 1,
                times[i + 1],
                times[i]
            ),
        ));
    }
    let dof = positions[0].as_ref().len();
    if dof == 0 {
        return Err(Error::invalid_argument(
            "positions",
            "need at least one joint",
        ));
    }
    for p in positions {
        check_finite_vector("positions[i]", p.as_ref(), dof)?;
    }
    Ok(dof)
}
