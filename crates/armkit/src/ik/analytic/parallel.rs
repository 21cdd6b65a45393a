//! Arms with axes 2, 3, 4 parallel and axes 5, 6 intersecting (the
//! Universal Robots family), derived from two invariants: rotations about
//! axes parallel to `h2` keep the `h2` component of every point and of every
//! direction.
//!
//! Everything that depends on the arm alone (the subproblems' fixed
//! vectors, their sinusoids, the axis signs) is read once by
//! [`ThreeParallel::new`]; a solve takes four angles by subproblem 4 in its
//! prepared form, whose sines and cosines come without trigonometry, and
//! the rest by subproblem 1.

use super::chain::{Candidates, Chain};
use super::subproblems::{
    any_normal, rotation_of, subproblem1_turn, Distance, Sinusoid, Spoke, Turn,
};
use crate::math::{Matrix3, Pose, Vector3};

/// The arm-fixed quantities of a three-parallel chain (chain order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ThreeParallel {
    /// Axis 1.
    h1: Vector3<f64>,
    /// `home^-1` applied to the meeting point of axes 5, 6, and its rotation.
    meet_home: Vector3<f64>,
    rotation_home: Matrix3<f64>,
    /// `k . (meet - c1)`: the height every solution keeps (joint 1's equation).
    height: f64,
    /// Joint 5: `k . R5 h6 = d`.
    joint5: Sinusoid,
    /// `meet - c4`, turned by joints 2-4.
    meet_c4: Vector3<f64>,
    /// Joints 2-4 and 6 once joints 1 and 5 are known.
    group: ParallelGroup,
}

impl ThreeParallel {
    /// The solver of `chain` with axes 5, 6 meeting at `meet`.
    pub(crate) fn new(chain: &Chain, meet: &Vector3<f64>) -> ThreeParallel {
        let (c, h) = (&chain.c, &chain.h);
        let k = h[1];
        ThreeParallel {
            h1: h[0],
            meet_home: chain.home_inverse.transform_point(meet),
            rotation_home: chain.home_inverse.rotation,
            height: k.dot(&(meet - c[0])),
            joint5: Sinusoid::new(&k, &h[4], &h[5]),
            meet_c4: meet - c[3],
            group: ParallelGroup::new(chain),
        }
    }

    /// Every solution for `target` (the chain's end-effector pose).
    pub(crate) fn solve(&self, target: &Pose, out: &mut Candidates) {
        let group = &self.group;
        let k = &group.k;
        // Where the meeting point of axes 5 and 6 goes, and R1 R234 R5 R6.
        let p = target.transform_point(&self.meet_home);
        let rd = target.rotation * self.rotation_home;
        // Position: k . R1' (P - c1) = k . (meet - c1)  (subproblem 4).
        let p1 = p - group.c1;
        let t1s = Sinusoid::new(k, &-self.h1, &p1).solve(self.height);
        for t1 in t1s.as_slice() {
            let joint1 = group.after_joint1(t1.angle, &rotation_of(&self.h1, t1), &rd, &p1);
            // Orientation: k' R5 h6 = k' R1' Rd h6  (subproblem 4, prepared).
            let t5s = self.joint5.solve(joint1.rdt_r1_k.dot(&group.h6));
            for t5 in t5s.as_slice() {
                let exact = t1s.exact && t5s.exact;
                group.finish(&joint1, t5, &self.meet_c4, exact, out);
            }
        }
    }
}

/// What the three-parallel classes share once joints 1 and 5 are known
/// (chain order, axes 2-4 parallel to `k = h2`): joint 6 by subproblem 1
/// (`R6 Rd' R1 k = R5' k`), the sum `t2 + t3 + t4` read off `R234`, and the
/// planar 3R of the parallel group (`t3` by subproblem 3, `t2` by
/// subproblem 1, `t4` from the sum).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ParallelGroup {
    /// Axes 5, 6 and the common direction `k = h2` of axes 2-4.
    h5: Vector3<f64>,
    pub(crate) h6: Vector3<f64>,
    pub(crate) k: Vector3<f64>,
    /// Signs of axes 3 and 4 relative to `h2`.
    s3: f64,
    s4: f64,
    /// Points on axes 1, 2, 3.
    pub(crate) c1: Vector3<f64>,
    c2: Vector3<f64>,
    c3: Vector3<f64>,
    /// Joint 3: `|R3 (c4 - c3) - (c2 - c3)| = d`.
    joint3: Distance,
    /// `c4 - c3` turned by joint 3, from `c3`.
    elbow: Spoke,
    /// `R5' k` as joint 5 turns.
    k_by_5: Spoke,
    /// A unit normal of `k` (reads the sum of joints 2-4 off `R234`).
    normal: Vector3<f64>,
    normal_cross: Vector3<f64>,
}

