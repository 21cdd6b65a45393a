//! Seed 002's continuous-path method (sec 3): inverse kinematics at `n + 1`
//! points of a Cartesian path, one polynomial per segment in normalized time,
//! and the adaptive choice of `n` (Fig 6).
//!
//! 1. Split the path's time span into `n` segments and solve IK at the
//!    `n + 1` knots, each time for the solution nearest the previous one
//!    (through a [`PathIk`], e.g. closed-form IK for the 4-DOF arm or numeric
//!    IK for any robot).
//! 2. Fit one polynomial per segment and joint (eq 25, normalized time
//!    `phi in [0, 1]`), in one of the seed's two schemes ([`SegmentScheme`]):
//!    * quartic first and last segments with cubic middles, the via-point
//!      velocities by finite differences (eq 23): position and velocity
//!      continuous (C1);
//!    * cubic segments with a quintic last one, position, velocity and
//!      acceleration continuous (C2).
//! 3. Adaptive segmentation (Fig 6): evaluate forward kinematics at every
//!    segment's midpoint, compare with the path's pose at that time, insert
//!    the midpoint as a new knot wherever the error exceeds the tolerance,
//!    re-plan and re-check until every midpoint meets the tolerance. The
//!    midpoint alone can miss the largest error of a segment (see
//!    [`ContinuousPathOptions::checks_per_segment`]); [`measure_path_error`]
//!    checks a planned trajectory at as many points as wanted.
//!
//! The path error is time-synchronized: the pose reached at time `t` against
//! the path's pose at the same `t` (an upper bound on the distance to the
//! path). [`PathTolerance::Position`] checks the position only: use it for
//! arms that cannot reach every orientation along the path (the 4-DOF `arm4`
//! reaches a 4-D subset of SE(3)); [`PathTolerance::Pose`] also bounds the
//! orientation error angle.
//!
//! ```
//! use armkit::math::{Pose, Vector3};
//! use armkit::trajectory::{CartesianTrajectory, LinePath, TimeLaw};
//! use armkit::trajectory::{plan_continuous_path, ContinuousPathOptions, PathStatus, PathTolerance};
//! use armkit::{forward_kinematics, Data, Error, Model};
//! use armkit::model::{DhConvention, DhLink};
//! // A planar 2R arm (0.5 m, 0.4 m) and a 0.3 m line; its IK in closed form,
//! // elbow on the side of the previous solution.
//! let model = Model::from_dh("2r", DhConvention::Standard, &[DhLink::revolute(0.0, 0.5, 0.0), DhLink::revolute(0.0, 0.4, 0.0)]).unwrap();
//! let mut ik = |target: &Pose, previous: &[f64]| -> Result<Vec<f64>, Error> {
//!     let (x, y) = (target.translation.x, target.translation.y);
//!     let c2 = (x * x + y * y - 0.41) / 0.4;
//!     if c2.abs() > 1.0 { return Err(Error::invalid_argument("target", "out of reach")); }
//!     let q2 = c2.acos().copysign(previous[1]);
//!     let q1 = y.atan2(x) - (0.4 * q2.sin()).atan2(0.5 + 0.4 * q2.cos());
//!     Ok(vec![q1, q2])
//! };
//! let start = Pose::from_translation(Vector3::new(0.6, -0.15, 0.0));
//! let end = Pose::from_translation(Vector3::new(0.6, 0.15, 0.0));
//! let path = CartesianTrajectory::new(LinePath::new(start, end).unwrap(), TimeLaw::Quintic.timing(1.0).unwrap()).unwrap();
//! let options = ContinuousPathOptions { tolerance: PathTolerance::Position(1e-4), ..Default::default() };
//! let report = plan_continuous_path(&model, &path, &mut ik, &[0.0, 1.0], &options).unwrap();
//! assert_eq!(report.status, PathStatus::ToleranceMet);
//! assert!(report.checked_error.position <= 1e-4);
//! ```

