//! Inverse kinematics for seed 002's continuous path: [`PathIk`]
//! implementations on top of [`crate::ik`].
//!
//! * [`ClosedFormPathIk`]: every closed-form solution (seed 002's 4-DOF
//!   `arm4`, PUMA-type arms), the one nearest the previous configuration.
//! * [`NumericPathIk`]: numeric IK for any robot (panda, UR5, gantry9, ...),
//!   started from the previous configuration with minimum-norm steps and no
//!   random restarts, so that the solution is the one connected to the
//!   previous knot (a restart could land on another branch).
//! * [`path_ik_for`]: the closed form where one exists, numeric otherwise.
//!
//! [`IkTask::Position`] solves for the tool position only: for `arm4`, whose
//! reachable set is 4-D in SE(3), a Cartesian line with interpolated
//! orientation is reachable in position but not in orientation; plan it with
//! [`super::continuous_path::PathTolerance::Position`].
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::trajectory::{path_ik_for, IkTask};
//! let model = armkit::robots::by_name("panda").unwrap();
//! let q = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
//! let target = *forward_kinematics(&model, &mut Data::new(&model), &[0.05, -0.25, 0.0, -2.1, 0.0, 2.0, 0.8]).unwrap();
//! let (mut ik, method) = path_ik_for(&model, IkTask::Pose).unwrap();
//! assert!(method.starts_with("numeric"));
//! let solution = ik.solve_near(&target, &q).unwrap();
//! let reached = *forward_kinematics(&model, &mut Data::new(&model), &solution).unwrap();
//! assert!((reached.translation - target.translation).norm() < 1e-9);
//! ```

use super::cartesian::CartesianTrajectory;
use super::continuous_path::PathIk;
use crate::error::{Error, Result};
use crate::ik::closed_form::{ClosedFormSolver, Fit};
use crate::ik::{IkOptions, IkSelection, IkSolver, Redundancy};
use crate::math::Pose;
use crate::model::Model;

/// What the IK must reach.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IkTask {
    /// Position and orientation of the end-effector.
    Pose,
    /// Position of the end-effector origin only (orientation free): for arms
    /// that cannot follow the path's orientation (arm4).
    Position,
}

/// Closed-form IK along a path: the solution nearest the previous
/// configuration, within the joint limits.
///
/// With [`IkTask::Pose`] only exact solutions are accepted; with
/// [`IkTask::Position`], arm4's best fits of unreachable orientations
/// (tool position exact, orientation as close as the arm allows) are too.
#[derive(Clone, Debug)]
pub struct ClosedFormPathIk {
    solver: ClosedFormSolver,
    task: IkTask,
}

impl ClosedFormPathIk {
    /// For `model`; errors if it has no closed-form solver.
    pub fn new(model: &Model, task: IkTask) -> Result<Self> {
        Ok(ClosedFormPathIk {
            solver: ClosedFormSolver::new(model)?,
            task,
        })
    }
}

impl PathIk for ClosedFormPathIk {
    fn solve_near(&mut self, target: &Pose, previous: &[f64]) -> Result<Vec<f64>> {
        let solutions = self.solver.solve(target, previous)?;
        let accepted = solutions.into_iter().find(|s| match self.task {
            IkTask::Pose => s.fit == Fit::Exact,
            IkTask::Position => true,
        });
        match accepted {
            Some(s) => Ok(s.q),
            None => Err(Error::invalid_argument(
                "target",
                match self.task {
                    IkTask::Pose => "no exact closed-form solution within the joint limits",
                    IkTask::Position => {
                        "no closed-form solution within the joint limits reaches the position"
                    }
                },
            )),
        }
    }
}

/// Numeric IK along a path, started from the previous configuration.
#[derive(Clone, Debug)]
pub struct NumericPathIk {
    solver: IkSolver,
    /// The joints' position limits (lower, upper), to name the joints the
    /// search ended on when it fails.
    limits: (Vec<f64>, Vec<f64>),
}

impl NumericPathIk {
    /// With the given IK options (the start is always the previous knot).
    pub fn new(model: &Model, options: IkOptions) -> Result<Self> {
        Ok(NumericPathIk {
            solver: IkSolver::new(model, options)?,
            limits: model.position_limits(),
        })
    }

