//! Singularity detection and avoidance along Cartesian paths (seed 004),
//! with damped least squares and the singularity-robust inverse as
//! baselines; singular configurations and the manipulability ellipsoid.
//!
//! # Tracking a path through a singularity
//!
//! [`PathTracker`] tracks a straight pose line ([`LineTask`]: position
//! linear, orientation by slerp, seed 004's trapezoidal speed profile) at
//! the velocity level, every control period `h`: the pose error from the
//! current pose to the planned pose at `t + h` (position difference and
//! axis-angle, seed 004 eqs 26-27) over `h` gives the twist, and joint
//! rates follow from the [`Method`]'s inverse of the Jacobian (eq 28):
//!
//! * [`Method::Plain`]: `q_dot = J^-1 x_dot`; near a singularity the rates
//!   blow up (seed 004 Fig 5).
//! * [`Method::Avoidance`]: seed 004 sec 2.3. Plain tracking, checked every
//!   period by [`detect`]: `|det J|` below `determinant_threshold`, or a
//!   plain joint step above `joint_step_threshold` (`eps_dq`). On entry, a
//!   Newton-Raphson IK (Fig 2) of every `k`-th planned pose, each
//!   warm-started from the previous knot moved on by the last secant, until
//!   a knot is regular again; the knots are joined by the clamped C2 cubic
//!   of eqs 33-42 (`theta''` linear on each interval), starting at the
//!   current rates and ending at the plain rates of the exit knot, and the
//!   joints follow it; plain tracking resumes after the exit.
//! * [`Method::DampedLeastSquares`] (Nakamura's adaptive damping) and
//!   [`Method::SingularityRobust`] (Chiaverini's filtered inverse): the
//!   baselines, over the whole path; [`Method::ClampedDampedLeastSquares`]
//!   is DLS held to a joint speed bound.
//! * [`Method::SeparatedDampedReciprocal`]: seed 004's reference [9], the
//!   comparator its conclusion 1 names: the arm and wrist blocks solved
//!   apart at the wrist centre, only the wrist block's smallest singular
//!   value's reciprocal damped (6-joint arms with a spherical wrist).
//!
//! [`PathTracker::compare`] runs them all from the same start and a sweep of
//! `k` (Figs 7-8); each [`MethodRun`] records, per sample, the time, joint
//! positions and rates, position and orientation error, `|det J|`, the
//! regions crossed, and a [`MethodSummary`] (peak joint rate, maximum and final
//! errors, time in the singular region, IK solves). A run allocates by
//! design (it records these series, sized once per run, and each region's
//! knots and fit); the per-period step of the plain, DLS and SRI methods
//! allocates nothing, so a run's allocation count does not depend on its
//! number of periods (`tests/no_allocation.rs`).
//!
//! Both [`Manipulator::FixedBase`] (any arm, its `J`) and
//! [`Manipulator::AttitudeHeld`] (a free-floating system whose base attitude
//! is held, zero linear momentum: the generalized Jacobian `J*`, the base
//! translating with the arm) are tracked the same way. The held system is
//! holonomic (the centre of mass stays put, so the base position is a
//! function of the joints), so its knots are solved by Newton on that
//! constrained map with `J*`: solving on the fixed-base kinematics from the
//! current base pose would miss by the base's reaction.
//!
//! # Thresholds and the paper's `eps_dq = 5`, `eps_T = 1e-8`
//!
//! * `eps_T` is [`AvoidanceOptions::ik_tolerance`], 1e-8 (m and rad), as in
//!   the paper.
//! * The paper's `eps_dq = 5` has no printed unit (5 deg per step would be
//!   8.7 rad/s at our 0.01 s period, beyond any space arm). Ours,
//!   [`DetectionOptions::joint_step_threshold`], is 0.005 rad per period:
//!   space6r's 0.5 rad/s joint speed limit.
//! * The paper derives the determinant threshold from the configuration
//!   where the joints start jumping: [`calibrate_determinant_threshold`]
//!   does that on a plain run, and [`crate::study::AvoidanceStudy`] uses it
//!   by default (`ThresholdRule::Calibrated`). On our path, which passes
//!   exactly through the singular pose, plain tracking stays accurate until
//!   0.05 s before it and that rule gives 1.6e-4 m^3, a region of about
//!   9.96 s to 10.04 s. [`DetectionOptions::default`]'s 0.004 m^3 is instead
//!   the `|det J|` of the plain run at the paper's region start (fitted:
//!   region 8.86 s to 11.43 s, the paper's 8.8 s to 11.2 s); the study
//!   reports it beside the paper's rule as a labelled comparison.
//!
//! # The path
//!
//! The paper's start configuration and end poses are for its own DH table,
//! lost in the extraction, so [`seed004_path`] builds the path from the
//! singularity outwards: [`line_through`] the wrist-singular configuration
//! [`SEED004_THROUGH`] (`q5 = 0`) along [`SEED004_DIRECTION`] (q5 crossing
//! zero), no miss, 20 s with 4 s of acceleration and deceleration. The end
//! effector is at the singular pose at 10 s; joints 4 and 6 are the ones
//! that jump under plain tracking, as in the paper.
//!
//! # Errata and deviations
//!
//! * Eqs 1-19 (the generalized Jacobian) and the DH table are lost in the
//!   extraction: [`crate::space`] derives `J*` (Umetani and Yoshida with
//!   the base angular velocity zero) and [`crate::robots::space6r`] builds
//!   the arm.
//! * Eqs 30-32 (the "differential terms" at the region's ends) are garbled:
//!   the fit is clamped with the current rates at entry and the plain rates
//!   at the exit knot instead, which keeps the rates continuous there.
//! * Step 5's stopping test is garbled: the region ends at the first exact
//!   knot where both detection tests pass again (`|det J|` at or above the
//!   threshold, the plain rates of the planned twist within `eps_dq` per
//!   period), or at the path's end.
//! * After the region the paper re-plans from the current pose to the goal;
//!   here tracking resumes on the same planned path, whose pose error term
//!   pulls the end effector back (the same path when the fit is on it).
//! * Near the singular pose the IK solutions form a continuum (`q4 + d`,
//!   `q6 - d`); a knot's drift along it is removed (projected back toward
//!   the warm start) when that keeps the pose within `eps_T`.
//! * A path that misses the singular pose by a little asks the wrist to flip
//!   (joints 4 and 6 turn by about pi in a time proportional to the miss
//!   `d`), faster than the arm can: the paper does not say what its knots
//!   do then. Staying on the wrist branch with bounded rates costs an error
//!   that grows with the lag; crossing `q5 = 0` (switching branch, joints 4
//!   and 6 barely moving) costs about `d` at the crossing, the distance from
//!   the target to the singular poses ([`PathTracker::singular_gap`]): a
//!   rate-bounded plan has a floor near `d` on such lines. Here a knot whose
//!   Newton solution would move some joint more than `eps_dq` per period
//!   since the last knot (or whose solve does not converge) is first the
//!   least-squares knot, the nearest pose within `eps_dq` per period of the
//!   last ([`SingularRegion::bounded_knots`]); this greedy plan reacts late
//!   (about `2 d` of error). The region's knots are then planned jointly
//!   ([`RegionPlan::Joint`]): a sequential cone program minimises the
//!   largest knot error under the joint-step bound from the greedy knots,
//!   and is kept where it errs less (about `d` at 1 and 3 mm). The region's
//!   rates stay within `eps_dq / h` for `k = 1`; `AvoidanceStudy` sweeps the
//!   miss and compares with DLS, DLS clamped to that speed
//!   ([`Method::ClampedDampedLeastSquares`]) and the floor.
//! * The paper sees larger errors at the region's entry for smaller `k`
//!   (error accumulated before it). Here tracking before the entry is the
//!   same for every `k`, so the entry errors are equal; `AvoidanceStudy`
//!   reports both of the paper's orderings as findings with their figures.
//!
//! # Singular configurations and ellipsoids
//!
//! [`classify`] names the singularity of a configuration (wrist, elbow,
//! shoulder for 6R arms with a spherical wrist, from the factors of
//! `det J`; unclassified rank loss otherwise), [`nearest_singularity`] and
//! [`find_singularities`] find singular configurations, and
//! [`manipulability_ellipsoid`] gives the translational or rotational
//! velocity ellipsoid.
//!
//! # Example
//!
//! ```
//! use armkit::singularity::{
//!     seed004_path, AvoidanceOptions, Manipulator, Method, PathTracker,
//! };
//! let arm = armkit::robots::space6r()?;
//! let manipulator = Manipulator::FixedBase(&arm);
//! let line = seed004_path(&manipulator)?;
//! let tracker = PathTracker::new(manipulator, line.task(20.0, 4.0), AvoidanceOptions::default())?;
//! let plain = tracker.run(&Method::Plain)?;
//! let avoid = tracker.run(&Method::Avoidance { k: 5 })?;
//! // Plain tracking spins joints 4 and 6 through the singularity; the
//! // avoidance keeps every joint slow and stays on the path.
//! assert!(plain.summary.peak_joint_rate > 10.0 * avoid.summary.peak_joint_rate);
//! assert!(avoid.summary.max_position_error < 1e-6);
//! let region = &avoid.regions[0];
//! assert!(region.start_time > 8.5 && region.end_time < 11.7);
//! # Ok::<(), armkit::Error>(())
//! ```

