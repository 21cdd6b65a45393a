//! Trigonometric polynomials of degree 2,
//! `f(phi) = c0 + c1 cos phi + s1 sin phi + c2 cos 2phi + s2 sin 2phi`,
//! and their real roots: the one root finder of subproblem 6
//! ([`super::subproblem6`]) and of the three-axes positioning step
//! ([`super::three_axes`]).
//!
//! Roots. With `phi = phi0 + 2 atan u`, `(1 + u^2)^2 f` is a quartic in `u`
//! whose leading coefficient is `f(phi0 + pi)`; `phi0` is chosen so that
//! this is the largest `|f|` of 8 samples an eighth of a turn apart (no
//! root near `u = infinity`). The quartic's real roots are isolated exactly
//! by the real roots of its derivative (recursively, down to a line): on
//! each monotone interval with a sign change a safeguarded
//! Newton-bisection converges to the last bit; a critical point where the
//! quartic is within [`TANGENT_TOLERANCE`] of zero (of the size of its
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

use super::subproblems::Turn;
use crate::math::roots::{safeguarded_newton, Newton, Tolerance};
use crate::math::{sin_cos, wrap_angle};

/// Angle (rad) below which two polished roots are one.
const SAME_ROOT: f64 = 1e-12;

/// Angle (rad) two roots tracked by [`Trig2::roots_near`] must be apart.
const DISTINCT: f64 = 1e-9;
/// Newton step (rad) after which a tracked root counts as converged.
const CONVERGED: f64 = 1e-13;

/// How far [`Trig2::roots_near`]'s Newton iterations go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Precision {
    /// Until a step is below 1e-13 rad (the error after it is of its
    /// square): roots to the last bits.
    Full,
}

