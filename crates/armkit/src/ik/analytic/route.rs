//! Which analytic solver a model gets: the route shared by `armkit ik
//! --solver analytic` and Python's `Robot.ik_solutions` (a 6-joint arm as
//! it is, a 7-joint arm by a held joint or its elbow angle), the values of
//! a redundancy sweep, and the class `--explain` reports.

use super::structure::ArmStructure;
use super::{explain, joint_to_hold, AnalyticOptions, AnalyticSolver, ArmClass, Parameter};
use crate::error::{check_finite_vector, Error, Result};
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
        None => {
            return Err(Error::invalid_argument(
                "sweep",
                "only for 7-joint arms (the redundancy parameter is swept)",
            ))
        }
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
