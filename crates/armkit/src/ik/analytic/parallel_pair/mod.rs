//! 6R arms whose only special structure is two consecutive parallel axes:
//! a 1-D search over one joint, the rest in closed form (IK-Geo's
//! "two parallel axes" case; derived here from the geometry, not ported).
//!
//! Chain as solved (`T home^-1 = E1 ... E6`), the pair at joints `p`,
//! `p + 1` with common direction `h` (`h_{p+1} = s h`, `s = +-1`), its
//! neighbours `l = p - 1` and `r = p + 2`, joint 6 the tail, and the one
//! joint left, `k`, searched: with the pair at 2-3 `k = 5`; with the pair
//! at 3-4 `k = 1`; a pair at 4-5 is the 2-3 case of the reversed chain.
//! (Pairs at 1-2 and 5-6 leave two joints beside the pair coupled in both
//! equations below: refused with the class named.)
//!
//! The pair turns about parallel lines: `R_p R_{p+1} = R(h, th)` with
//! `th = q_p + s q_{p+1}`, and `E_p E_{p+1}` keeps the `h` component of
//! every point. With `Rb`, `Eb` the joints before the pair and `Ra`, `Ea`
//! those after it (not the tail), `R_O = R_T R_home'`, `X = T home^-1 c6`
//! (`c6` on the tail's axis, which `E6` leaves in place):
//!
//! * orientation, `h' Rb' R_O h6 = h' Ra h6` (`h' R(h, th) = h'`,
//!   `R6 h6 = h6`);
//! * position, `h . (Eb^-1 X) = h . (Ea c6)`.
//!
//! At a trial value `t` of joint `k`, each side holds one unknown joint
//! turning one fixed vector, `g . R(h_j, q_j) v` (`g` is `h`, or `h` turned
//! by joint `k` when `k` lies between the pair and `j`): both equations are
//! `wave_l(q_l) + wave_r(q_r) = d`, subproblem 6 ([`super::subproblem6`],
//! its exact solutions only: up to 4 `(q_l, q_r)`, the branches). Every
//! wave and `d` is affine in `(cos t, sin t)`: read once per solve
//! (`sweep`), so an evaluation starts from 25 values `a + b cos t + c sin t`.
//! Joint `k` turns one side only, so the other unknown's 2 x 2 block of
//! subproblem 6 is fixed per solve: it is inverted once and that unknown
//! eliminated (`subproblem6::Eliminated`: a degree-2 trigonometric
//! polynomial in the other angle directly; the null-space form when the
//! block's condition exceeds 1e4). Then `th` follows by
//! subproblem 1 (`R(h, th) Ra h6 = Rb' R_O h6`) and the pair must carry
//! `y = Ea c6` onto `x = Eb^-1 X`:
//! `x = c_p + R_p (c_{p+1} - c_p) + R(h, th) (y - c_{p+1})`, i.e.
//! `w = x - c_p - R(h, th)(y - c_{p+1}) = R_p L`, `L = c_{p+1} - c_p`. The
//! `h` components agree by the position equation; the lengths across `h`
//! must too: the residual `f(t) = |w_perp| - |L_perp|` (m), smooth on each
//! branch, with its derivative along the branch (the branch's rates
//! `(q_l, q_r)' = -J^-1 dF/dt` from subproblem 6's Jacobian, carried
//! through every rotation). Its roots are found by the search with slopes
//! of `sloped` ([`SAMPLES`] = 192 per turn, Hermite dip checks, Newton
//! refinement to 1e-13 rad); `q_p` by subproblem 1 (`R_p L = w`),
//! `q_{p+1} = s (th - q_p)`, the tail by subproblem 1 on
//! `R6 = Ra' R(h, -th) Rb' R_O`.
//!
//! Two searches per solve, merged (duplicates within 1e-9 rad dropped):
//! the one above, and the one over the other joint on `k`'s side (joint 4
//! for the pair at 2-3, subproblem 6 on joints 1 and 5; joint 2 for the
//! pair at 3-4, subproblem 6 on joints 1 and 5), skipped when one of those
//! is parallel to the pair. A branch that lives only between two samples (a
//! small loop of solutions) and roots beside a fold are where a search
//! misses; the second search sees them at other values of its joint (one
//! search alone at 128 samples missed 39 of 8 000 poses of a unit test's
//! random arms, both 0). On the 20 000 poses of
//! `many_random_parallel_pair_arms_by_1d_search` the generating
//! configuration is found on 19 999 at 192 samples per turn (19 996 at 128,
//! 19 997 at 160; `search::find_roots` at 512 without slopes: 19 998).
//!
//! Branches are keyed by the subproblem-6 angles and the sign of the
//! Jacobian determinant of its two equations (two solutions that merge as
//! `t` moves have opposite signs), matched sample to sample within
//! [`LINK`]. Subproblem 6's roots are tracked from the last evaluation's
//! or the nearest sample's (within `NEAR`; `Trig2::roots_near`: Newton
//! on its `f`, accepted only when the quartic's discriminant certifies the
//! same number of real roots and Newton finds that many distinct ones),
//! isolated completely otherwise (near folds). A branch's end (a fold: two
//! solutions of subproblem 6 merge) is located on the discriminant of `f`
//! alone to 1e-9 rad (once for the two branches that merge there), by the
//! Jacobian determinant where that does not apply. Cost: 4.6M
//! instructions per solve (`parallel_pair_2_3_1d_search/distinct`, two
//! searches, ~500 evaluations of ~7k instructions), down from 9.6M with
//! `search::find_roots` at 512 samples and the null-space subproblem 6
//! (3.9M at 128 samples, with 3 more misses in 20 000). Each root is
//! checked by the chain's forward kinematics: exact
//! when within 1e-10 m and rad (a root missing by more than 1e-12 is first
//! polished by a few Gauss-Newton steps); roots missing by more than 1e-6
//! are dropped.
//!
//! ```
//! use armkit::ik::analytic::{AnalyticOptions, AnalyticSolver};
//! use armkit::ik::closed_form::Fit;
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::math::{Pose, Vector3};
//! use armkit::model::{JointSpec, ModelBuilder};
//! // Axes 2 and 3 parallel (both along y), every other consecutive pair skew.
//! let lines = [
//!     ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
//!     ([0.1, 0.05, 0.4], [0.0, 1.0, 0.0]),
//!     ([0.5, -0.1, 0.6], [0.0, 1.0, 0.0]),
//!     ([0.8, 0.1, 0.55], [0.9, 0.2, -0.4]),
//!     ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
//!     ([1.1, 0.1, 0.45], [0.85, -0.2, 0.5]),
//! ];
//! let mut builder = ModelBuilder::new("parallel23");
//! let mut previous = Vector3::zeros();
//! for (i, (c, h)) in lines.iter().enumerate() {
//!     let c = Vector3::from(*c);
//!     builder = builder.joint(
//!         JointSpec::revolute(format!("q{}", i + 1), -3.2, 3.2)
//!             .with_origin(Pose::from_translation(c - previous))
//!             .with_axis(Vector3::from(*h).normalize()),
//!     );
//!     previous = c;
//! }
//! let model = builder.build().unwrap();
//! let mut solver = AnalyticSolver::new(&model, AnalyticOptions::default()).unwrap();
//! assert_eq!(solver.class().as_str(), "one_pair_parallel_2_3_1d_search");
//! let q = [0.3, -0.4, 0.5, 0.2, -0.6, 0.1];
//! let target = *forward_kinematics(&model, &mut Data::new(&model), &q).unwrap();
//! let solutions = solver.solve(&target, &q).unwrap();
//! assert!(solutions.iter().all(|s| s.fit == Fit::Exact));
//! assert!(solutions[0].q().iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
//! ```

