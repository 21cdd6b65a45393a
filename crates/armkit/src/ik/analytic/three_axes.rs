//! Three rotation axes (general lines) carrying a point onto a goal, in
//! closed form: `E_a(t_a) E_b(t_b) E_c(t_c) w = X` (the positioning step of
//! a spherical wrist behind three general axes; IK-Geo calls a problem of
//! this kind its subproblem 5; derived here from the circles, not ported).
//!
//! Joint `b` carries `u = E_c w` onto `v = E_a^-1 X` only if both lie at
//! the same height along `h_b` and at the same distance from `c_b`:
//!
//! * `h_b . (u - c_b) = h_b . (v - c_b)`,
//! * `|u - c_b|^2 = |v - c_b|^2`.
//!
//! A point turning on a circle, `u = u0 + u1 cos t_c + u2 sin t_c`, has both
//! quantities affine in `x_c = (cos t_c, sin t_c)` (`u1 . u2 = 0`,
//! `|u1| = |u2|`), and so has `v` in `x_a`: `A x_c = B x_a + e`, with `A`
//! fixed by the arm. With the better conditioned of `A` and `B` inverted,
//! `x_c = P x_a + m` (or the other way round), and `|x_c| = 1` leaves one
//! trigonometric polynomial of degree 2 in one angle,
//! `f(t) = k0 + k1 cos t + k2 sin t + k3 cos 2t + k4 sin 2t = 0`: a quartic
//! in `tan(t / 2)` (module `trig2`), up to 4 solutions. Joint `b` follows
//! by subproblem 1.

use super::geometry::trig2::Trig2;
use super::subproblems::{subproblem1_turn, Spoke, Turn};
use crate::math::Vector3;
use nalgebra::{Matrix2, Vector2};

/// Relative determinant of `A` (arm-fixed) above which it is inverted;
/// below, `B` is (its conditioning varies with the goal; a goal where both
/// are singular gets no solutions).
const WELL_CONDITIONED: f64 = 1e-2;
/// Relative determinant below which a 2 x 2 system counts as singular.
const SINGULAR: f64 = 1e-10;

/// Three lines `(c, h)` (points and unit directions, in the order applied
/// to the goal: `a` outermost) and the point `w` they carry, read once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ThreeAxes {
    c: [Vector3<f64>; 3],
    h: [Vector3<f64>; 3],
    /// `w - c_c` turned about `h_c`.
    arm_c: Spoke,
    /// `u0 = c_c + par`, `u1 = perp`, `u2 = h_c x (w - c_c)`.
    u: [Vector3<f64>; 3],
    /// `A` and the constant side of `u`: `[h_b . (u0 - c_b), |u0 - c_b|^2 + |u1|^2]`.
    a: Matrix2<f64>,
    /// `A^-1` (when it exists).
    a_inverse: Option<Matrix2<f64>>,
    a0: Vector2<f64>,
    /// Which side is inverted, fixed at set-up: `A` (the polynomial in
    /// `t_a`) unless it is poorly conditioned (axes `b` and `c` nearly
    /// parallel), then `B` (in `t_c`).
    invert_a: bool,
}

/// Up to four solutions `[t_a, t_b, t_c]` as turns (angle, rad, with its
/// sine and cosine).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Placements {
    turns: [[Turn; 3]; 4],
    count: usize,
}

impl Placements {
    /// The placements found (0 to 4).
    pub(crate) fn as_slice(&self) -> &[[Turn; 3]] {
        &self.turns[..self.count]
    }
}

/// The rows `[h . s1, h . s2]` and `[2 (s0 - c) . s1, 2 (s0 - c) . s2]` of a
/// circle `s0 + s1 cos + s2 sin` and its constant side.
fn circle_rows(
    h: &Vector3<f64>,
    c: &Vector3<f64>,
    s: &[Vector3<f64>; 3],
) -> (Matrix2<f64>, Vector2<f64>) {
    let d = s[0] - c;
    (
        Matrix2::new(
            h.dot(&s[1]),
            h.dot(&s[2]),
            2.0 * d.dot(&s[1]),
            2.0 * d.dot(&s[2]),
        ),
        Vector2::new(h.dot(&d), d.norm_squared() + s[1].norm_squared()),
    )
}

/// `|det M|` relative to the product of its row norms (1 for orthogonal rows).
fn conditioning(m: &Matrix2<f64>) -> f64 {
    let rows = (m[(0, 0)].hypot(m[(0, 1)])) * (m[(1, 0)].hypot(m[(1, 1)]));
    if rows > 0.0 {
        m.determinant().abs() / rows
    } else {
        0.0
    }
}

impl ThreeAxes {
    pub(crate) fn new(c: [Vector3<f64>; 3], h: [Vector3<f64>; 3], w: &Vector3<f64>) -> ThreeAxes {
        let arm_c = Spoke::new(&h[2], &(w - c[2]));
        let par = h[2] * h[2].dot(&(w - c[2]));
        let u = [c[2] + par, (w - c[2]) - par, h[2].cross(&(w - c[2]))];
        let (a, a0) = circle_rows(&h[1], &c[1], &u);
        ThreeAxes {
            c,
            h,
            arm_c,
            u,
            a,
            a_inverse: a.try_inverse(),
            a0,
            invert_a: conditioning(&a) > WELL_CONDITIONED,
        }
    }

