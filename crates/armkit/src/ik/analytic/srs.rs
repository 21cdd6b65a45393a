//! 7-DOF arms with a spherical shoulder (axes 1-2-3 meet at S), an elbow
//! (axes 3-4-5 meet at E) and a spherical wrist (axes 5-6-7 meet at W), the
//! KUKA LWR4 / iiwa layout, parameterized by the elbow (arm) angle.
//!
//! The elbow angle `psi` (rad) places E on the circle of points at distance
//! `|SE|` from S and `|EW|` from W: `psi = 0` where E lies in the half-plane
//! spanned by the line SW and the first joint's axis `h1`, increasing
//! right-handed about S -> W. It is undefined when SW is parallel to `h1`
//! (then any normal of SW serves as the reference).

use super::chain::Candidates;
use super::structure::ArmStructure;
use super::subproblems::{rotation, subproblem1_turn, subproblem2_turns, Distance, Spoke};
use super::wrist::WristOrientation;
use crate::math::{Pose, Vector3};

/// The geometry of an SRS arm in fixed-size form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SrsChain {
    h: [Vector3<f64>; 7],
    shoulder: Vector3<f64>,
    elbow: Vector3<f64>,
    wrist: Vector3<f64>,
    home_inverse: Pose,
    /// `home^-1` applied to `h7` and `h6` (the wrist's goal is read
    /// through these two only).
    h7_home: Vector3<f64>,
    h6_home: Vector3<f64>,
    /// Joint 4: `|R4 (w - e) - (s - e)| = |W - S|`; `w - e` turned by it.
    joint4: Distance,
    forearm: Spoke,
    /// `|e - s|`, `|w - e|`.
    upper: f64,
    lower: f64,
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
        let home_inverse = structure.home.inverse();
        SrsChain {
            h,
            shoulder,
            elbow,
            wrist,
            home_inverse,
            h7_home: home_inverse.rotation * h[6],
            h6_home: home_inverse.rotation * h[5],
            joint4: Distance::new(&h[3], &(wrist - elbow), &(shoulder - elbow)),
            forearm: Spoke::new(&h[3], &(wrist - elbow)),
            upper: (elbow - shoulder).norm(),
            lower: (wrist - elbow).norm(),
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
        let (s, e, h) = (self.shoulder, self.elbow, &self.h);
        let wrist_goal = target.transform_point(&self.home_inverse.transform_point(&self.wrist));
        let reach = (wrist_goal - s).norm();
        let (upper, lower) = (self.upper, self.lower);
        // Joint 4 sets the shoulder-wrist distance (subproblem 3, prepared).
        let t4s = self.joint4.solve(reach);
        // The elbow on its circle about SW.
        let (k, x, y) = self.frame(&wrist_goal);
        let along = (upper * upper - lower * lower + reach * reach) / (2.0 * reach);
        let radius2 = upper * upper - along * along;
        let circle_exact = radius2 >= 0.0;
        let (sin, cos) = crate::math::sin_cos(psi);
        let elbow_goal = s + k * along + (x * cos + y * sin) * radius2.max(0.0).sqrt();
        // The wrist's goal (R1 R2 R3 R4)' T home^-1, read through h7 and h6.
        let g7 = target.rotation * self.h7_home;
        let g6 = target.rotation * self.h6_home;
        // R1 R2 (E - S) = E_goal - S (independent of joint 4); axis 3 runs
        // along S -> E.
        let pairs = subproblem2_turns(&-h[0], &(elbow_goal - s), &h[1], &(e - s));
        let forearm_goal = wrist_goal - elbow_goal;
        for (turn1, turn2) in pairs.as_slice() {
            let back = |v: &Vector3<f64>| turn2.rotate_back(&h[1], &turn1.rotate_back(&h[0], v));
            let (forearm_2, g7_2, g6_2) = (back(&forearm_goal), back(&g7), back(&g6));
            for t4 in t4s.as_slice() {
                let w4 = self.forearm.turned(t4);
                let (t3, e3) = subproblem1_turn(&h[2], &w4, &forearm_2);
                let back34 = |v: &Vector3<f64>| t4.rotate_back(&h[3], &t3.rotate_back(&h[2], v));
                let exact = t4s.exact && circle_exact && pairs.exact && e3;
                let prefix = [turn1.angle, turn2.angle, t3.angle, t4.angle];
                self.orientation.solve_directions(
                    &back34(&g7_2),
                    &back34(&g6_2),
                    &prefix,
                    exact,
                    out,
                );
            }
        }
    }
}
