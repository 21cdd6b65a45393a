//! The automatic route: the analytic solver where the arm's class allows,
//! otherwise (or when it finds nothing within the limits) the numeric one.
//!
//! * 6-joint arms of an analytic class: every solution, the nearest exact
//!   one within the limits is returned. Not the one-pair and general
//!   classes (elimination, slower than the numeric solver): those arms,
//!   and 7-joint arms whose held joint leaves that class, go to the
//!   numeric solver.
//! * 7-joint arms: a spherical-shoulder-elbow-wrist arm by its elbow angle,
//!   any other by holding the joint [`super::analytic::joint_to_hold`]
//!   picks. The answer is the solution nearest the start over the
//!   parameter values within [`NEAREST_WINDOW`] of the start's own (the
//!   start's elbow angle or joint value: a grid, then golden-section
//!   refinement around its best point), so a start near a solution lands on
//!   it, whichever parameter value that solution has; when the answer is
//!   still farther than [`NEAREST_WINDOW`] from the start (a start near a
//!   fold of the self-motion, where the parameter turns back), one numeric
//!   descent from the start (no random restarts) answers if it converges
//!   nearer. If none of those
//!   values gives a solution, a held joint is tried at every value of a
//!   [`SWEEP_VALUES`]-point grid over its range, nearest the start's value
//!   first, before the numeric solver (on the Panda a try costs about a
//!   ninth of a numeric solve, and the numeric solver is slowest on the
//!   poses the held values near the start miss).
//! * The analytic solutions' fit comes from the subproblems; the one
//!   returned is checked by forward kinematics against the tolerances
//!   (nearest first, until one passes).
//! * Otherwise, or when nothing exact lies within the limits: the numeric
//!   solver from the start; if it does not converge on a 7-joint arm with an
//!   elbow angle, a sweep of [`SWEEP_VALUES`] values of it, the nearest
//!   exact solution winning.
//! * A target beyond the reach bound ([`super::ReachBound`]) is not attempted.
//!
//! ```
//! use armkit::ik::{AutoSolver, IkOptions, IkRoute, IkStatus};
//! use armkit::kinematics::{forward_kinematics, Data};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let mut data = Data::new(&model);
//! let goal = *forward_kinematics(&model, &mut data, &[0.3, -1.2, 1.4, -0.5, 1.2, 0.4]).unwrap();
//! let mut solver = AutoSolver::new(&model, IkOptions::default()).unwrap();
//! let solved = solver.solve(&goal, &model.neutral_configuration()).unwrap();
//! assert_eq!(solved.report.status, IkStatus::Converged);
//! assert_eq!(solved.route, IkRoute::Analytic);
//! ```

use std::time::Instant;

use super::analytic::{
    AnalyticOptions, AnalyticSolution, AnalyticSolver, ArmClass, Fit, Parameter,
};
use super::pose_error::pose_error;
use super::{IkOptions, IkReport, IkSolver, IkStatus};
use crate::error::Result;
use crate::kinematics::{forward_kinematics, Data};
use crate::math::roots::golden_section;
use crate::math::Pose;
use crate::model::{JointLimits, Model};

/// Values of the redundancy parameter tried by a 7-DOF sweep (evenly over
/// the elbow angle's circle or the held joint's range).
pub const SWEEP_VALUES: usize = 16;

/// Half-width of the window of redundancy-parameter values (a held joint's
/// value, rad or m, or the elbow angle, rad) searched around the start's own
/// for the solution nearest the start: twice the 0.2 rad within which a
/// start counts as near a solution.
pub const NEAREST_WINDOW: f64 = 0.4;

/// Grid points on each side of the start's value within [`NEAREST_WINDOW`]
/// (then golden-section refinement around the best of them).
const NEAREST_GRID: usize = 4;

/// Golden-section shrinks of the refinement bracket (two grid steps wide:
/// 0.2 rad to about 1.6e-3 rad).
const NEAREST_REFINE: usize = 10;

/// Distance (rad or m, joint space) below which the start itself counts as
/// a solution and no nearer one is searched for.
const START_REACHED: f64 = 1e-9;

/// Values of a held joint tried before the numeric solver: the start's own
/// value, then every value of a [`SWEEP_VALUES`]-point grid over the joint's
/// range, nearest the start's first.
pub const HELD_TRIES: usize = SWEEP_VALUES + 1;

