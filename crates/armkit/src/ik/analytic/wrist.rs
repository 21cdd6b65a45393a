//! Arms with a spherical wrist: the wrist point is moved by the first three
//! joints only, so position (joints 1-3) and orientation (joints 4-6)
//! decouple (Pieper). Everything here works on a [`Chain`] (lines in the
//! zero configuration, as solved: a wrist at the base is handled on the
//! reversed chain by the caller).

use super::chain::{Candidates, Chain, MAX_JOINTS};
use super::class::Positioning;
use super::subproblems::{
    atan2, same_circle, subproblem1_turn, subproblem2_turns, Distance, Sinusoid, SinusoidFamily,
    Spoke, Turn, RELATIVE_TOLERANCE,
};
use super::three_axes::ThreeAxes;
use crate::math::{Pose, Vector3};

/// The arm-fixed quantities of a spherical-wrist chain, read once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SphericalWrist {
    chain: Chain,
    positioning: Positioning,
    /// The wrist point and the meeting point of the intersecting pair
    /// (zero configuration, chain as solved).
    wrist: Vector3<f64>,
    shoulder: Vector3<f64>,
    /// `home^-1` applied to the wrist point, and to `h6` and `h5` (the
    /// orientation enters the wrist's equations through these two only).
    wrist_home: Vector3<f64>,
    h6_home: Vector3<f64>,
    h5_home: Vector3<f64>,
    /// Parallel axes 2-3: `h2 . (w - c1)`, joint 3's distance equation,
    /// the wrist point turned by joint 3, and the sign of `h3` relative to
    /// `h2` (joints 2 and 3 then turn about one direction by `t2 + s3 t3`).
    height: f64,
    joint1: SinusoidFamily,
    joint3: Distance,
    arm3: Spoke,
    s3: f64,
    /// Joints 4-6.
    orientation: WristOrientation,
    /// Three general rotation axes in front of the wrist: joints 1-3
    /// carrying the wrist point in closed form (None for other positionings;
    /// detection gives a general positioning rotation joints only).
    three_axes: Option<ThreeAxes>,
}

impl SphericalWrist {
    /// The solver of `chain` with axes 4-6 meeting at `wrist`; `shoulder`
    /// is the intersecting pair's point when `positioning` has one.
    pub(crate) fn new(
        chain: &Chain,
        positioning: Positioning,
        wrist: &Vector3<f64>,
        shoulder: &Vector3<f64>,
    ) -> SphericalWrist {
        let (c, h) = (&chain.c, &chain.h);
        SphericalWrist {
            chain: *chain,
            positioning,
            wrist: *wrist,
            shoulder: *shoulder,
            wrist_home: chain.home_inverse.transform_point(wrist),
            h6_home: chain.home_inverse.rotation * h[5],
            h5_home: chain.home_inverse.rotation * h[4],
            height: h[1].dot(&(wrist - c[0])),
            joint1: SinusoidFamily::new(&h[1], &-h[0]),
            joint3: Distance::new(&h[2], &(wrist - c[2]), &(c[1] - c[2])),
            arm3: Spoke::new(&h[2], &(wrist - c[2])),
            s3: h[1].dot(&h[2]).signum(),
            orientation: WristOrientation::new(&h[3], &h[4], &h[5]),
            three_axes: (positioning == Positioning::General
                && !chain.translation[..3].iter().any(|t| *t))
            .then(|| ThreeAxes::new([c[0], c[1], c[2]], [h[0], h[1], h[2]], wrist)),
        }
    }

