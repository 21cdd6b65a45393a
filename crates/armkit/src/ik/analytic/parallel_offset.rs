//! Arms with axes 2, 3, 4 parallel and the other three general (no
//! intersecting pair needed: a UR-type arm whose wrist axes 5 and 6 are
//! offset), derived from the invariant of rotations about axes parallel to
//! `k = h2`: they keep the `k` component of every point and every
//! direction.
//!
//! With `E_i` joint i's rigid motion (see [`super::structure`]) and `Tc =
//! T home^-1 = E1 ... E6`:
//!
//! * position: `E6` fixes a point `c6` of axis 6, so `E2 E3 E4 (E5 c6) =
//!   E1^-1 Tc c6`; the `k` components of both sides agree:
//!   `k . R5 (c6 - c5) - k . R1' (P - c1) = k . (c1 - c5)`, `P = Tc c6`;
//! * orientation: `R1 R234 R5 R6 = Rd` with `R234 k = k`, applied to `h6`
//!   (which `R6` keeps): `k . R5 h6 - k . R1' Rd h6 = 0`.
//!
//! Two equations in `t1` and `t5` of the form of subproblem 6
//! (`k . R1' p = k . R(-h1, t1) p`): up to 4 pairs. Then `t6` by subproblem
//! 1 (`R6 Rd' R1 k = R5' k`), the sum `t2 + t3 + t4` from `R234`, and the
//! planar 3R of the parallel group: `t3` by subproblem 3, `t2` by
//! subproblem 1, `t4` from the sum: up to 8 solutions.
//!
//! Everything that depends on the arm alone is read once by
//! [`ThreeParallelOffset::new`]; a solve allocates nothing.

use super::chain::{Candidates, Chain};
use super::parallel::ParallelGroup;
use super::subproblem6::{Sinusoids, Wave};
use super::subproblems::{rotation_of, Spoke};
use crate::math::{Matrix3, Pose, Vector3};

/// The arm-fixed quantities of a three-parallel chain without an
/// intersecting end pair (chain order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ThreeParallelOffset {
    /// `-h1` (joint 1 enters as `R1' = R(-h1, t1)`).
    minus_h1: Vector3<f64>,
    /// `home^-1 c6` and `home^-1`'s rotation.
    c6_home: Vector3<f64>,
    rotation_home: Matrix3<f64>,
    /// The `t5` terms of the two equations: `k . R5 (c6 - c5)`, `k . R5 h6`.
    waves5: [Wave; 2],
    /// `k . (c1 - c5)`: the first equation's right side.
    height: f64,
    /// `R5 (c6 - c5)` as joint 5 turns.
    arm5: Spoke,
    /// `c5 - c4`: with `arm5`, where `c6` is before joints 2-4, from `c4`.
    c5_c4: Vector3<f64>,
    /// Joints 2-4 and 6 once joints 1 and 5 are known.
    group: ParallelGroup,
}

impl ThreeParallelOffset {
    /// The solver of `chain` (axes 2-4 parallel, 1 and 5 not parallel to them).
    pub(crate) fn new(chain: &Chain) -> ThreeParallelOffset {
        let (c, h) = (&chain.c, &chain.h);
        let k = h[1];
        let arm = c[5] - c[4];
        ThreeParallelOffset {
            minus_h1: -h[0],
            c6_home: chain.home_inverse.transform_point(&c[5]),
            rotation_home: chain.home_inverse.rotation,
            waves5: [Wave::new(&k, &h[4], &arm), Wave::new(&k, &h[4], &h[5])],
            height: k.dot(&(c[0] - c[4])),
            arm5: Spoke::new(&h[4], &arm),
            c5_c4: c[4] - c[3],
            group: ParallelGroup::new(chain),
        }
    }

    /// Every solution for `target` (the chain's end-effector pose).
    pub(crate) fn solve(&self, target: &Pose, out: &mut Candidates) {
        let group = &self.group;
        // Where c6 goes, and R1 R234 R5 R6.
        let p = target.transform_point(&self.c6_home);
        let rd = target.rotation * self.rotation_home;
        let rd_h6 = rd * group.h6;
        let p1 = p - group.c1;
        let minus_k = -group.k;
        // Subproblem 6 in (t1, t5).
        let system = Sinusoids {
            first: [
                Wave::new(&minus_k, &self.minus_h1, &p1),
                Wave::new(&minus_k, &self.minus_h1, &rd_h6),
            ],
            second: self.waves5,
        };
        let pairs = system.solve([self.height, 0.0]);
        for pair in pairs.as_slice() {
            let (t1, t5) = (&pair.first, &pair.second);
            // R1 = R(h1, t1) = R(-h1, t1)'.
            let r1 = rotation_of(&self.minus_h1, t1).transpose();
            let joint1 = group.after_joint1(t1.angle, &r1, &rd, &p1);
            // c6 from c4 before joints 2-4: c5 - c4 + R5 (c6 - c5).
            let c4_to_c6 = self.c5_c4 + self.arm5.turned(t5);
            group.finish(&joint1, t5, &c4_to_c6, pair.exact, out);
        }
    }
}
