//! Cartesian paths of the end-effector, timed by a scalar law.
//!
//! A path is geometry: a pose `X(s)` for `s in [0, 1]` ([`CartesianPath`]):
//! a straight line with the orientation interpolated by slerp
//! ([`LinePath`]), a circular arc ([`ArcPath`]), or any user curve
//! ([`FnPath`], seed 002 eq 19). A [`CartesianTrajectory`] times it with a
//! scalar law `s(t)` ([`TimeLaw`]: linear, trapezoidal or quintic, or any
//! one-joint [`Trajectory`] from 0 to 1), and either follows the path's own
//! orientation or, as seed 002 does (eqs 20-22), interpolates the
//! roll-pitch-yaw angles of the end poses linearly in time
//! ([`OrientationLaw`]).
//!
//! Frames and units: poses in the world frame, metres and radians; twists and
//! their derivatives are `[v; w]` (linear velocity of the end-effector origin,
//! angular velocity), world axes, m/s and rad/s (m/s^2, rad/s^2).
//!
//! ```
//! use armkit::math::Pose;
//! use armkit::trajectory::{CartesianTrajectory, LinePath, TimeLaw};
//! let start = Pose::from_xyz_rpy([0.4, 0.0, 0.3], [0.0, 0.0, 0.0]);
//! let end = Pose::from_xyz_rpy([0.4, 0.3, 0.3], [0.0, 0.0, 0.5]);
//! let line = LinePath::new(start, end).unwrap();
//! let timing = TimeLaw::Trapezoidal { acceleration_time: 0.5 }.timing(2.0).unwrap();
//! let traj = CartesianTrajectory::new(line, timing).unwrap();
//! let mid = traj.sample(1.0).unwrap();
//! assert!((mid.pose.translation.y - 0.15).abs() < 1e-12);
//! assert!((mid.twist[1] - 0.3 / 1.5).abs() < 1e-12); // cruise speed d / (T - ta)
//! assert!((mid.pose.rpy().2 - 0.25).abs() < 1e-12);  // slerp: half the yaw
//! ```

use std::fmt;

use super::limits::{check_limits, TrajectoryLimits};
use super::{profile, JointState, Trajectory};
use crate::error::{check_finite, Error, Result};
use crate::math::{rotation_log, Pose, Rotation3, Vector3, Vector6};

/// A pose and its first two derivatives with respect to the path parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathDerivatives {
    /// The pose `X(s)`, world frame.
    pub pose: Pose,
    /// `[dp/ds; w_s]`: position derivative (m) and the angular rate per unit
    /// `s` (rad) with `dR/ds = [w_s]x R`, world axes.
    pub first: Vector6<f64>,
    /// `[d2p/ds2; dw_s/ds]`, world axes.
    pub second: Vector6<f64>,
}

/// A geometric end-effector path `X(s)`, `s in [0, 1]`, in the world frame.
///
/// Implementors give [`CartesianPath::pose`]; [`CartesianPath::derivatives`]
/// defaults to finite differences (step `1e-4`, second order, one-sided at
/// the ends; about 1e-8 relative accuracy for smooth paths) and is exact for
/// the built-in paths.
pub trait CartesianPath: Send + Sync {
    /// The pose at path parameter `s in [0, 1]`.
    fn pose(&self, s: f64) -> Pose;

    /// The pose and its first two derivatives with respect to `s`.
    fn derivatives(&self, s: f64) -> PathDerivatives {
        finite_difference_derivatives(|x| self.pose(x), s)
    }
}

/// Finite-difference derivatives of a pose function (see [`CartesianPath::derivatives`]).
fn finite_difference_derivatives(pose: impl Fn(f64) -> Pose, s: f64) -> PathDerivatives {
    const H: f64 = 1e-4;
    let centre = pose(s);
    // Values of [p; rotation vector from R(s)] at s + k h, as 6-vectors.
    let at = |k: f64| -> Vector6<f64> {
        let x = pose(s + k * H);
        let delta = x.translation - centre.translation;
        let r = rotation_log(&(x.rotation * centre.rotation.transpose()));
        Vector6::new(delta.x, delta.y, delta.z, r.x, r.y, r.z)
    };
    let (first, second) = if s - H < 0.0 {
        let (f1, f2, f3) = (at(1.0), at(2.0), at(3.0));
        (
            (4.0 * f1 - f2) / (2.0 * H),
            (-5.0 * f1 + 4.0 * f2 - f3) / (H * H),
        )
    } else if s + H > 1.0 {
        let (f1, f2, f3) = (at(-1.0), at(-2.0), at(-3.0));
        (
            (f2 - 4.0 * f1) / (2.0 * H),
            (-5.0 * f1 + 4.0 * f2 - f3) / (H * H),
        )
    } else {
        let (fp, fm) = (at(1.0), at(-1.0));
        ((fp - fm) / (2.0 * H), (fp + fm) / (H * H))
    };
    PathDerivatives {
        pose: centre,
        first,
        second,
    }
}