    /// Every solution for `target` (the chain's end-effector pose).
    pub(crate) fn solve(&self, target: &Pose, out: &mut Candidates) {
        // Joints 4-6 fix the wrist point: E1 E2 E3 w = T home^-1 w; the
        // wrist's goal R4 R5 R6 = (R1 R2 R3)' T home^-1 is needed only
        // applied to h6 and h5.
        let goal = target.transform_point(&self.wrist_home);
        let g6 = target.rotation * self.h6_home;
        let g5 = target.rotation * self.h5_home;
        if self.positioning == Positioning::ParallelSecondThird {
            self.parallel_second_third(&goal, &g6, &g5, out);
            return;
        }
        let (h, translation) = (&self.chain.h, &self.chain.translation);
        // Joints 4-6 behind joints 1-3 at `t`: the wrist's directions
        // turned back by the rotation joints among them.
        let orient = |t: &[Turn; 3], exact: bool, out: &mut Candidates| {
            let (mut v6, mut v5) = (g6, g5);
            for i in (0..3).filter(|&i| !translation[i]) {
                v6 = t[i].rotate_back(&h[i], &v6);
                v5 = t[i].rotate_back(&h[i], &v5);
            }
            let q = [t[0].angle, t[1].angle, t[2].angle];
            self.orientation.solve_directions(&v6, &v5, &q, exact, out);
        };
        if let Some(three) = &self.three_axes {
            // Three general rotation axes: subproblem 5 in closed form
            // (`three_axes`: a quartic, up to 4 placements).
            for t in three.solve(&goal).as_slice() {
                orient(t, true, out);
            }
            return;
        }
        let mut turns = [([Turn::ZERO; 3], false); MAX_POSITIONS];
        let count = position(
            &self.chain,
            self.positioning,
            &self.wrist,
            &self.shoulder,
            &goal,
            &mut turns,
        );
        for (t, exact) in &turns[..count] {
            orient(t, *exact, out);
        }
    }

    /// Axes 2 and 3 parallel (PUMA): rotations about axes parallel to h2
    /// keep the h2 component: h2 . R1' (W - c1) = h2 . (w - c1)
    /// (subproblem 4); the distance from axis 2's point fixes joint 3
    /// (subproblem 3, prepared); joint 2 by subproblem 1. Joints 2 and 3
    /// turn the wrist's directions by `t2 + s3 t3` about `h2`.
    fn parallel_second_third(
        &self,
        goal: &Vector3<f64>,
        g6: &Vector3<f64>,
        g5: &Vector3<f64>,
        out: &mut Candidates,
    ) {
        let (c, h) = (&self.chain.c, &self.chain.h);
        let to_goal = goal - c[0];
        let t1s = self.joint1.of(&to_goal).solve(self.height);
        for t1 in t1s.as_slice() {
            let to_goal1 = t1.rotate_back(&h[0], &to_goal) + (c[0] - c[1]);
            let (g6_1, g5_1) = (t1.rotate_back(&h[0], g6), t1.rotate_back(&h[0], g5));
            let t3s = self.joint3.solve(to_goal1.norm());
            for t3 in t3s.as_slice() {
                let w3 = (c[2] - c[1]) + self.arm3.turned(t3);
                let (t2, e2) = subproblem1_turn(&h[1], &w3, &to_goal1);
                let t23 = t2.plus(&t3.times_sign(self.s3));
                let v6 = t23.rotate_back(&h[1], &g6_1);
                let v5 = t23.rotate_back(&h[1], &g5_1);
                let exact = t1s.exact && t3s.exact && e2;
                let q = [t1.angle, t2.angle, t3.angle];
                self.orientation.solve_directions(&v6, &v5, &q, exact, out);
            }
        }
    }
}

/// The most solutions of joints 1-3 in closed form (two roots of the
/// first subproblem, each giving at most two of the second): the buffer
/// [`position`] fills is this size (zeroing a larger one per solve cost
/// more than 100 instructions).
const MAX_POSITIONS: usize = 4;

