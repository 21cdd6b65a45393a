//! Real polynomials of degree up to 4 (the quartic a [`super::Trig2`]
//! becomes in `u = tan(psi / 2)`): their real roots, isolated by the real
//! roots of the derivative (recursively, down to a line) and closed by
//! Newton safeguarded by bisection ([`safeguarded_newton`]); tangent points
//! within [`TANGENT_TOLERANCE`] counted as double roots.

use crate::math::roots::{safeguarded_newton, Newton, Tolerance};

/// Size (relative to the sum of its terms' magnitudes) below which the
/// quartic at one of its critical points counts as zero: a double root.
/// Near-double roots whose quartic value is above it but which have no
/// sign change are not solutions; their answers are at most this far from
/// the equations (forward kinematics then decides).
pub(crate) const TANGENT_TOLERANCE: f64 = 1e-13;

/// Most real roots [`real_roots`] returns (a quartic's 4, with room for
/// tangent points beside them).
pub(super) const MAX_ROOTS: usize = 4;

/// Real roots (ascending) of `sum p[i] u^i`, `p.len() - 1 <= 4` its degree
/// with `p[last] != 0`: see the module docs.
pub(super) fn real_roots(p: &[f64]) -> ([f64; MAX_ROOTS], usize) {
    roots_to(p, FULL_PRECISION, 0.0)
}

/// Relative bracket width at which [`real_roots`] stops: a few ulps.
pub(super) const FULL_PRECISION: f64 = 4.0 * f64::EPSILON;
/// Relative bracket width for the derivatives' roots, which only split the
/// line into monotone pieces (an error `delta` there changes the
/// polynomial's value at a critical point by `O(delta^2)`).
const CRITICAL_PRECISION: f64 = 1e-10;

/// [`real_roots`] with the brackets closed to `precision` (relative);
/// `terms` is the size of the terms `p` was formed from (a trigonometric
/// polynomial's [`super::Trig2::terms`], 0 for a plain polynomial): `p`'s
/// coefficients carry round-off of that size times `(1 + u^2)^2`, which
/// the tangent test allows for besides `p`'s own terms.
pub(super) fn roots_to(p: &[f64], precision: f64, terms: f64) -> ([f64; MAX_ROOTS], usize) {
    let mut roots = [0.0; MAX_ROOTS];
    let n = p.len() - 1;
    if n == 0 {
        return (roots, 0);
    }
    if n == 1 {
        roots[0] = -p[0] / p[1];
        return (roots, 1);
    }
    if n == 2 {
        return quadratic_roots(p);
    }
    // Fixed-size copies (zero above the degree): the evaluations in the
    // Newton loop are then unrolled, with the same roundings.
    let mut padded = [0.0; 5];
    padded[..=n].copy_from_slice(p);
    let mut derivative = [0.0; 5];
    for i in 0..n {
        derivative[i] = (i + 1) as f64 * p[i + 1];
    }
    let (critical, m) = roots_to(&derivative[..n], CRITICAL_PRECISION, 0.0);
    let bound = root_bound(p);
    let mut points = [0.0; MAX_ROOTS + 2];
    points[0] = -bound;
    for (slot, c) in points[1..].iter_mut().zip(&critical[..m]) {
        *slot = c.max(-bound).min(bound);
    }
    points[m + 1] = bound;
    let points = &points[..m + 2];
    let mut count = 0;
    let mut push = |root: f64, count: &mut usize| {
        if *count < MAX_ROOTS {
            roots[*count] = root;
            *count += 1;
        }
    };
    let mut changed = [false; MAX_ROOTS + 1];
    for i in 0..m + 1 {
        let (a, b) = (points[i], points[i + 1]);
        let (fa, fb) = (evaluate(&padded, a), evaluate(&padded, b));
        if fa == 0.0 && i > 0 {
            continue; // pushed as the previous interval's end
        }
        if fa == 0.0 {
            push(a, &mut count);
            changed[i] = true;
        } else if fb == 0.0 {
            push(b, &mut count);
            changed[i] = true;
        } else if (fa < 0.0) != (fb < 0.0) {
            let root = bracketed_root(&padded, &derivative, (a, b), fa, precision);
            push(root, &mut count);
            changed[i] = true;
        }
    }
    // Tangent points: a critical point where p vanishes to round-off
    // without a sign change beside it.
    for j in 0..m {
        let c = points[j + 1];
        let round_off = size(&padded, c).max(terms * (1.0 + c * c) * (1.0 + c * c));
        if !changed[j]
            && !changed[j + 1]
            && evaluate(&padded, c).abs() <= TANGENT_TOLERANCE * round_off
        {
            push(c, &mut count);
        }
    }
    roots[..count].sort_unstable_by(f64::total_cmp);
    (roots, count)
}

