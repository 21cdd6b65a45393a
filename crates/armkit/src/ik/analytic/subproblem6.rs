//! Subproblem 6 (Elias and Wen's IK-Geo numbering), derived here: two
//! angles `t1`, `t2` (rad) with
//!
//! ```text
//! h1 . R(k1, t1) p1 + h2 . R(k2, t2) p2 = d1
//! h3 . R(k1, t1) p3 + h4 . R(k2, t2) p4 = d2
//! ```
//!
//! (`k1`, `k2` unit axes, the rest any vectors; `R(k, t)` as in
//! [`super::subproblems`]). Up to 4 solutions.
//!
//! Derivation. Each term is a sinusoid,
//! `h . R(k, t) p = a . (cos t, sin t) + c` ([`Wave`]), so with the unit vectors `x1 = (cos t1, sin t1)` and
//! `x2 = (cos t2, sin t2)` stacked as `x` in R^4 the two equations are
//! linear: `M x = e` (`M` 2 x 4). Its solutions are `x = x0 + N z`, `x0`
//! the least-norm one and `N` (4 x 2, orthonormal columns) the null space
//! of `M`. The two unit-norm conditions, `|x1|^2 = 1` and `|x2|^2 = 1`,
//! split into their sum and their difference:
//!
//! * sum: `|x|^2 = |x0|^2 + |z|^2 = 2` (as `x0` is normal to `N`), so `z`
//!   lies on the circle of radius `rho = sqrt(2 - |x0|^2)`:
//!   `z = rho (cos phi, sin phi)`;
//! * difference: `x' D x = 0` with `D = diag(1, 1, -1, -1)`, on that
//!   circle a trigonometric polynomial of degree 2,
//!   `f(phi) = A cos 2phi + B sin 2phi + C cos phi + S sin phi + E`.
//!
//! `f`'s zeros (at most 4) are the solutions. With `phi = phi0 + 2 atan u`,
//! `(1 + u^2)^2 f` is a quartic in `u` whose leading coefficient is
//! `f(phi0 + pi)`; `phi0` is chosen so that this is the largest `|f|` of 8
//! samples (no root near `u = infinity`). The quartic's real roots are
//! isolated exactly by the real roots of its derivative (recursively, down
//! to a line): on each monotone interval with a sign change a safeguarded
//! Newton-bisection converges to the last bit; a critical point where the
//! quartic is within [`TANGENT_TOLERANCE`] of zero (of the size of its
//! terms) without a sign change beside it counts as a (double) root. Each
//! `phi` is then polished by Newton on `f` itself, and `t1`, `t2` read off
//! `x1`, `x2` (normalized).
//!
//! Least squares: when no solution exists (`|x0|^2 > 2`, or `f` keeps its
//! sign), the pair minimizing `|r|^2`, `r` the two equations' residual, is
//! returned, by damped Newton on `|r|^2` from the start of least `|f|` (or
//! `x0` itself), and from each critical point of `f`: the best of these
//! local minima. A rank-deficient `M` (one equation a multiple of the
//! other: a continuum of solutions or none) takes the same path and returns
//! one pair. Every pair's `exact` flag says whether its residual is within
//! [`super::subproblems::RELATIVE_TOLERANCE`] of the equations' size.
//!
//! ```
//! use armkit::ik::analytic::subproblem6::subproblem6;
//! use armkit::ik::analytic::subproblems::rotation;
//! use armkit::math::Vector3;
//! let (k1, k2) = (Vector3::z(), Vector3::x());
//! let h = [Vector3::new(1.0, 0.2, 0.1), Vector3::y(), Vector3::x(), Vector3::new(0.3, 0.0, 1.0)];
//! let p = [Vector3::new(0.5, 1.0, 0.2), Vector3::new(0.1, 0.7, -0.3), Vector3::y(), Vector3::z()];
//! let (t1, t2) = (0.4, -1.1);
//! let d1 = h[0].dot(&(rotation(&k1, t1) * p[0])) + h[1].dot(&(rotation(&k2, t2) * p[1]));
//! let d2 = h[2].dot(&(rotation(&k1, t1) * p[2])) + h[3].dot(&(rotation(&k2, t2) * p[3]));
//! let pairs = subproblem6(&h, &k1, &k2, &p, [d1, d2]);
//! assert!(pairs.exact);
//! assert!(pairs.as_slice().iter().any(|(a, b)| (a - t1).abs() < 1e-9 && (b - t2).abs() < 1e-9));
//! ```

