//! How a closed-loop run ended, and why when it did not converge
//! ([`RunStatus`], [`diagnose_run`]).
//!
//! A run that stops short of its target is not an error: the status names
//! the cause. [`diagnose_run`] looks at the final configuration: IK with
//! restarts (is the target reachable within the limits at all?), the joints
//! sitting on a limit that the task's descent direction `J' W (y_d - y)`
//! pushes further out (which limit blocks), and the smallest singular value
//! of the tracked rows of the Jacobian (a singularity).
//!
//! ```
//! use armkit::mpc::{diagnose_run, MpcOptions, MpcPlanner, RunStatus};
//! use armkit::math::{Matrix3, Pose, Vector3};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let mut planner = MpcPlanner::new(&model, MpcOptions::default()).unwrap();
//! // 5 m away: beyond the arm's reach.
//! planner.set_target(&Pose::new(Matrix3::identity(), Vector3::new(5.0, 0.0, 0.0))).unwrap();
//! let q = model.neutral_configuration();
//! let status = diagnose_run(&planner, &q, false).unwrap();
//! assert_eq!(status.as_str(), "unreachable");
//! ```

use crate::error::Result;
use crate::ik::{IkOptions, IkSolver, IkStatus};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{rotation_log, DMatrix};

use super::active_set::BoundSide;
use super::planner::MpcPlanner;
use super::reach::GoalSearch;

/// Smallest singular value of the tracked Jacobian rows (m/rad or rad/rad)
/// below which a stalled run is reported as [`RunStatus::Singular`].
pub const SINGULAR_VALUE_THRESHOLD: f64 = 1e-3;

/// A joint counts as on its limit within this distance (m or rad).
pub const AT_LIMIT_TOLERANCE: f64 = 1e-6;

/// How a closed-loop run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum RunStatus {
    /// At the target and at rest.
    Converged,
    /// No configuration within the joint limits reaches the target (IK with
    /// restarts failed): the best had these errors.
    Unreachable {
        /// Position error of the best IK attempt, m.
        position_error: f64,
        /// Orientation error of the best IK attempt, rad.
        orientation_error: f64,
    },
    /// The run stopped against a joint limit: the joint is on it and the
    /// task's descent direction points beyond it.
    JointLimit {
        /// Joint index.
        joint: usize,
        /// Joint name.
        name: String,
        /// Which limit.
        side: BoundSide,
    },
    /// The run stalled at a singular configuration of the tracked task.
    Singular {
        /// Smallest singular value of the tracked rows of the Jacobian.
        smallest_singular_value: f64,
    },
    /// The step budget ran out with the target reachable and no limit or
    /// singularity in the way (still moving, or slowly converging).
    StepLimit {
        /// Position error at the end, m.
        position_error: f64,
        /// Orientation error at the end, rad.
        orientation_error: f64,
    },
}

impl RunStatus {
    /// `converged`, `unreachable`, `joint-limit`, `singular` or `step-limit`.
    pub fn as_str(&self) -> &'static str {
        match self {
            RunStatus::Converged => "converged",
            RunStatus::Unreachable { .. } => "unreachable",
            RunStatus::JointLimit { .. } => "joint-limit",
            RunStatus::Singular { .. } => "singular",
            RunStatus::StepLimit { .. } => "step-limit",
        }
    }

    /// True for [`RunStatus::Converged`].
    pub fn is_converged(&self) -> bool {
        matches!(self, RunStatus::Converged)
    }
}

impl std::fmt::Display for RunStatus {
    /// A sentence naming the cause, e.g. `stopped at the upper limit of joint 3 (panda_joint4)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunStatus::Converged => f.write_str("converged"),
            RunStatus::Unreachable {
                position_error,
                orientation_error,
            } => write!(
                f,
                "unreachable: no configuration within the joint limits reaches the target \
                 (best IK attempt {position_error:.3e} m, {orientation_error:.3e} rad away)"
            ),
            RunStatus::JointLimit { joint, name, side } => write!(
                f,
                "joint limit: stopped at the {side} limit of joint {joint} ({name}), which blocks the way to the target"
            ),
            RunStatus::Singular {
                smallest_singular_value,
            } => write!(
                f,
                "singularity: stalled where the tracked Jacobian's smallest singular value is {smallest_singular_value:.3e}"
            ),
            RunStatus::StepLimit {
                position_error,
                orientation_error,
            } => write!(
                f,
                "step limit: the target is reachable but was not reached in the steps allowed \
                 ({position_error:.3e} m, {orientation_error:.3e} rad left)"
            ),
        }
    }
}

