//! Which analytic solver a model gets: the route shared by `armkit ik
//! --solver analytic`, `armkit bench-ik --solver analytic` and Python's
//! `Robot.ik_solutions` (a 6-joint arm as it is, a 7-joint arm by a held
//! joint or its elbow angle, seed 002's 4-joint arm by its closed form:
//! [`AnalyticRoute`]), the values of a redundancy sweep, and the class
//! `--explain` reports.
//!
//! ```
//! use armkit::ik::analytic::{AnalyticOptions, AnalyticRoute, JointNumbering, Redundancy};
//! use armkit::kinematics::{forward_kinematics, Data};
//! let model = armkit::robots::by_name("arm4").unwrap();
//! let q = [0.3, -0.4, 0.5, 0.2];
//! let mut data = Data::new(&model);
//! forward_kinematics(&model, &mut data, &q).unwrap();
//! let target = *data.end_effector_pose();
//! let mut route = AnalyticRoute::new(&model, AnalyticOptions::default(), Redundancy::default(), &q).unwrap();
//! assert_eq!(route.class_name(), "seed002_arm4");
//! let solutions = route.solve(&target, &q, None).unwrap();
//! assert!(solutions.iter().any(|s| s.q.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9)));
//! assert!(route.method(JointNumbering::OneBased).contains("4-DOF"));
//! ```

use super::structure::ArmStructure;
use super::{explain, joint_to_hold, AnalyticOptions, AnalyticSolver, ArmClass, Fit, Parameter};
use crate::error::{check_finite_vector, Error, Result};
use crate::ik::closed_form::{ClosedFormSolution, ClosedFormSolver};
use crate::math::Pose;
use crate::model::Model;

/// How [`solver_for`] resolves a 7-joint arm's redundancy. Nothing set (the
/// default): the elbow angle of a spherical-shoulder-elbow-wrist arm, else
/// the joint [`joint_to_hold`] picks, at the start configuration's value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Redundancy {
    /// The joint to hold, 0-based (None: the default choice above).
    pub fixed_joint: Option<usize>,
    /// The elbow angle (rad) or the held joint's value (rad or m); None:
    /// the start configuration's.
    pub value: Option<f64>,
}

/// The analytic solver of `model` (the route of `armkit ik --solver
/// analytic` and of Python's `Robot.ik_solutions`): [`AnalyticSolver::new`]
/// for a 6-joint arm; for a 7-joint arm, joint `redundancy.fixed_joint`
/// held, else the elbow angle of a spherical-shoulder-elbow-wrist arm, else
/// [`joint_to_hold`]'s joint held; the parameter's value is
/// `redundancy.value`, else read from `start` (rad or m, one per joint).
/// Errors: a redundancy setting for an arm without 7 joints (named
/// `fixed_joint` or `parameter`), a held joint index of 7 or more, a
/// non-finite `start` or value, or an arm without analytic solver (the
/// message names its class).
///
/// ```
/// use armkit::ik::analytic::{solver_for, AnalyticOptions, Redundancy};
/// let model = armkit::robots::by_name("panda").unwrap();
/// let start = model.neutral_configuration();
/// let solver = solver_for(&model, AnalyticOptions::default(), Redundancy::default(), &start).unwrap();
/// assert!(solver.parameter().is_some());
/// ```
pub fn solver_for(
    model: &Model,
    options: AnalyticOptions,
    redundancy: Redundancy,
    start: &[f64],
) -> Result<AnalyticSolver> {
    if model.dof() != 7 {
        if redundancy != Redundancy::default() {
            let what = match redundancy.fixed_joint {
                Some(_) => "fixed_joint",
                None => "parameter",
            };
            return Err(Error::invalid_argument(
                what,
                format!(
                    "a held joint or redundancy parameter is for 7-joint arms; `{}` has {}",
                    model.name(),
                    model.dof()
                ),
            ));
        }
        return AnalyticSolver::new(model, options);
    }
    check_finite_vector("start", start, model.dof())?;
    if let Some(joint) = redundancy.fixed_joint {
        if joint >= model.dof() {
            return Err(Error::invalid_argument(
                "fixed_joint",
                format!("must be 0 to 6 (0-based), got {joint}"),
            ));
        }
        let value = redundancy.value.unwrap_or(start[joint]);
        let parameter = Parameter::FixedJoint { joint, value };
        return AnalyticSolver::with_parameter(model, options, parameter);
    }
    let elbow_error =
        match AnalyticSolver::with_parameter(model, options, Parameter::ElbowAngle(0.0)) {
            Ok(mut solver) => {
                let psi = match redundancy.value {
                    Some(psi) => psi,
                    None => solver.elbow_angle(start)?,
                };
                solver.set_parameter_value(psi)?;
                return Ok(solver);
            }
            Err(error) => error,
        };
    match joint_to_hold(model) {
        Some((joint, _)) => {
            let value = redundancy.value.unwrap_or(start[joint]);
            let parameter = Parameter::FixedJoint { joint, value };
            AnalyticSolver::with_parameter(model, options, parameter)
        }
        None => Err(elbow_error),
    }
}