    /// Every `[t_a, t_b, t_c]` carrying `w` onto `goal` exactly (none when
    /// out of reach, or for a degenerate pair of circles).
    pub(crate) fn solve(&self, goal: &Vector3<f64>) -> Placements {
        let mut out = Placements {
            turns: [[Turn::ZERO; 3]; 4],
            count: 0,
        };
        let Some((k, p, m, v)) = self.system(goal) else {
            return out;
        };
        for root in k.roots().as_slice() {
            // The other angle of `|P x + m| = 1`.
            let x = p * Vector2::new(root.cos, root.sin) + m;
            let other = Turn::of_direction(x.y, x.x);
            let (ta, tc) = if self.invert_a {
                (*root, other)
            } else {
                (other, *root)
            };
            self.push(ta, tc, &v, &mut out);
        }
        out
    }

    /// The polynomial `k(t) = |P x(t) + m|^2 - 1` in the angle of the
    /// inverted side, `P`, `m`, and the circle `v` of the goal about
    /// axis `a`.
    #[allow(clippy::type_complexity)]
    fn system(
        &self,
        goal: &Vector3<f64>,
    ) -> Option<(Trig2, Matrix2<f64>, Vector2<f64>, [Vector3<f64>; 3])> {
        // v(t_a) = c_a + R(h_a, -t_a)(X - c_a) = v0 + v1 cos t_a + v2 sin t_a.
        let (c_a, h_a) = (&self.c[0], &self.h[0]);
        let to_goal = goal - c_a;
        let par = h_a * h_a.dot(&to_goal);
        let v = [c_a + par, to_goal - par, -h_a.cross(&to_goal)];
        let (b, b0) = circle_rows(&self.h[1], &self.c[1], &v);
        let e = b0 - self.a0;
        // A x_c = B x_a + e.
        let (p, m) = if self.invert_a {
            let inverse = self.a_inverse?;
            (inverse * b, inverse * e)
        } else if conditioning(&b) > SINGULAR {
            let inverse = b.try_inverse()?;
            (inverse * self.a, -(inverse * e))
        } else {
            return None;
        };
        Some((circle_poly(&p, &m), p, m, v))
    }

    /// Completes a solution with joint `b` (subproblem 1).
    fn push(&self, ta: Turn, tc: Turn, v: &[Vector3<f64>; 3], out: &mut Placements) {
        let (c, h) = (&self.c, &self.h);
        let u = c[2] + self.arm_c.turned(&tc);
        let va = v[0] + v[1] * ta.cos + v[2] * ta.sin;
        let (tb, _) = subproblem1_turn(&h[1], &(u - c[1]), &(va - c[1]));
        if out.count < 4 {
            out.turns[out.count] = [ta, tb, tc];
            out.count += 1;
        }
    }
}

/// `|P x + m|^2 - 1` for `x = (cos t, sin t)`.
fn circle_poly(p: &Matrix2<f64>, m: &Vector2<f64>) -> Trig2 {
    let s = p.transpose() * p;
    let g = p.transpose() * m;
    Trig2 {
        c0: 0.5 * (s[(0, 0)] + s[(1, 1)]) + m.norm_squared() - 1.0,
        c1: 2.0 * g.x,
        s1: 2.0 * g.y,
        c2: 0.5 * (s[(0, 0)] - s[(1, 1)]),
        s2: s[(0, 1)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::analytic::subproblems::rotation;
    use crate::ik::analytic::test_random::{point, unit};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn three_axes_recover_the_generating_angles() {
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        for _ in 0..2000 {
            let c = [point(&mut rng), point(&mut rng), point(&mut rng)];
            let h = [unit(&mut rng), unit(&mut rng), unit(&mut rng)];
            let w = point(&mut rng) * 2.0;
            let t: [f64; 3] = [
                rng.gen_range(-3.0..3.0),
                rng.gen_range(-3.0..3.0),
                rng.gen_range(-3.0..3.0),
            ];
            let apply = |t: &[f64; 3]| {
                let mut x = w;
                for i in (0..3).rev() {
                    x = c[i] + rotation(&h[i], t[i]) * (x - c[i]);
                }
                x
            };
            let goal = apply(&t);
            let solver = ThreeAxes::new(c, h, &w);
            let found: Vec<[f64; 3]> = solver
                .solve(&goal)
                .as_slice()
                .iter()
                .map(|t| [t[0].angle, t[1].angle, t[2].angle])
                .collect();
            for s in &found {
                assert!((apply(s) - goal).norm() < 1e-9, "{s:?}");
            }
            assert!(
                found.iter().any(|s| s
                    .iter()
                    .zip(&t)
                    .all(|(a, b)| crate::math::wrap_angle(a - b).abs() < 1e-7)),
                "{t:?} not in {found:?}"
            );
        }
    }
}
