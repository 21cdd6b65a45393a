//! `armkit ik --solver analytic` (alias `closed-form`) and `--explain`.

use armkit::ik::analytic::{self, AnalyticOptions, AnalyticSolver, Fit, Parameter};
use armkit::ik::closed_form::ClosedFormSolver;
use armkit::ik::{IkOptions, IkSolver, IkStatus};
use armkit::kinematics::Data;
use armkit::math::Pose;
use armkit::Model;

use super::report::{errors, fit_json, fit_name, format_q, outcome};
use super::{failure_reason, IkArgs, RedundancyArgs};
use crate::common::{print_json, CliError, CliResult, Outcome};

/// The analytic solver of a model: subproblem decomposition, or seed 002's
/// arm4 closed form.
pub(super) enum Route {
    Subproblems(Box<AnalyticSolver>),
    Arm4(Box<ClosedFormSolver>),
}

/// One solution in a common form.
pub(super) struct Solution {
    pub q: Vec<f64>,
    pub fit: Fit,
    pub position_error: f64,
    pub orientation_error: f64,
}

impl Route {
    /// The solver for `model`; 7-DOF arms per `redundancy` (defaults from `start`).
    pub(super) fn new(
        model: &Model,
        redundancy: &RedundancyArgs,
        start: &[f64],
    ) -> CliResult<Route> {
        let options = AnalyticOptions {
            search: redundancy.search.policy(),
            ..AnalyticOptions::default()
        };
        if model.dof() != 7 {
            if redundancy.fixed_joint.is_some()
                || redundancy.parameter.is_some()
                || redundancy.sweep.is_some()
            {
                return Err(CliError(format!(
                    "--fixed-joint / --parameter / --sweep: only for 7-joint arms; `{}` has {}",
                    model.name(),
                    model.dof()
                )));
            }
            return match AnalyticSolver::new(model, options) {
                Ok(s) => Ok(Route::Subproblems(Box::new(s))),
                Err(error) => match ClosedFormSolver::new(model) {
                    Ok(arm4 @ ClosedFormSolver::Arm4(_)) => Ok(Route::Arm4(Box::new(arm4))),
                    _ => Err(error.into()),
                },
            };
        }
        if let Some(joint) = redundancy.fixed_joint {
            if joint == 0 || joint > 7 {
                return Err(CliError(format!(
                    "--fixed-joint: must be 1 to 7, got {joint}"
                )));
            }
        }
        let choice = analytic::Redundancy {
            fixed_joint: redundancy.fixed_joint.map(|joint| joint - 1),
            value: redundancy.parameter,
        };
        Ok(Route::Subproblems(Box::new(analytic::solver_for(
            model, options, choice, start,
        )?)))
    }

    /// The class name (JSON `class`).
    pub(super) fn class(&self) -> &'static str {
        match self {
            Route::Subproblems(s) => s.class().as_str(),
            Route::Arm4(_) => "seed002_arm4",
        }
    }

    /// A one-line description of the method.
    pub(super) fn description(&self) -> String {
        match self {
            Route::Subproblems(s) => {
                let mut text = s.class().description().to_string();
                match s.parameter() {
                    Some(Parameter::ElbowAngle(psi)) => {
                        text.push_str(&format!("; elbow angle {psi:.6} rad"))
                    }
                    Some(Parameter::FixedJoint { joint, value }) => {
                        text.push_str(&format!("; joint {} held at {value:.6}", joint + 1))
                    }
                    None => {}
                }
                text
            }
            Route::Arm4(c) => c.description().to_string(),
        }
    }

    /// The nearest exact solution within the limits (the benchmark's answer:
    /// every solution is computed, only the first is copied out).
    pub(super) fn first_exact(
        &mut self,
        target: &Pose,
        start: &[f64],
    ) -> CliResult<Option<Vec<f64>>> {
        match self {
            Route::Subproblems(s) => Ok(s
                .solve(target, start)?
                .iter()
                .find(|s| s.fit == Fit::Exact)
                .map(|s| s.q().to_vec())),
            Route::Arm4(c) => Ok(c
                .solve(target, start)?
                .into_iter()
                .find(|s| s.fit == Fit::Exact)
                .map(|s| s.q)),
        }
    }

    /// Every solution within the limits, nearest `start` first; with `sweep`
    /// N, over N values of the 7-DOF parameter.
    pub(super) fn solve(
        &mut self,
        target: &Pose,
        start: &[f64],
        sweep: Option<usize>,
    ) -> CliResult<Vec<Solution>> {
        match self {
            Route::Arm4(c) => Ok(c
                .solve(target, start)?
                .into_iter()
                .map(|s| Solution {
                    q: s.q,
                    fit: s.fit,
                    position_error: s.position_error,
                    orientation_error: s.orientation_error,
                })
                .collect()),
            Route::Subproblems(s) => {
                let found = match sweep {
                    None => s.solve(target, start)?.to_vec(),
                    Some(0) => return Err(CliError("--sweep: must be >= 1".into())),
                    Some(n) => {
                        let values = analytic::sweep_values(s, n)?;
                        s.sweep(target, start, &values)?
                    }
                };
                Ok(found
                    .iter()
                    .map(|s| Solution {
                        q: s.q().to_vec(),
                        fit: s.fit,
                        position_error: s.position_error,
                        orientation_error: s.orientation_error,
                    })
                    .collect())
            }
        }
    }
}

