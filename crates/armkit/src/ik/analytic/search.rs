//! One-dimensional searches: the root finder `find_roots` of any scalar
//! residual of one angle with branches (`Residual`), and its first use,
//! three general positioning joints (no intersecting or parallel pair among
//! them) in front of a spherical wrist (the one-pair classes in
//! `pair_search` are the other).
//!
//! For a trial `t1`, the wrist goal seen before joint 1 is
//! `X(t1) = c1 + R1' (W - c1)`. Joint 2 can carry a point `y` onto `X`
//! only if both lie at the same height along `h2` and at the same distance
//! from axis 2. The height condition fixes joint 3 (subproblem 4, two
//! branches `b`: `h2 . R3 (w - c3) = h2 . (X - c3)`); what is left is the
//! scalar residual `f_b(t1) = |E3 w - c2|^2 - |X - c2|^2`, whose zeros are
//! the solutions (joint 2 then by subproblem 1).
//!
//! Search ([`SAMPLES`], [`ROOT_TOLERANCE`]): `f_b` is sampled on
//! [`SAMPLES`] evenly spaced `t1` over one turn (the number is the
//! caller's, a const parameter of `find_roots`; a residual may ask for
//! `Sampling::Refined` instead: a coarse pass, then midpoints only where
//! roots may hide, as the one-pair search does); every sign change between
//! neighbouring samples (or between a sample and the end of the branch,
//! where subproblem 4's two solutions merge, found by bisection) is refined
//! by the Illinois variant of regula falsi until the bracket is narrower
//! than [`ROOT_TOLERANCE`] rad or `f` is exactly zero; where `|f_b|` has a
//! local minimum at a sample without a sign change and the parabola through
//! the three samples dips below a quarter of it, a golden-section search
//! (to the same tolerance) looks for a sign change hiding between the
//! neighbours (two close roots). A root where `f_b` only touches zero (a
//! double root) can still be missed by one formulation, hence two (see
//! `position`); the search classes are held to >= 99.9 % of random
//! poses, not 100 %.

use super::chain::Chain;
use super::subproblems::{subproblem1, Sinusoid, Spoke, Turn, Turns};
use super::trig2::Trig2;
use crate::math::Vector3;

/// Samples of `t1` over one turn.
pub const SAMPLES: usize = 128;
/// Width (rad) below which a bracket of `t1` counts as converged.
pub const ROOT_TOLERANCE: f64 = 1e-13;
/// Most refinement steps per root.
const MAX_STEPS: usize = 100;

/// The residuals of both branches at `t1` (one rotation and one
/// subproblem 4 shared), for the sampling pass.
fn residuals(p: &Problem, t1: f64) -> [Option<f64>; 2] {
    let (x, t3s) = p.joint3(t1);
    if !t3s.exact || t3s.as_slice().len() < 2 {
        return [None, None];
    }
    let c2 = p.chain.c[1];
    let radius = (x - c2).norm_squared();
    let at = |t3: &Turn| Some((p.turned(t3) - c2).norm_squared() - radius);
    [at(&t3s.as_slice()[0]), at(&t3s.as_slice()[1])]
}

/// The residual of branch `branch` at `t1`, if the branch exists there.
fn residual(p: &Problem, t1: f64, branch: usize) -> Option<f64> {
    let (x, t3s) = p.joint3(t1);
    if !t3s.exact || t3s.as_slice().len() < 2 {
        return None;
    }
    let c2 = p.chain.c[1];
    let y = p.turned(&t3s.as_slice()[branch]);
    Some((y - c2).norm_squared() - (x - c2).norm_squared())
}

/// Three positioning axes as lines: points `c`, unit directions `h`.
pub(crate) struct Lines3 {
    c: [Vector3<f64>; 3],
    h: [Vector3<f64>; 3],
}

/// One search: the lines, the point `w` joints 1-3 must carry onto `goal`,
/// and what every residual evaluation shares (read once per search).
struct Problem {
    chain: Lines3,
    /// `goal - c1`, turned back by joint 1.
    goal_by_1: Spoke,
    /// Joint 3's height equation `h2 . R3 (w - c3) = h2 . (X - c3)`.
    height3: Sinusoid,
    /// `w - c3` turned by joint 3.
    arm3: Spoke,
}

