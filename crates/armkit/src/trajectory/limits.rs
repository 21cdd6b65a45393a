//! Where a trajectory exceeds its joint limits, and uniform time scaling to
//! meet velocity and acceleration limits.
//!
//! Checks are exact, not sampled: on each segment the polynomial of the
//! position, velocity or acceleration is compared with the bound through the
//! real roots of `f - bound`, and peaks are found at the roots of the next
//! derivative. A value counts as exceeding its bound when it does so by more
//! than `1e-9` relative (so that a trajectory scaled to touch a limit does not
//! report a violation from rounding).
//!
//! ```
//! use armkit::trajectory::{check_limits, scale_to_limits, TimeScaling, TrajectoryLimits};
//! use armkit::trajectory::{quintic, JointState};
//! let traj = quintic(&JointState::at_rest(&[0.0]), &JointState::at_rest(&[2.0]), 1.0).unwrap();
//! // A quintic's peak velocity is 1.875 d / T = 3.75 rad/s here.
//! let limits = TrajectoryLimits::new(vec![3.0], vec![f64::INFINITY]).unwrap();
//! let violations = check_limits(&traj, &limits).unwrap();
//! assert_eq!(violations.len(), 1);
//! assert!((violations[0].peak_value - 3.75).abs() < 1e-12);
//! assert!((violations[0].peak_time - 0.5).abs() < 1e-9);
//! let slower = scale_to_limits(&traj, &limits, TimeScaling::SlowDownOnly).unwrap();
//! assert!((slower.trajectory.duration() - 1.25).abs() < 1e-12);
//! assert!(check_limits(&slower.trajectory, &limits).unwrap().is_empty());
//! ```

use super::poly;
use super::Trajectory;
use crate::error::{check_finite_vector, Error, Result};
use crate::model::{JointLimits, Model};

/// Joint limits a trajectory is checked against.
///
/// One entry per joint in each vector. Position bounds in rad or m
/// (`-inf` / `+inf` for none); velocity and acceleration limits are bounds on
/// the magnitude, `> 0`, in rad/s and rad/s^2 or m/s and m/s^2 (`+inf` for none).
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryLimits {
    /// Lower position bounds.
    pub lower: Vec<f64>,
    /// Upper position bounds.
    pub upper: Vec<f64>,
    /// Velocity magnitude limits.
    pub velocity: Vec<f64>,
    /// Acceleration magnitude limits.
    pub acceleration: Vec<f64>,
}

impl TrajectoryLimits {
    /// Velocity and acceleration limits only (positions unbounded), checked.
    pub fn new(velocity: Vec<f64>, acceleration: Vec<f64>) -> Result<Self> {
        let dof = velocity.len();
        let limits = TrajectoryLimits {
            lower: vec![f64::NEG_INFINITY; dof],
            upper: vec![f64::INFINITY; dof],
            velocity,
            acceleration,
        };
        limits.validate()?;
        Ok(limits)
    }

    /// The model's limits; a missing velocity or acceleration limit is `+inf`.
    pub fn from_model(model: &Model) -> Self {
        let limits: Vec<JointLimits> = model.joints().iter().map(|j| j.limits).collect();
        Self::from_joint_limits(&limits)
    }

    /// Per-joint [`JointLimits`] (the model's vocabulary: `lower`, `upper`,
    /// `velocity`, `acceleration`) as one set; a missing velocity or
    /// acceleration limit is `+inf`.
    pub fn from_joint_limits(limits: &[JointLimits]) -> Self {
        TrajectoryLimits {
            lower: limits.iter().map(|l| l.lower).collect(),
            upper: limits.iter().map(|l| l.upper).collect(),
            velocity: limits
                .iter()
                .map(|l| l.velocity.unwrap_or(f64::INFINITY))
                .collect(),
            acceleration: limits
                .iter()
                .map(|l| l.acceleration.unwrap_or(f64::INFINITY))
                .collect(),
        }
    }

