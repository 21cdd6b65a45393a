//! Unit tests of the root finders and the minimiser: results, evaluation
//! counts and the points tried, against hand-worked brackets.

use super::{
    bisect, golden_section, regula_falsi, safeguarded_newton, Newton, Tolerance, BISECTION_STEPS,
    ILLINOIS_STEPS,
};
use std::cell::Cell;

/// `f` counting its evaluations in `calls`.
fn counted<'a, T>(calls: &'a Cell<usize>, f: impl Fn(f64) -> T + 'a) -> impl FnMut(f64) -> T + 'a {
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
    // A bracket exactly `width` wide is not narrower: one trial.
    let found = regula_falsi(|x| x - 0.25, (0.0, -1.0), (1.0, 1.0), 1.0);
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
    // The first trial of [1, 2] for ends whose values put the secant's
    // zero outside, or exactly on an end: the midpoint 1.5 instead.
    for (a, b) in [
        // Values inconsistent with f (the ends' values lie): outside.
        ((1.0, 1.0), (2.0, 2.0)),
        // |f(a)| far below f(b): the secant's zero rounds onto a.
        ((1.0, -1e-300), (2.0, 1.0)),
        // And onto b.
        ((1.0, -1.0), (2.0, 1e-300)),
    ] {
        let seen = std::cell::RefCell::new(Vec::new());
        let found = regula_falsi(
            |x| {
                seen.borrow_mut().push(x);
                x - 1.5
            },
            a,
            b,
            0.6,
        );
        assert_eq!(*seen.borrow(), vec![1.5], "{a:?} {b:?}");
        assert_eq!(found, 1.5);
    }
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
    // Steps exactly as long as the stall width go on.
    calls.set(0);
    let at_width = Newton {
        stall: 2f64.powi(-34),
        ..stalling
    };
    safeguarded_newton(f, (0.0, 2.0), -1.0, 1.0, &at_width);
    assert!(calls.get() > 2);
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
fn golden_section_scales_with_the_bracket() {
    // On [2, 4] the inner points are 2 + 0.382 * 2 and 2 + 0.618 * 2.
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let seen = std::cell::RefCell::new(Vec::new());
    let mut f = |x: f64| -> Result<f64, ()> {
        seen.borrow_mut().push(x);
        Ok(x)
    };
    let x = golden_section(&mut f, 2.0, 4.0, 1).unwrap();
    let seen = seen.borrow();
    assert!((seen[0] - (4.0 - 2.0 * ratio)).abs() < 1e-15, "{seen:?}");
    assert!((seen[1] - (2.0 + 2.0 * ratio)).abs() < 1e-15, "{seen:?}");
    // Rising: the bracket [2, 2 + 2 * 0.618], its new lower point.
    assert!(
        (seen[2] - (2.0 + 2.0 * ratio * (1.0 - ratio))).abs() < 1e-15,
        "{seen:?}"
    );
    assert!((x - (2.0 + ratio)).abs() < 1e-15, "{x}");
}

#[test]
fn golden_section_keeps_the_upper_part_on_a_tie() {
    // Equal values at both inner points: the bracket [0.382, 1].
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut flat = |_: f64| -> Result<f64, ()> { Ok(1.0) };
    let x = golden_section(&mut flat, 0.0, 1.0, 1).unwrap();
    assert_eq!(x, 0.5 * (1.0 - ratio + 1.0));
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
