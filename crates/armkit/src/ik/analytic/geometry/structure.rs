//! The structure of an arm: its joint axes as lines in the zero
//! configuration, which consecutive axes intersect or are parallel, and the
//! class of analytic solver that fits.
//!
//! Forward kinematics as a product of exponentials (Brockett): with joint i
//! turning about (or sliding along) the line through `points[i]` with unit
//! direction `axes[i]` (world frame, all joints at zero), and `home` the
//! end-effector pose at zero, `T(q) = E_1(q_1) ... E_n(q_n) home` where
//! `E_i(t)` rotates by `t` about line i (or translates by `t` along it).
//! Every model armkit builds (DH, modified DH, URDF, built-in) reduces to
//! this form; the lines are read from forward kinematics at `q = 0`.
//!
//! Tolerances: two axes are parallel when the sine
//! of their angle is below 1e-9, they intersect when they are not parallel
//! and the distance between the lines is below 1e-9 m times
//! `max(1, reach)`; three axes meet in one point when each pair intersects
//! and the pairwise meeting points agree to the same distance.
//!
//! ```
//! use armkit::ik::analytic::structure::{ArmStructure, Relation};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let structure = ArmStructure::of_model(&model).unwrap();
//! assert_eq!(structure.relation(1, 2), Relation::Parallel);
//! assert_eq!(structure.relation(2, 3), Relation::Parallel);
//! ```

use crate::error::{Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::math::{Pose, Vector3};
use crate::model::{JointKind, Model};

/// Sine below which two axes count as parallel, and relative distance
/// (1e-9 m per metre of reach, at least 1e-9 m) below which two lines count
/// as intersecting.
pub(crate) const GEOMETRY_TOLERANCE: f64 = 1e-9;

/// How a joint moves, for the analytic solvers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Motion {
    /// Rotation about the axis (rad).
    Rotation,
    /// Translation along the axis (m).
    Translation,
}

/// How two joint axes (lines) lie relative to each other.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Relation {
    /// Parallel (possibly the same line).
    Parallel,
    /// Meet in one point (world frame at zero configuration, m).
    Intersecting(Vector3<f64>),
    /// Skew: neither; the common normal's length, m.
    Skew(f64),
}

/// An arm as lines (product-of-exponentials form): see the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmStructure {
    /// A point on each joint axis, world frame at zero configuration, m.
    pub points: Vec<Vector3<f64>>,
    /// Unit direction of each joint axis (positive joint motion turns
    /// right-handed about it / slides along it), world frame.
    pub axes: Vec<Vector3<f64>>,
    /// How each joint moves.
    pub motions: Vec<Motion>,
    /// End-effector pose at zero configuration, world frame.
    pub home: Pose,
    /// Length scale (m, >= 1) for the intersection tolerance: the sum of the
    /// distances between consecutive axis points and to the end effector.
    pub scale: f64,
}

impl ArmStructure {
    /// The lines of `model` at `q = 0`. Errors: a joint coupling (the chain
    /// is then not a product of exponentials in `q`).
    pub fn of_model(model: &Model) -> Result<ArmStructure> {
        if model.coupling().is_some() {
            return Err(Error::invalid_argument(
                "model",
                format!(
                    "`{}` has a joint coupling: the analytic solvers need independent joints",
                    model.name()
                ),
            ));
        }
        let mut data = Data::new(model);
        let zero = vec![0.0; model.dof()];
        let home = *forward_kinematics(model, &mut data, &zero)?;
        let frames = data.joint_frames();
        let points: Vec<Vector3<f64>> = frames.iter().map(|f| f.translation).collect();
        let axes = frames.iter().map(|f| f.rotation.column(2).into()).collect();
        let motions = model
            .joints()
            .iter()
            .map(|j| match j.kind {
                JointKind::Prismatic => Motion::Translation,
                _ => Motion::Rotation,
            })
            .collect();
        Ok(ArmStructure::from_lines(points, axes, motions, home))
    }

    /// A structure from its lines (points and unit axes, world frame at
    /// zero) and home pose.
    pub fn from_lines(
        points: Vec<Vector3<f64>>,
        axes: Vec<Vector3<f64>>,
        motions: Vec<Motion>,
        home: Pose,
    ) -> ArmStructure {
        let mut scale = 0.0;
        for pair in points.windows(2) {
            scale += (pair[1] - pair[0]).norm();
        }
        if let Some(last) = points.last() {
            scale += (home.translation - last).norm();
        }
        ArmStructure {
            points,
            axes,
            motions,
            home,
            scale: f64::max(1.0, scale),
        }
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.axes.len()
    }

