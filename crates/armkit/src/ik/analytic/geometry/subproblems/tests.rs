//! Unit tests of the subproblems: each against its equation on random
//! instances, exact and least-squares.

use super::{atan2, rotation, subproblem1, subproblem2, subproblem3, subproblem4};
use crate::ik::analytic::test_random::{unit, vector};
use crate::math::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_angle(rng: &mut ChaCha8Rng) -> f64 {
    rng.gen_range(-std::f64::consts::PI..std::f64::consts::PI)
}

/// True when some angle of `found` equals `t` modulo 2 pi to 1e-8.
fn contains_angle(found: &[f64], t: f64) -> bool {
    found
        .iter()
        .any(|f| crate::math::wrap_angle(f - t).abs() < 1e-8)
}

#[test]
fn atan2_matches_the_platform_to_two_ulp() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut worst: f64 = 0.0;
    let mut check = |y: f64, x: f64| {
        let (ours, platform) = (atan2(y, x), y.atan2(x));
        let ulp = f64::EPSILON * platform.abs().max(f64::MIN_POSITIVE);
        worst = worst.max((ours - platform).abs() / ulp);
        assert_eq!(
            ours.is_sign_negative(),
            platform.is_sign_negative(),
            "{y} {x}"
        );
    };
    for _ in 0..200_000 {
        let angle = rng.gen_range(-std::f64::consts::PI..std::f64::consts::PI);
        let length = 10f64.powf(rng.gen_range(-6.0..3.0));
        check(length * angle.sin(), length * angle.cos());
    }
    // The octant and interval boundaries, the axes and tiny angles.
    for k in -800..=800 {
        let angle = k as f64 * std::f64::consts::PI / 800.0;
        for d in [0.0, 1e-15, -1e-12, 1e-9] {
            let a = angle + d;
            check(a.sin(), a.cos());
        }
    }
    for r in [
        7.0 / 16.0,
        11.0 / 16.0,
        1.0 / 16.0,
        3.0 / 16.0,
        15.0 / 16.0,
        1.0,
        1e-300,
        1e-20,
        1.0 - 1e-16,
    ] {
        for (sy, sx) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            check(sy * r, sx * 1.0);
            check(sy * 1.0, sx * r);
        }
    }
    assert!(worst <= 2.0, "worst {worst} ulp");
    assert_eq!(atan2(0.0, 0.0), 0.0);
    assert_eq!(atan2(0.0, -1.0), std::f64::consts::PI);
    assert!(atan2(f64::NAN, 1.0).is_nan());
    assert_eq!(atan2(1.0, f64::INFINITY), 0.0);
}

/// The heavy version: 20 million directions, half of them within 1e-3
/// of the table's nodes and midpoints (`a = k / 32`, `(2 k + 1) / 64`),
/// against the platform routine: at most 1.5 units of `EPSILON |atan2|`
/// (the platform's own error included).
#[test]
#[ignore]
fn atan2_matches_the_platform_on_many_directions() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let mut worst: f64 = 0.0;
    for i in 0..20_000_000u64 {
        let (y, x) = if i % 2 == 0 {
            let angle = random_angle(&mut rng);
            (angle.sin(), angle.cos())
        } else {
            let k = rng.gen_range(0..32) as f64;
            let node = if i % 4 == 1 {
                k / 32.0
            } else {
                (2.0 * k + 1.0) / 64.0
            };
            let a = node + rng.gen_range(-1e-3..1e-3);
            let (y, x) = if i % 8 < 4 { (a, 1.0) } else { (1.0, -a) };
            (y, x)
        };
        let (ours, platform) = (atan2(y, x), y.atan2(x));
        let ulp = f64::EPSILON * platform.abs().max(f64::MIN_POSITIVE);
        worst = worst.max((ours - platform).abs() / ulp);
    }
    assert!(worst <= 1.5, "worst {worst}");
}

#[test]
fn rotation_matches_nalgebra() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..100 {
        let k = unit(&mut rng);
        let t = random_angle(&mut rng);
        let expected = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(k), t);
        assert!((rotation(&k, t) - expected.matrix()).amax() < 1e-15);
    }
}

#[test]
fn subproblem1_recovers_the_rotation() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for _ in 0..1000 {
        let k = unit(&mut rng);
        let p1 = vector(&mut rng);
        let t = random_angle(&mut rng);
        let (found, exact) = subproblem1(&k, &p1, &(rotation(&k, t) * p1));
        assert!(exact);
        assert!(crate::math::wrap_angle(found - t).abs() < 1e-9);
    }
}

