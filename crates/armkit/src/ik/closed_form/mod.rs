//! Closed-form inverse kinematics: every solution, each checked by forward
//! kinematics.
//!
//! * [`SphericalWristSolver`]: 6R arms of the PUMA type (a vertical first
//!   axis, parallel shoulder and elbow axes, a spherical wrist), read from
//!   the model's standard DH table: up to 8 solutions (Pieper; Craig's PUMA
//!   solution, with the shoulder offset and `a3`). Fits `puma560` and `space6r`.
//! * [`Arm4Solver`]: seed 002's 4-DOF arm (two parallel vertical axes, a roll
//!   about link 2, a pitch, a tool along x4), `arm4`: every branch, exact
//!   where the pose is reachable, otherwise the tool position exactly with
//!   the orientation fitted as well as the arm allows (flagged
//!   [`Fit::Approximate`] with its residual). See [`arm4_solutions`].
//! * [`ClosedFormSolver`]: whichever of the two fits a model.
//!
//! Solutions are joint vectors (rad) within the joint limits (each angle is
//! the 2 pi multiple nearest the current configuration that lies within its
//! limits; a solution with no such multiple for some joint is dropped),
//! sorted nearest the current configuration first (Euclidean distance in
//! joint space). Each is verified by forward kinematics: an exact solution
//! reproduces the target within 1e-10 m and 1e-10 rad ([`EXACT_TOLERANCE`]).
//!
//! ```
//! use armkit::ik::closed_form::{ClosedFormSolver, Fit};
//! use armkit::kinematics::{forward_kinematics, Data};
//! let model = armkit::robots::by_name("puma560").unwrap();
//! let mut data = Data::new(&model);
//! let q = [0.3, 0.6, -1.9, 0.4, 0.8, -0.5];
//! let target = *forward_kinematics(&model, &mut data, &q).unwrap();
//! let solver = ClosedFormSolver::new(&model).unwrap();
//! let solutions = solver.solve(&target, &q).unwrap();
//! assert!(solutions.len() >= 2);
//! // The nearest solution is the configuration the target came from.
//! assert!(solutions[0].q.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
//! assert!(solutions.iter().all(|s| s.fit == Fit::Exact && s.position_error < 1e-10));
//! ```

mod arm4;
mod pieper;

pub use arm4::{arm4_solutions, Arm4Solver};
pub use pieper::SphericalWristSolver;

use super::numeric::check_target;
use super::pose_error::pose_error;
use crate::error::{Error, Result};
use crate::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use crate::math::{Pose, Vector6};
use crate::model::{DhConvention, DhLink, JointKind, Model};

/// Largest position (m) and orientation (rad) error of a solution called exact.
pub const EXACT_TOLERANCE: f64 = 1e-10;

/// How well a closed-form solution reproduces its target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Fit {
    /// Within [`EXACT_TOLERANCE`] in position and orientation.
    Exact,
    /// The best the arm can do for a pose outside its reachable set (see
    /// [`arm4_solutions`]); the errors say by how much it misses.
    Approximate,
}

impl Fit {
    /// `"exact"` or `"approximate"` (the CLI's JSON, Python's `fits`).
    pub fn as_str(self) -> &'static str {
        match self {
            Fit::Exact => "exact",
            Fit::Approximate => "approximate",
        }
    }
}

impl std::fmt::Display for Fit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Whether solutions outside the joint limits are kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RangeFilter {
    /// Only solutions within the limits (the default everywhere).
    WithinLimits,
    /// Every solution, angles taken nearest the current configuration
    /// (for counting the solutions of a pose, e.g. Pieper's 8).
    IgnoreLimits,
}

/// One closed-form solution.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedFormSolution {
    /// Joint positions, rad, one per joint.
    pub q: Vec<f64>,
    /// Exact, or the best fit of an unreachable pose.
    pub fit: Fit,
    /// Position error of `FK(q)` from the target, m.
    pub position_error: f64,
    /// Orientation error of `FK(q)` from the target, rad (angle of `R_goal R'`).
    pub orientation_error: f64,
}

/// A closed-form solver for the model structures armkit knows.
#[derive(Clone, Debug)]
pub enum ClosedFormSolver {
    /// PUMA-type 6R arm with a spherical wrist.
    SphericalWrist(SphericalWristSolver),
    /// Seed 002's 4-DOF arm.
    Arm4(Arm4Solver),
}

