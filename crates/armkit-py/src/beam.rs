//! The simply supported beam of seed 000's gantry from Python: `armkit.Beam`.

use armkit::beam::{PointLoad, SimplySupportedBeam};
use pyo3::prelude::*;

use crate::arrays::{copy_values, float_array, shape_error};
use crate::errors::OrRaise;
use numpy::PyUntypedArrayMethods;

/// A simply supported beam (Euler-Bernoulli): length (m), Young's modulus
/// (Pa), second moment of area (m^4). Deflections are positive downward, m.
#[pyclass(frozen, module = "armkit", name = "Beam")]
pub struct Beam {
    beam: SimplySupportedBeam,
}

/// Point loads from a (K, 2) array of `(position m, force N)`.
fn point_loads(loads: &Bound<'_, PyAny>) -> PyResult<Vec<PointLoad>> {
    let array = float_array(loads, "loads")?;
    let shape = array.shape();
    if shape.len() != 2 || shape[1] != 2 {
        return Err(shape_error("loads", "(K, 2) of (position, force)", shape));
    }
    let mut values = Vec::new();
    copy_values(&array, &mut values);
    Ok(values
        .chunks_exact(2)
        .map(|p| PointLoad::new(p[0], p[1]))
        .collect())
}

#[pymethods]
impl Beam {
    #[new]
    fn new(length: f64, youngs_modulus: f64, second_moment: f64) -> PyResult<Self> {
        Ok(Beam {
            beam: SimplySupportedBeam::new(length, youngs_modulus, second_moment).or_raise()?,
        })
    }

    /// Seed 000's beam (its Table 1).
    #[staticmethod]
    fn seed000() -> Self {
        Beam {
            beam: SimplySupportedBeam::seed000(),
        }
    }

    /// Length, m.
    #[getter]
    fn length(&self) -> f64 {
        self.beam.length()
    }

    /// Bending stiffness E I, N m^2.
    #[getter]
    fn stiffness(&self) -> f64 {
        self.beam.stiffness()
    }

    /// Deflection (m, downward) at `x` (m from the left support) under
    /// `loads` ((K, 2): position m, force N, downward).
    fn deflection(&self, x: f64, loads: &Bound<'_, PyAny>) -> PyResult<f64> {
        self.beam.deflection(x, &point_loads(loads)?).or_raise()
    }

    /// Slope dw/dx (rad) at `x` under `loads`.
    fn slope(&self, x: f64, loads: &Bound<'_, PyAny>) -> PyResult<f64> {
        self.beam.slope(x, &point_loads(loads)?).or_raise()
    }

    /// Deflection (m) under a single load `force` (N) at `position` (m).
    fn deflection_under_load(&self, position: f64, force: f64) -> PyResult<f64> {
        self.beam.deflection_under_load(position, force).or_raise()
    }

    fn __repr__(&self) -> String {
        format!(
            "Beam(length={}, stiffness={:.4e})",
            self.beam.length(),
            self.beam.stiffness()
        )
    }
}