mod avoidance;
mod comparison;
mod configurations;
mod detection;
mod ellipsoid;
mod gap;
mod method;
mod plant;
mod region;
mod region_plan;
mod scenario;

pub use avoidance::PathTracker;
pub use comparison::{Baselines, Comparison};
pub use configurations::{
    classify, find_singularities, nearest_singularity, Classification, ClassifyOptions,
    SearchOptions, SearchStatus, SearchTarget, SingularConfiguration, SingularityKind,
    WristFactors,
};
pub use detection::{detect, jacobian_determinant, Detection, DetectionOptions, Trigger};
pub use ellipsoid::{manipulability_ellipsoid, Ellipsoid, JacobianPart};
pub use gap::SingularGap;
pub use method::{
    calibrate_determinant_threshold, AvoidanceOptions, LineTask, Method, MethodRun, MethodSummary,
    SingularRegion, MAX_IK_ITERATIONS, SEPARATION,
};
pub use region_plan::RegionPlan;
pub use scenario::{line_through, seed004_path, LineThrough, SEED004_DIRECTION, SEED004_THROUGH};

use crate::math::Pose;
use crate::model::Model;
use crate::space::FreeFloatingModel;

/// Which base the arm stands on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum BaseKind {
    /// A fixed base: the arm's world frame is the inertial frame.
    Fixed,
    /// A free-floating base whose attitude is held (seed 004): it translates
    /// so that the linear momentum stays zero.
    AttitudeHeld,
}