impl Problem {
    fn new(chain: Lines3, w: &Vector3<f64>, goal: &Vector3<f64>) -> Problem {
        let (c, h) = (&chain.c, &chain.h);
        Problem {
            goal_by_1: Spoke::new(&h[0], &(goal - c[0])),
            height3: Sinusoid::new(&h[1], &h[2], &(w - c[2])),
            arm3: Spoke::new(&h[2], &(w - c[2])),
            chain,
        }
    }

    /// The wrist goal seen before joint 1, `X(t1) = c1 + R1' (goal - c1)`,
    /// and joint 3's solutions of the height equation there.
    fn joint3(&self, t1: f64) -> (Vector3<f64>, Turns) {
        let (c, h) = (&self.chain.c, &self.chain.h);
        let x = c[0] + self.goal_by_1.turned_back(&Turn::of_angle(t1));
        (x, self.height3.solve(h[1].dot(&(x - c[2]))))
    }

    /// `E3 w = c3 + R3 (w - c3)` at joint 3's turn `t3`.
    fn turned(&self, t3: &Turn) -> Vector3<f64> {
        self.chain.c[2] + self.arm3.turned(t3)
    }
}

/// Joints 1-3 of `chain` putting `w` at `goal`, by the search; written to
/// `out`, returns how many. The search runs twice and the roots are merged
/// (duplicates within 1e-9 rad dropped): over joint 1, and over joint 3 on
/// the inverted problem `E3^-1 E2^-1 E1^-1 goal = w`. Each alone misses
/// some roots where its residual is flat or only touches zero (the one over
/// joint 1 when axes 1 and 2 nearly meet, as in the iiwa14 URDF); on 4 000
/// poses of 40 random arms each missed 0.3-0.5 %, merged none.
pub(crate) fn position(
    chain: &Chain,
    w: &Vector3<f64>,
    goal: &Vector3<f64>,
    out: &mut [([f64; 3], bool)],
) -> usize {
    let (c, h) = (&chain.c, &chain.h);
    let forward = Lines3 {
        c: [c[0], c[1], c[2]],
        h: [h[0], h[1], h[2]],
    };
    let mut count = search(&Problem::new(forward, w, goal), out);
    let inverted = Lines3 {
        c: [c[2], c[1], c[0]],
        h: [-h[2], -h[1], -h[0]],
    };
    let mut more = [([0.0; 3], false); 16];
    let extra = search(&Problem::new(inverted, goal, w), &mut more);
    for (mut q, exact) in more.into_iter().take(extra) {
        q.swap(0, 2);
        let duplicate = out[..count].iter().any(|(p, _)| {
            p.iter()
                .zip(&q)
                .all(|(a, b)| crate::math::wrap_angle(a - b).abs() < 1e-9)
        });
        if !duplicate && count < out.len() {
            out[count] = (q, exact);
            count += 1;
        }
    }
    count
}

/// The spherical-wrist search as a residual of joint 1 with two branches
/// (subproblem 4's solutions for joint 3), each keyed by its index.
impl Residual<2> for Problem {
    type Key = u8;

    #[inline]
    fn sample(&self, t: f64) -> [Option<(f64, u8)>; 2] {
        let [a, b] = residuals(self, t);
        [a.map(|f| (f, 0)), b.map(|f| (f, 1))]
    }

    #[inline]
    fn residual(&self, t: f64, branch: &u8) -> Option<(f64, u8)> {
        residual(self, t, usize::from(*branch)).map(|f| (f, *branch))
    }
}

/// The search over the first joint of `chain`.
fn search(p: &Problem, out: &mut [([f64; 3], bool)]) -> usize {
    let mut count = 0;
    find_roots::<_, 2, SAMPLES>(p, |t1, branch| {
        let found = finish(p, t1, usize::from(branch));
        let duplicate = out[..count].iter().any(|(q, _)| {
            q.iter()
                .zip(&found.0)
                .all(|(a, b)| crate::math::wrap_angle(a - b).abs() < 1e-9)
        });
        if !duplicate && count < out.len() {
            out[count] = found;
            count += 1;
        }
    });
    count
}

/// A scalar residual `f_b(t)` of one angle `t` (rad) on up to `B` branches
/// `b`: what [`find_roots`] searches. A branch is named by a key read at a
/// sample (its index, or where the branch was, for branches without a
/// fixed order) and followed from there: each evaluation returns the key
/// of the branch where it was evaluated, used for the next, nearby one.
pub(crate) trait Residual<const B: usize> {
    /// What names a branch.
    type Key: Copy;