/// Which route answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IkRoute {
    /// The analytic solver, at the start's parameter for a 7-DOF arm.
    Analytic,
    /// The analytic solver over a sweep of the 7-DOF parameter.
    AnalyticSweep,
    /// The numeric solver.
    Numeric,
    /// Nothing attempted: the target is beyond the reach bound.
    Unreachable,
}

impl IkRoute {
    /// `analytic`, `analytic_sweep`, `numeric` or `unreachable`.
    pub fn as_str(&self) -> &'static str {
        match self {
            IkRoute::Analytic => "analytic",
            IkRoute::AnalyticSweep => "analytic_sweep",
            IkRoute::Numeric => "numeric",
            IkRoute::Unreachable => "unreachable",
        }
    }
}

impl std::fmt::Display for IkRoute {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What [`AutoSolver::solve`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoReport {
    /// The answer, as the numeric solver reports it (iterations and
    /// restarts 0 on the analytic routes).
    pub report: IkReport,
    /// Which route answered.
    pub route: IkRoute,
}

/// Which analytic attempt.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    /// At the start's own parameter (or the 6-DOF arm's only solve).
    OwnParameter,
    /// Over a sweep of the 7-DOF parameter.
    Sweep,
}

/// How a 7-joint arm's spare freedom is parameterized.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Spare {
    None,
    ElbowAngle,
    Joint(usize),
}

/// The automatic solver for one model (see the module docs).
#[derive(Clone, Debug)]
pub struct AutoSolver {
    numeric: IkSolver,
    /// The numeric solver without random restarts: one descent from the
    /// start, for a 7-joint start the parameter window did not reach.
    local: IkSolver,
    analytic: Option<AnalyticSolver>,
    spare: Spare,
    /// Forward kinematics workspace for checking analytic answers.
    data: Data,
}

impl AutoSolver {
    /// A solver for `model` with the numeric options `options` (also the
    /// tolerances an analytic answer must meet).
    pub fn new(model: &Model, options: IkOptions) -> Result<AutoSolver> {
        let numeric = IkSolver::new(model, options)?;
        let local = IkSolver::new(
            model,
            IkOptions {
                max_restarts: 0,
                ..options
            },
        )?;
        let (analytic, spare) = analytic_for(model);
        Ok(AutoSolver {
            numeric,
            local,
            analytic,
            spare,
            data: Data::new(model),
        })
    }

    /// The class the analytic route uses, if any.
    pub fn class(&self) -> Option<ArmClass> {
        self.analytic.as_ref().map(|a| a.class())
    }

    /// Solves for `target` (world frame) from `start` (rad or m). Errors
    /// only for bad input, as [`IkSolver::solve`].
    pub fn solve(&mut self, target: &Pose, start: &[f64]) -> Result<AutoReport> {
        let began = Instant::now();
        if self.numeric.beyond_reach(target) {
            let report = self.numeric.solve(target, start)?;
            return Ok(AutoReport {
                report,
                route: IkRoute::Unreachable,
            });
        }
        // The answer's joint values are copied out once, for the answer
        // returned (the report owns its `q`).
        let analytic = |(solution, route): (AnalyticSolution, IkRoute)| AutoReport {
            report: IkReport {
                status: IkStatus::Converged,
                q: solution.q().to_vec(),
                position_error: solution.position_error,
                orientation_error: solution.orientation_error,
                iterations: 0,
                restarts: 0,
                elapsed: began.elapsed(),
            },
            route,
        };
        if let Some(found) = self.analytic_answer(target, start, Stage::OwnParameter)? {
            let nearest = distance2(found.0.q(), start);
            if self.spare == Spare::None || nearest <= NEAREST_WINDOW * NEAREST_WINDOW {
                return Ok(analytic(found));
            }
            // A 7-joint arm's start on a branch the parameter window did not
            // reach (near a fold of the self-motion, where the held
            // parameter turns back): one numeric descent from the start (no
            // random restarts: a restart lands anywhere), when it converges
            // nearer.
            let mut report = self.local.solve(target, start)?;
            if report.converged() && distance2(&report.q, start) < nearest {
                report.elapsed = began.elapsed();
                return Ok(AutoReport {
                    report,
                    route: IkRoute::Numeric,
                });
            }
            return Ok(analytic(found));
        }
        let mut report = self.numeric.solve(target, start)?;
        if !report.converged() {
            // The numeric solver gave up: sweep the 7-DOF parameter.
            if let Some(found) = self.analytic_answer(target, start, Stage::Sweep)? {
                return Ok(analytic(found));
            }
        }
        report.elapsed = began.elapsed();
        Ok(AutoReport {
            report,
            route: IkRoute::Numeric,
        })
    }

