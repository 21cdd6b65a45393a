//! Unit tests of the degree-2 trigonometric polynomials' roots.

use super::{real_roots, Trig2};
use crate::math::wrap_angle;
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
