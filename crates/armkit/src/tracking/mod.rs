//! One velocity-level tracking loop for every plant and every rate law.
//!
//! A tracker follows a timed end-effector path ([`TimedPath`]: a
//! [`crate::trajectory::CartesianTrajectory`], or any closure `t -> Pose`
//! through [`crate::trajectory::TimeFn`]) by resolved rates: every control
//! period it evaluates the [`Plant`], forms the commanded twist from the
//! path and the pose error ([`Feedback`]), asks a [`RateLaw`] for the joint
//! rates, and advances the plant. [`track`] is that loop, written once:
//!
//! * plants: [`FixedBase`] (any arm, the flexible gantry included), and in
//!   the modules above: [`crate::space::FloatingBase`] (a free-floating
//!   space robot, attitude held or fully free, seed 004) and the singularity
//!   study's attitude-held system;
//! * rate laws: [`LeastSquares`] (minimum norm / damped least squares, seed
//!   004 eq 28), the weighted and energy-optimal distributions of
//!   [`crate::redundancy`] (seed 001, seed 000's priorities), Nakamura's
//!   damping, Chiaverini's singularity-robust inverse and seed 004's
//!   avoidance in [`crate::singularity`].
//!
//! Redundancy, space and singularity each supply only their law or plant:
//! [`crate::redundancy::ResolvedRateTracker`],
//! [`crate::space::track_pose_path`] and
//! [`crate::singularity::PathTracker`] are this loop. A singular Jacobian
//! or a joint limit that stops the motion is a [`TrackingStatus`]; an
//! error means bad input or a numerical failure of the model (an FK
//! overflow is an error, not a singularity).
//!
//! Frames and units: world (inertial) frame; m, rad, s; twists `[v; w]`.
//!
//! ```
//! use armkit::math::{Pose, Vector3};
//! use armkit::tracking::{track_samples, FixedBase, LeastSquares, TrackingOptions, TrackingStatus};
//! use armkit::trajectory::{CartesianTrajectory, TimeLaw};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let q0 = [0.3, -1.2, 1.4, -1.5, -1.4, 0.2];
//! let mut data = armkit::Data::new(&model);
//! let start = *armkit::forward_kinematics(&model, &mut data, &q0).unwrap();
//! let goal = Pose::from_translation(Vector3::new(0.0, 0.1, 0.05)) * start;
//! let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 1.0).unwrap();
//! let mut plant = FixedBase::new(&model, &mut data, &q0).unwrap();
//! let mut law = LeastSquares { damping: 0.0 };
//! let report = track_samples(&mut plant, &mut law, &path, &TrackingOptions::default()).unwrap();
//! assert_eq!(report.status, TrackingStatus::Completed);
//! assert!(report.max_position_error < 1e-4);
//! ```

mod plant;
mod report;
mod run;
mod status;

pub use plant::{FixedBase, Plant};
pub use report::{SampleRecorder, TrackingReport, TrackingSample};
pub use run::{
    track, Feedback, LeastSquares, RateLaw, RateOutcome, Recorder, SampleState, Step,
    TrackingOptions, MAX_PERIODS,
};
pub use status::TrackingStatus;

pub use crate::trajectory::TimedPath;

use crate::error::Result;

/// [`track`] recording every sample ([`SampleRecorder`]) into a
/// [`TrackingReport`]. Allocates the samples (one per period).
pub fn track_samples<P: Plant + ?Sized, L: RateLaw<P> + ?Sized>(
    plant: &mut P,
    law: &mut L,
    path: &dyn TimedPath,
    options: &TrackingOptions,
) -> Result<TrackingReport> {
    options.validate()?;
    let (periods, _) = options.periods(path.duration().max(0.0), plant.dof())?;
    let mut recorder = SampleRecorder::with_capacity(periods + 1);
    let mut rates = vec![0.0; plant.dof()];
    let status = track(plant, law, path, options, &mut recorder, &mut rates)?;
    Ok(TrackingReport::new(status, recorder.samples))
}