fn check_pose(what: &'static str, pose: &Pose) -> Result<()> {
    pose.check_rigid()
        .map_err(|reason| Error::invalid_argument(what, reason))
}

/// A straight line from `start` to `end`, the orientation interpolated by
/// slerp: `p(s) = p0 + s (p1 - p0)`, `R(s) = R0 exp(s log(R0' R1))` (the
/// shortest rotation, constant angular velocity axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinePath {
    start: Pose,
    end: Pose,
    /// `log(R0' R1)` in the start frame, rad.
    rotation: Vector3<f64>,
}

impl LinePath {
    /// The line between two poses (world frame). Errors: non-finite poses or
    /// improper rotation matrices.
    pub fn new(start: Pose, end: Pose) -> Result<Self> {
        check_pose("start", &start)?;
        check_pose("end", &end)?;
        Ok(LinePath {
            start,
            end,
            rotation: rotation_log(&(start.rotation.transpose() * end.rotation)),
        })
    }

    /// Length of the line, m.
    pub fn length(&self) -> f64 {
        (self.end.translation - self.start.translation).norm()
    }
}

impl CartesianPath for LinePath {
    fn pose(&self, s: f64) -> Pose {
        let translation =
            self.start.translation + (self.end.translation - self.start.translation) * s;
        let rotation = self.start.rotation * Rotation3::new(self.rotation * s).into_inner();
        Pose::new(rotation, translation)
    }

    fn derivatives(&self, s: f64) -> PathDerivatives {
        let dp = self.end.translation - self.start.translation;
        let w = self.start.rotation * self.rotation;
        PathDerivatives {
            pose: self.pose(s),
            first: Vector6::new(dp.x, dp.y, dp.z, w.x, w.y, w.z),
            second: Vector6::zeros(),
        }
    }
}

/// How the orientation moves along an [`ArcPath`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArcOrientation {
    /// Keep the start orientation.
    Constant,
    /// Turn with the arc: `R(s) = Rot(axis, s angle) R0` (the tool keeps its
    /// orientation relative to the arc's radius and tangent).
    FollowArc,
}

/// A circular arc: the start position turned about an axis through `centre`.
///
/// `p(s) = c + Rot(n, s angle) (p0 - c)`, `n` the unit axis; positive angles
/// turn counter-clockwise about `n`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPath {
    start: Pose,
    centre: Vector3<f64>,
    axis: Vector3<f64>,
    angle: f64,
    orientation: ArcOrientation,
}

impl ArcPath {
    /// The arc from `start` turning by `angle` (rad, non-zero) about the axis
    /// `axis` (any non-zero vector, normalized here) through `centre` (m).
    /// Errors: non-finite input, zero axis or angle, start on the axis.
    pub fn new(
        start: Pose,
        centre: Vector3<f64>,
        axis: Vector3<f64>,
        angle: f64,
        orientation: ArcOrientation,
    ) -> Result<Self> {
        check_pose("start", &start)?;
        check_finite("centre", centre.as_slice())?;
        check_finite("axis", axis.as_slice())?;
        check_finite("angle", &[angle])?;
        let norm = axis.norm();
        if norm == 0.0 {
            return Err(Error::invalid_argument("axis", "must be non-zero"));
        }
        if angle == 0.0 {
            return Err(Error::invalid_argument("angle", "must be non-zero"));
        }
        let axis = axis / norm;
        let radial = start.translation - centre;
        if (radial - axis * axis.dot(&radial)).norm() <= 1e-12 * radial.norm().max(1.0) {
            return Err(Error::invalid_argument(
                "centre",
                "the start position lies on the arc's axis (zero radius)",
            ));
        }
        Ok(ArcPath {
            start,
            centre,
            axis,
            angle,
            orientation,
        })
    }

