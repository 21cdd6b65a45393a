//! The root search of the parallel-pair class: `search::find_roots`'s
//! sampling, branch matching and bracketing, with the residual's
//! derivative along each branch read at every sample (the branch's
//! implicit rates, see `Problem::point`), so that what lies between two
//! samples is judged by the cubic Hermite interpolant of their values and
//! slopes (error of the fourth power of the step) instead of a parabola
//! through three values (error of the third power). That is what lets the
//! search take 192 samples per turn where `find_roots` took 512, for the
//! same recall (a separate driver: `find_roots` reads values only).
//!
//! Between two samples of one branch:
//!
//! * a sign change is refined by Newton on the value and slope, kept
//!   inside the bracket, to [`ROOT_TOLERANCE`];
//! * without one, where the Hermite cubic has an inner minimum of `|f|`
//!   below half the smaller end (or below its own error estimate, from
//!   the change of the cubics' third derivative to the neighbouring
//!   intervals), two roots may hide there (a near-double root: two
//!   solutions of the arm close together): [`dip`] walks into the minimum,
//!   each step at the current cubic's minimum, until `f` changes sign (both
//!   roots refined) or the cubic's minimum clears zero by more than the last
//!   step's prediction error.
//!
//! Between a sample and the end of its branch (a fold, located by
//! `Residual::branch_end`), the residual goes as the square root of the
//! distance to the end: a sign change is refined; without one, the piece
//! is probed once at the minimum of the quadratic in
//! `s = sqrt(|t - t_end|)` through the end's value and the sample's value
//! and slope (see [`end_piece`]).

use crate::ik::analytic::search::{Point, Residual, ROOT_TOLERANCE};
use std::f64::consts::{PI, TAU};

/// A residual with its derivative along each branch.
pub(in crate::ik::analytic) trait Sloped<const B: usize>:
    Residual<B>
{
    /// The largest gap (by [`Sloped::gap`]) between the keys of one branch
    /// at neighbouring samples.
    const LINK: f64;

    /// The distance between two keys (see `search::align_nearest`).
    fn gap(a: &Self::Key, b: &Self::Key) -> f64;

    /// Every branch at `t`: its value, and its key with the slope `df/dt`.
    fn sample_sloped(&self, t: f64) -> Samples<Self::Key, B>;

    /// The branch named `key` at `t`: value, slope, key.
    fn residual_sloped(&self, t: f64, key: &Self::Key) -> Option<Knot<Self::Key>>;
}

/// Every branch at one sample: its value, and its key with the slope.
pub(in crate::ik::analytic) type Samples<K, const B: usize> = [Option<(f64, (K, f64))>; B];

/// A point of a branch with its slope.
#[derive(Clone, Copy, Debug)]
pub(in crate::ik::analytic) struct Knot<K> {
    /// The searched angle, rad.
    pub t: f64,
    /// The residual and its derivative by `t`.
    pub f: f64,
    pub g: f64,
    pub key: K,
}

impl<K: Copy> Knot<K> {
    fn point(&self) -> Point<K> {
        (self.t, self.f, self.key)
    }
}

/// Most steps of one [`dip`] walk.
const DIP_STEPS: usize = 40;

/// Every root of every branch of `p` over one turn, `N` samples (see the
/// module docs), each given to `found` with its branch's key there.
pub(in crate::ik::analytic) fn find_roots_sloped<R: Sloped<B>, const B: usize, const N: usize>(
    p: &R,
    mut found: impl FnMut(f64, R::Key),
) {
    let step = TAU / N as f64;
    let mut samples = [[None; B]; N];
    let align = |previous: &Samples<R::Key, B>, current: &mut Samples<R::Key, B>| {
        crate::ik::analytic::search::align_nearest(
            previous,
            current,
            |a: &(R::Key, f64), b: &(R::Key, f64)| R::gap(&a.0, &b.0),
            R::LINK,
        );
    };
    for k in 0..N {
        let mut current = p.sample_sloped(-PI + step * k as f64);
        if k > 0 {
            align(&samples[k - 1], &mut current);
        }
        samples[k] = current;
    }
    let mut wrapped = samples[0];
    align(&samples[N - 1], &mut wrapped);
    for branch in 0..B {
        let at = |k: usize| -> Option<Knot<R::Key>> {
            let s = if k == N {
                wrapped[branch]
            } else {
                samples[k % N][branch]
            };
            s.map(|(f, (key, g))| Knot {
                t: -PI + step * k as f64,
                f,
                g,
                key,
            })
        };
        let linked = |a: &Option<Knot<R::Key>>, b: &Option<Knot<R::Key>>| match (a, b) {
            (Some(a), Some(b)) => p.same_branch(&a.key, &b.key),
            _ => false,
        };
        // The third derivative of the Hermite cubic on the interval ending
        // at sample k, where both ends are on the branch.
        let third = |k: usize| -> Option<f64> {
            if k == 0 || k > N {
                return None;
            }
            let (a, b) = (at(k - 1), at(k));
            if !linked(&a, &b) {
                return None;
            }
            let (a, b) = (a?, b?);
            Some((12.0 * (a.f - b.f) + 6.0 * step * (a.g + b.g)) / (step * step * step))
        };
        for k in 1..=N {
            let (a, b) = (at(k - 1), at(k));
            match (a, b) {
                (Some(a), Some(b)) if p.same_branch(&a.key, &b.key) => {
                    let here = third(k).unwrap_or(0.0);
                    let mut change = 0.0_f64;
                    for other in [third(k - 1), third(k + 1)].into_iter().flatten() {
                        change = change.max((other - here).abs());
                    }
                    if !change.is_finite() {
                        change = f64::INFINITY;
                    }
                    // Hermite error: step^4 / 384 max |f''''|, with f''''
                    // about the change of the third derivative per step.
                    let error = step * step * step * change / 384.0;
                    interval(p, a, b, error, &mut found);
                }
                (a, b) => {
                    if let Some(a) = a {
                        let end = p.branch_end(a.point(), b.map_or(a.t + step, |b| b.t));
                        end_piece(p, end, a, true, &mut found);
                    }
                    if let Some(b) = b {
                        let end = p.branch_end(b.point(), b.t - step);
                        end_piece(p, end, b, true, &mut found);
                    }
                }
            }
        }
    }
}