use super::cartesian::CartesianTrajectory;
use super::path_ik::{solve_path_point, PathPoint};
use super::poly;
use super::spline::check_via_points;
use super::{JointState, Trajectory};
use crate::error::{check_finite_vector, check_positive, Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::math::rotation_angle;
use crate::math::Pose;
use crate::model::Model;

/// Inverse kinematics along a path: the configuration reaching `target`
/// nearest `previous` (seed 002: "the solution closest to the current
/// configuration").
///
/// Implemented for closures `FnMut(&Pose, &[f64]) -> Result<Vec<f64>>`.
/// Return an error when the target is out of reach (the planner adds which
/// path point it was).
pub trait PathIk {
    /// Joint positions (rad or m, one per joint, within the joint limits)
    /// reaching `target` (world frame), nearest `previous`.
    fn solve_near(&mut self, target: &Pose, previous: &[f64]) -> Result<Vec<f64>>;
}

impl<F: FnMut(&Pose, &[f64]) -> Result<Vec<f64>>> PathIk for F {
    fn solve_near(&mut self, target: &Pose, previous: &[f64]) -> Result<Vec<f64>> {
        self(target, previous)
    }
}

/// How the via-point velocities of [`SegmentScheme::QuarticCubicQuartic`]
/// are estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ViaVelocity {
    /// Seed 002, eq 23: `v_i = (q_i - q_{i-1}) / (t_i - t_{i-1})`, the slope
    /// of the segment before (first order).
    BackwardDifference,
    /// The three-point derivative on the (possibly uneven) knots,
    /// `v_i = (h+ d- + h- d+) / (h- + h+)` with the slopes `d-`, `d+` and
    /// lengths `h-`, `h+` of the segments before and after (second order,
    /// exact for quadratics). Not in the seed.
    CentralDifference,
}

/// Seed 002's two ways of fitting polynomials to the knots (eqs 26-28).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SegmentScheme {
    /// "Via-point velocity constraints": a quartic first segment (start
    /// position, velocity, acceleration; end position and via velocity),
    /// cubic middle segments (positions and via velocities at both ends), a
    /// quartic last segment (start position and via velocity; end position,
    /// velocity, acceleration). C1: the acceleration jumps at via points.
    QuarticCubicQuartic(ViaVelocity),
    /// "No velocity constraints at via points": cubic segments (each starts
    /// with the previous one's end position, velocity and acceleration and
    /// ends at its knot) and a quintic last segment meeting the end
    /// position, velocity and acceleration. C2. The scheme has no free
    /// parameter, so it is a forward recursion, and that recursion is
    /// unstable: an error in the velocity and acceleration carried into a
    /// segment is multiplied by up to `2 + sqrt(3) = 3.73` per segment (the
    /// eigenvalues of the cubic's end-state map on even knots are
    /// `-2 +- sqrt(3)`). Fine for a few segments; with many, the joints
    /// oscillate between knots and the adaptive segmentation may not
    /// converge. Use it knowingly.
    CubicQuinticLast,
}

/// Joint velocities and accelerations at the start and the end of a
/// via-point trajectory.
#[derive(Clone, Debug, PartialEq)]
pub enum BoundaryRates {
    /// At rest at both ends (zero velocity and acceleration): right for a
    /// path timed by a rest-to-rest law.
    Rest,
    /// From the knots by finite differences (seed 002, eqs 23-24): at the
    /// end `v_n = (q_n - q_{n-1}) / h_n`, `a_n = (v_n - v_{n-1}) / h_n`; at
    /// the start the same with forward differences.
    FiniteDifference,
    /// Given (rad/s and rad/s^2 or m/s and m/s^2, one per joint each).
    Given {
        /// Velocities at the start.
        start: JointState,
        /// Velocities and accelerations at the end (positions ignored).
        end: JointState,
    },
}

/// The joint trajectory through `positions[i]` at `times[i]` (s, strictly
/// increasing, at least 2 points) by one of seed 002's segment schemes.
///
/// For [`BoundaryRates::Given`] only the velocities and accelerations of the
/// two states are used. With two points both schemes are one quintic.
pub fn interpolate_via_points<P: AsRef<[f64]>>(
    scheme: SegmentScheme,
    times: &[f64],
    positions: &[P],
    boundary: &BoundaryRates,
) -> Result<Trajectory> {
    let (dof, coefficients) = via_point_coefficients(scheme, times, positions, boundary)?;
    Trajectory::from_polynomials(times.to_vec(), dof, coefficients)
}