    /// The nearest analytic solution within the tolerances, if any.
    fn analytic_answer(
        &mut self,
        target: &Pose,
        start: &[f64],
        stage: Stage,
    ) -> Result<Option<(AnalyticSolution, IkRoute)>> {
        let options = *self.numeric.options();
        let Some(analytic) = self.analytic.as_mut() else {
            return Ok(None);
        };
        let data = &mut self.data;
        // The first solution (nearest first) flagged exact by the
        // subproblems whose forward kinematics meets the tolerances, with
        // its errors.
        let model = self.numeric.model();
        let mut accepted = |solutions: &[AnalyticSolution]| -> Result<Option<AnalyticSolution>> {
            for s in solutions.iter().filter(|s| s.fit == Fit::Exact) {
                if let Some(s) = checked(model, data, s, target, &options)? {
                    return Ok(Some(s));
                }
            }
            Ok(None)
        };
        let own = match self.spare {
            Spare::None => None,
            Spare::ElbowAngle => Some(analytic.elbow_angle(start)?),
            Spare::Joint(j) => Some(start[j]),
        };
        if stage == Stage::OwnParameter {
            let Some(own) = own else {
                let found = accepted(analytic.solve(target, start)?)?;
                return Ok(found.map(|s| (s, IkRoute::Analytic)));
            };
            // The solution nearest the start over the parameter values near
            // the start's own: the start's branch, followed as the parameter
            // moves (a start within NEAREST_WINDOW of a solution's
            // parameter finds that solution's branch).
            let mut best: Option<(AnalyticSolution, f64)> = None;
            let mut distance = |value: f64| -> Result<f64> {
                if analytic.set_parameter_value(value).is_err() {
                    return Ok(f64::INFINITY);
                }
                let Some(s) = accepted(analytic.solve(target, start)?)? else {
                    return Ok(f64::INFINITY);
                };
                let d = distance2(s.q(), start);
                if best.as_ref().is_none_or(|(_, b)| d < *b) {
                    best = Some((s, d));
                }
                Ok(d)
            };
            let at_own = distance(own)?;
            if at_own > START_REACHED * START_REACHED {
                let step = NEAREST_WINDOW / NEAREST_GRID as f64;
                let mut nearest = (own, at_own);
                for k in 1..=NEAREST_GRID {
                    for value in [own - step * k as f64, own + step * k as f64] {
                        let d = distance(value)?;
                        if d < nearest.1 {
                            nearest = (value, d);
                        }
                    }
                }
                if nearest.1.is_finite() {
                    let center = nearest.0;
                    golden_section(&mut distance, center - step, center + step, NEAREST_REFINE)?;
                }
            }
            if let Some((found, _)) = best {
                return Ok(Some((found, IkRoute::Analytic)));
            }
            // A held joint: the far values of its range, nearest first.
            let Spare::Joint(j) = self.spare else {
                return Ok(None);
            };
            let mut values = [own; HELD_TRIES];
            held_values(&model.joints()[j].limits, own, &mut values);
            for &value in &values[1..] {
                if analytic.set_parameter_value(value).is_err() {
                    continue;
                }
                if let Some(found) = accepted(analytic.solve(target, start)?)? {
                    return Ok(Some((found, IkRoute::AnalyticSweep)));
                }
            }
            return Ok(None);
        }
        // A held joint was swept before the numeric solver.
        let (Some(own), Spare::ElbowAngle) = (own, self.spare) else {
            return Ok(None);
        };
        // Sweep the elbow angle; keep the nearest exact solution.
        let (lower, upper) = (own - std::f64::consts::PI, own + std::f64::consts::PI);
        let mut best: Option<(AnalyticSolution, f64)> = None;
        for k in 0..SWEEP_VALUES {
            let value = lower + (upper - lower) * (k as f64 + 0.5) / SWEEP_VALUES as f64;
            if analytic.set_parameter_value(value).is_err() {
                continue;
            }
            if let Some(s) = accepted(analytic.solve(target, start)?)? {
                let distance = distance2(s.q(), start);
                if best.as_ref().is_none_or(|(_, d)| distance < *d) {
                    best = Some((s, distance));
                }
            }
        }
        Ok(best.map(|(s, _)| (s, IkRoute::AnalyticSweep)))
    }
}

