//! A fast, accurate `sin_cos` for joint angles.
//!
//! Forward kinematics spends most of its time in trigonometry: the platform
//! `f64::sin_cos` calls `sin` and `cos` separately, each doing its own
//! argument reduction. This computes both from one Cody-Waite reduction and the
//! fdlibm minimax kernels (the polynomials of FreeBSD's and musl's
//! `__kernel_sin` / `__kernel_cos`, public domain, Sun Microsystems 1993), which
//! are accurate to about one unit in the last place on `[-pi/4, pi/4]`.
//! Arguments beyond `|x| > 1e5` (never joint angles) and non-finite ones go to
//! the platform routine.

#![allow(clippy::excessive_precision)]

#[cfg(test)]
use super::lanes::F64x4;
use super::lanes::{Lane, Lanes4};

// fdlibm kernel coefficients, written as fdlibm prints them.
const S1: f64 = -1.666_666_666_666_663_243_48e-01;
const S2: f64 = 8.333_333_333_322_489_461_24e-03;
const S3: f64 = -1.984_126_982_985_794_931_34e-04;
const S4: f64 = 2.755_731_370_707_006_767_89e-06;
const S5: f64 = -2.505_076_025_340_686_341_95e-08;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;
const C1: f64 = 4.166_666_666_666_660_190_37e-02;
const C2: f64 = -1.388_888_888_887_410_957_49e-03;
const C3: f64 = 2.480_158_728_947_672_941_78e-05;
const C4: f64 = -2.755_731_435_139_066_330_35e-07;
const C5: f64 = 2.087_572_321_298_174_827_90e-09;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

// pi/2 split for the reduction: PIO2_1 holds the first 33 bits (so that
// n * PIO2_1 is exact for |n| < 2^20), PIO2_2 the next 33, PIO2_2T the rest.
const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;
const PIO2_1: f64 = 1.570_796_326_734_125_614_17e+00;
const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
const PIO2_2T: f64 = 2.022_266_248_795_950_631_54e-21;
const TO_INT: f64 = 1.5 / f64::EPSILON;
const REDUCTION_LIMIT: f64 = 1e5;

// pi/2 in three parts of 53 bits each, for the fused reduction: with one
// rounding, x - n PIO2_A is exact for |x| < REDUCTION_LIMIT (the difference
// is below 2 and lies on the grid of n PIO2_A's last bit), so three fused
// steps give r to about half an ulp without the double-double tail.
const PIO2_A: f64 = std::f64::consts::FRAC_PI_2;
const PIO2_B: f64 = 6.123_233_995_736_766e-17;
const PIO2_C: f64 = -1.497_384_904_859_169_8e-33;

/// `(sin x, cos x)` for an angle in radians, to about one ulp.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // NaN fails the comparison and goes to the platform routine too.
    if x.abs() < REDUCTION_LIMIT {
        reduced_sin_cos(x)
    } else {
        x.sin_cos()
    }
}

/// `out[i] = sin_cos(angles[i])` for every `i` (the shorter length wins).
/// One range check for the whole slice, then a loop without branches that
/// the compiler can vectorize: cheaper than calling [`sin_cos`] per angle.
#[inline]
pub fn sin_cos_slice(angles: &[f64], out: &mut [(f64, f64)]) {
    if angles.iter().all(|x| x.abs() < REDUCTION_LIMIT) {
        for (o, &x) in out.iter_mut().zip(angles) {
            *o = reduced_sin_cos(x);
        }
    } else {
        for (o, &x) in out.iter_mut().zip(angles) {
            *o = sin_cos(x);
        }
    }
}

/// `(sin, cos)` of four angles at once, lane by lane (each lane equal, bit
/// for bit, to [`sin_cos`] of its angle: no product is fused here), on
/// [`super::F64x4`] or the AVX register lanes: the vectorised form of the
/// batched kinematics. One range check for the four lanes, then the
/// branch-free reduction and polynomials on all four; a lane out of range
/// (or NaN) sends the four to the checked scalar path.
#[inline(always)]
pub fn sin_cos_x4<L: Lanes4>(x: L) -> (L, L) {
    if x.all_below(REDUCTION_LIMIT) {
        reduced_sin_cos(x)
    } else {
        checked_lanes(x)
    }
}