/// The number of joints and the per-segment, per-joint coefficients of
/// [`interpolate_via_points`], not yet checked for finiteness (the
/// cubic-quintic recursion can overflow: the planner reports that as
/// [`PathStatus::SchemeDiverged`]).
fn via_point_coefficients<P: AsRef<[f64]>>(
    scheme: SegmentScheme,
    times: &[f64],
    positions: &[P],
    boundary: &BoundaryRates,
) -> Result<(usize, Vec<[f64; 6]>)> {
    let dof = check_via_points(times, positions)?;
    let n = times.len() - 1;
    let q = |i: usize| positions[i].as_ref();
    let h = |i: usize| times[i] - times[i - 1]; // duration of segment i (1-based)
    let slope = |i: usize, j: usize| (q(i)[j] - q(i - 1)[j]) / h(i);
    // Boundary rates: (v0, a0, vn, an) per joint.
    let mut ends = vec![[0.0; 4]; dof];
    match boundary {
        BoundaryRates::Rest => {}
        BoundaryRates::FiniteDifference => {
            for (j, e) in ends.iter_mut().enumerate() {
                e[0] = slope(1, j);
                e[2] = slope(n, j);
                if n >= 2 {
                    e[1] = (slope(2, j) - slope(1, j)) / h(1);
                    e[3] = (slope(n, j) - slope(n - 1, j)) / h(n);
                }
            }
        }
        BoundaryRates::Given { start, end } => {
            check_finite_vector("boundary.start.velocity", &start.velocity, dof)?;
            check_finite_vector("boundary.start.acceleration", &start.acceleration, dof)?;
            check_finite_vector("boundary.end.velocity", &end.velocity, dof)?;
            check_finite_vector("boundary.end.acceleration", &end.acceleration, dof)?;
            for (j, e) in ends.iter_mut().enumerate() {
                *e = [
                    start.velocity[j],
                    start.acceleration[j],
                    end.velocity[j],
                    end.acceleration[j],
                ];
            }
        }
    }
    let mut coefficients = vec![[0.0; 6]; n * dof];
    for (j, &[v0, a0, vn, an]) in ends.iter().enumerate() {
        let at = |segment: usize| segment * dof + j; // 0-based segment
        if n == 1 {
            let hn = h(1);
            coefficients[at(0)] = poly::quintic_hermite(
                q(0)[j],
                v0 * hn,
                a0 * hn * hn,
                q(1)[j],
                vn * hn,
                an * hn * hn,
            );
            continue;
        }
        match scheme {
            SegmentScheme::QuarticCubicQuartic(estimate) => {
                // Via velocities at knots 1..n-1 (eq 23 or central).
                let via = |i: usize| match estimate {
                    ViaVelocity::BackwardDifference => slope(i, j),
                    ViaVelocity::CentralDifference => {
                        (h(i + 1) * slope(i, j) + h(i) * slope(i + 1, j)) / (h(i) + h(i + 1))
                    }
                };
                let h1 = h(1);
                coefficients[at(0)] =
                    poly::quartic_first(q(0)[j], v0 * h1, a0 * h1 * h1, q(1)[j], via(1) * h1);
                for i in 2..n {
                    let hi = h(i);
                    coefficients[at(i - 1)] =
                        poly::cubic_hermite(q(i - 1)[j], via(i - 1) * hi, q(i)[j], via(i) * hi);
                }
                let hn = h(n);
                coefficients[at(n - 1)] = poly::quartic_last(
                    q(n - 1)[j],
                    via(n - 1) * hn,
                    q(n)[j],
                    vn * hn,
                    an * hn * hn,
                );
            }
            SegmentScheme::CubicQuinticLast => {
                // Carry (velocity, acceleration) forward in physical units.
                let (mut v, mut a) = (v0, a0);
                for i in 1..n {
                    let hi = h(i);
                    let c = poly::cubic_forward(q(i - 1)[j], v * hi, a * hi * hi, q(i)[j]);
                    let (_, d, dd) = poly::evaluate(&c, 1.0);
                    v = d / hi;
                    a = dd / (hi * hi);
                    coefficients[at(i - 1)] = c;
                }
                let hn = h(n);
                coefficients[at(n - 1)] = poly::quintic_hermite(
                    q(n - 1)[j],
                    v * hn,
                    a * hn * hn,
                    q(n)[j],
                    vn * hn,
                    an * hn * hn,
                );
            }
        }
    }
    Ok((dof, coefficients))
}

/// The Cartesian tolerance of the adaptive segmentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathTolerance {
    /// Position error of the end-effector origin only, m: for arms whose
    /// reachable set does not contain the path's orientations (arm4).
    Position(f64),
    /// Position error (m) and orientation error angle (rad), both bounded.
    Pose {
        /// Position tolerance, m.
        position: f64,
        /// Orientation tolerance, rad (angle of `R_reached R_path'`).
        orientation: f64,
    },
}

