//! Inverse kinematics: numeric solvers with joint limits and an honest
//! status, and closed-form solvers for the seed arms.
//!
//! * [`IkSolver`]: one interface over four numeric methods ([`IkMethod`]):
//!   Newton-Raphson with the pseudo-inverse Jacobian (seed 004, Fig 2),
//!   damped least squares with Nakamura's adaptive damping,
//!   Levenberg-Marquardt with Sugihara's damping (the default, and the
//!   fastest), and Chiaverini's singularity-robust inverse with numerical
//!   filtering. All of them drive the pose error of seed 004 (eqs 20-28,
//!   [`pose_error`]) to zero, keep every iterate within the joint limits
//!   (each step is projected onto the limits; continuous joints wrap), restart
//!   from seeded random configurations when an attempt stalls, and return an
//!   [`IkReport`] whose [`IkStatus`] is `Converged` only when both errors are
//!   within tolerance. Non-convergence is a status with the best iterate, not
//!   an error; `Err` is for bad input only.
//! * [`analytic`]: every solution of 6-joint arms of the classes solvable by
//!   subproblem decomposition (spherical wrist at either end, the UR family)
//!   and of 7-DOF arms at a redundancy parameter; [`AutoSolver`] takes it
//!   where the class allows and the numeric solver otherwise. Targets beyond
//!   the [`ReachBound`] are not attempted.
//! * [`closed_form`]: every solution of PUMA-type 6R arms with a spherical
//!   wrist (`puma560`, `space6r`; Pieper) and of seed 002's 4-DOF arm
//!   (`arm4`), each verified by forward kinematics.
//! * The velocity-level building blocks, reusable on their own:
//!   [`damped_least_squares_step`], [`singularity_robust_step`],
//!   [`damped_pseudo_inverse`], [`singularity_robust_inverse`].
//!
//! Conventions: poses in the world frame (metres); joint positions in rad
//! or m; the pose error and Jacobian rows are `[vx, vy, vz, wx, wy, wz]`.
//!
//! ```
//! use armkit::ik::{IkOptions, IkSolver, IkStatus};
//! use armkit::kinematics::{forward_kinematics, Data};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let mut data = Data::new(&model);
//! let goal = *forward_kinematics(&model, &mut data, &[0.3, -1.2, 1.4, -0.5, 1.2, 0.4]).unwrap();
//! let mut solver = IkSolver::new(&model, IkOptions::default()).unwrap();
//! let report = solver.solve(&goal, &model.neutral_configuration()).unwrap();
//! assert_eq!(report.status, IkStatus::Converged);
//! assert!(report.position_error <= 1e-6 && report.orientation_error <= 1e-6);
//! model.check_limits(&report.q).unwrap();
//! let reached = forward_kinematics(&model, &mut data, &report.q).unwrap();
//! assert!((reached.translation - goal.translation).norm() <= 1e-6);
//! ```

pub mod analytic;
mod auto;
pub mod closed_form;
mod damping;
mod kernel;
mod numeric;
mod pose_error;
mod protocol;
mod reach;
mod solver_name;
mod steps;

use std::time::Duration;

pub use crate::math::rotation_log;
pub use auto::{AutoReport, AutoSolver, IkRoute, NEAREST_WINDOW, SWEEP_VALUES};
pub use damping::{ChiaveriniFilter, DampedReciprocal, LmDamping, NakamuraDamping};
pub use numeric::IkSolver;
pub use pose_error::{masked_error_norms, orientation_error, pose_error};
pub use protocol::{benchmark_targets, random_configuration};
pub use reach::{ReachBound, REACH_MARGIN};
pub use solver_name::{SolverName, SOLVER_ALIASES};
pub use steps::{
    damped_least_squares_step, damped_pseudo_inverse, separated_damped_reciprocal_step,
    singularity_robust_inverse, singularity_robust_step,
};

use crate::error::{check_positive, Error, Result};

/// The numeric method an [`IkSolver`] iterates with, and its parameters.
///
/// Each iteration solves the linearized problem `J dq = e` (`J` the
/// world-frame geometric Jacobian, `e` the weighted pose error) in the least
/// squares sense, differing in how the step is regularized near
/// singularities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IkMethod {
    /// Newton-Raphson (seed 004, Fig 2): `dq = J+ e`, the plain
    /// (pseudo-)inverse; every step is taken. Fast near a solution, erratic
    /// near singularities. If `J J'` is numerically singular a damping of
    /// `1e-12` of its trace is added so that the step stays finite.
    NewtonRaphson,
    /// Damped least squares `dq = J' (J J' + lambda^2 I)^-1 e` with
    /// Nakamura's adaptive damping (grows as the manipulability falls below a
    /// threshold); every step is taken.
    DampedLeastSquares(NakamuraDamping),
    /// Levenberg-Marquardt with Sugihara's damping `lambda = E + w_N`
    /// (`E = e' W e / 2`): a step is taken only if it lowers `E`, otherwise
    /// the damping grows. The default and the fastest.
    LevenbergMarquardt(LmDamping),
    /// Chiaverini's singularity-robust inverse: damped least squares on the
    /// smallest singular value only, with a variable damping, plus a small
    /// numerical filter on all of them; every step is taken.
    SingularityRobust(ChiaveriniFilter),
}

