//! Four `f64` lanes in one 256-bit AVX register ([`Avx4`]), with fused
//! multiply-adds: the lane type of the kinematic kernels' AVX2 + FMA builds.
//!
//! [`super::F64x4`] stays the reference: an array the compiler may or may
//! not keep in registers, every operation rounded as the `f64` code rounds.
//! [`Avx4`] is the same four lanes held in a `__m256d`, so that a kernel's
//! frame stays in registers, the quadrant fix-up of the sine-cosine is three
//! integer vector instructions, and [`Lane::mul_add`] is one `vfmadd`
//! (rounded once, so the AVX kernels' results differ from the reference's in
//! the last bits; the tests compare them to 1e-14).
//!
//! # Safety
//!
//! The intrinsics need AVX2 and FMA. [`Avx4`] is crate-private and its
//! values are made only inside functions compiled with
//! `#[target_feature(enable = "avx2,fma")]` that are entered after
//! `is_x86_feature_detected!` found both features (`kinematics::batch`,
//! `kinematics`'s chain): every `unsafe` block below relies on that, and on
//! nothing else (no memory is read or written but the arguments' own).

use std::arch::x86_64::{
    __m256d, _mm256_add_epi64, _mm256_add_pd, _mm256_and_si256, _mm256_andnot_pd, _mm256_blendv_pd,
    _mm256_castpd_si256, _mm256_castsi256_pd, _mm256_cmp_pd, _mm256_fmadd_pd, _mm256_loadu_pd,
    _mm256_movemask_pd, _mm256_mul_pd, _mm256_permute2f128_pd, _mm256_set1_epi64x, _mm256_set1_pd,
    _mm256_slli_epi64, _mm256_storeu_pd, _mm256_sub_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
    _mm256_xor_pd, _mm256_xor_si256, _CMP_LT_OQ,
};
use std::ops::{Add, Mul, Neg, Sub};

use super::lanes::{Lane, Lanes4};

/// Four `f64` lanes in one AVX register. Only inside the AVX2 + FMA kernels
/// (see the module's safety note).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx4(__m256d);

impl Add for Avx4 {
    type Output = Avx4;
    #[inline(always)]
    fn add(self, other: Avx4) -> Avx4 {
        // SAFETY: AVX is present wherever an `Avx4` exists (module note).
        Avx4(unsafe { _mm256_add_pd(self.0, other.0) })
    }
}

impl Sub for Avx4 {
    type Output = Avx4;
    #[inline(always)]
    fn sub(self, other: Avx4) -> Avx4 {
        // SAFETY: AVX is present wherever an `Avx4` exists (module note).
        Avx4(unsafe { _mm256_sub_pd(self.0, other.0) })
    }
}

impl Mul for Avx4 {
    type Output = Avx4;
    #[inline(always)]
    fn mul(self, other: Avx4) -> Avx4 {
        // SAFETY: AVX is present wherever an `Avx4` exists (module note).
        Avx4(unsafe { _mm256_mul_pd(self.0, other.0) })
    }
}

impl Mul<f64> for Avx4 {
    type Output = Avx4;
    #[inline(always)]
    fn mul(self, k: f64) -> Avx4 {
        self * Avx4::splat(k)
    }
}

impl Neg for Avx4 {
    type Output = Avx4;
    #[inline(always)]
    fn neg(self) -> Avx4 {
        // Flipping the sign bit, as `-x` on `f64` does (no rounding).
        // SAFETY: AVX is present wherever an `Avx4` exists (module note).
        Avx4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

impl Lane for Avx4 {
    const FUSED: bool = true;

    #[inline(always)]
    fn splat(value: f64) -> Self {
        // SAFETY: called only inside the AVX2 + FMA kernels (module note).
        Avx4(unsafe { _mm256_set1_pd(value) })
    }

    /// `self * a + b` rounded once (`vfmadd`).
    #[inline(always)]
    fn mul_add(self, a: Avx4, b: Avx4) -> Avx4 {
        // SAFETY: FMA is present wherever an `Avx4` exists (module note).
        Avx4(unsafe { _mm256_fmadd_pd(self.0, a.0, b.0) })
    }

    /// `trig::by_quadrant` on the four lanes: the same bit operations with
    /// 64-bit integer lanes (swap where the quadrant is odd, then the signs).
    #[inline(always)]
    fn by_quadrant(s: Avx4, c: Avx4, shifted: Avx4) -> (Avx4, Avx4) {
        // SAFETY: AVX2 is present wherever an `Avx4` exists (module note).
        unsafe {
            let quadrant = _mm256_castpd_si256(shifted.0);
            // The blend takes the second operand where the mask's sign bit
            // is set: shift the quadrant's low bit there.
            let odd = _mm256_castsi256_pd(_mm256_slli_epi64::<63>(quadrant));
            let first = _mm256_blendv_pd(s.0, c.0, odd);
            let second = _mm256_blendv_pd(c.0, s.0, odd);
            // Sign bits: sin negative in quadrants 2, 3; cos in 1, 2.
            let two = _mm256_set1_epi64x(2);
            let sin_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(quadrant, two));
            let cos_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(
                _mm256_add_epi64(quadrant, _mm256_set1_epi64x(1)),
                two,
            ));
            let flip = |v: __m256d, sign| {
                _mm256_castsi256_pd(_mm256_xor_si256(_mm256_castpd_si256(v), sign))
            };
            (Avx4(flip(first, sin_sign)), Avx4(flip(second, cos_sign)))
        }
    }
}

impl Lanes4 for Avx4 {
    #[inline(always)]
    fn from_array(values: [f64; 4]) -> Self {
        // SAFETY: reads the four values of `values` only; AVX as above.
        Avx4(unsafe { _mm256_loadu_pd(values.as_ptr()) })
    }

    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        let mut out = [0.0; 4];
        // SAFETY: writes the four values of `out` only; AVX as above.
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) };
        out
    }

    /// One compare of the magnitudes (sign bit cleared) and its mask.
    #[inline(always)]
    fn all_below(self, bound: f64) -> bool {
        // SAFETY: AVX is present wherever an `Avx4` exists (module note).
        unsafe {
            let magnitude = _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0);
            let below = _mm256_cmp_pd::<_CMP_LT_OQ>(magnitude, _mm256_set1_pd(bound));
            _mm256_movemask_pd(below) == 0b1111
        }
    }

    /// Pairs interleaved within 128-bit halves, then the halves exchanged:
    /// eight shuffles instead of sixteen lane moves.
    #[inline(always)]
    fn transpose(rows: [Avx4; 4]) -> [Avx4; 4] {
        let [a, b, c, d] = rows;
        // SAFETY: AVX is present wherever an `Avx4` exists (module note).
        unsafe {
            let ab_even = _mm256_unpacklo_pd(a.0, b.0); // a0 b0 a2 b2
            let ab_odd = _mm256_unpackhi_pd(a.0, b.0); // a1 b1 a3 b3
            let cd_even = _mm256_unpacklo_pd(c.0, d.0);
            let cd_odd = _mm256_unpackhi_pd(c.0, d.0);
            [
                Avx4(_mm256_permute2f128_pd::<0x20>(ab_even, cd_even)),
                Avx4(_mm256_permute2f128_pd::<0x20>(ab_odd, cd_odd)),
                Avx4(_mm256_permute2f128_pd::<0x31>(ab_even, cd_even)),
                Avx4(_mm256_permute2f128_pd::<0x31>(ab_odd, cd_odd)),
            ]
        }
    }
}