mod branches;
mod ends;

#[cfg(test)]
pub(super) use self::ends::slopes_checked;
pub(super) use self::ends::{merged_roots, nearest_among, no_folds, Branches, Folds, PairBranches};
mod sloped;
mod sweep;
mod tracker;

use self::sweep::{flatten, unflatten};
pub(super) use self::sweep::{read_system, write_system, Sweep};
pub(super) use self::tracker::{branch_rates, Tracker};
use super::chain::{Candidates, Chain};
use super::search::BranchKey;
use super::structure::GEOMETRY_TOLERANCE;
use super::subproblem6::{Sinusoids, Wave};
use super::subproblems::{atan2, rotation, subproblem1, Turn};
use crate::math::{wrap_angle, Matrix3, Pose, Vector3};

/// Samples per turn of the search.
pub const SAMPLES: usize = 192;
/// Largest joint-space step (rad, summed over the two subproblem-6 joints)
/// between two samples (or a sample and a refinement point) of one branch.
pub const LINK: f64 = 1.0;
/// Width (rad) to which the end of a branch (a fold) is located.
pub const END_TOLERANCE: f64 = 1e-9;
/// Largest step (rad) of the searched joint over which subproblem 6's
/// roots are tracked from the previous evaluation's (else isolated from
/// scratch).
pub(super) const NEAR: f64 = 0.1;
/// Largest ratio of the Jacobian determinant of subproblem 6 just past a
/// fold located on the discriminant to the one at the sample before it for
/// the branch to count as ending there.
pub(super) const FOLDING: f64 = 1e-2;

