//! Trigonometric polynomials of degree 2,
//! `f(phi) = c0 + c1 cos phi + s1 sin phi + c2 cos 2phi + s2 sin 2phi`,
//! and their real roots: the one root finder of subproblem 6
//! ([`super::subproblem6`]) and of the three-axes positioning step
//! (the analytic solvers' `three_axes`).
//!
//! Roots. With `phi = phi0 + 2 atan u`, `(1 + u^2)^2 f` is a quartic in `u`
//! whose leading coefficient is `f(phi0 + pi)`; `phi0` is chosen so that
//! this is the largest `|f|` of 8 samples an eighth of a turn apart (no
//! root near `u = infinity`). The quartic's real roots are isolated exactly
//! by the real roots of its derivative (recursively, down to a line): on
//! each monotone interval with a sign change a safeguarded
//! Newton-bisection converges to the last bit; a critical point where the
//! quartic is within [`quartic::TANGENT_TOLERANCE`] of zero (of the size of its
//! terms, or of `f`'s terms times `(1 + u^2)^2`: the round-off of forming
//! the quartic from `f`) without a sign change beside it counts as a (double) root. Each
//! `phi` is then polished by Newton on `f` itself (kept while it lowers
//! `|f|`). Unlike a closed-form (Ferrari) quartic, this keeps both roots
//! of a near-double pair and finds exact double roots.
//!
//! ```text
//! let f = Trig2 { c0: 1.0, c1: -1.0, s1: 0.0, c2: 0.0, s2: 0.0 }; // 1 - cos phi
//! assert_eq!(f.roots().as_slice().len(), 1); // the double root phi = 0
//! ```
//! (crate-internal: the runnable version is the unit test
//! `double_roots_are_found_once`).

mod quartic;

use self::quartic::{real_roots, roots_to, FULL_PRECISION};
use super::subproblems::Turn;
use crate::math::{sin_cos, wrap_angle};

/// Angle (rad) below which two polished roots are one.
const SAME_ROOT: f64 = 1e-12;

/// A trigonometric polynomial of degree 2 in an angle `phi` (rad):
/// `c2 cos 2phi + s2 sin 2phi + c1 cos phi + s1 sin phi + c0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Trig2 {
    pub c2: f64,
    pub s2: f64,
    pub c1: f64,
    pub s1: f64,
    pub c0: f64,
}

/// Up to 4 distinct roots of a [`Trig2`], each a [`Turn`] (angle in
/// `[-pi, pi]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TrigRoots {
    items: [Turn; 4],
    count: usize,
}

impl TrigRoots {
    /// The roots found (0 to 4).
    pub(crate) fn as_slice(&self) -> &[Turn] {
        &self.items[..self.count]
    }
}

/// A [`Trig2`] written as a quartic in `u = tan((phi - shift) / 2)`.
struct Shifted {
    /// `phi` of `u = 0`, rad.
    shift: f64,
    /// `f(shift + pi)`, the quartic's leading coefficient (0 only when `f`
    /// vanishes at all 8 samples).
    far_value: f64,
    /// `(1 + u^2)^2 f`, coefficients by ascending power.
    quartic: [f64; 5],
}

impl Trig2 {
    /// `f` at the angle of sine `s` and cosine `c`.
    pub(crate) fn at_direction(&self, s: f64, c: f64) -> f64 {
        let (s2, c2) = (2.0 * s * c, c * c - s * s);
        self.c2 * c2 + self.s2 * s2 + self.c1 * c + self.s1 * s + self.c0
    }

    /// `f` and `df / dphi` at the angle of sine `s` and cosine `c`.
    pub(crate) fn value_and_slope(&self, s: f64, c: f64) -> (f64, f64) {
        let (s2, c2) = (2.0 * s * c, c * c - s * s);
        (
            self.c2 * c2 + self.s2 * s2 + self.c1 * c + self.s1 * s + self.c0,
            2.0 * (self.s2 * c2 - self.c2 * s2) + self.s1 * c - self.c1 * s,
        )
    }

    /// The same polynomial in `psi = phi - shift`.
    fn shifted(&self, shift: f64) -> Trig2 {
        let (s, c) = shift.sin_cos();
        let (s2, c2) = (2.0 * s * c, c * c - s * s);
        // cos(psi + shift) = cos psi c - sin psi s, sin(psi + shift) = sin psi c + cos psi s.
        Trig2 {
            c2: self.c2 * c2 + self.s2 * s2,
            s2: self.s2 * c2 - self.c2 * s2,
            c1: self.c1 * c + self.s1 * s,
            s1: self.s1 * c - self.c1 * s,
            c0: self.c0,
        }
    }

