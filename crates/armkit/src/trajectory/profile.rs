//! Point-to-point joint-space profiles, synchronized over all joints: cubic,
//! quintic and trapezoidal velocity, for a given duration or in minimum time.
//!
//! Every profile starts at time 0 and is one [`Trajectory`]. Synchronized
//! means all joints start and stop together; the rest-to-rest profiles
//! ([`trapezoidal`], [`minimum_time`], and [`cubic`] / [`quintic`] from rest
//! to rest) move every joint as `q(t) = q0 + s(t) (qf - q0)` with one scalar
//! `s(t)` from 0 to 1: a straight line in joint space, whatever the timing.
//!
//! ```
//! use armkit::trajectory::{minimum_time, quintic, JointState, ProfileShape, TrajectoryLimits};
//! let q0 = [0.0, 0.5];
//! let qf = [1.0, -0.5];
//! // Quintic in 2 s, from and to rest.
//! let profile = quintic(&JointState::at_rest(&q0), &JointState::at_rest(&qf), 2.0).unwrap();
//! let mid = profile.sample(1.0).unwrap();
//! assert!((mid.position[0] - 0.5).abs() < 1e-12);
//! // The fastest trapezoid under 1 rad/s and 2 rad/s^2 on both joints.
//! let limits = TrajectoryLimits::new(vec![1.0, 1.0], vec![2.0, 2.0]).unwrap();
//! let fastest = minimum_time(ProfileShape::Trapezoidal, &q0, &qf, &limits).unwrap();
//! assert!((fastest.duration() - 1.5).abs() < 1e-12); // 0.5 s ramps, 0.5 s cruise
//! ```

use super::limits::{scale_to_limits, TimeScaling, TrajectoryLimits};
use super::poly;
use super::{JointState, Trajectory};
use crate::error::{brief, check_finite_vector, Error, Result};

/// Shortest duration a profile ([`cubic`], [`quintic`], [`trapezoidal`],
/// [`rest_to_rest`]) plans, s; [`minimum_time`] stretches a shorter move to
/// it. Below a millisecond the accelerations of a move of a few radians
/// leave what any joint (or the torque fit's slow-down, `1 / k^2`) can take
/// in floating point.
pub const MIN_DURATION: f64 = 1e-3;

/// Longest duration a profile plans, s (about 11.6 days): beyond it
/// the polynomial coefficients (`1 / T^5`) underflow.
pub const MAX_DURATION: f64 = 1e6;

/// The shape of a point-to-point profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProfileShape {
    /// Cubic polynomial: continuous velocity, acceleration jumps at the ends.
    Cubic,
    /// Quintic polynomial: continuous acceleration.
    Quintic,
    /// Trapezoidal velocity (linear segment with parabolic blends): constant
    /// acceleration, cruise, constant deceleration.
    Trapezoidal,
}

fn check_duration(duration: f64) -> Result<()> {
    if !(MIN_DURATION..=MAX_DURATION).contains(&duration) {
        return Err(Error::invalid_argument(
            "duration",
            format!(
                "must be in [{MIN_DURATION}, {}] s, got {} s",
                brief(MAX_DURATION),
                brief(duration)
            ),
        ));
    }
    Ok(())
}

/// Checks two endpoint vectors of equal, non-zero length.
fn check_endpoints(q0: &[f64], qf: &[f64]) -> Result<usize> {
    if q0.is_empty() {
        return Err(Error::invalid_argument(
            "q0",
            "must have at least one joint",
        ));
    }
    check_finite_vector("q0", q0, q0.len())?;
    check_finite_vector("qf", qf, q0.len())?;
    Ok(q0.len())
}

/// One-segment profile from per-joint coefficient formulas in normalized units.
fn single_segment(
    start: &JointState,
    end: &JointState,
    duration: f64,
    coefficients: impl Fn(usize, f64, f64) -> [f64; 6],
) -> Result<Trajectory> {
    check_duration(duration)?;
    let dof = start.dof();
    if dof == 0 {
        return Err(Error::invalid_argument(
            "start",
            "must have at least one joint",
        ));
    }
    start.check(dof)?;
    end.check(dof)?;
    let h = duration;
    let c = (0..dof).map(|j| coefficients(j, h, h * h)).collect();
    Trajectory::from_polynomials(vec![0.0, duration], dof, c)
}