/// The quantities of one joint-1 solution that every joint-5 solution
/// reuses (see [`ParallelGroup::after_joint1`]).
pub(crate) struct AfterJoint1 {
    /// Joint 1's angle, rad.
    angle: f64,
    /// `R1' Rd`.
    r1t_rd: Matrix3<f64>,
    /// `Rd' R1 k`.
    pub(crate) rdt_r1_k: Vector3<f64>,
    /// The wrist point `P` seen before joint 1: `c1 + R1' (P - c1)`.
    goal_before_1: Vector3<f64>,
}

impl ParallelGroup {
    /// The group of `chain` (axes 2-4 parallel).
    pub(crate) fn new(chain: &Chain) -> ParallelGroup {
        let (c, h) = (&chain.c, &chain.h);
        let k = h[1];
        let normal = any_normal(&k);
        ParallelGroup {
            h5: h[4],
            h6: h[5],
            k,
            s3: k.dot(&h[2]).signum(),
            s4: k.dot(&h[3]).signum(),
            c1: c[0],
            c2: c[1],
            c3: c[2],
            joint3: Distance::new(&h[2], &(c[3] - c[2]), &(c[1] - c[2])),
            elbow: Spoke::new(&h[2], &(c[3] - c[2])),
            k_by_5: Spoke::new(&h[4], &k),
            normal,
            normal_cross: k.cross(&normal),
        }
    }

    /// Joint 1 at `angle` (rad) with rotation `r1`, for the goal rotation
    /// `rd` (`R1 R234 R5 R6`) and the wrist point `P` given as `p1 = P - c1`.
    #[inline]
    pub(crate) fn after_joint1(
        &self,
        angle: f64,
        r1: &Matrix3<f64>,
        rd: &Matrix3<f64>,
        p1: &Vector3<f64>,
    ) -> AfterJoint1 {
        AfterJoint1 {
            angle,
            r1t_rd: r1.transpose() * rd,
            rdt_r1_k: rd.transpose() * (r1 * self.k),
            goal_before_1: self.c1 + r1.transpose() * p1,
        }
    }

    /// Joints 6, 2, 3, 4 for joint 1 (`joint1`) and joint 5 (`t5`), the
    /// wrist point being `c4_to_wrist` from `c4` before joints 2-4 turn it
    /// (m); `exact` is the fit of joints 1 and 5. Pushes up to 2 solutions.
    #[inline]
    pub(crate) fn finish(
        &self,
        joint1: &AfterJoint1,
        t5: &Turn,
        c4_to_wrist: &Vector3<f64>,
        exact: bool,
        out: &mut Candidates,
    ) {
        let k = &self.k;
        // R6' R5' k = Rd' R1 k  (subproblem 1).
        let (t6, e6) = subproblem1_turn(&self.h6, &joint1.rdt_r1_k, &self.k_by_5.turned_back(t5));
        let r234 = joint1.r1t_rd
            * rotation_of(&self.h6, &t6).transpose()
            * rotation_of(&self.h5, t5).transpose();
        // R234 = rotation about k by t2 + s3 t3 + s4 t4.
        let turned = r234 * self.normal;
        let t234 = turned
            .dot(&self.normal_cross)
            .atan2(turned.dot(&self.normal));
        // The planar 3R: c2 + R2 (c3 - c2 + R3 (c4 - c3)) = E1' P - R234 (wrist - c4).
        let to_goal = joint1.goal_before_1 - r234 * c4_to_wrist - self.c2;
        let t3s = self.joint3.solve(to_goal.norm());
        for t3 in t3s.as_slice() {
            let x3 = self.c3 + self.elbow.turned(t3);
            let (t2, e2) = subproblem1_turn(k, &(x3 - self.c2), &to_goal);
            let t4 = self.s4 * (t234 - t2.angle - self.s3 * t3.angle);
            let exact = exact && t3s.exact && e6 && e2;
            out.push(
                &[joint1.angle, t2.angle, t3.angle, t4, t5.angle, t6.angle],
                exact,
            );
        }
    }
}