#[test]
fn subproblem1_least_squares_aligns_the_projections() {
    let k = Vector3::z();
    let p1 = Vector3::new(1.0, 0.0, 0.0);
    let p2 = Vector3::new(0.0, 3.0, 1.0);
    let (t, exact) = subproblem1(&k, &p1, &p2);
    assert!(!exact);
    assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
}

#[test]
fn subproblem2_finds_the_generating_pair() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..1000 {
        let k1 = unit(&mut rng);
        let k2 = unit(&mut rng);
        let p1 = vector(&mut rng);
        let (t1, t2) = (random_angle(&mut rng), random_angle(&mut rng));
        // p2 such that R(k1, t1) p1 = R(k2, t2) p2.
        let p2 = rotation(&k2, -t2) * rotation(&k1, t1) * p1;
        let pairs = subproblem2(&k1, &p1, &k2, &p2);
        assert!(pairs.exact);
        for (a, b) in pairs.as_slice() {
            let residual = rotation(&k1, *a) * p1 - rotation(&k2, *b) * p2;
            assert!(residual.norm() < 1e-9, "{residual}");
        }
        assert!(pairs.as_slice().iter().any(|(a, b)| {
            crate::math::wrap_angle(a - t1).abs() < 1e-7
                && crate::math::wrap_angle(b - t2).abs() < 1e-7
        }));
    }
}

#[test]
fn subproblem2_without_intersection_is_least_squares() {
    let k1 = Vector3::z();
    let k2 = Vector3::x();
    // Circle 1 at height 1 of radius 1 about z; circle 2 at x = 1.
    let p1 = Vector3::new(0.0, 0.1, 1.0);
    let p2 = Vector3::new(1.0, 0.0, 0.05);
    let pairs = subproblem2(&k1, &p1, &k2, &p2);
    assert!(!pairs.exact);
    assert_eq!(pairs.as_slice().len(), 1);
    assert!(subproblem2(&k1, &p1, &k1, &p2).as_slice().is_empty());
}

#[test]
fn subproblem3_finds_the_generating_angle() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for _ in 0..1000 {
        let k = unit(&mut rng);
        let p1 = vector(&mut rng);
        let p2 = vector(&mut rng);
        let t = random_angle(&mut rng);
        let d = (rotation(&k, t) * p1 - p2).norm();
        let angles = subproblem3(&k, &p1, &p2, d);
        assert!(angles.exact);
        for a in angles.as_slice() {
            let err = (rotation(&k, *a) * p1 - p2).norm() - d;
            assert!(err.abs() < 1e-8, "{err}");
        }
        assert!(contains_angle(angles.as_slice(), t));
    }
}

#[test]
fn subproblem3_out_of_reach_returns_the_nearest_distance() {
    let k = Vector3::z();
    let p1 = Vector3::new(1.0, 0.0, 0.0);
    let p2 = Vector3::new(3.0, 0.0, 0.0);
    // Distances range over [2, 4]: 5 is out of reach, 4 is the nearest.
    let angles = subproblem3(&k, &p1, &p2, 5.0);
    assert!(!angles.exact);
    let t = angles.as_slice()[0];
    assert!(((rotation(&k, t) * p1 - p2).norm() - 4.0).abs() < 1e-12);
}

#[test]
fn subproblem4_finds_the_generating_angle() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..1000 {
        let h = unit(&mut rng);
        let k = unit(&mut rng);
        let p = vector(&mut rng);
        let t = random_angle(&mut rng);
        let d = h.dot(&(rotation(&k, t) * p));
        let angles = subproblem4(&h, &k, &p, d);
        assert!(angles.exact);
        for a in angles.as_slice() {
            assert!((h.dot(&(rotation(&k, *a) * p)) - d).abs() < 1e-9);
        }
        assert!(contains_angle(angles.as_slice(), t));
    }
}

#[test]
fn subproblem4_out_of_reach_is_least_squares() {
    let h = Vector3::x();
    let k = Vector3::z();
    let p = Vector3::new(1.0, 0.0, 0.0);
    let angles = subproblem4(&h, &k, &p, -2.0);
    assert!(!angles.exact);
    assert!((angles.as_slice()[0].abs() - std::f64::consts::PI).abs() < 1e-15);
}