/// Where the parallel pair is, along the chain as solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum ParallelLayout {
    /// Axes 2-3 parallel: searches over joints 5 and 4.
    SecondThird,
    /// Axes 3-4 parallel: searches over joints 1 and 2.
    ThirdFourth,
}

impl ParallelLayout {
    /// The pair's first joint (0-based).
    pub(crate) fn first(self) -> usize {
        match self {
            ParallelLayout::SecondThird => 1,
            ParallelLayout::ThirdFourth => 2,
        }
    }

    /// The layout's searches: the first always, the second when its
    /// subproblem-6 joints are not parallel to the pair (`h` the pair's
    /// direction).
    fn forms(self, h: &[Vector3<f64>; 6]) -> ([Form; 2], usize) {
        let form = |k, l, r, side| Form { k, l, r, side };
        let (first, second) = match self {
            ParallelLayout::SecondThird => (
                form(4, 0, 3, Known::RightOuter),
                form(3, 0, 4, Known::RightInner),
            ),
            ParallelLayout::ThirdFourth => (
                form(0, 1, 4, Known::LeftOuter),
                form(1, 0, 4, Known::LeftInner),
            ),
        };
        let axis = h[self.first()];
        let usable = |f: &Form| {
            axis.cross(&h[f.l]).norm() > GEOMETRY_TOLERANCE
                && axis.cross(&h[f.r]).norm() > GEOMETRY_TOLERANCE
        };
        ([first, second], if usable(&second) { 2 } else { 1 })
    }
}

/// Where the searched joint `k` sits: before the pair (left) or after it
/// (right, the tail excluded), between the pair and the subproblem-6 joint
/// of its side (inner) or beyond it (outer).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Known {
    LeftInner,
    LeftOuter,
    RightInner,
    RightOuter,
}

/// One search: the searched joint `k`, the subproblem-6 joints `l`
/// (before the pair) and `r` (after it), 0-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Form {
    k: usize,
    l: usize,
    r: usize,
    side: Known,
}

/// The arm-fixed quantities of a parallel-pair search, read once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ParallelPairSearch {
    chain: Chain,
    /// The pair's first joint `p` (0-based).
    p: usize,
    forms: [Form; 2],
    searches: usize,
    home: Pose,
    /// `h_p` and `s = h_p . h_{p+1}` (+-1).
    h: Vector3<f64>,
    sign: f64,
    /// `L = c_{p+1} - c_p` and `|L_perp|`.
    link: Vector3<f64>,
    link_length: f64,
    /// A unit vector normal to `h6` (reads the tail's angle).
    tail_normal: Vector3<f64>,
}

impl ParallelPairSearch {
    pub(crate) fn new(chain: &Chain, layout: ParallelLayout) -> ParallelPairSearch {
        let p = layout.first();
        let (c, h) = (&chain.c, &chain.h);
        let link = c[p + 1] - c[p];
        let axis = h[p];
        let tail = h[5];
        let helper = if tail.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let (forms, searches) = layout.forms(h);
        ParallelPairSearch {
            chain: *chain,
            p,
            forms,
            searches,
            home: chain.home_inverse.inverse(),
            h: axis,
            sign: axis.dot(&h[p + 1]).signum(),
            link,
            link_length: (link - axis * axis.dot(&link)).norm(),
            tail_normal: tail.cross(&helper).normalize(),
        }
    }