/// Refines a sign change between `a` and `b`: Newton on the residual and
/// its slope from the secant point, kept inside the bracket (a bisection
/// where a step would leave it), until a step is below
/// [`ROOT_TOLERANCE`] (the error after it is of its square) or the bracket
/// is that narrow.
fn bracket<R: Sloped<B>, const B: usize>(
    p: &R,
    a: Point<R::Key>,
    b: Point<R::Key>,
    found: &mut impl FnMut(f64, R::Key),
) {
    if a.1 == 0.0 {
        found(a.0, a.2);
        return;
    }
    if a.1.signum() == b.1.signum() {
        return;
    }
    let (mut lo, mut hi) = (a, b);
    let mut t = (a.0 * b.1 - b.0 * a.1) / (b.1 - a.1);
    for _ in 0..MAX_NEWTON {
        if !(t > lo.0.min(hi.0) && t < lo.0.max(hi.0)) {
            t = 0.5 * (lo.0 + hi.0);
        }
        let near = if (t - lo.0).abs() <= (t - hi.0).abs() {
            &lo.2
        } else {
            &hi.2
        };
        let Some(c) = p.residual_sloped(t, near) else {
            return;
        };
        if c.f == 0.0 {
            found(c.t, c.key);
            return;
        }
        if c.f.signum() == lo.1.signum() {
            lo = c.point();
        } else {
            hi = c.point();
        }
        let step = c.f / c.g;
        if step.abs() < ROOT_TOLERANCE {
            found(c.t, c.key);
            return;
        }
        if (hi.0 - lo.0).abs() < ROOT_TOLERANCE {
            let end = if lo.1.abs() < hi.1.abs() { lo } else { hi };
            found(end.0, end.2);
            return;
        }
        t = c.t - step;
    }
}

/// Most steps of one [`bracket`] refinement.
const MAX_NEWTON: usize = 100;

/// The cubic Hermite interpolant on `[a, b]` at the fraction `u`.
fn hermite<K>(a: &Knot<K>, b: &Knot<K>, u: f64) -> f64 {
    let h = b.t - a.t;
    let (u2, u3) = (u * u, u * u * u);
    (2.0 * u3 - 3.0 * u2 + 1.0) * a.f
        + (u3 - 2.0 * u2 + u) * h * a.g
        + (-2.0 * u3 + 3.0 * u2) * b.f
        + (u3 - u2) * h * b.g
}

/// The fraction `u` in `(0, 1)` of the inner minimum of `sign * p` (`p`
/// the Hermite cubic on `[a, b]`), if it has one.
fn hermite_minimum<K>(a: &Knot<K>, b: &Knot<K>, sign: f64) -> Option<f64> {
    let h = b.t - a.t;
    // p'(u) / 6 = A u^2 + B u + C.
    let (fa, fb, ga, gb) = (sign * a.f, sign * b.f, sign * h * a.g, sign * h * b.g);
    let qa = (6.0 * fa + 3.0 * ga - 6.0 * fb + 3.0 * gb) / 6.0;
    let qb = (-6.0 * fa - 4.0 * ga + 6.0 * fb - 2.0 * gb) / 6.0;
    let qc = ga / 6.0;
    // A minimum: p' = 0 with p'' = 2 A u + B = +sqrt(B^2 - 4 A C) > 0,
    // u = (-B + sqrt) / 2A, written without cancellation.
    let disc = qb * qb - 4.0 * qa * qc;
    if disc.is_nan() || disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    let u = if qb > 0.0 {
        -2.0 * qc / (root + qb)
    } else if qa != 0.0 {
        (root - qb) / (2.0 * qa)
    } else {
        return None;
    };
    (u > 0.0 && u < 1.0).then_some(u)
}