/// Real roots of `p[0] + p[1] u + p[2] u^2` (`p[2] != 0`), ascending, by
/// the cancellation-free formula; a double root when the discriminant is
/// negative within [`TANGENT_TOLERANCE`] of its terms.
fn quadratic_roots(p: &[f64]) -> ([f64; MAX_ROOTS], usize) {
    let mut roots = [0.0; MAX_ROOTS];
    let (c, b, a) = (p[0], p[1], p[2]);
    let discriminant = b * b - 4.0 * a * c;
    let terms = b * b + (4.0 * a * c).abs();
    if discriminant < 0.0 {
        if discriminant >= -TANGENT_TOLERANCE * terms {
            roots[0] = -b / (2.0 * a);
            return (roots, 1);
        }
        return (roots, 0);
    }
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    if q == 0.0 {
        return (roots, 1); // b = c = 0: the double root 0
    }
    let (r1, r2) = (q / a, c / q);
    roots[0] = r1.min(r2);
    roots[1] = r1.max(r2);
    (roots, 2)
}

/// Fujiwara's bound, a little widened: every root has `|u| < 2 max_i
/// |p[n - i] / p[n]|^(1 / i)` (the last term halved first), with the cube
/// root `r^(1/3)` bounded by `max(r^(1/2), r^(1/4))` (no library call; the
/// Newton starts move a little, the roots do not).
fn root_bound(p: &[f64]) -> f64 {
    let n = p.len() - 1;
    let mut bound = 0.0_f64;
    for i in 1..=n {
        let mut ratio = (p[n - i] / p[n]).abs();
        if i == n {
            ratio *= 0.5;
        }
        let term = match i {
            1 => ratio,
            2 => ratio.sqrt(),
            4 => ratio.sqrt().sqrt(),
            _ => ratio.sqrt().max(ratio.sqrt().sqrt()),
        };
        bound = bound.max(term);
    }
    2.0 * bound * (1.0 + 1e-12) + f64::MIN_POSITIVE
}

/// `sum p[i] u^i` by Horner's rule (`p` zero above its degree).
#[inline]
fn evaluate(p: &[f64; 5], u: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, c| acc * u + c)
}

/// The sum of the terms' magnitudes at `u`.
fn size(p: &[f64; 5], u: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, c| acc * u.abs() + c.abs())
}

/// The root of `p` (derivative `slope`) in `[a, b]` (monotone there, `fa`
/// and `p(b)` of opposite signs): Newton from the midpoint, falling back
/// to bisection whenever a step leaves the bracket
/// ([`safeguarded_newton`]), until the bracket or the step is `precision`
/// wide relative to `max(1, |u|)` (`u = tan(psi / 2)`, so that is the
/// precision of `psi` near 0 too); at most 200 evaluations.
fn bracketed_root(
    p: &[f64; 5],
    slope: &[f64; 5],
    (a, b): (f64, f64),
    fa: f64,
    precision: f64,
) -> f64 {
    let newton = Newton {
        tolerance: Tolerance {
            absolute: precision,
            relative: precision,
        },
        steps: 200,
        stall: 0.0,
    };
    let f = |u: f64| (evaluate(p, u), evaluate(slope, u));
    safeguarded_newton(f, (a, b), fa, 0.5 * (a + b), &newton)
}
