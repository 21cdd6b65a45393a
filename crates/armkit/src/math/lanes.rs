//! Arithmetic written once for one value (`f64`) and for four values side
//! by side ([`F64x4`]), so that a kinematic kernel runs on one configuration
//! or on four at a time from the same source.
//!
//! [`F64x4`] is four independent lanes (structure of arrays: lane `l` is
//! configuration `l` of a block). Its operations are lane-wise loops over
//! `[f64; 4]` that the compiler turns into one vector instruction each where
//! the processor has 256-bit registers (AVX2), two 128-bit ones otherwise.
//! No operation mixes lanes, so every lane rounds exactly as the `f64` code
//! does on the same value.

use std::ops::{Add, Mul, Neg, Sub};

/// A number type the kinematic kernels compute with: `f64`, or four `f64`
/// lanes ([`F64x4`]).
pub trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Mul<f64, Output = Self>
    + Neg<Output = Self>
{
    /// Whether [`Lane::mul_add`] rounds once (a fused multiply-add): false
    /// for `f64` and [`F64x4`], whose results are the reference's bits.
    const FUSED: bool = false;
    /// Every lane `value`.
    fn splat(value: f64) -> Self;
    /// `self * a + b`, lane-wise: two roundings for `f64` and [`F64x4`]
    /// (the reference), one where a vector build fuses it (`vfmadd`).
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    /// `(sin, cos)` of `r + n pi/2` from `(sin r, cos r)`, `n` the integer in
    /// the low bits of `shifted`'s representation (`trig`'s quadrant), lane-wise.
    fn by_quadrant(s: Self, c: Self, shifted: Self) -> (Self, Self);
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(value: f64) -> Self {
        value
    }

    #[inline(always)]
    fn by_quadrant(s: f64, c: f64, shifted: f64) -> (f64, f64) {
        super::trig::by_quadrant(s, c, shifted.to_bits())
    }
}

/// A four-lane number type: [`F64x4`] (the reference), or the AVX
/// register type of the vector builds (`lanes_avx`), loaded from and
/// stored to `[f64; 4]`.
pub trait Lanes4: Lane {
    /// The lanes `values[0..4]`.
    fn from_array(values: [f64; 4]) -> Self;
    /// The four lanes.
    fn to_array(self) -> [f64; 4];
    /// Whether every lane's magnitude is below `bound` (false for a NaN lane).
    #[inline(always)]
    fn all_below(self, bound: f64) -> bool {
        self.to_array().iter().all(|v| v.abs() < bound)
    }
    /// The 4 x 4 transpose: lane `l` of `rows[k]` becomes lane `k` of the
    /// result's `l`-th value (four lanes of four quantities to four
    /// consecutive quantities of each lane, for row-major output).
    #[inline(always)]
    fn transpose(rows: [Self; 4]) -> [Self; 4] {
        let values: [[f64; 4]; 4] = std::array::from_fn(|k| rows[k].to_array());
        std::array::from_fn(|l| Self::from_array(std::array::from_fn(|k| values[k][l])))
    }
}

impl Lanes4 for F64x4 {
    #[inline(always)]
    fn from_array(values: [f64; 4]) -> Self {
        F64x4(values)
    }

    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        self.0
    }
}

/// Four `f64` lanes: one value of four configurations.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(align(32))]
pub struct F64x4(pub [f64; 4]);

/// The number of lanes of [`F64x4`].
pub const LANES: usize = 4;

impl F64x4 {
    #[inline(always)]
    fn zip(self, other: F64x4, f: impl Fn(f64, f64) -> f64) -> F64x4 {
        let (a, b) = (self.0, other.0);
        F64x4([f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])])
    }
}

impl Add for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn add(self, other: F64x4) -> F64x4 {
        self.zip(other, |a, b| a + b)
    }
}

impl Sub for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn sub(self, other: F64x4) -> F64x4 {
        self.zip(other, |a, b| a - b)
    }
}

impl Mul for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn mul(self, other: F64x4) -> F64x4 {
        self.zip(other, |a, b| a * b)
    }
}

impl Mul<f64> for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn mul(self, k: f64) -> F64x4 {
        self * F64x4::splat(k)
    }
}

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        let a = self.0;
        F64x4([-a[0], -a[1], -a[2], -a[3]])
    }
}

impl Lane for F64x4 {
    #[inline(always)]
    fn splat(value: f64) -> Self {
        F64x4([value; 4])
    }

    #[inline(always)]
    fn by_quadrant(s: F64x4, c: F64x4, shifted: F64x4) -> (F64x4, F64x4) {
        let mut out = (F64x4::default(), F64x4::default());
        for l in 0..LANES {
            let (sl, cl) = super::trig::by_quadrant(s.0[l], c.0[l], shifted.0[l].to_bits());
            out.0 .0[l] = sl;
            out.1 .0[l] = cl;
        }
        out
    }
}