/// Two samples `a`, `b` of one branch: a sign change refined, or a dip
/// judged by the Hermite cubic (`error`: its estimated error) and walked.
fn interval<R: Sloped<B>, const B: usize>(
    p: &R,
    a: Knot<R::Key>,
    b: Knot<R::Key>,
    error: f64,
    found: &mut impl FnMut(f64, R::Key),
) {
    if a.f == 0.0 || a.f.signum() != b.f.signum() {
        bracket(p, a.point(), b.point(), found);
        return;
    }
    let sign = a.f.signum();
    let Some(u) = hermite_minimum(&a, &b, sign) else {
        if a.g.is_finite() && b.g.is_finite() {
            return;
        }
        // No slope at an end: walk from the middle.
        dip(p, a, b, found);
        return;
    };
    let lowest = sign * hermite(&a, &b, u);
    let ends = (sign * a.f).min(sign * b.f);
    if lowest < 0.5 * ends || lowest < 4.0 * error {
        dip(p, a, b, found);
    }
}

/// Walks into the minimum of `|f|` between `a` and `b` (same sign, see the
/// module docs); both roots refined when `f` changes sign there.
fn dip<R: Sloped<B>, const B: usize>(
    p: &R,
    mut a: Knot<R::Key>,
    mut b: Knot<R::Key>,
    found: &mut impl FnMut(f64, R::Key),
) {
    let sign = a.f.signum();
    let mut error = f64::INFINITY;
    for _ in 0..DIP_STEPS {
        let h = b.t - a.t;
        if h.abs() < ROOT_TOLERANCE {
            return;
        }
        let u = hermite_minimum(&a, &b, sign);
        if let Some(u) = u {
            // The cubic's minimum clears zero by more than its error.
            if sign * hermite(&a, &b, u) > 2.0 * error {
                return;
            }
        } else if error.is_finite() {
            return;
        }
        let u = u.unwrap_or(0.5).clamp(0.05, 0.95);
        let t = a.t + u * h;
        let predicted = hermite(&a, &b, u);
        let near = if u < 0.5 { &a.key } else { &b.key };
        let Some(c) = p.residual_sloped(t, near) else {
            return;
        };
        if c.f == 0.0 || c.f.signum() != sign {
            bracket(p, a.point(), c.point(), found);
            bracket(p, c.point(), b.point(), found);
            return;
        }
        error = (c.f - predicted).abs();
        if !error.is_finite() {
            error = f64::INFINITY;
        }
        if sign * c.g * h.signum() > 0.0 {
            b = c;
        } else {
            a = c;
        }
    }
}

/// A branch's piece between its end `end` (no slope: the residual goes
/// as the square root of the distance there) and the sample `sample`: a
/// sign change refined; else the quadratic in `s = sqrt(|t - t_end|)`
/// through the end's value and the sample's value and slope is read at its
/// minimum (at the middle of `s` without one inside), always where `probe`
/// (the sample's own piece), else only where it dips below half the
/// smaller end; the probe splits the piece into an end piece (checked the
/// same way, not probed) and an interval (the Hermite check).
fn end_piece<R: Sloped<B>, const B: usize>(
    p: &R,
    end: Point<R::Key>,
    sample: Knot<R::Key>,
    probe: bool,
    found: &mut impl FnMut(f64, R::Key),
) {
    if end.1 == 0.0 || end.1.signum() != sample.f.signum() {
        bracket(p, end, sample.point(), found);
        return;
    }
    let sign = end.1.signum();
    let span = sample.t - end.0;
    if span == 0.0 {
        return;
    }
    // f(s) = f_end + alpha s + beta s^2, t = t_end + sign(span) s^2.
    let reach = span.abs().sqrt();
    let slope = sample.g * 2.0 * reach * span.signum();
    let beta = (end.1 + slope * reach - sample.f) / (reach * reach);
    let alpha = slope - 2.0 * beta * reach;
    let inner = -alpha / (2.0 * beta);
    let (lowest, at) = if sign * beta > 0.0 && inner > 0.0 && inner < reach {
        (sign * (end.1 + alpha * inner + beta * inner * inner), inner)
    } else if probe || !slope.is_finite() {
        (f64::NEG_INFINITY, 0.5 * reach)
    } else {
        return;
    };
    if !probe && lowest >= 0.5 * (sign * end.1).min(sign * sample.f) {
        return;
    }
    let s = at.clamp(0.05 * reach, 0.95 * reach);
    let t = end.0 + span.signum() * s * s;
    let Some(c) = p.residual_sloped(t, &end.2) else {
        return;
    };
    if c.f == 0.0 || c.f.signum() != sign {
        bracket(p, end, c.point(), found);
        bracket(p, c.point(), sample.point(), found);
        return;
    }
    if probe {
        end_piece(p, end, c, false, found);
    }
    interval(p, c, sample, 0.0, found);
}
