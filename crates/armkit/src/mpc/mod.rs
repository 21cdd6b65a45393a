//! Model-predictive trajectory planning for (redundant) manipulators, after
//! seed 000 sections 4-5 (Wang, Li, Xi), on a maintained QP solver.
//!
//! Every sample the planner
//! 1. re-linearises: the Jacobian `J(q)` at the measured joint positions (on
//!    the gantry with beam coupling, `J = J0 M` with the slope `m2` of the
//!    deflection at the carriage: seed 000 eqs 8-10, corrected);
//! 2. predicts the task outputs over `N` samples with the incremental model
//!    `x(k+1) = x(k) + T J u(k)`, `u(k) = u(k-1) + du(k)` (eqs 13-14, 21; see
//!    [`prediction`]) from the measured pose (the feedback correction of
//!    sec 4.5: the prediction restarts from the measurement, so a
//!    model error made at the previous sample, reported as
//!    [`StepReport::prediction_error`], does not accumulate);
//! 3. solves the QP of eq 22: tracking cost with weights `Q` (a terminal
//!    weight on step `N`) plus `|dU|^2_R` (the joint priorities of sec 4.4),
//!    subject to the joint velocity limits (eq 17) over the control horizon
//!    and the joint position limits (eq 18) at every one of the `N`
//!    predicted samples (the joint-space prediction `q(k+i) = q(k) + T sum u`
//!    is exact for velocity commands held over a sample, so no limit is
//!    crossed between samples either);
//! 4. applies the first input `u(k)` (receding horizon), after a last check
//!    that clamps it to the velocity limits and to the position limits one
//!    sample ahead (it only acts on solver round-off or failure, and says so).
//!
//! The task is the end-effector pose: position (m, world frame) and
//! orientation as the rotation vector from the current to the target
//! orientation (rad, world axes), each of the 6 coordinates weighted on its
//! own ([`TaskWeights`]): position only, full pose, or any subset.
//!
//! The QP is solved by the dense active-set solver of [`active_set`]
//! (Clarabel as its fallback and reference, OSQP optional; [`qp`]); with
//! [`PriorityMode::Strict`] the joint priorities are strict, one QP per
//! level ([`lexicographic`]). The
//! linearised task cost can hold the arm in a local minimum (a joint limit
//! or a singularity in the way): [`ReachAid::GoalPosture`] (the default)
//! adds a pull toward an IK goal posture ([`GoalPostureOptions`]);
//! [`ReachAid::Off`] is seed 000's plain planner. A run that does not
//! converge gets its cause from [`diagnose_run`] ([`RunStatus`]: unreachable,
//! which joint limit, singularity, step limit).
//!
//! Layout: [`MpcOptions`] and its parts in `options`, the constraints of
//! eqs 17-19 in `constraints`, the planner in `planner`, the goal posture in
//! `reach`, run statuses in `outcome`, solve-time statistics in `timing`;
//! the QP interface in [`qp`], its backends in [`active_set`],
//! `clarabel_qp` and `osqp_qp`, and the one place that builds a backend from
//! its [`qp::QpSolverKind`] in `solver`.
//!
//! Infeasibility is handled, never hidden: a start outside the position
//! limits relaxes those joints' bounds to what they can reach moving back at
//! [`MpcOptions::recovery_speed`] of their speed limit ([`StepStatus::Recovering`]);
//! a QP failure gives a controlled stop ([`StepStatus::Stopped`]);
//! contradictory limits are rejected when the planner is built.
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::math::{Pose, Vector3};
//! use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights};
//!
//! let model = armkit::robots::by_name("panda").unwrap();
//! let mut q = vec![0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
//! let start = *forward_kinematics(&model, &mut Data::new(&model), &q).unwrap();
//! let target = Pose::new(start.rotation, start.translation + Vector3::new(0.05, -0.05, 0.05));
//! let options = MpcOptions {
//!     task_weights: TaskWeights::position_only(10.0, 200.0),
//!     ..MpcOptions::default()
//! };
//! let mut planner = MpcPlanner::new(&model, options).unwrap();
//! planner.set_target(&target).unwrap();
//! for _ in 0..100 {
//!     let report = planner.step(&q).unwrap();
//!     // Integrate the commanded joint velocities over one sample (the plant).
//!     for (qj, uj) in q.iter_mut().zip(&report.velocity) {
//!         *qj += 0.05 * uj;
//!     }
//! }
//! assert!(planner.step(&q).unwrap().position_error < 1e-4);
//! ```

pub mod active_set;
mod clarabel_qp;
mod constraints;
pub mod lexicographic;
mod mismatch;
mod options;
#[cfg(feature = "osqp")]
mod osqp_qp;
mod outcome;
mod planner;
mod plant;
pub mod prediction;
pub mod qp;
mod reach;
pub mod scenario;
mod solver;
mod timing;

pub use clarabel_qp::{ClarabelAccuracy, ClarabelQp};
pub use mismatch::with_link_length_error;
pub use options::{
    GoalPostureOptions, MpcOptions, PriorityMode, ReachAid, TaskWeights, VelocityWeights,
    MAX_SAMPLE_TIME,
};
#[cfg(feature = "osqp")]
pub use osqp_qp::OsqpQp;
pub use outcome::{diagnose_run, RunStatus};
pub use planner::{MpcPlanner, StepReport, StepStatus};
pub use plant::{ActuatorPrecision, Plant, PlantModel};
pub use reach::GoalSearch;
pub use timing::SolveTimes;

/// Default sample time `T`, s. Seed 000 does not print it; 0.05 s (20 Hz
/// planning, a 0.5 s horizon with `N = 10`) makes its weights behave as its
/// figures describe (seed 000's examples, `armkit::study::Seed000Example`).
pub const DEFAULT_SAMPLE_TIME: f64 = 0.05;

/// Commands that cross a limit by more than this (m/s or rad/s, after the
/// QP) are reported as [`StepStatus::Clamped`]; smaller crossings are solver
/// round-off, clamped silently.
pub const CLAMP_REPORT_THRESHOLD: f64 = 1e-6;