    /// Joint `j`'s limits as a [`JointLimits`] (`+inf` becomes `None`);
    /// `None` for a joint index out of range.
    pub fn joint(&self, j: usize) -> Option<JointLimits> {
        let finite = |v: f64| v.is_finite().then_some(v);
        Some(JointLimits {
            lower: *self.lower.get(j)?,
            upper: *self.upper.get(j)?,
            velocity: finite(*self.velocity.get(j)?),
            acceleration: finite(*self.acceleration.get(j)?),
            // Torque limits need the dynamics: `torque_profile` checks them.
            effort: None,
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.velocity.len()
    }

    /// Checks sizes, `lower <= upper` (no NaN), and velocity and acceleration
    /// limits `> 0` (infinite allowed). The error names the field and joint.
    pub fn validate(&self) -> Result<()> {
        let dof = self.dof();
        if dof == 0 {
            return Err(Error::invalid_argument(
                "limits",
                "must have at least one joint",
            ));
        }
        for (what, v) in [
            ("limits.lower", &self.lower),
            ("limits.upper", &self.upper),
            ("limits.acceleration", &self.acceleration),
        ] {
            if v.len() != dof {
                return Err(Error::DimensionMismatch {
                    what,
                    expected: dof,
                    got: v.len(),
                });
            }
        }
        for j in 0..dof {
            if self.lower[j].is_nan() || self.upper[j].is_nan() || self.lower[j] > self.upper[j] {
                return Err(Error::invalid_argument(
                    format!("limits.lower[{j}], limits.upper[{j}]"),
                    format!(
                        "need lower <= upper, got [{}, {}]",
                        self.lower[j], self.upper[j]
                    ),
                ));
            }
            for (what, v) in [
                ("velocity", self.velocity[j]),
                ("acceleration", self.acceleration[j]),
            ] {
                if v.is_nan() || v <= 0.0 {
                    return Err(Error::invalid_argument(
                        format!("limits.{what}[{j}]"),
                        format!("must be > 0 (or infinite for none), got {v}"),
                    ));
                }
            }
        }
        Ok(())
    }

    pub(crate) fn check_dof(&self, dof: usize) -> Result<()> {
        self.validate()?;
        if self.dof() != dof {
            return Err(Error::DimensionMismatch {
                what: "limits (joints)",
                expected: dof,
                got: self.dof(),
            });
        }
        Ok(())
    }
}

/// Which quantity exceeds its limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LimitKind {
    /// Joint position (rad or m) outside `[lower, upper]`.
    Position,
    /// Joint velocity magnitude (rad/s or m/s) above its limit.
    Velocity,
    /// Joint acceleration magnitude (rad/s^2 or m/s^2) above its limit.
    Acceleration,
}

/// One time interval during which one joint exceeds one limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LimitViolation {
    /// 0-based joint index.
    pub joint: usize,
    /// Position, velocity or acceleration.
    pub kind: LimitKind,
    /// First time the bound is exceeded, s.
    pub start_time: f64,
    /// Last time it is exceeded, s.
    pub end_time: f64,
    /// Time of the worst value, s.
    pub peak_time: f64,
    /// The worst value (signed; rad, rad/s, rad/s^2 or m, m/s, m/s^2).
    pub peak_value: f64,
    /// The bound crossed (signed: `upper` or `lower` for positions, `+limit`
    /// or `-limit` for rates).
    pub bound: f64,
}

/// Largest magnitudes of velocity and acceleration of each joint, with when
/// they occur.
#[derive(Clone, Debug, PartialEq)]
pub struct PeakRates {
    /// Per joint: largest |velocity| (rad/s or m/s).
    pub velocity: Vec<f64>,
    /// Per joint: time of the largest |velocity|, s.
    pub velocity_time: Vec<f64>,
    /// Per joint: largest |acceleration| (rad/s^2 or m/s^2).
    pub acceleration: Vec<f64>,
    /// Per joint: time of the largest |acceleration|, s.
    pub acceleration_time: Vec<f64>,
}

