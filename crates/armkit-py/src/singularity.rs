//! Singularity detection from Python (`armkit.singularity`).

use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::singularity::{classify as library_classify, jacobian_determinant, ClassifyOptions};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{vector, vector_argument};
use crate::errors::OrRaise;
use crate::robot::Robot;

/// The kinds of singularity at `q` (seed 004; wrist, elbow, shoulder for a
/// 6R arm with a spherical wrist). Returns a dict: `kinds` (list of
/// `"wrist"`, `"elbow"`, `"shoulder"`, `"unclassified"`; empty when
/// regular), `singular` (bool), `rank`, `singular_values` (largest first,
/// of the world-frame Jacobian), `determinant` (of a square Jacobian, else
/// None). `tolerance`: relative singular-value threshold.
#[pyfunction]
#[pyo3(signature = (robot, q, tolerance=1e-6))]
pub fn classify<'py>(
    py: Python<'py>,
    robot: &Robot,
    q: &Bound<'py, PyAny>,
    tolerance: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let model = &robot.model;
    let q = vector_argument(q, "q", model.dof())?;
    let mut data = Data::new(model);
    let found =
        library_classify(model, &mut data, &q, &ClassifyOptions { tolerance }).or_raise()?;
    let out = PyDict::new(py);
    let kinds: Vec<&str> = found.kinds.iter().map(|k| k.as_str()).collect();
    out.set_item("kinds", kinds)?;
    out.set_item("singular", found.is_singular())?;
    out.set_item("rank", found.rank)?;
    out.set_item("singular_values", vector(py, &found.singular_values))?;
    let determinant = if model.dof() == 6 {
        let j = jacobian(model, &mut data, &q, JacobianFrame::World).or_raise()?;
        Some(jacobian_determinant(j))
    } else {
        None
    };
    out.set_item("determinant", determinant)?;
    Ok(out)
}
