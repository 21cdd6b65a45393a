//! The one-dimensional search for three general positioning joints (no
//! intersecting or parallel pair among them) in front of a spherical wrist.
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
//! [`SAMPLES`] evenly spaced `t1` over one turn; every sign change between
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

/// The search over the first joint of `chain`.
fn search(p: &Problem, out: &mut [([f64; 3], bool)]) -> usize {
    use std::f64::consts::{PI, TAU};
    let mut count = 0;
    let mut push = |t1: f64, branch: usize, out: &mut [([f64; 3], bool)]| {
        let found = finish(p, t1, branch);
        let duplicate = out[..count].iter().any(|(q, _)| {
            q.iter()
                .zip(&found.0)
                .all(|(a, b)| crate::math::wrap_angle(a - b).abs() < 1e-9)
        });
        if !duplicate && count < out.len() {
            out[count] = found;
            count += 1;
        }
    };
    let step = TAU / SAMPLES as f64;
    let mut samples = [[None; SAMPLES]; 2];
    let [first, second] = &mut samples;
    for (k, (a, b)) in first.iter_mut().zip(second.iter_mut()).enumerate() {
        [*a, *b] = residuals(p, -PI + step * k as f64);
    }
    for (branch, row) in samples.iter().enumerate() {
        let at = |k: usize| row[k % SAMPLES];
        let mut before = at(SAMPLES - 1);
        let mut previous = at(0);
        for k in 1..=SAMPLES {
            let t = -PI + step * k as f64;
            let ta = t - step;
            let value = at(k);
            let bracket = match (previous, value) {
                (Some(fa), Some(fb)) => Some(((ta, fa), (t, fb))),
                // The branch ends between the samples (its two solutions of
                // subproblem 4 merge): the root may lie before the end.
                (Some(fa), None) => Some(((ta, fa), branch_end(p, branch, ta, t))),
                (None, Some(fb)) => Some((branch_end(p, branch, t, ta), (t, fb))),
                (None, None) => None,
            };
            if let Some(((ta, fa), (tb, fb))) = bracket {
                if fa == 0.0 || fa.signum() != fb.signum() {
                    if let Some(t1) = refine(p, branch, (ta, fa), (tb, fb)) {
                        push(t1, branch, out);
                    }
                }
            }
            // |f| has a local minimum at the previous sample without a sign
            // change: two roots may hide in the two intervals around it.
            if let (Some(f0), Some(f1), Some(f2)) = (before, previous, value) {
                if f0.signum() == f1.signum()
                    && f1.signum() == f2.signum()
                    && f1.abs() < f0.abs()
                    && f1.abs() < f2.abs()
                    && parabola_nears_zero(f0, f1, f2)
                {
                    let (a, b) = (ta - step, t);
                    if let Some((tm, fm)) = minimize(p, branch, a, b) {
                        if fm.signum() != f1.signum() {
                            for (x, fx) in [(a, f0), (b, f2)] {
                                let (lo, hi) = if x < tm {
                                    ((x, fx), (tm, fm))
                                } else {
                                    ((tm, fm), (x, fx))
                                };
                                if let Some(t1) = refine(p, branch, lo, hi) {
                                    push(t1, branch, out);
                                }
                            }
                        }
                    }
                }
            }
            before = previous;
            previous = value;
        }
    }
    count
}

/// True when the parabola through three equally spaced samples of the
/// same sign, smallest in the middle, dips below a quarter of the middle
/// sample's magnitude (or through zero): only then can two roots hide there.
fn parabola_nears_zero(f0: f64, f1: f64, f2: f64) -> bool {
    let s = f1.signum();
    let (g0, g1, g2) = (s * f0, s * f1, s * f2);
    let curvature = g0 - 2.0 * g1 + g2;
    if curvature <= 0.0 {
        return true;
    }
    let vertex = g1 - (g2 - g0) * (g2 - g0) / (8.0 * curvature);
    vertex < 0.25 * g1
}

/// Golden-section search for the minimum of `|f|` of branch `branch` on
/// `[a, b]`, stopping early when `f` changes sign; `None` if the branch
/// ends inside.
fn minimize(p: &Problem, branch: usize, mut a: f64, mut b: f64) -> Option<(f64, f64)> {
    const RATIO: f64 = 0.618_033_988_749_894_9;
    let f = |t: f64| residual(p, t, branch);
    let reference = f(0.5 * (a + b))?.signum();
    let mut x1 = b - RATIO * (b - a);
    let mut x2 = a + RATIO * (b - a);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    for _ in 0..60 {
        if f1.signum() != reference {
            return Some((x1, f1));
        }
        if f2.signum() != reference {
            return Some((x2, f2));
        }
        if (b - a).abs() < ROOT_TOLERANCE {
            break;
        }
        if f1.abs() < f2.abs() {
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
    Some(if f1.abs() < f2.abs() {
        (x1, f1)
    } else {
        (x2, f2)
    })
}

/// The last point (and residual) of branch `branch` between `defined`,
/// where it exists, and `undefined`, where it does not (bisection to
/// [`ROOT_TOLERANCE`]).
fn branch_end(p: &Problem, branch: usize, defined: f64, undefined: f64) -> (f64, f64) {
    let (mut a, mut b) = (defined, undefined);
    let mut fa = residual(p, a, branch).unwrap_or(0.0);
    for _ in 0..60 {
        if (b - a).abs() < ROOT_TOLERANCE {
            break;
        }
        let m = 0.5 * (a + b);
        match residual(p, m, branch) {
            Some(f) => {
                a = m;
                fa = f;
            }
            None => b = m,
        }
    }
    (a, fa)
}

/// Illinois regula falsi on a bracket `[a, b]` with `f(a) f(b) <= 0`.
fn refine(p: &Problem, branch: usize, a: (f64, f64), b: (f64, f64)) -> Option<f64> {
    let ((mut ta, mut fa), (mut tb, mut fb)) = (a, b);
    if fa == 0.0 {
        return Some(ta);
    }
    let mut side = 0i8;
    for _ in 0..MAX_STEPS {
        if (tb - ta).abs() < ROOT_TOLERANCE {
            break;
        }
        let mut t = (ta * fb - tb * fa) / (fb - fa);
        if !(t > ta.min(tb) && t < ta.max(tb)) {
            t = 0.5 * (ta + tb);
        }
        let f = residual(p, t, branch)?;
        if f == 0.0 {
            return Some(t);
        }
        if f.signum() == fb.signum() {
            tb = t;
            fb = f;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            ta = t;
            fa = f;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    Some(if fa.abs() < fb.abs() { ta } else { tb })
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