/// The polynomial of joint `joint`'s quantity `kind` on `segment`, in physical
/// units, as a function of `phi`.
fn quantity(traj: &Trajectory, segment: usize, joint: usize, kind: LimitKind) -> [f64; 6] {
    let c = traj.coefficients[segment * traj.dof + joint];
    let rate = traj.inverse_durations[segment];
    match kind {
        LimitKind::Position => c,
        LimitKind::Velocity => poly::derivative(&c).map(|v| v * rate),
        LimitKind::Acceleration => poly::derivative(&poly::derivative(&c)).map(|v| v * rate * rate),
    }
}

/// Largest `score(f(phi))` over `[a, b]` and where (phi): the extremes of
/// `f` lie at the ends or at the roots of `f'`.
fn extremum(f: &[f64; 6], a: f64, b: f64, score: impl Fn(f64) -> f64) -> (f64, f64) {
    let roots = poly::roots_in_unit_interval(&poly::derivative(f));
    let candidates = roots
        .as_slice()
        .iter()
        .copied()
        .filter(|&r| r > a && r < b)
        .chain([a, b]);
    candidates.fold((f64::NEG_INFINITY, a), |best, phi| {
        let v = score(poly::value(f, phi));
        if v > best.0 {
            (v, phi)
        } else {
            best
        }
    })
}

/// Largest |velocity| and |acceleration| of every joint (exact, through the
/// roots of the next derivative on each segment).
pub fn peak_rates(traj: &Trajectory) -> PeakRates {
    let dof = traj.dof();
    let mut peaks = PeakRates {
        velocity: vec![0.0; dof],
        velocity_time: vec![traj.start_time(); dof],
        acceleration: vec![0.0; dof],
        acceleration_time: vec![traj.start_time(); dof],
    };
    for segment in 0..traj.segment_count() {
        let t0 = traj.knots[segment];
        let h = traj.knots[segment + 1] - t0;
        for joint in 0..dof {
            for kind in [LimitKind::Velocity, LimitKind::Acceleration] {
                let f = quantity(traj, segment, joint, kind);
                let (peak, time) = if kind == LimitKind::Velocity {
                    (&mut peaks.velocity[joint], &mut peaks.velocity_time[joint])
                } else {
                    (
                        &mut peaks.acceleration[joint],
                        &mut peaks.acceleration_time[joint],
                    )
                };
                let (value, phi) = extremum(&f, 0.0, 1.0, f64::abs);
                if value > *peak {
                    *peak = value;
                    *time = t0 + phi * h;
                }
            }
        }
    }
    peaks
}

/// Every interval during which a joint's position leaves `[lower, upper]` or
/// its velocity or acceleration magnitude exceeds its limit, sorted by start
/// time. Intervals that continue across a knot are merged.
///
/// Errors: limits for another number of joints, or invalid limits.
pub fn check_limits(traj: &Trajectory, limits: &TrajectoryLimits) -> Result<Vec<LimitViolation>> {
    limits.check_dof(traj.dof())?;
    let mut found: Vec<LimitViolation> = Vec::new();
    for joint in 0..traj.dof() {
        let bounds = [
            (LimitKind::Position, limits.upper[joint], 1.0),
            (LimitKind::Position, limits.lower[joint], -1.0),
            (LimitKind::Velocity, limits.velocity[joint], 1.0),
            (LimitKind::Velocity, -limits.velocity[joint], -1.0),
            (LimitKind::Acceleration, limits.acceleration[joint], 1.0),
            (LimitKind::Acceleration, -limits.acceleration[joint], -1.0),
        ];
        for (kind, bound, sign) in bounds {
            if !bound.is_finite() {
                continue;
            }
            let tolerance = 1e-9 * bound.abs().max(1.0);
            let mut open: Option<LimitViolation> = None;
            for segment in 0..traj.segment_count() {
                let f = quantity(traj, segment, joint, kind);
                // Excess e(phi) = sign (f - bound) > 0 means outside.
                let mut excess = f.map(|c| sign * c);
                excess[0] -= sign * bound;
                let roots = poly::roots_in_unit_interval(&excess);
                let t0 = traj.knots[segment];
                let h = traj.knots[segment + 1] - t0;
                let mut edges = [0.0; 7];
                let inner = roots.as_slice();
                edges[1..=inner.len()].copy_from_slice(inner);
                edges[inner.len() + 1] = 1.0;
                for w in edges[..inner.len() + 2].windows(2) {
                    let (a, b) = (w[0], w[1]);
                    let (worst, phi) = extremum(&excess, a, b, |v| v);
                    if worst <= tolerance {
                        if let Some(v) = open.take() {
                            found.push(v);
                        }
                        continue;
                    }
                    let peak_value = poly::value(&f, phi);
                    let (ta, tb, tp) = (t0 + a * h, t0 + b * h, t0 + phi * h);
                    match &mut open {
                        Some(v) => {
                            v.end_time = tb;
                            if sign * (peak_value - v.peak_value) > 0.0 {
                                v.peak_value = peak_value;
                                v.peak_time = tp;
                            }
                        }
                        None => {
                            open = Some(LimitViolation {
                                joint,
                                kind,
                                start_time: ta,
                                end_time: tb,
                                peak_time: tp,
                                peak_value,
                                bound,
                            })
                        }
                    }
                }
            }
            if let Some(v) = open.take() {
                found.push(v);
            }
        }
    }
    found.sort_by(|a, b| {
        a.start_time
            .total_cmp(&b.start_time)
            .then(a.joint.cmp(&b.joint))
    });
    Ok(found)
}