/// Joints 1-3 putting the wrist point `w` at `goal` in closed form (every
/// positioning but `ParallelSecondThird`, solved in
/// [`SphericalWrist::parallel_second_third`], and `General`, in
/// `three_axes`), as
/// turns (a sliding joint's `angle` is its slide, m, with the zero turn's
/// sine and cosine); returns how many.
fn position(
    chain: &Chain,
    positioning: Positioning,
    w: &Vector3<f64>,
    o: &Vector3<f64>,
    goal: &Vector3<f64>,
    out: &mut [([Turn; 3], bool); MAX_POSITIONS],
) -> usize {
    let (c, h) = (&chain.c, &chain.h);
    let mut count = 0;
    let mut push = |q: [Turn; 3], exact: bool| {
        if count < out.len() {
            out[count] = (q, exact);
            count += 1;
        }
    };
    // R(k, t) v for a turn t (`rotate_back` by the opposite turn).
    let turned =
        |t: &Turn, k: &Vector3<f64>, v: &Vector3<f64>| t.times_sign(-1.0).rotate_back(k, v);
    match positioning {
        Positioning::ParallelFirstSecond => {
            // h1 . W = h1 . E3 w (subproblem 4 for joint 3).
            let t3s = Sinusoid::new(&h[0], &h[2], &(w - c[2])).solve(h[0].dot(&(goal - c[2])));
            for t3 in t3s.as_slice() {
                let w3 = c[2] + turned(t3, &h[2], &(w - c[2]));
                let t2s =
                    Distance::new(&h[1], &(w3 - c[1]), &(c[0] - c[1])).solve((goal - c[0]).norm());
                for t2 in t2s.as_slice() {
                    let w2 = c[1] + turned(t2, &h[1], &(w3 - c[1]));
                    let (t1, e1) = subproblem1_turn(&h[0], &(w2 - c[0]), &(goal - c[0]));
                    push([t1, *t2, *t3], t3s.exact && t2s.exact && e1);
                }
            }
        }
        Positioning::IntersectingFirstSecond => {
            // Joints 1, 2 turn about lines through o: |E3 w - o| = |W - o|.
            let t3s = Distance::new(&h[2], &(w - c[2]), &(o - c[2])).solve((goal - o).norm());
            for t3 in t3s.as_slice() {
                let w3 = c[2] + turned(t3, &h[2], &(w - c[2]));
                let pairs = subproblem2_turns(&-h[0], &(goal - o), &h[1], &(w3 - o));
                for (t1, t2) in pairs.as_slice() {
                    push([*t1, *t2, *t3], t3s.exact && pairs.exact);
                }
            }
        }
        Positioning::IntersectingSecondThird => {
            // |W - E1 o| = |w - o| (subproblem 3 for joint 1).
            let t1s = Distance::new(&h[0], &(o - c[0]), &(goal - c[0])).solve((w - o).norm());
            for t1 in t1s.as_slice() {
                let goal1 = c[0] + t1.rotate_back(&h[0], &(goal - c[0]));
                let pairs = subproblem2_turns(&-h[1], &(goal1 - o), &h[2], &(w - o));
                for (t2, t3) in pairs.as_slice() {
                    push([*t1, *t2, *t3], t1s.exact && pairs.exact);
                }
            }
        }
        // Solved by `SphericalWrist::parallel_second_third` and `three_axes`.
        Positioning::ParallelSecondThird | Positioning::General => {}
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
                let pairs = subproblem2_turns(&-h[0], &(goal - o), &h[1], &(w3 - o));
                let slide = Turn {
                    angle: d3,
                    ..Turn::ZERO
                };
                for (t1, t2) in pairs.as_slice() {
                    push([*t1, *t2, slide], exact && pairs.exact);
                }
            }
        }
    }
    count
}

/// The last three joints of a spherical wrist (axes `h4`, `h5`, `h6`
/// meeting in one point), read once: `R4 R5 R6 = goal`.
///
/// `R4' h4 = h4` turns the first column condition `R4 R5 h6 = goal h6` into
/// `h4 . R5 h6 = h4 . goal h6` (subproblem 4 for joint 5, prepared), then
/// `R4 (R5 h6) = goal h6` (subproblem 1 for joint 4) and
/// `R6 h5 = (R4 R5)' goal h5` (subproblem 1 for joint 6): one inverse
/// cosine and four arctangents per wrist, no subproblem 2. Only `goal h6`
/// and `goal h5` are read.
///
/// Both subproblems 1 are evaluated from dot products: with
/// `p = R5 h6 = par + cos t5 perp + sin t5 cross` (split once), joint 4's
/// `x = p . g6 - (h4 . p)(h4 . g6)` and `y = h4 . (p x g6) = p . (g6 x h4)`
/// are sums of the three parts' dot products (taken once per goal); joint
/// 6's `v = R5' R4' g5` enters only through `h6 . v = p . u`,
/// `h5 . v = h5 . u` and `(h6 x h5) . v = p . (h5 x u)` with `u = R4' g5`.
///
/// When `h6 = +-h4` and `h5 . h4 = 0` (PUMA, Stanford, KUKA, the iiwa's
/// wrist; [`WristForm::Euler`]) the wrist is a Z-Y-Z Euler wrist in the
/// frame `F = (h5 x h6, h5, h6)`: `R(h4, t) = F Rz(s t) F'` (`s = h4 . h6`),
/// `R5 = F Ry(t5) F'`, `R6 = F Rz(t6) F'`, so `Rz(s t4) Ry(t5) Rz(t6) =
/// M = F' goal F`, whose third column is `F' (goal h6)` and second
/// `F' (goal h5)`: `t5 = atan2(hypot(M13, M23), M33)`, `s t4 =
/// atan2(M23, M13)`, and `t6` from the second column turned back by joints
/// 4 and 5 (`Rz(t6) e2 = Ry(-t5) Rz(-s t4) M e2`, consistent with the
/// computed `t4`, so accurate near `t5 = 0`); three arctangents, no
/// subproblem. The second solution mirrors the first: with
/// `S = R(h4, pi) = R(h6, pi)`, `S R(h5, t) S = R(h5, -t)` (a half turn
/// about `h4` reverses `h5`), so `R4(t4 + pi) R5(-t5) R6(t6 + pi) =
/// R4 S R5(-t5) S R6 = R4 R5 R6`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct WristOrientation {
    h: [Vector3<f64>; 3],
    form: WristForm,
    joint5: Sinusoid,
    /// `h6` turned by joint 5, and `h4 .` its three parts.
    h6_by_5: Spoke,
    h4_dot_parts: [f64; 3],
    /// `|h6|^2`, `h6 . h5` and the distance of `h5` from axis 6.
    h6_length2: f64,
    h6_h5: f64,
    h5_radius: f64,
}

