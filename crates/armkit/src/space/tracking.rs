//! Resolved-rate tracking of a Cartesian pose path with the generalized
//! Jacobian (seed 004, eqs 20-28 at velocity level): the free-floating
//! system as a [`crate::tracking::Plant`] ([`FloatingBase`]), and the one
//! tracking loop ([`crate::tracking::track`]) on it.

use super::{
    generalized_jacobian, step, BaseMode, FreeFloatingModel, FreeFloatingState, SpaceData,
};
use crate::error::{Error, Result};
use crate::math::{Matrix6xX, Pose};
use crate::tracking::{track_samples, LeastSquares, Plant, TrackingOptions, TrackingReport};
use crate::trajectory::TimedPath;

/// A free-floating space robot (seed 004): the generalized Jacobian `J*` of
/// its base mode, and [`super::step`] (momentum conserved, the base
/// moving) to advance.
#[derive(Debug)]
pub struct FloatingBase<'a> {
    model: &'a FreeFloatingModel,
    data: &'a mut SpaceData,
    mode: BaseMode,
    state: FreeFloatingState,
}

impl<'a> FloatingBase<'a> {
    /// The system from `initial` (base pose and joint positions), the base
    /// behaving as `mode` says. Errors: an arm with fewer than 6 joints (a
    /// 6-D pose cannot be tracked).
    pub fn new(
        model: &'a FreeFloatingModel,
        data: &'a mut SpaceData,
        mode: BaseMode,
        initial: &FreeFloatingState,
    ) -> Result<Self> {
        let n = model.dof();
        if n < 6 {
            return Err(Error::invalid_argument(
                "model",
                format!("tracking a 6-D pose needs at least 6 joints, the arm has {n}"),
            ));
        }
        Ok(FloatingBase {
            model,
            data,
            mode,
            state: initial.clone(),
        })
    }

    /// The current state (base pose and joints).
    pub fn state(&self) -> &FreeFloatingState {
        &self.state
    }
}

impl Plant for FloatingBase<'_> {
    fn dof(&self) -> usize {
        self.state.q.len()
    }

    fn joint_positions(&self) -> &[f64] {
        &self.state.q
    }

    fn evaluate(&mut self) -> Result<()> {
        generalized_jacobian(
            self.model,
            self.data,
            &self.state.base,
            &self.state.q,
            self.mode,
        )?;
        Ok(())
    }

    fn end_effector(&self) -> &Pose {
        self.data.end_effector_pose()
    }

    fn jacobian(&self) -> &Matrix6xX<f64> {
        self.data.jacobian()
    }

    fn base(&self) -> Pose {
        self.state.base
    }

    fn advance(&mut self, rates: &[f64], dt: f64) -> Result<()> {
        step(self.model, self.data, &mut self.state, rates, dt, self.mode)
    }
}

/// Resolved-rate tracking of the end-effector pose path `path` (inertial
/// frame, `t` in `[0, duration]` s) by the free-floating system from
/// `initial`, the base moving as `mode` says.
///
/// Every period `h`: `J*` at the current state; with the default
/// [`crate::tracking::Feedback::NextPose`], the pose error `e` from the
/// current end-effector pose to `path(t + h)` (position difference, and the
/// axis-angle vector `k phi` of `R_goal R'`, seed 004 eqs 26-27); the twist
/// `e / h`; joint rates from the (damped) least-squares inverse of `J*`
/// (`law`, eq 28; damping 0 is the plain inverse, the pseudo-inverse for
/// more than 6 joints); then [`super::step`]. The error is thus fed back
/// every period.
///
/// Errors: bad options or damping, an arm with fewer than 6 joints, a
/// non-positive duration, `path` returning a pose that is not a finite
/// proper rigid transform, and the errors of
/// [`super::generalized_jacobian`] and [`super::step`]. Reaching a singular
/// `J*` is a status ([`crate::tracking::TrackingStatus::Singular`]), not an
/// error.
pub fn track_pose_path(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    mode: BaseMode,
    initial: &FreeFloatingState,
    path: &dyn TimedPath,
    law: LeastSquares,
    options: &TrackingOptions,
) -> Result<TrackingReport> {
    options.validate()?;
    law.validate()?;
    let mut plant = FloatingBase::new(model, data, mode, initial)?;
    let mut law = law;
    track_samples(&mut plant, &mut law, path, options)
}
