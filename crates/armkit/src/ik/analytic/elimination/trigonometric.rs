//! The determinant's trigonometric polynomial in joint 3 and its real
//! roots: certified isolation by Hermite bounds, the quiet stretches scanned
//! on the determinant itself, double roots split.

use super::{
    DET_SAMPLES, HARMONICS, QUIET, QUIET_REFINEMENTS, QUIET_STEPS, ROOT_SAMPLES, ROUNDING, TANGENT,
};
use crate::math::roots::{regula_falsi, safeguarded_newton, Newton, Tolerance};
use crate::math::sin_cos;
use std::f64::consts::TAU;

/// Width (rad) to which the bracket of a root is closed.
const ROOT_WIDTH: f64 = 1e-15;

/// `a0 + sum_k (a_k cos k t + b_k sin k t)`, `k = 1..8`.
pub(super) struct Trigonometric {
    pub(super) cosines: [f64; HARMONICS + 1],
    pub(super) sines: [f64; HARMONICS + 1],
}

impl Trigonometric {
    /// The polynomial through `samples` at `t_j = 2 pi j / 17` (a discrete
    /// Fourier transform; `table[j][k] = (cos, sin)(k t_j)`).
    pub(super) fn of_samples(
        samples: &[f64; DET_SAMPLES],
        table: &[[(f64, f64); HARMONICS + 1]; DET_SAMPLES],
    ) -> Trigonometric {
        let mut polynomial = Trigonometric {
            cosines: [0.0; HARMONICS + 1],
            sines: [0.0; HARMONICS + 1],
        };
        let n = DET_SAMPLES as f64;
        for (sample, row) in samples.iter().zip(table) {
            for (k, (c, s)) in row.iter().enumerate() {
                polynomial.cosines[k] += sample * c;
                polynomial.sines[k] += sample * s;
            }
        }
        polynomial.cosines[0] /= n;
        polynomial.sines[0] = 0.0;
        for k in 1..=HARMONICS {
            polynomial.cosines[k] *= 2.0 / n;
            polynomial.sines[k] *= 2.0 / n;
        }
        polynomial
    }

    /// Value and first two derivatives at `t`.
    pub(super) fn at(&self, t: f64) -> [f64; 3] {
        let (s1, c1) = sin_cos(t);
        let (mut c, mut s) = (1.0, 0.0);
        let mut out = [self.cosines[0], 0.0, 0.0];
        for k in 1..=HARMONICS {
            (c, s) = (c * c1 - s * s1, s * c1 + c * s1);
            let (a, b, kf) = (self.cosines[k], self.sines[k], k as f64);
            out[0] += a * c + b * s;
            out[1] += kf * (b * c - a * s);
            out[2] -= kf * kf * (a * c + b * s);
        }
        out
    }

    /// Value and derivative at sample `j` of `ROOT_SAMPLES` per turn.
    pub(super) fn at_sample(&self, table: &[(f64, f64); ROOT_SAMPLES], j: usize) -> [f64; 2] {
        let mut out = [self.cosines[0], 0.0];
        for k in 1..=HARMONICS {
            let (c, s) = table[(k * j) % ROOT_SAMPLES];
            let (a, b, kf) = (self.cosines[k], self.sines[k], k as f64);
            out[0] += a * c + b * s;
            out[1] += kf * (b * c - a * s);
        }
        out
    }

