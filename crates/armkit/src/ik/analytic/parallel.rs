//! Arms with axes 2, 3, 4 parallel and axes 5, 6 intersecting (the
//! Universal Robots family), derived from two invariants: rotations about
//! axes parallel to `h2` keep the `h2` component of every point and of every
//! direction.

use super::chain::{Candidates, Chain};
use super::subproblems::{rotation, subproblem1, subproblem3, subproblem4};
use crate::math::{Pose, Vector3};

/// Every solution for a chain with `h2 || h3 || h4` and axes 5, 6 meeting at
/// `meet` (zero configuration).
pub(crate) fn solve(chain: &Chain, meet: &Vector3<f64>, target: &Pose, out: &mut Candidates) {
    let (c, h) = (&chain.c, &chain.h);
    let k = h[1];
    // Signs of the parallel axes relative to h2 (they may point either way).
    let s3 = k.dot(&h[2]).signum();
    let s4 = k.dot(&h[3]).signum();
    // Where the meeting point of axes 5 and 6 goes, and R1 R234 R5 R6.
    let p = target.transform_point(&chain.home_inverse.transform_point(meet));
    let rd = target.rotation * chain.home_inverse.rotation;
    // Position: h2 . R1' (P - c1) = h2 . (meet - c1)  (subproblem 4).
    let t1s = subproblem4(&k, &-h[0], &(p - c[0]), k.dot(&(meet - c[0])));
    for &t1 in t1s.as_slice() {
        let r1 = rotation(&h[0], t1);
        let r1t_rd = r1.transpose() * rd;
        // Orientation: h2' R5 h6 = h2' R1' Rd h6  (subproblem 4).
        let t5s = subproblem4(&k, &h[4], &h[5], k.dot(&(r1t_rd * h[5])));
        for &t5 in t5s.as_slice() {
            let r5 = rotation(&h[4], t5);
            // R6' R5' h2 = Rd' R1 h2  (subproblem 1).
            let (t6, e6) = subproblem1(&h[5], &(r1t_rd.transpose() * k), &(r5.transpose() * k));
            let r234 = r1t_rd * rotation(&h[5], t6).transpose() * r5.transpose();
            // The planar 3R: E2 E3 c4 = E1' P - R234 (meet - c4).
            let goal = c[0] + r1.transpose() * (p - c[0]) - r234 * (meet - c[3]);
            let t3s = subproblem3(&h[2], &(c[3] - c[2]), &(c[1] - c[2]), (goal - c[1]).norm());
            for &t3 in t3s.as_slice() {
                let x3 = c[2] + rotation(&h[2], t3) * (c[3] - c[2]);
                let (t2, e2) = subproblem1(&k, &(x3 - c[1]), &(goal - c[1]));
                // R234 = rotation about h2 by t2 + s3 t3 + s4 t4.
                let reference = any_normal(&k);
                let (t234, e234) = subproblem1(&k, &reference, &(r234 * reference));
                let t4 = s4 * (t234 - t2 - s3 * t3);
                let exact = t1s.exact && t5s.exact && t3s.exact && e6 && e2 && e234;
                out.push(&[t1, t2, t3, t4, t5, t6], exact);
            }
        }
    }
}

/// A unit vector normal to the unit vector `k`.
fn any_normal(k: &Vector3<f64>) -> Vector3<f64> {
    let seed = if k.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    k.cross(&seed).normalize()
}