/// How [`scale_to_limits`] may change the duration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TimeScaling {
    /// Only slow down: a trajectory within its limits is returned unchanged.
    SlowDownOnly,
    /// Slow down or speed up until the tightest velocity or acceleration limit
    /// is met exactly (minimum time for this path and timing shape).
    Tight,
}

/// A time-scaled trajectory and the factor applied to its duration.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaledTrajectory {
    /// The scaled trajectory.
    pub trajectory: Trajectory,
    /// New duration / old duration.
    pub factor: f64,
}

/// Uniform time scaling to meet velocity and acceleration limits.
///
/// Playing the same path `k` times slower divides velocities by `k` and
/// accelerations by `k^2`, so
/// `k = max_j max(peak_v_j / vmax_j, sqrt(peak_a_j / amax_j))` is the smallest
/// factor that meets every limit. Uniform scaling keeps the joint-space path
/// and the continuity of the trajectory; it scales non-zero boundary
/// velocities by `1 / k` too. Position limits are not affected by timing (use
/// [`check_limits`] for them).
///
/// Errors: limits for another number of joints; [`TimeScaling::Tight`] on a
/// moving trajectory without a finite velocity or acceleration limit on any
/// moving joint (it could be made arbitrarily fast).
pub fn scale_to_limits(
    traj: &Trajectory,
    limits: &TrajectoryLimits,
    mode: TimeScaling,
) -> Result<ScaledTrajectory> {
    limits.check_dof(traj.dof())?;
    let peaks = peak_rates(traj);
    let mut factor = 0.0f64;
    for j in 0..traj.dof() {
        factor = factor
            .max(peaks.velocity[j] / limits.velocity[j])
            .max((peaks.acceleration[j] / limits.acceleration[j]).sqrt());
    }
    check_finite_vector("time scaling factor", &[factor], 1)?;
    let moving = peaks
        .velocity
        .iter()
        .chain(&peaks.acceleration)
        .any(|&p| p > 0.0);
    let factor = match mode {
        TimeScaling::SlowDownOnly => factor.max(1.0),
        TimeScaling::Tight if !moving => 1.0,
        TimeScaling::Tight if factor == 0.0 => {
            return Err(Error::invalid_argument(
                "limits",
                "no finite velocity or acceleration limit on a moving joint: \
                 the motion could be made arbitrarily fast",
            ))
        }
        TimeScaling::Tight => factor,
    };
    Ok(ScaledTrajectory {
        trajectory: traj.time_scaled(factor)?,
        factor,
    })
}
