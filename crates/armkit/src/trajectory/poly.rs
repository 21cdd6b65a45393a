//! Polynomials in normalized time `phi in [0, 1]` (seed 002, eq 25): the
//! coefficient formulas of every segment type, evaluation, and real roots.
//!
//! A segment of duration `h` is `q(t) = sum_k c[k] phi^k` with
//! `phi = (t - t_start) / h`. Boundary data enter in normalized units: a
//! physical velocity `v` becomes `V = v h` and an acceleration `a` becomes
//! `A = a h^2` (chain rule, `d/dt = (1/h) d/dphi`). Coefficients are stored
//! ascending, always six of them (unused high orders are zero).
//!
//! The seed prints the coefficient formulas of its quartic and cubic segments
//! garbled (the last quartic's `a_n4` is a copy of `a_n2`); every formula here
//! is derived from its boundary conditions, stated on each function, and the
//! tests check those conditions to 1e-12.

use crate::math::roots::bisect;

/// Six polynomial coefficients, ascending powers of `phi`.
pub(crate) type Coefficients = [f64; 6];

/// Value, first and second derivative with respect to `phi` (Horner).
#[inline(always)]
pub(crate) fn evaluate(c: &Coefficients, phi: f64) -> (f64, f64, f64) {
    let p = c[0] + phi * (c[1] + phi * (c[2] + phi * (c[3] + phi * (c[4] + phi * c[5]))));
    let d = c[1] + phi * (2.0 * c[2] + phi * (3.0 * c[3] + phi * (4.0 * c[4] + phi * 5.0 * c[5])));
    let dd = 2.0 * c[2] + phi * (6.0 * c[3] + phi * (12.0 * c[4] + phi * 20.0 * c[5]));
    (p, d, dd)
}

/// Coefficients of the derivative with respect to `phi`.
pub(crate) fn derivative(c: &Coefficients) -> Coefficients {
    [c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4], 5.0 * c[5], 0.0]
}

/// Value of a polynomial with coefficients `c` (ascending) at `x`.
pub(crate) fn value(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * x + ck)
}

/// Cubic Hermite: `p(0) = p0, p'(0) = v0, p(1) = p1, p'(1) = v1`
/// (seed 002's middle segments, eq 27, with via-point velocities).
pub(crate) fn cubic_hermite(p0: f64, v0: f64, p1: f64, v1: f64) -> Coefficients {
    let d = p1 - p0;
    [
        p0,
        v0,
        3.0 * d - 2.0 * v0 - v1,
        -2.0 * d + v0 + v1,
        0.0,
        0.0,
    ]
}

/// Cubic from its start state and end position:
/// `p(0) = p0, p'(0) = v0, p''(0) = a0, p(1) = p1` (seed 002's first and middle
/// segments of the C2 variant, eqs 26-27).
pub(crate) fn cubic_forward(p0: f64, v0: f64, a0: f64, p1: f64) -> Coefficients {
    [p0, v0, 0.5 * a0, p1 - p0 - v0 - 0.5 * a0, 0.0, 0.0]
}

/// Quartic first segment: `p(0) = p0, p'(0) = v0, p''(0) = a0, p(1) = p1, p'(1) = v1`.
///
/// With `r1 = p1 - p0 - v0 - a0/2` and `r2 = v1 - v0 - a0` the last two
/// coefficients solve `c3 + c4 = r1`, `3 c3 + 4 c4 = r2`:
/// `c3 = 4 r1 - r2 = 4(p1 - p0) - 3 v0 - v1 - a0`,
/// `c4 = r2 - 3 r1 = 3(p0 - p1) + 2 v0 + v1 + a0/2`.
pub(crate) fn quartic_first(p0: f64, v0: f64, a0: f64, p1: f64, v1: f64) -> Coefficients {
    let r1 = p1 - p0 - v0 - 0.5 * a0;
    let r2 = v1 - v0 - a0;
    [p0, v0, 0.5 * a0, 4.0 * r1 - r2, r2 - 3.0 * r1, 0.0]
}

/// Quartic last segment: `p(0) = p0, p'(0) = v0, p(1) = p1, p'(1) = v1, p''(1) = a1`.
///
/// With `r1 = p1 - p0 - v0` and `r2 = v1 - v0`, the system
/// `c2 + c3 + c4 = r1`, `2 c2 + 3 c3 + 4 c4 = r2`, `2 c2 + 6 c3 + 12 c4 = a1`
/// gives `c2 = 6 r1 - 3 r2 + a1/2`, `c3 = 5 r2 - 8 r1 - a1`,
/// `c4 = 3 r1 - 2 r2 + a1/2`. (The seed's `a_n2` and `a_n3` agree; its `a_n4`
/// is misprinted.)
pub(crate) fn quartic_last(p0: f64, v0: f64, p1: f64, v1: f64, a1: f64) -> Coefficients {
    let r1 = p1 - p0 - v0;
    let r2 = v1 - v0;
    [
        p0,
        v0,
        6.0 * r1 - 3.0 * r2 + 0.5 * a1,
        5.0 * r2 - 8.0 * r1 - a1,
        3.0 * r1 - 2.0 * r2 + 0.5 * a1,
        0.0,
    ]
}