    /// The real roots in `[0, 2 pi)` into `roots` (see the module docs);
    /// how many.
    ///
    /// Where two neighbouring samples are both below [`QUIET`] of the
    /// largest, the interpolation's rounding (relative to the largest
    /// sample) may hide or invent sign changes: there `determinant` (the
    /// function interpolated, evaluated directly: accurate relative to its
    /// own size) is scanned instead ([`scan_directly`]).
    pub(super) fn roots(
        &self,
        table: &[(f64, f64); ROOT_SAMPLES],
        determinant: &dyn Fn(f64) -> f64,
        roots: &mut [f64],
    ) -> usize {
        let mut samples = [[0.0; 2]; ROOT_SAMPLES];
        for (j, sample) in samples.iter_mut().enumerate() {
            *sample = self.at_sample(table, j);
        }
        let largest = samples.iter().map(|s| s[0].abs()).fold(0.0, f64::max);
        if largest == 0.0 || !largest.is_finite() {
            return 0;
        }
        // The fourth derivative's bound bounds the cubic Hermite
        // interpolants' errors in `isolate`; the second's, the cheap test.
        let fourth = derivative_bound(&self.cosines, &self.sines, 4);
        let second = derivative_bound(&self.cosines, &self.sines, 2);
        let mut found = Found {
            roots,
            count: 0,
            fourth,
            second,
            noise: ROUNDING * largest,
        };
        let step = TAU / ROOT_SAMPLES as f64;
        for j in 0..ROOT_SAMPLES {
            let start = Knot {
                t: step * j as f64,
                value: samples[j][0],
                slope: samples[j][1],
            };
            if start.value == 0.0 {
                found.push(start.t);
                continue;
            }
            let [value, slope] = samples[(j + 1) % ROOT_SAMPLES];
            let end = Knot {
                t: step * (j + 1) as f64,
                value,
                slope,
            };
            if start.value.abs().max(end.value.abs()) < QUIET * largest {
                scan_directly(determinant, (start.t, end.t), QUIET_REFINEMENTS, &mut found);
            } else {
                self.isolate(&start, &end, &mut found);
            }
        }
        found.count
    }

    /// The roots in `(start.t, end.t)` (values and slopes known at both
    /// ends): none when the cubic Hermite interpolant stays farther from
    /// zero than its error bound (the fourth derivative's bound times
    /// `h^4 / 384`); one, refined, when the ends differ in sign and the
    /// interpolant's slope stays away from zero by more than its error bound
    /// (times `h^3 / 72`); otherwise the interval is halved, down to
    /// [`SMALLEST_INTERVAL`], where a sign change gives one root and an
    /// interpolant reaching the bound a double-root candidate.
    pub(super) fn isolate(&self, start: &Knot, end: &Knot, found: &mut Found) {
        let h = end.t - start.t;
        // Cheap first: within h/2 of an end the polynomial moves at most
        // |slope| h/2 + max|p''| h^2/8; farther from zero than that (and
        // than TANGENT of itself) at both ends of one sign, no root here.
        let reach = |knot: &Knot| knot.slope.abs() * h / 2.0 + found.second * h * h / 8.0;
        if start.value * end.value > 0.0
            && start.value.abs() - reach(start) > TANGENT * start.value.abs()
            && end.value.abs() - reach(end) > TANGENT * end.value.abs()
        {
            return;
        }
        let cubic = Hermite::new(start, end);
        let (low, high) = cubic.value_range();
        let (value_error, slope_error) = hermite_error_bounds(found.fourth, h);
        if low > value_error || high < -value_error {
            // No root, but one of a pair made complex by rounding may be
            // near: the interpolant's closest approach to zero (`low` or
            // `-high`), if within TANGENT of the ends or within the
            // rounding of the samples.
            let ends = start.value.abs().max(end.value.abs());
            let threshold = (TANGENT * ends).max(found.noise);
            if low.max(-high) > threshold {
                return;
            }
            let (s, value) = cubic.nearest_zero();
            if s > 0.0 && s < 1.0 && value.abs() <= threshold {
                let [value, _, curvature] = self.at(start.t + s * h);
                found.push_double(start.t + s * h, value.abs().max(found.noise), curvature);
            }
            return;
        }
        let sign_change = start.value * end.value < 0.0;
        let (slope_low, slope_high) = cubic.slope_range();
        if sign_change && (slope_low > slope_error || slope_high < -slope_error) {
            found.push(self.bracketed(start.t, end.t));
            return;
        }
        if h < SMALLEST_INTERVAL {
            if sign_change {
                found.push(self.bracketed(start.t, end.t));
            } else {
                found.push(0.5 * (start.t + end.t));
            }
            return;
        }
        let t = 0.5 * (start.t + end.t);
        let [value, slope, _] = self.at(t);
        if value == 0.0 {
            found.push(t);
        }
        let middle = Knot { t, value, slope };
        self.isolate(start, &middle, found);
        self.isolate(&middle, end, found);
    }