    /// The arc from `start`'s position through `via` to `end` (m, world),
    /// the circle through the three points. Errors: (nearly) collinear or
    /// coincident points.
    pub fn through(
        start: Pose,
        via: Vector3<f64>,
        end: Vector3<f64>,
        orientation: ArcOrientation,
    ) -> Result<Self> {
        check_pose("start", &start)?;
        check_finite("via", via.as_slice())?;
        check_finite("end", end.as_slice())?;
        let p0 = start.translation;
        let a = p0 - end;
        let b = via - end;
        let normal = a.cross(&b);
        let scale = a.norm().max(b.norm()).max(f64::MIN_POSITIVE);
        if normal.norm() <= 1e-9 * scale * scale {
            return Err(Error::invalid_argument(
                "via",
                "start, via and end are collinear or coincide: no unique circle",
            ));
        }
        // Circumcentre of the triangle (p0, via, end), relative to `end`.
        let centre = end
            + (b * a.norm_squared() - a * b.norm_squared()).cross(&normal)
                / (2.0 * normal.norm_squared());
        // Travel p0 -> via -> end is counter-clockwise about this axis.
        let axis = (via - p0).cross(&(end - via)).normalize();
        let (u0, u2) = (p0 - centre, end - centre);
        let mut angle = axis.dot(&u0.cross(&u2)).atan2(u0.dot(&u2));
        if angle <= 0.0 {
            angle += std::f64::consts::TAU;
        }
        ArcPath::new(start, centre, axis, angle, orientation)
    }

    /// Radius, m.
    pub fn radius(&self) -> f64 {
        let radial = self.start.translation - self.centre;
        (radial - self.axis * self.axis.dot(&radial)).norm()
    }

    /// Centre (m), unit axis and signed angle (rad).
    pub fn geometry(&self) -> (Vector3<f64>, Vector3<f64>, f64) {
        (self.centre, self.axis, self.angle)
    }
}

impl CartesianPath for ArcPath {
    fn pose(&self, s: f64) -> Pose {
        let turn = Rotation3::new(self.axis * (s * self.angle)).into_inner();
        let translation = self.centre + turn * (self.start.translation - self.centre);
        let rotation = match self.orientation {
            ArcOrientation::Constant => self.start.rotation,
            ArcOrientation::FollowArc => turn * self.start.rotation,
        };
        Pose::new(rotation, translation)
    }

    fn derivatives(&self, s: f64) -> PathDerivatives {
        let pose = self.pose(s);
        let w = self.axis * self.angle;
        let radial = pose.translation - self.centre;
        let dp = w.cross(&radial);
        let ddp = w.cross(&dp);
        let ws = match self.orientation {
            ArcOrientation::Constant => Vector3::zeros(),
            ArcOrientation::FollowArc => w,
        };
        PathDerivatives {
            pose,
            first: Vector6::new(dp.x, dp.y, dp.z, ws.x, ws.y, ws.z),
            second: Vector6::new(ddp.x, ddp.y, ddp.z, 0.0, 0.0, 0.0),
        }
    }
}

/// A user curve `X(s)`, `s in [0, 1]` (seed 002, eq 19: the path as a
/// parametric function given by the user). Derivatives by finite differences.
pub struct FnPath<F>(pub F);

impl<F> fmt::Debug for FnPath<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("FnPath(..)")
    }
}

impl<F: Fn(f64) -> Pose + Send + Sync> CartesianPath for FnPath<F> {
    fn pose(&self, s: f64) -> Pose {
        (self.0)(s)
    }
}

/// A scalar timing law `s(t)`, from `s = 0` at the start to `s = 1` at the end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeLaw {
    /// `s = t / T`: constant speed, from start to end (seed 002's default
    /// when `s` is linear in time; the speed jumps at both ends).
    Linear,
    /// Trapezoidal speed from rest to rest with `acceleration_time` seconds
    /// of constant acceleration and of deceleration (seed 004: 20 s with 4 s).
    Trapezoidal {
        /// Acceleration (and deceleration) time, s, in `(0, T/2]`.
        acceleration_time: f64,
    },
    /// Quintic from rest to rest (zero speed and acceleration at both ends).
    Quintic,
}

