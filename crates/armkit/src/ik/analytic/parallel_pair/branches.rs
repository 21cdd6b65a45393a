//! A parallel-pair search's evaluation at one value of the searched joint:
//! subproblem 6's branches, and on each the residual and its slope (see
//! the parent module's docs).

use super::tracker::branch_rates;
use super::{moved, moved_back, Form, Key, Known, Point, Problem, Sides};
use crate::ik::analytic::subproblems::{rotate_by, Turn};

impl Problem<'_> {
    /// The branches at `t`: their keys and points.
    pub(super) fn branches(&self, t: f64) -> [Option<(Key, Point)>; 4] {
        let (v, system) = self.at(t);
        let pairs = self.tracker.solve(t, &system, [0.0, v.d]);
        let (dv, moving) = self.slope_at(v.k);
        let mut out = [None, None, None, None];
        for (slot, pair) in out.iter_mut().zip(pairs.as_slice()) {
            let (a, b) = (&pair.first, &pair.second);
            // (q_l, q_r)' = -J^-1 F_t.
            let (determinant, rates) = branch_rates(&system, &moving, [0.0, dv.d], a, b);
            let key = Key {
                angles: [a.angle, b.angle],
                fold: determinant,
            };
            *slot = Some((key, self.point(&v, &dv, a, b, rates)));
        }
        out
    }

    /// The pair's angle `th` and `w` at `q_l`, `q_r` (see the module docs):
    /// `Rb' R_O h6`, `x = Eb^-1 X` from the left side, `Ra h6`,
    /// `y = Ea c6` from the right, the known joint applied where inner;
    /// with the residual and its derivative along the branch (`dv` the
    /// sides' derivatives by `t`, `rates` those of `q_l`, `q_r`), each
    /// vector's derivative carried beside it (`d/dq R(k, q) v = k x R v`).
    #[inline]
    pub(super) fn point(
        &self,
        v: &Sides,
        dv: &Sides,
        left: &Turn,
        right: &Turn,
        rates: (f64, f64),
    ) -> Point {
        let Form { k, l, r, side } = self.form;
        let p = self.s.p;
        let (c, h) = (&self.s.chain.c, &self.s.chain.h);
        let axis = &self.s.h;
        let mut before = left.rotate_back(&h[l], &v.left[0]);
        let mut d_before = left.rotate_back(&h[l], &dv.left[0]) - h[l].cross(&before) * rates.0;
        let mut x = moved_back(&c[l], &h[l], &v.left[1], left);
        let mut dx = left.rotate_back(&h[l], &dv.left[1]) - h[l].cross(&(x - c[l])) * rates.0;
        let mut after = right.rotate(&h[r], &v.right[0]);
        let mut d_after = right.rotate(&h[r], &dv.right[0]) + h[r].cross(&after) * rates.1;
        let mut y = moved(&c[r], &h[r], &v.right[1], right);
        let mut dy = right.rotate(&h[r], &dv.right[1]) + h[r].cross(&(y - c[r])) * rates.1;
        match side {
            Known::LeftInner => {
                before = v.k.rotate_back(&h[k], &before);
                d_before = v.k.rotate_back(&h[k], &d_before) - h[k].cross(&before);
                x = moved_back(&c[k], &h[k], &x, &v.k);
                dx = v.k.rotate_back(&h[k], &dx) - h[k].cross(&(x - c[k]));
            }
            Known::RightInner => {
                after = v.k.rotate(&h[k], &after);
                d_after = v.k.rotate(&h[k], &d_after) + h[k].cross(&after);
                y = moved(&c[k], &h[k], &y, &v.k);
                dy = v.k.rotate(&h[k], &dy) + h[k].cross(&(y - c[k]));
            }
            Known::LeftOuter | Known::RightOuter => {}
        }
        // Subproblem 1, `R(h, th) after = before`, as a direction.
        let (ha, hb) = (axis.dot(&after), axis.dot(&before));
        let (sin, cos) = (
            axis.dot(&after.cross(&before)),
            after.dot(&before) - ha * hb,
        );
        let length = (sin * sin + cos * cos).sqrt();
        let pair = if length > 0.0 {
            (sin / length, cos / length)
        } else {
            (0.0, 1.0)
        };
        // th is the angle of before_perp less that of after_perp.
        let d_pair = axis.dot(&before.cross(&d_before)) / (before.norm_squared() - hb * hb)
            - axis.dot(&after.cross(&d_after)) / (after.norm_squared() - ha * ha);
        let arm = rotate_by(axis, &(y - c[p + 1]), pair.0, pair.1);
        let w = x - c[p] - arm;
        let dw = dx - axis.cross(&arm) * d_pair - rotate_by(axis, &dy, pair.0, pair.1);
        let across = w - axis * axis.dot(&w);
        let length = across.norm();
        Point {
            left: *left,
            right: *right,
            pair,
            w,
            residual: length - self.s.link_length,
            slope: across.dot(&dw) / length,
        }
    }
}