    /// The options for following a path: the default method
    /// (Levenberg-Marquardt), tolerances 1e-10 m and 1e-10 rad (far below
    /// any path tolerance), 100 iterations, no random restarts, no time
    /// budget (deterministic), minimum-norm steps (the spare freedom of a
    /// redundant arm stays where the previous knot put it), and the task's
    /// weights.
    pub fn path_options(task: IkTask) -> IkOptions {
        IkOptions {
            position_tolerance: 1e-10,
            orientation_tolerance: 1e-10,
            max_iterations: 100,
            max_restarts: 0,
            time_budget: None,
            task_weights: match task {
                IkTask::Pose => [1.0; 6],
                IkTask::Position => [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            },
            selection: IkSelection::First,
            redundancy: Redundancy::MinimumNorm,
            ..IkOptions::default()
        }
    }

    /// With [`NumericPathIk::path_options`].
    pub fn for_path(model: &Model, task: IkTask) -> Result<Self> {
        Self::new(model, Self::path_options(task))
    }
}

impl PathIk for NumericPathIk {
    fn solve_near(&mut self, target: &Pose, previous: &[f64]) -> Result<Vec<f64>> {
        let report = self.solver.solve(target, previous)?;
        if report.converged() {
            return Ok(report.q);
        }
        // The search keeps the joints within their limits: a joint that
        // ended on one is what stopped it short of a target in reach.
        let (lower, upper) = &self.limits;
        let blocked: Vec<String> = report
            .q
            .iter()
            .enumerate()
            .filter_map(|(j, &v)| {
                let at = |bound: f64| (v - bound).abs() <= 1e-6 * (1.0 + bound.abs());
                if at(lower[j]) {
                    Some(format!("joint {} at its lower limit {}", j + 1, lower[j]))
                } else if at(upper[j]) {
                    Some(format!("joint {} at its upper limit {}", j + 1, upper[j]))
                } else {
                    None
                }
            })
            .collect();
        let cause = if blocked.is_empty() {
            "no joint at a limit: the point is beyond the arm's reach from there, or a singularity \
             blocks the way"
                .to_string()
        } else {
            format!("blocked by {}", blocked.join(" and "))
        };
        Err(Error::invalid_argument(
            "target",
            format!(
                "numeric IK from the previous configuration did not converge (best: position error \
                 {:.3e} m, orientation error {:.3e} rad; {cause})",
                report.position_error, report.orientation_error
            ),
        ))
    }
}

/// The IK to follow a path with `model`: closed form when the model has one
/// (arm4, PUMA-type 6R arms), numeric otherwise; with a one-line description.
pub fn path_ik_for(model: &Model, task: IkTask) -> Result<(Box<dyn PathIk>, &'static str)> {
    match ClosedFormPathIk::new(model, task) {
        Ok(ik) => {
            let description = ik.solver.description();
            Ok((Box::new(ik), description))
        }
        Err(_) => Ok((
            Box::new(NumericPathIk::for_path(model, task)?),
            "numeric (Levenberg-Marquardt from the previous knot)",
        )),
    }
}

/// Which path point an IK solve is for, to name it in errors.
#[derive(Clone, Copy, Debug)]
pub(super) enum PathPoint {
    /// Knot `k` of the `n` initial segments (0 the start, `n` the goal).
    Knot { k: usize, n: usize },
    /// The midpoint inserted into segment `segment` (0-based) by Fig 6's
    /// adaptive segmentation.
    Midpoint { segment: usize },
}

/// IK at the path's pose at time `t`, near `previous`, within the joint
/// limits; errors name the point (knot or inserted midpoint, time,
/// position) and the cause (the IK's, or the joint and limit).
pub(super) fn solve_path_point(
    model: &Model,
    path: &CartesianTrajectory,
    ik: &mut dyn PathIk,
    t: f64,
    previous: &[f64],
    point: PathPoint,
) -> Result<Vec<f64>> {
    let target = path.pose_at(t);
    let p = target.translation;
    let which = match point {
        PathPoint::Knot { k, n } => format!("knot {k} of knots 0..{n}"),
        PathPoint::Midpoint { segment } => format!("midpoint inserted into segment {segment}"),
    };
    let at = format!(
        "path point ({which}, t = {t:.6} s, position [{:.6}, {:.6}, {:.6}] m)",
        p.x, p.y, p.z
    );
    let q = ik.solve_near(&target, previous).map_err(|e| {
        Error::invalid_argument("path", format!("IK failed at the {at}: {}", reason(&e)))
    })?;
    model.check_limits(&q).map_err(|e| {
        Error::invalid_argument(
            "path",
            format!(
                "IK solution for the {at} is outside the joint limits: {}",
                reason(&e)
            ),
        )
    })?;
    Ok(q)
}

/// The reason of an argument error (without its `invalid argument` prefix),
/// else the error's text.
fn reason(e: &Error) -> String {
    match e {
        Error::InvalidArgument { reason, .. } => reason.clone(),
        other => other.to_string(),
    }
}
