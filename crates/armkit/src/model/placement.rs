//! The shape of each joint placement, found once when the model is built,
//! so that forward kinematics multiplies only by what is not zero.
//!
//! A placement `P = (R, p)` is applied to the running frame `F = (A, t)` as
//! `F P = (A R, t + A p)`. A general `R` costs 27 products and 18 sums; a
//! placement without rotation (URDF links along an axis) needs only `t + A
//! p`; one whose rotation keeps the x axis (`R = [1 0 0; 0 a b; 0 c d]`:
//! every DH link without a joint offset, `Rx(alpha)`) mixes two columns of
//! `A`, 12 products. The forms are decided on exact zeros and ones, so the
//! product is the general one's, term for term, without the terms that are
//! zero.

use crate::math::Pose;

/// How a placement's rotation acts on the running frame's columns; its
/// coefficients `K` are `f64`, or four lanes of each (the batched kinematics
/// keep them so, one vector operand each).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PlacementForm<K = f64> {
    /// `R = I`: only the translation moves the frame.
    Translation {
        /// `p`, in the running frame's axes (m).
        p: [K; 3],
    },
    /// `R = [1 0 0; 0 a b; 0 c d]`: the new y column is `a y + c z`, the new
    /// z column `b y + d z`; x stays.
    AboutX {
        /// `[[a, c], [b, d]]`: the y and z columns of `R`'s lower-right block.
        block: [[K; 2]; 2],
        /// `p` (m).
        p: [K; 3],
    },
    /// Any rotation.
    General {
        /// The columns of `R`.
        r: [[K; 3]; 3],
        /// `p` (m).
        p: [K; 3],
    },
}

impl PlacementForm<f64> {
    /// The form of `placement`, from the exact zeros and ones of its rotation.
    pub(crate) fn of(placement: &Pose) -> Self {
        let r = &placement.rotation;
        let p = [
            placement.translation.x,
            placement.translation.y,
            placement.translation.z,
        ];
        let x_kept = r[(0, 0)] == 1.0
            && r[(1, 0)] == 0.0
            && r[(2, 0)] == 0.0
            && r[(0, 1)] == 0.0
            && r[(0, 2)] == 0.0;
        if x_kept && r[(1, 1)] == 1.0 && r[(2, 2)] == 1.0 && r[(1, 2)] == 0.0 && r[(2, 1)] == 0.0 {
            PlacementForm::Translation { p }
        } else if x_kept {
            PlacementForm::AboutX {
                block: [[r[(1, 1)], r[(2, 1)]], [r[(1, 2)], r[(2, 2)]]],
                p,
            }
        } else {
            PlacementForm::General {
                r: [
                    [r[(0, 0)], r[(1, 0)], r[(2, 0)]],
                    [r[(0, 1)], r[(1, 1)], r[(2, 1)]],
                    [r[(0, 2)], r[(1, 2)], r[(2, 2)]],
                ],
                p,
            }
        }
    }

    /// The same form with every coefficient through `f` (`K` = `f64` here).
    pub(crate) fn map<K>(&self, f: impl Fn(f64) -> K) -> PlacementForm<K> {
        let f3 = |v: &[f64; 3]| [f(v[0]), f(v[1]), f(v[2])];
        match self {
            PlacementForm::Translation { p } => PlacementForm::Translation { p: f3(p) },
            PlacementForm::AboutX { block, p } => PlacementForm::AboutX {
                block: [
                    [f(block[0][0]), f(block[0][1])],
                    [f(block[1][0]), f(block[1][1])],
                ],
                p: f3(p),
            },
            PlacementForm::General { r, p } => PlacementForm::General {
                r: [f3(&r[0]), f3(&r[1]), f3(&r[2])],
                p: f3(p),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Matrix3;

    #[test]
    fn forms_follow_the_exact_zeros() {
        let t = Pose::trans_x(0.3);
        assert_eq!(
            PlacementForm::of(&t),
            PlacementForm::Translation { p: [0.3, 0.0, 0.0] }
        );
        let x = Pose::trans_x(0.3) * Pose::rot_x(0.7);
        assert!(matches!(
            PlacementForm::of(&x),
            PlacementForm::AboutX { .. }
        ));
        let g = Pose::rot_z(0.2) * Pose::rot_x(0.7);
        assert!(matches!(
            PlacementForm::of(&g),
            PlacementForm::General { .. }
        ));
        // A rotation one rounding away from the identity is general.
        let mut near = Pose::identity();
        near.rotation = Matrix3::identity();
        near.rotation[(1, 0)] = 1e-17;
        assert!(matches!(
            PlacementForm::of(&near),
            PlacementForm::General { .. }
        ));
    }
}
