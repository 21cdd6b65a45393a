//! Inverse kinematics from Python: one pose (`Robot.ik`, a result object
//! with a status) or many (`Robot.ik_batch`, arrays; GIL released).

use std::time::Duration;

use armkit::ik::analytic::{AnalyticOptions, AnalyticRoute, Fit, Redundancy, Representatives};
use armkit::ik::{AutoSolver, IkMethod, IkOptions, IkRoute, IkSolver, IkStatus, SolverName};
use armkit::math::Pose;
use armkit::{Error, Model};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::arrays::{matrix_from_rows, vector};

/// The solver named by `solver=`: the library's [`SolverName`]
/// vocabulary, the names of `armkit ik --solver`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolverChoice {
    /// The library's automatic solver: analytic where the arm's class
    /// allows (spherical wrist, the UR family, 7-DOF arms by their
    /// redundancy parameter), Levenberg-Marquardt otherwise; targets beyond
    /// the reach bound are not attempted.
    Auto,
    /// Every analytic solution ([`AnalyticRoute`], as `armkit ik --solver
    /// analytic`; alias `closed-form`), the nearest exact one returned.
    Analytic,
    /// A numeric method.
    Numeric(IkMethod),
}

impl SolverChoice {
    /// A name of [`SolverName`] (or an alias): `"auto"`, `"analytic"`,
    /// `"lm"`, `"nr"`, `"dls"`, `"sri"`.
    pub fn parse(name: &str) -> armkit::Result<SolverChoice> {
        Ok(match SolverName::parse(name)? {
            SolverName::Auto => SolverChoice::Auto,
            SolverName::Analytic => SolverChoice::Analytic,
            numeric => SolverChoice::Numeric(numeric.method()),
        })
    }
}

/// The options of `Robot.ik` and `Robot.ik_batch` (seconds for the budget).
#[derive(Clone, Debug, PartialEq)]
pub struct IkArguments {
    pub solver: SolverChoice,
    pub options: IkOptions,
}

impl IkArguments {
    /// Builds and validates the options (the library's messages).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        solver: &str,
        position_tolerance: f64,
        orientation_tolerance: f64,
        max_iterations: usize,
        max_restarts: usize,
        time_budget: Option<f64>,
        seed: u64,
        task_weights: Option<Vec<f64>>,
    ) -> armkit::Result<Self> {
        let solver = SolverChoice::parse(solver)?;
        let method = match solver {
            SolverChoice::Numeric(method) => method,
            _ => IkMethod::default(),
        };
        let time_budget = match time_budget {
            None => None,
            Some(seconds) => {
                armkit::error::check_positive("time_budget", seconds)?;
                Some(Duration::try_from_secs_f64(seconds).map_err(|e| {
                    Error::invalid_argument("time_budget", format!("{e}, got {seconds} s"))
                })?)
            }
        };
        let task_weights = match task_weights {
            None => [1.0; 6],
            Some(w) => {
                <[f64; 6]>::try_from(w.as_slice()).map_err(|_| Error::DimensionMismatch {
                    what: "task_weights",
                    expected: 6,
                    got: w.len(),
                })?
            }
        };
        let options = IkOptions {
            method,
            position_tolerance,
            orientation_tolerance,
            max_iterations,
            max_restarts,
            time_budget,
            seed,
            task_weights,
            ..IkOptions::default()
        };
        options.validate()?;
        Ok(IkArguments { solver, options })
    }
}

/// One solve's outcome, whichever solver ran.
pub struct Outcome {
    pub status: IkStatus,
    pub solver: &'static str,
    pub q: Vec<f64>,
    pub position_error: f64,
    pub orientation_error: f64,
    pub iterations: usize,
    pub restarts: usize,
    pub elapsed: Duration,
    pub solutions: Vec<Vec<f64>>,
}

