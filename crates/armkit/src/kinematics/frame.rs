//! The running frame of the chain's product, written once for one
//! configuration (`f64`) and for four side by side (`F64x4`): the single
//! call and the batched kernels take the same steps. The sums are written
//! with [`Lane::mul_add`] in the order of the plain `a * b + c` (addition
//! commutes bit for bit), so `f64` and `F64x4` round as the plain products
//! do, and the AVX lanes fuse each multiply-add.

use crate::math::{Lane, Pose};
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

/// `a * ka + b * kb`, lane-wise on 3-vectors.
#[inline(always)]
fn mix<L: Lane>(a: &[L; 3], ka: L, b: &[L; 3], kb: L) -> [L; 3] {
    std::array::from_fn(|i| a[i].mul_add(ka, b[i] * kb))
}

/// `a * ka + b * kb + c * kc` with constant coefficients.
#[inline(always)]
fn combine<L: Lane>(a: &[L; 3], b: &[L; 3], c: &[L; 3], k: &[f64; 3]) -> [L; 3] {
    let k: [L; 3] = std::array::from_fn(|i| L::splat(k[i]));
    std::array::from_fn(|i| c[i].mul_add(k[2], a[i].mul_add(k[0], b[i] * k[1])))
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
    pub(super) fn place(&mut self, form: &PlacementForm) {
        match form {
            PlacementForm::Translation { p } => {
                self.t = add(&self.t, &combine(&self.x, &self.y, &self.z, p));
            }
            PlacementForm::AboutX { block, p } => {
                self.t = add(&self.t, &combine(&self.x, &self.y, &self.z, p));
                let (y, z) = (self.y, self.z);
                self.y = mix(&y, L::splat(block[0][0]), &z, L::splat(block[0][1]));
                self.z = mix(&y, L::splat(block[1][0]), &z, L::splat(block[1][1]));
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
        let (t, z) = (self.t, self.z);
        self.t = std::array::from_fn(|i| z[i].mul_add(distance, t[i]));
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
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