/// `n` values of `solver`'s redundancy parameter for
/// [`AnalyticSolver::sweep`], evenly (cell midpoints): the elbow angle over
/// [-pi, pi) rad, or the held joint over its limits (a full turn when
/// unbounded). Errors (named `sweep`): `n` = 0, or a solver without
/// parameter (not a 7-joint arm).
pub fn sweep_values(solver: &AnalyticSolver, n: usize) -> Result<Vec<f64>> {
    use std::f64::consts::PI;
    if n == 0 {
        return Err(Error::invalid_argument("sweep", "must be >= 1, got 0"));
    }
    let (lower, upper) = match solver.parameter() {
        Some(Parameter::ElbowAngle(_)) => (-PI, PI),
        Some(Parameter::FixedJoint { joint, .. }) => {
            let limits = solver.model().joints()[joint].limits;
            if limits.is_bounded() {
                (limits.lower, limits.upper)
            } else {
                (-PI, PI)
            }
        }
        None => return Err(nothing_to_sweep()),
    };
    Ok((0..n)
        .map(|k| lower + (upper - lower) * (k as f64 + 0.5) / n as f64)
        .collect())
}

/// The class `armkit ik --explain` reports, with the lines it was read
/// from: [`explain`]'s, or, for a 7-joint arm given no parameter whose
/// class has no solver, the class with [`joint_to_hold`]'s joint held (that
/// joint, 0-based, is returned too; [`solver_for`] holds it).
pub fn route_class(
    model: &Model,
    parameter: Option<Parameter>,
) -> Result<(ArmClass, Option<usize>, ArmStructure)> {
    let (class, structure) = explain(model, parameter)?;
    if model.dof() == 7 && parameter.is_none() && !class.is_solvable() {
        if let Some((joint, reduced)) = joint_to_hold(model) {
            return Ok((reduced, Some(joint), structure));
        }
    }
    Ok((class, None, structure))
}

/// The error of a sweep asked of an arm without redundancy parameter.
fn nothing_to_sweep() -> Error {
    Error::invalid_argument(
        "sweep",
        "only for 7-joint arms (the redundancy parameter is swept)",
    )
}

/// The analytic solver of one model, chosen once: the subproblem
/// decomposition ([`solver_for`]), or, for seed 002's 4-joint arm (which
/// the decomposition does not take), its closed form
/// ([`ClosedFormSolver::Arm4`]).
#[derive(Clone, Debug)]
pub enum AnalyticRoute {
    /// [`solver_for`]'s solver.
    Subproblems(Box<AnalyticSolver>),
    /// Seed 002's 4-DOF arm.
    Arm4(Box<ClosedFormSolver>),
}

/// How joints are numbered in text meant for a user.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointNumbering {
    /// 0 to n - 1 (Python).
    ZeroBased,
    /// 1 to n (the CLI's flags).
    OneBased,
}