    /// Every solution found for `target` (the chain's end-effector pose).
    pub(crate) fn solve(&self, target: &Pose, out: &mut Candidates) {
        let problems = self.forms[..self.searches]
            .iter()
            .map(|form| Problem::new(self, target, *form));
        merged_roots::<_, SAMPLES>(problems, out);
    }
}

/// `E(t) y = c + R(k, t)(y - c)`, the joint's motion.
#[inline]
fn moved(c: &Vector3<f64>, k: &Vector3<f64>, y: &Vector3<f64>, t: &Turn) -> Vector3<f64> {
    c + t.rotate(k, &(y - c))
}

/// `E(t)^-1 y = c + R(k, t)' (y - c)`.
#[inline]
fn moved_back(c: &Vector3<f64>, k: &Vector3<f64>, y: &Vector3<f64>, t: &Turn) -> Vector3<f64> {
    c + t.rotate_back(k, &(y - c))
}

/// The wave `-w` (a term moved to the other side).
#[inline]
pub(super) fn negated(w: Wave) -> Wave {
    Wave {
        cos_part: -w.cos_part,
        sin_part: -w.sin_part,
        constant: -w.constant,
    }
}

/// One search of one solve: the target read into what every evaluation
/// shares.
struct Problem<'a> {
    s: &'a ParallelPairSearch,
    form: Form,
    target: Pose,
    /// `R_O = R_T R_home'`.
    orientation: Matrix3<f64>,
    /// `R_O h6`.
    tail_goal: Vector3<f64>,
    /// `X = T home^-1 c6`.
    goal: Vector3<f64>,
    /// The sides and subproblem 6 as functions of `t`.
    sweep: Sweep,
    /// Subproblem 6 at the evaluations, with the unknown whose waves do
    /// not move with `t` eliminated where its block is well conditioned.
    tracker: Tracker<SAMPLES>,
    /// The last few folds located (two branches that merge end at the
    /// same place).
    folds: Folds<Point>,
}

/// A branch: the subproblem-6 angles `(q_l, q_r)` and its Jacobian
/// determinant.
type Key = BranchKey<2>;

/// What subproblem 6 turns at a trial `t` (see the module docs): the
/// left side is `g_l . R(h_l, q_l)' v` (`v` = `left[0]` for the
/// orientation, `left[1] - c_l` for the position), the right side
/// `g_r . R(h_r, q_r) u` likewise, `k` the searched joint's turn.
struct Sides {
    k: Turn,
    left: [Vector3<f64>; 2],
    right: [Vector3<f64>; 2],
    /// The position equation's right-hand side.
    d: f64,
}

/// What the residual and the finish read at `t` on one branch.
#[derive(Clone, Copy)]
struct Point {
    /// `q_l`, `q_r` as turns.
    left: Turn,
    right: Turn,
    /// `th` of the pair: its sine and cosine.
    pair: (f64, f64),
    /// `w` (see the module docs).
    w: Vector3<f64>,
    /// `|w_perp| - |L_perp|` (m) and its derivative along the branch by
    /// `t` (m/rad; not finite where the pair's angle or `w_perp` is
    /// undefined).
    residual: f64,
    slope: f64,
}