use super::subproblems::{Turn, RELATIVE_TOLERANCE};
use crate::math::Vector3;

/// Size (relative to the sum of its terms' magnitudes) below which the
/// quartic at one of its critical points counts as zero: a double root.
/// Near-double roots whose quartic value is above it but which have no
/// sign change are not solutions; their answers are at most this far from
/// the equations (forward kinematics then decides).
pub const TANGENT_TOLERANCE: f64 = 1e-13;

/// The term `h . R(k, t) p` as `cos t * cos_part + sin t * sin_part +
/// constant` (Rodrigues: `cos_part = h . p - (h . k)(k . p)`,
/// `sin_part = h . (k x p)`, `constant = (h . k)(k . p)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wave {
    /// Coefficient of `cos t`.
    pub cos_part: f64,
    /// Coefficient of `sin t`.
    pub sin_part: f64,
    /// The part independent of `t`.
    pub constant: f64,
}

impl Wave {
    /// The wave of `h . R(k, t) p` (`k` a unit axis).
    #[inline]
    pub fn new(h: &Vector3<f64>, k: &Vector3<f64>, p: &Vector3<f64>) -> Wave {
        let hk = h.dot(k);
        let kp = k.dot(p);
        Wave {
            cos_part: h.dot(p) - hk * kp,
            sin_part: h.dot(&k.cross(p)),
            constant: hk * kp,
        }
    }
}

/// Up to 4 angle pairs `(t1, t2)` (rad), with a flag, from [`subproblem6`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairsOfFour {
    values: [(f64, f64); 4],
    count: usize,
    /// True when every pair solves the equations (to round-off).
    pub exact: bool,
}

impl PairsOfFour {
    /// The pairs, rad (one to four).
    pub fn as_slice(&self) -> &[(f64, f64)] {
        &self.values[..self.count]
    }
}

/// Subproblem 6 (see the module docs): `h[0] . R(k1, t1) p[0] + h[1] .
/// R(k2, t2) p[1] = d[0]`, `h[2] . R(k1, t1) p[2] + h[3] . R(k2, t2) p[3] =
/// d[1]`. Every solution, or the least-squares pair.
pub fn subproblem6(
    h: &[Vector3<f64>; 4],
    k1: &Vector3<f64>,
    k2: &Vector3<f64>,
    p: &[Vector3<f64>; 4],
    d: [f64; 2],
) -> PairsOfFour {
    let system = Sinusoids {
        first: [Wave::new(&h[0], k1, &p[0]), Wave::new(&h[2], k1, &p[2])],
        second: [Wave::new(&h[1], k2, &p[1]), Wave::new(&h[3], k2, &p[3])],
    };
    let turns = system.solve(d);
    let mut values = [(0.0, 0.0); 4];
    for (value, pair) in values.iter_mut().zip(turns.as_slice()) {
        *value = (pair.first.angle, pair.second.angle);
    }
    PairsOfFour {
        values,
        count: turns.count,
        exact: turns.as_slice().iter().all(|p| p.exact),
    }
}

/// One solution of subproblem 6 as [`Turn`]s, with its own flag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TurnPair {
    pub first: Turn,
    pub second: Turn,
    /// True when the pair solves the equations (to round-off).
    pub exact: bool,
}

/// Up to 4 [`TurnPair`]s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TurnPairs {
    items: [TurnPair; 4],
    count: usize,
}

impl TurnPairs {
    pub(crate) fn as_slice(&self) -> &[TurnPair] {
        &self.items[..self.count]
    }

    fn push(&mut self, pair: TurnPair) {
        if self.count < 4 {
            self.items[self.count] = pair;
            self.count += 1;
        }
    }
}