impl PathTolerance {
    fn validate(&self) -> Result<()> {
        let (position, orientation) = match *self {
            PathTolerance::Position(p) => (p, 1.0),
            PathTolerance::Pose {
                position,
                orientation,
            } => (position, orientation),
        };
        for (what, v) in [
            ("tolerance.position", position),
            ("tolerance.orientation", orientation),
        ] {
            check_positive(what, v)?;
        }
        Ok(())
    }

    fn is_met(&self, error: &PathError) -> bool {
        match *self {
            PathTolerance::Position(p) => error.position <= p,
            PathTolerance::Pose {
                position,
                orientation,
            } => error.position <= position && error.orientation <= orientation,
        }
    }
}

/// How many segments the continuous path has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Segmentation {
    /// Exactly this many equal segments (>= 1).
    Fixed(usize),
    /// Seed 002's Fig 6: start from `initial` equal segments, halve those
    /// whose midpoint misses the tolerance until all meet it or the count
    /// would exceed `max`.
    Adaptive {
        /// Initial number of segments (>= 1).
        initial: usize,
        /// Largest number of segments (>= `initial`).
        max: usize,
    },
}

/// Options of [`plan_continuous_path`].
#[derive(Clone, Debug, PartialEq)]
pub struct ContinuousPathOptions {
    /// Polynomial scheme. Default: the seed's quartic-cubic-quartic with
    /// eq 23's backward-difference via velocities.
    pub scheme: SegmentScheme,
    /// Joint rates at both ends. Default: [`BoundaryRates::Rest`].
    pub boundary: BoundaryRates,
    /// Segment count. Default: adaptive (Fig 6) from 4 up to 4096 segments.
    pub segmentation: Segmentation,
    /// Cartesian tolerance checked at each segment's check points. Default:
    /// 0.1 mm and 1 mrad.
    pub tolerance: PathTolerance,
    /// Points per segment at which the tolerance is checked, evenly spaced
    /// strictly inside (`phi = k / (m + 1)`); a segment failing at any of
    /// them is halved at its midpoint. 1 is exactly the seed's Fig 6 (the
    /// midpoint). Default 3 (the quarter points and the midpoint), because
    /// the midpoint is blind to an error that is odd about it: with eq 23's
    /// lagging via velocities both ends of a cubic carry about the same
    /// velocity error `e`, whose effect `e phi (1 - phi) (1 - 2 phi)`
    /// vanishes at the midpoint and peaks near the quarter points (on a
    /// 0.3 m line of arm4 with a 0.1 mm tolerance, midpoint checks alone
    /// leave 0.98 mm between them).
    pub checks_per_segment: usize,
}

impl Default for ContinuousPathOptions {
    fn default() -> Self {
        ContinuousPathOptions {
            scheme: SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference),
            boundary: BoundaryRates::Rest,
            segmentation: Segmentation::Adaptive {
                initial: 4,
                max: 4096,
            },
            tolerance: PathTolerance::Pose {
                position: 1e-4,
                orientation: 1e-3,
            },
            checks_per_segment: 3,
        }
    }
}

impl ContinuousPathOptions {
    /// Checks the segment counts, the tolerance and the number of checks.
    pub fn validate(&self) -> Result<()> {
        self.tolerance.validate()?;
        if self.checks_per_segment == 0 {
            return Err(Error::invalid_argument(
                "checks_per_segment",
                "must be at least 1",
            ));
        }
        match self.segmentation {
            Segmentation::Fixed(0) => Err(Error::invalid_argument(
                "segmentation",
                "needs at least 1 segment",
            )),
            Segmentation::Adaptive { initial, max } if initial == 0 || max < initial => {
                Err(Error::invalid_argument(
                    "segmentation",
                    format!("need 1 <= initial <= max, got initial {initial}, max {max}"),
                ))
            }
            _ => Ok(()),
        }
    }
}

/// Largest time-synchronized path errors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathError {
    /// Largest position error, m.
    pub position: f64,
    /// Largest orientation error angle, rad.
    pub orientation: f64,
}

impl PathError {
    fn include(&mut self, other: PathError) {
        self.position = self.position.max(other.position);
        self.orientation = self.orientation.max(other.orientation);
    }
}

/// Whether the planned trajectory meets the tolerance at every check point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PathStatus {
    /// Every segment's check points (midpoints by default) are within the tolerance.
    ToleranceMet,
    /// Some check point is not: with fixed segmentation, or when the adaptive
    /// segmentation reached its maximum count (or a segment 1e-9 of the
    /// duration long). The trajectory is still valid, just coarser.
    ToleranceNotMet,
    /// The segment scheme blew up: refining made the cubic-quintic
    /// recursion's coefficients overflow (its errors grow up to 3.73x per
    /// segment). The report holds the last finite pass, which does not meet
    /// the tolerance either.
    SchemeDiverged,
}

