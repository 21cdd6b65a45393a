//! Unit tests of the elimination: the method's claims one by one.

use super::system::{dense_determinant, shifted_determinant, tensor3};
use super::trigonometric::Trigonometric;
use super::{harmonic_table, Cut, Elimination, DET_SAMPLES, HARMONICS};
use crate::ik::analytic::chain::Candidates;
use crate::ik::analytic::chain::Chain;
use crate::ik::analytic::structure::{ArmStructure, Motion};
use crate::ik::analytic::subproblems::rotation;
use crate::ik::analytic::test_random::{point, unit};
use crate::math::sin_cos;
use crate::math::wrap_angle;
use crate::math::Pose;
use crate::math::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// Which consecutive pair (0-based first joint) is made special.
#[derive(Clone, Copy, Debug)]
enum Special {
    None,
    Intersecting(usize),
    Parallel(usize),
}

fn random_arm(rng: &mut ChaCha8Rng, special: Special) -> ArmStructure {
    let mut points: Vec<_> = (0..6).map(|_| point(rng) * 2.0).collect();
    let mut axes: Vec<_> = (0..6).map(|_| unit(rng)).collect();
    match special {
        Special::None => {}
        Special::Intersecting(i) => points[i + 1] = points[i],
        Special::Parallel(i) => axes[i + 1] = axes[i],
    }
    let home = Pose::new(rotation(&unit(rng), 0.8), point(rng));
    ArmStructure::from_lines(points, axes, vec![Motion::Rotation; 6], home)
}

fn random_q(rng: &mut ChaCha8Rng) -> [f64; 6] {
    std::array::from_fn(|_| rng.gen_range(-3.1..3.1))
}

/// A random general arm, its chain, elimination and a configuration.
fn random_case(rng: &mut ChaCha8Rng) -> (ArmStructure, Chain, Elimination, [f64; 6]) {
    let s = random_arm(rng, Special::None);
    let chain = Chain::of(&s).unwrap();
    let elimination = Elimination::new(&chain, Cut::Tip).unwrap();
    (s, chain, elimination, random_q(rng))
}

/// Raghavan and Roth's claim the method rests on: the fourteen
/// functions are linear in `(1, cos, sin)` of each joint, so the fits on
/// the grid reproduce them at any angles (a wrong function or a wrong
/// grid inversion fails here).
#[test]
fn the_fits_reproduce_both_sides_at_random_angles() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..20 {
        let (s, chain, elimination, q) = random_case(&mut rng);
        let goal = s.forward_kinematics(&q) * chain.home_inverse;
        let right = elimination.fit_right(&goal);
        let (c, h) = (&chain.c, &chain.h);
        let r = |k: usize| rotation(&h[k], q[k]);
        let e = |k: usize, x: &Vector3<f64>| c[k] + r(k) * (x - c[k]);
        let point = e(2, &e(3, &e(4, &c[5])));
        let direction = r(2) * r(3) * r(4) * h[5];
        let exact = elimination.functions(&point, &direction);
        let m345 = tensor3(q[2], q[3], q[4]);
        // m1 (x) m2 is the first block of (1, 1, 0) (x) m1 (x) m2.
        let m12 = tensor3(0.0, q[0], q[1]);
        for (n, value) in exact.iter().enumerate() {
            let left: f64 = elimination.left[n]
                .iter()
                .zip(&m345)
                .map(|(a, b)| a * b)
                .sum();
            let right: f64 = right[n].iter().zip(&m12[..9]).map(|(a, b)| a * b).sum();
            assert!((left - value).abs() < 1e-12, "left {n}: {left} vs {value}");
            assert!(
                (right - value).abs() < 1e-12,
                "right {n}: {right} vs {value}"
            );
        }
    }
}

/// `det Sigma(q3)` vanishes at the generating configuration's `q3`, and
/// its harmonics above 8 vanish (Manocha and Canny's factor), so 17
/// samples give it exactly: checked with 25.
#[test]
fn the_determinant_is_of_degree_8_and_vanishes_at_the_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for _ in 0..20 {
        let (s, chain, elimination, q) = random_case(&mut rng);
        let system = elimination.system(&(s.forward_kinematics(&q) * chain.home_inverse));
        let det = |t: f64| system.determinant(t);
        let samples: Vec<f64> = (0..25).map(|j| det(TAU * j as f64 / 25.0)).collect();
        let largest = samples.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for k in 0..=12 {
            let (mut a, mut b) = (0.0, 0.0);
            for (j, v) in samples.iter().enumerate() {
                let (s, c) = sin_cos(TAU * (j * k) as f64 / 25.0);
                a += v * c;
                b += v * s;
            }
            let size = a.hypot(b) / 25.0;
            if k > HARMONICS {
                assert!(size < 1e-12 * largest, "harmonic {k}: {size} of {largest}");
            }
        }
        assert!(
            det(q[2]).abs() < 1e-10 * largest,
            "{} of {largest}",
            det(q[2])
        );
    }
}