/// Cubic profile from `start` to `end` in `duration` seconds, meeting the
/// positions and velocities of both states (`q(0) = q0`, `q'(0) = v0`,
/// `q(T) = qf`, `q'(T) = vf`).
///
/// A cubic cannot meet boundary accelerations: both states' accelerations
/// must be zero (use [`quintic`] otherwise). Errors: `duration` outside
/// [[`MIN_DURATION`], [`MAX_DURATION`]] s, mismatched sizes, non-finite
/// values, non-zero boundary accelerations.
pub fn cubic(start: &JointState, end: &JointState, duration: f64) -> Result<Trajectory> {
    for (what, state) in [("start", start), ("end", end)] {
        if state.acceleration.iter().any(|&a| a != 0.0) {
            return Err(Error::invalid_argument(
                format!("{what}.acceleration"),
                "a cubic cannot meet a boundary acceleration: pass zeros, or use a quintic",
            ));
        }
    }
    single_segment(start, end, duration, |j, h, _| {
        poly::cubic_hermite(
            start.position[j],
            start.velocity[j] * h,
            end.position[j],
            end.velocity[j] * h,
        )
    })
}

/// Quintic profile from `start` to `end` in `duration` seconds, meeting
/// position, velocity and acceleration at both ends.
///
/// Errors: `duration` outside [[`MIN_DURATION`], [`MAX_DURATION`]] s,
/// mismatched sizes, non-finite values.
pub fn quintic(start: &JointState, end: &JointState, duration: f64) -> Result<Trajectory> {
    single_segment(start, end, duration, |j, h, h2| {
        poly::quintic_hermite(
            start.position[j],
            start.velocity[j] * h,
            start.acceleration[j] * h2,
            end.position[j],
            end.velocity[j] * h,
            end.acceleration[j] * h2,
        )
    })
}

/// Trapezoidal velocity profile from rest at `q0` to rest at `qf` in
/// `duration` seconds, with `acceleration_time` seconds of constant
/// acceleration at the start and of constant deceleration at the end.
///
/// All joints share the timing (synchronized): joint `j` cruises at
/// `v_j = (qf_j - q0_j) / (T - ta)` and accelerates at `v_j / ta`.
/// `acceleration_time = duration / 2` gives a triangular profile (no cruise).
/// `q0 == qf` gives a trajectory that stays put. Seed 004's path is
/// `trapezoidal(.., 20.0, 4.0)`.
///
/// Errors: `duration` outside [[`MIN_DURATION`], [`MAX_DURATION`]] s;
/// `acceleration_time <= 0` or `> duration / 2` (the ramps would overlap);
/// mismatched sizes; non-finite values.
pub fn trapezoidal(
    q0: &[f64],
    qf: &[f64],
    duration: f64,
    acceleration_time: f64,
) -> Result<Trajectory> {
    let dof = check_endpoints(q0, qf)?;
    check_duration(duration)?;
    if !(acceleration_time.is_finite() && acceleration_time > 0.0) {
        return Err(Error::invalid_argument(
            "acceleration_time",
            format!("must be finite and > 0 s, got {acceleration_time} s"),
        ));
    }
    if acceleration_time > 0.5 * duration {
        return Err(Error::invalid_argument(
            "acceleration_time",
            format!(
                "must be at most half the duration ({} s) so that acceleration and \
                 deceleration do not overlap, got {acceleration_time} s",
                0.5 * duration
            ),
        ));
    }
    let ta = acceleration_time;
    let cruise = duration - 2.0 * ta;
    // A cruise shorter than rounding of the knots is a triangular profile.
    let triangular = cruise <= 1e-12 * duration;
    let mut knots = vec![0.0, ta];
    if !triangular {
        knots.push(duration - ta);
    }
    knots.push(duration);
    let segments = knots.len() - 1;
    let mut coefficients = vec![[0.0; 6]; segments * dof];
    for j in 0..dof {
        let delta = qf[j] - q0[j];
        // Cruise velocity v = delta / (T - ta); in normalized units the ramp
        // (length ta, acceleration v / ta) covers v ta / 2 with end velocity v ta.
        let v = delta / (duration - ta);
        let ramp = 0.5 * v * ta;
        coefficients[j] = [q0[j], 0.0, ramp, 0.0, 0.0, 0.0];
        if !triangular {
            coefficients[dof + j] = [q0[j] + ramp, v * cruise, 0.0, 0.0, 0.0, 0.0];
        }
        coefficients[(segments - 1) * dof + j] = [qf[j] - ramp, v * ta, -ramp, 0.0, 0.0, 0.0];
    }
    Trajectory::from_polynomials(knots, dof, coefficients)
}