/// `(sin, cos)` of four angles at once for the batched kinematics, which
/// may differ from [`sin_cos`] in the last bit: on lanes whose
/// [`Lane::mul_add`] is fused ([`Lane::FUSED`], the AVX register lanes) a
/// single three-step Cody-Waite reduction and Horner polynomials of fused
/// multiply-adds, about 1 ulp from libm (the tests bound it over the joint
/// ranges); on the other lanes [`sin_cos_x4`] (the fused reduction needs
/// the single rounding). A lane with `|x| >= 1e5` or not finite sends the
/// four to the checked scalar path, as [`sin_cos_x4`] does.
#[inline(always)]
pub fn sin_cos_x4_fused<L: Lanes4>(x: L) -> (L, L) {
    if !L::FUSED {
        sin_cos_x4(x)
    } else if x.all_below(REDUCTION_LIMIT) {
        fused_reduced_sin_cos(x)
    } else {
        checked_lanes(x)
    }
}

/// [`sin_cos`] lane by lane (out of range or not finite lanes).
#[inline(always)]
fn checked_lanes<L: Lanes4>(x: L) -> (L, L) {
    let (s, c) = checked_values(x.to_array());
    (L::from_array(s), L::from_array(c))
}

/// Out of line (rare, and the batched kernels' loops stay small); plain
/// arrays, so that no vector register crosses into a function compiled
/// without the caller's features.
#[inline(never)]
fn checked_values(x: [f64; 4]) -> ([f64; 4], [f64; 4]) {
    let pairs = x.map(sin_cos);
    (pairs.map(|p| p.0), pairs.map(|p| p.1))
}

/// [`sin_cos_x4_fused`]'s kernel for finite `|x| < REDUCTION_LIMIT` on fused
/// lanes: n the nearest integer to x / (pi/2) (the add-and-subtract trick,
/// its low bits the quadrant), r = x - n pi/2 in three fused steps, then
/// fdlibm's polynomials in Horner form, cos keeping the rounding error of
/// `1 - r^2/2` as fdlibm does.
#[inline(always)]
fn fused_reduced_sin_cos<L: Lane>(x: L) -> (L, L) {
    let to_int = L::splat(TO_INT);
    let shifted = x.mul_add(L::splat(INV_PIO2), to_int);
    let n = shifted - to_int;
    let r = n.mul_add(L::splat(-PIO2_A), x);
    let r = n.mul_add(L::splat(-PIO2_B), r);
    let r = n.mul_add(L::splat(-PIO2_C), r);
    let z = r * r;
    let s = (r * z).mul_add(horner(z, [S1, S2, S3, S4, S5, S6]), r);
    let one = L::splat(1.0);
    let hz = z * 0.5;
    let w = one - hz;
    let lost = (one - w) - hz;
    let c = w + (z * z).mul_add(horner(z, [C1, C2, C3, C4, C5, C6]), lost);
    L::by_quadrant(s, c, shifted)
}

/// `k[0] + z k[1] + ... + z^5 k[5]` in fused Horner steps (a function, not
/// a closure: a closure is not inlined into the caller's target features).
#[inline(always)]
fn horner<L: Lane>(z: L, k: [f64; 6]) -> L {
    let p = z.mul_add(L::splat(k[5]), L::splat(k[4]));
    let p = z.mul_add(p, L::splat(k[3]));
    let p = z.mul_add(p, L::splat(k[2]));
    let p = z.mul_add(p, L::splat(k[1]));
    z.mul_add(p, L::splat(k[0]))
}

/// [`sin_cos_slice`] four angles per [`sin_cos_x4`] on lanes `L` (the
/// last group padded with zeros, computed and dropped): the same bits, in a
/// quarter of the instructions where `L` is a vector register.
#[inline(always)]
pub fn sin_cos_slice_x4<L: Lanes4>(angles: &[f64], out: &mut [(f64, f64)]) {
    for (angles, out) in angles.chunks(4).zip(out.chunks_mut(4)) {
        let mut group = [0.0; 4];
        group[..angles.len()].copy_from_slice(angles);
        let (s, c) = sin_cos_x4(L::from_array(group));
        let (s, c) = (s.to_array(), c.to_array());
        for (k, o) in out.iter_mut().enumerate().take(angles.len()) {
            *o = (s[k], c[k]);
        }
    }
}