/// A solver for one thread: the numeric solver and, where chosen, the
/// automatic one; the analytic route of the arm, if it has one, lists every
/// solution.
#[derive(Clone)]
pub struct IkEngine {
    numeric: IkSolver,
    auto: Option<AutoSolver>,
    /// The analytic route (a 6-joint arm's, built once; a 7-joint arm's is
    /// built per solve, at the answer's redundancy parameter).
    analytic: Option<AnalyticRoute>,
    choice: SolverChoice,
}

/// The analytic route's options in `Robot.ik`: each distinct solution once.
fn analytic_options() -> AnalyticOptions {
    AnalyticOptions {
        representatives: Representatives::Nearest,
        ..AnalyticOptions::default()
    }
}

impl IkEngine {
    /// Errors: invalid options, or `analytic` for a robot without analytic
    /// solver (the message names its class).
    pub fn new(model: &Model, arguments: &IkArguments) -> armkit::Result<Self> {
        let start = model.neutral_configuration();
        let analytic = match arguments.solver {
            SolverChoice::Analytic => Some(AnalyticRoute::new(
                model,
                analytic_options(),
                Redundancy::default(),
                &start,
            )?),
            SolverChoice::Auto => {
                AnalyticRoute::new(model, analytic_options(), Redundancy::default(), &start).ok()
            }
            SolverChoice::Numeric(_) => None,
        };
        let auto = match arguments.solver {
            SolverChoice::Auto => Some(AutoSolver::new(model, arguments.options)?),
            _ => None,
        };
        Ok(IkEngine {
            numeric: IkSolver::new(model, arguments.options)?,
            auto,
            analytic,
            choice: arguments.solver,
        })
    }

    /// The exact analytic solutions for `target`, nearest `start` first,
    /// with a 7-joint arm's redundancy parameter read from `at` (empty
    /// when the arm has no analytic route).
    fn exact_solutions(
        &mut self,
        target: &Pose,
        start: &[f64],
        at: &[f64],
    ) -> armkit::Result<Vec<Vec<f64>>> {
        let model = self.numeric.model();
        if model.dof() == 7 && self.analytic.is_some() {
            self.analytic = Some(AnalyticRoute::new(
                model,
                analytic_options(),
                Redundancy::default(),
                at,
            )?);
        }
        let Some(route) = self.analytic.as_mut() else {
            return Ok(Vec::new());
        };
        Ok(route
            .solve(target, start, None)?
            .into_iter()
            .filter(|s| s.fit == Fit::Exact)
            .map(|s| s.q)
            .collect())
    }

    /// Solves for `target` (world frame) from `start`.
    pub fn solve(&mut self, target: &Pose, start: &[f64]) -> armkit::Result<Outcome> {
        // The start is checked as every other solver checks it (the same
        // message, `joint_positions: ...`).
        self.numeric.model().check_joint_positions(start)?;
        if let Some(auto) = &mut self.auto {
            let found = auto.solve(target, start)?;
            let report = found.report;
            let solutions = match (report.converged(), found.route) {
                (true, IkRoute::Analytic | IkRoute::AnalyticSweep) => {
                    self.exact_solutions(target, start, &report.q)?
                }
                (true, _) => vec![report.q.clone()],
                (false, _) => Vec::new(),
            };
            return Ok(Outcome {
                status: report.status,
                solver: match found.route {
                    IkRoute::Numeric => self.numeric.options().method.short_name(),
                    route => route.as_str(),
                },
                q: report.q,
                position_error: report.position_error,
                orientation_error: report.orientation_error,
                iterations: report.iterations,
                restarts: report.restarts,
                elapsed: report.elapsed,
                solutions,
            });
        }
        if self.choice == SolverChoice::Analytic {
            let began = std::time::Instant::now();
            let solutions = self.exact_solutions(target, start, start)?;
            let Some(best) = solutions.first().cloned() else {
                // No exact solution within the limits: the numeric best
                // effort, never reported as converged.
                let mut outcome = self.numeric_solve(target, start)?;
                outcome.status = IkStatus::NotConverged;
                outcome.solutions.clear();
                return Ok(outcome);
            };
            let mut data = armkit::kinematics::Data::new(self.numeric.model());
            let pose =
                armkit::kinematics::forward_kinematics(self.numeric.model(), &mut data, &best)?;
            let e = armkit::ik::pose_error(target, pose);
            return Ok(Outcome {
                status: IkStatus::Converged,
                solver: "analytic",
                q: best,
                position_error: e.fixed_rows::<3>(0).norm(),
                orientation_error: e.fixed_rows::<3>(3).norm(),
                iterations: 0,
                restarts: 0,
                elapsed: began.elapsed(),
                solutions,
            });
        }
        self.numeric_solve(target, start)
    }

