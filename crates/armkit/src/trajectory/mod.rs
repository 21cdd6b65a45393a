//! Trajectory generation: joint-space profiles and splines, Cartesian paths,
//! seed 002's continuous-path method with adaptive segmentation, and limits.
//!
//! Every joint-space result is one type, [`Trajectory`]: a piecewise
//! polynomial (degree up to 5 per segment, in normalized time, seed 002
//! eq 25) over all joints, whose [`Trajectory::sample`] always fills
//! position, velocity and acceleration.
//!
//! * Profiles ([`cubic`], [`quintic`], [`trapezoidal`], [`rest_to_rest`],
//!   [`minimum_time`]): point-to-point cubic, quintic and trapezoidal profiles,
//!   synchronized over all joints, for a given duration or in minimum time
//!   under velocity and acceleration limits.
//! * [`clamped_cubic_spline`]: the clamped C2 cubic spline through via points at given times.
//! * Cartesian paths ([`CartesianPath`], [`LinePath`], [`ArcPath`], [`FnPath`],
//!   [`CartesianTrajectory`]): straight lines (slerp, or seed 002's angles linear in
//!   time), circular arcs and user curves, timed by a trapezoidal or quintic law.
//! * [`plan_continuous_path`]: seed 002's continuous-path method (IK at n + 1 path
//!   points, one polynomial per segment) and its adaptive segmentation (Fig 6).
//! * [`path_ik_for`]: the IK the continuous path uses: closed form (arm4,
//!   PUMA-type arms) or numeric (any robot), nearest the previous knot.
//! * [`check_limits`], [`scale_to_limits`]: where a trajectory exceeds position, velocity or acceleration
//!   limits, and uniform time scaling to meet them.
//! * [`torque_profile`], [`scale_to_torque_limits`]: the joint torques along
//!   a trajectory (inverse dynamics, [`crate::dynamics::rnea`]) against the
//!   motors' limits, and the uniform time scaling that meets them.
//!
//! Units: seconds; rad, rad/s, rad/s^2 for revolute joints; m, m/s, m/s^2 for
//! prismatic ones.
//!
//! ```
//! use armkit::trajectory::{trapezoidal, JointState};
//! // Seed 004's trapezoid: 20 s with 4 s of acceleration, two joints.
//! let traj = trapezoidal(&[0.0, 1.0], &[1.6, -0.6], 20.0, 4.0).unwrap();
//! assert_eq!(traj.duration(), 20.0);
//! let mut state = JointState::zeros(2);
//! traj.sample_into(10.0, &mut state).unwrap(); // no allocation
//! assert!((state.position[0] - 0.8).abs() < 1e-12);
//! assert!((state.velocity[0] - 1.6 / 16.0).abs() < 1e-12); // cruise: d / (T - ta)
//! assert_eq!(state.acceleration[0], 0.0);
//! ```

mod cartesian;
mod continuous_path;
mod limits;
mod path_ik;
mod poly;
mod profile;
mod spline;
mod timed;
mod torque_limits;

pub use cartesian::{
    ArcOrientation, ArcPath, CartesianPath, CartesianState, CartesianTrajectory, FnPath, LinePath,
    OrientationLaw, PathDerivatives, TimeLaw,
};
pub use continuous_path::{
    interpolate_via_points, measure_path_error, plan_continuous_path, rate_amplification,
    BoundaryRates, ContinuousPathOptions, ContinuousPathReport, PathError, PathIk, PathStatus,
    PathTolerance, SegmentScheme, Segmentation, ViaVelocity,
};
pub use limits::{
    check_limits, peak_rates, scale_to_limits, LimitKind, LimitViolation, PeakRates,
    ScaledTrajectory, TimeScaling, TrajectoryLimits,
};
pub use path_ik::{path_ik_for, ClosedFormPathIk, IkTask, NumericPathIk};
pub use profile::{
    cubic, minimum_time, quintic, rest_to_rest, trapezoidal, ProfileShape, MAX_DURATION,
    MIN_DURATION,
};
pub use spline::clamped_cubic_spline;
pub(crate) use timed::rename_argument;
pub use timed::{TimeFn, TimedPath};
pub use torque_limits::{
    scale_to_torque_limits, torque_profile, JointTorquePeak, TorqueCheckOptions, TorqueReport,
    TorqueScaling, TorqueStatus,
};

use crate::error::{check_finite, check_finite_vector, check_positive, Error, Result};