    /// Every branch's residual at `t` with its key (`None` where a branch
    /// does not exist).
    fn sample(&self, t: f64) -> [Option<(f64, Self::Key)>; B];

    /// The residual at `t` of the branch named `key` (read near `t`) and
    /// its key at `t`, if the branch exists there.
    fn residual(&self, t: f64, key: &Self::Key) -> Option<(f64, Self::Key)>;

    /// Reorders `current`'s branches so that each continues the branch of
    /// the same index in `previous` (the sample before). Default: branches
    /// keep their order.
    fn align(
        &self,
        _previous: &[Option<(f64, Self::Key)>; B],
        _current: &mut [Option<(f64, Self::Key)>; B],
    ) {
    }

    /// What is looked for between a sample and the end of its branch.
    const ENDS: EndCheck = EndCheck::SignChange;

    /// Where the samples go (default: evenly spaced).
    const SAMPLING: Sampling = Sampling::Even;

    /// The last point of the branch between `defined`, where it exists,
    /// and `undefined`, where it does not. Default: bisection to
    /// [`ROOT_TOLERANCE`], following the branch's key.
    fn branch_end(&self, defined: (f64, f64, Self::Key), undefined: f64) -> (f64, f64, Self::Key)
    where
        Self: Sized,
    {
        bisect_end(self, defined, undefined)
    }

    /// True when the keys of two neighbouring samples name the same branch
    /// (default: always, for branches of a fixed order). When not, each is
    /// treated as a branch ending between the samples.
    fn same_branch(&self, _a: &Self::Key, _b: &Self::Key) -> bool {
        true
    }

    /// True when the root inside the bracket `lo`, `hi` (a sign change of
    /// one branch) is known already (found by another search of the same
    /// problem): it is then not refined again. Default: never.
    fn known_root(&self, _lo: &Point<Self::Key>, _hi: &Point<Self::Key>) -> bool {
        false
    }
}

/// What [`find_roots`] looks for between a sample and the end of its
/// branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum EndCheck {
    /// A sign change only (the residual is not expected to turn near an
    /// end: the spherical-wrist search).
    SignChange,
    /// A sign change, or a dip through zero and back (a square-root end,
    /// where two roots can sit between the last sample and the end: the
    /// one-pair search).
    SignChangeOrDip,
}

/// Every branch's residual and key at one sample (`None` where a branch
/// does not exist).
type Sample<K, const B: usize> = [Option<(f64, K)>; B];

/// A point of a branch: angle, residual, key.
pub(crate) type Point<K> = (f64, f64, K);