/// The shifted-structure determinant against the dense 12 x 12
/// elimination of the same `Sigma`, on random equations (and on equations
/// whose first block is singular).
#[test]
fn the_shifted_determinant_agrees_with_the_dense_one() {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    for trial in 0..200 {
        let mut a: [[f64; 9]; 6] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
        if trial % 10 == 0 {
            // A0's third column a multiple of its first.
            for row in a.iter_mut() {
                row[2] = 0.5 * row[0];
            }
        }
        let mut sigma = [[0.0; 12]; 12];
        for (k, row) in a.iter().enumerate() {
            sigma[k][..9].copy_from_slice(row);
            sigma[6 + k][3..].copy_from_slice(row);
        }
        let dense = dense_determinant(&mut sigma);
        let shifted = shifted_determinant(&a);
        assert!(
            (dense - shifted).abs() <= 1e-12 * dense.abs().max(1e-3),
            "trial {trial}: {dense} vs {shifted}"
        );
    }
}

/// The roots of the polynomial: the trigonometric polynomial with
/// roots at chosen angles (a product of `sin((t - r)/2)` pairs) gives
/// them all back, including two roots 1e-4 rad apart.
#[test]
fn the_polynomial_roots_are_found() {
    let table = Elimination::new(
        &Chain::of(&random_arm(
            &mut ChaCha8Rng::seed_from_u64(5),
            Special::None,
        ))
        .unwrap(),
        Cut::Tip,
    )
    .unwrap()
    .root_table;
    let chosen = [0.3, 0.3001, 1.7, 2.9, 4.0, 4.4, 5.5, 6.1];
    // prod 2 sin((t - r)/2) over an even count is a trigonometric
    // polynomial of degree count/2; sampled and read by the DFT.
    let value = |t: f64| {
        chosen
            .iter()
            .map(|r| 2.0 * ((t - r) / 2.0).sin())
            .product::<f64>()
    };
    let samples = std::array::from_fn(|j| value(TAU * j as f64 / DET_SAMPLES as f64));
    let polynomial = Trigonometric::of_samples(&samples, &harmonic_table());
    let mut roots = [0.0; 20];
    let count = polynomial.roots(&table, &value, &mut roots);
    assert_eq!(count, chosen.len(), "{:?}", &roots[..count]);
    // Rounding of the interpolation (a few epsilon of the largest
    // sample) moves a root by that over the slope there: 1e-15 rad for
    // a simple root, 1e-11 for each of the pair 1e-4 apart.
    let largest = samples.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (found, expected) in roots[..count].iter().zip(&chosen) {
        let slope = chosen
            .iter()
            .filter(|r| *r != expected)
            .map(|r| 2.0 * ((expected - r) / 2.0).sin())
            .product::<f64>();
        // (At least 1e-14: the refinement stops at steps of 1e-15 rad.)
        let tolerance = (8.0 * f64::EPSILON * largest / slope.abs()).max(1e-14);
        assert!(
            (found - expected).abs() < tolerance,
            "{found} vs {expected}"
        );
    }
}

/// Every layout of one special pair, forwards or (pairs at 1-2) on the
/// reversed chain, and the general arm: the generating configuration is
/// among the solutions, each of which reproduces the pose.
#[test]
fn random_arms_of_every_pair_layout_are_solved() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let mut layouts = vec![Special::None];
    for i in 0..5 {
        layouts.push(Special::Intersecting(i));
        layouts.push(Special::Parallel(i));
    }
    for special in layouts {
        for _ in 0..4 {
            let s = random_arm(&mut rng, special);
            let (s, reversed) = match Elimination::new(&Chain::of(&s).unwrap(), Cut::Tip) {
                Some(_) => (s, false),
                None => (s.reversed(), true),
            };
            let chain = Chain::of(&s).unwrap();
            let elimination = Elimination::new(&chain, Cut::Tip)
                .unwrap_or_else(|| panic!("{special:?}: neither direction applies"));
            if matches!(special, Special::None) {
                assert!(!reversed, "the general arm needs no reversal");
            }
            for _ in 0..10 {
                let q = random_q(&mut rng);
                let target = s.forward_kinematics(&q);
                let mut found = Candidates::new();
                elimination.solve(&target, &mut found);
                for candidate in found.as_slice().iter().filter(|c| c.exact) {
                    let pose = s.forward_kinematics(&candidate.q[..6]);
                    assert!((pose.translation - target.translation).norm() < 1e-10);
                    assert!((pose.rotation - target.rotation).norm() < 1e-10);
                }
                let recovered = found.as_slice().iter().any(|c| {
                    c.exact
                        && c.q
                            .iter()
                            .zip(&q)
                            .all(|(a, b)| wrap_angle(a - b).abs() < 1e-6)
                });
                assert!(
                    recovered,
                    "{special:?} reversed {reversed}: {q:?} not found"
                );
            }
        }
    }
}

/// A spherical wrist makes `det Sigma` vanish identically, in both
/// directions: set-up says so rather than returning wrong roots.
#[test]
fn a_spherical_wrist_is_refused() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut s = random_arm(&mut rng, Special::None);
    s.points[4] = s.points[3];
    s.points[5] = s.points[3];
    assert!(Elimination::new(&Chain::of(&s).unwrap(), Cut::Tip).is_none());
    assert!(Elimination::new(&Chain::of(&s.reversed()).unwrap(), Cut::Tip).is_none());
}