impl PathStatus {
    /// `tolerance_met`, `tolerance_not_met` or `scheme_diverged`.
    pub fn as_str(&self) -> &'static str {
        match self {
            PathStatus::ToleranceMet => "tolerance_met",
            PathStatus::ToleranceNotMet => "tolerance_not_met",
            PathStatus::SchemeDiverged => "scheme_diverged",
        }
    }
}

impl std::fmt::Display for PathStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// How much a trajectory amplifies the joint rates: the largest joint
/// velocity at a knot over the largest mean velocity of a segment
/// (`|q_i - q_{i-1}| / h_i`), over all joints (1 for a motion that does not
/// move). About 1 for the quartic-cubic scheme, whose via velocities are
/// segment slopes (eq 23); for the cubic-quintic recursion it grows like
/// `3.73^n` with the number of segments `n` (see
/// [`SegmentScheme::CubicQuinticLast`]).
pub fn rate_amplification(trajectory: &Trajectory) -> f64 {
    let knots = trajectory.knots();
    let dof = trajectory.dof();
    let mut state = JointState::zeros(dof);
    let (mut fastest_knot, mut fastest_mean) = (0.0_f64, 0.0_f64);
    let mut previous = trajectory.start_state().position;
    for (i, w) in knots.windows(2).enumerate() {
        for phi in [0.0, 1.0] {
            if trajectory.sample_segment_into(i, phi, &mut state).is_ok() {
                let v = state.velocity.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                fastest_knot = fastest_knot.max(v);
            }
        }
        for (j, q) in state.position.iter().enumerate() {
            fastest_mean = fastest_mean.max((q - previous[j]).abs() / (w[1] - w[0]));
        }
        previous.clone_from(&state.position);
    }
    if fastest_mean > 0.0 {
        fastest_knot / fastest_mean
    } else {
        1.0
    }
}

/// What [`plan_continuous_path`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct ContinuousPathReport {
    /// The joint trajectory (same start time and duration as the path).
    pub trajectory: Trajectory,
    /// Whether every check point meets the tolerance.
    pub status: PathStatus,
    /// The IK solution at every knot (`segments + 1` configurations).
    pub configurations: Vec<Vec<f64>>,
    /// Largest errors over the final segments' check points (their
    /// midpoints by default, see [`ContinuousPathOptions::checks_per_segment`]).
    pub checked_error: PathError,
    /// Number of plan-and-check passes.
    pub passes: usize,
    /// Number of IK solves.
    pub ik_solves: usize,
}

/// Position and orientation error between a reached pose and the target.
fn pose_error(reached: &Pose, target: &Pose) -> PathError {
    PathError {
        position: (reached.translation - target.translation).norm(),
        orientation: rotation_angle(&(reached.rotation * target.rotation.transpose())),
    }
}

/// Error of `trajectory` against `path` at time `t`.
fn error_at(
    model: &Model,
    data: &mut Data,
    trajectory: &Trajectory,
    path: &CartesianTrajectory,
    state: &mut JointState,
    t: f64,
) -> Result<PathError> {
    trajectory.sample_into(t, state)?;
    let reached = *forward_kinematics(model, data, &state.position)?;
    Ok(pose_error(&reached, &path.pose_at(t)))
}

/// The largest errors of a joint trajectory against a Cartesian path at
/// `samples_per_segment` evenly spaced points strictly inside every segment
/// (`phi = k / (N + 1)`, `k = 1..N`): a check of the adaptive method
/// independent of the points it was built on.
pub fn measure_path_error(
    model: &Model,
    trajectory: &Trajectory,
    path: &CartesianTrajectory,
    samples_per_segment: usize,
) -> Result<PathError> {
    if trajectory.dof() != model.dof() {
        return Err(Error::DimensionMismatch {
            what: "trajectory (joints)",
            expected: model.dof(),
            got: trajectory.dof(),
        });
    }
    let mut data = Data::new(model);
    let mut state = JointState::zeros(model.dof());
    let mut worst = PathError::default();
    let knots = trajectory.knots();
    for w in knots.windows(2) {
        for k in 1..=samples_per_segment {
            let t = w[0] + (w[1] - w[0]) * k as f64 / (samples_per_segment + 1) as f64;
            worst.include(error_at(model, &mut data, trajectory, path, &mut state, t)?);
        }
    }
    Ok(worst)
}