/// Every root of every branch of `p` over one turn (see the module docs
/// for the sampling, bracketing and refinement), each given to `found`
/// with the key of its branch there.
pub(crate) fn find_roots<R: Residual<B>, const B: usize, const N: usize>(
    p: &R,
    mut found: impl FnMut(f64, R::Key),
) {
    use std::f64::consts::{PI, TAU};
    let step = TAU / N as f64;
    let mut times = [0.0; N];
    let mut samples = [[None; B]; N];
    let n = match R::SAMPLING {
        Sampling::Even => {
            for (k, (t, sample)) in times.iter_mut().zip(samples.iter_mut()).enumerate() {
                *t = -PI + step * k as f64;
                *sample = p.sample(*t);
            }
            N
        }
        Sampling::Refined { levels } => refined_samples(p, levels, &mut times, &mut samples),
    };
    for k in 1..n {
        let (before, current) = samples.split_at_mut(k);
        p.align(&before[k - 1], &mut current[0]);
    }
    // Sample n is sample 0 again (at pi), aligned to the last.
    let mut wrapped = samples[0];
    p.align(&samples[n - 1], &mut wrapped);
    let linked = |a: &Option<(f64, R::Key)>, b: &Option<(f64, R::Key)>| match (a, b) {
        (Some((_, ka)), Some((_, kb))) => p.same_branch(ka, kb),
        _ => true,
    };
    let mut bracket = |lo: Point<R::Key>, hi: Point<R::Key>| {
        if (lo.1 == 0.0 || lo.1.signum() != hi.1.signum()) && !p.known_root(&lo, &hi) {
            if let Some((root, key)) = refine(p, lo, hi) {
                found(root, key);
            }
        }
    };
    // The angle of sample k (k = n: sample 0 a turn on; k < 0: a turn back).
    let time = |k: isize| -> f64 {
        if k < 0 {
            times[(k + n as isize) as usize] - TAU
        } else if k as usize >= n {
            times[k as usize - n] + TAU
        } else {
            times[k as usize]
        }
    };
    for branch in 0..B {
        let at = |k: usize| {
            if k == n {
                wrapped[branch]
            } else {
                samples[k][branch]
            }
        };
        // The sample before sample 0 is the last one of the turn.
        let mut before = at(n - 1);
        for k in 1..=n {
            let previous = at(k - 1);
            let value = at(k);
            let t = time(k as isize);
            let ta = time(k as isize - 1);
            match (previous, value) {
                (Some((fa, ka)), Some((fb, kb))) if p.same_branch(&ka, &kb) => {
                    bracket((ta, fa, ka), (t, fb, kb));
                }
                // The branch ends between the samples (e.g. two solutions of
                // a subproblem merge): a root may lie before the end.
                (a, b) => {
                    if let Some((fa, ka)) = a {
                        let end = p.branch_end((ta, fa, ka), t);
                        end_bracket(p, (ta, fa, ka), end, &mut bracket);
                    }
                    if let Some((fb, kb)) = b {
                        let end = p.branch_end((t, fb, kb), ta);
                        end_bracket(p, end, (t, fb, kb), &mut bracket);
                    }
                }
            }
            // |f| has a local minimum at the previous sample without a sign
            // change: two roots may hide in the two intervals around it.
            if let (Some((f0, k0)), Some((f1, key)), Some((f2, k2))) = (before, previous, value) {
                let a = time(k as isize - 2);
                if linked(&before, &previous)
                    && linked(&previous, &value)
                    && f0.signum() == f1.signum()
                    && f1.signum() == f2.signum()
                    && f1.abs() < f0.abs()
                    && f1.abs() < f2.abs()
                    && parabola_nears_zero([a, ta, t], [f0, f1, f2])
                {
                    if let Some(middle) = minimize(p, key, f1.signum(), a, t) {
                        if middle.1.signum() != f1.signum() {
                            bracket((a, f0, k0), middle);
                            bracket(middle, (t, f2, k2));
                        }
                    }
                }
            }
            before = previous;
        }
    }
}

/// How [`find_roots`] places its samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sampling {
    /// `N` evenly spaced over the turn.
    Even,
    /// One in `2^levels` of those first (a coarse pass), then, `levels`
    /// times, the midpoint of each interval only where the residual may
    /// hide roots the coarser samples cannot see ([`needs_midpoint`]): a
    /// branch ending or changing between them, a sign change, or a local
    /// minimum of `|f|` at either end. Elsewhere each branch is clear of
    /// zero and monotone-looking there, where finer samples find nothing
    /// more.
    Refined {
        /// Halvings of the coarse step down to `2 pi / N`.
        levels: u32,
    },
}

