//! The goal posture that gets the planner out of the local minima of its
//! linearised task cost ([`super::ReachAid::GoalPosture`]).
//!
//! Seed 000's cost (eq 20) sees the target only through the Jacobian at the
//! current configuration: when a joint limit blocks the direction the
//! linearised task asks for, or the arm passes near a singularity, the
//! planner can settle short of a reachable target. A goal posture `q_g`
//! (a configuration within the limits whose end effector is at the target,
//! found by IK with restarts, nearest to the current configuration) adds a
//! joint-space term to the cost,
//!
//! ```text
//! sum_{i<N} |q(k+i) - q_g|^2_{P}  +  |q(k+N) - q_g|^2_{P_N},
//! q(k+i) = q(k) + T (i v_old + sum_l c(i,l) du(l)),
//! ```
//!
//! with `P = w Q_mean` on the tracking samples and `P_N = w Q_N,mean` on the
//! terminal one (`Q_mean` the mean of the non-zero task weights, so `w`
//! says how much one rad, or one m, of joint error counts against one m, or
//! rad, of task error). The joint limits are a box, so the straight
//! joint-space path to `q_g` never leaves them; both terms vanish at `q_g`,
//! so the term adds no steady-state error; it also fades out near the
//! target ([`GoalPostureOptions::fade_error`]). When the task error stops
//! falling for [`GoalPostureOptions::stall_steps`] steps, the pull is made
//! stronger (the task cost holds the arm in a local minimum against it; a
//! strong enough pull moves it along the straight joint-space path to
//! `q_g`), and a goal posture not found yet is searched again from where
//! the arm is (another IK seed).
//!
//! ```
//! use armkit::mpc::{GoalPostureOptions, MpcOptions, ReachAid};
//! let options = MpcOptions {
//!     reach: ReachAid::GoalPosture(GoalPostureOptions { weight: 0.5, ..GoalPostureOptions::default() }),
//!     ..MpcOptions::default()
//! };
//! options.validate().unwrap();
//! ```

use crate::error::Result;
use crate::ik::{IkOptions, IkSelection, IkSolver, IkStatus};
use crate::math::Pose;
use crate::model::Model;

use super::{GoalPostureOptions, TaskWeights};

/// Largest factor the stalls can put on the pull.
const MAX_ESCALATION: f64 = 1e3;

/// What the last goal-posture search found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GoalSearch {
    /// No search yet for this target.
    Pending,
    /// A goal posture reaching the target within the IK tolerances.
    Found,
    /// IK with restarts found no configuration within the limits reaching
    /// the target: the best had these errors (m, rad).
    NotFound {
        /// Position error of the best IK attempt, m.
        position_error: f64,
        /// Orientation error of the best IK attempt, rad (0 when untracked).
        orientation_error: f64,
    },
}

/// The goal-posture state the planner keeps (allocated at set-up; a search
/// allocates, a step without one does not).
pub(crate) struct GoalPosture {
    pub options: GoalPostureOptions,
    solver: IkSolver,
    /// The goal posture, valid when `search` is `Found`.
    pub posture: Vec<f64>,
    pub search: GoalSearch,
    searches: usize,
    best_error: f64,
    steps_since_progress: usize,
    /// Product of the stall gains so far (1 for a new target).
    escalation: f64,
}

impl GoalPosture {
    pub fn new(model: &Model, options: &GoalPostureOptions, weights: &TaskWeights) -> Result<Self> {
        let mut mask = [0.0; 6];
        for (r, m) in mask.iter_mut().enumerate() {
            if weights.tracking[r] > 0.0 || weights.terminal[r] > 0.0 {
                *m = 1.0;
            }
        }
        let ik = IkOptions {
            max_restarts: options.ik_restarts,
            time_budget: None,
            seed: options.seed,
            task_weights: mask,
            selection: IkSelection::Nearest {
                solutions: options.candidates,
            },
            ..IkOptions::default()
        };
        Ok(GoalPosture {
            options: options.clone(),
            solver: IkSolver::new(model, ik)?,
            posture: vec![0.0; model.dof()],
            search: GoalSearch::Pending,
            searches: 0,
            best_error: f64::INFINITY,
            steps_since_progress: 0,
            escalation: 1.0,
        })
    }

    /// Forgets the goal posture (a new target).
    pub fn reset(&mut self) {
        self.search = GoalSearch::Pending;
        self.searches = 0;
        self.best_error = f64::INFINITY;
        self.steps_since_progress = 0;
        self.escalation = 1.0;
    }

    /// Before a step at `q` with task error `error` (the weighted norm):
    /// searches when none was made for this target, or when progress has
    /// stalled and searches are left. Returns whether a goal posture is in use.
    pub fn update(&mut self, target: &Pose, q: &[f64], error: f64, tolerance: f64) -> Result<bool> {
        if error < 0.99 * self.best_error {
            self.best_error = error;
            self.steps_since_progress = 0;
        } else {
            self.steps_since_progress += 1;
        }
        let stalled = self.steps_since_progress >= self.options.stall_steps && error > tolerance;
        if stalled {
            self.steps_since_progress = 0;
            self.best_error = error;
            if self.search == GoalSearch::Found {
                self.escalation = (self.escalation * self.options.stall_gain).min(MAX_ESCALATION);
            }
        }
        let search = match self.search {
            GoalSearch::Pending => true,
            GoalSearch::NotFound { .. } => stalled && self.searches < self.options.max_searches,
            GoalSearch::Found => false,
        };
        if search {
            self.search_from(target, q)?;
            self.steps_since_progress = 0;
            self.best_error = error;
        }
        Ok(self.search == GoalSearch::Found)
    }

    /// The factor on the posture weights at task error `error`:
    /// `min(1, error / fade_error)`. The pull fades near the target, where
    /// the linearised task cost has no local minimum left to escape, so
    /// that a pose measured apart from the model
    /// ([`super::MpcPlanner::step_with_measured_pose`]), whose goal posture
    /// the model's IK cannot know, still converges.
    pub fn fade(&self, error: f64) -> f64 {
        self.escalation * (error / self.options.fade_error).min(1.0)
    }

    fn search_from(&mut self, target: &Pose, q: &[f64]) -> Result<()> {
        let mut ik = *self.solver.options();
        ik.seed = self.options.seed.wrapping_add(self.searches as u64);
        self.solver.set_options(ik)?;
        self.searches += 1;
        let report = self.solver.solve(target, q)?;
        self.search = if report.status == IkStatus::Converged {
            self.posture.copy_from_slice(&report.q);
            GoalSearch::Found
        } else {
            GoalSearch::NotFound {
                position_error: report.position_error,
                orientation_error: report.orientation_error,
            }
        };
        Ok(())
    }
}