impl AnalyticRoute {
    /// [`solver_for`]'s solver for `model`; if it has none, seed 002's
    /// 4-joint closed form when the model is that arm. Errors: those of
    /// [`solver_for`] (the message names the class it cannot solve).
    pub fn new(
        model: &Model,
        options: AnalyticOptions,
        redundancy: Redundancy,
        start: &[f64],
    ) -> Result<AnalyticRoute> {
        match solver_for(model, options, redundancy, start) {
            Ok(solver) => Ok(AnalyticRoute::Subproblems(Box::new(solver))),
            Err(error) => match ClosedFormSolver::new(model) {
                Ok(arm4 @ ClosedFormSolver::Arm4(_)) => Ok(AnalyticRoute::Arm4(Box::new(arm4))),
                _ => Err(error),
            },
        }
    }

    /// The class name (`armkit ik --json`'s `class`, Python's `arm_class`).
    pub fn class_name(&self) -> &'static str {
        match self {
            AnalyticRoute::Subproblems(s) => s.class().as_str(),
            AnalyticRoute::Arm4(_) => "seed002_arm4",
        }
    }

    /// The method in one line: the class's description and, for a 7-joint
    /// arm, the redundancy parameter (the held joint numbered per
    /// `numbering`).
    pub fn method(&self, numbering: JointNumbering) -> String {
        let solver = match self {
            AnalyticRoute::Subproblems(s) => s,
            AnalyticRoute::Arm4(c) => return c.description().to_string(),
        };
        let class = solver.method();
        match solver.parameter() {
            Some(Parameter::ElbowAngle(psi)) => format!("{class}; elbow angle {psi:.6} rad"),
            Some(Parameter::FixedJoint { joint, value }) => match numbering {
                JointNumbering::ZeroBased => {
                    format!("{class}; joint {joint} (0-based) held at {value:.6}")
                }
                JointNumbering::OneBased => {
                    format!("{class}; joint {} held at {value:.6}", joint + 1)
                }
            },
            None => class.to_string(),
        }
    }

    /// Every solution within the limits for `target` (end-effector pose,
    /// base frame), exact ones first, each group nearest `start` first (rad or m, one per joint); with
    /// `sweep` = Some(n), over n values of a 7-joint arm's redundancy
    /// parameter ([`sweep_values`]). Errors: those of the solvers, and a
    /// sweep asked of an arm without parameter (named `sweep`).
    pub fn solve(
        &mut self,
        target: &Pose,
        start: &[f64],
        sweep: Option<usize>,
    ) -> Result<Vec<ClosedFormSolution>> {
        let solver = match (self, sweep) {
            (AnalyticRoute::Arm4(c), None) => {
                // Exact first, each group nearest first (a stable sort of
                // the closed form's nearest-first list), as the subproblems'.
                let mut found = c.solve(target, start)?;
                found.sort_by_key(|s| s.fit != Fit::Exact);
                return Ok(found);
            }
            (AnalyticRoute::Arm4(_), Some(_)) => return Err(nothing_to_sweep()),
            (AnalyticRoute::Subproblems(s), _) => s,
        };
        let found = match sweep {
            None => solver.solve(target, start)?.to_vec(),
            Some(n) => {
                let values = sweep_values(solver, n)?;
                solver.sweep(target, start, &values)?
            }
        };
        Ok(found
            .iter()
            .map(|s| ClosedFormSolution {
                q: s.q().to_vec(),
                fit: s.fit,
                position_error: s.position_error,
                orientation_error: s.orientation_error,
            })
            .collect())
    }

    /// The exact solution within the limits nearest `start`, if any (every
    /// solution is computed, only this one copied out: what `armkit
    /// bench-ik --solver analytic` times).
    pub fn nearest_exact(&mut self, target: &Pose, start: &[f64]) -> Result<Option<Vec<f64>>> {
        Ok(match self {
            AnalyticRoute::Subproblems(s) => s
                .solve(target, start)?
                .iter()
                .find(|s| s.fit == Fit::Exact)
                .map(|s| s.q().to_vec()),
            AnalyticRoute::Arm4(c) => c
                .solve(target, start)?
                .into_iter()
                .find(|s| s.fit == Fit::Exact)
                .map(|s| s.q),
        })
    }
}
