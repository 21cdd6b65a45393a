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
mod tests {
    use super::*;
    use std::cell::Cell;

    /// `f` counting its evaluations in `calls`.
    fn counted<'a, T>(
        calls: &'a Cell<usize>,
        f: impl Fn(f64) -> T + 'a,
    ) -> impl FnMut(f64) -> T + 'a {
        move |x| {
            calls.set(calls.get() + 1);
            f(x)
        }
    }

    #[test]
    fn a_tolerance_is_the_larger_of_its_parts() {
        let t = Tolerance {
            absolute: 1e-3,
            relative: 0.1,
        };
        assert_eq!(t.at(0.0), 1e-3);
        assert_eq!(t.at(-0.005), 1e-3);
        assert_eq!(t.at(10.0), 1.0);
        assert_eq!(t.at(-10.0), 1.0);
        let relative = Tolerance {
            absolute: 0.0,
            relative: 0.5,
        };
        assert_eq!(relative.at(4.0), 2.0);
        assert_eq!(relative.at(0.25), 0.125);
    }

    #[test]
    fn bisection_closes_the_bracket_to_machine_precision() {
        // A rising and a falling cubic, root 0.3 (not a dyadic number).
        for sign in [1.0, -1.0] {
            let f = |x: f64| sign * (x - 0.3) * (1.0 + x * x);
            let root = bisect(f, 0.0, 1.0, f(0.0));
            assert!((root - 0.3).abs() <= 2.0 * f64::EPSILON, "{root}");
        }
        // A root on a midpoint is returned at once.
        let calls = Cell::new(0);
        let root = bisect(counted(&calls, |x| x - 0.5), 0.0, 1.0, -0.5);
        assert_eq!((root, calls.get()), (0.5, 1));
        // Two evaluations for the root at 0.75.
        calls.set(0);
        let root = bisect(counted(&calls, |x| 0.75 - x), 0.0, 1.0, 0.75);
        assert_eq!((root, calls.get()), (0.75, 2));
        // About 52 halvings from [1, 2] to one ulp, never 200.
        calls.set(0);
        let root = bisect(counted(&calls, |x| x * x - 2.0), 1.0, 2.0, -1.0);
        assert!((root - 2f64.sqrt()).abs() <= 4.0 * f64::EPSILON, "{root}");
        assert!((50..=54).contains(&calls.get()), "{}", calls.get());
        // A bracket already one ulp wide: nothing to evaluate.
        calls.set(0);
        let a = 1.0_f64;
        let b = f64::from_bits(a.to_bits() + 1);
        let root = bisect(counted(&calls, |x| x - 1.0), a, b, -1.0);
        assert_eq!(calls.get(), 0);
        assert_eq!(root, 0.5 * (a + b));
    }

    #[test]
    fn bisection_stops_after_its_step_budget() {
        // A bracket of 2^300 wide halves 200 times and stops 2^100 wide.
        let calls = Cell::new(0);
        let huge = 2f64.powi(300);
        let root = bisect(counted(&calls, |x| x - 1.0), -huge, huge, -huge);
        assert_eq!(calls.get(), BISECTION_STEPS);
        assert!(root > 0.0 && root < 2f64.powi(101), "{root:e}");
    }

    #[test]
    fn regula_falsi_converges_superlinearly_from_either_side() {
        // Convex: plain regula falsi would keep the right end for ever and
        // creep; the Illinois halving brings it in.
        let f = |x: f64| x.powi(6) - 0.5;
        let root = 0.5f64.powf(1.0 / 6.0);
        for (a, b) in [(0.0, 1.5), (1.5, 0.0)] {
            let calls = Cell::new(0);
            let found = regula_falsi(counted(&calls, f), (a, f(a)), (b, f(b)), 1e-14);
            assert!((found - root).abs() < 1e-14, "{found} vs {root}");
            assert!(calls.get() <= 20, "{} evaluations", calls.get());
        }
        // Without the halving, 100 steps would not reach the root.
        let f = |x: f64| x.powi(20) - 0.5;
        let root = 0.5f64.powf(1.0 / 20.0);
        let found = regula_falsi(f, (0.0, f(0.0)), (1.0, f(1.0)), 1e-15);
        assert!((found - root).abs() < 1e-14, "{found} vs {root}");
    }

    #[test]
    fn regula_falsi_returns_the_end_nearer_zero() {
        // A wide width: the first trial (0.5, the secant of the ends'
        // values) ends the search; the end returned is the one of smaller
        // |f|: the moved one, the unmoved one, the first of a tie.
        let calls = Cell::new(0);
        let found = regula_falsi(counted(&calls, |x| x - 0.25), (0.0, -1.0), (1.0, 1.0), 0.6);
        assert_eq!((found, calls.get()), (0.5, 1));
        let found = regula_falsi(|x| 100.0 * (x - 0.005), (0.0, -0.01), (1.0, 1.0), 0.5);
        assert_eq!(found, 0.0);
        let found = regula_falsi(|x| 2.0 * x, (0.0, -1.0), (1.0, 1.0), 0.6);
        assert_eq!(found, 0.0);
        // The same with the ends given the other way round.
        let found = regula_falsi(|x| x - 0.75, (1.0, 1.0), (0.0, -1.0), 0.6);
        assert_eq!(found, 0.5);
        // A zero at an end, and a zero hit exactly.
        assert_eq!(regula_falsi(|x| x, (0.0, 0.0), (1.0, 1.0), 1e-12), 0.0);
        assert_eq!(
            regula_falsi(|x| x - 0.5, (0.0, -1.0), (1.0, 1.0), 1e-12),
            0.5
        );
    }

    #[test]
    fn regula_falsi_bisects_a_trial_outside_the_bracket() {
        // Values inconsistent with f (the ends' values lie): the secant
        // trial falls outside [0, 1], the midpoint is tried instead.
        let calls = Cell::new(0);
        let seen = std::cell::RefCell::new(Vec::new());
        let found = regula_falsi(
            |x| {
                calls.set(calls.get() + 1);
                seen.borrow_mut().push(x);
                x - 0.5
            },
            (0.0, 1.0),
            (1.0, 2.0),
            0.6,
        );
        assert_eq!(seen.borrow()[0], 0.5);
        assert_eq!(found, 0.5);
        assert_eq!(calls.get(), 1);
    }

    #[test]
    fn regula_falsi_stops_after_its_step_budget() {
        // A width it never reaches (0): the budget stops it.
        let calls = Cell::new(0);
        let f = |x: f64| x.powi(3) - 0.2;
        let found = regula_falsi(counted(&calls, f), (0.0, -0.2), (1.0, 0.8), 0.0);
        assert!((found - 0.2f64.cbrt()).abs() < 1e-15);
        assert_eq!(calls.get(), ILLINOIS_STEPS);
    }

    fn cubic(x: f64) -> (f64, f64) {
        (
            (x - 0.3) * (1.0 + x * x),
            (1.0 + x * x) + 2.0 * x * (x - 0.3),
        )
    }

    const FULL: Newton = Newton {
        tolerance: Tolerance {
            absolute: 4.0 * f64::EPSILON,
            relative: 4.0 * f64::EPSILON,
        },
        steps: 200,
        stall: 0.0,
    };

    #[test]
    fn safeguarded_newton_converges_quadratically_from_either_side() {
        let calls = Cell::new(0);
        let root = safeguarded_newton(counted(&calls, cubic), (0.0, 1.0), -0.3, 0.5, &FULL);
        assert!((root - 0.3).abs() <= f64::EPSILON, "{root}");
        assert!(calls.get() <= 6, "{} evaluations", calls.get());
        // Falling: the bracket's left end is positive.
        let falling = |x: f64| {
            let (v, s) = cubic(x);
            (-v, -s)
        };
        let root = safeguarded_newton(falling, (0.0, 1.0), 0.3, 0.9, &FULL);
        assert!((root - 0.3).abs() <= f64::EPSILON, "{root}");
        // A zero at the start.
        let calls = Cell::new(0);
        let root = safeguarded_newton(counted(&calls, cubic), (0.0, 1.0), -0.3, 0.3, &FULL);
        assert!(root == 0.3 && calls.get() == 1);
    }

    #[test]
    fn safeguarded_newton_bisects_where_newton_leaves_the_bracket() {
        // atan: Newton from 2 away overshoots far out of [-1, 9]; bisection
        // brings it in.
        let f = |x: f64| ((x - 0.4).atan(), 1.0 / (1.0 + (x - 0.4) * (x - 0.4)));
        let seen = std::cell::RefCell::new(Vec::new());
        let root = safeguarded_newton(
            |x| {
                seen.borrow_mut().push(x);
                f(x)
            },
            (-1.0, 9.0),
            f(-1.0).0,
            6.0,
            &FULL,
        );
        assert!((root - 0.4).abs() <= f64::EPSILON, "{root}");
        let seen = seen.borrow();
        assert!(seen.iter().all(|x| (-1.0..=9.0).contains(x)), "{seen:?}");
        // From 6 Newton goes to about -23: the midpoint of [-1, 6] instead.
        assert_eq!(seen[1], 2.5);
        // A flat start: the slope 0 sends Newton to infinity; the midpoint
        // of [1, 2] is the root.
        let flat = |x: f64| ((x - 1.0) * (x - 1.0) - 0.25, 2.0 * (x - 1.0));
        let seen = std::cell::RefCell::new(Vec::new());
        let root = safeguarded_newton(
            |x| {
                seen.borrow_mut().push(x);
                flat(x)
            },
            (1.0, 2.0),
            -0.25,
            1.0,
            &FULL,
        );
        assert_eq!((root, seen.borrow().clone()), (1.5, vec![1.0, 1.5]));
    }

    #[test]
    fn safeguarded_newton_keeps_a_step_onto_an_end() {
        // Linear: Newton from 0.5 lands exactly on the end 1 (the root).
        let seen = std::cell::RefCell::new(Vec::new());
        let root = safeguarded_newton(
            |x| {
                seen.borrow_mut().push(x);
                (x - 1.0, 1.0)
            },
            (0.0, 1.0),
            -1.0,
            0.5,
            &Newton {
                tolerance: Tolerance {
                    absolute: 1e-15,
                    relative: 0.0,
                },
                steps: 60,
                stall: 0.0,
            },
        );
        assert_eq!(*seen.borrow(), vec![0.5, 1.0]);
        assert_eq!(root, 1.0);
    }

    #[test]
    fn a_coarse_relative_tolerance_stops_newton_early() {
        // Root 1000, slope 2x there: from 1100 the Newton steps are about
        // 95, 4.5, 0.01, 5e-8. A relative tolerance of 1e-4 (0.1 at 1000)
        // stops after the third step; a much smaller width would take a
        // fourth, a much larger one would stop at the first.
        let f = |x: f64| (x * x - 1e6, 2.0 * x);
        let options = Newton {
            tolerance: Tolerance {
                absolute: 0.0,
                relative: 1e-4,
            },
            steps: 60,
            stall: 0.0,
        };
        let calls = Cell::new(0);
        let root = safeguarded_newton(counted(&calls, f), (0.0, 2000.0), -1e6, 1100.0, &options);
        assert_eq!(calls.get(), 3);
        assert!((root - 1000.0).abs() < 1e-4 && root != 1000.0, "{root}");
        // The absolute part alone, just as coarse.
        let options = Newton {
            tolerance: Tolerance {
                absolute: 0.1,
                relative: 0.0,
            },
            ..options
        };
        calls.set(0);
        safeguarded_newton(counted(&calls, f), (0.0, 2000.0), -1e6, 1100.0, &options);
        assert_eq!(calls.get(), 3);
    }

    #[test]
    fn a_narrow_bracket_stops_newton() {
        // Newton creeping (a slope 100 times too steep: steps of 1 % of the
        // distance) in a bracket whose far end is close: the bracket's
        // width stops it.
        let options = Newton {
            tolerance: Tolerance {
                absolute: 0.08,
                relative: 0.0,
            },
            steps: 60,
            stall: 0.0,
        };
        let calls = Cell::new(0);
        let root = safeguarded_newton(
            counted(&calls, |x| (x - 1.0, 0.1)),
            (0.0, 1.05),
            -1.0,
            0.99,
            &options,
        );
        // At 0.99: the value -0.01, Newton to 1.09 (outside [0.99, 1.05]):
        // the midpoint 1.02, and the bracket is 0.06 < 0.08 wide.
        assert_eq!(calls.get(), 1);
        assert_eq!(root, 0.5 * (0.99 + 1.05));
        // Without a tolerance the budget stops it.
        let options = Newton {
            tolerance: Tolerance {
                absolute: 0.0,
                relative: 0.0,
            },
            steps: 7,
            stall: 0.0,
        };
        calls.set(0);
        safeguarded_newton(
            counted(&calls, |x| (x - 1.0, 0.1)),
            (0.0, 1.05),
            -1.0,
            0.99,
            &options,
        );
        assert_eq!(calls.get(), 7);
    }

    #[test]
    fn a_stalled_newton_stops_at_the_current_point() {
        // Values that ignore x, alternating in sign: each Newton step is
        // 2^-34 (6e-11) long, the second no shorter than the first.
        let calls = Cell::new(0);
        let f = |_: f64| {
            calls.set(calls.get() + 1);
            let sign = if calls.get() % 2 == 1 { 1.0 } else { -1.0 };
            (sign * 2f64.powi(-34), 1.0)
        };
        let stalling = Newton {
            tolerance: Tolerance {
                absolute: 1e-15,
                relative: 0.0,
            },
            steps: 60,
            stall: 1e-9,
        };
        let root = safeguarded_newton(f, (0.0, 2.0), -1.0, 1.0, &stalling);
        assert_eq!(calls.get(), 2);
        assert_eq!(root, 1.0 - 2f64.powi(-34));
        // Steps longer than the stall width go on.
        calls.set(0);
        let f = |_: f64| {
            calls.set(calls.get() + 1);
            let sign = if calls.get() % 2 == 1 { 1.0 } else { -1.0 };
            (sign * 2f64.powi(-26), 1.0)
        };
        safeguarded_newton(f, (0.0, 2.0), -1.0, 1.0, &stalling);
        assert!(calls.get() > 2);
        // Shrinking steps below the stall width go on too.
        calls.set(0);
        let root = safeguarded_newton(
            counted(&calls, |x| (x - 1.0, 1.1)),
            (0.0, 2.0),
            -1.0,
            1.0 + 1e-10,
            &stalling,
        );
        assert!(calls.get() > 2);
        assert!((root - 1.0).abs() < 1e-15);
    }

    #[test]
    fn golden_section_shrinks_onto_the_minimum() {
        let calls = Cell::new(0);
        let mut f = counted(&calls, |x: f64| -> Result<f64, ()> {
            Ok((x - 0.3) * (x - 0.3))
        });
        let x = golden_section(&mut f, 0.0, 1.0, 60).unwrap();
        assert!((x - 0.3).abs() < 1e-8, "{x}");
        assert_eq!(calls.get(), 62);
        // A minimum at either end.
        let mut rising = |x: f64| -> Result<f64, ()> { Ok(x) };
        assert!(golden_section(&mut rising, 2.0, 3.0, 60).unwrap() - 2.0 < 1e-12);
        let mut falling = |x: f64| -> Result<f64, ()> { Ok(-x) };
        assert!(3.0 - golden_section(&mut falling, 2.0, 3.0, 60).unwrap() < 1e-12);
    }

    #[test]
    fn golden_section_steps_are_exact() {
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let mut rising = |x: f64| -> Result<f64, ()> { Ok(x) };
        // No iteration: the midpoint of [0, 1].
        assert_eq!(golden_section(&mut rising, 0.0, 1.0, 0).unwrap(), 0.5);
        // One: [0, 0.618] for a rising f, [0.382, 1] for a falling one.
        assert_eq!(
            golden_section(&mut rising, 0.0, 1.0, 1).unwrap(),
            0.5 * ratio
        );
        let mut falling = |x: f64| -> Result<f64, ()> { Ok(-x) };
        let x = golden_section(&mut falling, 0.0, 1.0, 1).unwrap();
        assert_eq!(x, 0.5 * (1.0 - ratio + 1.0));
        // Two: [0, 0.382] then; [0.618, 1].
        let x = golden_section(&mut rising, 0.0, 1.0, 2).unwrap();
        assert!((x - 0.5 * (1.0 - ratio)).abs() < 1e-15, "{x}");
        let x = golden_section(&mut falling, 0.0, 1.0, 2).unwrap();
        assert!((x - 0.5 * (ratio + 1.0)).abs() < 1e-15, "{x}");
        // The samples: 0.382 and 0.618 first, then the new inner point.
        let seen = std::cell::RefCell::new(Vec::new());
        let mut f = |x: f64| -> Result<f64, ()> {
            seen.borrow_mut().push(x);
            Ok((x - 0.7).abs())
        };
        golden_section(&mut f, 0.0, 1.0, 2).unwrap();
        let seen = seen.borrow();
        assert!((seen[0] - (1.0 - ratio)).abs() < 1e-15);
        assert!((seen[1] - ratio).abs() < 1e-15);
        // |0.382 - 0.7| > |0.618 - 0.7|: the bracket is [0.382, 1], its new
        // upper inner point 0.382 + 0.618^2.
        assert!(
            (seen[2] - (1.0 - ratio + ratio * ratio)).abs() < 1e-15,
            "{seen:?}"
        );
        // At 0.382 + 0.618 * 0.618 = 0.764: |0.764 - 0.7| < |0.618 - 0.7|,
        // so the bracket is [0.618, 1], its new upper inner point
        // 0.618 + 0.618 * 0.382.
        assert!(
            (seen[3] - (ratio + ratio * ratio * ratio)).abs() < 1e-12,
            "{seen:?}"
        );
    }

    #[test]
    fn golden_section_passes_the_first_error_on() {
        let calls = Cell::new(0);
        let mut f = |x: f64| {
            calls.set(calls.get() + 1);
            if calls.get() == 4 {
                Err(x)
            } else {
                Ok(x * x)
            }
        };
        let error = golden_section(&mut f, -1.0, 1.0, 10).unwrap_err();
        assert_eq!(calls.get(), 4);
        assert!(error.abs() < 1.0);
        let mut failing = |x: f64| -> Result<f64, f64> { Err(x) };
        assert!(golden_section(&mut failing, 0.0, 1.0, 10).is_err());
    }
}