/// The samples of [`Sampling::Refined`] (see there) in `times`,
/// `samples` (ascending; aligned, though [`find_roots`] aligns again);
/// returns how many.
fn refined_samples<R: Residual<B>, const B: usize, const N: usize>(
    p: &R,
    levels: u32,
    times: &mut [f64; N],
    samples: &mut [Sample<R::Key, B>; N],
) -> usize {
    use std::f64::consts::{PI, TAU};
    let step = TAU / N as f64;
    let stride = 1usize << levels.min(N.trailing_zeros());
    // Sample positions as multiples of the fine step; each level reads
    // one buffer and writes the other (the last level `samples`).
    let mut index = [0usize; N];
    let mut next_index = [0usize; N];
    let mut own = [[None; B]; N];
    let halvings = stride.trailing_zeros();
    let (mut current, mut next) = if halvings % 2 == 1 {
        (&mut own, samples)
    } else {
        (samples, &mut own)
    };
    let mut n = 0;
    for k in (0..N).step_by(stride) {
        index[n] = k;
        current[n] = p.sample(-PI + step * k as f64);
        n += 1;
    }
    let mut gap = stride;
    let mut swaps = 0;
    while gap > 1 && n > 2 {
        let samples = &mut *current;
        for k in 1..n {
            let (done, rest) = samples.split_at_mut(k);
            p.align(&done[k - 1], &mut rest[0]);
        }
        // The neighbours across the wrap, aligned to the sample beside them.
        let mut wrapped = samples[0];
        p.align(&samples[n - 1], &mut wrapped);
        let mut last_before_first = samples[n - 1];
        p.align(&samples[0], &mut last_before_first);
        let mut second_after_wrapped = samples[1];
        p.align(&wrapped, &mut second_after_wrapped);
        let mut m = 0;
        for j in 0..n {
            next_index[m] = index[j];
            next[m] = samples[j];
            m += 1;
            let end = if j + 1 < n { index[j + 1] } else { N };
            if end - index[j] < 2 || m >= N {
                continue;
            }
            let before = if j == 0 {
                &last_before_first
            } else {
                &samples[j - 1]
            };
            let b = if j + 1 < n { &samples[j + 1] } else { &wrapped };
            let after = match j + 2 {
                k if k < n => &samples[k],
                k if k == n => &wrapped,
                _ => &second_after_wrapped,
            };
            if needs_midpoint(p, before, &samples[j], b, after) {
                let k = index[j] + (end - index[j]) / 2;
                next_index[m] = k;
                next[m] = p.sample(-PI + step * k as f64);
                m += 1;
            }
        }
        std::mem::swap(&mut index, &mut next_index);
        std::mem::swap(&mut current, &mut next);
        swaps += 1;
        n = m;
        gap /= 2;
    }
    // Stopped early (too few samples): the result is in the other buffer.
    if swaps % 2 != halvings % 2 {
        next[..n].copy_from_slice(&current[..n]);
    }
    for (t, k) in times.iter_mut().zip(&index[..n]) {
        *t = -PI + step * *k as f64;
    }
    n
}

/// True when the coarse interval between samples `a` and `b` (aligned:
/// same slot, same branch) must get its midpoint: a branch present at one
/// end only or changing between them, a sign change, or a local minimum
/// of `|f|` at `a` or `b` (against `before` and `after`, the coarse
/// samples around them).
fn needs_midpoint<R: Residual<B>, const B: usize>(
    p: &R,
    before: &Sample<R::Key, B>,
    a: &Sample<R::Key, B>,
    b: &Sample<R::Key, B>,
    after: &Sample<R::Key, B>,
) -> bool {
    let magnitude = |x: &Option<(f64, R::Key)>| x.map_or(f64::INFINITY, |(f, _)| f.abs());
    for i in 0..B {
        match (&a[i], &b[i]) {
            (None, None) => continue,
            (Some((fa, ka)), Some((fb, kb))) => {
                if !p.same_branch(ka, kb) || fa.signum() != fb.signum() || *fa == 0.0 {
                    return true;
                }
                let (ma, mb) = (fa.abs(), fb.abs());
                // A minimum at `a` (below `b` and the sample before it) or
                // at `b` (below `a` and the sample after it).
                if (ma <= mb && ma <= magnitude(&before[i]))
                    || (mb <= ma && mb <= magnitude(&after[i]))
                {
                    return true;
                }
            }
            _ => return true,
        }
    }
    false
}

/// A branch's piece between a sample and the branch's end: a sign change
/// is refined; without one the residual may still dip through zero and
/// back (two roots near a fold, where it has a square-root end), so it is
/// also read at 1/16 and 1/4 of the way from the end (square roots of the
/// distance evenly spaced); a sign change there is refined, and an inner
/// value smaller in magnitude than both ends is minimized (golden section)
/// for one.
fn end_bracket<R: Residual<B>, const B: usize>(
    p: &R,
    end: Point<R::Key>,
    sample: Point<R::Key>,
    bracket: &mut impl FnMut(Point<R::Key>, Point<R::Key>),
) {
    if end.1 == 0.0 || end.1.signum() != sample.1.signum() {
        bracket(end, sample);
        return;
    }
    if R::ENDS == EndCheck::SignChange {
        return;
    }
    let mut points = [end; 4];
    let mut n = 1;
    let mut key = end.2;
    for fraction in [0.0625, 0.25] {
        let t = end.0 + (sample.0 - end.0) * fraction;
        let Some((f, k)) = p.residual(t, &key) else {
            break;
        };
        key = k;
        points[n] = (t, f, k);
        n += 1;
    }
    points[n] = sample;
    n += 1;
    let points = &points[..n];
    for pair in points.windows(2) {
        if pair[0].1.signum() != pair[1].1.signum() {
            bracket(pair[0], pair[1]);
        }
    }
    if points.iter().any(|x| x.1.signum() != end.1.signum()) {
        return;
    }
    // No sign change seen: an inner dip may hide two roots.
    for k in 1..n - 1 {
        let (before, x, after) = (points[k - 1], points[k], points[k + 1]);
        if x.1.abs() < before.1.abs() && x.1.abs() < after.1.abs() {
            let (a, b) = if before.0 < after.0 {
                (before.0, after.0)
            } else {
                (after.0, before.0)
            };
            if let Some(middle) = minimize(p, x.2, x.1.signum(), a, b) {
                if middle.1.signum() != x.1.signum() {
                    bracket(before, middle);
                    bracket(middle, after);
                }
            }
        }
    }
}

