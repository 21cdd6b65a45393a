//! How close a path comes to a set of singular poses: the error floor of a
//! plan that crosses that set (a wrist-branch switch on a near miss).

use super::avoidance::PathTracker;
use super::plant::Plant;
use crate::error::{check_finite_vector, Error, Result};
use crate::ik::pose_error;

/// The smallest distance from a path's planned poses to the poses reachable
/// with one joint held (see [`PathTracker::singular_gap`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SingularGap {
    /// Time of the planned pose nearest the set, s.
    pub time: f64,
    /// Position part of the pose error there, m.
    pub position: f64,
    /// Orientation part (rotation angle), rad.
    pub orientation: f64,
    /// Norm of the 6-vector pose error (m and rad), the quantity minimised.
    pub norm: f64,
}

/// Spacing of the scanned planned poses, in control periods.
const SCAN_STRIDE: usize = 5;

impl PathTracker<'_> {
    /// The distance from the planned path to the poses reachable with joint
    /// `joint` (0-based) held at `value` (rad or m): for the planned poses
    /// every 5 control periods within `window` s of `around` s, the nearest
    /// pose of that set (least squares on the 6-vector pose error, the other
    /// joints free, from `start` at `around` and warm-started outwards),
    /// and the smallest of those errors.
    ///
    /// With the joint whose zero is a wrist singularity (`q5 = 0` on a
    /// PUMA-type wrist such as space6r's) the set is the wrist-singular
    /// poses near `start`, and the gap is the error any plan that switches
    /// wrist branch (crosses `q5 = 0`) must make at its crossing: the floor
    /// of a rate-bounded plan on a near miss.
    ///
    /// Errors: `joint` out of range, `start` of the wrong size or not
    /// finite, `value`, `around` or `window` not finite, `window` negative.
    pub fn singular_gap(
        &self,
        joint: usize,
        value: f64,
        start: &[f64],
        around: f64,
        window: f64,
    ) -> Result<SingularGap> {
        let manipulator = self.manipulator();
        let n = manipulator.dof();
        if joint >= n {
            return Err(Error::invalid_argument(
                "joint",
                format!("joint index {joint} is out of range (the arm has {n} joints)"),
            ));
        }
        check_finite_vector("start", start, n)?;
        crate::error::check_finite("value", &[value])?;
        crate::error::check_finite("around", &[around])?;
        if !(window >= 0.0 && window.is_finite()) {
            return Err(Error::invalid_argument(
                "window",
                format!("must be finite and >= 0 s, got {window}"),
            ));
        }
        let options = self.options();
        // The plant starts where the path does (on a held system that fixes
        // the centre of mass); `start` is only the first guess.
        let mut plant = Plant::new(
            &manipulator,
            &self.task().start,
            options.ik_tolerance,
            options.ik_max_iterations,
        )?;
        let (steps, h) = self.steps();
        let duration = steps as f64 * h;
        let lower: Vec<f64> = (0..n)
            .map(|j| if j == joint { value } else { f64::NEG_INFINITY })
            .collect();
        let upper: Vec<f64> = (0..n)
            .map(|j| if j == joint { value } else { f64::INFINITY })
            .collect();
        let spacing = SCAN_STRIDE as f64 * h;
        let reach = (window / spacing).floor() as i64;
        let mut best = SingularGap {
            time: around,
            position: f64::INFINITY,
            orientation: f64::INFINITY,
            norm: f64::INFINITY,
        };
        // Outwards from `around`, each side warm-started from the last.
        for direction in [1i64, -1] {
            let mut q = start.to_vec();
            let first = if direction > 0 { 0 } else { 1 };
            for i in first..=reach {
                let t = around + (direction * i) as f64 * spacing;
                if !(0.0..=duration).contains(&t) {
                    break;
                }
                let target = self.trajectory().pose_at(t);
                let solve = plant.box_solve(&target, &lower, &upper, &q)?;
                plant.evaluate(&solve.q)?;
                let e = pose_error(&target, plant.pose());
                if e.norm() < best.norm {
                    best = SingularGap {
                        time: t,
                        position: e.fixed_rows::<3>(0).norm(),
                        orientation: e.fixed_rows::<3>(3).norm(),
                        norm: e.norm(),
                    };
                }
                q = solve.q;
            }
        }
        Ok(best)
    }
}
