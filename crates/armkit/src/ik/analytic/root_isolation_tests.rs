//! The elimination's root isolation ([`trigonometric_roots`]) on
//! trigonometric polynomials of degree 8 with known roots: close pairs
//! placed anywhere inside a sample interval, including dips the cubic
//! Hermite interpolant of the interval's ends does not show, and a
//! property test of the error bounds the isolation relies on
//! ([`hermite_error_bounds`], [`derivative_bound`]).

use super::elimination::trigonometric::{
    derivative_bound, hermite_error_bounds, trigonometric_roots,
};
use super::elimination::ROOT_SAMPLES;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};

/// The isolation's sample interval, rad.
const STEP: f64 = TAU / ROOT_SAMPLES as f64;

/// Value and slope of `a0 + sum_k (a_k cos k t + b_k sin k t)`, and its
/// fourth derivative, evaluated term by term (the test's own evaluation).
fn evaluate(cosines: &[f64; 9], sines: &[f64; 9], t: f64) -> [f64; 3] {
    let mut out = [cosines[0], 0.0, 0.0];
    for k in 1..9 {
        let (s, c) = (k as f64 * t).sin_cos();
        let kf = k as f64;
        out[0] += cosines[k] * c + sines[k] * s;
        out[1] += kf * (sines[k] * c - cosines[k] * s);
        out[2] += kf.powi(4) * (cosines[k] * c + sines[k] * s);
    }
    out
}

/// The cubic Hermite interpolant of `f` (value, slope) between `a` and `b`
/// at `t`: value and slope (the standard basis, written here on its own).
fn hermite(a: f64, b: f64, fa: [f64; 2], fb: [f64; 2], t: f64) -> [f64; 2] {
    let h = b - a;
    let s = (t - a) / h;
    let (s2, s3) = (s * s, s * s * s);
    let value = (2.0 * s3 - 3.0 * s2 + 1.0) * fa[0]
        + (s3 - 2.0 * s2 + s) * h * fa[1]
        + (-2.0 * s3 + 3.0 * s2) * fb[0]
        + (s3 - s2) * h * fb[1];
    let slope = (6.0 * s2 - 6.0 * s) / h * fa[0]
        + (3.0 * s2 - 4.0 * s + 1.0) * fa[1]
        + (-6.0 * s2 + 6.0 * s) / h * fb[0]
        + (3.0 * s2 - 2.0 * s) * fb[1];
    [value, slope]
}

/// The smallest value of the Hermite interpolant of the sample interval
/// holding `t` (the dip the interpolant shows there).
fn interpolant_low(cosines: &[f64; 9], sines: &[f64; 9], t: f64) -> f64 {
    let a = (t / STEP).floor() * STEP;
    let b = a + STEP;
    let [va, sa, _] = evaluate(cosines, sines, a);
    let [vb, sb, _] = evaluate(cosines, sines, b);
    (0..=1000)
        .map(|i| hermite(a, b, [va, sa], [vb, sb], a + STEP * i as f64 / 1000.0)[0])
        .fold(f64::INFINITY, f64::min)
}

/// `roots` wrapped into `[0, 2 pi)` and sorted.
fn sorted(mut roots: Vec<f64>) -> Vec<f64> {
    for r in &mut roots {
        *r = r.rem_euclid(TAU);
    }
    roots.sort_by(f64::total_cmp);
    roots
}

/// Each found root within `tolerance(expected)` of an expected one, one to one.
fn assert_roots(found: &[f64], expected: &[f64], tolerance: impl Fn(f64) -> f64, what: &str) {
    let (found, expected) = (sorted(found.to_vec()), sorted(expected.to_vec()));
    assert_eq!(
        found.len(),
        expected.len(),
        "{what}: found {found:?}, expected {expected:?}"
    );
    for (f, e) in found.iter().zip(&expected) {
        let gap = (f - e).abs().min(TAU - (f - e).abs());
        assert!(gap <= tolerance(*e), "{what}: root {f} for {e} ({gap:e})");
    }
}

