//! Free-floating space manipulators from Python: `armkit.SpaceRobot`.

use armkit::math::Pose;
use armkit::robots::space6r_free_floating;
use armkit::space::{
    generalized_jacobian, step as space_step, BaseMode, FreeFloatingModel, FreeFloatingState,
    SpaceData,
};
use armkit::Error;
use numpy::ndarray::Dim;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::arrays::{
    new_array, pose_argument, vector, vector_argument, write_jacobian, write_pose,
};
use crate::errors::OrRaise;

/// Longest `SpaceRobot.step` interval, s: the joint rates are held over one
/// step, so a longer interval is a trajectory, not a step.
const MAX_STEP_SECONDS: f64 = 1.0;

fn base_mode(name: &str) -> armkit::Result<BaseMode> {
    match name {
        "attitude-held" | "attitude_held" => Ok(BaseMode::AttitudeHeld),
        "free-floating" | "free_floating" => Ok(BaseMode::FreeFloating),
        other => Err(Error::invalid_argument(
            "mode",
            format!("expected \"attitude-held\" or \"free-floating\", got \"{other}\""),
        )),
    }
}

/// A free-floating space manipulator: an arm on a spacecraft base, no
/// external force. Poses in the inertial frame (m); `mode`:
/// `"attitude-held"` (seed 004: the base attitude is held, it translates)
/// or `"free-floating"` (linear and angular momentum both zero).
#[pyclass(frozen, module = "armkit", name = "SpaceRobot")]
pub struct SpaceRobot {
    model: FreeFloatingModel,
}

impl SpaceRobot {
    fn base_or_identity(&self, base: Option<&Bound<'_, PyAny>>) -> PyResult<Pose> {
        base.map_or(Ok(Pose::identity()), |b| pose_argument(b, "base"))
    }
}

#[pymethods]
impl SpaceRobot {
    /// Seed 004's space robot: `space6r` on a 400 kg satellite.
    #[staticmethod]
    fn space6r() -> PyResult<Self> {
        Ok(SpaceRobot {
            model: space6r_free_floating().or_raise()?,
        })
    }

    /// Arm degrees of freedom.
    #[getter]
    fn dof(&self) -> usize {
        self.model.dof()
    }

    /// Total mass, kg.
    #[getter]
    fn total_mass(&self) -> f64 {
        self.model.total_mass()
    }

    /// The generalized Jacobian J* (6, dof), rows `[vx vy vz wx wy wz]`
    /// (inertial frame): the end-effector twist per joint rate with the base
    /// moving as momentum conservation makes it. `base`: base pose (4, 4),
    /// default identity.
    #[pyo3(signature = (q, base=None, mode="attitude-held"))]
    fn generalized_jacobian<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        base: Option<&Bound<'py, PyAny>>,
        mode: &str,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let q = vector_argument(q, "joint_positions", self.model.dof())?;
        let base = self.base_or_identity(base)?;
        let mode = base_mode(mode).or_raise()?;
        let mut data = SpaceData::new(&self.model);
        let j = generalized_jacobian(&self.model, &mut data, &base, &q, mode).or_raise()?;
        new_array(py, Dim([6, self.model.dof()]), |out| {
            write_jacobian(j, out);
            Ok(())
        })
    }

    /// Integrates the system for `joint_rates` (dof,) held over `dt` s
    /// (0 < `dt` <= 1 s) from (`base`, `q`). Returns the new `(base (4, 4), q (dof,))`.
    #[pyo3(signature = (q, joint_rates, dt, base=None, mode="attitude-held"))]
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        joint_rates: &Bound<'py, PyAny>,
        dt: f64,
        base: Option<&Bound<'py, PyAny>>,
        mode: &str,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
        // One step is one integration interval: a zero step does nothing and a
        // step beyond the bound is no longer a step of this integrator.
        if !(dt.is_finite() && dt > 0.0 && dt <= MAX_STEP_SECONDS) {
            return Err::<_, Error>(Error::invalid_argument(
                "dt",
                format!(
                    "must be > 0 and <= {MAX_STEP_SECONDS} s, got {} s",
                    armkit::error::brief(dt)
                ),
            ))
            .or_raise();
        }
        let dof = self.model.dof();
        let q = vector_argument(q, "joint_positions", dof)?;
        let rates = vector_argument(joint_rates, "joint_rates", dof)?;
        let base = self.base_or_identity(base)?;
        let mode = base_mode(mode).or_raise()?;
        let mut data = SpaceData::new(&self.model);
        let mut state = FreeFloatingState::new(base, q);
        space_step(&self.model, &mut data, &mut state, &rates, dt, mode).or_raise()?;
        let pose = new_array(py, Dim([4, 4]), |out| {
            write_pose(&state.base, out);
            Ok(())
        })?;
        Ok((pose, vector(py, &state.q)))
    }
}