/// True when the parabola through three samples `f` at `t` (ascending)
/// of the same sign, smallest in the middle, dips below a quarter of the
/// middle sample's magnitude (or through zero): only then can two roots
/// hide there.
fn parabola_nears_zero(t: [f64; 3], f: [f64; 3]) -> bool {
    let s = f[1].signum();
    let (g0, g1, g2) = (s * f[0], s * f[1], s * f[2]);
    let (h0, h1) = (t[1] - t[0], t[2] - t[1]);
    let vertex = if h0 == h1 {
        // Evenly spaced.
        let curvature = g0 - 2.0 * g1 + g2;
        if curvature <= 0.0 {
            return true;
        }
        g1 - (g2 - g0) * (g2 - g0) / (8.0 * curvature)
    } else {
        // g1 + b x + c x^2 about t[1].
        let (d01, d12) = ((g1 - g0) / h0, (g2 - g1) / h1);
        let c = (d12 - d01) / (h0 + h1);
        if c <= 0.0 {
            return true;
        }
        let b = d01 + c * h0;
        g1 - b * b / (4.0 * c)
    };
    vertex < 0.25 * g1
}

/// Golden-section search for the minimum of `|f|` of the branch `key` on
/// `[a, b]` (where `f` has the sign `reference` at both ends), stopping
/// early where `f` has the other sign; `None` if the branch ends inside.
fn minimize<R: Residual<B>, const B: usize>(
    p: &R,
    mut key: R::Key,
    reference: f64,
    mut a: f64,
    mut b: f64,
) -> Option<Point<R::Key>> {
    const RATIO: f64 = 0.618_033_988_749_894_9;
    let mut f = |t: f64| -> Option<(f64, R::Key)> {
        let (value, next) = p.residual(t, &key)?;
        key = next;
        Some((value, next))
    };
    let middle = 0.5 * (a + b);
    let (fm, km) = f(middle)?;
    if fm.signum() != reference {
        return Some((middle, fm, km));
    }
    let mut x1 = b - RATIO * (b - a);
    let mut x2 = a + RATIO * (b - a);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    for _ in 0..60 {
        if f1.0.signum() != reference {
            return Some((x1, f1.0, f1.1));
        }
        if f2.0.signum() != reference {
            return Some((x2, f2.0, f2.1));
        }
        if (b - a).abs() < ROOT_TOLERANCE {
            break;
        }
        if f1.0.abs() < f2.0.abs() {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - RATIO * (b - a);
            f1 = f(x1)?;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + RATIO * (b - a);
            f2 = f(x2)?;
        }
    }
    Some(if f1.0.abs() < f2.0.abs() {
        (x1, f1.0, f1.1)
    } else {
        (x2, f2.0, f2.1)
    })
}

/// The last point of the branch between `defined`, where it exists, and
/// `undefined`, where it does not (bisection to [`ROOT_TOLERANCE`],
/// following the branch's key).
fn bisect_end<R: Residual<B>, const B: usize>(
    p: &R,
    defined: Point<R::Key>,
    undefined: f64,
) -> Point<R::Key> {
    let (mut a, mut fa, mut key) = defined;
    let mut b = undefined;
    for _ in 0..60 {
        if (b - a).abs() < ROOT_TOLERANCE {
            break;
        }
        let m = 0.5 * (a + b);
        match p.residual(m, &key) {
            Some((f, next)) => {
                a = m;
                fa = f;
                key = next;
            }
            None => b = m,
        }
    }
    (a, fa, key)
}