/// Subproblem 6 as sinusoids: equation `i` is `first[i](t1) + second[i](t2)
/// = d[i]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sinusoids {
    /// The `t1` terms of the two equations.
    pub first: [Wave; 2],
    /// The `t2` terms of the two equations.
    pub second: [Wave; 2],
}

type Vector4 = [f64; 4];

fn dot4(a: &Vector4, b: &Vector4) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

fn axpy(a: f64, x: &Vector4, y: &Vector4) -> Vector4 {
    [
        a * x[0] + y[0],
        a * x[1] + y[1],
        a * x[2] + y[2],
        a * x[3] + y[3],
    ]
}

fn scaled(a: f64, x: &Vector4) -> Vector4 {
    [a * x[0], a * x[1], a * x[2], a * x[3]]
}

/// `x' D x`, `D = diag(1, 1, -1, -1)`.
fn split(a: &Vector4, b: &Vector4) -> f64 {
    a[0] * b[0] + a[1] * b[1] - a[2] * b[2] - a[3] * b[3]
}

/// A trigonometric polynomial of degree 2:
/// `c2 cos 2phi + s2 sin 2phi + c1 cos phi + s1 sin phi + c0`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Trig2 {
    c2: f64,
    s2: f64,
    c1: f64,
    s1: f64,
    c0: f64,
}

impl Trig2 {
    /// `f` at the angle of sine `s` and cosine `c`.
    fn at_direction(&self, s: f64, c: f64) -> f64 {
        let (s2, c2) = (2.0 * s * c, c * c - s * s);
        self.c2 * c2 + self.s2 * s2 + self.c1 * c + self.s1 * s + self.c0
    }

