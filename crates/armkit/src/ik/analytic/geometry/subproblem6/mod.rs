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
//! `f`'s zeros (at most 4, found by the crate's `trig2` module: a quartic in
//! `tan(phi / 2)` with its real roots isolated exactly, double roots
//! included) are the solutions. Each
//! `phi` gives `t1`, `t2` read off
//! `x1`, `x2` (normalized).
//!
//! Least squares: when no solution exists (`|x0|^2 > 2`, or `f` keeps its
//! sign), the pair minimizing `|r|^2`, `r` the two equations' residual, is
//! returned, by damped Newton on `|r|^2` from the start of least `|f|` (or
//! `x0` itself), and from each critical point of `f`: the best of these
//! local minima. A rank-deficient `M` (one equation a multiple of the
//! other: a continuum of solutions or none) takes the same path and returns
//! one pair. Every pair's `exact` flag says whether its residual is within
//! the subproblems' relative tolerance (1e-9) of the equations' size.
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

use super::subproblems::{Solutions, Turn, RELATIVE_TOLERANCE};
use super::trig2::Trig2;
use crate::math::Vector3;

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

/// Up to 4 angle pairs `(t1, t2)` (rad) from [`subproblem6`], exact when
/// every pair solves the equations (to round-off).
pub type PairsOfFour = Solutions<(f64, f64), 4>;

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
    let exact = turns.as_slice().iter().all(|p| p.exact);
    let values = turns.items.map(|p| (p.first.angle, p.second.angle));
    PairsOfFour::new(values, turns.count, exact)
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
    /// No pair.
    const EMPTY: TurnPairs = TurnPairs {
        items: [TurnPair {
            first: Turn::ZERO,
            second: Turn::ZERO,
            exact: false,
        }; 4],
        count: 0,
    };

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
        let scale = equations_scale(&m, &e);
        let mut out = TurnPairs::EMPTY;
        let Some(space) = Affine::of(&m, &e) else {
            let x0 = Affine::rank_one(&m, &e);
            out.push(least_squares(&m, &e, scale, &with_axis_starts(&[x0])));
            return out;
        };
        let rho2 = 2.0 - dot4(&space.x0, &space.x0);
        let rho = rho2.max(0.0).sqrt();
        let f = space.difference(rho);
        if rho2 >= -RELATIVE_TOLERANCE {
            for root in f.roots().as_slice() {
                let pair = self.pair_at(&space.point(rho, root.sin, root.cos), &m, &e, scale);
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
            let (critical, count) = f.quartic_critical_angles();
            for phi in &critical[..count] {
                let (s, c) = phi.sin_cos();
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

/// The size the equations' residual is measured against: the larger row of
/// `M`, or of `e`.
fn equations_scale(m: &[Vector4; 2], e: &[f64; 2]) -> f64 {
    dot4(&m[0], &m[0])
        .sqrt()
        .max(dot4(&m[1], &m[1]).sqrt())
        .max(e[0].abs())
        .max(e[1].abs())
        .max(f64::MIN_POSITIVE)
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
struct Affine {
    x0: Vector4,
    null: [Vector4; 2],
}

impl Affine {
    /// `None` when `M` is rank-deficient (relative to its larger row).
    fn of(m: &[Vector4; 2], e: &[f64; 2]) -> Option<Affine> {
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
        Some(Affine { x0, null })
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
mod tests;