/// Position, velocity and acceleration of every joint at one instant.
///
/// Units: rad, rad/s, rad/s^2 (revolute) or m, m/s, m/s^2 (prismatic); one
/// entry per joint in each vector.
#[derive(Clone, Debug, PartialEq)]
pub struct JointState {
    /// Joint positions.
    pub position: Vec<f64>,
    /// Joint velocities.
    pub velocity: Vec<f64>,
    /// Joint accelerations.
    pub acceleration: Vec<f64>,
}

impl JointState {
    /// All zeros, for `dof` joints (a buffer for [`Trajectory::sample_into`]).
    pub fn zeros(dof: usize) -> Self {
        JointState {
            position: vec![0.0; dof],
            velocity: vec![0.0; dof],
            acceleration: vec![0.0; dof],
        }
    }

    /// At rest at `position`: zero velocity and acceleration.
    pub fn at_rest(position: &[f64]) -> Self {
        let dof = position.len();
        JointState {
            position: position.to_vec(),
            velocity: vec![0.0; dof],
            acceleration: vec![0.0; dof],
        }
    }

    /// A state from its three vectors (same length).
    pub fn new(position: Vec<f64>, velocity: Vec<f64>, acceleration: Vec<f64>) -> Self {
        JointState {
            position,
            velocity,
            acceleration,
        }
    }

    /// Number of joints (length of `position`).
    pub fn dof(&self) -> usize {
        self.position.len()
    }

    /// Checks that all three vectors have `dof` finite entries.
    pub fn check(&self, dof: usize) -> Result<()> {
        check_finite_vector("state.position", &self.position, dof)?;
        check_finite_vector("state.velocity", &self.velocity, dof)?;
        check_finite_vector("state.acceleration", &self.acceleration, dof)
    }

    fn check_buffer(&self, dof: usize) -> Result<()> {
        for (what, len) in [
            ("out.position", self.position.len()),
            ("out.velocity", self.velocity.len()),
            ("out.acceleration", self.acceleration.len()),
        ] {
            if len != dof {
                return Err(Error::DimensionMismatch {
                    what,
                    expected: dof,
                    got: len,
                });
            }
        }
        Ok(())
    }
}

/// A joint-space trajectory: one polynomial of degree <= 5 per segment and
/// joint, in normalized time (seed 002, eq 25).
///
/// Segment `i` spans `[t_i, t_{i+1}]` (the knots, absolute times in seconds);
/// joint `j` follows `q_j(t) = sum_k c_k phi^k` with
/// `phi = (t - t_i) / (t_{i+1} - t_i)`. Velocity and acceleration are the
/// exact time derivatives. Immutable once built; sampling allocates nothing
/// with [`Trajectory::sample_into`].
///
/// Outside `[start_time, end_time]` the time is clamped: the trajectory
/// reports its first or last state (with that state's velocity and
/// acceleration, which are zero for rest-to-rest motions).
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    dof: usize,
    knots: Vec<f64>,
    inverse_durations: Vec<f64>,
    /// Segment-major: `coefficients[segment * dof + joint]`.
    coefficients: Vec<[f64; 6]>,
}

impl Trajectory {
    /// A trajectory from its knots and per-segment, per-joint coefficients.
    ///
    /// `knots`: `m + 1 >= 2` strictly increasing finite times, s.
    /// `coefficients[i * dof + j]`: the six ascending coefficients of joint
    /// `j` on segment `i` in normalized time `phi in [0, 1]` (rad or m).
    /// Continuity across knots is the caller's business (see
    /// [`Trajectory::knot_discontinuities`]).
    pub fn from_polynomials(
        knots: Vec<f64>,
        dof: usize,
        coefficients: Vec<[f64; 6]>,
    ) -> Result<Self> {
        if dof == 0 {
            return Err(Error::invalid_argument("dof", "must be at least 1"));
        }
        if knots.len() < 2 {
            return Err(Error::invalid_argument(
                "knots",
                format!("need at least 2 knot times, got {}", knots.len()),
            ));
        }
        check_finite("knots", &knots)?;
        if let Some(i) = knots.windows(2).position(|w| w[1] <= w[0]) {
            return Err(Error::invalid_argument(
                "knots",
                format!(
                    "must be strictly increasing: knot {} = {} s is not after knot {} = {} s",
                    i + 1,
                    knots[i + 1],
                    i,
                    knots[i]
                ),
            ));
        }
        let segments = knots.len() - 1;
        if coefficients.len() != segments * dof {
            return Err(Error::DimensionMismatch {
                what: "coefficients (segments x dof)",
                expected: segments * dof,
                got: coefficients.len(),
            });
        }
        if coefficients.iter().flatten().any(|c| !c.is_finite()) {
            return Err(Error::invalid_argument(
                "coefficients",
                "must all be finite",
            ));
        }
        Ok(Self::from_parts(knots, dof, coefficients))
    }