/// How a wrist's joints are found (see [`WristOrientation`]).
#[derive(Clone, Copy, Debug, PartialEq)]
enum WristForm {
    /// `h6 = +-h4`, `h5 . h4 = 0` (unit axes, to [`EULER_TOLERANCE`]):
    /// Z-Y-Z Euler angles in the frame `(h5 x h6, h5, h6)`, the second
    /// solution mirrored from the first.
    Euler {
        /// `h5 x h6`, the frame's first axis.
        first_axis: Vector3<f64>,
        /// `h4 . h6 = +-1`.
        sign: f64,
    },
    /// Subproblem 4 for joint 5, two subproblems 1 per root (any other wrist).
    Subproblems,
}

/// Largest `|h4 x h6|`, `|h4 . h5|` and departure of the axes' squared
/// lengths from 1 for which a wrist is solved as an Euler wrist
/// ([`WristForm::Euler`]): its joints are then off by at most about this
/// angle (rad), two orders below [`super::EXACT_TOLERANCE`]. Axes read from
/// DH tables or URDF files with right angles meet it to round-off (1e-16).
pub(crate) const EULER_TOLERANCE: f64 = 1e-12;

impl WristOrientation {
    pub(crate) fn new(h4: &Vector3<f64>, h5: &Vector3<f64>, h6: &Vector3<f64>) -> WristOrientation {
        let h6_by_5 = Spoke::new(h5, h6);
        let [par, perp, cross] = h6_by_5.parts();
        let h6_h5 = h6.dot(h5);
        let unit = |v: &Vector3<f64>| (v.norm_squared() - 1.0).abs() <= EULER_TOLERANCE;
        let euler = h4.cross(h6).norm() <= EULER_TOLERANCE
            && h4.dot(h5).abs() <= EULER_TOLERANCE
            && unit(h4)
            && unit(h5)
            && unit(h6);
        WristOrientation {
            h: [*h4, *h5, *h6],
            form: if euler {
                WristForm::Euler {
                    first_axis: h5.cross(h6),
                    sign: h4.dot(h6).signum(),
                }
            } else {
                WristForm::Subproblems
            },
            joint5: Sinusoid::new(h4, h5, h6),
            h6_by_5,
            h4_dot_parts: [h4.dot(&par), h4.dot(&perp), h4.dot(&cross)],
            h6_length2: h6.norm_squared(),
            h6_h5,
            h5_radius: (h5.norm_squared() - h6_h5 * h6_h5).max(0.0).sqrt(),
        }
    }