impl Default for IkMethod {
    fn default() -> Self {
        IkMethod::LevenbergMarquardt(LmDamping::default())
    }
}

impl IkMethod {
    /// Short name: `nr`, `dls`, `lm` or `sri` (as the CLI's `--solver`).
    pub fn short_name(&self) -> &'static str {
        match self {
            IkMethod::NewtonRaphson => "nr",
            IkMethod::DampedLeastSquares(_) => "dls",
            IkMethod::LevenbergMarquardt(_) => "lm",
            IkMethod::SingularityRobust(_) => "sri",
        }
    }

    /// The method with default parameters for a short name (`nr`, `dls`,
    /// `lm`, `sri`, case-insensitive).
    pub fn from_short_name(name: &str) -> Result<IkMethod> {
        match name.to_ascii_lowercase().as_str() {
            "nr" => Ok(IkMethod::NewtonRaphson),
            "dls" => Ok(IkMethod::DampedLeastSquares(NakamuraDamping::default())),
            "lm" => Ok(IkMethod::LevenbergMarquardt(LmDamping::default())),
            "sri" => Ok(IkMethod::SingularityRobust(ChiaveriniFilter::default())),
            _ => Err(Error::invalid_argument(
                "method",
                format!("unknown IK method `{name}`; expected nr, dls, lm or sri"),
            )),
        }
    }

    fn validate(&self) -> Result<()> {
        match self {
            IkMethod::NewtonRaphson => Ok(()),
            IkMethod::DampedLeastSquares(p) => p.validate(),
            IkMethod::LevenbergMarquardt(p) => p.validate(),
            IkMethod::SingularityRobust(p) => p.validate(),
        }
    }
}

/// Which converged solution a solve returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IkSelection {
    /// The first one found. The first attempt starts from the given start
    /// configuration, so when it converges the answer is the one the start
    /// leads to (continuity); restarts are tried only if it does not.
    First,
    /// Keep restarting until `solutions` converged solutions are found (or
    /// the budget runs out) and return the one nearest the start (Euclidean
    /// distance in joint space), like TRAC-IK's `Distance` mode.
    Nearest {
        /// How many converged solutions to compare (>= 1).
        solutions: usize,
    },
}

/// How a redundant robot (more joints than constrained task components)
/// uses its spare freedom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Redundancy {
    /// Every step is the (damped) minimum-norm one: the joints move no more
    /// than the task needs, so the spare freedom stays where the start put it.
    MinimumNorm,
    /// After convergence, up to `iterations` extra steps move the joints
    /// toward the start within the Jacobian's null space
    /// (`dq = J+ e + gain (I - J+ J)(q_start - q)`); the answer is the
    /// iterate nearest the start among those that meet the tolerances.
    PullToStart {
        /// Fraction of the remaining distance to the start removed per step, in (0, 1].
        gain: f64,
        /// Maximum number of extra steps.
        iterations: usize,
    },
}

/// Options of an [`IkSolver`]. Defaults: Levenberg-Marquardt, tolerances
/// 1e-6 m and 1e-6 rad, 50 iterations per attempt, up to 1000 seeded random
/// restarts within a 5 ms budget, seed 0, all six task components weighted 1,
/// first solution found, minimum-norm redundancy resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkOptions {
    /// The numeric method and its parameters.
    pub method: IkMethod,
    /// Largest accepted position error, m (> 0): Euclidean norm of the
    /// active position components of `p_goal - p`.
    pub position_tolerance: f64,
    /// Largest accepted orientation error, rad (> 0): norm of the active
    /// components of the rotation vector of `R_goal R'`.
    pub orientation_tolerance: f64,
    /// Iterations per attempt (>= 1). An attempt also ends early when it
    /// stalls: the attempt from the start after 5 iterations in a row that
    /// did not lower its best objective by 10 %, a random restart after 4
    /// that did not lower it by 30 % (a fresh restart is cheaper than a slow
    /// one; the start's own solution is worth more patience).
    pub max_iterations: usize,
    /// Random restarts after the first attempt (0: only the start).
    pub max_restarts: usize,
    /// Wall-clock budget per solve; `None` for none. The result is a
    /// deterministic function of the inputs and `seed` unless this budget
    /// cuts the search short.
    pub time_budget: Option<Duration>,
    /// Seed of the restart generator (ChaCha8): same inputs and seed, same answer.
    pub seed: u64,
    /// Weights of the task components `[x, y, z, rx, ry, rz]` (>= 0, not
    /// all zero; world axes). A zero masks the component (e.g.
    /// `[1, 1, 1, 0, 0, 0]`: position only); masked components count in
    /// neither the objective nor the reported errors.
    pub task_weights: [f64; 6],
    /// Which converged solution to return.
    pub selection: IkSelection,
    /// Use of the spare freedom of redundant robots.
    pub redundancy: Redundancy,
}

