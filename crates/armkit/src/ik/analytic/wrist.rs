//! Arms with a spherical wrist: the wrist point is moved by the first three
//! joints only, so position (joints 1-3) and orientation (joints 4-6)
//! decouple (Pieper). Everything here works on a [`Chain`] (lines in the
//! zero configuration, as solved: a wrist at the base is handled on the
//! reversed chain by the caller).

use super::chain::{Candidates, Chain, MAX_JOINTS};
use super::class::Positioning;
use super::subproblems::{rotation, subproblem1, subproblem2, subproblem3, subproblem4};
use crate::math::{Matrix3, Pose, Vector3};

/// Every solution for a 6-joint chain whose axes 4, 5, 6 meet at `wrist`
/// (zero configuration); `shoulder` is the meeting point of the
/// intersecting pair among joints 1-3 when `positioning` has one.
pub(crate) fn solve(
    chain: &Chain,
    positioning: Positioning,
    wrist: &Vector3<f64>,
    shoulder: &Vector3<f64>,
    target: &Pose,
    out: &mut Candidates,
) {
    // Joints 4-6 fix the wrist point: E1 E2 E3 w = T home^-1 w.
    let goal = target.transform_point(&chain.home_inverse.transform_point(wrist));
    let mut positions = [([0.0; 3], false); 16];
    let count = position(chain, positioning, wrist, shoulder, &goal, &mut positions);
    let wrist_goal = target.rotation * chain.home_inverse.rotation;
    for &(q, exact) in &positions[..count] {
        let r03 = chain.rotation(0, q[0]) * chain.rotation(1, q[1]) * chain.rotation(2, q[2]);
        let h = &chain.h;
        orientation(
            [&h[3], &h[4], &h[5]],
            &(r03.transpose() * wrist_goal),
            &q,
            exact,
            out,
        );
    }
}

/// Joints 1-3 putting the wrist point `w` at `goal`; returns how many.
fn position(
    chain: &Chain,
    positioning: Positioning,
    w: &Vector3<f64>,
    o: &Vector3<f64>,
    goal: &Vector3<f64>,
    out: &mut [([f64; 3], bool); 16],
) -> usize {
    if positioning == Positioning::General {
        return super::search::position(chain, w, goal, out);
    }
    let (c, h) = (&chain.c, &chain.h);
    let mut count = 0;
    let mut push = |q: [f64; 3], exact: bool| {
        if count < out.len() {
            out[count] = (q, exact);
            count += 1;
        }
    };
    match positioning {
        Positioning::ParallelSecondThird => {
            // Rotations about axes parallel to h2 keep the h2 component:
            // h2 . R1' (W - c1) = h2 . (w - c1) (subproblem 4).
            let t1s = subproblem4(&h[1], &-h[0], &(goal - c[0]), h[1].dot(&(w - c[0])));
            for &t1 in t1s.as_slice() {
                let goal1 = c[0] + rotation(&h[0], t1).transpose() * (goal - c[0]);
                // Distance from axis 2's point fixes joint 3 (subproblem 3).
                let t3s = subproblem3(&h[2], &(w - c[2]), &(c[1] - c[2]), (goal1 - c[1]).norm());
                for &t3 in t3s.as_slice() {
                    let w3 = c[2] + rotation(&h[2], t3) * (w - c[2]);
                    let (t2, e2) = subproblem1(&h[1], &(w3 - c[1]), &(goal1 - c[1]));
                    push([t1, t2, t3], t1s.exact && t3s.exact && e2);
                }
            }
        }
        Positioning::ParallelFirstSecond => {
            // h1 . W = h1 . E3 w (subproblem 4 for joint 3).
            let t3s = subproblem4(&h[0], &h[2], &(w - c[2]), h[0].dot(&(goal - c[2])));
            for &t3 in t3s.as_slice() {
                let w3 = c[2] + rotation(&h[2], t3) * (w - c[2]);
                let t2s = subproblem3(&h[1], &(w3 - c[1]), &(c[0] - c[1]), (goal - c[0]).norm());
                for &t2 in t2s.as_slice() {
                    let w2 = c[1] + rotation(&h[1], t2) * (w3 - c[1]);
                    let (t1, e1) = subproblem1(&h[0], &(w2 - c[0]), &(goal - c[0]));
                    push([t1, t2, t3], t3s.exact && t2s.exact && e1);
                }
            }
        }
        Positioning::IntersectingFirstSecond => {
            // Joints 1, 2 turn about lines through o: |E3 w - o| = |W - o|.
            let t3s = subproblem3(&h[2], &(w - c[2]), &(o - c[2]), (goal - o).norm());
            for &t3 in t3s.as_slice() {
                let w3 = c[2] + rotation(&h[2], t3) * (w - c[2]);
                let pairs = subproblem2(&-h[0], &(goal - o), &h[1], &(w3 - o));
                for &(t1, t2) in pairs.as_slice() {
                    push([t1, t2, t3], t3s.exact && pairs.exact);
                }
            }
        }
        Positioning::IntersectingSecondThird => {
            // |W - E1 o| = |w - o| (subproblem 3 for joint 1).
            let t1s = subproblem3(&h[0], &(o - c[0]), &(goal - c[0]), (w - o).norm());
            for &t1 in t1s.as_slice() {
                let goal1 = c[0] + rotation(&h[0], t1).transpose() * (goal - c[0]);
                let pairs = subproblem2(&-h[1], &(goal1 - o), &h[2], &(w - o));
                for &(t2, t3) in pairs.as_slice() {
                    push([t1, t2, t3], t1s.exact && pairs.exact);
                }
            }
        }
        Positioning::General => {}
        Positioning::PrismaticThird => {
            // |w + d h3 - o|^2 = |W - o|^2: d^2 + 2 b d + (|w - o|^2 - |W - o|^2) = 0.
            let b = h[2].dot(&(w - o));
            let discriminant = b * b - ((w - o).norm_squared() - (goal - o).norm_squared());
            let exact = discriminant >= 0.0;
            let root = discriminant.max(0.0).sqrt();
            let slides = [-b + root, -b - root];
            let slides = if root > 0.0 {
                &slides[..]
            } else {
                &slides[..1]
            };
            for &d3 in slides {
                let w3 = w + h[2] * d3;
                let pairs = subproblem2(&-h[0], &(goal - o), &h[1], &(w3 - o));
                for &(t1, t2) in pairs.as_slice() {
                    push([t1, t2, d3], exact && pairs.exact);
                }
            }
        }
    }
    count
}

/// The last three joints, axes `h` meeting in one point, with
/// `R(h[0]) R(h[1]) R(h[2]) = goal`, appended to the joint values `prefix`
/// (subproblems 2 and 1).
pub(crate) fn orientation(
    h: [&Vector3<f64>; 3],
    goal: &Matrix3<f64>,
    prefix: &[f64],
    exact: bool,
    out: &mut Candidates,
) {
    // R4 R5 h6 = goal h6.
    let pairs = subproblem2(&-h[0], &(goal * h[2]), h[1], h[2]);
    let n = prefix.len();
    let mut q = [0.0; MAX_JOINTS];
    q[..n].copy_from_slice(prefix);
    for &(t4, t5) in pairs.as_slice() {
        let r45 = rotation(h[0], t4) * rotation(h[1], t5);
        let (t6, e6) = subproblem1(h[2], h[1], &(r45.transpose() * goal * h[1]));
        q[n] = t4;
        q[n + 1] = t5;
        q[n + 2] = t6;
        out.push(&q[..n + 3], exact && pairs.exact && e6);
    }
}
