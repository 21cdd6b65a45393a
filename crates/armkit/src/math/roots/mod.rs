//! One-dimensional root finders and a minimiser, one definition each for
//! the whole crate: bisection ([`bisect`]), the Illinois variant of regula
//! falsi ([`regula_falsi`]), Newton safeguarded by bisection
//! ([`safeguarded_newton`]) and golden-section minimisation
//! ([`golden_section`]).
//!
//! Each works on a bracket `[a, b]`, `a < b`: for the root finders one with
//! a sign change (`f(a) f(b) < 0`), for the minimiser one holding a
//! minimum. What is specific to one caller (the polynomial's derivative
//! roots that split a line into monotone pieces, the Hermite bounds that
//! certify a trigonometric polynomial's brackets) stays with that caller,
//! which hands the brackets here.

/// A width in `x`: the larger of an absolute part and a part relative to
/// `|x|` (`max(absolute, relative |x|)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tolerance {
    /// Width at `x = 0`, in `x`'s unit.
    pub absolute: f64,
    /// Width per unit of `|x|` (dimensionless).
    pub relative: f64,
}

impl Tolerance {
    /// The width at `x`.
    pub(crate) fn at(&self, x: f64) -> f64 {
        self.absolute.max(self.relative * x.abs())
    }
}

/// Most halvings of [`bisect`]: 200 take any finite bracket of `f64` below
/// its spacing.
pub(crate) const BISECTION_STEPS: usize = 200;

/// Bisection on `[a, b]` where `f` changes sign (`fa = f(a)`): halves the
/// bracket until its midpoint is no longer strictly inside (machine
/// precision) or [`BISECTION_STEPS`] halvings; the midpoint where `f` is
/// exactly zero, else the last bracket's midpoint.
pub(crate) fn bisect(mut f: impl FnMut(f64) -> f64, mut a: f64, mut b: f64, mut fa: f64) -> f64 {
    for _ in 0..BISECTION_STEPS {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        let fm = f(m);
        if fm == 0.0 {
            return m;
        }
        if (fm < 0.0) == (fa < 0.0) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// Most steps of [`regula_falsi`] per bracket.
pub(crate) const ILLINOIS_STEPS: usize = 100;

/// The zero of `f` between `a` and `b` (points `(t, f(t))` with
/// `f(a) f(b) <= 0`, in either order) by the Illinois variant of regula
/// falsi (Dowell and Jarratt, 1971: superlinear, the stale end's value
/// halved when one end moves twice running): the bracket shrinks until it
/// is narrower than `width` (or [`ILLINOIS_STEPS`] steps; a trial outside
/// the bracket is replaced by its midpoint). Returns the trial where `f`
/// is exactly zero, else the end of the last bracket where `|f|` is
/// smaller.
pub(crate) fn regula_falsi(
    mut f: impl FnMut(f64) -> f64,
    a: (f64, f64),
    b: (f64, f64),
    width: f64,
) -> f64 {
    let (mut a, mut b) = (a, b);
    if a.1 == 0.0 {
        return a.0;
    }
    let mut side = 0i8;
    for _ in 0..ILLINOIS_STEPS {
        if (b.0 - a.0).abs() < width {
            break;
        }
        let mut t = (a.0 * b.1 - b.0 * a.1) / (b.1 - a.1);
        if !(t > a.0.min(b.0) && t < a.0.max(b.0)) {
            t = 0.5 * (a.0 + b.0);
        }
        let value = f(t);
        if value == 0.0 {
            return t;
        }
        if value.signum() == b.1.signum() {
            b = (t, value);
            if side == -1 {
                a.1 *= 0.5;
            }
            side = -1;
        } else {
            a = (t, value);
            if side == 1 {
                b.1 *= 0.5;
            }
            side = 1;
        }
    }
    if a.1.abs() <= b.1.abs() {
        a.0
    } else {
        b.0
    }
}

/// How far [`safeguarded_newton`] goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Newton {
    /// Converged when a Newton step, or the bracket, is within this width
    /// of the current point.
    pub tolerance: Tolerance,
    /// Most evaluations.
    pub steps: usize,
    /// A Newton step below this that is no shorter than the one before
    /// stops the search at the current point (the rounding of `f`
    /// reached); 0 never stops so.
    pub stall: f64,
}

/// The root of `f` in `[a, b]` (`a < b`, `fa = f(a)`, `f(b)` of the other
/// sign): Newton from `start`, `f` returning the value and the slope,
/// the bracket shrunk to the current point after each evaluation by the
/// sign there; a Newton step that leaves the bracket is replaced by its
/// midpoint (a step onto an end is kept: the root may lie there to within
/// the rounding). Stops at a point where `f` is exactly zero, at the
/// Newton point (clamped into the bracket) when a Newton step is within
/// `options.tolerance` of the current point, at the next point when the
/// bracket is that narrow, at a stall (see [`Newton::stall`]), or after
/// `options.steps` evaluations.
pub(crate) fn safeguarded_newton(
    mut f: impl FnMut(f64) -> (f64, f64),
    (mut a, mut b): (f64, f64),
    fa: f64,
    start: f64,
    options: &Newton,
) -> f64 {
    let rising = fa < 0.0;
    let mut x = start;
    let mut last_step = f64::INFINITY;
    for _ in 0..options.steps {
        let (value, slope) = f(x);
        if value == 0.0 {
            return x;
        }
        if (value < 0.0) == rising {
            a = x;
        } else {
            b = x;
        }
        let tolerance = options.tolerance.at(x);
        let newton = x - value / slope;
        let step = (newton - x).abs();
        if step <= tolerance {
            return newton.max(a).min(b);
        }
        if newton >= a && newton <= b {
            if step < options.stall && step >= last_step {
                return x;
            }
            last_step = step;
            x = newton;
        } else {
            x = 0.5 * (a + b);
        }
        if b - a <= tolerance {
            break;
        }
    }
    x
}

/// Golden-section search for a minimum of `f` on `[a, b]`: `iterations`
/// shrinks of the bracket by `(sqrt 5 - 1) / 2 = 0.618` each, one
/// evaluation each (two to start); the last bracket's midpoint. The first
/// error of `f` is returned as is.
pub(crate) fn golden_section<E>(
    f: &mut impl FnMut(f64) -> Result<f64, E>,
    mut a: f64,
    mut b: f64,
    iterations: usize,
) -> Result<f64, E> {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let mut fc = f(c)?;
    let mut fd = f(d)?;
    for _ in 0..iterations {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = f(c)?;
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = f(d)?;
        }
    }
    Ok(0.5 * (a + b))
}

#[cfg(test)]
mod tests;
