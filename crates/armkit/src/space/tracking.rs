//! Resolved-rate tracking of a Cartesian pose path with the generalized
//! Jacobian (seed 004, eqs 20-28 at velocity level): the one tracking loop
//! ([`crate::tracking::track`]) on a [`FloatingBase`] plant.

use super::{BaseMode, FreeFloatingModel, FreeFloatingState, SpaceData};
use crate::error::Result;
use crate::tracking::{track_samples, FloatingBase, LeastSquares, TrackingOptions, TrackingReport};
use crate::trajectory::TimedPath;

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