    /// `f` and `df / dphi` at the angle of sine `s` and cosine `c`.
    fn value_and_slope(&self, s: f64, c: f64) -> (f64, f64) {
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

    /// Newton on `f` (at most 3 steps), kept while it lowers `|f|`;
    /// returns the angle with its sine and cosine.
    fn polish(&self, phi: f64) -> (f64, f64, f64) {
        let (s, c) = phi.sin_cos();
        let mut best = (phi, s, c);
        let (mut value, mut slope) = self.value_and_slope(s, c);
        for _ in 0..3 {
            if slope == 0.0 || value == 0.0 {
                break;
            }
            let next = best.0 - value / slope;
            let (s, c) = next.sin_cos();
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

/// Most real roots [`real_roots`] returns (a quartic's 4, with room for
/// tangent points beside them).
const MAX_ROOTS: usize = 4;

/// Real roots (ascending) of `sum p[i] u^i`, `p.len() - 1 <= 4` its degree
/// with `p[last] != 0`: see the module docs.
fn real_roots(p: &[f64]) -> ([f64; MAX_ROOTS], usize) {
    roots_to(p, FULL_PRECISION)
}

/// Relative bracket width at which [`real_roots`] stops: a few ulps.
const FULL_PRECISION: f64 = 4.0 * f64::EPSILON;
/// Relative bracket width for the derivatives' roots, which only split the
/// line into monotone pieces (an error `delta` there changes the
/// polynomial's value at a critical point by `O(delta^2)`).
const CRITICAL_PRECISION: f64 = 1e-10;

/// [`real_roots`] with the brackets closed to `precision` (relative).
fn roots_to(p: &[f64], precision: f64) -> ([f64; MAX_ROOTS], usize) {
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
    let (critical, m) = roots_to(&derivative[..n], CRITICAL_PRECISION);
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
        } else if fb == 0.0 || (fa < 0.0) != (fb < 0.0) {
            let start = 0.5 * (a + b);
            push(
                bracketed_root(p, a, b, fa, fb, start, precision),
                &mut count,
            );
            changed[i] = true;
        }
    }
    // Tangent points: a critical point where p vanishes to round-off
    // without a sign change beside it.
    for j in 0..m {
        let c = points[j + 1];
        if !changed[j] && !changed[j + 1] && evaluate(p, c).abs() <= TANGENT_TOLERANCE * size(p, c)
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

/// The root of `p` in `[a, b]` (monotone there, `fa`, `fb` of opposite
/// signs or `fb = 0`): Newton from `start`, falling back to bisection whenever a step
/// leaves the bracket, until the bracket or the step is `precision` wide
/// (relative to `max(1, |u|)`: `u = tan(psi / 2)`, so that is the
/// precision of `psi` near 0 too).
fn bracketed_root(
    p: &[f64],
    mut a: f64,
    mut b: f64,
    fa: f64,
    fb: f64,
    start: f64,
    precision: f64,
) -> f64 {
    if fb == 0.0 {
        return b;
    }
    let rising = fa < 0.0;
    let mut u = start;
    for _ in 0..200 {
        let value = evaluate(p, u);
        if value == 0.0 {
            return u;
        }
        if (value < 0.0) == rising {
            a = u;
        } else {
            b = u;
        }
        let slope = evaluate_slope(p, u);
        let newton = u - value / slope;
        let size = u.abs().max(1.0);
        if slope != 0.0 && (newton - u).abs() <= precision * size {
            // Converged: the last step is within the precision.
            return newton.max(a).min(b);
        }
        u = if slope != 0.0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if b - a <= precision * size {
            break;
        }
    }
    u
}

impl Sinusoids {
    /// The rows of `M` (see the module docs) and `e = d - constants`.
    fn linear(&self, d: [f64; 2]) -> ([Vector4; 2], [f64; 2]) {
        let row = |i: usize| {
            [
                self.first[i].cos_part,
                self.first[i].sin_part,
                self.second[i].cos_part,
                self.second[i].sin_part,
            ]
        };
        let e = |i: usize| d[i] - self.first[i].constant - self.second[i].constant;
        ([row(0), row(1)], [e(0), e(1)])
    }

    /// Every solution, or the least-squares pair (see the module docs).
    pub(crate) fn solve(&self, d: [f64; 2]) -> TurnPairs {
        let (m, e) = self.linear(d);
        let scale = dot4(&m[0], &m[0])
            .sqrt()
            .max(dot4(&m[1], &m[1]).sqrt())
            .max(e[0].abs())
            .max(e[1].abs())
            .max(f64::MIN_POSITIVE);
        let mut out = TurnPairs {
            items: [TurnPair {
                first: Turn::of_direction(0.0, 1.0),
                second: Turn::of_direction(0.0, 1.0),
                exact: false,
            }; 4],
            count: 0,
        };
        let Some(space) = Solutions::of(&m, &e) else {
            let x0 = Solutions::rank_one(&m, &e);
            out.push(least_squares(&m, &e, scale, &with_axis_starts(&[x0])));
            return out;
        };
        let rho2 = 2.0 - dot4(&space.x0, &space.x0);
        let rho = rho2.max(0.0).sqrt();
        let f = space.difference(rho);
        // Sample f; the quartic in u is taken about the sample of largest |f|.
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
            let phi = i as f64 * std::f64::consts::FRAC_PI_4;
            let v = f.at_direction(s, c);
            if v.abs() > far_value.abs() {
                far = phi;
                far_value = v;
            }
        }
        let shift = far - std::f64::consts::PI;
        let shifted = f.shifted(shift);
        let quartic = shifted.quartic();
        if rho2 >= -RELATIVE_TOLERANCE && far_value != 0.0 {
            let (roots, count) = real_roots(&quartic);
            for u in &roots[..count] {
                let (_, s, c) = f.polish(shift + 2.0 * u.atan());
                let pair = self.pair_at(&space.point(rho, s, c), &m, &e, scale);
                out.push(pair);
            }
        }
        if out.count > 0 {
            return out;
        }
        // No exact solution: least squares from x0 and from f's critical
        // points on the circle (f nearest zero there).
        let mut starts = [space.x0; 4];
        let mut n = 1;
        if rho > 0.0 {
            let (critical, count) = real_roots(&derivative_of(&quartic));
            for u in &critical[..count.min(3)] {
                let (s, c) = (shift + 2.0 * u.atan()).sin_cos();
                starts[n] = space.point(rho, s, c);
                n += 1;
            }
        }
        out.push(least_squares(
            &m,
            &e,
            scale,
            &with_axis_starts(&starts[..n]),
        ));
        out
    }

    /// The pair read off `x` (normalized), with its residual's flag.
    fn pair_at(&self, x: &Vector4, m: &[Vector4; 2], e: &[f64; 2], scale: f64) -> TurnPair {
        let first = Turn::of_direction(x[1], x[0]);
        let second = Turn::of_direction(x[3], x[2]);
        let exact = residual_norm(m, e, &first, &second) <= RELATIVE_TOLERANCE * scale;
        TurnPair {
            first,
            second,
            exact,
        }
    }
}

/// `starts` and the four points `t1 = t2 = 0, pi/2, pi, -pi/2`, at most 8.
fn with_axis_starts(starts: &[Vector4]) -> ([Vector4; 8], usize) {
    let mut all = [[0.0; 4]; 8];
    let mut n = 0;
    for x in starts.iter().take(4) {
        all[n] = *x;
        n += 1;
    }
    for (c, s) in [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)] {
        all[n] = [c, s, c, s];
        n += 1;
    }
    (all, n)
}

/// Damped Newton on `|r(t1, t2)|^2 / 2` from each start (read as angles
/// of its two halves); the best local minimum.
fn least_squares(
    m: &[Vector4; 2],
    e: &[f64; 2],
    scale: f64,
    starts: &([Vector4; 8], usize),
) -> TurnPair {
    let mut best = (f64::INFINITY, Turn::of_angle(0.0), Turn::of_angle(0.0));
    for x in &starts.0[..starts.1] {
        let (t1, t2) = minimize(
            m,
            e,
            Turn::of_direction(x[1], x[0]).angle,
            Turn::of_direction(x[3], x[2]).angle,
        );
        let (first, second) = (Turn::of_angle(t1), Turn::of_angle(t2));
        let r = residual_norm(m, e, &first, &second);
        if r < best.0 {
            best = (r, first, second);
        }
    }
    let (r, first, second) = best;
    TurnPair {
        first,
        second,
        exact: r <= RELATIVE_TOLERANCE * scale,
    }
}

fn derivative_of(p: &[f64; 5]) -> [f64; 4] {
    [p[1], 2.0 * p[2], 3.0 * p[3], 4.0 * p[4]]
}

/// `M x - e` at `x = (cos t1, sin t1, cos t2, sin t2)`.
fn residual(m: &[Vector4; 2], e: &[f64; 2], first: &Turn, second: &Turn) -> [f64; 2] {
    let x = [first.cos, first.sin, second.cos, second.sin];
    [dot4(&m[0], &x) - e[0], dot4(&m[1], &x) - e[1]]
}

fn residual_norm(m: &[Vector4; 2], e: &[f64; 2], first: &Turn, second: &Turn) -> f64 {
    let r = residual(m, e, first, second);
    (r[0] * r[0] + r[1] * r[1]).sqrt()
}

/// A local minimum of `|r|^2 / 2` over `(t1, t2)` from a start: Newton with
/// the exact Hessian when it is positive definite and lowers the cost,
/// else a halving gradient step; at most 50 steps.
fn minimize(m: &[Vector4; 2], e: &[f64; 2], mut t1: f64, mut t2: f64) -> (f64, f64) {
    let cost = |t1: f64, t2: f64| {
        let r = residual(m, e, &Turn::of_angle(t1), &Turn::of_angle(t2));
        0.5 * (r[0] * r[0] + r[1] * r[1])
    };
    let mut value = cost(t1, t2);
    for _ in 0..50 {
        let (a, b) = (Turn::of_angle(t1), Turn::of_angle(t2));
        let r = residual(m, e, &a, &b);
        // d x1 / d t1 = (-sin, cos); d^2 x1 / d t1^2 = -x1.
        let j = |i: usize| {
            (
                -m[i][0] * a.sin + m[i][1] * a.cos,
                -m[i][2] * b.sin + m[i][3] * b.cos,
            )
        };
        let (j0, j1) = (j(0), j(1));
        let g = (r[0] * j0.0 + r[1] * j1.0, r[0] * j0.1 + r[1] * j1.1);
        let curl = |i: usize| {
            (
                m[i][0] * a.cos + m[i][1] * a.sin,
                m[i][2] * b.cos + m[i][3] * b.sin,
            )
        };
        let (w0, w1) = (curl(0), curl(1));
        let h11 = j0.0 * j0.0 + j1.0 * j1.0 - r[0] * w0.0 - r[1] * w1.0;
        let h22 = j0.1 * j0.1 + j1.1 * j1.1 - r[0] * w0.1 - r[1] * w1.1;
        let h12 = j0.0 * j0.1 + j1.0 * j1.1;
        let det = h11 * h22 - h12 * h12;
        let gradient2 = g.0 * g.0 + g.1 * g.1;
        if gradient2 == 0.0 {
            break;
        }
        let mut moved = false;
        if det > 0.0 && h11 > 0.0 {
            let (d1, d2) = (
                -(h22 * g.0 - h12 * g.1) / det,
                -(h11 * g.1 - h12 * g.0) / det,
            );
            let next = cost(t1 + d1, t2 + d2);
            if next < value {
                t1 += d1;
                t2 += d2;
                value = next;
                moved = true;
            }
        }
        if !moved {
            let curvature = h11
                .abs()
                .max(h22.abs())
                .max(h12.abs())
                .max(f64::MIN_POSITIVE);
            let mut step = 1.0 / curvature;
            for _ in 0..30 {
                let next = cost(t1 - step * g.0, t2 - step * g.1);
                if next < value {
                    t1 -= step * g.0;
                    t2 -= step * g.1;
                    value = next;
                    moved = true;
                    break;
                }
                step *= 0.5;
            }
        }
        if !moved {
            break;
        }
    }
    (t1, t2)
}

/// The solutions of `M x = e`: `x0 + N z`.
struct Solutions {
    x0: Vector4,
    null: [Vector4; 2],
}

impl Solutions {
    /// `None` when `M` is rank-deficient (relative to its larger row).
    fn of(m: &[Vector4; 2], e: &[f64; 2]) -> Option<Solutions> {
        let (n0, n1) = (dot4(&m[0], &m[0]).sqrt(), dot4(&m[1], &m[1]).sqrt());
        let (i, j) = if n0 >= n1 { (0, 1) } else { (1, 0) };
        let big = n0.max(n1);
        if big == 0.0 {
            return None;
        }
        let e1 = scaled(1.0 / big, &m[i]);
        let along = dot4(&m[j], &e1);
        let w = axpy(-along, &e1, &m[j]);
        let wn = dot4(&w, &w).sqrt();
        if wn <= 1e-12 * big {
            return None;
        }
        let e2 = scaled(1.0 / wn, &w);
        let alpha = e[i] / big;
        let beta = (e[j] - along * alpha) / wn;
        let x0 = axpy(alpha, &e1, &scaled(beta, &e2));
        // Complete e1, e2 to an orthonormal basis with the standard vectors
        // of largest remainder.
        let mut null = [[0.0; 4]; 2];
        let mut basis = [e1, e2, [0.0; 4]];
        for slot in 0..2 {
            let mut best = [0.0; 4];
            let mut best_norm = -1.0;
            for axis in 0..4 {
                let mut v = [0.0; 4];
                v[axis] = 1.0;
                for b in &basis[..2 + slot] {
                    v = axpy(-dot4(&v, b), b, &v);
                }
                let norm = dot4(&v, &v);
                if norm > best_norm {
                    best_norm = norm;
                    best = v;
                }
            }
            let unit = scaled(1.0 / best_norm.sqrt(), &best);
            null[slot] = unit;
            basis[2] = unit;
        }
        Some(Solutions { x0, null })
    }

    /// The least-norm solution of a rank-deficient `M x = e` (its larger
    /// row's equation alone), or zero.
    fn rank_one(m: &[Vector4; 2], e: &[f64; 2]) -> Vector4 {
        let (n0, n1) = (dot4(&m[0], &m[0]), dot4(&m[1], &m[1]));
        let i = if n0 >= n1 { 0 } else { 1 };
        let n = n0.max(n1);
        if n > 0.0 {
            scaled(e[i] / n, &m[i])
        } else {
            [0.0; 4]
        }
    }

    /// `x0 + N rho (cos phi, sin phi)`, from `s = sin phi`, `c = cos phi`.
    fn point(&self, rho: f64, s: f64, c: f64) -> Vector4 {
        axpy(
            rho * c,
            &self.null[0],
            &axpy(rho * s, &self.null[1], &self.x0),
        )
    }

    /// `f(phi) = x' D x` on the circle of radius `rho`.
    fn difference(&self, rho: f64) -> Trig2 {
        let [n0, n1] = &self.null;
        let q11 = split(n0, n0);
        let q22 = split(n1, n1);
        let q12 = split(n0, n1);
        let rho2 = rho * rho;
        Trig2 {
            c2: 0.5 * rho2 * (q11 - q22),
            s2: rho2 * q12,
            c1: 2.0 * rho * split(&self.x0, n0),
            s1: 2.0 * rho * split(&self.x0, n1),
            c0: split(&self.x0, &self.x0) + 0.5 * rho2 * (q11 + q22),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::subproblems::rotation;
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::PI;

    fn unit(rng: &mut ChaCha8Rng) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            );
            if v.norm() > 0.1 && v.norm() < 1.0 {
                return v.normalize();
            }
        }
    }

    fn vector(rng: &mut ChaCha8Rng) -> Vector3<f64> {
        unit(rng) * rng.gen_range(0.1..2.0)
    }

    struct Instance {
        h: [Vector3<f64>; 4],
        k1: Vector3<f64>,
        k2: Vector3<f64>,
        p: [Vector3<f64>; 4],
    }

    impl Instance {
        fn random(rng: &mut ChaCha8Rng) -> Instance {
            Instance {
                h: [unit(rng), unit(rng), unit(rng), unit(rng)],
                k1: unit(rng),
                k2: unit(rng),
                p: [vector(rng), vector(rng), vector(rng), vector(rng)],
            }
        }

        /// The two left sides at `(t1, t2)`.
        fn sides(&self, t1: f64, t2: f64) -> [f64; 2] {
            let (r1, r2) = (rotation(&self.k1, t1), rotation(&self.k2, t2));
            [
                self.h[0].dot(&(r1 * self.p[0])) + self.h[1].dot(&(r2 * self.p[1])),
                self.h[2].dot(&(r1 * self.p[2])) + self.h[3].dot(&(r2 * self.p[3])),
            ]
        }

        fn residual(&self, t1: f64, t2: f64, d: [f64; 2]) -> f64 {
            let s = self.sides(t1, t2);
            ((s[0] - d[0]).powi(2) + (s[1] - d[1]).powi(2)).sqrt()
        }

        fn solve(&self, d: [f64; 2]) -> PairsOfFour {
            subproblem6(&self.h, &self.k1, &self.k2, &self.p, d)
        }

        /// Every root by brute force: a 240 x 240 grid, each cell's local
        /// minima of the residual polished by Newton on the equations
        /// (finite-difference Jacobian), kept when it converges.
        fn brute_force_roots(&self, d: [f64; 2]) -> Vec<(f64, f64)> {
            let n = 240;
            let step = 2.0 * PI / n as f64;
            let grid: Vec<Vec<f64>> = (0..n)
                .map(|i| {
                    (0..n)
                        .map(|j| self.residual(i as f64 * step, j as f64 * step, d))
                        .collect()
                })
                .collect();
            let mut roots: Vec<(f64, f64)> = Vec::new();
            for i in 0..n {
                for j in 0..n {
                    let v = grid[i][j];
                    let mut minimum = true;
                    for (di, dj) in [
                        (1, 0),
                        (n - 1, 0),
                        (0, 1),
                        (0, n - 1),
                        (1, 1),
                        (n - 1, n - 1),
                        (1, n - 1),
                        (n - 1, 1),
                    ] {
                        if grid[(i + di) % n][(j + dj) % n] < v {
                            minimum = false;
                        }
                    }
                    if !minimum {
                        continue;
                    }
                    let (mut a, mut b) = (i as f64 * step, j as f64 * step);
                    for _ in 0..60 {
                        let s = self.sides(a, b);
                        let r = [s[0] - d[0], s[1] - d[1]];
                        let e = 1e-7;
                        let sa = self.sides(a + e, b);
                        let sb = self.sides(a, b + e);
                        let j11 = (sa[0] - s[0]) / e;
                        let j21 = (sa[1] - s[1]) / e;
                        let j12 = (sb[0] - s[0]) / e;
                        let j22 = (sb[1] - s[1]) / e;
                        let det = j11 * j22 - j12 * j21;
                        if det.abs() < 1e-14 {
                            break;
                        }
                        a -= (j22 * r[0] - j12 * r[1]) / det;
                        b -= (j11 * r[1] - j21 * r[0]) / det;
                    }
                    if self.residual(a, b, d) < 1e-9
                        && !roots.iter().any(|&(x, y)| same(x, a) && same(y, b))
                    {
                        roots.push((a, b));
                    }
                }
            }
            roots
        }
    }

    fn same(a: f64, b: f64) -> bool {
        crate::math::wrap_angle(a - b).abs() < 1e-6
    }

    #[test]
    fn every_root_is_found_on_random_instances() {
        let mut rng = ChaCha8Rng::seed_from_u64(61);
        let mut counts = [0; 5];
        for _ in 0..60 {
            let instance = Instance::random(&mut rng);
            let (t1, t2) = (rng.gen_range(-PI..PI), rng.gen_range(-PI..PI));
            let d = instance.sides(t1, t2);
            let pairs = instance.solve(d);
            let res: Vec<f64> = pairs
                .as_slice()
                .iter()
                .map(|&(a, b)| instance.residual(a, b, d))
                .collect();
            assert!(pairs.exact, "{:?} {res:?} gen {t1} {t2}", pairs.as_slice());
            for &(a, b) in pairs.as_slice() {
                assert!(
                    instance.residual(a, b, d) < 1e-12,
                    "{}",
                    instance.residual(a, b, d)
                );
            }
            let found = |x: f64, y: f64| {
                pairs
                    .as_slice()
                    .iter()
                    .any(|&(a, b)| same(a, x) && same(b, y))
            };
            assert!(found(t1, t2), "generating pair missing");
            let brute = instance.brute_force_roots(d);
            for &(x, y) in &brute {
                assert!(
                    found(x, y),
                    "root ({x}, {y}) missing from {:?}",
                    pairs.as_slice()
                );
            }
            assert!(pairs.as_slice().len() <= brute.len().max(1) + 1);
            counts[pairs.as_slice().len()] += 1;
        }
        // Instances with 2 and with 4 solutions both occur.
        assert!(counts[2] > 0 && counts[4] > 0, "{counts:?}");
    }

    #[test]
    fn unsolvable_instances_return_the_least_squares_pair() {
        let mut rng = ChaCha8Rng::seed_from_u64(62);
        let mut tested = 0;
        while tested < 20 {
            let instance = Instance::random(&mut rng);
            let (t1, t2) = (rng.gen_range(-PI..PI), rng.gen_range(-PI..PI));
            let mut d = instance.sides(t1, t2);
            d[0] += rng.gen_range(1.0..4.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
            if !instance.brute_force_roots(d).is_empty() {
                continue; // still solvable
            }
            tested += 1;
            let pairs = instance.solve(d);
            assert!(!pairs.exact);
            assert_eq!(pairs.as_slice().len(), 1);
            let (a, b) = pairs.as_slice()[0];
            let ours = instance.residual(a, b, d);
            // No grid point does better, and the gradient vanishes.
            let n = 300;
            let step = 2.0 * PI / n as f64;
            for i in 0..n {
                for j in 0..n {
                    let r = instance.residual(i as f64 * step, j as f64 * step, d);
                    assert!(ours <= r + 1e-12, "grid point {r} below ours {ours}");
                }
            }
            let e = 1e-6;
            let da = (instance.residual(a + e, b, d).powi(2)
                - instance.residual(a - e, b, d).powi(2))
                / (2.0 * e);
            let db = (instance.residual(a, b + e, d).powi(2)
                - instance.residual(a, b - e, d).powi(2))
                / (2.0 * e);
            assert!(da.abs() < 1e-7 && db.abs() < 1e-7, "gradient {da} {db}");
        }
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