impl Default for IkOptions {
    fn default() -> Self {
        IkOptions {
            method: IkMethod::default(),
            position_tolerance: 1e-6,
            orientation_tolerance: 1e-6,
            max_iterations: 50,
            max_restarts: 1000,
            time_budget: Some(Duration::from_millis(5)),
            seed: 0,
            task_weights: [1.0; 6],
            selection: IkSelection::First,
            redundancy: Redundancy::MinimumNorm,
        }
    }
}

impl IkOptions {
    /// Checks every field; the error names the field and what was expected.
    pub fn validate(&self) -> Result<()> {
        self.method.validate()?;
        for (name, value) in [
            ("position_tolerance", self.position_tolerance),
            ("orientation_tolerance", self.orientation_tolerance),
        ] {
            check_positive(name, value)?;
        }
        if self.max_iterations == 0 {
            return Err(Error::invalid_argument("max_iterations", "must be >= 1"));
        }
        if let Some(budget) = self.time_budget {
            if budget.is_zero() {
                return Err(Error::invalid_argument(
                    "time_budget",
                    "must be > 0 (use None for no budget)",
                ));
            }
        }
        if self
            .task_weights
            .iter()
            .any(|w| !(w.is_finite() && *w >= 0.0))
        {
            return Err(Error::invalid_argument(
                "task_weights",
                format!("must be finite and >= 0, got {:?}", self.task_weights),
            ));
        }
        if self.task_weights.iter().all(|w| *w == 0.0) {
            return Err(Error::invalid_argument(
                "task_weights",
                "at least one task component must have a weight > 0",
            ));
        }
        if let IkSelection::Nearest { solutions: 0 } = self.selection {
            return Err(Error::invalid_argument(
                "selection",
                "Nearest needs solutions >= 1",
            ));
        }
        if let Redundancy::PullToStart { gain, .. } = self.redundancy {
            if !(gain.is_finite() && gain > 0.0 && gain <= 1.0) {
                return Err(Error::invalid_argument(
                    "redundancy",
                    format!("PullToStart gain must be in (0, 1], got {gain}"),
                ));
            }
        }
        Ok(())
    }

    /// These options with another method.
    pub fn with_method(mut self, method: IkMethod) -> Self {
        self.method = method;
        self
    }

    /// These options with another seed.
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
}

/// Outcome of a solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IkStatus {
    /// Both errors are within their tolerances at the returned `q`.
    Converged,
    /// No attempt met the tolerances within the budget; the returned `q` is
    /// the best iterate seen (smallest weighted error), within the limits.
    NotConverged,
}

impl IkStatus {
    /// `"converged"` or `"not_converged"` (the CLI's JSON).
    pub fn as_str(&self) -> &'static str {
        match self {
            IkStatus::Converged => "converged",
            IkStatus::NotConverged => "not_converged",
        }
    }
}

impl std::fmt::Display for IkStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What a solve found.
#[derive(Clone, Debug, PartialEq)]
pub struct IkReport {
    /// Converged, or not with the best iterate.
    pub status: IkStatus,
    /// Joint positions (rad or m), always within the joint limits; for
    /// rotational joints the 2 pi multiple nearest the start is chosen.
    pub q: Vec<f64>,
    /// Position error at `q`, m (norm of the active components of `p_goal - p`).
    pub position_error: f64,
    /// Orientation error at `q`, rad (norm of the active components of the
    /// rotation vector of `R_goal R'`).
    pub orientation_error: f64,
    /// Iterations over all attempts.
    pub iterations: usize,
    /// Random restarts used (0 when the first attempt, from the start, decided).
    pub restarts: usize,
    /// Wall-clock time of the solve.
    pub elapsed: Duration,
}

impl IkReport {
    /// True when the status is [`IkStatus::Converged`].
    pub fn converged(&self) -> bool {
        self.status == IkStatus::Converged
    }
}