    /// How axes `i` and `j` (0-based) lie. Translation axes are directions
    /// only: two of them, or one with anything, are `Parallel` or `Skew`
    /// by direction alone (a prismatic axis has no fixed line).
    pub fn relation(&self, i: usize, j: usize) -> Relation {
        let (hi, hj) = (self.axes[i], self.axes[j]);
        let normal = hi.cross(&hj);
        let sine = normal.norm();
        if sine < GEOMETRY_TOLERANCE {
            return Relation::Parallel;
        }
        if self.motions[i] == Motion::Translation || self.motions[j] == Motion::Translation {
            return Relation::Skew(f64::INFINITY);
        }
        let (pi, pj) = (self.points[i], self.points[j]);
        let distance = (pj - pi).dot(&normal).abs() / sine;
        if distance > GEOMETRY_TOLERANCE * self.scale {
            return Relation::Skew(distance);
        }
        Relation::Intersecting(closest_point(&pi, &hi, &pj, &hj))
    }

    /// The common point of axes `i`, `j`, `k` if the three meet in one
    /// point (two of them may be the same line, as the shoulder and wrist
    /// of a stretched-out 7-DOF arm): the meeting point of a non-parallel
    /// intersecting pair, through which the third line must pass.
    pub fn common_point(&self, i: usize, j: usize, k: usize) -> Option<Vector3<f64>> {
        let point =
            [(i, j), (j, k), (i, k)]
                .into_iter()
                .find_map(|(a, b)| match self.relation(a, b) {
                    Relation::Intersecting(p) => Some(p),
                    _ => None,
                })?;
        let tolerance = GEOMETRY_TOLERANCE * self.scale;
        [i, j, k]
            .into_iter()
            .all(|l| {
                self.motions[l] == Motion::Rotation && self.distance_to_axis(l, &point) <= tolerance
            })
            .then_some(point)
    }

    /// Distance (m) from `point` to the line of axis `i`.
    pub fn distance_to_axis(&self, i: usize, point: &Vector3<f64>) -> f64 {
        let r = point - self.points[i];
        (r - self.axes[i] * self.axes[i].dot(&r)).norm()
    }

    /// The same arm seen from its end effector: `T(q)^-1` as a chain of the
    /// joints in reverse order, each line mapped by `home^-1` with its
    /// direction reversed, so that joint `n - 1 - i` of the result moves by
    /// the same value as joint `i` of this one (`home^-1 E_i(-t) home` is the
    /// motion by `t` about the mapped, reversed line).
    pub fn reversed(&self) -> ArmStructure {
        let inverse = self.home.inverse();
        let points = self
            .points
            .iter()
            .rev()
            .map(|p| inverse.transform_point(p))
            .collect();
        let axes = self
            .axes
            .iter()
            .rev()
            .map(|h| -(inverse.rotation * h))
            .collect();
        let motions = self.motions.iter().rev().copied().collect();
        ArmStructure::from_lines(points, axes, motions, inverse)
    }

    /// The arm with joint `joint` held at `value` (rad or m): its motion is
    /// folded into the joints after it (their lines moved by it) and the home
    /// pose, leaving a chain of `dof - 1` joints.
    pub fn with_fixed_joint(&self, joint: usize, value: f64) -> ArmStructure {
        let motion = self.motion(joint, value);
        let mut points = Vec::with_capacity(self.dof() - 1);
        let mut axes = Vec::with_capacity(self.dof() - 1);
        let mut motions = Vec::with_capacity(self.dof() - 1);
        for i in 0..self.dof() {
            if i == joint {
                continue;
            }
            let (p, h) = if i > joint {
                (
                    motion.transform_point(&self.points[i]),
                    motion.rotation * self.axes[i],
                )
            } else {
                (self.points[i], self.axes[i])
            };
            points.push(p);
            axes.push(h);
            motions.push(self.motions[i]);
        }
        ArmStructure::from_lines(points, axes, motions, motion * self.home)
    }

    /// The rigid motion `E_i(value)` of joint `i`, world frame.
    pub fn motion(&self, i: usize, value: f64) -> Pose {
        let (h, c) = (self.axes[i], self.points[i]);
        match self.motions[i] {
            Motion::Translation => Pose::from_translation(h * value),
            Motion::Rotation => {
                let r = super::subproblems::rotation(&h, value);
                Pose::new(r, c - r * c)
            }
        }
    }

    /// Forward kinematics of the product of exponentials (for tests and set-up).
    pub fn forward_kinematics(&self, q: &[f64]) -> Pose {
        let mut pose = Pose::identity();
        for (i, value) in q.iter().enumerate().take(self.dof()) {
            pose = pose * self.motion(i, *value);
        }
        pose * self.home
    }