    /// Every `(t4, t5, t6)` with `R4 R5 R6 = goal`, from `goal h6` and
    /// `goal h5` alone (the rest of the goal matrix adds nothing), appended
    /// to the joint values `prefix`.
    #[inline]
    pub(crate) fn solve_directions<const N: usize>(
        &self,
        goal_h6: &Vector3<f64>,
        goal_h5: &Vector3<f64>,
        prefix: &[f64; N],
        exact: bool,
        out: &mut Candidates,
    ) {
        if let WristForm::Euler { first_axis, sign } = &self.form {
            self.solve_euler(first_axis, *sign, goal_h6, goal_h5, prefix, exact, out);
            return;
        }
        let [h4, h5, _] = &self.h;
        let (g6, g5) = (goal_h6, goal_h5);
        let height6 = h4.dot(g6);
        let t5s = self.joint5.solve(height6);
        // Joint 4's dot products, once per goal.
        let [par, perp, cross] = self.h6_by_5.parts();
        let g6_by_h4 = g6.cross(h4);
        let along = [par.dot(g6), perp.dot(g6), cross.dot(g6)];
        let across = [
            par.dot(&g6_by_h4),
            perp.dot(&g6_by_h4),
            cross.dot(&g6_by_h4),
        ];
        let g6_length2 = g6.norm_squared();
        let g6_radius = (g6_length2 - height6 * height6).max(0.0).sqrt();
        let scale4 = self.h6_length2.max(g6_length2);
        // Joint 6's: u = R4' g5 = cos t4 g5 - sin t4 h4 x g5 + (1 - cos t4)(h4 . g5) h4.
        let h4_g5 = h4.cross(g5);
        let h4_dot_g5 = h4.dot(g5);
        let g5_length2 = g5.norm_squared();
        let scale6 = h5.norm_squared().max(g5_length2);
        let n = N;
        let mut q = [0.0; MAX_JOINTS];
        q[..n].copy_from_slice(prefix);
        let combine = |parts: &[f64; 3], t: &Turn| parts[0] + t.cos * parts[1] + t.sin * parts[2];
        // Joints 4 and 6 for one joint-5 turn, and whether both were exact.
        let joints_4_6 = |t5: &Turn| {
            // Joint 4: R4 p = g6 with p = R5 h6.
            let height_p = combine(&self.h4_dot_parts, t5);
            let x = combine(&along, t5) - height_p * height6;
            let y = combine(&across, t5);
            let radius_p = (self.h6_length2 - height_p * height_p).max(0.0).sqrt();
            let e4 = same_circle(height_p, radius_p, height6, g6_radius, scale4);
            let t4 = Turn::of_direction(y, x);
            // Joint 6: R6 h5 = v = R5' u.
            let p = self.h6_by_5.turned(t5);
            let u = g5 * t4.cos - h4_g5 * t4.sin + h4 * ((1.0 - t4.cos) * h4_dot_g5);
            let height_v = p.dot(&u);
            let x6 = h5.dot(&u) - self.h6_h5 * height_v;
            let y6 = p.dot(&h5.cross(&u));
            let radius_v = (g5_length2 - height_v * height_v).max(0.0).sqrt();
            let e6 = same_circle(self.h6_h5, self.h5_radius, height_v, radius_v, scale6);
            (t4.angle, atan2(y6, x6), e4 && e6)
        };
        let exact = exact && t5s.exact;
        for t5 in t5s.as_slice() {
            let (t4, t6, e) = joints_4_6(t5);
            q[n] = t4;
            q[n + 1] = t5.angle;
            q[n + 2] = t6;
            out.push(&q[..n + 3], exact && e);
        }
    }