    /// Builds without validation (callers guarantee sizes and increasing knots).
    fn from_parts(knots: Vec<f64>, dof: usize, coefficients: Vec<[f64; 6]>) -> Self {
        let inverse_durations = knots
            .windows(2)
            .map(|w| {
                let h = w[1] - w[0];
                if h > 0.0 {
                    1.0 / h
                } else {
                    0.0
                }
            })
            .collect();
        Trajectory {
            dof,
            knots,
            inverse_durations,
            coefficients,
        }
    }

    /// Holding `position` from `start_time` for `duration >= 0` seconds
    /// (zero velocity and acceleration). A zero duration is allowed: it is
    /// the minimum-time answer to a move of zero length.
    pub fn stationary(position: &[f64], start_time: f64, duration: f64) -> Result<Self> {
        if position.is_empty() {
            return Err(Error::invalid_argument(
                "position",
                "must have at least one joint",
            ));
        }
        check_finite("position", position)?;
        check_finite("start_time", &[start_time])?;
        if !(duration >= 0.0 && duration.is_finite()) {
            return Err(Error::invalid_argument(
                "duration",
                format!("must be finite and >= 0 s, got {duration}"),
            ));
        }
        let coefficients = position
            .iter()
            .map(|&q| [q, 0.0, 0.0, 0.0, 0.0, 0.0])
            .collect();
        Ok(Self::from_parts(
            vec![start_time, start_time + duration],
            position.len(),
            coefficients,
        ))
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Number of polynomial segments.
    pub fn segment_count(&self) -> usize {
        self.knots.len() - 1
    }

    /// Knot times (segment boundaries), s, increasing.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Start time, s.
    pub fn start_time(&self) -> f64 {
        self.knots[0]
    }

    /// End time, s.
    pub fn end_time(&self) -> f64 {
        self.knots[self.knots.len() - 1]
    }

    /// Duration, s (`end_time - start_time`, >= 0).
    pub fn duration(&self) -> f64 {
        self.end_time() - self.start_time()
    }

    /// The six ascending coefficients of `joint` on `segment`, in normalized
    /// time `phi in [0, 1]` (rad or m).
    pub fn polynomial(&self, segment: usize, joint: usize) -> Result<[f64; 6]> {
        self.check_segment(segment)?;
        if joint >= self.dof {
            return Err(Error::invalid_argument(
                "joint",
                format!("must be < {} (the number of joints), got {joint}", self.dof),
            ));
        }
        Ok(self.coefficients[segment * self.dof + joint])
    }

    fn check_segment(&self, segment: usize) -> Result<()> {
        if segment >= self.segment_count() {
            return Err(Error::invalid_argument(
                "segment",
                format!(
                    "must be < {} (the number of segments), got {segment}",
                    self.segment_count()
                ),
            ));
        }
        Ok(())
    }

    /// The segment containing time `t` (clamped into the trajectory), and `phi`.
    #[inline]
    fn locate(&self, t: f64) -> (usize, f64) {
        let last = self.knots.len() - 1;
        if t >= self.knots[last] {
            // Exactly the end state (t / h may round below 1).
            return (last - 1, 1.0);
        }
        let t = t.max(self.knots[0]);
        // Number of interior knots <= t: the segment index, in 0..segments.
        let segment = self.knots[1..last].partition_point(|&k| k <= t);
        let phi = (t - self.knots[segment]) * self.inverse_durations[segment];
        (segment, phi.clamp(0.0, 1.0))
    }

    /// Samples at time `t` (s) into `out` (sized for [`Trajectory::dof`]
    /// joints): position, velocity and acceleration of every joint.
    /// Allocates nothing. `t` is clamped into `[start_time, end_time]`.
    pub fn sample_into(&self, t: f64, out: &mut JointState) -> Result<()> {
        if !t.is_finite() {
            return Err(Error::NonFinite {
                what: "t",
                index: 0,
                value: t,
            });
        }
        out.check_buffer(self.dof)?;
        let (segment, phi) = self.locate(t);
        self.fill(segment, phi, out);
        Ok(())
    }

    /// Samples at time `t` (s): position, velocity and acceleration of every
    /// joint. Allocates the result; see [`Trajectory::sample_into`].
    pub fn sample(&self, t: f64) -> Result<JointState> {
        let mut out = JointState::zeros(self.dof);
        self.sample_into(t, &mut out)?;
        Ok(out)
    }

    /// Samples segment `segment` at normalized time `phi in [0, 1]` into
    /// `out`: at `phi = 0` and `phi = 1` this is the segment's own boundary
    /// state (used to check boundary conditions and continuity at knots).
    pub fn sample_segment_into(
        &self,
        segment: usize,
        phi: f64,
        out: &mut JointState,
    ) -> Result<()> {
        self.check_segment(segment)?;
        if !(0.0..=1.0).contains(&phi) {
            return Err(Error::invalid_argument(
                "phi",
                format!("must be in [0, 1], got {phi}"),
            ));
        }
        out.check_buffer(self.dof)?;
        self.fill(segment, phi, out);
        Ok(())
    }

    #[inline(always)]
    fn fill(&self, segment: usize, phi: f64, out: &mut JointState) {
        let rate = self.inverse_durations[segment];
        let rate2 = rate * rate;
        let coefficients = &self.coefficients[segment * self.dof..(segment + 1) * self.dof];
        for (j, c) in coefficients.iter().enumerate() {
            let (p, d, dd) = poly::evaluate(c, phi);
            out.position[j] = p;
            out.velocity[j] = d * rate;
            out.acceleration[j] = dd * rate2;
        }
    }

    /// Position, velocity and acceleration of joint 0 at `t` (clamped),
    /// without allocation: for scalar timing laws.
    #[inline]
    pub(crate) fn sample_scalar(&self, t: f64) -> (f64, f64, f64) {
        let (segment, phi) = self.locate(t);
        let rate = self.inverse_durations[segment];
        let (p, d, dd) = poly::evaluate(&self.coefficients[segment * self.dof], phi);
        (p, d * rate, dd * rate * rate)
    }

    /// The state at the start time.
    pub fn start_state(&self) -> JointState {
        let mut out = JointState::zeros(self.dof);
        self.fill(0, 0.0, &mut out);
        out
    }

    /// The state at the end time.
    pub fn end_state(&self) -> JointState {
        let mut out = JointState::zeros(self.dof);
        self.fill(self.segment_count() - 1, 1.0, &mut out);
        out
    }

    /// The largest jumps of position, velocity and acceleration across the
    /// interior knots, over all joints: `[position, velocity, acceleration]`
    /// (rad, rad/s, rad/s^2 or m, m/s, m/s^2). Zero (to rounding) for a C2
    /// trajectory.
    pub fn knot_discontinuities(&self) -> [f64; 3] {
        let mut worst = [0.0f64; 3];
        let mut left = JointState::zeros(self.dof);
        let mut right = JointState::zeros(self.dof);
        for segment in 1..self.segment_count() {
            self.fill(segment - 1, 1.0, &mut left);
            self.fill(segment, 0.0, &mut right);
            let pairs = [
                (&left.position, &right.position),
                (&left.velocity, &right.velocity),
                (&left.acceleration, &right.acceleration),
            ];
            for (w, (a, b)) in worst.iter_mut().zip(pairs) {
                for (x, y) in a.iter().zip(b.iter()) {
                    *w = w.max((x - y).abs());
                }
            }
        }
        worst
    }

    /// The same motion played `factor` times slower (`factor > 1`) or faster
    /// (`factor < 1`), starting at the same time: duration times `factor`,
    /// velocities divided by `factor`, accelerations by `factor^2`. The path
    /// in joint space is unchanged (the polynomials are in normalized time,
    /// only the knots move).
    pub fn time_scaled(&self, factor: f64) -> Result<Trajectory> {
        check_positive("factor", factor)?;
        let t0 = self.start_time();
        let knots = self.knots.iter().map(|&t| t0 + (t - t0) * factor).collect();
        Ok(Self::from_parts(knots, self.dof, self.coefficients.clone()))
    }

    /// The same motion starting at `start_time` (s) instead.
    pub fn shifted_to(&self, start_time: f64) -> Result<Trajectory> {
        check_finite("start_time", &[start_time])?;
        let shift = start_time - self.start_time();
        let knots = self.knots.iter().map(|&t| t + shift).collect();
        Ok(Self::from_parts(knots, self.dof, self.coefficients.clone()))
    }
}