/// `1 - depth + cos(8 (t - phase))`: eight dips to `-depth`, each a pair of
/// roots `t = phase + (pi -+ acos(1 - depth)) / 8 + k pi / 4`, all at the
/// same place inside their sample interval (a turn is 16 intervals per dip).
/// Its fourth derivative is `4096 cos(8 (t - phase))`: at a dip the cubic
/// Hermite interpolant lies above the polynomial by up to the full bound
/// `4096 h^4 / 384`, so a dip shallower than that can be invisible to it.
#[test]
fn close_pairs_anywhere_in_a_sample_interval_are_found() {
    let (bound, _) = hermite_error_bounds(4096.0, STEP);
    let (mut cases, mut hidden) = (0, 0);
    for fraction in [0.03, 0.11, 0.25, 0.37, 0.5, 0.58, 0.71, 0.86, 0.97] {
        for relative_depth in [1e-4, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.5, 3.0, 30.0] {
            let depth = relative_depth * bound;
            // The dip's bottom at `fraction` of interval 5.
            let bottom = (5.0 + fraction) * STEP;
            let phase = bottom - PI / 8.0;
            let mut cosines = [0.0; 9];
            let mut sines = [0.0; 9];
            cosines[0] = 1.0 - depth;
            cosines[8] = (8.0 * phase).cos();
            sines[8] = (8.0 * phase).sin();
            let f = |t: f64| 1.0 - depth + (8.0 * (t - phase)).cos();
            let half = (1.0 - depth).acos() / 8.0;
            let expected: Vec<f64> = (0..8)
                .flat_map(|k| {
                    let centre = bottom + k as f64 * PI / 4.0;
                    [centre - half, centre + half]
                })
                .collect();
            if interpolant_low(&cosines, &sines, bottom) > 0.0 {
                hidden += 1;
            }
            let mut roots = [0.0; 20];
            let count = trigonometric_roots(cosines, sines, &f, &mut roots);
            // The polynomial's rounding (a few epsilon of its largest value,
            // 2) over its slope at a root, `8 sin(acos(1 - depth))`.
            let slope = 8.0 * (2.0 * depth - depth * depth).sqrt();
            let tolerance = |_| (16.0 * f64::EPSILON * 2.0 / slope).max(1e-14);
            assert_roots(
                &roots[..count],
                &expected,
                tolerance,
                &format!("dip at {fraction} of the interval, {relative_depth} of the bound"),
            );
            cases += 1;
        }
    }
    // Dips the interpolant of the interval's ends does not show are among them.
    assert!(
        hidden >= 20,
        "{hidden} of {cases} hidden from the interpolant"
    );
}

/// The trigonometric polynomial `prod_i 2 sin((t - r_i) / 2)` over an even
/// number of roots (degree: half their count), read by a discrete Fourier
/// transform of 17 samples (exact for degree 8).
fn from_roots(roots: &[f64]) -> ([f64; 9], [f64; 9]) {
    let value = |t: f64| {
        roots
            .iter()
            .map(|r| 2.0 * ((t - r) / 2.0).sin())
            .product::<f64>()
    };
    let (mut cosines, mut sines) = ([0.0; 9], [0.0; 9]);
    for j in 0..17 {
        let t = TAU * j as f64 / 17.0;
        let v = value(t);
        for k in 0..9 {
            let (s, c) = (k as f64 * t).sin_cos();
            cosines[k] += v * c;
            sines[k] += v * s;
        }
    }
    cosines[0] /= 17.0;
    sines[0] = 0.0;
    for k in 1..9 {
        cosines[k] *= 2.0 / 17.0;
        sines[k] *= 2.0 / 17.0;
    }
    (cosines, sines)
}

/// Random polynomials of degree 8 with one close pair (1e-5 to 1e-2 rad
/// apart) anywhere inside a random sample interval and the other roots
/// random: every root is found.
#[test]
fn random_close_pairs_among_random_roots_are_found() {
    let mut rng = ChaCha8Rng::seed_from_u64(37);
    let mut hidden = 0;
    for trial in 0..400 {
        let interval = rng.gen_range(0..ROOT_SAMPLES) as f64;
        let gap = 10f64.powf(rng.gen_range(-5.0..-2.0)).min(0.9 * STEP);
        let first = (interval + rng.gen_range(0.0..1.0)) * STEP;
        let mut roots = vec![first, (first + gap).rem_euclid(TAU)];
        let count = 2 * rng.gen_range(1..=7);
        while roots.len() < 2 + count {
            let r = rng.gen_range(0.0..TAU);
            if roots.iter().all(|&x| {
                let d = (x - r).rem_euclid(TAU);
                d.min(TAU - d) > 0.05
            }) {
                roots.push(r);
            }
        }
        let (cosines, sines) = from_roots(&roots);
        let value = |t: f64| {
            roots
                .iter()
                .map(|r| 2.0 * ((t - r) / 2.0).sin())
                .product::<f64>()
        };
        let largest = (0..ROOT_SAMPLES)
            .map(|j| value(j as f64 * STEP).abs())
            .fold(0.0, f64::max);
        if interpolant_low(&cosines, &sines, (first + gap / 2.0).rem_euclid(TAU)) > 0.0 {
            hidden += 1;
        }
        let mut found = [0.0; 20];
        let n = trigonometric_roots(cosines, sines, &value, &mut found);
        // The coefficients' rounding (a few epsilon of the largest sample)
        // over the slope at each root.
        let tolerance = |expected: f64| {
            let slope: f64 = roots
                .iter()
                .filter(|&&r| r != expected)
                .map(|r| 2.0 * ((expected - r) / 2.0).sin())
                .product();
            (16.0 * f64::EPSILON * largest / slope.abs()).max(1e-14)
        };
        assert_roots(
            &found[..n],
            &roots,
            tolerance,
            &format!("trial {trial}: pair {gap:e} apart at {first}"),
        );
    }
    assert!(hidden > 0, "no pair hidden from the interpolant");
}