    /// The zero in `[t0, t1]`, where the value changes sign: Newton kept
    /// inside the bracket, bisection when a step leaves it
    /// ([`safeguarded_newton`]); until a step is within [`ROOT_WIDTH`] or a
    /// Newton step below 1e-9 rad no longer shrinks (the rounding of the
    /// samples reached). A root on an end of the bracket (an end of the
    /// isolation's halving can fall on it within the rounding) is reached by
    /// Newton: only a step beyond an end is replaced by bisection.
    pub(super) fn bracketed(&self, t0: f64, t1: f64) -> f64 {
        let newton = Newton {
            tolerance: Tolerance {
                absolute: ROOT_WIDTH,
                relative: 0.0,
            },
            steps: 60,
            stall: 1e-9,
        };
        let f = |t: f64| {
            let [value, slope, _] = self.at(t);
            (value, slope)
        };
        safeguarded_newton(f, (t0, t1), self.at(t0)[0], 0.5 * (t0 + t1), &newton)
    }
}

/// The roots of `f` in `[t0, t1)` from its values at [`QUIET_STEPS`] + 1
/// evenly spaced points: a sign change refined by [`regula_falsi`]; where
/// `|f|` dips at a point between two of one sign (a pair of roots, or a
/// double root, closer than a step may hide there), the two steps around it
/// scanned again the same way `refinements` times (a quarter of the step
/// each time), then by [`dip`].
pub(super) fn scan_directly(
    f: &dyn Fn(f64) -> f64,
    (t0, t1): (f64, f64),
    refinements: usize,
    found: &mut Found,
) {
    let step = (t1 - t0) / QUIET_STEPS as f64;
    let points: [(f64, f64); QUIET_STEPS + 1] = std::array::from_fn(|i| {
        let t = t0 + step * i as f64;
        (t, f(t))
    });
    let mut i = 0;
    while i < QUIET_STEPS {
        let ((a, fa), (b, fb)) = (points[i], points[i + 1]);
        let dips = i + 2 <= QUIET_STEPS && {
            let fc = points[i + 2].1;
            fa * fb > 0.0 && fb * fc > 0.0 && fb.abs() < fa.abs() && fb.abs() <= fc.abs()
        };
        if dips {
            let window = (a, points[i + 2].0);
            if refinements > 0 {
                scan_directly(f, window, refinements - 1, found);
            } else {
                dip(f, points[i], points[i + 1], points[i + 2], found);
            }
            i += 2;
            continue;
        }
        if fa == 0.0 {
            found.push(a);
        } else if fa * fb < 0.0 {
            found.push(regula_falsi(f, (a, fa), (b, fb), ROOT_WIDTH));
        }
        i += 1;
    }
}

/// Where `|f|` dips at `middle` between `left` and `right` (same signs):
/// the bottom by successive parabolic interpolation (4 steps); two roots
/// if `f` changes sign there, one double-root candidate if it comes within
/// [`TANGENT`] of the sides' values of zero.
pub(super) fn dip(
    f: &dyn Fn(f64) -> f64,
    left: (f64, f64),
    middle: (f64, f64),
    right: (f64, f64),
    found: &mut Found,
) {
    let (mut a, mut m, mut b) = (left, middle, right);
    for _ in 0..4 {
        // The vertex of the parabola through the three points.
        let (p, q) = ((m.0 - a.0) * (m.1 - b.1), (m.0 - b.0) * (m.1 - a.1));
        let denominator = 2.0 * (p - q);
        if denominator == 0.0 {
            break;
        }
        let t = m.0 - ((m.0 - a.0) * p - (m.0 - b.0) * q) / denominator;
        if !(t > a.0 && t < b.0) {
            break;
        }
        let bottom = (t, f(t));
        if bottom.1 * m.1 <= 0.0 {
            found.push(regula_falsi(f, a, bottom, ROOT_WIDTH));
            found.push(regula_falsi(f, bottom, b, ROOT_WIDTH));
            return;
        }
        if bottom.1.abs() >= m.1.abs() {
            break;
        }
        (a, b) = if t < m.0 { (a, m) } else { (m, b) };
        m = bottom;
    }
    if m.1.abs() <= TANGENT * left.1.abs().min(right.1.abs()) {
        // The parabola's curvature: twice the second divided difference.
        let slope = |(t0, f0): (f64, f64), (t1, f1): (f64, f64)| (f1 - f0) / (t1 - t0);
        let curvature = 2.0 * (slope(m, b) - slope(a, m)) / (b.0 - a.0);
        found.push_double(m.0, m.1.abs(), curvature);
    }
}

