//! Subproblem 6 with one unknown eliminated (see [`Eliminated`]): the
//! form a search uses where one unknown's waves stay fixed.

use super::{equations_scale, residual_norm, Sinusoids, TurnPair, TurnPairs};
use crate::ik::analytic::subproblems::{Turn, RELATIVE_TOLERANCE};
use crate::ik::analytic::trig2::{Trig2, TrigRoots};

/// Largest condition (squared Frobenius norm over `|det|`) of the block
/// [`Sinusoids::eliminating`] inverts: past it the elimination would lose
/// more than 4 digits and the null-space form (the module docs) answers
/// instead.
const ELIMINATION_CONDITION: f64 = 1e4;

/// One unknown of subproblem 6 eliminated. With `A` the 2 x 2 block of `M`
/// of that unknown (its two waves' cos and sin parts) invertible and `A_v`
/// the other's, `x_e = A^-1 (e - A_v x_v) = u - W x_v`, and `|x_e|^2 = 1`
/// is a degree-2 trigonometric polynomial in the other unknown directly,
/// `f(t_v) = |u - W x_v|^2 - 1` (`u = A^-1 e`, `W = A^-1 A_v`): its roots
/// are the solutions' `t_v`, each `x_e` then read off linearly. No null
/// space and no circle; where the block stays fixed as the rest of the
/// system moves (a search whose searched joint does not turn one unknown's
/// waves), `A^-1` is read once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Eliminated {
    /// The eliminated unknown: 0 for `t1`, 1 for `t2`.
    unknown: usize,
    /// `A^-1`.
    inverse: [[f64; 2]; 2],
}

impl Sinusoids {
    /// The block of `M` of `unknown` (0: `t1`, 1: `t2`): row `i` is the
    /// cos and sin parts of its wave in equation `i`.
    fn block(&self, unknown: usize) -> [[f64; 2]; 2] {
        let waves = if unknown == 0 {
            &self.first
        } else {
            &self.second
        };
        [
            [waves[0].cos_part, waves[0].sin_part],
            [waves[1].cos_part, waves[1].sin_part],
        ]
    }

    /// `unknown` (0: `t1`, 1: `t2`) eliminated from this system's block;
    /// `None` when the block's condition exceeds [`ELIMINATION_CONDITION`].
    pub(crate) fn eliminating(&self, unknown: usize) -> Option<Eliminated> {
        let [[a, b], [c, d]] = self.block(unknown);
        let det = a * d - b * c;
        let size = a * a + b * b + c * c + d * d;
        let conditioned = det.abs() * ELIMINATION_CONDITION > size;
        if !conditioned {
            return None;
        }
        Some(Eliminated {
            unknown,
            inverse: [[d / det, -b / det], [-c / det, a / det]],
        })
    }

    /// `u`, `W` and `f` of `eliminated` (see [`Eliminated`]) for `e`;
    /// `eliminated` read from a system with the same block.
    fn eliminated(
        &self,
        e: &[f64; 2],
        eliminated: &Eliminated,
    ) -> ([f64; 2], [[f64; 2]; 2], Trig2) {
        let p = &eliminated.inverse;
        let other = self.block(1 - eliminated.unknown);
        let u = [
            p[0][0] * e[0] + p[0][1] * e[1],
            p[1][0] * e[0] + p[1][1] * e[1],
        ];
        let w = [
            [
                p[0][0] * other[0][0] + p[0][1] * other[1][0],
                p[0][0] * other[0][1] + p[0][1] * other[1][1],
            ],
            [
                p[1][0] * other[0][0] + p[1][1] * other[1][0],
                p[1][0] * other[0][1] + p[1][1] * other[1][1],
            ],
        ];
        // |u - W x|^2 - 1 = |u|^2 - 2 (W' u) . x + x' W'W x - 1, and with
        // x = (cos, sin), x' G x = (G11 + G22) / 2 + (G11 - G22) / 2 cos 2t
        // + G12 sin 2t.
        let g11 = w[0][0] * w[0][0] + w[1][0] * w[1][0];
        let g22 = w[0][1] * w[0][1] + w[1][1] * w[1][1];
        let g12 = w[0][0] * w[0][1] + w[1][0] * w[1][1];
        let wu = [
            w[0][0] * u[0] + w[1][0] * u[1],
            w[0][1] * u[0] + w[1][1] * u[1],
        ];
        let f = Trig2 {
            c2: 0.5 * (g11 - g22),
            s2: g12,
            c1: -2.0 * wu[0],
            s1: -2.0 * wu[1],
            c0: u[0] * u[0] + u[1] * u[1] + 0.5 * (g11 + g22) - 1.0,
        };
        (u, w, f)
    }

    /// [`Sinusoids::exact_solutions_near`] by `eliminated` (read from a
    /// system with this one's block): `f`'s roots in the other unknown
    /// tracked from `previous` (its roots in a nearby system, the same
    /// certification) or isolated from scratch. Also returns every root
    /// of `f` (exact or not), for the next call. `previous` holds up to
    /// two sets of starts, tried in order.
    pub(crate) fn exact_solutions_eliminated(
        &self,
        d: [f64; 2],
        eliminated: &Eliminated,
        previous: [Option<TrigRoots>; 2],
    ) -> (TurnPairs, TrigRoots) {
        let (m, e) = self.linear(d);
        let scale = equations_scale(&m, &e);
        let (u, w, f) = self.eliminated(&e, eliminated);
        let roots = previous
            .iter()
            .flatten()
            .find_map(|p| f.roots_near(p))
            .unwrap_or_else(|| f.roots());
        let mut out = TurnPairs::EMPTY;
        for root in roots.as_slice() {
            let x = [
                u[0] - w[0][0] * root.cos - w[0][1] * root.sin,
                u[1] - w[1][0] * root.cos - w[1][1] * root.sin,
            ];
            let read = Turn::of_direction(x[1], x[0]);
            let (first, second) = if eliminated.unknown == 0 {
                (read, *root)
            } else {
                (*root, read)
            };
            if residual_norm(&m, &e, &first, &second) <= RELATIVE_TOLERANCE * scale {
                out.push(TurnPair {
                    first,
                    second,
                    exact: true,
                });
            }
        }
        (out, roots)
    }

    /// `f` of `eliminated` at the right-hand side `d`: like
    /// [`Sinusoids::difference_polynomial`]'s, its discriminant changes
    /// sign where two solutions merge.
    pub(crate) fn eliminated_polynomial(&self, d: [f64; 2], eliminated: &Eliminated) -> Trig2 {
        let (_, e) = self.linear(d);
        self.eliminated(&e, eliminated).2
    }
}
