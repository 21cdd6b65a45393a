//! A parallel-pair search's evaluation at one value of the searched joint:
//! subproblem 6's branches, and on each the residual and its slope (see
//! the parent module's docs).

use super::*;

impl Problem<'_> {
    /// The branches at `t`: their keys and points.
    pub(super) fn branches(&self, t: f64) -> [Option<(Key, Point)>; 4] {
        let (v, system) = self.at(t);
        // The nearest sample of the search, and whether `t` is one.
        let step = std::f64::consts::TAU / SAMPLES as f64;
        let index = ((t + std::f64::consts::PI) / step).round();
        let sample = -std::f64::consts::PI + step * index;
        let slot = self.grid.get(index as usize % SAMPLES);
        let on_grid = (t - sample).abs() <= 1e-12;
        // Starts within NEAR, the nearer first: the last evaluation's
        // roots and the nearest sample's (when the first does not certify:
        // a fold between).
        let mut starts = [None, None];
        if let Some((at, tracked)) = self.last.get() {
            if (at - t).abs() <= NEAR {
                starts[0] = Some((at - t).abs()).zip(Some(tracked));
            }
        }
        if let (false, Some(tracked)) = (on_grid, slot.and_then(Cell::get)) {
            if (sample - t).abs() <= NEAR {
                starts[1] = Some((sample - t).abs()).zip(Some(tracked));
            }
        }
        if let [Some((a, _)), Some((b, _))] = starts {
            if b < a {
                starts.swap(0, 1);
            }
        }
        let d = [0.0, v.d];
        let (pairs, tracked) = match &self.elimination {
            Some(eliminated) => {
                let start = starts.map(|s| match s {
                    Some((_, Tracked::Roots(roots))) => Some(roots),
                    _ => None,
                });
                let (pairs, roots) = system.exact_solutions_eliminated(d, eliminated, start);
                (pairs, Some(Tracked::Roots(roots)))
            }
            None => {
                let start = match starts.iter().flatten().next() {
                    Some((_, Tracked::Circle(points))) => Some(points),
                    _ => None,
                };
                let (pairs, points) = system.exact_solutions_near(d, start);
                (pairs, points.map(Tracked::Circle))
            }
        };
        self.last.set(tracked.map(|tracked| (t, tracked)));
        if let (true, Some(slot)) = (on_grid, slot) {
            slot.set(tracked);
        }
        let (dv, moving) = self.slope_at(v.k);
        let mut out = [None, None, None, None];
        for (slot, pair) in out.iter_mut().zip(pairs.as_slice()) {
            let (a, b) = (&pair.first, &pair.second);
            // The branch's Jacobian by (q_l, q_r), and the equations'
            // derivative by t: (q_l, q_r)' = -J^-1 F_t.
            let j = [
                [
                    wave_slope(&system.first[0], a),
                    wave_slope(&system.second[0], b),
                ],
                [
                    wave_slope(&system.first[1], a),
                    wave_slope(&system.second[1], b),
                ],
            ];
            let determinant = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let f_t = [
                wave_value(&moving.first[0], a) + wave_value(&moving.second[0], b),
                wave_value(&moving.first[1], a) + wave_value(&moving.second[1], b) - dv.d,
            ];
            let rates = (
                -(j[1][1] * f_t[0] - j[0][1] * f_t[1]) / determinant,
                -(j[0][0] * f_t[1] - j[1][0] * f_t[0]) / determinant,
            );
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