/// The real roots in `[0, 2 pi)` of `a0 + sum_k (a_k cos k t + b_k sin k t)`
/// (`k = 1..8`, `a = cosines`, `b = sines`; `sines[0]` unused) by the
/// certified isolation of the module docs (**Roots**), with `function` (the
/// same polynomial, evaluated directly) scanned where the samples are
/// quiet; written into `roots` (at most its length), how many. (The
/// isolation's entry point for its tests; `Elimination::solve` keeps its
/// table.)
#[cfg(test)]
pub(crate) fn trigonometric_roots(
    cosines: [f64; HARMONICS + 1],
    sines: [f64; HARMONICS + 1],
    function: &dyn Fn(f64) -> f64,
    roots: &mut [f64],
) -> usize {
    let mut sines = sines;
    sines[0] = 0.0;
    Trigonometric { cosines, sines }.roots(&root_table(), function, roots)
}

/// `(cos, sin)(2 pi j / ROOT_SAMPLES)`, `j < ROOT_SAMPLES`.
pub(super) fn root_table() -> [(f64, f64); ROOT_SAMPLES] {
    std::array::from_fn(|j| {
        let (s, c) = sin_cos(TAU * j as f64 / ROOT_SAMPLES as f64);
        (c, s)
    })
}

/// A bound on the `order`-th derivative of `a0 + sum_k (a_k cos k t + b_k
/// sin k t)` over every `t`: `sum_k k^order (|a_k| + |b_k|)` (per rad^order).
pub(crate) fn derivative_bound(cosines: &[f64], sines: &[f64], order: i32) -> f64 {
    (1..cosines.len())
        .map(|k| (k as f64).powi(order) * (cosines[k].abs() + sines[k].abs()))
        .sum()
}

/// The errors of cubic Hermite interpolation (values and slopes at both
/// ends) over an interval of `h` rad of a function whose fourth derivative
/// is at most `fourth` in magnitude: `(fourth h^4 / 384, fourth h^3 / 72)`,
/// on the values and on the slope (per rad).
pub(crate) fn hermite_error_bounds(fourth: f64, h: f64) -> (f64, f64) {
    (fourth * h.powi(4) / 384.0, fourth * h.powi(3) / 72.0)
}

/// Smallest interval [`Trigonometric::isolate`] halves, rad.
pub(super) const SMALLEST_INTERVAL: f64 = 1e-9;

/// A point of the polynomial: angle (rad), value, slope.
pub(super) struct Knot {
    pub(super) t: f64,
    pub(super) value: f64,
    pub(super) slope: f64,
}

/// Roots found so far (the buffer of [`Trigonometric::roots`]) and the
/// bounds on the polynomial's fourth and second derivatives.
pub(super) struct Found<'a> {
    pub(super) roots: &'a mut [f64],
    pub(super) count: usize,
    pub(super) fourth: f64,
    /// The bound on the polynomial's second derivative.
    pub(super) second: f64,
    /// [`ROUNDING`] of the largest sample.
    pub(super) noise: f64,
}

impl Found<'_> {
    pub(super) fn push(&mut self, t: f64) {
        if self.count < self.roots.len() {
            self.roots[self.count] = t;
            self.count += 1;
        }
    }

    /// A double root at `t` where the function, of curvature `curvature`,
    /// comes within `gap` of zero without crossing (two real roots made a
    /// complex pair by rounding, or nearly meeting): pushed as the two
    /// roots the parabola would have at that depth, `t -+ sqrt(2 gap /
    /// |curvature|)`, each then polished apart on the chain (from `t`
    /// itself, where the two solutions' Jacobian is singular, Gauss-Newton
    /// would not separate them).
    pub(super) fn push_double(&mut self, t: f64, gap: f64, curvature: f64) {
        let half_gap = (2.0 * gap / curvature.abs()).sqrt();
        if half_gap.is_finite() && half_gap < 1e-2 {
            self.push(t - half_gap);
            self.push(t + half_gap);
        } else {
            self.push(t);
        }
    }
}

