//! The ends of a parallel-pair search's branches (folds) and the search
//! traits (`search::Residual`, `sloped::Sloped`), shared with the
//! end-pair search (`end_parallel_pair`) through [`PairBranches`].

use super::sloped::{find_roots_sloped, Knot, Samples, Sloped};
use super::{Key, Point, Problem, END_TOLERANCE, FOLDING, LINK};
use crate::ik::analytic::chain::Candidates;
use crate::ik::analytic::polish::settle_root;
use crate::ik::analytic::search::{
    align_nearest, discriminant_sign_change, fold_by_extrapolation, EndCheck, Residual,
};
use crate::ik::analytic::trig2::Trig2;
use std::cell::Cell;

impl PairBranches for Problem<'_> {
    type Point = Point;

    fn finish(&self, t: f64, key: &Key) -> Option<([f64; 6], bool)> {
        let (_, point) = self.nearest(t, key)?;
        let q = self.configuration(t, &point);
        settle_root(&self.s.chain, &self.s.home, q, &self.target)
    }

    fn branches(&self, t: f64) -> Branches<Point> {
        self.branches(t)
    }

    fn residual_of(&self, point: &Point) -> f64 {
        point.residual
    }

    fn slope_of(&self, point: &Point) -> f64 {
        point.slope
    }

    fn folds(&self) -> &Folds<Point> {
        &self.folds
    }

    fn difference_at(&self, t: f64) -> Option<Trig2> {
        let (v, system) = self.at(t);
        self.tracker.difference(&system, [0.0, v.d])
    }
}

/// A subproblem-6 search of a parallel pair (the pair inside the chain,
/// [`Problem`], or at an end, `end_parallel_pair::Problem`): up to four
/// branches keyed by [`Key`], each evaluation a `Point` with its residual.
/// Implements `search::Residual` for both, with the branches' ends (folds)
/// located once per interval (see [`fold_by_discriminant`]).
pub(in crate::ik::analytic) trait PairBranches {
    /// What the residual and the finish read on one branch at one `t`.
    type Point: Copy;

    /// The branches at `t`: their keys and points.
    fn branches(&self, t: f64) -> Branches<Self::Point>;

    /// The residual of a branch's point, m.
    fn residual_of(&self, point: &Self::Point) -> f64;

    /// Its derivative along the branch by the searched joint, m/rad.
    fn slope_of(&self, point: &Self::Point) -> f64;

    /// Subproblem 6's `f` at `t` (no roots), `None` without a circle.
    fn difference_at(&self, t: f64) -> Option<Trig2>;

    /// The last few folds located (see [`FoldMemo`]).
    fn folds(&self) -> &Folds<Self::Point>;

    /// The joint values (chain order) at a root `t` (rad) of the branch
    /// `key`, and whether the chain's forward kinematics reproduces the
    /// target to [`EXACT_TOLERANCE`](crate::ik::analytic::EXACT_TOLERANCE);
    /// `None` if it misses by more (`polish::settle_root`).
    fn finish(&self, t: f64, key: &Key) -> Option<([f64; 6], bool)>;
}

/// Every root of each search in `problems` (one per searched joint, `N`
/// samples per turn), finished and merged into `out`
/// (`Candidates::push_distinct`).
pub(in crate::ik::analytic) fn merged_roots<P: PairBranches, const N: usize>(
    problems: impl Iterator<Item = P>,
    out: &mut Candidates,
) {
    for problem in problems {
        find_roots_sloped::<_, 4, N>(&problem, |t, key| {
            if let Some((q, exact)) = problem.finish(t, &key) {
                out.push_distinct(&q, exact);
            }
        });
    }
}

/// The branches at one evaluation.
pub(in crate::ik::analytic) type Branches<P> = [Option<(Key, P)>; 4];

/// The last few sign changes of the discriminant located
/// (`discriminant_sign_change` of the interval): two branches that merge
/// end at the same place.
pub(in crate::ik::analytic) type Folds<P> = Cell<[Option<FoldMemo<P>>; 4]>;

/// A fold located between two samples: the interval (the branch's side
/// first), where in it the discriminant changes sign, and the branches at
/// the two ends of that bracket (read once for the two branches that
/// merge there).
#[derive(Clone, Copy)]
pub(in crate::ik::analytic) struct FoldMemo<P> {
    interval: [f64; 2],
    located: Option<(f64, f64)>,
    ends: Option<(Branches<P>, Branches<P>)>,
}