/// Runs `armkit ik --solver analytic`.
pub(super) fn run(
    args: &IkArgs,
    model: &Model,
    target: &Pose,
    start: &[f64],
    options: IkOptions,
) -> CliResult<Outcome> {
    let mut route = Route::new(model, &args.redundancy, start)?;
    let solutions = route.solve(target, start, args.redundancy.sweep)?;
    let status = match solutions.first() {
        Some(s) if s.fit == Fit::Exact => IkStatus::Converged,
        _ => IkStatus::NotConverged,
    };
    // The nearest solution; with none, the numeric best effort.
    let (best_effort, numeric) = match solutions.first() {
        Some(s) => (s.q.clone(), None),
        None => {
            let report = IkSolver::new(model, options)?.solve(target, start)?;
            (report.q.clone(), Some(report))
        }
    };
    let mut data = Data::new(model);
    let (position_error, orientation_error) = errors(model, &mut data, &best_effort, target)?;
    if args.json {
        print_json(&serde_json::json!({
            "robot": model.name(),
            "solver": "analytic",
            "class": route.class(),
            "method": route.description(),
            "status": status.as_str(),
            "q": best_effort,
            "position_error": position_error,
            "orientation_error": orientation_error,
            "solutions": solutions.iter().map(|s| s.q.clone()).collect::<Vec<_>>(),
            "solution_fits": solutions.iter().map(|s| fit_json(s.fit, s.position_error, s.orientation_error)).collect::<Vec<_>>(),
        }))?;
    } else {
        print!("{}: analytic inverse kinematics ({})\nclass: {}\nstatus: {status}\n{} solution(s) within the joint limits, nearest the start first:\n",
            model.name(), route.description(), route.class(), solutions.len());
        for (i, s) in solutions.iter().enumerate() {
            println!(
                "  {}: [{}]  {}, position error {:.1e} m, orientation error {:.1e} rad",
                i + 1,
                format_q(&s.q),
                fit_name(s.fit),
                s.position_error,
                s.orientation_error
            );
        }
        if numeric.is_some() {
            println!(
                "best effort (numeric, lm): q = {}\nposition error {position_error:.3e} m, orientation error {orientation_error:.3e} rad",
                format_q(&best_effort)
            );
        }
    }
    if status != IkStatus::Converged {
        match &numeric {
            Some(report) => eprintln!("{}", failure_reason(model, target, report, &options)),
            None => eprintln!(
                "ik: no exact analytic solution within the joint limits: the nearest is least-squares, position error {position_error:.3e} m, orientation error {orientation_error:.3e} rad"
            ),
        }
    }
    Ok(outcome(status))
}

/// Prints the arm's lines, axis relations and class (`--explain`).
pub(super) fn explain(model: &Model, redundancy: &RedundancyArgs, json: bool) -> CliResult<()> {
    let parameter = redundancy.fixed_joint.map(|j| Parameter::FixedJoint {
        joint: j.saturating_sub(1),
        value: redundancy.parameter.unwrap_or(0.0),
    });
    let (class, held, structure) = analytic::route_class(model, parameter)?;
    let held = held.map(|joint| joint + 1);
    let held_text = held
        .map(|j| format!(" (with joint {j} held, the route of --solver analytic)"))
        .unwrap_or_default();
    if json {
        return print_json(&serde_json::json!({
            "robot": model.name(),
            "class": class.as_str(),
            "solvable": class.is_solvable(),
            "description": class.description(),
            "held_joint": held,
        }));
    }
    print!(
        "{}: {} joints\n{}class: {class}{held_text}\n  {}\n",
        model.name(),
        model.dof(),
        structure.describe(),
        class.description()
    );
    Ok(())
}