/// Illinois regula falsi on a bracket with `f(a) f(b) <= 0`, each trial
/// evaluated on the branch as read at the nearer end; the root and its key.
fn refine<R: Residual<B>, const B: usize>(
    p: &R,
    a: Point<R::Key>,
    b: Point<R::Key>,
) -> Option<(f64, R::Key)> {
    let (a, b) = illinois(a, b, ROOT_TOLERANCE, |t, near| p.residual(t, near))?;
    Some(if a.1.abs() < b.1.abs() {
        (a.0, a.2)
    } else {
        (b.0, b.2)
    })
}

/// Where the discriminant of the degree-2 trigonometric polynomial
/// `polynomial(t)` changes sign between `defined` and `undefined`: two of
/// its roots merge there (a fold of the branches they carry). Located by
/// [`illinois`] to `width` (rad) on the discriminant alone (the
/// polynomial's coefficients, no roots), taken about one quarter shift
/// (`Trig2::quarter_shift` at `defined`) so that its sign means the same at
/// every trial. The bracket's ends, `defined`'s side first; `None` when
/// the sign does not change or `polynomial` is undefined at a trial.
pub(crate) fn discriminant_sign_change(
    defined: f64,
    undefined: f64,
    width: f64,
    polynomial: impl Fn(f64) -> Option<Trig2>,
) -> Option<(f64, f64)> {
    let start = polynomial(defined)?;
    let shift = start.quarter_shift();
    let at = |t: f64| polynomial(t).map(|f| f.discriminant_about(shift));
    let (fa, fb) = (start.discriminant_about(shift), at(undefined)?);
    let product = fa * fb;
    if product.is_nan() || product >= 0.0 {
        return None;
    }
    let ((a, _, _), (b, _, _)) =
        illinois((defined, fa, ()), (undefined, fb, ()), width, |t, _| {
            at(t).map(|f| (f, ()))
        })?;
    Some((a, b))
}

/// The Illinois variant of regula falsi: shrinks the bracket `a`, `b`
/// (points `(t, f(t), payload)` with `f(a) f(b) <= 0`) until it is
/// narrower than `width` (or [`MAX_STEPS`] steps); each trial is evaluated
/// by `f(t, payload of the nearer end)`. Returns the final ends (both the
/// trial where `f` is exactly zero); `None` where `f` is undefined.
pub(crate) fn illinois<P: Copy>(
    a: Point<P>,
    b: Point<P>,
    width: f64,
    mut f: impl FnMut(f64, &P) -> Option<(f64, P)>,
) -> Option<(Point<P>, Point<P>)> {
    let (mut a, mut b) = (a, b);
    if a.1 == 0.0 {
        return Some((a, a));
    }
    let mut side = 0i8;
    for _ in 0..MAX_STEPS {
        if (b.0 - a.0).abs() < width {
            break;
        }
        let mut t = (a.0 * b.1 - b.0 * a.1) / (b.1 - a.1);
        if !(t > a.0.min(b.0) && t < a.0.max(b.0)) {
            t = 0.5 * (a.0 + b.0);
        }
        let near = if (t - a.0).abs() <= (t - b.0).abs() {
            &a.2
        } else {
            &b.2
        };
        let (value, payload) = f(t, near)?;
        let point = (t, value, payload);
        if value == 0.0 {
            return Some((point, point));
        }
        if value.signum() == b.1.signum() {
            b = point;
            if side == -1 {
                a.1 *= 0.5;
            }
            side = -1;
        } else {
            a = point;
            if side == 1 {
                b.1 *= 0.5;
            }
            side = 1;
        }
    }
    Some((a, b))
}