impl<'a> Problem<'a> {
    fn new(s: &'a ParallelPairSearch, target: &Pose, form: Form) -> Problem<'a> {
        let (c, h) = (&s.chain.c, &s.chain.h);
        let moved = *target * s.chain.home_inverse;
        let mut problem = Problem {
            s,
            form,
            target: *target,
            orientation: moved.rotation,
            tail_goal: moved.rotation * h[5],
            goal: moved.transform_point(&c[5]),
            sweep: Sweep::ZERO,
            tracker: Tracker::new(),
            folds: no_folds(),
        };
        problem.sweep = Sweep::of(|turn| {
            let (sides, g) = problem.sides(turn);
            flatten(&sides, &problem.system(&sides, &g))
        });
        // The unknown on the side away from `k` keeps its waves.
        let fixed = match form.side {
            Known::LeftInner | Known::LeftOuter => 1,
            Known::RightInner | Known::RightOuter => 0,
        };
        let (_, system) = problem.at(0.0);
        problem.tracker.eliminate(&system, fixed);
        problem
    }

    /// The sides and subproblem 6 at `t`, from the sweep.
    #[inline]
    fn at(&self, t: f64) -> (Sides, Sinusoids) {
        let turn = Turn::of_angle(t);
        unflatten(&self.sweep.at(&turn), turn)
    }

    /// Their derivatives by `t` at the turn `turn`.
    #[inline]
    fn slope_at(&self, turn: Turn) -> (Sides, Sinusoids) {
        unflatten(&self.sweep.slope_at(&turn), turn)
    }

    /// The two sides at `t`. The known joint `k` turns the pair's `h`
    /// (inner: `g = R_k h` before the pair, `R_k' h` after it, with the
    /// constant `h . c_k - g . c_k` of `h . E_k^-1 y` or `h . E_k y`) or
    /// the vectors (outer: `R_k' R_O h6`, `E_k^-1 X` before, `R_k h6`,
    /// `E_k c6` after).
    /// Also returns `g` (see [`Sides`]). Read at set-up only, by
    /// [`Sweep`].
    fn sides(&self, turn: &Turn) -> (Sides, [Vector3<f64>; 2]) {
        let Form { k, l, r, side } = self.form;
        let (c, h) = (&self.s.chain.c, &self.s.chain.h);
        let axis = self.s.h;
        let turn = *turn;
        let mut g = [axis, axis];
        let mut offsets = [0.0, 0.0];
        let mut left = [self.tail_goal, self.goal];
        let mut right = [h[5], c[5]];
        match side {
            Known::LeftInner => {
                g[0] = turn.rotate(&h[k], &axis);
                offsets[0] = (axis - g[0]).dot(&c[k]);
            }
            Known::LeftOuter => {
                left = [
                    turn.rotate_back(&h[k], &self.tail_goal),
                    moved_back(&c[k], &h[k], &self.goal, &turn),
                ];
            }
            Known::RightInner => {
                g[1] = turn.rotate_back(&h[k], &axis);
                offsets[1] = (axis - g[1]).dot(&c[k]);
            }
            Known::RightOuter => {
                right = [turn.rotate(&h[k], &h[5]), moved(&c[k], &h[k], &c[5], &turn)];
            }
        }
        let d = g[1].dot(&c[r]) + offsets[1] - g[0].dot(&c[l]) - offsets[0];
        let sides = Sides {
            k: turn,
            left,
            right,
            d,
        };
        (sides, g)
    }

    /// Subproblem 6 of the two sides: `q_l` first, `q_r` second.
    fn system(&self, v: &Sides, g: &[Vector3<f64>; 2]) -> Sinusoids {
        let Form { l, r, .. } = self.form;
        let (c, h) = (&self.s.chain.c, &self.s.chain.h);
        let (back, forth) = (-h[l], h[r]);
        Sinusoids {
            first: [
                Wave::new(&g[0], &back, &v.left[0]),
                Wave::new(&g[0], &back, &(v.left[1] - c[l])),
            ],
            second: [
                negated(Wave::new(&g[1], &forth, &v.right[0])),
                negated(Wave::new(&g[1], &forth, &(v.right[1] - c[r]))),
            ],
        }
    }

    /// The branch nearest `key` at `t`, within [`LINK`].
    fn nearest(&self, t: f64, key: &Key) -> Option<(Key, Point)> {
        nearest_among(self.branches(t), key)
    }

    /// Every joint from `t` and a branch's point.
    fn configuration(&self, t: f64, point: &Point) -> [f64; 6] {
        let Form { k, l, r, .. } = self.form;
        let p = self.s.p;
        let h = &self.s.chain.h;
        let axis = &self.s.h;
        let mut q = [0.0; 6];
        q[k] = t;
        q[l] = point.left.angle;
        q[r] = point.right.angle;
        let (first, _) = subproblem1(axis, &self.s.link, &point.w);
        let pair = atan2(point.pair.0, point.pair.1);
        q[p] = first;
        q[p + 1] = wrap_angle(self.s.sign * (pair - first));
        // R6 = Ra' R(h, -th) Rb' R_O.
        let mut before = Matrix3::<f64>::identity();
        for (j, value) in q.iter().enumerate().take(p) {
            before *= rotation(&h[j], *value);
        }
        let mut after = Matrix3::<f64>::identity();
        for (j, value) in q.iter().enumerate().take(5).skip(p + 2) {
            after *= rotation(&h[j], *value);
        }
        let tail =
            after.transpose() * rotation(axis, -pair) * before.transpose() * self.orientation;
        let n = &self.s.tail_normal;
        q[5] = subproblem1(&h[5], n, &(tail * n)).0;
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::analytic::structure::{ArmStructure, Motion};
    use crate::ik::analytic::test_random::{point, unit};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The derivation, form by form: at the generating value of the
    /// searched joint, subproblem 6 has the generating `(q_l, q_r)` among
    /// its solutions, and on that branch the residual vanishes and every
    /// joint is read back.
    #[test]
    fn each_form_reads_back_the_generating_configuration() {
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        for layout in [ParallelLayout::SecondThird, ParallelLayout::ThirdFourth] {
            for _ in 0..50 {
                let p = layout.first();
                let points: Vec<_> = (0..6).map(|_| point(&mut rng) * 2.0).collect();
                let mut axes: Vec<_> = (0..6).map(|_| unit(&mut rng)).collect();
                axes[p + 1] = -axes[p];
                let home = Pose::new(
                    crate::math::Rotation3::from_euler_angles(0.3, -0.2, 1.1).into_inner(),
                    point(&mut rng),
                );
                let s = ArmStructure::from_lines(points, axes, vec![Motion::Rotation; 6], home);
                let search = ParallelPairSearch::new(&Chain::of(&s).unwrap(), layout);
                assert_eq!(search.searches, 2);
                let q: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-3.1..3.1));
                let target = s.forward_kinematics(&q);
                for form in search.forms {
                    let problem = Problem::new(&search, &target, form);
                    let branch =
                        problem
                            .branches(q[form.k])
                            .into_iter()
                            .flatten()
                            .find(|(key, _)| {
                                wrap_angle(key.angles[0] - q[form.l]).abs() < 1e-8
                                    && wrap_angle(key.angles[1] - q[form.r]).abs() < 1e-8
                            });
                    let (_, at) = branch.unwrap_or_else(|| panic!("{form:?}: no branch"));
                    assert!(problem.residual_of(&at).abs() < 1e-9, "{form:?}");
                    let read = problem.configuration(q[form.k], &at);
                    for (a, b) in read.iter().zip(&q) {
                        assert!(wrap_angle(a - b).abs() < 1e-8, "{form:?}: {read:?} {q:?}");
                    }
                }
            }
        }
    }

    /// The residual's slope along each branch against central differences
    /// (the branch followed by its key), every form.
    #[test]
    fn residual_slopes_match_finite_differences() {
        let mut rng = ChaCha8Rng::seed_from_u64(23);
        let mut checked = 0;
        for layout in [ParallelLayout::SecondThird, ParallelLayout::ThirdFourth] {
            for _ in 0..20 {
                let p = layout.first();
                let points: Vec<_> = (0..6).map(|_| point(&mut rng) * 2.0).collect();
                let mut axes: Vec<_> = (0..6).map(|_| unit(&mut rng)).collect();
                axes[p + 1] = axes[p];
                let s = ArmStructure::from_lines(
                    points,
                    axes,
                    vec![Motion::Rotation; 6],
                    Pose::identity(),
                );
                let search = ParallelPairSearch::new(&Chain::of(&s).unwrap(), layout);
                let q: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-3.1..3.1));
                let target = s.forward_kinematics(&q);
                for form in search.forms {
                    let problem = Problem::new(&search, &target, form);
                    checked += slopes_checked(&problem, rng.gen_range(-3.0..3.0));
                }
            }
        }
        assert!(checked > 50, "{checked}");
    }
}