/// No fold located yet.
pub(in crate::ik::analytic) fn no_folds<P: Copy>() -> Folds<P> {
    Cell::new([None; 4])
}

/// The branch of `branches` nearest `key`, within [`LINK`].
pub(in crate::ik::analytic) fn nearest_among<P>(
    branches: Branches<P>,
    key: &Key,
) -> Option<(Key, P)> {
    let mut best: Option<(f64, Key, P)> = None;
    for (k, point) in branches.into_iter().flatten() {
        let d = k.gap(key);
        if d < LINK && best.as_ref().is_none_or(|(e, _, _)| d < *e) {
            best = Some((d, k, point));
        }
    }
    best.map(|(_, k, point)| (k, point))
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
fn fold_by_discriminant<P: PairBranches>(
    p: &P,
    defined: &(f64, f64, Key),
    undefined: f64,
) -> Option<(f64, f64, Key)> {
    // The branch that merges with this one there was located before,
    // or the fold is located now (and kept for it).
    let interval = [defined.0, undefined];
    let mut folds = p.folds().get();
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
                    p.difference_at(t)
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
            let ends = (p.branches(a), p.branches(b));
            memo.ends = Some(ends);
            Some(ends)
        }
    };
    p.folds().set(folds);
    let ((a, _), (at_a, at_b)) = located.zip(ends)?;
    let (k, point) = nearest_among(at_a, &defined.2)?;
    let f = p.residual_of(&point);
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

impl<P: PairBranches> Residual<4> for P {
    type Key = Key;

    const ENDS: EndCheck = EndCheck::SignChangeOrDip;

    fn sample(&self, t: f64) -> [Option<(f64, Key)>; 4] {
        self.branches(t)
            .map(|b| b.map(|(key, point)| (self.residual_of(&point), key)))
    }

    fn residual(&self, t: f64, key: &Key) -> Option<(f64, Key)> {
        let (k, point) = nearest_among(self.branches(t), key)?;
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
    /// ([`fold_by_discriminant`]); where that does not apply, where the
    /// squared Jacobian determinant extrapolates to zero
    /// (`search::fold_by_extrapolation`, to [`END_TOLERANCE`]).
    fn branch_end(&self, defined: (f64, f64, Key), undefined: f64) -> (f64, f64, Key) {
        if let Some(end) = fold_by_discriminant(self, &defined, undefined) {
            return end;
        }
        let determinant = |k: &Key| k.fold * k.fold;
        fold_by_extrapolation(self, defined, undefined, END_TOLERANCE, determinant).0
    }
}

impl<P: PairBranches> Sloped<4> for P {
    const LINK: f64 = LINK;

    fn gap(a: &Key, b: &Key) -> f64 {
        a.gap(b)
    }

    fn sample_sloped(&self, t: f64) -> Samples<Key, 4> {
        self.branches(t)
            .map(|b| b.map(|(key, point)| (self.residual_of(&point), (key, self.slope_of(&point)))))
    }

    fn residual_sloped(&self, t: f64, key: &Key) -> Option<Knot<Key>> {
        let (key, point) = nearest_among(self.branches(t), key)?;
        Some(Knot {
            t,
            f: self.residual_of(&point),
            g: self.slope_of(&point),
            key,
        })
    }
}

/// Test support: at `t`, each branch's slope ([`PairBranches::slope_of`])
/// against central differences of its residual (the branch followed by its
/// key), away from folds (where the difference is not accurate); the
/// number of branches checked.
#[cfg(test)]
pub(in crate::ik::analytic) fn slopes_checked<P: PairBranches>(problem: &P, t: f64) -> usize {
    let mut checked = 0;
    for (key, at) in problem.branches(t).into_iter().flatten() {
        let e = 1e-6;
        let (Some((fp, _)), Some((fm, _))) =
            (problem.residual(t + e, &key), problem.residual(t - e, &key))
        else {
            continue;
        };
        if key.fold.abs() < 1e-2 {
            continue;
        }
        let difference = (fp - fm) / (2.0 * e);
        let slope = problem.slope_of(&at);
        let tolerance = 1e-5 * (1.0 + difference.abs());
        assert!(
            (difference - slope).abs() < tolerance,
            "at t = {t}: slope {slope} against {difference}"
        );
        checked += 1;
    }
    checked
}
