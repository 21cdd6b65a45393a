//! Seed 002's claims beyond the continuous path, tested on the planning
//! model when it has the seed's structure ([`Arm4Solver`]): the closed-form
//! inverse kinematics with theta1 + theta2 solved as one angle (sec 2.2,
//! eqs 10-18) and the forward-kinematics example of sec 2.1; and, on every
//! run, how armkit reads the orientation angles of eqs 20-22.

use super::outcome::PlannedPath;
use crate::error::Result;
use crate::ik::closed_form::{Arm4Solver, Fit, RangeFilter};
use crate::ik::orientation_error;
use crate::kinematics::{forward_kinematics, Data};
use crate::math::{Matrix3, Pose};
use crate::model::Model;
use crate::study::{Finding, FindingStatus};
use crate::trajectory::PathStatus;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Configurations of the inverse-kinematics test (a low-discrepancy grid
/// over the joint limits).
const IK_SAMPLES: usize = 200;

/// A candidate reproduces the pose when forward kinematics puts it within
/// this of the target (m and rad): far below the extraneous roots' errors
/// (centimetres and radians), far above rounding.
const EXACT: f64 = 1e-9;

/// The seed-002 structure's findings on `model`: empty when `model` is not
/// of that structure (e.g. the Panda).
pub(super) fn arm4_findings(model: &Model) -> Result<Vec<Finding>> {
    let Ok(solver) = Arm4Solver::new(model) else {
        return Ok(Vec::new());
    };
    Ok(vec![
        ik_finding(model, &solver)?,
        fk_example_finding(model, &solver)?,
    ])
}

/// `q` wrapped to (-pi, pi] per joint, for comparing angles.
fn wrapped_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let d = (x - y).rem_euclid(TAU);
            d.min(TAU - d)
        })
        .fold(0.0, f64::max)
}

/// Position (m) and orientation (rad) error of `q`'s pose from `target`.
fn pose_errors(model: &Model, data: &mut Data, q: &[f64], target: &Pose) -> Result<(f64, f64)> {
    let pose = forward_kinematics(model, data, q)?;
    Ok((
        (pose.translation - target.translation).norm(),
        orientation_error(&target.rotation, &pose.rotation).norm(),
    ))
}

/// Eqs 10-18 as printed, on configurations spread over the joint limits:
/// which of the 16 sign choices reproduce the pose, whether the
/// configuration that made it is among them, and whether they are armkit's
/// closed-form solutions.
fn ik_finding(model: &Model, solver: &Arm4Solver) -> Result<Finding> {
    let mut data = Data::new(model);
    // Weyl sequence: joint j at the fractional part of k * sqrt(prime_j).
    let steps = [2f64.sqrt(), 3f64.sqrt(), 5f64.sqrt(), 7f64.sqrt()];
    let (mut exact_min, mut exact_max) = (usize::MAX, 0);
    let (mut recovered, mut agree) = (0, 0);
    let (mut worst_exact, mut best_extraneous) = (0.0_f64, f64::INFINITY);
    for k in 1..=IK_SAMPLES {
        let q: Vec<f64> = model
            .joints()
            .iter()
            .zip(steps)
            .map(|(joint, step)| {
                let (low, high) = (joint.limits.lower.max(-PI), joint.limits.upper.min(PI));
                low + (high - low) * (k as f64 * step).fract()
            })
            .collect();
        let target = *forward_kinematics(model, &mut data, &q)?;
        let mut exact = Vec::new();
        for candidate in solver.paper_candidates(&target)? {
            let (position, orientation) = pose_errors(model, &mut data, &candidate, &target)?;
            let error = position.max(orientation);
            if error <= EXACT {
                worst_exact = worst_exact.max(error);
                exact.push(candidate);
            } else {
                best_extraneous = best_extraneous.min(error);
            }
        }
        exact_min = exact_min.min(exact.len());
        exact_max = exact_max.max(exact.len());
        if exact.iter().any(|c| wrapped_distance(c, &q) <= 1e-9) {
            recovered += 1;
        }
        let armkit: Vec<Vec<f64>> = solver
            .solve_with(&target, &q, RangeFilter::IgnoreLimits)?
            .into_iter()
            .filter(|s| s.fit == Fit::Exact)
            .map(|s| s.q)
            .collect();
        let same = armkit.len() == exact.len()
            && armkit
                .iter()
                .all(|a| exact.iter().any(|e| wrapped_distance(a, e) <= 1e-9));
        if same {
            agree += 1;
        }
    }
    let holds = recovered == IK_SAMPLES
        && agree == IK_SAMPLES
        && exact_min >= 1
        && best_extraneous > 1e3 * EXACT;
    Ok(Finding::new(
        "seed 002, sec 2.2, eqs 10-18: the closed-form inverse kinematics solves theta1 + theta2 \
         as one angle (eqs 13-16), then theta1, theta3 and theta4; eqs 11, 15, 17 and 18 are \
         each two-valued, and the roots that do not fit come from the square roots",
        format!(
            "{IK_SAMPLES} configurations over {}'s joint ranges (a low-discrepancy grid), the \
             paper's equations in DH angles, 16 sign choices each: {exact_min} to {exact_max} \
             reproduce the pose (forward-kinematics error <= {worst_exact:.1e} m or rad), the \
             others miss it by >= {best_extraneous:.2e} (extraneous roots; eq 11's other \
             elbow turns theta12 and so the tool's heading, which the roll and pitch cannot \
             undo); the configuration that made the pose is among them for {recovered} of \
             {IK_SAMPLES}; they are exactly armkit's closed-form solutions for {agree} of \
             {IK_SAMPLES}",
            model.name()
        ),
        FindingStatus::from_holds(holds),
    ))
}