/// Size (relative to the sum of its terms' magnitudes) below which the
/// quartic at one of its critical points counts as zero: a double root.
/// Near-double roots whose quartic value is above it but which have no
/// sign change are not solutions; their answers are at most this far from
/// the equations (forward kinematics then decides).
pub const TANGENT_TOLERANCE: f64 = 1e-13;

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

    /// Up to 4 given turns (the rest dropped) as a set of roots: starts
    /// for [`Trig2::roots_near`] read from elsewhere (e.g. the previous
    /// solutions projected onto the current variable).
    pub(crate) fn of_turns(turns: &[Turn]) -> TrigRoots {
        let mut out = TrigRoots {
            items: [Turn::of_angle(0.0); 4],
            count: turns.len().min(4),
        };
        out.items[..out.count].copy_from_slice(&turns[..out.count]);
        out
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
            items: [Turn {
                angle: 0.0,
                sin: 0.0,
                cos: 1.0,
            }; 4],
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

    /// Every real root, given the roots of a nearby polynomial (the one
    /// before it in a search: same variable, coefficients moved a little):
    /// Newton on `f` from each of them. Accepted only when certain: the
    /// number of real roots, read from the quartic's discriminant and its
    /// two companions `P`, `D` (shift 0), each clear of zero by 4 times a
    /// bound on its round-off, equals the number given, and Newton
    /// from them converges to that many distinct roots (a complete set, in
    /// whatever order). `None` otherwise (a fold between the two: roots
    /// appear or merge), where [`Trig2::roots`] is the answer.
    pub(crate) fn roots_near(&self, previous: &TrigRoots) -> Option<TrigRoots> {
        self.roots_near_to(previous, Precision::Full)
    }

    /// [`Trig2::roots_near`] with Newton stopped at `precision`.
    pub(crate) fn roots_near_to(
        &self,
        previous: &TrigRoots,
        precision: Precision,
    ) -> Option<TrigRoots> {
        if self.real_root_count()? != previous.count {
            return None;
        }
        let mut out = TrigRoots {
            items: [Turn::of_angle(0.0); 4],
            count: 0,
        };
        for start in previous.as_slice() {
            let root = self.newton_from(start, out.as_slice(), precision)?;
            // The chord between two unit directions, about their angle.
            if out
                .as_slice()
                .iter()
                .any(|r| (r.sin - root.sin).abs() + (r.cos - root.cos).abs() < DISTINCT)
            {
                return None;
            }
            out.items[out.count] = root;
            out.count += 1;
        }
        Some(out)
    }

    /// A shift putting `u = infinity` at the quarter turn of largest `|f|`
    /// (the quartic's leading coefficient): a quartic about as well scaled
    /// as [`Trig2::roots`]' at a fraction of the cost.
    pub(crate) fn quarter_shift(&self) -> f64 {
        let values = [
            self.c0 + self.c1 + self.c2,
            self.c0 + self.s1 - self.c2,
            self.c0 - self.c1 + self.c2,
            self.c0 - self.s1 - self.c2,
        ];
        let mut far = 0;
        for (i, v) in values.iter().enumerate() {
            if v.abs() > values[far].abs() {
                far = i;
            }
        }
        far as f64 * std::f64::consts::FRAC_PI_2 - std::f64::consts::PI
    }

    /// The discriminant of the quartic in `u = tan((phi - shift) / 2)`:
    /// negative with 2 real roots, positive with 0 or 4, zero at a double
    /// root (where two roots merge as the coefficients move, it changes
    /// sign).
    #[cfg(test)]
    pub(crate) fn discriminant_about(&self, shift: f64) -> f64 {
        discriminant(&self.shifted(shift).quartic())
    }

    /// The number of real roots (0, 2 or 4) when the quartic in
    /// `tan(phi / 2)` has a clear leading coefficient, discriminant and
    /// (for a positive discriminant) `P` and `D`; `None` near a multiple
    /// root or a root near `phi = pi`.
    fn real_root_count(&self) -> Option<usize> {
        let q = self.shifted(self.quarter_shift()).quartic();
        // Each coefficient is off by up to a few ulps of `f`'s terms (the
        // sums forming it): `delta`. A polynomial in the coefficients is
        // then off by at most its value at `|coefficients| + delta` minus
        // its value at `|coefficients|` (first order), plus its own
        // round-off: the margin each quantity must clear.
        let delta = 8.0 * f64::EPSILON * self.terms();
        let [e, d, c, b, a] = q;
        if a.abs() <= 2.0 * delta {
            return None;
        }
        let clear = |value: f64, exact: f64, widened: f64| {
            let error = (widened - exact) + 32.0 * f64::EPSILON * exact;
            value.abs() > 4.0 * error
        };
        let abs = q.map(f64::abs);
        let wide = abs.map(|x| x + delta);
        let discriminant = discriminant(&q);
        if !clear(
            discriminant,
            discriminant_size(&abs),
            discriminant_size(&wide),
        ) {
            return None;
        }
        if discriminant < 0.0 {
            return Some(2);
        }
        let p = 8.0 * a * c - 3.0 * b * b;
        let p_size = |[_, _, c, b, a]: [f64; 5]| 8.0 * a * c + 3.0 * b * b;
        let dd = 64.0 * a * a * a * e - 16.0 * a * a * c * c + 16.0 * a * b * b * c
            - 16.0 * a * a * b * d
            - 3.0 * b * b * b * b;
        let d_size = |[e, d, c, b, a]: [f64; 5]| {
            64.0 * a * a * a * e
                + 16.0 * a * a * c * c
                + 16.0 * a * b * b * c
                + 16.0 * a * a * b * d
                + 3.0 * b * b * b * b
        };
        let p_clear = clear(p, p_size(abs), p_size(wide));
        let d_clear = clear(dd, d_size(abs), d_size(wide));
        if p_clear && d_clear && p < 0.0 && dd < 0.0 {
            Some(4)
        } else if (p_clear && p > 0.0) || (d_clear && dd > 0.0) {
            Some(0)
        } else {
            None
        }
    }

    /// Newton on `f`, deflated by the roots `found` already (so that it
    /// does not converge to one of them again), from `start` to a root (until a step is below
    /// [`CONVERGED`]: the error after it is of its square), the sine and cosine
    /// carried along (a small step's by its Taylor series); `None` when it
    /// does not converge within 10 steps or wanders off by more than 1
    /// rad.
    fn newton_from(&self, start: &Turn, found: &[Turn], precision: Precision) -> Option<Turn> {
        let (mut s, mut c) = (start.sin, start.cos);
        let mut moved = 0.0_f64;
        for _ in 0..10 {
            let (value, slope) = self.value_and_slope(s, c);
            // Maehly's deflation: Newton on f / prod sin((phi - r) / 2)
            // over the roots `r` found, whose log-derivative is
            // f' / f - sum cot((phi - r) / 2) / 2.
            let mut correction = 0.0;
            for r in found {
                let (sin_x, cos_x) = (s * r.cos - c * r.sin, c * r.cos + s * r.sin);
                if sin_x == 0.0 {
                    return None;
                }
                correction += 0.5 * (1.0 + cos_x) / sin_x;
            }
            let deflated = slope - value * correction;
            if deflated == 0.0 {
                return None;
            }
            let step = -value / deflated;
            if step.is_nan() || step.abs() >= 1.0 {
                return None;
            }
            let (ds, dc) = if step.abs() < 1e-3 {
                let q = step * step;
                (
                    step * (1.0 - q / 6.0 * (1.0 - q / 20.0)),
                    1.0 - q / 2.0 * (1.0 - q / 12.0 * (1.0 - q / 30.0)),
                )
            } else {
                sin_cos(step)
            };
            (s, c) = (s * dc + c * ds, c * dc - s * ds);
            moved += step;
            let converged = match precision {
                Precision::Full => step.abs() < CONVERGED,
            };
            if converged {
                // A root of f itself (not a point the deflation stalls at
                // beside a root found before: there the plain Newton step
                // differs from the deflated one), not far from the start.
                let plain = (value / slope).abs();
                let bound = match precision {
                    Precision::Full => CONVERGED,
                };
                if plain.is_nan() || plain >= bound || moved.abs() > 1.0 {
                    return None;
                }
                // `start.angle` is in [-pi, pi] and `|moved| <= 1`.
                let mut angle = start.angle + moved;
                if angle > std::f64::consts::PI {
                    angle -= std::f64::consts::TAU;
                } else if angle <= -std::f64::consts::PI {
                    angle += std::f64::consts::TAU;
                }
                return Some(Turn {
                    angle,
                    sin: s,
                    cos: c,
                });
            }
        }
        None
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

/// The discriminant of the quartic `q[4] u^4 + ... + q[0]`.
fn discriminant(q: &[f64; 5]) -> f64 {
    discriminant_terms(q, 1.0)
}

/// The sum of the magnitudes of the discriminant's terms for nonnegative
/// coefficients `q`.
fn discriminant_size(q: &[f64; 5]) -> f64 {
    discriminant_terms(q, -1.0)
}

/// The discriminant's 16 terms summed, the negative ones multiplied by
/// `negative` (1: the discriminant; -1 with `q >= 0`: its terms' size).
#[inline]
fn discriminant_terms(q: &[f64; 5], negative: f64) -> f64 {
    let [e, d, c, b, a] = *q;
    let (aa, bb, cc, dd, ee) = (a * a, b * b, c * c, d * d, e * e);
    let positive = 256.0 * aa * a * ee * e
        + 144.0 * aa * c * dd * e
        + 144.0 * a * bb * c * ee
        + 18.0 * a * b * c * dd * d
        + 16.0 * a * cc * cc * e
        + 18.0 * bb * b * c * d * e
        + bb * cc * dd;
    let negatives = 192.0 * aa * b * d * ee
        + 128.0 * aa * cc * ee
        + 27.0 * aa * dd * dd
        + 6.0 * a * bb * dd * e
        + 80.0 * a * b * cc * d * e
        + 4.0 * a * cc * c * dd
        + 27.0 * bb * bb * ee
        + 4.0 * bb * b * dd * d
        + 4.0 * bb * cc * c * e;
    positive - negative * negatives
}

/// Most real roots [`real_roots`] returns (a quartic's 4, with room for
/// tangent points beside them).
const MAX_ROOTS: usize = 4;

/// Real roots (ascending) of `sum p[i] u^i`, `p.len() - 1 <= 4` its degree
/// with `p[last] != 0`: see the module docs.
fn real_roots(p: &[f64]) -> ([f64; MAX_ROOTS], usize) {
    roots_to(p, FULL_PRECISION, 0.0)
}

/// Relative bracket width at which [`real_roots`] stops: a few ulps.
const FULL_PRECISION: f64 = 4.0 * f64::EPSILON;
/// Relative bracket width for the derivatives' roots, which only split the
/// line into monotone pieces (an error `delta` there changes the
/// polynomial's value at a critical point by `O(delta^2)`).
const CRITICAL_PRECISION: f64 = 1e-10;

/// [`real_roots`] with the brackets closed to `precision` (relative);
/// `terms` is the size of the terms `p` was formed from (a trigonometric
/// polynomial's [`Trig2::terms`], 0 for a plain polynomial): `p`'s
/// coefficients carry round-off of that size times `(1 + u^2)^2`, which
/// the tangent test allows for besides `p`'s own terms.
fn roots_to(p: &[f64], precision: f64, terms: f64) -> ([f64; MAX_ROOTS], usize) {
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
    let mut derivative = [0.0; 4];
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
        let (fa, fb) = (evaluate(p, a), evaluate(p, b));
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
            push(bracketed_root(p, a, b, fa, precision), &mut count);
            changed[i] = true;
        }
    }
    // Tangent points: a critical point where p vanishes to round-off
    // without a sign change beside it.
    for j in 0..m {
        let c = points[j + 1];
        let round_off = size(p, c).max(terms * (1.0 + c * c) * (1.0 + c * c));
        if !changed[j] && !changed[j + 1] && evaluate(p, c).abs() <= TANGENT_TOLERANCE * round_off {
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
/// |p[n - i] / p[n]|^(1 / i)` (the last term halved first).
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
            _ => ratio.cbrt(),
        };
        bound = bound.max(term);
    }
    2.0 * bound * (1.0 + 1e-12) + f64::MIN_POSITIVE
}