/// The manipulator a path is tracked with.
#[derive(Clone, Copy, Debug)]
pub enum Manipulator<'m> {
    /// Any arm on a fixed base; poses and Jacobian in its world frame.
    FixedBase(&'m Model),
    /// A free-floating system with the base attitude held (seed 004): the
    /// generalized Jacobian `J*`, the base moving with the arm.
    AttitudeHeld {
        /// The system.
        system: &'m FreeFloatingModel,
        /// Base pose at the start configuration, inertial frame. Its attitude
        /// is held throughout; its position follows from zero momentum.
        base: Pose,
    },
}

impl Manipulator<'_> {
    /// Number of joints.
    pub fn dof(&self) -> usize {
        match self {
            Manipulator::FixedBase(arm) => arm.dof(),
            Manipulator::AttitudeHeld { system, .. } => system.dof(),
        }
    }

    /// Which base.
    pub fn base_kind(&self) -> BaseKind {
        match self {
            Manipulator::FixedBase(_) => BaseKind::Fixed,
            Manipulator::AttitudeHeld { .. } => BaseKind::AttitudeHeld,
        }
    }

    /// The arm model.
    pub fn arm(&self) -> &Model {
        match self {
            Manipulator::FixedBase(arm) => arm,
            Manipulator::AttitudeHeld { system, .. } => system.arm(),
        }
    }
}
