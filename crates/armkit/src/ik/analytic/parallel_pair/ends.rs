//! The ends of a parallel-pair search's branches (folds) and the search
//! traits (`search::Residual`, `sloped::Sloped`) of its problem.

use super::*;

impl Problem<'_> {
    /// Subproblem 6's `f` at `t` (no roots), `None` without a circle.
    pub(super) fn difference_at(&self, t: f64) -> Option<Trig2> {
        let (v, system) = self.at(t);
        let d = [0.0, v.d];
        match &self.elimination {
            Some(eliminated) => Some(system.eliminated_polynomial(d, eliminated)),
            None => system.difference_polynomial(d),
        }
    }

    /// A fold between `defined` and `undefined` located where the
    /// discriminant of subproblem 6's `f` changes sign (two of its roots
    /// merge there; the sign does not depend on how `f`'s circle is
    /// parametrized): Illinois regula falsi on the discriminant, which
    /// needs `f`'s coefficients only (no roots), to [`END_TOLERANCE`]; then
    /// the branch read at the bracket's end on the defined side, and
    /// checked gone (or folding) at the other. The branch's last point; `None` when the
    /// discriminant does not change sign (the branch ends otherwise: the
    /// circle vanishes), the branch is not found there or does not end.
    pub(super) fn fold_by_discriminant(
        &self,
        defined: &(f64, f64, Key),
        undefined: f64,
    ) -> Option<(f64, f64, Key)> {
        // The branch that merges with this one there was located before,
        // or the fold is located now (and kept for it).
        let interval = [defined.0, undefined];
        let mut folds = self.folds.get();
        let slot = match folds
            .iter()
            .position(|m| m.as_ref().is_some_and(|m| m.interval == interval))
        {
            Some(i) => i,
            None => {
                folds.rotate_right(1);
                folds[0] = Some(FoldMemo {
                    interval,
                    located: discriminant_sign_change(defined.0, undefined, END_TOLERANCE, |t| {
                        self.difference_at(t)
                    }),
                    ends: None,
                });
                0
            }
        };
        let memo = folds[slot].as_mut()?;
        let located = memo.located;
        let ends = match (located, memo.ends) {
            (None, _) => None,
            (Some(_), Some(ends)) => Some(ends),
            (Some((a, b)), None) => {
                let ends = (self.branches(a), self.branches(b));
                memo.ends = Some(ends);
                Some(ends)
            }
        };
        self.folds.set(folds);
        let ((a, _), (at_a, at_b)) = located.zip(ends)?;
        let (k, point) = nearest_among(at_a, &defined.2)?;
        let f = point.residual;
        // Past the fold the branch is gone, or lingers as the double root
        // of `f` that round-off lets through (within `TANGENT_TOLERANCE`),
        // its Jacobian determinant near zero (it falls as the square root
        // of the distance to the fold: ~3e-4 of a sample's at 1e-9 rad
        // from it); a branch going on at its own size there means the sign
        // change was another pair's fold.
        if let Some((past, _)) = nearest_among(at_b, &k) {
            if past.fold.abs() >= FOLDING * defined.2.fold.abs() {
                return None;
            }
        }
        Some((a, f, k))
    }
}

impl Residual<4> for Problem<'_> {
    type Key = Key;

    const ENDS: EndCheck = EndCheck::SignChangeOrDip;

    fn sample(&self, t: f64) -> [Option<(f64, Key)>; 4] {
        self.branches(t)
            .map(|b| b.map(|(key, point)| (self.residual_of(&point), key)))
    }

    fn residual(&self, t: f64, key: &Key) -> Option<(f64, Key)> {
        let (k, point) = self.nearest(t, key)?;
        Some((self.residual_of(&point), k))
    }

    fn align(&self, previous: &[Option<(f64, Key)>; 4], current: &mut [Option<(f64, Key)>; 4]) {
        align_nearest(previous, current, Key::gap, LINK);
    }

    fn same_branch(&self, a: &Key, b: &Key) -> bool {
        a.gap(b) < LINK
    }

    /// The end of a branch is where two solutions of subproblem 6 merge:
    /// first located on the discriminant of its `f`
    /// ([`Problem::fold_by_discriminant`]); where that does not apply, where
    /// the squared Jacobian determinant extrapolates to zero
    /// (`search::fold_by_extrapolation`, to [`END_TOLERANCE`]).
    fn branch_end(&self, defined: (f64, f64, Key), undefined: f64) -> (f64, f64, Key) {
        if let Some(end) = self.fold_by_discriminant(&defined, undefined) {
            return end;
        }
        let determinant = |k: &Key| k.fold * k.fold;
        fold_by_extrapolation(self, defined, undefined, END_TOLERANCE, determinant).0
    }
}

impl Sloped<4> for Problem<'_> {
    const LINK: f64 = LINK;

    fn gap(a: &Key, b: &Key) -> f64 {
        a.gap(b)
    }

    fn sample_sloped(&self, t: f64) -> Samples<Key, 4> {
        self.branches(t)
            .map(|b| b.map(|(key, point)| (point.residual, (key, point.slope))))
    }

    fn residual_sloped(&self, t: f64, key: &Key) -> Option<Knot<Key>> {
        let (key, point) = self.nearest(t, key)?;
        Some(Knot {
            t,
            f: point.residual,
            g: point.slope,
            key,
        })
    }
}
