//! Every analytic IK solution from Python (`Robot.ik_solutions`) and the
//! arm's analytic class (`Robot.arm_class`): the library's
//! [`armkit::ik::analytic`] solver, chosen as `armkit ik --solver analytic`
//! chooses it ([`AnalyticRoute`]: seed 002's 4-DOF arm by its closed form).

use armkit::ik::analytic::{
    self, AnalyticOptions, AnalyticRoute, Fit, JointNumbering, Redundancy, Representatives,
};
use armkit::ik::closed_form::ClosedFormSolution;
use armkit::math::Pose;
use armkit::{Error, Model};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::arrays::{matrix_from_rows, vector};
use crate::errors::OrRaise;

/// The arguments of `Robot.ik_solutions`, checked (the errors name the
/// Python argument).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolutionsArguments {
    /// `fixed_joint=` (0-based) and `parameter=`.
    pub redundancy: Redundancy,
    /// `sweep=`: how many parameter values (None: one).
    pub sweep: Option<usize>,
    /// `representatives=`: `"nearest"` (each distinct solution once) or
    /// `"every"` (every 2 pi multiple within the limits), as the CLI's
    /// `--representatives`.
    pub representatives: Representatives,
}

impl SolutionsArguments {
    /// Errors: an unknown `search` or `representatives`, a negative
    /// `fixed_joint`, `sweep` < 1.
    pub fn new(
        search: &str,
        fixed_joint: Option<i64>,
        parameter: Option<f64>,
        sweep: Option<i64>,
        representatives: &str,
    ) -> armkit::Result<Self> {
        let representatives = match representatives {
            "nearest" => Representatives::Nearest,
            "every" => Representatives::Every,
            other => {
                return Err(Error::invalid_argument(
                    "representatives",
                    format!("unknown value `{other}`; expected \"nearest\" or \"every\""),
                ))
            }
        };
        match search {
            "elimination" => {}
            "1d" | "2d" => {
                return Err(Error::invalid_argument(
                    "search",
                    format!("\"{search}\" is retired (the searches are gone: every 6R arm without a closed form is solved by elimination, the default; arms elimination does not take need a numeric solver, e.g. robot.ik(T, solver=\"lm\")); expected \"elimination\""),
                ))
            }
            other => {
                return Err(Error::invalid_argument(
                    "search",
                    format!("unknown value `{other}`; expected \"elimination\""),
                ))
            }
        }
        let fixed_joint = match fixed_joint {
            None => None,
            Some(joint) => Some(usize::try_from(joint).map_err(|_| {
                Error::invalid_argument(
                    "fixed_joint",
                    format!("must be 0 to 6 (0-based), got {joint}"),
                )
            })?),
        };
        let sweep = match sweep {
            None => None,
            Some(n) if n >= 1 => Some(n as usize),
            Some(n) => {
                return Err(Error::invalid_argument(
                    "sweep",
                    format!("must be >= 1, got {n}"),
                ))
            }
        };
        Ok(SolutionsArguments {
            redundancy: Redundancy {
                fixed_joint,
                value: parameter,
            },
            sweep,
            representatives,
        })
    }
}

/// `Robot.arm_class()`: the class name and its description (the `armkit
/// ik --explain` class; a 7-joint arm's with the held joint named, 0-based).
pub fn arm_class(model: &Model) -> armkit::Result<(&'static str, String)> {
    let (class, held, _) = analytic::route_class(model, None)?;
    let mut description = class.description().to_string();
    if let Some(joint) = held {
        description.push_str(&format!(
            " (with joint {joint} held, 0-based: the route of ik_solutions)"
        ));
    }
    Ok((class.as_str(), description))
}

/// The result of `Robot.ik_solutions`: every analytic solution within the
/// joint limits, exact ones first, each group nearest the start first.
#[pyclass(frozen, module = "armkit", name = "IkSolutions")]
pub struct IkSolutions {
    /// Joint positions (rad or m), shape (k, dof), nearest `q0` first.
    #[pyo3(get)]
    q: Py<PyArray2<f64>>,
    /// Shape (k,): True where the solution reproduces the pose within 1e-10
    /// m and rad (fit `"exact"`), False for a least-squares one.
    #[pyo3(get)]
    exact: Py<PyArray1<bool>>,
    /// Per solution `"exact"` or `"approximate"` (the library's `Fit`).
    #[pyo3(get)]
    fits: Vec<&'static str>,
    /// Position error of each solution, m, shape (k,).
    #[pyo3(get)]
    position_error: Py<PyArray1<f64>>,
    /// Orientation error of each solution, rad, shape (k,).
    #[pyo3(get)]
    orientation_error: Py<PyArray1<f64>>,
    /// The arm's class name (e.g. `"three_parallel_2_3_4_intersecting_5_6"`).
    #[pyo3(get)]
    arm_class: &'static str,
    /// The method: the class's description and the redundancy parameter.
    #[pyo3(get)]
    method: String,
}

impl IkSolutions {
    fn new(
        py: Python<'_>,
        found: &[ClosedFormSolution],
        arm_class: &'static str,
        method: String,
        dof: usize,
    ) -> PyResult<Self> {
        let rows: Vec<Vec<f64>> = found.iter().map(|s| s.q.clone()).collect();
        let exact: Vec<bool> = found.iter().map(|s| s.fit == Fit::Exact).collect();
        let position: Vec<f64> = found.iter().map(|s| s.position_error).collect();
        let orientation: Vec<f64> = found.iter().map(|s| s.orientation_error).collect();
        Ok(IkSolutions {
            q: matrix_from_rows(py, &rows, dof)?.unbind(),
            exact: PyArray1::from_slice(py, &exact).unbind(),
            fits: found.iter().map(|s| s.fit.as_str()).collect(),
            position_error: vector(py, &position).unbind(),
            orientation_error: vector(py, &orientation).unbind(),
            arm_class,
            method,
        })
    }
}

#[pymethods]
impl IkSolutions {
    /// The number of solutions.
    fn __len__(&self) -> usize {
        self.fits.len()
    }

    fn __repr__(&self) -> String {
        let exact = self.fits.iter().filter(|f| **f == "exact").count();
        format!(
            "IkSolutions({} solution(s), {exact} exact, arm_class='{}')",
            self.fits.len(),
            self.arm_class
        )
    }
}

/// `Robot.ik_solutions` after argument parsing: solves with the GIL released.
pub fn ik_solutions(
    py: Python<'_>,
    model: &Model,
    arguments: &SolutionsArguments,
    target: &Pose,
    start: &[f64],
) -> PyResult<IkSolutions> {
    let (found, class, method) = py
        .detach(|| {
            let options = AnalyticOptions {
                representatives: arguments.representatives,
                ..AnalyticOptions::default()
            };
            let mut route = AnalyticRoute::new(model, options, arguments.redundancy, start)?;
            let found = route.solve(target, start, arguments.sweep)?;
            Ok::<_, armkit::Error>((
                found,
                route.class_name(),
                route.method(JointNumbering::ZeroBased),
            ))
        })
        .or_raise()?;
    IkSolutions::new(py, &found, class, method, model.dof())
}