    /// An upper bound on the distance (m) from the first axis's point to the
    /// end effector over every configuration: the sum of the distances
    /// between consecutive axis points and to the end effector, plus the
    /// largest travel of each prismatic joint (`travel[i]`, m; ignored for
    /// rotation joints).
    pub fn reach_bound(&self, travel: &[f64]) -> f64 {
        let mut reach = 0.0;
        for pair in self.points.windows(2) {
            reach += (pair[1] - pair[0]).norm();
        }
        if let Some(last) = self.points.last() {
            reach += (self.home.translation - last).norm();
        }
        for (motion, t) in self.motions.iter().zip(travel) {
            if *motion == Motion::Translation {
                reach += t.abs();
            }
        }
        reach
    }

    /// One line per joint and per consecutive pair, for `--explain`.
    pub fn describe(&self) -> String {
        let mut text = String::new();
        for i in 0..self.dof() {
            let (c, h) = (self.points[i], self.axes[i]);
            let kind = match self.motions[i] {
                Motion::Rotation => "rotation",
                Motion::Translation => "translation",
            };
            text.push_str(&format!(
                "  joint {}: {kind} axis ({:.4}, {:.4}, {:.4}) through ({:.4}, {:.4}, {:.4}) m\n",
                i + 1,
                clean(h.x),
                clean(h.y),
                clean(h.z),
                clean(c.x),
                clean(c.y),
                clean(c.z)
            ));
        }
        for i in 0..self.dof().saturating_sub(1) {
            let relation = match self.relation(i, i + 1) {
                Relation::Parallel => "parallel".to_string(),
                Relation::Intersecting(p) => format!(
                    "intersect at ({:.4}, {:.4}, {:.4}) m",
                    clean(p.x),
                    clean(p.y),
                    clean(p.z)
                ),
                Relation::Skew(d) if d.is_finite() => format!("skew, {d:.4} m apart"),
                Relation::Skew(_) => "skew (a prismatic axis)".to_string(),
            };
            text.push_str(&format!("  axes {} and {}: {relation}\n", i + 1, i + 2));
        }
        text
    }
}

fn clean(v: f64) -> f64 {
    if v.abs() < 5e-13 {
        0.0
    } else {
        v
    }
}

/// The midpoint of the common normal of two non-parallel lines.
fn closest_point(
    p1: &Vector3<f64>,
    h1: &Vector3<f64>,
    p2: &Vector3<f64>,
    h2: &Vector3<f64>,
) -> Vector3<f64> {
    // Minimize |p1 + s h1 - p2 - t h2|: [1 -c; c -1] [s; t] = [h1.r; h2.r], r = p2 - p1.
    let r = p2 - p1;
    let c = h1.dot(h2);
    let (a, b) = (h1.dot(&r), h2.dot(&r));
    let det = 1.0 - c * c;
    let s = (a - c * b) / det;
    let t = (c * a - b) / det;
    0.5 * ((p1 + h1 * s) + (p2 + h2 * t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::forward_kinematics;

    #[test]
    fn product_of_exponentials_matches_the_model() {
        for name in ["ur5", "puma560", "stanford", "panda"] {
            let model = crate::robots::by_name(name).unwrap();
            let structure = ArmStructure::of_model(&model).unwrap();
            let mut data = Data::new(&model);
            let q: Vec<f64> = (0..model.dof()).map(|i| 0.3 * i as f64 - 0.7).collect();
            let expected = *forward_kinematics(&model, &mut data, &q).unwrap();
            let pose = structure.forward_kinematics(&q);
            assert!((pose.rotation - expected.rotation).amax() < 1e-12, "{name}");
            assert!(
                (pose.translation - expected.translation).amax() < 1e-12,
                "{name}"
            );
            // Reversed: the inverse pose.
            let reversed = structure.reversed();
            let back: Vec<f64> = q.iter().rev().copied().collect();
            let inverse = reversed.forward_kinematics(&back);
            let identity = inverse * expected;
            assert!((identity.rotation - crate::math::Matrix3::identity()).amax() < 1e-12);
            assert!(identity.translation.norm() < 1e-12, "{name}");
            // A fixed joint folds in.
            let fixed = structure.with_fixed_joint(2, q[2]);
            let mut rest = q.clone();
            rest.remove(2);
            let folded = fixed.forward_kinematics(&rest);
            assert!((folded.translation - expected.translation).amax() < 1e-12);
        }
    }

    #[test]
    fn puma_has_a_spherical_wrist_and_parallel_shoulder_and_elbow() {
        let model = crate::robots::by_name("puma560").unwrap();
        let s = ArmStructure::of_model(&model).unwrap();
        assert!(s.common_point(3, 4, 5).is_some());
        assert_eq!(s.relation(1, 2), Relation::Parallel);
        assert!(matches!(s.relation(0, 1), Relation::Intersecting(_)));
        assert!(matches!(s.relation(2, 3), Relation::Skew(_)));
    }
}