/// The end of a branch between `defined`, where it exists, and
/// `undefined`, where it does not, at a fold: where `measure` of the
/// branch's key (a squared slope or Jacobian determinant, which falls
/// linearly to zero as two solutions merge) extrapolates to zero. Each step
/// goes 99 % of the way from the branch's last point to that zero (a
/// bisection when the extrapolation fails; just past it once it is within
/// `width`), until the bracket is narrower than `width`. Returns the last
/// point on the branch and the nearest point known beyond it.
pub(crate) fn fold_by_extrapolation<R: Residual<B>, const B: usize>(
    p: &R,
    defined: Point<R::Key>,
    undefined: f64,
    width: f64,
    measure: impl Fn(&R::Key) -> f64,
) -> (Point<R::Key>, f64) {
    let (mut a, mut fa, mut ka) = defined;
    let mut b = undefined;
    let mut previous: Option<(f64, f64)> = None;
    for _ in 0..60 {
        if (b - a).abs() < width {
            break;
        }
        let g = measure(&ka);
        let mut t = 0.5 * (a + b);
        if let Some((t0, g0)) = previous {
            if g0 != g {
                let zero = a - g * (a - t0) / (g - g0);
                if (zero - a) * (b - a) > 0.0 && (zero - a).abs() < (b - a).abs() {
                    t = a + 0.99 * (zero - a);
                    if (zero - a).abs() < 0.5 * width {
                        t = a + (b - a).signum() * 0.75 * width;
                    }
                }
            }
        }
        match p.residual(t, &ka) {
            Some((f, k)) => {
                previous = Some((a, g));
                a = t;
                fa = f;
                ka = k;
            }
            None => b = t,
        }
    }
    ((a, fa, ka), b)
}

/// A branch of a 1-D search at one point: the closed-form step's angles
/// there (rad) and `fold`, the quantity that vanishes where two of its
/// solutions merge (the placing quartic's slope at its root, subproblem 6's
/// Jacobian determinant): its sign tells apart the two branches about to
/// merge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BranchKey<const N: usize> {
    /// The step's angles, each in `[-pi, pi]`, rad.
    pub angles: [f64; N],
    /// The merging quantity.
    pub fold: f64,
}

impl<const N: usize> BranchKey<N> {
    /// Joint-space gap (rad, summed over the angles) between two points;
    /// infinite across a sign of `fold` (never the same branch).
    pub(crate) fn gap(&self, other: &Self) -> f64 {
        if (self.fold > 0.0) != (other.fold > 0.0) {
            return f64::INFINITY;
        }
        self.angles
            .iter()
            .zip(&other.angles)
            .map(|(x, y)| angle_between(*x, *y))
            .sum()
    }
}

/// `|wrap_angle(x - y)|` for `x`, `y` in `[-pi, pi]` (no rounding call).
#[inline]
pub(crate) fn angle_between(x: f64, y: f64) -> f64 {
    let d = (x - y).abs();
    if d > std::f64::consts::PI {
        std::f64::consts::TAU - d
    } else {
        d
    }
}

/// Matches `current`'s branches to `previous`'s (one sample before): each
/// previous branch takes the nearest current one by `gap` within `link`;
/// current branches left over go to slots empty before, then to any free
/// slot. The [`Residual::align`] of searches whose branches have no natural
/// order.
pub(crate) fn align_nearest<K: Copy, const B: usize>(
    previous: &[Option<(f64, K)>; B],
    current: &mut [Option<(f64, K)>; B],
    gap: impl Fn(&K, &K) -> f64,
    link: f64,
) {
    let mut result = [None; B];
    let mut used = [false; B];
    for (slot, before) in result.iter_mut().zip(previous) {
        let Some((_, key)) = before else { continue };
        let mut best: Option<(f64, usize)> = None;
        for (j, now) in current.iter().enumerate() {
            if let (false, Some((_, k))) = (used[j], now) {
                let d = gap(key, k);
                if d < link && best.is_none_or(|(e, _)| d < e) {
                    best = Some((d, j));
                }
            }
        }
        if let Some((_, j)) = best {
            *slot = current[j];
            used[j] = true;
        }
    }
    for j in 0..B {
        if used[j] || current[j].is_none() {
            continue;
        }
        let free = (0..B)
            .find(|&i| result[i].is_none() && previous[i].is_none())
            .or_else(|| (0..B).find(|&i| result[i].is_none()));
        if let Some(i) = free {
            result[i] = current[j];
        }
    }
    *current = result;
}

/// Joints 1-3 at a root `t1` of branch `branch`.
fn finish(p: &Problem, t1: f64, branch: usize) -> ([f64; 3], bool) {
    let (c, h) = (&p.chain.c, &p.chain.h);
    let (x, t3s) = p.joint3(t1);
    let slice = t3s.as_slice();
    let t3 = slice[branch.min(slice.len() - 1)];
    let y = p.turned(&t3);
    let (t2, exact) = subproblem1(&h[1], &(y - c[1]), &(x - c[1]));
    ([t1, t2, t3.angle], exact && t3s.exact)
}