    fn numeric_solve(&mut self, target: &Pose, start: &[f64]) -> armkit::Result<Outcome> {
        let report = self.numeric.solve(target, start)?;
        let solutions = if report.converged() {
            vec![report.q.clone()]
        } else {
            Vec::new()
        };
        Ok(Outcome {
            status: report.status,
            solver: self.numeric.options().method.short_name(),
            q: report.q,
            position_error: report.position_error,
            orientation_error: report.orientation_error,
            iterations: report.iterations,
            restarts: report.restarts,
            elapsed: report.elapsed,
            solutions,
        })
    }
}

/// The result of `Robot.ik`.
///
/// `status` is `"converged"` (both errors within tolerance) or
/// `"not_converged"` (`q` is the best effort, within the joint limits).
#[pyclass(frozen, module = "armkit", name = "IkResult")]
pub struct IkResult {
    /// `"converged"` or `"not_converged"`.
    #[pyo3(get)]
    status: &'static str,
    /// `status == "converged"`.
    #[pyo3(get)]
    converged: bool,
    /// The solver that produced `q`: `"analytic"`, `"analytic_sweep"`,
    /// `"unreachable"` (auto: beyond the reach bound, not attempted),
    /// `"lm"`, `"nr"`, `"dls"` or `"sri"`.
    #[pyo3(get)]
    solver: &'static str,
    /// Joint positions (rad or m), shape (dof,), within the joint limits.
    #[pyo3(get)]
    q: Py<PyArray1<f64>>,
    /// Position error at `q`, m.
    #[pyo3(get)]
    position_error: f64,
    /// Orientation error at `q`, rad.
    #[pyo3(get)]
    orientation_error: f64,
    /// Iterations over all attempts (0 for the analytic solver).
    #[pyo3(get)]
    iterations: usize,
    /// Random restarts used.
    #[pyo3(get)]
    restarts: usize,
    /// Wall-clock time of the solve, s.
    #[pyo3(get)]
    elapsed: f64,
    /// Every solution found, shape (k, dof): where the analytic solver
    /// answered (`analytic`, or `auto` on its analytic route), every exact
    /// analytic solution within the limits, each distinct one once, nearest
    /// the start first (a 7-joint arm's at the answer's redundancy
    /// parameter); for a numeric solver the converged `q` (k = 1) or none
    /// (k = 0).
    #[pyo3(get)]
    solutions: Py<PyArray2<f64>>,
}

impl IkResult {
    pub fn new(py: Python<'_>, outcome: Outcome, dof: usize) -> PyResult<Self> {
        Ok(IkResult {
            status: outcome.status.as_str(),
            converged: outcome.status == IkStatus::Converged,
            solver: outcome.solver,
            q: vector(py, &outcome.q).unbind(),
            position_error: outcome.position_error,
            orientation_error: outcome.orientation_error,
            iterations: outcome.iterations,
            restarts: outcome.restarts,
            elapsed: outcome.elapsed.as_secs_f64(),
            solutions: matrix_from_rows(py, &outcome.solutions, dof)?.unbind(),
        })
    }
}

#[pymethods]
impl IkResult {
    fn __repr__(&self) -> String {
        format!(
            "IkResult(status='{}', solver='{}', position_error={:.3e}, orientation_error={:.3e})",
            self.status, self.solver, self.position_error, self.orientation_error
        )
    }
}