/// The fastest rest-to-rest profile of the given shape from `q0` to `qf`
/// under the velocity and acceleration limits (synchronized: the slowest
/// joint sets the time, the others are slowed to match).
///
/// * Trapezoidal: with `C = max_j |dq_j| / vmax_j` and
///   `P = max_j |dq_j| / amax_j`, every joint obeys its limits when
///   `T - ta >= C` and `ta (T - ta) >= P`; `T = c + P / c` is smallest at
///   `c = T - ta = max(C, sqrt(P))`, which also keeps `ta <= T / 2`.
///   Needs a finite acceleration limit on every moving joint.
/// * Cubic and quintic: the shape is fixed, so the profile is planned in 1 s
///   and time-scaled until the tightest limit is met exactly
///   ([`scale_to_limits`] with [`TimeScaling::Tight`]).
///
/// A zero-length move returns a stationary trajectory of zero duration.
pub fn minimum_time(
    shape: ProfileShape,
    q0: &[f64],
    qf: &[f64],
    limits: &TrajectoryLimits,
) -> Result<Trajectory> {
    let dof = check_endpoints(q0, qf)?;
    limits.check_dof(dof)?;
    if q0 == qf {
        return Trajectory::stationary(q0, 0.0, 0.0);
    }
    match shape {
        ProfileShape::Trapezoidal => {
            let mut c_velocity = 0.0f64;
            let mut p_acceleration = 0.0f64;
            for j in 0..dof {
                let delta = (qf[j] - q0[j]).abs();
                if delta == 0.0 {
                    continue;
                }
                if !limits.acceleration[j].is_finite() {
                    return Err(Error::invalid_argument(
                        format!("limits.acceleration[{j}]"),
                        "a minimum-time trapezoid needs a finite acceleration limit on every moving joint",
                    ));
                }
                c_velocity = c_velocity.max(delta / limits.velocity[j]);
                p_acceleration = p_acceleration.max(delta / limits.acceleration[j]);
            }
            let c = c_velocity.max(p_acceleration.sqrt());
            let ta = p_acceleration / c;
            // A move shorter than MIN_DURATION is stretched to it: slower
            // keeps every velocity and acceleration within its limit.
            let stretch = (MIN_DURATION / (c + ta)).max(1.0);
            trapezoidal(q0, qf, (c + ta) * stretch, ta.min(0.5 * (c + ta)) * stretch)
        }
        ProfileShape::Cubic | ProfileShape::Quintic => {
            let start = JointState::at_rest(q0);
            let end = JointState::at_rest(qf);
            let unit = if shape == ProfileShape::Cubic {
                cubic(&start, &end, 1.0)?
            } else {
                quintic(&start, &end, 1.0)?
            };
            Ok(scale_to_limits(&unit, limits, TimeScaling::Tight)?.trajectory)
        }
    }
}

/// A rest-to-rest profile of the given shape in `duration` seconds.
/// `acceleration_time` (s) is required for the trapezoid and must be `None`
/// for the cubic and the quintic.
///
/// Errors as the individual profiles, plus a clear message when
/// `acceleration_time` is missing for a trapezoid or given for a polynomial,
/// and `duration` outside [[`MIN_DURATION`], [`MAX_DURATION`]] s (named
/// `duration`).
pub fn rest_to_rest(
    shape: ProfileShape,
    q0: &[f64],
    qf: &[f64],
    duration: f64,
    acceleration_time: Option<f64>,
) -> Result<Trajectory> {
    check_endpoints(q0, qf)?;
    check_duration(duration)?;
    match (shape, acceleration_time) {
        (ProfileShape::Trapezoidal, Some(ta)) => trapezoidal(q0, qf, duration, ta),
        (ProfileShape::Trapezoidal, None) => Err(Error::invalid_argument(
            "acceleration_time",
            "a trapezoidal profile with a given duration needs an acceleration time",
        )),
        (_, Some(_)) => Err(Error::invalid_argument(
            "acceleration_time",
            "only the trapezoidal profile has an acceleration time",
        )),
        (ProfileShape::Cubic, None) => {
            cubic(&JointState::at_rest(q0), &JointState::at_rest(qf), duration)
        }
        (ProfileShape::Quintic, None) => {
            quintic(&JointState::at_rest(q0), &JointState::at_rest(qf), duration)
        }
    }
}