/// [`sin_cos`] for a finite `|x| < REDUCTION_LIMIT`, without branches, on
/// one value or on four lanes (the same operations, lane-wise).
#[inline(always)]
fn reduced_sin_cos<L: Lane>(x: L) -> (L, L) {
    // n = nearest integer to x / (pi/2), by the add-and-subtract trick; the
    // low bits of `shifted` hold n modulo 4 (two's complement), the quadrant.
    let to_int = L::splat(TO_INT);
    let shifted = x * INV_PIO2 + to_int;
    let n = shifted - to_int;
    // r = x - n pi/2 in double-double (head, tail).
    let t = x - n * PIO2_1;
    let w = n * PIO2_2;
    let head_before_tail = t - w;
    let tail = n * PIO2_2T - ((t - head_before_tail) - w);
    let head = head_before_tail - tail;
    let tail = (head_before_tail - head) - tail;
    let s = kernel_sin(head, tail);
    let c = kernel_cos(head, tail);
    L::by_quadrant(s, c, shifted)
}

/// `(sin, cos)` of `r + quadrant pi/2` from `(sin r, cos r)`: quadrant 0
/// `(s, c)`, 1 `(c, -s)`, 2 `(-s, -c)`, 3 `(-c, s)` (only the two low bits
/// of `quadrant` count). Without branches: the quadrant of a random joint
/// angle is unpredictable, and a mispredicted four-way branch cost more than
/// the polynomials (FK of a 6R arm took 143 instead of ~115 ns on random
/// configurations).
#[inline(always)]
pub(super) fn by_quadrant(s: f64, c: f64, quadrant: u64) -> (f64, f64) {
    let (s_bits, c_bits) = (s.to_bits(), c.to_bits());
    // All ones when the quadrant is odd: sin and cos swap.
    let swap = (quadrant & 1).wrapping_neg();
    let first = (s_bits & !swap) | (c_bits & swap);
    let second = (c_bits & !swap) | (s_bits & swap);
    // Sign bits: sin is negative in quadrants 2, 3; cos in quadrants 1, 2.
    let sin_sign = (quadrant & 2) << 62;
    let cos_sign = (quadrant.wrapping_add(1) & 2) << 62;
    (
        f64::from_bits(first ^ sin_sign),
        f64::from_bits(second ^ cos_sign),
    )
}

/// sin(x + y) for |x| <= pi/4, |y| tiny (the reduction's tail).
#[inline(always)]
fn kernel_sin<L: Lane>(x: L, y: L) -> L {
    let z = x * x;
    let v = z * x;
    let r = L::splat(S2) + z * (L::splat(S3) + z * (L::splat(S4) + z * (L::splat(S5) + z * S6)));
    x - ((z * (y * 0.5 - v * r) - y) - v * S1)
}