    /// [`WristOrientation::solve_directions`] for an Euler wrist (see
    /// [`WristOrientation`]): `M`'s third and second columns are `g6` and
    /// `g5` in the frame `(first_axis, h5, h6)`. Exact when `g6` and `g5`
    /// are unit and perpendicular (as `h6` and `h5`) to
    /// [`RELATIVE_TOLERANCE`], as the subproblems' tests would find.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn solve_euler<const N: usize>(
        &self,
        first_axis: &Vector3<f64>,
        sign: f64,
        g6: &Vector3<f64>,
        g5: &Vector3<f64>,
        prefix: &[f64; N],
        exact: bool,
        out: &mut Candidates,
    ) {
        let [_, h5, h6] = &self.h;
        let (m13, m23, m33) = (first_axis.dot(g6), h5.dot(g6), h6.dot(g6));
        let (m12, m22, m32) = (first_axis.dot(g5), h5.dot(g5), h6.dot(g5));
        let exact = exact
            && (g6.norm_squared() - 1.0).abs() <= 2.0 * RELATIVE_TOLERANCE
            && (g5.norm_squared() - 1.0).abs() <= 2.0 * RELATIVE_TOLERANCE
            && g6.dot(g5).abs() <= RELATIVE_TOLERANCE;
        // Joint 5 in [0, pi] (sin t5 >= 0), joint 4 (times `sign`).
        let sine5 = (m13 * m13 + m23 * m23).sqrt();
        let t5 = atan2(sine5, m33);
        let t4 = Turn::of_direction(m23, m13);
        // Joint 6: Rz(t6) e2 = (-sin t6, cos t6, 0) = Ry(-t5) Rz(-t4) M e2.
        let inverse = 1.0 / (sine5 * sine5 + m33 * m33).sqrt().max(f64::MIN_POSITIVE);
        let (s5, c5) = (sine5 * inverse, m33 * inverse);
        let v1 = t4.cos * m12 + t4.sin * m22;
        let v2 = t4.cos * m22 - t4.sin * m12;
        let t6 = atan2(s5 * m32 - c5 * v1, v2);
        let n = N;
        let mut q = [0.0; MAX_JOINTS];
        q[..n].copy_from_slice(prefix);
        q[n] = sign * t4.angle;
        q[n + 1] = t5;
        q[n + 2] = t6;
        out.push(&q[..n + 3], exact);
        // The mirrored solution; at t5 = 0 it is the same configuration
        // family (one solution, as the subproblems give).
        if t5 != 0.0 {
            use std::f64::consts::PI;
            q[n] = sign * t4.angle + PI;
            q[n + 1] = -t5;
            q[n + 2] = t6 + PI;
            out.push(&q[..n + 3], exact);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::subproblems::rotation;
    use super::super::test_random::unit;
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The wrist's solutions as rotations' errors from `goal`, and their
    /// joint values (angles wrapped).
    fn solutions(
        wrist: &WristOrientation,
        goal: &crate::math::Matrix3<f64>,
    ) -> Vec<([f64; 3], f64, bool)> {
        let [h4, h5, h6] = &wrist.h;
        let mut out = Candidates::new();
        wrist.solve_directions(&(goal * h6), &(goal * h5), &[], true, &mut out);
        out.as_slice()
            .iter()
            .map(|c| {
                let q = [c.q[0], c.q[1], c.q[2]];
                let r = rotation(h4, q[0]) * rotation(h5, q[1]) * rotation(h6, q[2]);
                let wrapped = q.map(crate::math::wrap_angle);
                (wrapped, (r - goal).norm(), c.exact)
            })
            .collect()
    }

    /// Wrists with `h6 = +-h4 _|_ h5` are solved as Euler wrists (the
    /// second solution mirrored); both solutions reproduce the goal
    /// rotation and equal the ones the subproblems find (the `Subproblems`
    /// form on the same wrist), on random wrists and goals. Other wrists
    /// are solved by the subproblems.
    #[test]
    fn the_euler_wrist_matches_the_subproblems() {
        let mut rng = ChaCha8Rng::seed_from_u64(23);
        for _ in 0..200 {
            let h4 = unit(&mut rng);
            let h5 = h4.cross(&unit(&mut rng)).normalize();
            let h6 = if rng.r#gen::<bool>() { h4 } else { -h4 };
            let wrist = WristOrientation::new(&h4, &h5, &h6);
            assert!(matches!(wrist.form, WristForm::Euler { .. }));
            let solved = WristOrientation {
                form: WristForm::Subproblems,
                ..wrist
            };
            for _ in 0..20 {
                let t = [0; 3].map(|_| rng.gen_range(-3.0..3.0));
                let goal = rotation(&h4, t[0]) * rotation(&h5, t[1]) * rotation(&h6, t[2]);
                let mirrored = solutions(&wrist, &goal);
                let reference = solutions(&solved, &goal);
                assert_eq!(mirrored.len(), reference.len());
                assert_eq!(mirrored.len(), 2);
                let same = |a: &[f64; 3], b: &[f64; 3]| {
                    a.iter()
                        .zip(b)
                        .all(|(x, y)| crate::math::wrap_angle(x - y).abs() < 1e-11)
                };
                for (a, error, exact) in &mirrored {
                    // Joints 4 and 6 are ill-conditioned as sin t5 -> 0
                    // (only their sum or difference is well defined at 0).
                    let sine = a[1].sin().abs();
                    assert!(*exact && *error < 1e-13 + 1e-14 / sine, "{error:e} {a:?}");
                    if sine < 0.01 {
                        continue;
                    }
                    assert!(
                        reference.iter().any(|(b, _, _)| same(a, b)),
                        "{a:?} vs {reference:?}"
                    );
                }
            }
        }
        // A wrist whose first and last axes differ is solved twice.
        let wrist = WristOrientation::new(&Vector3::x(), &Vector3::y(), &Vector3::z());
        assert_eq!(wrist.form, WristForm::Subproblems);
        let tilted = Vector3::new(1.0, 0.0, 1e-9).normalize();
        let wrist = WristOrientation::new(&Vector3::x(), &Vector3::y(), &tilted);
        assert_eq!(wrist.form, WristForm::Subproblems);
    }
}