/// The bounds the isolation certifies with, as a property: on random
/// trigonometric polynomials of degree 8 (random coefficients, or one
/// harmonic) and random intervals up to a sample interval long, the cubic
/// Hermite interpolant's errors stay within [`hermite_error_bounds`] of
/// [`derivative_bound`]; the fourth derivative stays within its bound; and
/// the bounds are tight (reached within a few per cent by the eighth
/// harmonic at its extremum), so they certify no more than they must.
#[test]
fn the_hermite_error_bounds_hold_and_are_tight() {
    let mut rng = ChaCha8Rng::seed_from_u64(384);
    let (mut worst_value, mut worst_slope) = (0.0_f64, 0.0_f64);
    for trial in 0..3000 {
        let (mut cosines, mut sines) = ([0.0; 9], [0.0; 9]);
        if trial % 3 == 0 {
            let k = rng.gen_range(1..9);
            let phase: f64 = rng.gen_range(0.0..TAU);
            cosines[k] = phase.cos();
            sines[k] = phase.sin();
        } else {
            for k in 0..9 {
                cosines[k] = rng.gen_range(-1.0..1.0);
                sines[k] = if k == 0 {
                    0.0
                } else {
                    rng.gen_range(-1.0..1.0)
                };
            }
        }
        let fourth = derivative_bound(&cosines, &sines, 4);
        let h = STEP * rng.gen_range(0.01..1.0);
        let a = rng.gen_range(0.0..TAU);
        let b = a + h;
        let [va, sa, _] = evaluate(&cosines, &sines, a);
        let [vb, sb, _] = evaluate(&cosines, &sines, b);
        let (value_bound, slope_bound) = hermite_error_bounds(fourth, h);
        for i in 0..=200 {
            let t = a + h * i as f64 / 200.0;
            let [v, s, d4] = evaluate(&cosines, &sines, t);
            let [hv, hs] = hermite(a, b, [va, sa], [vb, sb], t);
            // (Rounding of the evaluations: a few epsilon of the values.)
            let noise = 64.0 * f64::EPSILON * (1.0 + v.abs());
            assert!(
                d4.abs() <= fourth * (1.0 + 1e-12),
                "trial {trial}: {d4} > {fourth}"
            );
            assert!(
                (v - hv).abs() <= value_bound + noise,
                "trial {trial}: value error {:e} > {value_bound:e}",
                (v - hv).abs()
            );
            assert!(
                (s - hs).abs() <= slope_bound + noise / h,
                "trial {trial}: slope error {:e} > {slope_bound:e}",
                (s - hs).abs()
            );
        }
    }
    // Tightness: cos 8t around its maximum at t = 0, over a short interval
    // where its fourth derivative is nearly constant (like t^4 there).
    let (mut cosines, sines) = ([0.0; 9], [0.0; 9]);
    cosines[8] = 1.0;
    let h = STEP / 8.0;
    let (a, b) = (-h / 2.0, h / 2.0);
    let fa = evaluate(&cosines, &sines, a);
    let fb = evaluate(&cosines, &sines, b);
    let (value_bound, slope_bound) = hermite_error_bounds(derivative_bound(&cosines, &sines, 4), h);
    for i in 0..=2000 {
        let t = a + h * i as f64 / 2000.0;
        let [v, s, _] = evaluate(&cosines, &sines, t);
        let [hv, hs] = hermite(a, b, [fa[0], fa[1]], [fb[0], fb[1]], t);
        worst_value = worst_value.max((v - hv).abs() / value_bound);
        worst_slope = worst_slope.max((s - hs).abs() / slope_bound);
    }
    // t^4's errors: h^4 / 16 at the middle (the bound's 24 h^4 / 384) and
    // sqrt(3) h^3 / 9 on the slope (0.577 of the bound's 24 h^3 / 72).
    assert!(worst_value > 0.99 && worst_value <= 1.0, "{worst_value}");
    assert!(worst_slope > 0.57 && worst_slope <= 0.58, "{worst_slope}");
    // The second derivative's bound: |p''| of one harmonic is k^2 at most.
    assert_eq!(derivative_bound(&cosines, &sines, 2), 64.0);
}
