//! 7-DOF arms with a spherical shoulder (axes 1-2-3 meet at S), an elbow
//! (axes 3-4-5 meet at E) and a spherical wrist (axes 5-6-7 meet at W), the
//! KUKA LWR4 / iiwa layout, parameterized by the elbow (arm) angle.
//!
//! The elbow angle `psi` (rad) places E on the circle of points at distance
//! `|SE|` from S and `|EW|` from W: `psi = 0` where E lies in the half-plane
//! spanned by the line SW and the first joint's axis `h1`, increasing
//! right-handed about S -> W. It is undefined when SW is parallel to `h1`
//! (then any normal of SW serves as the reference).

use super::chain::{Candidates, MAX_JOINTS};
use super::structure::ArmStructure;
use super::subproblems::{rotation, rotation_of, subproblem1, subproblem2_turns, subproblem3};
use super::wrist::WristOrientation;
use crate::math::{Matrix3, Pose, Vector3};

/// The geometry of an SRS arm in fixed-size form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SrsChain {
    h: [Vector3<f64>; 7],
    shoulder: Vector3<f64>,
    elbow: Vector3<f64>,
    wrist: Vector3<f64>,
    home_inverse: Pose,
    orientation: WristOrientation,
}

impl SrsChain {
    pub(crate) fn new(
        structure: &ArmStructure,
        shoulder: Vector3<f64>,
        elbow: Vector3<f64>,
        wrist: Vector3<f64>,
    ) -> SrsChain {
        let mut h = [Vector3::zeros(); 7];
        for (slot, axis) in h.iter_mut().zip(&structure.axes) {
            *slot = *axis;
        }
        SrsChain {
            h,
            shoulder,
            elbow,
            wrist,
            home_inverse: structure.home.inverse(),
            orientation: WristOrientation::new(&h[4], &h[5], &h[6]),
        }
    }

    /// Unit vectors `(k, x, y)`: along S -> `wrist_goal`, and the reference
    /// pair normal to it (`x` toward `h1`, `y = k x x`).
    fn frame(&self, wrist_goal: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let k = (wrist_goal - self.shoulder).normalize();
        let mut x = self.h[0] - k * k.dot(&self.h[0]);
        if x.norm() < 1e-12 {
            x = k.cross(&Vector3::x());
            if x.norm() < 1e-12 {
                x = k.cross(&Vector3::y());
            }
        }
        let x = x.normalize();
        (k, x, k.cross(&x))
    }

    /// The elbow angle (rad) of an elbow at `elbow_goal` with the wrist at `wrist_goal`.
    pub(crate) fn elbow_angle(&self, elbow_goal: &Vector3<f64>, wrist_goal: &Vector3<f64>) -> f64 {
        let (_, x, y) = self.frame(wrist_goal);
        let e = elbow_goal - self.shoulder;
        y.dot(&e).atan2(x.dot(&e))
    }

    /// Where joints 1-7 at `q` put the elbow and wrist points (world).
    pub(crate) fn elbow_and_wrist(&self, q: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
        let s = self.shoulder;
        let r13 =
            rotation(&self.h[0], q[0]) * rotation(&self.h[1], q[1]) * rotation(&self.h[2], q[2]);
        let w4 = self.elbow + rotation(&self.h[3], q[3]) * (self.wrist - self.elbow);
        (s + r13 * (self.elbow - s), s + r13 * (w4 - s))
    }

    /// Every solution at elbow angle `psi` (rad).
    pub(crate) fn solve(&self, target: &Pose, psi: f64, out: &mut Candidates) {
        let (s, e, w, h) = (self.shoulder, self.elbow, self.wrist, &self.h);
        let wrist_goal = target.transform_point(&self.home_inverse.transform_point(&w));
        let reach = (wrist_goal - s).norm();
        let (upper, lower) = ((e - s).norm(), (w - e).norm());
        // Joint 4 sets the shoulder-wrist distance (subproblem 3).
        let t4s = subproblem3(&h[3], &(w - e), &(s - e), reach);
        // The elbow on its circle about SW.
        let (k, x, y) = self.frame(&wrist_goal);
        let along = (upper * upper - lower * lower + reach * reach) / (2.0 * reach);
        let radius2 = upper * upper - along * along;
        let circle_exact = radius2 >= 0.0;
        let (sin, cos) = crate::math::sin_cos(psi);
        let elbow_goal = s + k * along + (x * cos + y * sin) * radius2.max(0.0).sqrt();
        let wrist_rotation = target.rotation * self.home_inverse.rotation;
        for &t4 in t4s.as_slice() {
            let w4 = e + rotation(&h[3], t4) * (w - e);
            // R1 R2 (E - S) = E_goal - S; axis 3 runs along S -> E.
            let pairs = subproblem2_turns(&-h[0], &(elbow_goal - s), &h[1], &(e - s));
            for (turn1, turn2) in pairs.as_slice() {
                let r12 = rotation_of(&h[0], turn1) * rotation_of(&h[1], turn2);
                let (t1, t2) = (turn1.angle, turn2.angle);
                let (t3, e3) = subproblem1(
                    &h[2],
                    &(w4 - e),
                    &(r12.transpose() * (wrist_goal - elbow_goal)),
                );
                let r04: Matrix3<f64> = r12 * rotation(&h[2], t3) * rotation(&h[3], t4);
                let exact = t4s.exact && circle_exact && pairs.exact && e3;
                let mut prefix = [0.0; MAX_JOINTS];
                prefix[..4].copy_from_slice(&[t1, t2, t3, t4]);
                self.orientation.solve(
                    &(r04.transpose() * wrist_rotation),
                    &prefix[..4],
                    exact,
                    out,
                );
            }
        }
    }
}
