//! The 3-D view from Python: `armkit.view.animate(robot, t, Q, path=None)`
//! and `robot.show(q)` (the Python side, `python/armkit/view.py`, wraps the
//! page in an object Jupyter displays). The page is `armkit view`'s: links
//! placed by armkit's FK, three.js inlined, offline.

use numpy::PyUntypedArrayMethods;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::arrays::{copy_values, float_array, shape_error};
use crate::robot::Robot;

/// Rows of a 2-D argument: `(N, width)`, or one row for a 1-D one.
fn rows(obj: &Bound<'_, PyAny>, what: &str, width: usize) -> PyResult<Vec<Vec<f64>>> {
    let array = float_array(obj, what)?;
    let shape = array.shape().to_vec();
    let mut values = Vec::new();
    copy_values(&array, &mut values);
    match shape.as_slice() {
        [w] if *w == width => Ok(vec![values]),
        [_, w] if *w == width => Ok(values.chunks_exact(width).map(<[f64]>::to_vec).collect()),
        _ => Err(shape_error(
            what,
            &format!("(N, {width}) or ({width},)"),
            &shape,
        )),
    }
}

/// The HTML page of `robot` moving through the configurations `q` (shape
/// (N, dof)) at the times `t` (shape (N,), s, non-decreasing); `path`, if
/// given, is drawn as the path line instead of the end effector's (shape
/// (M, 3), world frame, m).
#[pyfunction]
#[pyo3(name = "_view_page", signature = (robot, t, q, path=None))]
pub fn view_page(
    robot: &Robot,
    t: &Bound<'_, PyAny>,
    q: &Bound<'_, PyAny>,
    path: Option<&Bound<'_, PyAny>>,
) -> PyResult<String> {
    let model = &robot.model;
    let t = float_array(t, "t")?;
    if t.ndim() != 1 {
        return Err(shape_error("t", "(N,)", t.shape()));
    }
    let mut times = Vec::new();
    copy_values(&t, &mut times);
    let configurations = rows(q, "Q", model.dof())?;
    if times.len() != configurations.len() {
        return Err(PyValueError::new_err(format!(
            "t has {} times but Q has {} rows: give one time per configuration",
            times.len(),
            configurations.len()
        )));
    }
    if times.is_empty()
        || times.iter().any(|v| !v.is_finite())
        || times.windows(2).any(|w| w[1] < w[0])
    {
        return Err(PyValueError::new_err(
            "t: expected finite, non-decreasing times (at least one)",
        ));
    }
    for (k, q) in configurations.iter().enumerate() {
        model
            .check_joint_positions(q)
            .map_err(|e| PyValueError::new_err(format!("Q row {k}: {e}")))?;
    }
    let mut scene = match &robot.urdf {
        Some(source) => armkit_view::urdf_scene(source, model, &times, &configurations)
            .map_err(PyValueError::new_err)?,
        None => armkit_view::chain_scene(model, &times, &configurations)
            .map_err(crate::errors::value_error)?,
    };
    if let Some(path) = path {
        scene.path = rows(path, "path", 3)?
            .into_iter()
            .map(|p| [p[0], p[1], p[2]])
            .collect();
        scene.path_flags = vec![false; scene.path.len()];
    }
    Ok(armkit_view::standalone_page(&scene))
}