/// Why a run of `planner` (towards its target) ended at joint positions
/// `q`: [`RunStatus::Converged`] when `converged`, otherwise the cause (see
/// the module doc). Runs IK with restarts (allocates; call it once per run).
///
/// Errors: `q` of the wrong size or not finite.
pub fn diagnose_run(planner: &MpcPlanner, q: &[f64], converged: bool) -> Result<RunStatus> {
    let model = planner.model();
    model.check_joint_positions(q)?;
    if converged {
        return Ok(RunStatus::Converged);
    }
    let weights = planner.options().task_weights;
    let mask: [f64; 6] = std::array::from_fn(|r| {
        if weights.tracking[r] > 0.0 || weights.terminal[r] > 0.0 {
            1.0
        } else {
            0.0
        }
    });
    let target = *planner.target();
    let mut data = Data::new(model);
    let j = jacobian(model, &mut data, q, JacobianFrame::World)?.clone();
    let pose = *data.end_effector_pose();
    // The task's wanted motion y_d - y, and its descent direction J' W (y_d - y).
    let dp = target.translation - pose.translation;
    let dr = rotation_log(&(target.rotation * pose.rotation.transpose()));
    let wanted: [f64; 6] = std::array::from_fn(|r| {
        mask[r]
            * if r < 3 {
                weights.terminal[r] * dp[r]
            } else {
                weights.terminal[r] * dr[r - 3]
            }
    });
    let reachable = match planner.goal_search() {
        GoalSearch::Found => None,
        _ => {
            let mut ik = IkSolver::new(
                model,
                IkOptions {
                    max_restarts: 500,
                    time_budget: None,
                    task_weights: mask,
                    ..IkOptions::default()
                },
            )?;
            let report = ik.solve(&target, q)?;
            (report.status != IkStatus::Converged)
                .then_some((report.position_error, report.orientation_error))
        }
    };
    let bounds = planner.bounds();
    let mut blocking: Option<(usize, BoundSide, f64)> = None;
    for (c, &qc) in q.iter().enumerate() {
        let descent: f64 = (0..6).map(|r| j[(r, c)] * wanted[r]).sum();
        let side = if qc >= bounds.upper[c] - AT_LIMIT_TOLERANCE && descent > 0.0 {
            BoundSide::Upper
        } else if qc <= bounds.lower[c] + AT_LIMIT_TOLERANCE && descent < 0.0 {
            BoundSide::Lower
        } else {
            continue;
        };
        if blocking.is_none_or(|(_, _, d)| descent.abs() > d) {
            blocking = Some((c, side, descent.abs()));
        }
    }
    if let Some((joint, side, _)) = blocking {
        return Ok(RunStatus::JointLimit {
            joint,
            name: model.joints()[joint].name.clone(),
            side,
        });
    }
    if let Some((position_error, orientation_error)) = reachable {
        return Ok(RunStatus::Unreachable {
            position_error,
            orientation_error,
        });
    }
    let rows: Vec<usize> = (0..6).filter(|&r| mask[r] > 0.0).collect();
    let tracked = DMatrix::from_fn(rows.len(), q.len(), |r, c| j[(rows[r], c)]);
    let smallest = tracked
        .singular_values()
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    if smallest < SINGULAR_VALUE_THRESHOLD {
        return Ok(RunStatus::Singular {
            smallest_singular_value: smallest,
        });
    }
    Ok(RunStatus::StepLimit {
        position_error: dp.norm(),
        orientation_error: dr.norm(),
    })
}