impl ClosedFormSolver {
    /// The solver that fits `model`; the error says why neither does.
    pub fn new(model: &Model) -> Result<ClosedFormSolver> {
        let wrist = match SphericalWristSolver::new(model) {
            Ok(s) => return Ok(ClosedFormSolver::SphericalWrist(s)),
            Err(e) => e,
        };
        let arm4 = match Arm4Solver::new(model) {
            Ok(s) => return Ok(ClosedFormSolver::Arm4(s)),
            Err(e) => e,
        };
        Err(Error::invalid_argument(
            "model",
            format!(
                "`{}` has no closed-form solver: not a 6R spherical-wrist arm ({}); not a seed-002 4-DOF arm ({})",
                model.name(),
                reason(&wrist),
                reason(&arm4)
            ),
        ))
    }

    /// Every solution within the limits, nearest `current` first.
    pub fn solve(&self, target: &Pose, current: &[f64]) -> Result<Vec<ClosedFormSolution>> {
        self.solve_with(target, current, RangeFilter::WithinLimits)
    }

    /// Every solution, filtered by `filter`, nearest `current` first.
    pub fn solve_with(
        &self,
        target: &Pose,
        current: &[f64],
        filter: RangeFilter,
    ) -> Result<Vec<ClosedFormSolution>> {
        match self {
            ClosedFormSolver::SphericalWrist(s) => s.solve_with(target, current, filter),
            ClosedFormSolver::Arm4(s) => s.solve_with(target, current, filter),
        }
    }

    /// A one-line name of the method (for reports).
    pub fn description(&self) -> &'static str {
        match self {
            ClosedFormSolver::SphericalWrist(_) => "6R spherical wrist (Pieper), up to 8 solutions",
            ClosedFormSolver::Arm4(_) => "seed 002 4-DOF arm, every branch",
        }
    }
}

fn reason(error: &Error) -> String {
    match error {
        Error::InvalidArgument { reason, .. } => reason.clone(),
        other => other.to_string(),
    }
}

/// The standard DH table of `model` if it has `dof` rotational joints and no
/// coupling; the error says what does not fit.
fn standard_dh_table(model: &Model, dof: usize) -> Result<Vec<DhLink>> {
    let not_fit = |why: String| Error::invalid_argument("model", why);
    let Some((convention, links)) = model.dh_table() else {
        return Err(not_fit("it has no DH table".into()));
    };
    if convention != DhConvention::Standard {
        return Err(not_fit("its DH table is not standard DH".into()));
    }
    if links.len() != dof || model.dof() != dof {
        return Err(not_fit(format!("it has {} joints, not {dof}", model.dof())));
    }
    if let Some(j) = model.joints().iter().position(|j| !j.kind.is_rotational()) {
        return Err(not_fit(format!("joint {} is prismatic", j + 1)));
    }
    if model.coupling().is_some() {
        return Err(not_fit("it has a joint coupling".into()));
    }
    Ok(links.to_vec())
}

/// True when `angle` equals `expected` (rad) to 1e-9.
fn angle_is(angle: f64, expected: f64) -> bool {
    crate::math::wrap_angle(angle - expected).abs() < 1e-9
}

/// +1 or -1 if `alpha` is +-90 deg, else `None`.
fn quarter_turn_sign(alpha: f64) -> Option<f64> {
    use std::f64::consts::FRAC_PI_2;
    if angle_is(alpha, FRAC_PI_2) {
        Some(1.0)
    } else if angle_is(alpha, -FRAC_PI_2) {
        Some(-1.0)
    } else {
        None
    }
}

/// The (up to two) angles with `a cos(t) + b sin(t) = d`; one when the
/// equation is tangent (to 1e-12 relative), none when `|d| > sqrt(a^2 + b^2)`.
fn solve_cos_sin(a: f64, b: f64, d: f64) -> Vec<f64> {
    let r = a.hypot(b);
    if r < 1e-300 {
        return Vec::new();
    }
    let ratio = d / r;
    if ratio.abs() > 1.0 + 1e-12 {
        return Vec::new();
    }
    let base = b.atan2(a);
    let spread = ratio.clamp(-1.0, 1.0).acos();
    if spread < 1e-12 {
        vec![base]
    } else {
        vec![base + spread, base - spread]
    }
}

/// `Rx(+-90 deg)` for `sign = +-1`.
fn rot_x_quarter(sign: f64) -> crate::math::Matrix3<f64> {
    crate::math::Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, -sign, 0.0, sign, 0.0)
}

/// The joint value for a DH angle: `q = theta_dh - theta - offset`.
fn joint_value(link: &DhLink, dh_angle: f64) -> f64 {
    dh_angle - link.theta - link.offset
}

/// The DH angle of a joint value: `theta_dh = q + theta + offset`.
fn dh_angle(link: &DhLink, q: f64) -> f64 {
    q + link.theta + link.offset
}