impl TimeLaw {
    /// The law as a one-joint [`Trajectory`] `s(t)` from 0 to 1 over
    /// `duration` seconds, starting at time 0.
    pub fn timing(self, duration: f64) -> Result<Trajectory> {
        match self {
            TimeLaw::Linear => profile::cubic(
                &JointState::new(vec![0.0], vec![1.0 / duration], vec![0.0]),
                &JointState::new(vec![1.0], vec![1.0 / duration], vec![0.0]),
                duration,
            ),
            TimeLaw::Trapezoidal { acceleration_time } => {
                profile::trapezoidal(&[0.0], &[1.0], duration, acceleration_time)
            }
            TimeLaw::Quintic => profile::quintic(
                &JointState::at_rest(&[0.0]),
                &JointState::at_rest(&[1.0]),
                duration,
            ),
        }
    }
}

/// How the orientation of a [`CartesianTrajectory`] moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OrientationLaw {
    /// The path's own orientation `R(s(t))` (slerp for a line).
    FollowPath,
    /// Seed 002, eqs 20-22: the three orientation angles of the end poses,
    /// interpolated linearly in time (not in `s`). The angles are our
    /// roll-pitch-yaw (`R = Rz(yaw) Ry(pitch) Rx(roll)`; the seed's are
    /// "angles with the X, Y and Z axes"); each difference is wrapped to
    /// `(-pi, pi]`, and a pitch near +-pi/2 makes the angles singular.
    RpyLinearInTime,
}

/// Pose, twist and its derivative at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CartesianState {
    /// End-effector pose, world frame.
    pub pose: Pose,
    /// `[v; w]`: m/s and rad/s, world axes.
    pub twist: Vector6<f64>,
    /// `[dv/dt; dw/dt]`: m/s^2 and rad/s^2, world axes.
    pub acceleration: Vector6<f64>,
}

/// A Cartesian path timed by a scalar law: `X(t) = X(s(t))`.
pub struct CartesianTrajectory {
    path: Box<dyn CartesianPath>,
    timing: Trajectory,
    orientation: OrientationLaw,
    rpy_start: Vector3<f64>,
    rpy_change: Vector3<f64>,
}

impl fmt::Debug for CartesianTrajectory {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CartesianTrajectory")
            .field("start_time", &self.start_time())
            .field("duration", &self.duration())
            .field("orientation", &self.orientation)
            .finish_non_exhaustive()
    }
}

impl CartesianTrajectory {
    /// `path` timed by `timing`: a one-joint trajectory with `s = 0` at its
    /// start, `s = 1` at its end and `s in [0, 1]` throughout (e.g. from
    /// [`TimeLaw::timing`]). Times are the timing's (s).
    ///
    /// Errors: a timing with more than one joint, not from 0 to 1 (to 1e-12),
    /// or leaving `[0, 1]`; a zero duration.
    pub fn new(path: impl CartesianPath + 'static, timing: Trajectory) -> Result<Self> {
        if timing.dof() != 1 {
            return Err(Error::invalid_argument(
                "timing",
                format!(
                    "must have one joint (the path parameter s), got {}",
                    timing.dof()
                ),
            ));
        }
        if timing.duration() <= 0.0 {
            return Err(Error::invalid_argument(
                "timing",
                "must have a duration > 0",
            ));
        }
        let (s0, s1) = (
            timing.start_state().position[0],
            timing.end_state().position[0],
        );
        if s0.abs() > 1e-12 || (s1 - 1.0).abs() > 1e-12 {
            return Err(Error::invalid_argument(
                "timing",
                format!("must run from s = 0 to s = 1, got {s0} to {s1}"),
            ));
        }
        let unit = TrajectoryLimits {
            lower: vec![0.0],
            upper: vec![1.0],
            velocity: vec![f64::INFINITY],
            acceleration: vec![f64::INFINITY],
        };
        if let Some(v) = check_limits(&timing, &unit)?.first() {
            return Err(Error::invalid_argument(
                "timing",
                format!(
                    "s leaves [0, 1]: s = {} at t = {} s",
                    v.peak_value, v.peak_time
                ),
            ));
        }
        let (r0, p0, y0) = path.pose(0.0).rpy();
        let (r1, p1, y1) = path.pose(1.0).rpy();
        let wrap = crate::math::wrap_angle;
        Ok(CartesianTrajectory {
            path: Box::new(path),
            timing,
            orientation: OrientationLaw::FollowPath,
            rpy_start: Vector3::new(r0, p0, y0),
            rpy_change: Vector3::new(wrap(r1 - r0), wrap(p1 - p0), wrap(y1 - y0)),
        })
    }