    /// `(1 + u^2)^2 f(2 atan u)`, coefficients by ascending power.
    fn quartic(&self) -> [f64; 5] {
        [
            self.c2 + self.c1 + self.c0,
            4.0 * self.s2 + 2.0 * self.s1,
            -6.0 * self.c2 + 2.0 * self.c0,
            -4.0 * self.s2 + 2.0 * self.s1,
            self.c2 - self.c1 + self.c0,
        ]
    }

    /// The sum of the magnitudes of `f`'s coefficients (a bound on `|f|`).
    fn terms(&self) -> f64 {
        self.c0.abs() + self.c1.abs() + self.s1.abs() + self.c2.abs() + self.s2.abs()
    }

    /// The quartic about the sample (of 8) of largest `|f|`.
    fn about_largest_sample(&self) -> Shifted {
        let mut far = 0.0;
        let mut far_value = 0.0_f64;
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let directions = [
            (0.0, 1.0),
            (h, h),
            (1.0, 0.0),
            (h, -h),
            (0.0, -1.0),
            (-h, -h),
            (-1.0, 0.0),
            (-h, h),
        ];
        for (i, (s, c)) in directions.into_iter().enumerate() {
            let v = self.at_direction(s, c);
            if v.abs() > far_value.abs() {
                far = i as f64 * std::f64::consts::FRAC_PI_4;
                far_value = v;
            }
        }
        let shift = far - std::f64::consts::PI;
        Shifted {
            shift,
            far_value,
            quartic: self.shifted(shift).quartic(),
        }
    }

    /// Every real root (see the module docs), polished; none when `f`
    /// vanishes at all 8 samples (`f = 0`, or degenerate to round-off).
    pub(crate) fn roots(&self) -> TrigRoots {
        let mut out = TrigRoots {
            items: [Turn::ZERO; 4],
            count: 0,
        };
        let shifted = self.about_largest_sample();
        if shifted.far_value == 0.0 {
            return out;
        }
        let (roots, count) = roots_to(&shifted.quartic, FULL_PRECISION, self.terms());
        for u in &roots[..count] {
            let (angle, sin, cos) = self.polish(shifted.shift + 2.0 * u.atan());
            let angle = wrap_angle(angle);
            // Two roots of a near-double pair polished onto one angle count once.
            if out
                .as_slice()
                .iter()
                .any(|r| wrap_angle(r.angle - angle).abs() < SAME_ROOT)
            {
                continue;
            }
            out.items[out.count] = Turn { angle, sin, cos };
            out.count += 1;
        }
        out
    }

    /// The angles (rad, up to 3) of the critical points of the quartic in
    /// `u` (see the module docs): where `|f|` is locally nearest zero on
    /// the circle, starts for a least-squares search when `f` has no root.
    pub(crate) fn quartic_critical_angles(&self) -> ([f64; 3], usize) {
        let shifted = self.about_largest_sample();
        let p = &shifted.quartic;
        let mut out = [0.0; 3];
        if p[4] == 0.0 {
            return (out, 0);
        }
        let (critical, count) = real_roots(&[p[1], 2.0 * p[2], 3.0 * p[3], 4.0 * p[4]]);
        let count = count.min(3);
        for (slot, u) in out.iter_mut().zip(&critical[..count]) {
            *slot = shifted.shift + 2.0 * u.atan();
        }
        (out, count)
    }

    /// Newton on `f` (at most 3 steps), kept while it lowers `|f|`;
    /// returns the angle with its sine and cosine.
    fn polish(&self, phi: f64) -> (f64, f64, f64) {
        let (s, c) = sin_cos(phi);
        let mut best = (phi, s, c);
        let (mut value, mut slope) = self.value_and_slope(s, c);
        for _ in 0..3 {
            if slope == 0.0 || value == 0.0 {
                break;
            }
            let next = best.0 - value / slope;
            let (s, c) = sin_cos(next);
            let (next_value, next_slope) = self.value_and_slope(s, c);
            if next_value.abs() >= value.abs() {
                break;
            }
            best = (next, s, c);
            value = next_value;
            slope = next_slope;
        }
        best
    }
}

#[cfg(test)]
mod tests;
