//! Straight-line paths through a chosen configuration, and seed 004's scenario.

use super::method::LineTask;
use super::plant::Plant;
use super::Manipulator;
use crate::error::{check_finite_vector, Error, Result};
use crate::math::{DMatrix, DVector, Pose, Rotation3, Vector3};

/// A straight line through a chosen configuration (see [`line_through`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LineThrough {
    /// Start joint positions, rad or m (the IK of the line's start connected
    /// to the chosen configuration).
    pub start: Vec<f64>,
    /// Base pose at the start (inertial frame; the identity on a fixed base).
    pub base: Pose,
    /// The line's end pose.
    pub goal: Pose,
    /// The pose of the chosen configuration: the line's midpoint.
    pub through: Pose,
}

impl LineThrough {
    /// The tracking task along this line: from `start` to `goal` in
    /// `duration` s with `acceleration_time` s of acceleration and of
    /// deceleration (seed 004: 20 s and 4 s).
    pub fn task(&self, duration: f64, acceleration_time: f64) -> LineTask {
        LineTask {
            start: self.start.clone(),
            goal: self.goal,
            duration,
            acceleration_time,
        }
    }
}

/// The configuration seed 004's path is built through on space6r (rad):
/// `q5 = 0`, axes 4 and 6 aligned (a wrist singularity); the other angles
/// keep the arm away from its elbow and shoulder singularities.
pub const SEED004_THROUGH: [f64; 6] = [0.4, 1.2, -0.5, 0.6, 0.0, -0.3];

/// The joint direction of seed 004's path at [`SEED004_THROUGH`] (rad per
/// path): `q5` crosses zero while joints 1 to 3 move the wrist centre,
/// joints 4 and 6 stay (any motion of theirs is lost at the singularity).
pub const SEED004_DIRECTION: [f64; 6] = [0.5, -0.3, 0.4, 0.0, 0.8, 0.0];

/// Seed 004's path on space6r, rebuilt: the straight pose line through the
/// wrist-singular configuration [`SEED004_THROUGH`] along
/// [`SEED004_DIRECTION`] with no miss (`line_through(manipulator,
/// SEED004_THROUGH, SEED004_DIRECTION, 0)`): the end effector passes exactly
/// through the singular pose at mid-path (10 s of 20). The paper prints its
/// start configuration and end poses, but they belong to its own DH table,
/// frames and Euler-angle convention, which the extraction lost; they cannot
/// be reused on our space6r, so the path is built from the singularity
/// outwards instead.
///
/// Errors: `manipulator` without 6 joints; those of [`line_through`].
pub fn seed004_path(manipulator: &Manipulator<'_>) -> Result<LineThrough> {
    line_through(manipulator, &SEED004_THROUGH, &SEED004_DIRECTION, 0.0)
}

/// Steps of the continuation from the chosen configuration to the line's start.
const CONTINUATION_STEPS: usize = 40;

/// A straight pose line whose midpoint is the pose of `through` (joint
/// positions, rad or m) and whose direction is the end-effector motion that
/// the joint displacement `joint_direction` would make there, to first
/// order: with `[v; w] = J(through) joint_direction`, the line runs from
/// `(p - v/2, exp(-[w/2]x) R)` to `(p + v/2, exp([w/2]x) R)` (inertial
/// frame; slerp passes `R` at mid-path). The start configuration is the IK
/// of the start pose reached by continuation from `through` (so that it lies
/// on the same branch).
///
/// `manipulator` gives the base at `through` (on a held system, the base
/// pose when the joints are at `through`; the returned `base` is the one at
/// the start configuration, with the same centre of mass).
///
/// Use: a `through` with `q5 = 0` on a PUMA-type wrist and a direction
/// moving `q5` gives a path crossing the wrist singularity at mid-path.
///
/// Errors: sizes, non-finite values, a start out of reach.
pub fn line_through(
    manipulator: &Manipulator<'_>,
    through: &[f64],
    joint_direction: &[f64],
    miss: f64,
) -> Result<LineThrough> {
    let n = manipulator.dof();
    check_finite_vector("through", through, n)?;
    check_finite_vector("joint_direction", joint_direction, n)?;
    let mut plant = Plant::new(manipulator, through, 1e-10, 50)?;
    plant.evaluate(through)?;
    let middle = *plant.pose();
    let jacobian = DMatrix::from_column_slice(6, n, plant.jacobian().as_slice());
    let twist = &jacobian * DVector::from_column_slice(joint_direction);
    // The direction J cannot produce at `through`: the left singular vector
    // of its smallest singular value.
    let svd = jacobian.svd(true, false);
    let lost = match (&svd.u, svd.singular_values.imin()) {
        (Some(u), smallest) => u.column(smallest).into_owned(),
        (None, _) => DVector::zeros(6),
    };
    let offset = Pose::new(
        Rotation3::new(Vector3::new(lost[3], lost[4], lost[5]) * miss).into_inner(),
        Vector3::new(lost[0], lost[1], lost[2]) * miss,
    );
    let displaced = |fraction: f64| -> Pose {
        let v = Vector3::new(twist[0], twist[1], twist[2]) * fraction;
        let w = Vector3::new(twist[3], twist[4], twist[5]) * fraction;
        let on_line = Pose::new(
            Rotation3::new(w).into_inner() * middle.rotation,
            middle.translation + v,
        );
        // The offset, a constant twist displacement, keeps the line straight.
        Pose::new(
            offset.rotation * on_line.rotation,
            offset.translation + on_line.translation,
        )
    };
    // Continuation from `through` back along the line without the offset
    // (through regular poses only, whatever the miss), then onto the offset.
    let mut q = through.to_vec();
    let unshifted = |fraction: f64| -> Pose {
        let v = Vector3::new(twist[0], twist[1], twist[2]) * fraction;
        let w = Vector3::new(twist[3], twist[4], twist[5]) * fraction;
        Pose::new(
            Rotation3::new(w).into_inner() * middle.rotation,
            middle.translation + v,
        )
    };
    for i in 1..=2 * CONTINUATION_STEPS {
        let target = if i <= CONTINUATION_STEPS {
            unshifted(-0.5 * i as f64 / CONTINUATION_STEPS as f64)
        } else {
            let along = (i - CONTINUATION_STEPS) as f64 / CONTINUATION_STEPS as f64;
            let partial = Pose::new(
                Rotation3::new(Vector3::new(lost[3], lost[4], lost[5]) * (miss * along))
                    .into_inner(),
                Vector3::new(lost[0], lost[1], lost[2]) * (miss * along),
            );
            let p = unshifted(-0.5);
            Pose::new(
                partial.rotation * p.rotation,
                partial.translation + p.translation,
            )
        };
        let solve = plant.reach(&target, &q)?;
        if !solve.converged {
            return Err(Error::invalid_argument(
                "joint_direction",
                format!(
                    "the line's start is out of reach (position error {:.3e} m)",
                    solve.position_error
                ),
            ));
        }
        q = solve.q;
    }
    let base = plant.base_at(&q)?;
    Ok(LineThrough {
        start: q,
        base,
        goal: displaced(0.5),
        through: middle,
    })
}