/// Seed 002's continuous-path planning: joint trajectory following `path`,
/// starting from the IK solution nearest `start` (joint positions).
///
/// Errors: invalid options; `start` of the wrong size; a path point out of
/// reach (the message gives the point's time and position and the IK's
/// reason) or an IK solution of the wrong size or outside the joint limits.
/// Not meeting the tolerance is a status, not an error.
pub fn plan_continuous_path(
    model: &Model,
    path: &CartesianTrajectory,
    ik: &mut dyn PathIk,
    start: &[f64],
    options: &ContinuousPathOptions,
) -> Result<ContinuousPathReport> {
    options.validate()?;
    model.check_joint_positions(start)?;
    let (initial, max) = match options.segmentation {
        Segmentation::Fixed(n) => (n, n),
        Segmentation::Adaptive { initial, max } => (initial, max),
    };
    let (t0, duration) = (path.start_time(), path.duration());
    let mut times: Vec<f64> = (0..=initial)
        .map(|i| t0 + duration * i as f64 / initial as f64)
        .collect();
    times[initial] = path.end_time();
    let mut ik_solves = times.len();
    let mut configurations = Vec::with_capacity(initial + 1);
    let mut previous = start.to_vec();
    for (k, &t) in times.iter().enumerate() {
        let point = PathPoint::Knot { k, n: initial };
        let q = solve_path_point(model, path, ik, t, &previous, point)?;
        previous.clone_from(&q);
        configurations.push(q);
    }
    let mut data = Data::new(model);
    let mut state = JointState::zeros(model.dof());
    let min_segment = 1e-9 * duration;
    let mut passes = 0;
    let mut last_finite: Option<ContinuousPathReport> = None;
    loop {
        passes += 1;
        let (dof, coefficients) =
            via_point_coefficients(options.scheme, &times, &configurations, &options.boundary)?;
        if coefficients.iter().flatten().any(|c| !c.is_finite()) {
            // The scheme's failure is an outcome: the last finite pass.
            let segments = times.len() - 1;
            return match last_finite {
                Some(report) => Ok(ContinuousPathReport {
                    status: PathStatus::SchemeDiverged,
                    passes,
                    ik_solves,
                    ..report
                }),
                None => Err(Error::invalid_argument(
                    "scheme",
                    format!(
                        "the polynomial coefficients overflow on {segments} segments (the cubic-quintic \
                         recursion multiplies errors by up to 3.73 per segment): use fewer segments or \
                         the quartic-cubic-quartic scheme"
                    ),
                )),
            };
        }
        let trajectory = Trajectory::from_polynomials(times.clone(), dof, coefficients)?;
        let mut checked_error = PathError::default();
        let mut failing = Vec::new();
        let checks = options.checks_per_segment;
        for i in 0..times.len() - 1 {
            let mut segment_error = PathError::default();
            for k in 1..=checks {
                let t = times[i] + (times[i + 1] - times[i]) * k as f64 / (checks + 1) as f64;
                segment_error.include(error_at(
                    model,
                    &mut data,
                    &trajectory,
                    path,
                    &mut state,
                    t,
                )?);
            }
            checked_error.include(segment_error);
            if !options.tolerance.is_met(&segment_error) {
                failing.push(i);
            }
        }
        let segments = times.len() - 1;
        let refinable = failing
            .iter()
            .all(|&i| times[i + 1] - times[i] > 2.0 * min_segment);
        if failing.is_empty() || segments + failing.len() > max || !refinable {
            let status = if failing.is_empty() {
                PathStatus::ToleranceMet
            } else {
                PathStatus::ToleranceNotMet
            };
            return Ok(ContinuousPathReport {
                trajectory,
                status,
                configurations,
                checked_error,
                passes,
                ik_solves,
            });
        }
        if options.scheme == SegmentScheme::CubicQuinticLast {
            last_finite = Some(ContinuousPathReport {
                trajectory,
                status: PathStatus::ToleranceNotMet,
                configurations: configurations.clone(),
                checked_error,
                passes,
                ik_solves,
            });
        }
        // Fig 6: insert the midpoint of every failing segment (from the back,
        // so that indices stay valid), IK nearest the segment's start.
        for &i in failing.iter().rev() {
            let t = 0.5 * (times[i] + times[i + 1]);
            let point = PathPoint::Midpoint { segment: i };
            let q = solve_path_point(model, path, ik, t, &configurations[i], point)?;
            ik_solves += 1;
            times.insert(i + 1, t);
            configurations.insert(i + 1, q);
        }
    }
}