/// The cubic Hermite interpolant between two knots, in `s in [0, 1]`:
/// `H(s) = c0 + c1 s + c2 s^2 + c3 s^3`.
pub(super) struct Hermite {
    pub(super) h: f64,
    pub(super) coefficients: [f64; 4],
}

impl Hermite {
    pub(super) fn new(start: &Knot, end: &Knot) -> Hermite {
        let h = end.t - start.t;
        let (v0, v1, d0, d1) = (start.value, end.value, start.slope * h, end.slope * h);
        Hermite {
            h,
            coefficients: [
                v0,
                d0,
                3.0 * (v1 - v0) - 2.0 * d0 - d1,
                2.0 * (v0 - v1) + d0 + d1,
            ],
        }
    }

    pub(super) fn value(&self, s: f64) -> f64 {
        let [a, b, c, d] = self.coefficients;
        a + s * (b + s * (c + s * d))
    }

    /// `dH/dt` at `s`.
    pub(super) fn slope(&self, s: f64) -> f64 {
        let [_, b, c, d] = self.coefficients;
        (b + s * (2.0 * c + 3.0 * s * d)) / self.h
    }

    /// Smallest and largest of `f` over `s = 0`, `s = 1` and `inside`
    /// (those in `(0, 1)`).
    pub(super) fn range(f: impl Fn(f64) -> f64, inside: [Option<f64>; 2]) -> (f64, f64) {
        let (a, b) = (f(0.0), f(1.0));
        let (mut low, mut high) = (a.min(b), a.max(b));
        for s in inside.into_iter().flatten() {
            if s > 0.0 && s < 1.0 {
                let v = f(s);
                low = low.min(v);
                high = high.max(v);
            }
        }
        (low, high)
    }

    /// Smallest and largest value on `[0, 1]`.
    pub(super) fn value_range(&self) -> (f64, f64) {
        Hermite::range(|s| self.value(s), self.slope_zeros())
    }

    /// The `s` in `[0, 1]` where `|H|` is smallest (an end or a zero of the
    /// slope), with `H` there.
    pub(super) fn nearest_zero(&self) -> (f64, f64) {
        let mut best = (0.0, self.value(0.0));
        for s in [Some(1.0)].into_iter().chain(self.slope_zeros()).flatten() {
            let value = self.value(s);
            if (0.0..=1.0).contains(&s) && value.abs() < best.1.abs() {
                best = (s, value);
            }
        }
        best
    }

    /// The zeros of the slope, `3 c3 s^2 + 2 c2 s + c1 = 0` (any `s`).
    /// Written without cancellation: with `c3` small beside `c2` (an
    /// interpolant nearly a parabola, as over a symmetric dip), `(-c2 +-
    /// sqrt(...)) / (3 c3)` would lose the zero near the vertex.
    pub(super) fn slope_zeros(&self) -> [Option<f64>; 2] {
        let [_, b, c, d] = self.coefficients;
        let discriminant = c * c - 3.0 * d * b;
        if d != 0.0 && discriminant >= 0.0 {
            let q = -(c + c.signum() * discriminant.sqrt());
            if q == 0.0 {
                // c = 0 and b = 0: a double zero at s = 0.
                return [Some(0.0), None];
            }
            [Some(q / (3.0 * d)), Some(b / q)]
        } else if d == 0.0 && c != 0.0 {
            [Some(-b / (2.0 * c)), None]
        } else {
            [None, None]
        }
    }

    /// Smallest and largest `dH/dt` on `[0, 1]` (the ends and the vertex).
    pub(super) fn slope_range(&self) -> (f64, f64) {
        let [_, _, c, d] = self.coefficients;
        let vertex = (d != 0.0).then(|| -c / (3.0 * d));
        Hermite::range(|s| self.slope(s), [vertex, None])
    }
}