/// cos(x + y) for |x| <= pi/4, |y| tiny.
#[inline(always)]
fn kernel_cos<L: Lane>(x: L, y: L) -> L {
    let z = x * x;
    let r = z
        * (L::splat(C1)
            + z * (L::splat(C2)
                + z * (L::splat(C3) + z * (L::splat(C4) + z * (L::splat(C5) + z * C6)))));
    let hz = z * 0.5;
    let one = L::splat(1.0);
    let w = one - hz;
    w + (((one - w) - hz) + (z * r - x * y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_platform_sin_cos_to_a_few_ulp() {
        let mut worst: f64 = 0.0;
        // A dense sweep over joint-angle ranges plus the multiples of pi/2,
        // where the reduction is hardest.
        let mut x = -40.0;
        while x < 40.0 {
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            worst = worst.max((s - s0).abs()).max((c - c0).abs());
            x += 0.000_731;
        }
        for k in -200..200 {
            let x = k as f64 * std::f64::consts::FRAC_PI_2;
            for dx in [0.0, 1e-12, -1e-9, 3e-7] {
                let (s, c) = sin_cos(x + dx);
                let (s0, c0) = (x + dx).sin_cos();
                worst = worst.max((s - s0).abs()).max((c - c0).abs());
            }
        }
        assert!(worst < 4.0 * f64::EPSILON, "worst error {worst:e}");
    }

    /// [`sin_cos_x4`] compiled for AVX2 and FMA, as the batched kinematics
    /// run it.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn sin_cos_x4_avx2_fma(x: F64x4) -> (F64x4, F64x4) {
        sin_cos_x4(x)
    }

    /// [`sin_cos_x4`] on the AVX register lanes, as the vector kernels run it.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn sin_cos_x4_avx_registers(x: F64x4) -> (F64x4, F64x4) {
        use crate::math::Avx4;
        let (s, c) = sin_cos_x4(Avx4::from_array(x.0));
        (F64x4(s.to_array()), F64x4(c.to_array()))
    }

    #[test]
    fn four_lanes_match_libm_over_the_joint_ranges_in_both_builds() {
        type Lanes = fn(F64x4) -> (F64x4, F64x4);
        let mut builds: Vec<(&str, Lanes)> = vec![("baseline", sin_cos_x4)];
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            // SAFETY: both features detected.
            builds.push(("avx2+fma", |x| unsafe { sin_cos_x4_avx2_fma(x) }));
            builds.push(("avx registers", |x| unsafe { sin_cos_x4_avx_registers(x) }));
        }
        for (name, lanes) in builds {
            let mut worst: f64 = 0.0;
            // Joint ranges (+-2 pi, and several turns) in steps that put
            // every quadrant in every lane; then NaN and a huge angle in one lane.
            let mut x = -40.0;
            while x < 40.0 {
                let v = F64x4([x, x + 0.25, -x * 0.5, x * 0.03]);
                let (s, c) = lanes(v);
                for l in 0..crate::math::LANES {
                    let (s0, c0) = v.0[l].sin_cos();
                    worst = worst.max((s.0[l] - s0).abs()).max((c.0[l] - c0).abs());
                    // Lane by lane the scalar routine's bits.
                    let (s1, c1) = sin_cos(v.0[l]);
                    assert_eq!(
                        (s.0[l].to_bits(), c.0[l].to_bits()),
                        (s1.to_bits(), c1.to_bits())
                    );
                }
                x += 0.000_917;
            }
            assert!(worst < 4.0 * f64::EPSILON, "{name}: worst error {worst:e}");
            let (s, c) = lanes(F64x4([0.5, f64::NAN, 1e6, -1.0]));
            assert!(s.0[1].is_nan() && c.0[1].is_nan(), "{name}");
            assert_eq!((s.0[2], c.0[2]), 1e6f64.sin_cos(), "{name}");
            assert_eq!((s.0[3], c.0[3]), sin_cos(-1.0), "{name}");
        }
    }

    /// [`sin_cos_x4_fused`] on the AVX register lanes (its fused build).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn sin_cos_fused_avx(x: F64x4) -> (F64x4, F64x4) {
        let (s, c) = sin_cos_x4_fused(crate::math::Avx4::from_array(x.0));
        (F64x4(s.to_array()), F64x4(c.to_array()))
    }

    /// `|value - reference|` in units in the last place of `reference`
    /// (the spacing of doubles at its magnitude).
    fn ulps(value: f64, reference: f64) -> f64 {
        let magnitude = reference.abs();
        let spacing = f64::from_bits(magnitude.to_bits() + 1) - magnitude;
        (value - reference).abs() / spacing
    }

    #[test]
    fn fused_lanes_are_within_about_one_ulp_of_libm() {
        // The portable lanes do not fuse: there the fused form is the
        // reference's, bit for bit.
        let v = F64x4([0.3, -2.0, 7.5, 1e6]);
        assert_eq!(sin_cos_x4_fused(v), sin_cos_x4(v));
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            let pi = std::f64::consts::PI;
            // Joint ranges, densely (every quadrant in every lane); the
            // multiples of pi/2 up to +-4 pi and far out, a few ulps either
            // side, where the reduction cancels most; a coarse sweep up to
            // the reduction's limit.
            let mut angles = Vec::new();
            let mut x = -4.0 * pi;
            while x < 4.0 * pi {
                angles.push(x);
                x += 1.3e-5;
            }
            for k in (-8..=8).chain([101, -2047, 40_000, 63_661]) {
                let m = k as f64 * std::f64::consts::FRAC_PI_2;
                let mut y = m;
                for _ in 0..8 {
                    angles.extend([y, -y]);
                    y = f64::from_bits(y.to_bits() + 1);
                }
            }
            let mut x = 4.0 * pi;
            while x < 1e5 {
                angles.extend([x, -x]);
                x += 0.37;
            }
            angles.extend([1e-300, -5e-324, 1e-8, 99_999.99]);
            let mut worst: f64 = 0.0;
            for group in angles.chunks(4) {
                let mut v = [0.25; 4];
                v[..group.len()].copy_from_slice(group);
                // SAFETY: both features detected.
                let (s, c) = unsafe { sin_cos_fused_avx(F64x4(v)) };
                for (l, x) in v.iter().enumerate() {
                    let (s0, c0) = x.sin_cos();
                    worst = worst.max(ulps(s.0[l], s0)).max(ulps(c.0[l], c0));
                }
            }
            assert!(worst <= 1.0, "worst {worst} ulp");
            // Zeros, then out of range and non-finite lanes: the checked path.
            // SAFETY (these two calls): both features detected.
            let (s, c) = unsafe { sin_cos_fused_avx(F64x4([0.0, -0.0, 1e5, 1e300])) };
            assert_eq!((s.0[0], s.0[1], c.0[0], c.0[1]), (0.0, 0.0, 1.0, 1.0));
            assert_eq!((s.0[2], c.0[2]), sin_cos(1e5));
            assert_eq!((s.0[3], c.0[3]), 1e300f64.sin_cos());
            let (s, c) = unsafe { sin_cos_fused_avx(F64x4([f64::NAN, f64::INFINITY, 1.0, 2.0])) };
            assert!(s.0[0].is_nan() && c.0[0].is_nan() && s.0[1].is_nan() && c.0[1].is_nan());
            assert!(ulps(s.0[3], 2f64.sin()) <= 1.0 && ulps(c.0[2], 1f64.cos()) <= 1.0);
            eprintln!(
                "fused sin_cos: worst {worst} ulp over {} angles",
                angles.len()
            );
        }
    }

    #[test]
    fn large_and_non_finite_arguments_use_the_platform() {
        assert_eq!(sin_cos(1e6), 1e6f64.sin_cos());
        assert!(sin_cos(f64::NAN).0.is_nan());
        assert!(sin_cos(f64::INFINITY).1.is_nan());
    }

    /// [`sin_cos_slice_x4`] on the AVX register lanes.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn sin_cos_slice_avx(angles: &[f64], out: &mut [(f64, f64)]) {
        sin_cos_slice_x4::<crate::math::Avx4>(angles, out)
    }

    #[test]
    fn the_slice_forms_equal_the_scalar_form_bit_for_bit() {
        type Slice = fn(&[f64], &mut [(f64, f64)]);
        let mut forms: Vec<Slice> = vec![sin_cos_slice, sin_cos_slice_x4::<F64x4>];
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            // SAFETY: both features detected.
            forms.push(|a, o| unsafe { sin_cos_slice_avx(a, o) });
        }
        for form in forms {
            // 199 angles: the last group of four is partial.
            let angles: Vec<f64> = (0..199).map(|i| (i as f64 - 100.0) * 0.377).collect();
            let mut out = vec![(0.0, 0.0); angles.len()];
            form(&angles, &mut out);
            for (&x, &(s, c)) in angles.iter().zip(&out) {
                let (s0, c0) = sin_cos(x);
                assert_eq!((s.to_bits(), c.to_bits()), (s0.to_bits(), c0.to_bits()));
            }
            let mixed = [0.3, 1e6, f64::NAN, -2.0, 0.5];
            let mut out = [(0.0, 0.0); 5];
            form(&mixed, &mut out);
            assert_eq!(out[1], 1e6f64.sin_cos());
            assert!(out[2].0.is_nan() && out[2].1.is_nan());
            assert_eq!(out[3], sin_cos(-2.0));
            assert_eq!(out[4], sin_cos(0.5));
        }
        let angles: Vec<f64> = (0..200).map(|i| (i as f64 - 100.0) * 0.377).collect();
        let mut out = vec![(0.0, 0.0); angles.len()];
        sin_cos_slice(&angles, &mut out);
        for (&x, &(s, c)) in angles.iter().zip(&out) {
            assert_eq!((s.to_bits(), c.to_bits()), {
                let (s0, c0) = sin_cos(x);
                (s0.to_bits(), c0.to_bits())
            });
        }
        // One angle out of range sends the whole slice to the checked path.
        let mixed = [0.3, 1e6, f64::NAN, -2.0];
        let mut out = [(0.0, 0.0); 4];
        sin_cos_slice(&mixed, &mut out);
        assert_eq!(out[1], 1e6f64.sin_cos());
        assert!(out[2].0.is_nan() && out[2].1.is_nan());
        assert_eq!(out[3], sin_cos(-2.0));
    }
}