/// The 2 pi multiple of `value` nearest `current` (within the limits for
/// [`RangeFilter::WithinLimits`]), or `None` if no multiple is within them.
fn representation(
    model: &Model,
    joint: usize,
    value: f64,
    current: f64,
    filter: RangeFilter,
) -> Option<f64> {
    use std::f64::consts::TAU;
    let limits = &model.joints()[joint].limits;
    let unlimited =
        filter == RangeFilter::IgnoreLimits || model.joints()[joint].kind == JointKind::Continuous;
    let nearest = value + TAU * ((current - value) / TAU).round();
    if unlimited {
        return Some(nearest);
    }
    [nearest, nearest - TAU, nearest + TAU]
        .into_iter()
        .filter(|v| limits.contains(*v))
        .min_by(|a, b| (a - current).abs().total_cmp(&(b - current).abs()))
}

/// Turns candidate joint vectors into verified solutions: each joint angle
/// moved to its representation nearest `current` (dropped if out of range),
/// forward kinematics checked (solutions off by less than 1e-6 polished by
/// Gauss-Newton steps), duplicates merged, sorted nearest `current` first.
fn finish(
    model: &Model,
    candidates: &[Vec<f64>],
    target: &Pose,
    current: &[f64],
    filter: RangeFilter,
) -> Result<Vec<ClosedFormSolution>> {
    let mut data = Data::new(model);
    let mut solutions: Vec<ClosedFormSolution> = Vec::new();
    'candidates: for candidate in candidates {
        let mut q = Vec::with_capacity(candidate.len());
        for (j, value) in candidate.iter().enumerate() {
            match representation(model, j, *value, current[j], filter) {
                Some(v) => q.push(v),
                None => continue 'candidates,
            }
        }
        let mut solution = measure(model, &mut data, q, target)?;
        if solution.fit == Fit::Approximate
            && solution.position_error.max(solution.orientation_error) < 1e-6
        {
            solution = polish(model, &mut data, solution, target, filter)?;
        }
        let duplicate = solutions.iter().any(|s| {
            s.q.iter()
                .zip(&solution.q)
                .all(|(a, b)| (a - b).abs() < 1e-7)
        });
        if !duplicate {
            solutions.push(solution);
        }
    }
    sort_nearest(&mut solutions, current);
    Ok(solutions)
}

/// Sorts solutions by joint-space distance to `current`.
fn sort_nearest(solutions: &mut [ClosedFormSolution], current: &[f64]) {
    let distance = |q: &[f64]| -> f64 {
        q.iter()
            .zip(current)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
    };
    solutions.sort_by(|a, b| distance(&a.q).total_cmp(&distance(&b.q)));
}

/// Forward kinematics of `q` against the target: errors and fit.
fn measure(
    model: &Model,
    data: &mut Data,
    q: Vec<f64>,
    target: &Pose,
) -> Result<ClosedFormSolution> {
    let pose = forward_kinematics(model, data, &q)?;
    let e = pose_error(target, pose);
    let position_error = e.fixed_rows::<3>(0).norm();
    let orientation_error = e.fixed_rows::<3>(3).norm();
    let fit = if position_error <= EXACT_TOLERANCE && orientation_error <= EXACT_TOLERANCE {
        Fit::Exact
    } else {
        Fit::Approximate
    };
    Ok(ClosedFormSolution {
        q,
        fit,
        position_error,
        orientation_error,
    })
}

/// Up to four Gauss-Newton steps on a nearly exact solution (round-off near
/// a singular configuration, where `acos` loses digits), kept only if they
/// make it exact and stay within range.
fn polish(
    model: &Model,
    data: &mut Data,
    solution: ClosedFormSolution,
    target: &Pose,
    filter: RangeFilter,
) -> Result<ClosedFormSolution> {
    let mut best = solution;
    let mut q = best.q.clone();
    let mut step = vec![0.0; q.len()];
    for _ in 0..4 {
        let j = jacobian(model, data, &q, JacobianFrame::World)?.clone();
        let e: Vector6<f64> = pose_error(target, data.end_effector_pose());
        if super::damped_least_squares_step(&j, &e, 1e-9, &mut step).is_err() {
            break;
        }
        for (v, d) in q.iter_mut().zip(&step) {
            *v += d;
        }
        if filter == RangeFilter::WithinLimits && model.check_limits(&q).is_err() {
            break;
        }
        let candidate = measure(model, data, q.clone(), target)?;
        if candidate.fit == Fit::Exact {
            best = candidate;
            break;
        }
    }
    // Only round-off is repaired: a solution that does not become exact is
    // returned as it was (an approximate fit keeps its own trade-off).
    Ok(best)
}

/// Checks the common arguments of the closed-form solvers.
fn check_arguments(model: &Model, target: &Pose, current: &[f64]) -> Result<()> {
    check_target(target)?;
    crate::error::check_finite_vector("current", current, model.dof())
}
