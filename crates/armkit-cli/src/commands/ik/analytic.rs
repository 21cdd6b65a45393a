//! `armkit ik --solver analytic` (alias `closed-form`) and `--explain`.

use armkit::ik::analytic::{
    self, AnalyticOptions, AnalyticRoute, Fit, JointNumbering, Parameter, Representatives,
};
use armkit::ik::{IkOptions, IkSolver, IkStatus};
use armkit::kinematics::Data;
use armkit::math::Pose;
use armkit::Model;

use super::report::{errors, fit_json, format_q, outcome};
use super::{failure_reason, IkArgs, RedundancyArgs, RepresentativesArg, MAX_SWEEP};
use crate::common::{print_json, CliError, CliResult, Outcome};

/// The analytic route of `model` (the library's [`AnalyticRoute`]) after
/// the CLI's own checks of its redundancy flags (1-based `--fixed-joint`),
/// listing `representatives` of each solution.
pub(super) fn route(
    model: &Model,
    redundancy: &RedundancyArgs,
    representatives: Representatives,
    start: &[f64],
) -> CliResult<AnalyticRoute> {
    redundancy.search.check()?;
    let options = AnalyticOptions {
        representatives,
        ..AnalyticOptions::default()
    };
    if model.dof() != 7
        && (redundancy.fixed_joint.is_some()
            || redundancy.parameter.is_some()
            || redundancy.sweep.is_some())
    {
        return Err(CliError(format!(
            "--fixed-joint / --parameter / --sweep: only for 7-joint arms; `{}` has {}",
            model.name(),
            model.dof()
        )));
    }
    if let Some(joint) = redundancy.fixed_joint {
        if joint == 0 || joint > 7 {
            return Err(CliError(format!(
                "--fixed-joint: must be 1 to 7, got {joint}"
            )));
        }
    }
    if let Some(n) = redundancy.sweep.filter(|&n| n == 0 || n > MAX_SWEEP) {
        return Err(CliError(format!(
            "--sweep: must be in 1..={MAX_SWEEP}, got {n}"
        )));
    }
    let choice = analytic::Redundancy {
        fixed_joint: redundancy.fixed_joint.map(|joint| joint - 1),
        value: redundancy.parameter,
    };
    let route = AnalyticRoute::new(model, options, choice, start)?;
    // A held joint outside its limits has no solution within them: said
    // here rather than listed as none.
    if let AnalyticRoute::Subproblems(solver) = &route {
        if let Some(Parameter::FixedJoint { joint, value }) = solver.parameter() {
            let limits = model.joints()[joint].limits;
            if value < limits.lower || value > limits.upper {
                let flag = match redundancy.parameter {
                    Some(_) => "--parameter",
                    None => "--start",
                };
                return Err(CliError(format!(
                    "{flag}: the held joint {}'s value {value} is outside its limits [{}, {}]",
                    joint + 1,
                    limits.lower,
                    limits.upper
                )));
            }
        }
    }
    Ok(route)
}

/// Runs `armkit ik --solver analytic`.
pub(super) fn run(
    args: &IkArgs,
    model: &Model,
    target: &Pose,
    start: &[f64],
    options: IkOptions,
) -> CliResult<Outcome> {
    let representatives = args.representatives.unwrap_or_default();
    let mut route = route(
        model,
        &args.redundancy,
        representatives.representatives(),
        start,
    )?;
    let solutions = route.solve(target, start, args.redundancy.sweep)?;
    let method = route.method(JointNumbering::OneBased);
    // The route lists exact solutions first: converged when any is exact,
    // and then the first is the nearest exact one.
    let status = match solutions.first() {
        Some(s) if s.fit == Fit::Exact => IkStatus::Converged,
        _ => IkStatus::NotConverged,
    };
    let listed = match representatives {
        RepresentativesArg::Nearest => "distinct solution(s)",
        RepresentativesArg::Every => "solution(s) (every 2 pi multiple)",
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
            "class": route.class_name(),
            "method": method,
            "status": status.as_str(),
            "q": best_effort,
            "position_error": position_error,
            "orientation_error": orientation_error,
            "solutions": solutions.iter().map(|s| s.q.clone()).collect::<Vec<_>>(),
            "solution_fits": solutions.iter().map(|s| fit_json(s.fit, s.position_error, s.orientation_error)).collect::<Vec<_>>(),
        }))?;
    } else {
        print!("{}: analytic inverse kinematics ({})\nclass: {}\nstatus: {status}\n{} {listed} within the joint limits, exact first, nearest the start first:\n",
            model.name(), method, route.class_name(), solutions.len());
        for (i, s) in solutions.iter().enumerate() {
            println!(
                "  {}: [{}]  {}, position error {:.1e} m, orientation error {:.1e} rad",
                i + 1,
                format_q(&s.q),
                s.fit,
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
    // How `--solver analytic` would solve it with these flags (None when it
    // refuses the arm; the class line then says why).
    let method = route(
        model,
        redundancy,
        Representatives::Nearest,
        &model.neutral_configuration(),
    )
    .ok()
    .map(|route| route.method(JointNumbering::OneBased));
    if json {
        // Solvable: `--solver analytic` takes the arm with these flags (by
        // a closed form, elimination or a search), whatever the class.
        return print_json(&serde_json::json!({
            "robot": model.name(),
            "class": class.as_str(),
            "solvable": method.is_some(),
            "description": class.description(),
            "method": method,
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
    // Printed where it says more than the class line: another method
    // (elimination, a search option) or a held joint's value.
    if let Some(method) = method.filter(|m| m != class.description()) {
        println!(
            "method (--solver analytic, --search {}): {method}",
            redundancy.search.name()
        );
    }
    Ok(())
}