/// Sec 2.1's check of eq 7: motor angles (0, 90, 0, -90) deg, i.e. wrist
/// (DH) angles (0, 90, 180, -90) deg, against the motors' zero, wrist
/// angles (0, 0, 180, 0) deg (the printed mapping adds 180 deg to joint 3
/// only): the wrist's orientation unchanged, its position moved by `d3` in
/// X and in Y, Z unchanged.
fn fk_example_finding(model: &Model, solver: &Arm4Solver) -> Result<Finding> {
    let mut data = Data::new(model);
    let home_q = solver.joints_from_dh_angles([0.0, 0.0, PI, 0.0]);
    let moved_q = solver.joints_from_dh_angles([0.0, FRAC_PI_2, PI, -FRAC_PI_2]);
    let home = *forward_kinematics(model, &mut data, &home_q)?;
    let moved = *forward_kinematics(model, &mut data, &moved_q)?;
    let shift = moved.translation - home.translation;
    let turn = orientation_error(&home.rotation, &moved.rotation).norm();
    let d3 = solver.link2_length();
    let off = (shift.x.abs() - d3)
        .abs()
        .max((shift.y.abs() - d3).abs())
        .max(shift.z.abs());
    Ok(Finding::new(
        "seed 002, sec 2.1 (eq 7 verified): motor angles (0, 90, 0, -90) deg, wrist angles \
         (0, 90, 180, -90) deg, leave the wrist's orientation unchanged and move it by d in X \
         and in Y, Z unchanged",
        format!(
            "{} at wrist (DH) angles (0, 90, 180, -90) deg against the motors' zero (0, 0, 180, \
             0) deg: position moved by ({:+.6}, {:+.6}, {:+.1e}) m (d3 = {d3} m; largest \
             departure {off:.1e} m), orientation turned by {turn:.1e} rad",
            model.name(),
            shift.x,
            shift.y,
            shift.z
        ),
        FindingStatus::from_holds(off <= 1e-12 && turn <= 1e-12),
    ))
}

/// Eqs 20-22 as armkit runs them: roll, pitch and yaw (fixed X, Y, Z)
/// linear in time. As printed, "the angles with the base's X, Y and Z
/// axes" are the direction angles of one tool axis: tied by
/// `cos^2 alpha + cos^2 beta + cos^2 gamma = 1`, which linear
/// interpolation breaks, and blind to a turn about that axis.
pub(super) fn orientation_law_finding(main: &PlannedPath) -> Finding {
    let start = main.path.pose_at(main.path.start_time()).rotation;
    let end = main.path.pose_at(main.path.end_time()).rotation;
    let (residual, axis) = (0..3)
        .map(|k| (direction_angle_residual(&start, &end, k), k))
        .fold(
            (0.0, 0),
            |best, this| if this.0 > best.0 { this } else { best },
        );
    Finding::new(
        "seed 002, sec 3, eqs 20-22: the tool's angles alpha, beta, gamma with the base's X, Y \
         and Z axes move linearly in time",
        format!(
            "armkit reads them as roll, pitch and yaw (fixed X, Y, Z), linear in time (run: {}, \
             {} segments). As printed they are the direction angles of one tool axis: linear \
             in time they leave cos^2 + cos^2 + cos^2 = 1 (on this line, at mid-time, off by \
             {residual:.2e} for the tool's {} axis) and they fix no turn about that axis, so \
             they cannot give the pose of eq 19-22's T_N",
            main.report.status,
            main.report.trajectory.segment_count(),
            ["x", "y", "z"][axis]
        ),
        FindingStatus::ReproducedWithDeviation
            .if_holds(main.report.status == PathStatus::ToleranceMet),
    )
}

/// `|sum cos^2 - 1|` at mid-time for tool axis `k` when its direction
/// angles move linearly from `start`'s to `end`'s.
fn direction_angle_residual(start: &Matrix3<f64>, end: &Matrix3<f64>, k: usize) -> f64 {
    let angle = |r: &Matrix3<f64>, i: usize| r[(i, k)].clamp(-1.0, 1.0).acos();
    let sum: f64 = (0..3)
        .map(|i| (0.5 * (angle(start, i) + angle(end, i))).cos().powi(2))
        .sum();
    (sum - 1.0).abs()
}