/// Quintic with position, velocity and acceleration at both ends (seed 002's
/// last segment of the C2 variant, eq 28; the quintic profile).
pub(crate) fn quintic_hermite(
    p0: f64,
    v0: f64,
    a0: f64,
    p1: f64,
    v1: f64,
    a1: f64,
) -> Coefficients {
    let d = p1 - p0;
    [
        p0,
        v0,
        0.5 * a0,
        10.0 * d - 6.0 * v0 - 4.0 * v1 - 0.5 * (3.0 * a0 - a1),
        -15.0 * d + 8.0 * v0 + 7.0 * v1 + 0.5 * (3.0 * a0 - 2.0 * a1),
        6.0 * d - 3.0 * v0 - 3.0 * v1 - 0.5 * (a0 - a1),
    ]
}

/// Up to five real roots, sorted (no allocation).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Roots {
    values: [f64; 5],
    len: usize,
}

impl Roots {
    fn push(&mut self, r: f64) {
        if self.len < self.values.len() {
            self.values[self.len] = r;
            self.len += 1;
        }
    }

    /// The roots, increasing.
    pub(crate) fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }
}

/// Real roots of the polynomial `c` (ascending, degree up to 5) inside the
/// open interval `(0, 1)`, sorted.
///
/// Recursive and robust: the roots of the derivative split `[0, 1]` into
/// intervals on which the polynomial is monotone; each sign change is then
/// bracketed and bisected to machine precision. A root of even multiplicity
/// (a touch without sign change) is found as a critical point only, which is
/// what the callers (extrema, limit crossings) need. Allocates nothing.
pub(crate) fn roots_in_unit_interval(c: &[f64]) -> Roots {
    let mut roots = Roots::default();
    let degree = match c.iter().take(6).rposition(|&v| v != 0.0) {
        None | Some(0) => return roots,
        Some(d) => d,
    };
    if degree == 1 {
        let r = -c[0] / c[1];
        if r > 0.0 && r < 1.0 {
            roots.push(r);
        }
        return roots;
    }
    let mut d = [0.0; 6];
    for k in 1..=degree {
        d[k - 1] = k as f64 * c[k];
    }
    let critical = roots_in_unit_interval(&d[..degree]);
    let mut left = 0.0;
    let mut f_left = value(c, left);
    for &right in critical.as_slice().iter().chain(std::iter::once(&1.0)) {
        let f_right = value(c, right);
        if f_left == 0.0 && left > 0.0 {
            roots.push(left);
        } else if f_left * f_right < 0.0 {
            roots.push(bisect(|x| value(c, x), left, right, f_left));
        }
        left = right;
        f_left = f_right;
    }
    roots
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(c: &Coefficients, start: (f64, f64, f64), end: (f64, f64, f64), mask: [bool; 6]) {
        let s = evaluate(c, 0.0);
        let e = evaluate(c, 1.0);
        let got = [s.0, s.1, s.2, e.0, e.1, e.2];
        let want = [start.0, start.1, start.2, end.0, end.1, end.2];
        for k in 0..6 {
            if mask[k] {
                assert!(
                    (got[k] - want[k]).abs() < 1e-12,
                    "condition {k}: {got:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn every_segment_type_meets_its_boundary_conditions() {
        let (p0, v0, a0, p1, v1, a1) = (0.3, -1.2, 2.5, -0.7, 0.4, -3.0);
        let all = [true; 6];
        check(
            &quintic_hermite(p0, v0, a0, p1, v1, a1),
            (p0, v0, a0),
            (p1, v1, a1),
            all,
        );
        let c = cubic_hermite(p0, v0, p1, v1);
        check(
            &c,
            (p0, v0, 0.0),
            (p1, v1, 0.0),
            [true, true, false, true, true, false],
        );
        let c = cubic_forward(p0, v0, a0, p1);
        check(
            &c,
            (p0, v0, a0),
            (p1, 0.0, 0.0),
            [true, true, true, true, false, false],
        );
        let c = quartic_first(p0, v0, a0, p1, v1);
        check(
            &c,
            (p0, v0, a0),
            (p1, v1, 0.0),
            [true, true, true, true, true, false],
        );
        let c = quartic_last(p0, v0, p1, v1, a1);
        check(
            &c,
            (p0, v0, 0.0),
            (p1, v1, a1),
            [true, true, false, true, true, true],
        );
    }

    #[test]
    fn roots_are_found_in_the_unit_interval() {
        // (x - 0.2)(x - 0.5)(x - 0.9) = -0.09 + 0.73 x - 1.6 x^2 + x^3
        let roots = roots_in_unit_interval(&[-0.09, 0.73, -1.6, 1.0]);
        let roots = roots.as_slice();
        assert_eq!(roots.len(), 3);
        for (r, e) in roots.iter().zip([0.2, 0.5, 0.9]) {
            assert!((r - e).abs() < 1e-14, "{r} vs {e}");
        }
        // A quintic with two roots in (0, 1) and others outside.
        // (x - 0.3)(x - 0.6)(x + 1)(x - 2)(x - 3)
        let factors = [-0.3, -0.6, 1.0, -2.0, -3.0];
        let mut c = vec![1.0];
        for f in factors {
            let mut next = vec![0.0; c.len() + 1];
            for (k, ck) in c.iter().enumerate() {
                next[k] += ck * f;
                next[k + 1] += ck;
            }
            c = next;
        }
        let roots = roots_in_unit_interval(&c);
        let roots = roots.as_slice();
        assert_eq!(roots.len(), 2);
        assert!((roots[0] - 0.3).abs() < 1e-13 && (roots[1] - 0.6).abs() < 1e-13);
        assert!(roots_in_unit_interval(&[1.0, 0.0, 0.0])
            .as_slice()
            .is_empty());
    }
}