    /// The same trajectory with another orientation law.
    pub fn with_orientation_law(mut self, law: OrientationLaw) -> Self {
        self.orientation = law;
        self
    }

    /// The orientation law.
    pub fn orientation_law(&self) -> OrientationLaw {
        self.orientation
    }

    /// The path.
    pub fn path(&self) -> &dyn CartesianPath {
        self.path.as_ref()
    }

    /// The timing law `s(t)`.
    pub fn timing(&self) -> &Trajectory {
        &self.timing
    }

    /// Start time, s.
    pub fn start_time(&self) -> f64 {
        self.timing.start_time()
    }

    /// End time, s.
    pub fn end_time(&self) -> f64 {
        self.timing.end_time()
    }

    /// Duration, s.
    pub fn duration(&self) -> f64 {
        self.timing.duration()
    }

    /// The pose at time `t` (s, clamped into the trajectory), world frame.
    pub fn pose_at(&self, t: f64) -> Pose {
        let (s, _, _) = self.timing.sample_scalar(t);
        let mut pose = self.path.pose(s);
        if self.orientation == OrientationLaw::RpyLinearInTime {
            let (rpy, _) = self.rpy_at(t);
            pose.rotation = Pose::from_xyz_rpy([0.0; 3], [rpy.x, rpy.y, rpy.z]).rotation;
        }
        pose
    }

    /// Roll-pitch-yaw and their (constant) rates at `t` (seed 002, eqs 20-22).
    fn rpy_at(&self, t: f64) -> (Vector3<f64>, Vector3<f64>) {
        let duration = self.duration();
        let elapsed = (t - self.start_time()).clamp(0.0, duration);
        let rate = self.rpy_change / duration;
        (self.rpy_start + rate * elapsed, rate)
    }

    /// Pose, twist and twist derivative at time `t` (s, clamped). Errors:
    /// non-finite `t`.
    pub fn sample(&self, t: f64) -> Result<CartesianState> {
        check_finite("t", &[t])?;
        let (s, sd, sdd) = self.timing.sample_scalar(t);
        let d = self.path.derivatives(s);
        // Chain rule: dX/dt = X' sd, d2X/dt2 = X'' sd^2 + X' sdd.
        let mut twist = d.first * sd;
        let mut acceleration = d.second * (sd * sd) + d.first * sdd;
        let mut pose = d.pose;
        if self.orientation == OrientationLaw::RpyLinearInTime {
            let (rpy, rate) = self.rpy_at(t);
            let (w, dw) = rpy_angular_velocity(&rpy, &rate);
            pose.rotation = Pose::from_xyz_rpy([0.0; 3], [rpy.x, rpy.y, rpy.z]).rotation;
            twist.fixed_rows_mut::<3>(3).copy_from(&w);
            acceleration.fixed_rows_mut::<3>(3).copy_from(&dw);
        }
        Ok(CartesianState {
            pose,
            twist,
            acceleration,
        })
    }
}

/// Angular velocity and acceleration (world axes) of `R = Rz(y) Ry(p) Rx(r)`
/// for roll-pitch-yaw `rpy` changing at constant rates `rate`:
/// `w = y' e_z + p' Rz(y) e_y + r' Rz(y) Ry(p) e_x`, differentiated once.
fn rpy_angular_velocity(rpy: &Vector3<f64>, rate: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let (sp, cp) = rpy.y.sin_cos();
    let (sy, cy) = rpy.z.sin_cos();
    let (dr, dp, dy) = (rate.x, rate.y, rate.z);
    let pitch_axis = Vector3::new(-sy, cy, 0.0);
    let roll_axis = Vector3::new(cy * cp, sy * cp, -sp);
    let w = Vector3::z() * dy + pitch_axis * dp + roll_axis * dr;
    let d_pitch_axis = Vector3::new(-cy, -sy, 0.0) * dy;
    let d_roll_axis = Vector3::new(
        -sy * cp * dy - cy * sp * dp,
        cy * cp * dy - sy * sp * dp,
        -cp * dp,
    );
    (w, d_pitch_axis * dp + d_roll_axis * dr)
}