/// Squared joint-space distance between `a` and `b` (rad^2 or m^2).
fn distance2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// `values[1..]`: the points of a [`SWEEP_VALUES`]-point grid over
/// `limits` nearest `own` (`values[0]` stays `own`); a joint without finite
/// limits gets `own` plus multiples of a grid over one turn.
fn held_values(limits: &JointLimits, own: f64, values: &mut [f64; HELD_TRIES]) {
    let (lower, upper) = if limits.is_bounded() {
        (limits.lower, limits.upper)
    } else {
        (own - std::f64::consts::PI, own + std::f64::consts::PI)
    };
    let step = (upper - lower) / SWEEP_VALUES as f64;
    let grid = |k: usize| lower + step * (k as f64 + 0.5);
    let mut used = [false; SWEEP_VALUES];
    for slot in values.iter_mut().skip(1) {
        let mut best: Option<usize> = None;
        for (k, taken) in used.iter().enumerate() {
            let nearer = best.is_none_or(|b| (grid(k) - own).abs() < (grid(b) - own).abs());
            if !taken && nearer {
                best = Some(k);
            }
        }
        if let Some(k) = best {
            used[k] = true;
            *slot = grid(k);
        }
    }
}

/// `s` with its forward-kinematics errors if they meet the tolerances of
/// `options`.
fn checked(
    model: &Model,
    data: &mut Data,
    s: &AnalyticSolution,
    target: &Pose,
    options: &IkOptions,
) -> Result<Option<AnalyticSolution>> {
    let pose = forward_kinematics(model, data, s.q())?;
    let e = pose_error(target, pose);
    let position_error = e.fixed_rows::<3>(0).norm();
    let orientation_error = e.fixed_rows::<3>(3).norm();
    let meets = position_error <= options.position_tolerance
        && orientation_error <= options.orientation_tolerance;
    Ok(meets.then(|| {
        let mut s = *s;
        s.position_error = position_error;
        s.orientation_error = orientation_error;
        s
    }))
}

/// The analytic solver for `model` and how its spare freedom is set, if any.
fn analytic_for(model: &Model) -> (Option<AnalyticSolver>, Spare) {
    let options = AnalyticOptions {
        representatives: super::analytic::Representatives::Nearest,
        // Checked by forward kinematics in `checked`, the returned one only.
        verification: super::analytic::Verification::Subproblems,
        ..AnalyticOptions::default()
    };
    if model.dof() != 7 {
        let solver = AnalyticSolver::new(model, options).ok();
        return (solver.filter(faster_than_numeric), Spare::None);
    }
    if let Ok(s) = AnalyticSolver::with_parameter(model, options, Parameter::ElbowAngle(0.0)) {
        return (Some(s), Spare::ElbowAngle);
    }
    if let Some((joint, _)) = super::analytic::joint_to_hold(model) {
        let parameter = Parameter::FixedJoint {
            joint,
            value: model.neutral_configuration()[joint],
        };
        if let Ok(s) = AnalyticSolver::with_parameter(model, options, parameter) {
            if faster_than_numeric(&s) {
                return (Some(s), Spare::Joint(joint));
            }
        }
    }
    (None, Spare::None)
}

/// False for the 6R classes without a closed form (elimination, 30-60 us a
/// solve; a numeric solve of such an arm
/// takes about 15 us): the automatic route is for the fastest answer, and a
/// caller who wants every solution of such an arm asks the analytic solver.
fn faster_than_numeric(solver: &AnalyticSolver) -> bool {
    !matches!(
        solver.class(),
        ArmClass::OnePair { .. } | ArmClass::General | ArmClass::OtherPairs
    )
}
