//! The running frame of the chain's product, written once for one
//! configuration (`f64`) and for four side by side (`F64x4`): the single
//! call and the batched kernels take the same steps. The sums are written
//! with [`Lane::mul_add`] in the order of the plain `a * b + c` (addition
//! commutes bit for bit), so `f64` and `F64x4` round as the plain products
//! do, and the AVX lanes fuse each multiply-add. Loops rather than
//! `from_fn` closures: a closure that is not inlined runs without the AVX
//! kernels' target features.

use crate::math::{F64x4, Lane, Lanes4, Pose};
use crate::model::PlacementForm;

/// A rigid frame: rotation columns `x`, `y`, `z` and origin `t`, in the
/// world frame.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame<L> {
    pub(super) x: [L; 3],
    pub(super) y: [L; 3],
    pub(super) z: [L; 3],
    pub(super) t: [L; 3],
}

/// A placement's coefficient as lanes: an `f64` splat into every lane, or
/// four lanes kept side by side (one vector operand, no broadcast).
pub(super) trait Coefficient<L> {
    fn lanes(&self) -> L;
}

impl<L: Lane> Coefficient<L> for f64 {
    #[inline(always)]
    fn lanes(&self) -> L {
        L::splat(*self)
    }
}

impl<L: Lanes4> Coefficient<L> for F64x4 {
    #[inline(always)]
    fn lanes(&self) -> L {
        L::from_array(self.0)
    }
}

/// `a * ka + b * kb`, lane-wise on 3-vectors.
#[inline(always)]
fn mix<L: Lane>(a: &[L; 3], ka: L, b: &[L; 3], kb: L) -> [L; 3] {
    let mut out = *a;
    for (o, (&a, &b)) in out.iter_mut().zip(a.iter().zip(b)) {
        *o = a.mul_add(ka, b * kb);
    }
    out
}

/// `a * ka + b * kb + c * kc` with the placement's coefficients.
#[inline(always)]
fn combine<L: Lane, K: Coefficient<L>>(a: &[L; 3], b: &[L; 3], c: &[L; 3], k: &[K; 3]) -> [L; 3] {
    let k: [L; 3] = [k[0].lanes(), k[1].lanes(), k[2].lanes()];
    let mut out = *a;
    for (o, ((&a, &b), &c)) in out.iter_mut().zip(a.iter().zip(b).zip(c)) {
        *o = c.mul_add(k[2], a.mul_add(k[0], b * k[1]));
    }
    out
}

impl<L: Lane> Frame<L> {
    /// The world frame.
    #[inline(always)]
    pub(super) fn identity() -> Self {
        let (o, i) = (L::splat(0.0), L::splat(1.0));
        Frame {
            x: [i, o, o],
            y: [o, i, o],
            z: [o, o, i],
            t: [o, o, o],
        }
    }

    /// `self = self * placement`, multiplying only by what the placement's
    /// form leaves non-zero (see `model::PlacementForm`).
    #[inline(always)]
    pub(super) fn place<K: Coefficient<L>>(&mut self, form: &PlacementForm<K>) {
        match form {
            PlacementForm::Translation { p } => {
                self.t = add(&self.t, &combine(&self.x, &self.y, &self.z, p));
            }
            PlacementForm::AboutX { block, p } => {
                self.t = add(&self.t, &combine(&self.x, &self.y, &self.z, p));
                let (y, z) = (self.y, self.z);
                self.y = mix(&y, block[0][0].lanes(), &z, block[0][1].lanes());
                self.z = mix(&y, block[1][0].lanes(), &z, block[1][1].lanes());
            }
            PlacementForm::General { r, p } => {
                self.t = add(&self.t, &combine(&self.x, &self.y, &self.z, p));
                let (x, y, z) = (self.x, self.y, self.z);
                self.x = combine(&x, &y, &z, &r[0]);
                self.y = combine(&x, &y, &z, &r[1]);
                self.z = combine(&x, &y, &z, &r[2]);
            }
        }
    }

    /// `self = self * Rz(angle)` from `(sin, cos)`: the x and y columns mixed.
    #[inline(always)]
    pub(super) fn rotate_about_z(&mut self, s: L, c: L) {
        let (x, y) = (self.x, self.y);
        self.x = mix(&x, c, &y, s);
        self.y = mix(&y, c, &x, -s);
    }

    /// `self = self * Tz(distance)`: the origin moved along the z column.
    #[inline(always)]
    pub(super) fn translate_along_z(&mut self, distance: L) {
        for (t, &z) in self.t.iter_mut().zip(&self.z) {
            *t = z.mul_add(distance, *t);
        }
    }
}

impl Frame<f64> {
    /// The frame as a [`Pose`].
    #[inline(always)]
    pub(super) fn to_pose(self) -> Pose {
        let mut pose = Pose::identity();
        for i in 0..3 {
            pose.rotation[(i, 0)] = self.x[i];
            pose.rotation[(i, 1)] = self.y[i];
            pose.rotation[(i, 2)] = self.z[i];
            pose.translation[i] = self.t[i];
        }
        pose
    }
}

#[inline(always)]
fn add<L: Lane>(a: &[L; 3], b: &[L; 3]) -> [L; 3] {
    let mut out = *a;
    for (o, &b) in out.iter_mut().zip(b) {
        *o = *o + b;
    }
    out
}