fn evaluate(p: &[f64], u: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, c| acc * u + c)
}

fn evaluate_slope(p: &[f64], u: f64) -> f64 {
    let mut acc = 0.0;
    for i in (1..p.len()).rev() {
        acc = acc * u + i as f64 * p[i];
    }
    acc
}

/// The sum of the terms' magnitudes at `u`.
fn size(p: &[f64], u: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, c| acc * u.abs() + c.abs())
}

/// The root of `p` in `[a, b]` (monotone there, `fa` and `p(b)` of
/// opposite signs): Newton from the midpoint, falling back to bisection
/// whenever a step leaves the bracket ([`safeguarded_newton`]), until the
/// bracket or the step is `precision` wide relative to `max(1, |u|)`
/// (`u = tan(psi / 2)`, so that is the precision of `psi` near 0 too); at
/// most 200 evaluations.
fn bracketed_root(p: &[f64], a: f64, b: f64, fa: f64, precision: f64) -> f64 {
    let newton = Newton {
        tolerance: Tolerance {
            absolute: precision,
            relative: precision,
        },
        steps: 200,
        stall: 0.0,
    };
    let f = |u: f64| (evaluate(p, u), evaluate_slope(p, u));
    safeguarded_newton(f, (a, b), fa, 0.5 * (a + b), &newton)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::{PI, TAU};

    fn value(f: &Trig2, t: f64) -> f64 {
        let (s, c) = t.sin_cos();
        f.at_direction(s, c)
    }

    fn angles(f: &Trig2) -> Vec<f64> {
        f.roots().as_slice().iter().map(|r| r.angle).collect()
    }

    fn found(roots: &[f64], t: f64, tolerance: f64) -> bool {
        roots.iter().any(|r| wrap_angle(r - t).abs() < tolerance)
    }

    /// `(cos psi - cos a)(cos psi - cos b)` in `psi = t - shift`: roots
    /// `shift +- a`, `shift +- b`.
    fn with_roots(a: f64, b: f64, shift: f64) -> Trig2 {
        let (ca, cb) = (a.cos(), b.cos());
        Trig2 {
            c2: 0.5,
            s2: 0.0,
            c1: -(ca + cb),
            s1: 0.0,
            c0: 0.5 + ca * cb,
        }
        .shifted(-shift)
    }

    #[test]
    fn random_instances_roots_are_roots_and_complete() {
        // Every root found is a root, and every sign change of f on a fine
        // grid (brute force) has a root found inside it.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut total = 0;
        for _ in 0..500 {
            let f = Trig2 {
                c0: rng.gen_range(-1.0..1.0),
                c1: rng.gen_range(-1.0..1.0),
                s1: rng.gen_range(-1.0..1.0),
                c2: rng.gen_range(-1.0..1.0),
                s2: rng.gen_range(-1.0..1.0),
            };
            let roots = f.roots();
            for r in roots.as_slice() {
                assert!(value(&f, r.angle).abs() < 1e-12, "{f:?} {r:?}");
                assert!((r.angle.sin() - r.sin).abs() < 1e-15);
                assert!((r.angle.cos() - r.cos).abs() < 1e-15);
            }
            let angles = angles(&f);
            let grid = 4_000;
            let step = TAU / grid as f64;
            let at = |i: usize| -PI + step * i as f64;
            let mut changes = 0;
            for i in 0..grid {
                if value(&f, at(i)).signum() != value(&f, at(i + 1)).signum() {
                    changes += 1;
                    assert!(
                        angles.iter().any(|&r| wrap_angle(r - at(i)) >= -1e-12
                            && wrap_angle(r - at(i)) <= step + 1e-12),
                        "{f:?}: no root in [{}, {}] among {angles:?}",
                        at(i),
                        at(i + 1)
                    );
                }
            }
            assert!(
                angles.len() >= changes,
                "{f:?}: {angles:?}, {changes} sign changes"
            );
            total += angles.len();
        }
        assert!(total > 500);
    }

    #[test]
    fn known_roots_are_found_to_round_off() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..500 {
            let (a, b): (f64, f64) = (rng.gen_range(0.05..3.1), rng.gen_range(0.05..3.1));
            if (a - b).abs() < 1e-3 {
                continue;
            }
            let shift = rng.gen_range(-PI..PI);
            let f = with_roots(a, b, shift);
            let roots = angles(&f);
            assert_eq!(roots.len(), 4, "{a} {b} {shift}: {roots:?}");
            for t in [shift + a, shift - a, shift + b, shift - b] {
                assert!(found(&roots, t, 1e-12), "{t} not in {roots:?}");
            }
        }
    }

    #[test]
    fn double_roots_are_found_once() {
        // 1 - cos t: double root at 0.
        let f = Trig2 {
            c2: 0.0,
            s2: 0.0,
            c1: -1.0,
            s1: 0.0,
            c0: 1.0,
        };
        let roots = angles(&f);
        assert_eq!(roots.len(), 1, "{roots:?}");
        assert!(roots[0].abs() < 1e-7, "{roots:?}");
        // 1 + cos 2t = 2 cos^2 t: double roots at +-pi/2.
        let f = Trig2 {
            c2: 1.0,
            s2: 0.0,
            c1: 0.0,
            s1: 0.0,
            c0: 1.0,
        };
        let roots = angles(&f);
        assert_eq!(roots.len(), 2, "{roots:?}");
        for t in [PI / 2.0, -PI / 2.0] {
            assert!(found(&roots, t, 1e-7), "{t} not in {roots:?}");
        }
        // Two double roots at random shifted places, and a double root
        // beside two simple ones: with the coefficients rounded, a double
        // root is found once or as two roots within sqrt(eps) of it.
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let mut single = 0;
        for _ in 0..200 {
            let a = rng.gen_range(0.1..3.0);
            let shift = rng.gen_range(-PI..PI);
            for (f, truth, simple) in [
                (with_roots(a, a, shift), vec![shift + a, shift - a], 0),
                (
                    with_roots(a, 0.0, shift),
                    vec![shift + a, shift - a, shift],
                    2,
                ),
            ] {
                let roots = angles(&f);
                for &t in &truth {
                    assert!(found(&roots, t, 1e-6), "{t} not in {roots:?}");
                }
                for &r in &roots {
                    assert!(found(&truth, r, 1e-6), "{r} not one of {truth:?}");
                }
                let doubles = truth.len() - simple;
                assert!(roots.len() >= truth.len() && roots.len() <= simple + 2 * doubles);
                if roots.len() == truth.len() {
                    single += 1;
                }
            }
        }
        assert!(single > 0);
    }

    #[test]
    fn roots_tracked_from_a_nearby_polynomial_are_all_the_roots() {
        // Newton from the roots of a polynomial moved a little: when
        // accepted, the same roots as the full isolation, none missing.
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        let (mut accepted, mut refused) = (0, 0);
        for _ in 0..2000 {
            let mut f = Trig2 {
                c0: rng.gen_range(-1.0..1.0),
                c1: rng.gen_range(-1.0..1.0),
                s1: rng.gen_range(-1.0..1.0),
                c2: rng.gen_range(-1.0..1.0),
                s2: rng.gen_range(-1.0..1.0),
            };
            let previous = f.roots();
            let size = rng.gen_range(0.0..0.05);
            f.c0 += rng.gen_range(-size..size);
            f.c1 += rng.gen_range(-size..size);
            f.s2 += rng.gen_range(-size..size);
            let full = angles(&f);
            match f.roots_near(&previous) {
                Some(tracked) => {
                    accepted += 1;
                    assert_eq!(tracked.as_slice().len(), full.len(), "{f:?}");
                    for r in tracked.as_slice() {
                        assert!(found(&full, r.angle, 1e-12), "{f:?}: {r:?} not in {full:?}");
                        assert!((r.angle.sin() - r.sin).abs() < 1e-14);
                        assert!((r.angle.cos() - r.cos).abs() < 1e-14);
                    }
                }
                None => refused += 1,
            }
        }
        assert!(accepted > 1500, "{accepted} accepted, {refused} refused");
    }

    #[test]
    fn tracking_refuses_double_and_appearing_roots() {
        // An exact double root: the count is uncertain, so the full
        // isolation answers.
        for (a, shift) in [(0.7, 0.3), (1.9, -2.0), (0.2, 3.0)] {
            let double = with_roots(a, a, shift);
            let apart = with_roots(a, a + 0.05, shift);
            assert!(double.roots_near(&apart.roots()).is_none());
            // A near-double pair: refused, or both roots found.
            let near = with_roots(a, a + 1e-7, shift);
            if let Some(tracked) = near.roots_near(&apart.roots()) {
                assert_eq!(tracked.as_slice().len(), 4);
            }
            // Two roots appearing (2 -> 4): the count differs, refused.
            // (Lowered, the double root at `shift` is gone.)
            let two = with_roots(a, 0.0, shift);
            let two = Trig2 {
                c0: two.c0 - 0.01,
                ..two
            };
            assert_eq!(two.roots().as_slice().len(), 2, "{two:?}");
            assert!(apart.roots_near(&two.roots()).is_none());
        }
        // The discriminant's sign: 4 roots, 2, none.
        let shift = 0.4;
        assert!(with_roots(0.5, 2.0, shift).discriminant_about(shift) > 0.0);
        let two = Trig2 {
            c2: 0.0,
            s2: 0.0,
            c1: 1.0,
            s1: 0.0,
            c0: 0.3,
        };
        assert!(two.discriminant_about(two.quarter_shift()) < 0.0);
        assert_eq!(two.real_root_count(), Some(2));
        let none = Trig2 { c0: 1.5, ..two };
        assert_eq!(none.real_root_count(), Some(0));
        assert_eq!(with_roots(0.5, 2.0, shift).real_root_count(), Some(4));
    }

    #[test]
    fn degenerate_polynomials_have_no_roots() {
        let zero = Trig2 {
            c2: 0.0,
            s2: 0.0,
            c1: 0.0,
            s1: 0.0,
            c0: 0.0,
        };
        assert!(zero.roots().as_slice().is_empty());
        assert_eq!(zero.quartic_critical_angles().1, 0);
        let constant = Trig2 { c0: 2.0, ..zero };
        assert!(constant.roots().as_slice().is_empty());
        // 2 + cos t + sin 2t > 0 everywhere.
        let positive = Trig2 {
            c0: 2.0,
            c1: 1.0,
            s2: 0.5,
            ..zero
        };
        assert!(positive.roots().as_slice().is_empty());
        // The least-squares starts: the quartic's critical points (1 or 3).
        let (critical, n) = positive.quartic_critical_angles();
        assert!(n == 1 || n == 3, "{n}");
        assert!(critical[..n].iter().all(|phi| phi.is_finite()));
    }

    #[test]
    fn real_roots_of_polynomials_with_known_roots() {
        // (u - 1)(u + 2)(u - 0.5)(u - 3) and a double root (u - 1)^2 (u^2 + 1).
        let p = [-3.0, 8.5, -4.0, -2.5, 1.0];
        let (roots, n) = real_roots(&p);
        assert_eq!(&roots[..n], &[-2.0, 0.5, 1.0, 3.0]);
        let double = [1.0, -2.0, 2.0, -2.0, 1.0];
        let (roots, n) = real_roots(&double);
        assert!(
            n >= 1 && roots[..n].iter().all(|r| (r - 1.0).abs() < 1e-7),
            "{:?}",
            &roots[..n]
        );
        let none = [1.0, 0.0, 1.0, 0.0, 1.0];
        assert_eq!(real_roots(&none).1, 0);
    }
}
