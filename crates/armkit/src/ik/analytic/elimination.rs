//! Every solution of a 6R arm by algebraic elimination: Raghavan and Roth's
//! fourteen equations (1993) in Manocha and Canny's matrix form (1994),
//! derived here for the product-of-exponentials chain of [`super::structure`]
//! (the papers write Denavit-Hartenberg frames). One method for every 6R
//! arm the closed forms do not take: a general arm, one intersecting or one
//! parallel pair of consecutive axes anywhere, the pairs no 1-D search
//! handles. No sampling of the pose equations: the solutions' third joint
//! angles are the real roots of a trigonometric polynomial of degree 8 in
//! that joint (16 roots, the most a 6R arm has).
//!
//! **The equations.** With `E_i(t)` the turn by `t` about line `i` and
//! `G = T home^-1` (world frame), `E1 E2 E3 E4 E5 E6 = G` gives, applied to
//! a point `c6` of axis 6 (which `E6` leaves in place) and to its direction
//! `h6`, with `c3` a point of axis 3 and `R_i` the turns' rotations:
//!
//! ```text
//! p = E3 E4 E5 c6 - c3 = E2^-1 E1^-1 (G c6) - c3
//! l = R3 R4 R5 h6      = R2^-1 R1^-1 R_G h6
//! ```
//!
//! Joint 6 is gone; the left sides depend on joints 3-5, the right sides on
//! joints 1-2. Raghavan and Roth's fourteen functions
//! `f = (p, l, p.p, p.l, p x l, (p.p) l - 2 (p.l) p)` keep the degree of
//! `p` and `l`: every one is linear in `(1, cos, sin)` of each joint on its
//! side (true for any points `c3`, `c6` on their axes; checked by
//! a unit test on random angles). So `f` is `P m3 (x) m4 (x) m5` on the
//! left (`P` 14 x 27, fixed by the arm, fitted once on a 3 x 3 x 3 grid of
//! angles) and `Q m1 (x) m2` on the right (`Q` 14 x 9, fitted per target on
//! a 3 x 3 grid), `m_i = (1, cos q_i, sin q_i)`.
//!
//! **Elimination.** The eight products of joints 1-2 other than `1` are
//! eliminated by the six combinations `N` with `N Q' = 0` (`Q'` the 14 x 8
//! non-constant columns; a Householder QR), leaving six equations in joints
//! 3-5 only. With the half-angle tangents `x4`, `x5` (each equation times
//! `(1 + x4^2)(1 + x5^2)`) they are six equations in the nine monomials
//! `x4^a x5^b` (`a, b <= 2`); the six again times `x4` give twelve
//! equations `Sigma(q3) v = 0` in the twelve monomials `x4^a x5^b`
//! (`a <= 3`, `b <= 2`), `Sigma` 12 x 12 with entries linear in
//! `(1, cos q3, sin q3)`. A solution needs `det Sigma(q3) = 0`: a
//! trigonometric polynomial of degree 12 whose top four harmonics vanish
//! (Manocha and Canny's factor `(1 + x3^2)^4`), so degree 8, read exactly
//! from [`DET_SAMPLES`] = 17 evaluations by a discrete Fourier transform.
//!
//! **Roots.** The polynomial is sampled at [`ROOT_SAMPLES`] points per turn
//! with its derivative. Each interval between samples is certified by cubic
//! Hermite interpolation and a bound on the polynomial's fourth derivative:
//! no root, or one (ends of opposite signs, the slope bounded away from
//! zero), refined by bracketed Newton to 1e-15 rad; otherwise it is halved.
//! Where the polynomial is flat at a root (slope below [`FLAT`] of its
//! largest sample per rad) the root is refined by the secant method on the
//! determinant itself; where two neighbouring samples are below [`QUIET`]
//! of the largest (the interpolation's rounding, about [`ROUNDING`], may
//! hide or invent sign changes there) the determinant itself is scanned.
//! A dip toward zero that does not cross it (within [`TANGENT`] of its
//! sides, or within the rounding) is a double root made a complex pair by
//! rounding: it is split into the two roots its parabola would have.
//!
//! **Back-substitution.** At each root `Sigma(q3)`'s null vector (Gaussian
//! elimination with full pivoting) is the monomial vector, whose ratios give
//! joints 4 and 5 (where the null space is two-dimensional, two solutions
//! sharing joint 3, the two monomial vectors in it by a 2 x 2 eigenproblem);
//! joints 1 and 2 follow from the fourteen equations by least squares (the
//! QR above), joint 6 by subproblem 1; each candidate is polished by
//! Gauss-Newton on the chain and checked there (exact within 1e-10).
//! A pose out of reach has no real root near a solution: elimination then
//! returns no solution (not a least-squares one, as the closed forms do),
//! and `armkit ik --solver analytic` reports the numeric best effort.
//!
//! **When it does not apply.** With a special pair at joints 1-2 (parallel
//! or intersecting axes), or a spherical wrist, `det Sigma` vanishes
//! identically. Set-up then tries the reversed chain, then the loop cut
//! elsewhere ([`Cut::Split`]: joints 1 and 6 on the right side, on either
//! side of `G`, joint 5 eliminated; special pairs at both ends), and it accepts a
//! chain only when two of three probe poses (forward kinematics of fixed
//! generic configurations) give back their configurations; otherwise the arm keeps its
//! 1-D search.
//!
//! ```
//! use armkit::ik::analytic::{AnalyticOptions, AnalyticSolver};
//! use armkit::ik::closed_form::Fit;
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::model::{DhConvention, DhLink, Model};
//! // A general 6R arm (standard DH d, a, alpha): no two consecutive axes
//! // intersect or are parallel.
//! let links = [
//!     (0.1, 0.3, 0.9), (-0.2, 0.25, -1.1), (0.15, 0.2, 0.8),
//!     (0.3, 0.1, -0.7), (-0.1, 0.15, 1.2), (0.2, 0.05, 0.6),
//! ]
//! .map(|(d, a, alpha)| DhLink::revolute(d, a, alpha).with_limits(-3.2, 3.2));
//! let model = Model::from_dh("general", DhConvention::Standard, &links).unwrap();
//! let q = [0.4, -0.9, 1.3, 0.2, -1.1, 0.7];
//! let target = *forward_kinematics(&model, &mut Data::new(&model), &q).unwrap();
//! let mut solver = AnalyticSolver::new(&model, AnalyticOptions::default()).unwrap();
//! let solutions = solver.solve(&target, &q).unwrap();
//! assert!(solutions.iter().all(|s| s.fit == Fit::Exact));
//! assert!(solutions[0].q().iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
//! ```

use super::chain::{Candidates, Chain};
use super::polish::{chain_pose, settle_root_within, Settle};
use super::roots::illinois;
use super::subproblems::{rotation, subproblem1};
use crate::math::{sin_cos, wrap_angle, Matrix3, Pose, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// [`AnalyticSolver::method`](super::AnalyticSolver::method) for an arm
/// solved by elimination.
pub(crate) const METHOD: &str = "no closed-form class: algebraic elimination (Raghavan and Roth's 14 equations, Manocha and Canny's 12 x 12 matrix in joint 3; the real roots of a degree-8 trigonometric polynomial read from 17 determinants, isolated with certified bounds, refined by Newton, on the determinant itself where the polynomial is flat or below its rounding; joints 4-5 from the null vector, 1-2 by least squares, 6 by subproblem 1, each polished on the chain), up to 16 solutions";
/// Raghavan and Roth's functions of `p` and `l`.
const FUNCTIONS: usize = 14;
/// Evaluations of `det Sigma(q3)` per solve (one turn, evenly spaced): a
/// trigonometric polynomial of degree 8 has 17 coefficients.
pub(crate) const DET_SAMPLES: usize = 17;
/// Harmonics of `det Sigma(q3)`.
const HARMONICS: usize = 8;
/// Samples per turn of the polynomial when its roots are bracketed.
pub(crate) const ROOT_SAMPLES: usize = 128;
/// Where the polynomial dips between two points to within this fraction of
/// its values there without crossing zero, the lowest point is tried as a
/// double root (two real roots made complex by rounding: a pose at a
/// singular configuration).
pub(crate) const TANGENT: f64 = 1e-3;
/// The rounding of the polynomial's values, relative to its largest sample
/// (each determinant's rounding, measured: 1e-14 to 1e-13 per harmonic).
pub(crate) const ROUNDING: f64 = 1e-13;
/// Samples of the polynomial below this fraction of the largest are
/// rounding-dominated: [`QUIET_STEPS`] direct evaluations per interval there.
pub(crate) const QUIET: f64 = 1e-11;
/// Direct evaluations of `det Sigma` per sample interval where the
/// polynomial is quiet (and per window around a dip of it).
pub(crate) const QUIET_STEPS: usize = 8;
/// How many times a dip of the direct evaluations is scanned again, a
/// quarter of the step each time.
pub(crate) const QUIET_REFINEMENTS: usize = 1;
/// A root where the polynomial's slope (per rad) is below this fraction of
/// its largest sample is refined on the determinant itself.
pub(crate) const FLAT: f64 = 1e-4;
/// The null space of `Sigma` at a root counts as two-dimensional (two
/// solutions sharing joint 3) when its eleventh pivot is below this
/// fraction of its first.
pub(crate) const DOUBLE_NULL: f64 = 1e-6;
/// How a back-substituted root is settled on the chain: kept within 1e-3
/// (m and rad) and polished by up to 10 steps. A root of a nearly double
/// root of `det Sigma` is found to about the square root of the
/// polynomial's rounding, which back-substitution amplifies; two solutions
/// that share joint 3 to the rounding come from one root and are polished
/// apart near a singular configuration, where Gauss-Newton slows down.
const SETTLE: Settle = Settle {
    keep: 1e-3,
    iterations: 10,
};
/// The grid of the fits: `(1, cos t, sin t)` at these angles is invertible.
const GRID: [f64; 3] = [0.0, FRAC_PI_2, PI];
/// `(1, cos t, sin t)` in half-angle-tangent polynomials times `1 + x^2`:
/// row `i` holds the coefficients of `x^0, x^1, x^2`.
const HALF_ANGLE: [[f64; 3]; 3] = [[1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [0.0, 2.0, 0.0]];
/// The probe configurations of set-up (generic: no special angles).
const PROBES: [[f64; 6]; 3] = [
    [0.31, -0.72, 1.13, 0.52, -1.27, 0.94],
    [-1.43, 2.21, -0.37, 1.86, 0.63, -2.58],
    [2.67, 0.48, 2.39, -1.12, 1.94, 0.27],
];

/// A 12 x 12 matrix, row major.
type Square = [[f64; 12]; 12];

/// Which joints play which part in the loop `E1 ... E6 = G` (0-based):
/// the two of the right side (with `G`), the three of the left side, the
/// one eliminated (the left side is applied to a point and direction of
/// its axis). Manocha and Canny's formulation leaves the choice free; the
/// loop is cut where no special pair makes `det Sigma` vanish.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cut {
    /// `E3 E4 E5 (c6, h6) = E2^-1 E1^-1 G (c6, h6)`: right 1-2, left 3-5,
    /// joint 6 eliminated.
    Tip,
    /// `E2 E3 E4 (c5, h5) = E1^-1 G E6^-1 (c5, h5)`: right 1 and 6 (on
    /// either side of `G`), left 2-4, joint 5 eliminated: for special
    /// pairs at both ends (1-2 and 5-6).
    Split,
}

impl Cut {
    /// (right side's two joints, left side's three, the eliminated one).
    fn roles(self) -> ([usize; 2], [usize; 3], usize) {
        match self {
            Cut::Tip => ([0, 1], [2, 3, 4], 5),
            Cut::Split => ([0, 5], [1, 2, 3], 4),
        }
    }
}

/// The eliminated equations of one arm (see the module docs), prepared
/// once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Elimination {
    chain: Chain,
    cut: Cut,
    home: Pose,
    /// Length scale (m) dividing `p`, so that the functions are of order 1.
    scale: f64,
    /// `P`: row = function, column `9 i3 + 3 i4 + i5` over `m3 (x) m4 (x) m5`.
    left: [[f64; 27]; FUNCTIONS],
    /// Rotations of the right side's joints by minus each grid angle.
    turned_back: [[Matrix3<f64>; 3]; 2],
    /// `(cos, sin)(k t_j)` at the det samples `t_j = 2 pi j / 17`, `k <= 8`.
    det_table: [[(f64, f64); HARMONICS + 1]; DET_SAMPLES],
    /// `(cos, sin)(2 pi j / ROOT_SAMPLES)`.
    root_table: [(f64, f64); ROOT_SAMPLES],
}

impl Elimination {
    /// The elimination of `chain` (6 rotation joints), or `None` when it
    /// does not apply (the probe poses are not solved back: see the module docs).
    pub(crate) fn new(chain: &Chain, cut: Cut) -> Option<Elimination> {
        if chain.translation.iter().any(|&t| t) {
            return None;
        }
        let home = chain.home_inverse.inverse();
        let scale = (1..6)
            .map(|i| (chain.c[i] - chain.c[i - 1]).norm())
            .sum::<f64>()
            .max(1e-3);
        let mut turned_back = [[Matrix3::identity(); 3]; 2];
        for (joint, turns) in cut.roles().0.into_iter().zip(turned_back.iter_mut()) {
            for (turn, t) in turns.iter_mut().zip(GRID) {
                *turn = rotation(&chain.h[joint], -t);
            }
        }
        let det_table = harmonic_table();
        let mut root_table = [(1.0, 0.0); ROOT_SAMPLES];
        for (j, entry) in root_table.iter_mut().enumerate() {
            let (s, c) = sin_cos(TAU * j as f64 / ROOT_SAMPLES as f64);
            *entry = (c, s);
        }
        let mut elimination = Elimination {
            chain: *chain,
            cut,
            home,
            scale,
            left: [[0.0; 27]; FUNCTIONS],
            turned_back,
            det_table,
            root_table,
        };
        elimination.left = elimination.fit_left();
        elimination.solves_probes().then_some(elimination)
    }

    /// The polynomial `det Sigma(q3)` of `system` and its largest sample's
    /// magnitude.
    fn polynomial(&self, system: &System) -> (Trigonometric, f64) {
        let mut samples = [0.0; DET_SAMPLES];
        for (j, sample) in samples.iter_mut().enumerate() {
            let (c, s) = self.det_table[j][1];
            *sample = system.determinant_at(c, s);
        }
        let largest = samples.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        (
            Trigonometric::of_samples(&samples, &self.det_table),
            largest,
        )
    }

    /// Every solution found for `target` (the chain's end-effector pose).
    pub(crate) fn solve(&self, target: &Pose, out: &mut Candidates) {
        let goal = *target * self.chain.home_inverse;
        let system = self.system(&goal);
        let (polynomial, largest) = self.polynomial(&system);
        let mut roots = [0.0; 2 * HARMONICS + 4];
        let count = polynomial.roots(&self.root_table, &|t| system.determinant(t), &mut roots);
        for &root in &roots[..count] {
            let q3 = if polynomial.at(root)[1].abs() < FLAT * largest {
                refined_on_determinant(&system, root)
            } else {
                root
            };
            self.back_substitute(&system, target, q3, out);
        }
    }

    /// Whether at least two of the [`PROBES`] poses give their configuration
    /// back (one may be near a singular configuration of this arm; an arm
    /// whose `det Sigma` vanishes identically gives none back).
    fn solves_probes(&self) -> bool {
        let solved = |probe: &[f64; 6]| {
            let target = chain_pose(&self.chain, &self.home, probe);
            let mut found = Candidates::new();
            self.solve(&target, &mut found);
            found.as_slice().iter().any(|candidate| {
                candidate.exact
                    && candidate
                        .q
                        .iter()
                        .zip(probe)
                        .all(|(a, b)| wrap_angle(a - b).abs() < 1e-6)
            })
        };
        PROBES.iter().filter(|probe| solved(probe)).count() >= 2
    }

    /// Raghavan and Roth's functions of `p` (divided by the scale) and `l`.
    fn functions(&self, point: &Vector3<f64>, direction: &Vector3<f64>) -> [f64; FUNCTIONS] {
        let p = (point - self.chain.c[self.cut.roles().1[0]]) / self.scale;
        let l = direction;
        let (pp, pl) = (p.dot(&p), p.dot(l));
        let cross = p.cross(l);
        let mixed = l * pp - p * (2.0 * pl);
        [
            p.x, p.y, p.z, l.x, l.y, l.z, pp, pl, cross.x, cross.y, cross.z, mixed.x, mixed.y,
            mixed.z,
        ]
    }

    /// `P` (see [`Elimination::left`]): the left sides on the 3 x 3 x 3 grid
    /// of joints 3-5, turned into coefficients.
    fn fit_left(&self) -> [[f64; 27]; FUNCTIONS] {
        let (c, h) = (&self.chain.c, &self.chain.h);
        let turn = |k: usize, t: f64, x: &Vector3<f64>| c[k] + rotation(&h[k], t) * (x - c[k]);
        let (_, [l3, l4, l5], e) = self.cut.roles();
        let mut values = [[0.0; 27]; FUNCTIONS];
        for (a, t3) in GRID.iter().enumerate() {
            for (b, t4) in GRID.iter().enumerate() {
                for (d, t5) in GRID.iter().enumerate() {
                    let point = turn(l3, *t3, &turn(l4, *t4, &turn(l5, *t5, &c[e])));
                    let direction = rotation(&h[l3], *t3)
                        * rotation(&h[l4], *t4)
                        * rotation(&h[l5], *t5)
                        * h[e];
                    let f = self.functions(&point, &direction);
                    for (row, value) in values.iter_mut().zip(f) {
                        row[9 * a + 3 * b + d] = value;
                    }
                }
            }
        }
        for row in values.iter_mut() {
            for stride in [1, 3, 9] {
                coefficients_along(row, stride);
            }
        }
        values
    }

    /// The right sides on the 3 x 3 grid of joints 1-2 for `goal`
    /// (`T home^-1`), as `Q` (row = function, column `3 i1 + i2`).
    fn fit_right(&self, goal: &Pose) -> [[f64; 9]; FUNCTIONS] {
        let (c, h) = (&self.chain.c, &self.chain.h);
        let ([ra, rb], _, e) = self.cut.roles();
        // Side `side`'s joint turned back by grid angle `i`.
        let back = |side: usize, i: usize, (p, d): (Vector3<f64>, Vector3<f64>)| {
            let (joint, turn) = ([ra, rb][side], &self.turned_back[side][i]);
            (c[joint] + turn * (p - c[joint]), turn * d)
        };
        let by_goal =
            |(p, d): (Vector3<f64>, Vector3<f64>)| (goal.transform_point(&p), goal.rotation * d);
        let end = (c[e], h[e]);
        let moved = by_goal(end);
        let mut values = [[0.0; 9]; FUNCTIONS];
        for a in 0..3 {
            for b in 0..3 {
                let (point, direction) = match self.cut {
                    // E_b^-1 E_a^-1 G (c, h).
                    Cut::Tip => back(1, b, back(0, a, moved)),
                    // E_a^-1 G E_b^-1 (c, h).
                    Cut::Split => back(0, a, by_goal(back(1, b, end))),
                };
                let f = self.functions(&point, &direction);
                for (row, value) in values.iter_mut().zip(f) {
                    row[3 * a + b] = value;
                }
            }
        }
        for row in values.iter_mut() {
            for stride in [1, 3] {
                coefficients_along(row, stride);
            }
        }
        values
    }

    /// The six eliminated equations for `goal` and the QR of `Q'` that
    /// gives joints 1 and 2 back.
    fn system(&self, goal: &Pose) -> System {
        let right = self.fit_right(goal);
        // Columns 0..8: Q' (the products other than 1); 8..35: P; 35: the
        // constant column of Q, moved to the left.
        let mut m = [[0.0; 36]; FUNCTIONS];
        for (row, (q, p)) in m.iter_mut().zip(right.iter().zip(&self.left)) {
            row[..8].copy_from_slice(&q[1..]);
            row[8..35].copy_from_slice(p);
            row[35] = q[0];
        }
        householder(&mut m);
        let mut equations = [[[0.0; 9]; 3]; 6];
        for (k, equation) in equations.iter_mut().enumerate() {
            let row = &m[8 + k];
            let mut coefficients = [0.0; 27];
            coefficients.copy_from_slice(&row[8..35]);
            coefficients[0] -= row[35];
            for (i3, polynomial) in equation.iter_mut().enumerate() {
                *polynomial = half_angle_form(&coefficients[9 * i3..9 * i3 + 9]);
            }
        }
        normalize(&mut equations);
        System {
            equations,
            upper: m,
        }
    }

    /// The solutions at a root `q3` (chain order), settled on the chain,
    /// into `out`: from the null vector of `Sigma(q3)`; and where its null
    /// space is two-dimensional (two solutions share joint 3 to the
    /// rounding) or that vector's configuration is not exact, from the two
    /// monomial vectors in the two-dimensional null space.
    fn back_substitute(&self, system: &System, target: &Pose, q3: f64, out: &mut Candidates) {
        let goal = *target * self.chain.home_inverse;
        let (s3, c3) = sin_cos(q3);
        let null = NullSpace::of(&system.sigma(c3, s3));
        let settled = |v: &[f64; 12]| {
            let q = self.completed(system, &goal, q3, v)?;
            settle_root_within(&self.chain, &self.home, q, target, SETTLE)
        };
        let single = settled(&null.vector());
        if let Some((q, true)) = single {
            out.push_distinct(&q, true);
            if !null.is_double() {
                return;
            }
        }
        let pair = monomials_in(&null.pair()).map(|pair| pair.map(|v| settled(&v)));
        let exact_pair = pair.is_some_and(|p| p.iter().any(|s| matches!(s, Some((_, true)))));
        for (q, exact) in pair.into_iter().flatten().flatten() {
            out.push_distinct(&q, exact);
        }
        if let (Some((q, false)), false) = (single, exact_pair) {
            out.push_distinct(&q, false);
        }
    }

    /// The configuration of the monomial vector `v` (`v[3 a + b] = x4^a
    /// x5^b`) at `q3`: joints 4-5 from the ratios of its largest
    /// neighbours, 1-2 by least squares, 6 by subproblem 1.
    fn completed(&self, system: &System, goal: &Pose, q3: f64, v: &[f64; 12]) -> Option<[f64; 6]> {
        let best = |pairs: &mut dyn Iterator<Item = (usize, usize)>| {
            pairs
                .max_by(|x, y| {
                    let size = |(i, j): (usize, usize)| v[i].abs() + v[j].abs();
                    size(*x).total_cmp(&size(*y))
                })
                .map(|(i, j)| 2.0 * v[j].atan2(v[i]))
        };
        let q4 = best(&mut (0..9).map(|i| (i, i + 3)))?;
        let q5 = best(&mut (0..12).filter(|i| i % 3 != 2).map(|i| (i, i + 1)))?;
        // Joints 1-2: R X = (Y' P) m345 - Y' q0 over the QR's first 8 rows.
        let m345 = tensor3(q3, q4, q5);
        let mut x = [0.0; 8];
        for (i, xi) in x.iter_mut().enumerate() {
            let row = &system.upper[i];
            *xi = row[8..35]
                .iter()
                .zip(&m345)
                .map(|(a, b)| a * b)
                .sum::<f64>()
                - row[35];
        }
        for i in (0..8).rev() {
            let row = &system.upper[i];
            let known: f64 = (i + 1..8).map(|j| row[j] * x[j]).sum();
            x[i] = (x[i] - known) / row[i];
        }
        // X over m1 (x) m2 without the constant: index 3 i1 + i2 - 1.
        let ([ra, rb], [l3, l4, l5], e) = self.cut.roles();
        let mut q = [0.0; 6];
        q[ra] = x[5].atan2(x[2]);
        q[rb] = x[1].atan2(x[0]);
        (q[l3], q[l4], q[l5]) = (q3, q4, q5);
        q[e] = self.eliminated_joint(goal, &q, e);
        q.iter().all(|v| v.is_finite()).then_some(q)
    }

    /// The eliminated joint `e` by subproblem 1: `R_e = (R1 ... R_{e-1})^-1
    /// R_G (R_{e+1} ... R6)^-1` turns a vector normal to `h_e` (`q[e]`
    /// unread).
    fn eliminated_joint(&self, goal: &Pose, q: &[f64; 6], e: usize) -> f64 {
        let h = &self.chain.h;
        let product = |joints: std::ops::Range<usize>| {
            joints.fold(Matrix3::<f64>::identity(), |m, k| m * rotation(&h[k], q[k]))
        };
        let (before, after) = (product(0..e), product(e + 1..6));
        let normal = h[e].cross(&if h[e].x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        });
        let turned = before.transpose() * goal.rotation * after.transpose() * normal;
        subproblem1(&h[e], &normal, &turned).0
    }
}

/// A root of the polynomial refined by the secant method on `det Sigma`
/// itself (at most 6 steps, to 1e-12 rad; the chain's polish follows): where the polynomial is flat
/// its interpolation's rounding (relative to its largest sample) moves the
/// root, while the determinant evaluated there is accurate relative to its
/// own size. The root itself is kept if the secant steps wander off.
fn refined_on_determinant(system: &System, root: f64) -> f64 {
    let det = |t: f64| system.determinant(t);
    let (mut t0, mut t1) = (root, root + 1e-7);
    let (mut f0, mut f1) = (det(t0), det(t1));
    for _ in 0..6 {
        if f1 == f0 {
            break;
        }
        let t2 = t1 - f1 * (t1 - t0) / (f1 - f0);
        if !t2.is_finite() || (t2 - root).abs() > 1e-3 {
            return root;
        }
        if (t2 - t1).abs() < 1e-12 {
            return t2;
        }
        (t0, f0) = (t1, f1);
        t1 = t2;
        f1 = det(t1);
    }
    t1
}

/// `(cos, sin)(k t_j)` at the det samples `t_j = 2 pi j / 17`, `k <= 8`.
fn harmonic_table() -> [[(f64, f64); HARMONICS + 1]; DET_SAMPLES] {
    std::array::from_fn(|j| {
        std::array::from_fn(|k| {
            let (s, c) = sin_cos(TAU * (j * k) as f64 / DET_SAMPLES as f64);
            (c, s)
        })
    })
}

/// One target's eliminated equations and the QR's triangle.
struct System {
    /// Six equations; `[i3][3 a + b]` the coefficient of `x4^a x5^b` times
    /// `m3[i3]`.
    equations: [[[f64; 9]; 3]; 6],
    /// After the Householder QR: rows 0..8 hold `R` (columns 0..8) and
    /// `Y' P`, `Y' q0` (columns 8..35, 35); rows 8..14 the eliminated
    /// equations.
    upper: [[f64; 36]; FUNCTIONS],
}

impl System {
    /// `det Sigma(q3)` at `q3` (rad).
    fn determinant(&self, q3: f64) -> f64 {
        let (s, c) = sin_cos(q3);
        self.determinant_at(c, s)
    }

    /// `det Sigma(q3)` at `(cos q3, sin q3)`, by [`shifted_determinant`].
    fn determinant_at(&self, c3: f64, s3: f64) -> f64 {
        shifted_determinant(&self.equations_at(c3, s3))
    }

    /// The six equations at `(cos q3, sin q3)`: `[k][3 a + b]` the
    /// coefficient of `x4^a x5^b`.
    fn equations_at(&self, c3: f64, s3: f64) -> [[f64; 9]; 6] {
        let mut at = [[0.0; 9]; 6];
        for (row, equation) in at.iter_mut().zip(&self.equations) {
            let [constant, cosine, sine] = equation;
            for (i, value) in row.iter_mut().enumerate() {
                *value = constant[i] + c3 * cosine[i] + s3 * sine[i];
            }
        }
        at
    }

    /// `Sigma(q3)` at `(cos q3, sin q3)`: rows 0..6 the equations, rows
    /// 6..12 the same times `x4`; column `3 a + b` is `x4^a x5^b`.
    fn sigma(&self, c3: f64, s3: f64) -> Square {
        let mut sigma = [[0.0; 12]; 12];
        for (k, row) in self.equations_at(c3, s3).iter().enumerate() {
            sigma[k][..9].copy_from_slice(row);
            sigma[6 + k][3..].copy_from_slice(row);
        }
        sigma
    }
}

/// `det Sigma` from the six equations `a` (6 x 9: blocks `A0 A1 A2` of the
/// powers of `x4`), using its shifted structure `Sigma = [A0 A1 A2 0; 0 A0
/// A1 A2]`: Gaussian elimination with row pivoting of `A0`'s three columns,
/// applied to all of `a` (an operation on both block rows at once, of
/// determinant +-1 squared), leaves `[U0 B1 B2 0; 0 C1 C2 0; 0 U0 B1 B2;
/// 0 0 C1 C2]`, whose determinant is `det U0` times that of the 9 x 9
/// `[C1 C2 0; U0 B1 B2; 0 C1 C2]`. About two thirds of the dense 12 x 12
/// elimination's work; checked against it in the tests.
fn shifted_determinant(a: &[[f64; 9]; 6]) -> f64 {
    let mut a = *a;
    let mut determinant = 1.0;
    for k in 0..3 {
        let pivot_row = (k..6)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap_or(k);
        // The same swap in both block rows: its sign counts twice.
        a.swap(pivot_row, k);
        let pivot = a[k][k];
        if pivot == 0.0 {
            return 0.0;
        }
        determinant *= pivot;
        let (above, below) = a.split_at_mut(k + 1);
        let pivot_values = &above[k][k + 1..];
        let inverse = 1.0 / pivot;
        for row in below.iter_mut() {
            let factor = row[k] * inverse;
            for (value, above) in row[k + 1..].iter_mut().zip(pivot_values) {
                *value -= factor * above;
            }
        }
    }
    // Rows 3..6 of `a` hold [0 C1 C2], rows 0..3 [U0 B1 B2] (the
    // elimination left the eliminated entries, zero in `U0`, unwritten).
    let mut m = [[0.0; 9]; 9];
    for i in 0..3 {
        m[i][..6].copy_from_slice(&a[3 + i][3..]);
        m[3 + i][i..].copy_from_slice(&a[i][i..]);
        m[6 + i][3..].copy_from_slice(&a[3 + i][3..]);
    }
    determinant * dense_determinant(&mut m)
}

/// The determinant of an n x n matrix (destroyed): Gaussian elimination
/// with row pivoting.
fn dense_determinant<const N: usize>(a: &mut [[f64; N]; N]) -> f64 {
    let mut determinant = 1.0;
    for k in 0..N {
        let mut pivot_row = k;
        for i in k + 1..N {
            if a[i][k].abs() > a[pivot_row][k].abs() {
                pivot_row = i;
            }
        }
        if pivot_row != k {
            a.swap(pivot_row, k);
            determinant = -determinant;
        }
        let pivot = a[k][k];
        determinant *= pivot;
        if pivot == 0.0 {
            return 0.0;
        }
        let (above, below) = a.split_at_mut(k + 1);
        let pivot_values = &above[k][k + 1..];
        let inverse = 1.0 / pivot;
        for row in below.iter_mut() {
            if row[k] == 0.0 {
                continue;
            }
            let factor = row[k] * inverse;
            for (value, above) in row[k + 1..].iter_mut().zip(pivot_values) {
                *value -= factor * above;
            }
        }
    }
    determinant
}

/// Turns values on the grid `(0, pi/2, pi)` along one index of stride
/// `stride` (of a 3 x 3 (x 3) tensor) into coefficients of
/// `(1, cos, sin)`: `1 = (v0 + v2)/2`, `cos = (v0 - v2)/2`,
/// `sin = v1 - (v0 + v2)/2`.
fn coefficients_along(values: &mut [f64], stride: usize) {
    let size = values.len();
    for start in 0..size {
        if (start / stride) % 3 != 0 {
            continue;
        }
        let (v0, v1, v2) = (
            values[start],
            values[start + stride],
            values[start + 2 * stride],
        );
        let mean = 0.5 * (v0 + v2);
        values[start] = mean;
        values[start + stride] = 0.5 * (v0 - v2);
        values[start + 2 * stride] = v1 - mean;
    }
}

/// Coefficients over `m4 (x) m5` (index `3 i4 + i5`) as coefficients of
/// `x4^a x5^b` (index `3 a + b`) after multiplying by `(1+x4^2)(1+x5^2)`.
fn half_angle_form(coefficients: &[f64]) -> [f64; 9] {
    let mut out = [0.0; 9];
    for i4 in 0..3 {
        for i5 in 0..3 {
            let value = coefficients[3 * i4 + i5];
            for a in 0..3 {
                for b in 0..3 {
                    out[3 * a + b] += value * HALF_ANGLE[i4][a] * HALF_ANGLE[i5][b];
                }
            }
        }
    }
    out
}

/// Each of the six equations scaled to a unit coefficient vector (the
/// same solutions; a determinant of order 1).
fn normalize(equations: &mut [[[f64; 9]; 3]; 6]) {
    for equation in equations.iter_mut() {
        let norm = equation.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 0.0 {
            equation.iter_mut().flatten().for_each(|x| *x /= norm);
        }
    }
}

/// `m3 (x) m4 (x) m5` (index `9 i3 + 3 i4 + i5`).
fn tensor3(q3: f64, q4: f64, q5: f64) -> [f64; 27] {
    let m = |q: f64| {
        let (s, c) = sin_cos(q);
        [1.0, c, s]
    };
    let (m3, m4, m5) = (m(q3), m(q4), m(q5));
    let mut out = [0.0; 27];
    for a in 0..3 {
        for b in 0..3 {
            for d in 0..3 {
                out[9 * a + 3 * b + d] = m3[a] * m4[b] * m5[d];
            }
        }
    }
    out
}

/// Householder QR of the first 8 columns of `m`, applied to all 36: after
/// it, `m = Y' m` with `Y' m[.., 0..8]` upper triangular.
fn householder(m: &mut [[f64; 36]; FUNCTIONS]) {
    for k in 0..8 {
        let norm = (k..FUNCTIONS)
            .map(|i| m[i][k] * m[i][k])
            .sum::<f64>()
            .sqrt();
        if norm == 0.0 {
            continue;
        }
        let alpha = if m[k][k] > 0.0 { -norm } else { norm };
        let mut v = [0.0; FUNCTIONS];
        for i in k..FUNCTIONS {
            v[i] = m[i][k];
        }
        v[k] -= alpha;
        let vv: f64 = v[k..].iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        // m -= v (2 v'm / v'v), row by row (the rows are contiguous).
        let mut dots = [0.0; 36];
        for (row, vi) in m[k..].iter().zip(&v[k..]) {
            for (dot, value) in dots[k..].iter_mut().zip(&row[k..]) {
                *dot += vi * value;
            }
        }
        let scale = 2.0 / vv;
        for (row, vi) in m[k..].iter_mut().zip(&v[k..]) {
            let factor = scale * vi;
            for (value, dot) in row[k..].iter_mut().zip(&dots[k..]) {
                *value -= factor * dot;
            }
        }
    }
}

/// The null space of a (nearly) singular 12 x 12 matrix: Gaussian
/// elimination with full pivoting over 11 pivots.
struct NullSpace {
    /// The upper triangle (columns permuted).
    upper: Square,
    /// `columns[j]`: the original column at position `j`.
    columns: [usize; 12],
}

impl NullSpace {
    fn of(matrix: &Square) -> NullSpace {
        let mut upper = *matrix;
        let mut columns = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];
        for k in 0..11 {
            let (mut row, mut column, mut largest) = (k, k, 0.0);
            for (i, values) in upper[k..].iter().enumerate() {
                for (j, value) in values[k..].iter().enumerate() {
                    if value.abs() > largest {
                        (row, column, largest) = (k + i, k + j, value.abs());
                    }
                }
            }
            upper.swap(row, k);
            for values in upper.iter_mut() {
                values.swap(column, k);
            }
            columns.swap(column, k);
            let pivot = upper[k][k];
            if pivot == 0.0 {
                continue;
            }
            let pivot_row = upper[k];
            for row in upper[k + 1..].iter_mut() {
                let factor = row[k] / pivot;
                for (value, above) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                    *value -= factor * above;
                }
            }
        }
        NullSpace { upper, columns }
    }

    /// Whether the eleventh pivot is below [`DOUBLE_NULL`] of the first:
    /// the null space is (nearly) two-dimensional.
    fn is_double(&self) -> bool {
        self.upper[10][10].abs() <= DOUBLE_NULL * self.upper[0][0].abs()
    }

    /// The null vector: the last pivoted unknown 1.
    fn vector(&self) -> [f64; 12] {
        let mut y = [0.0; 12];
        y[11] = 1.0;
        self.completed(y, 11)
    }

    /// A basis of the two-dimensional null space: the last two pivoted
    /// unknowns (1, 0) and (0, 1).
    fn pair(&self) -> [[f64; 12]; 2] {
        let mut first = [0.0; 12];
        first[10] = 1.0;
        let mut second = [0.0; 12];
        second[11] = 1.0;
        [self.completed(first, 10), self.completed(second, 10)]
    }

    /// `y` (pivoted order) with its first `solved` unknowns back-substituted
    /// from the rest, in the original order.
    fn completed(&self, mut y: [f64; 12], solved: usize) -> [f64; 12] {
        let u = &self.upper;
        for i in (0..solved).rev() {
            let known: f64 = (i + 1..12).map(|j| u[i][j] * y[j]).sum();
            y[i] = -known / u[i][i];
        }
        let mut v = [0.0; 12];
        for (j, value) in y.iter().enumerate() {
            v[self.columns[j]] = *value;
        }
        v
    }
}

/// The monomial vectors `(x4^a x5^b)` in a two-dimensional null space
/// `basis` (two solutions sharing joint 3): `v = N c` with `v[3 (a + 1) + b]
/// = x4 v[3 a + b]`, a 2 x 2 eigenproblem `(A'A)^-1 A'B c = x4 c` over the
/// shifted rows (least squares); `None` for a complex pair.
fn monomials_in(basis: &[[f64; 12]; 2]) -> Option<[[f64; 12]; 2]> {
    let (mut gram, mut cross) = ([[0.0; 2]; 2], [[0.0; 2]; 2]);
    for i in 0..9 {
        for r in 0..2 {
            for c in 0..2 {
                gram[r][c] += basis[r][i] * basis[c][i];
                cross[r][c] += basis[r][i] * basis[c][i + 3];
            }
        }
    }
    let det = gram[0][0] * gram[1][1] - gram[0][1] * gram[1][0];
    if det == 0.0 {
        return None;
    }
    // M = gram^-1 cross.
    let inverse = [
        [gram[1][1] / det, -gram[0][1] / det],
        [-gram[1][0] / det, gram[0][0] / det],
    ];
    let mut m = [[0.0; 2]; 2];
    for r in 0..2 {
        for c in 0..2 {
            m[r][c] = inverse[r][0] * cross[0][c] + inverse[r][1] * cross[1][c];
        }
    }
    let half_trace = 0.5 * (m[0][0] + m[1][1]);
    let discriminant = half_trace * half_trace - (m[0][0] * m[1][1] - m[0][1] * m[1][0]);
    if discriminant < 0.0 {
        return None;
    }
    let eigenvector = |lambda: f64| {
        if m[0][1].abs() > m[1][0].abs() {
            [m[0][1], lambda - m[0][0]]
        } else {
            [lambda - m[1][1], m[1][0]]
        }
    };
    let root = discriminant.sqrt();
    Some([half_trace + root, half_trace - root].map(|lambda| {
        let c = eigenvector(lambda);
        std::array::from_fn(|i| basis[0][i] * c[0] + basis[1][i] * c[1])
    }))
}

/// `a0 + sum_k (a_k cos k t + b_k sin k t)`, `k = 1..8`.
struct Trigonometric {
    cosines: [f64; HARMONICS + 1],
    sines: [f64; HARMONICS + 1],
}

impl Trigonometric {
    /// The polynomial through `samples` at `t_j = 2 pi j / 17` (a discrete
    /// Fourier transform; `table[j][k] = (cos, sin)(k t_j)`).
    fn of_samples(
        samples: &[f64; DET_SAMPLES],
        table: &[[(f64, f64); HARMONICS + 1]; DET_SAMPLES],
    ) -> Trigonometric {
        let mut polynomial = Trigonometric {
            cosines: [0.0; HARMONICS + 1],
            sines: [0.0; HARMONICS + 1],
        };
        let n = DET_SAMPLES as f64;
        for (sample, row) in samples.iter().zip(table) {
            for (k, (c, s)) in row.iter().enumerate() {
                polynomial.cosines[k] += sample * c;
                polynomial.sines[k] += sample * s;
            }
        }
        polynomial.cosines[0] /= n;
        polynomial.sines[0] = 0.0;
        for k in 1..=HARMONICS {
            polynomial.cosines[k] *= 2.0 / n;
            polynomial.sines[k] *= 2.0 / n;
        }
        polynomial
    }

    /// Value and first two derivatives at `t`.
    fn at(&self, t: f64) -> [f64; 3] {
        let (s1, c1) = sin_cos(t);
        let (mut c, mut s) = (1.0, 0.0);
        let mut out = [self.cosines[0], 0.0, 0.0];
        for k in 1..=HARMONICS {
            (c, s) = (c * c1 - s * s1, s * c1 + c * s1);
            let (a, b, kf) = (self.cosines[k], self.sines[k], k as f64);
            out[0] += a * c + b * s;
            out[1] += kf * (b * c - a * s);
            out[2] -= kf * kf * (a * c + b * s);
        }
        out
    }

    /// Value and derivative at sample `j` of `ROOT_SAMPLES` per turn.
    fn at_sample(&self, table: &[(f64, f64); ROOT_SAMPLES], j: usize) -> [f64; 2] {
        let mut out = [self.cosines[0], 0.0];
        for k in 1..=HARMONICS {
            let (c, s) = table[(k * j) % ROOT_SAMPLES];
            let (a, b, kf) = (self.cosines[k], self.sines[k], k as f64);
            out[0] += a * c + b * s;
            out[1] += kf * (b * c - a * s);
        }
        out
    }

    /// The real roots in `[0, 2 pi)` into `roots` (see the module docs);
    /// how many.
    ///
    /// Where two neighbouring samples are both below [`QUIET`] of the
    /// largest, the interpolation's rounding (relative to the largest
    /// sample) may hide or invent sign changes: there `determinant` (the
    /// function interpolated, evaluated directly: accurate relative to its
    /// own size) is scanned instead ([`scan_directly`]).
    fn roots(
        &self,
        table: &[(f64, f64); ROOT_SAMPLES],
        determinant: &dyn Fn(f64) -> f64,
        roots: &mut [f64],
    ) -> usize {
        let mut samples = [[0.0; 2]; ROOT_SAMPLES];
        for (j, sample) in samples.iter_mut().enumerate() {
            *sample = self.at_sample(table, j);
        }
        let largest = samples.iter().map(|s| s[0].abs()).fold(0.0, f64::max);
        if largest == 0.0 || !largest.is_finite() {
            return 0;
        }
        // The fourth derivative's bound bounds the cubic Hermite
        // interpolants' errors in `isolate`; the second's, the cheap test.
        let fourth = derivative_bound(&self.cosines, &self.sines, 4);
        let second = derivative_bound(&self.cosines, &self.sines, 2);
        let mut found = Found {
            roots,
            count: 0,
            fourth,
            second,
            noise: ROUNDING * largest,
        };
        let step = TAU / ROOT_SAMPLES as f64;
        for j in 0..ROOT_SAMPLES {
            let start = Knot {
                t: step * j as f64,
                value: samples[j][0],
                slope: samples[j][1],
            };
            if start.value == 0.0 {
                found.push(start.t);
                continue;
            }
            let [value, slope] = samples[(j + 1) % ROOT_SAMPLES];
            let end = Knot {
                t: step * (j + 1) as f64,
                value,
                slope,
            };
            if start.value.abs().max(end.value.abs()) < QUIET * largest {
                scan_directly(determinant, (start.t, end.t), QUIET_REFINEMENTS, &mut found);
            } else {
                self.isolate(&start, &end, &mut found);
            }
        }
        found.count
    }

    /// The roots in `(start.t, end.t)` (values and slopes known at both
    /// ends): none when the cubic Hermite interpolant stays farther from
    /// zero than its error bound (the fourth derivative's bound times
    /// `h^4 / 384`); one, refined, when the ends differ in sign and the
    /// interpolant's slope stays away from zero by more than its error bound
    /// (times `h^3 / 72`); otherwise the interval is halved, down to
    /// [`SMALLEST_INTERVAL`], where a sign change gives one root and an
    /// interpolant reaching the bound a double-root candidate.
    fn isolate(&self, start: &Knot, end: &Knot, found: &mut Found) {
        let h = end.t - start.t;
        // Cheap first: within h/2 of an end the polynomial moves at most
        // |slope| h/2 + max|p''| h^2/8; farther from zero than that (and
        // than TANGENT of itself) at both ends of one sign, no root here.
        let reach = |knot: &Knot| knot.slope.abs() * h / 2.0 + found.second * h * h / 8.0;
        if start.value * end.value > 0.0
            && start.value.abs() - reach(start) > TANGENT * start.value.abs()
            && end.value.abs() - reach(end) > TANGENT * end.value.abs()
        {
            return;
        }
        let cubic = Hermite::new(start, end);
        let (low, high) = cubic.value_range();
        let (value_error, slope_error) = hermite_error_bounds(found.fourth, h);
        if low > value_error || high < -value_error {
            // No root, but one of a pair made complex by rounding may be
            // near: the interpolant's closest approach to zero (`low` or
            // `-high`), if within TANGENT of the ends or within the
            // rounding of the samples.
            let ends = start.value.abs().max(end.value.abs());
            let threshold = (TANGENT * ends).max(found.noise);
            if low.max(-high) > threshold {
                return;
            }
            let (s, value) = cubic.nearest_zero();
            if s > 0.0 && s < 1.0 && value.abs() <= threshold {
                let [value, _, curvature] = self.at(start.t + s * h);
                found.push_double(start.t + s * h, value.abs().max(found.noise), curvature);
            }
            return;
        }
        let sign_change = start.value * end.value < 0.0;
        let (slope_low, slope_high) = cubic.slope_range();
        if sign_change && (slope_low > slope_error || slope_high < -slope_error) {
            found.push(self.bracketed(start.t, end.t));
            return;
        }
        if h < SMALLEST_INTERVAL {
            if sign_change {
                found.push(self.bracketed(start.t, end.t));
            } else {
                found.push(0.5 * (start.t + end.t));
            }
            return;
        }
        let t = 0.5 * (start.t + end.t);
        let [value, slope, _] = self.at(t);
        if value == 0.0 {
            found.push(t);
        }
        let middle = Knot { t, value, slope };
        self.isolate(start, &middle, found);
        self.isolate(&middle, end, found);
    }

    /// The zero in `[t0, t1]`, where the value changes sign: Newton kept
    /// inside the bracket, bisection when a step leaves it; until a step is
    /// below 1e-15 rad or a Newton step below 1e-9 rad no longer shrinks
    /// (the rounding of the samples reached).
    fn bracketed(&self, mut t0: f64, mut t1: f64) -> f64 {
        let sign0 = self.at(t0)[0].signum();
        let mut t = 0.5 * (t0 + t1);
        let mut last_newton = f64::INFINITY;
        for _ in 0..60 {
            let [value, slope, _] = self.at(t);
            if value == 0.0 {
                return t;
            }
            if value.signum() == sign0 {
                t0 = t;
            } else {
                t1 = t;
            }
            let newton = t - value / slope;
            // A root on an end of the bracket (an end of the isolation's
            // halving can fall on it within the rounding) is reached by
            // Newton: only a step beyond an end is replaced by bisection.
            let (next, step) = if newton >= t0 && newton <= t1 {
                let step = (newton - t).abs();
                if step < 1e-9 && step >= last_newton {
                    return t;
                }
                last_newton = step;
                (newton, step)
            } else {
                let middle = 0.5 * (t0 + t1);
                (middle, (middle - t).abs())
            };
            if step < 1e-15 || t1 - t0 < 1e-15 {
                return next;
            }
            t = next;
        }
        t
    }
}

/// The roots of `f` in `[t0, t1)` from its values at [`QUIET_STEPS`] + 1
/// evenly spaced points: a sign change refined by [`regula_falsi`]; where
/// `|f|` dips at a point between two of one sign (a pair of roots, or a
/// double root, closer than a step may hide there), the two steps around it
/// scanned again the same way `refinements` times (a quarter of the step
/// each time), then by [`dip`].
fn scan_directly(
    f: &dyn Fn(f64) -> f64,
    (t0, t1): (f64, f64),
    refinements: usize,
    found: &mut Found,
) {
    let step = (t1 - t0) / QUIET_STEPS as f64;
    let points: [(f64, f64); QUIET_STEPS + 1] = std::array::from_fn(|i| {
        let t = t0 + step * i as f64;
        (t, f(t))
    });
    let mut i = 0;
    while i < QUIET_STEPS {
        let ((a, fa), (b, fb)) = (points[i], points[i + 1]);
        let dips = i + 2 <= QUIET_STEPS && {
            let fc = points[i + 2].1;
            fa * fb > 0.0 && fb * fc > 0.0 && fb.abs() < fa.abs() && fb.abs() <= fc.abs()
        };
        if dips {
            let window = (a, points[i + 2].0);
            if refinements > 0 {
                scan_directly(f, window, refinements - 1, found);
            } else {
                dip(f, points[i], points[i + 1], points[i + 2], found);
            }
            i += 2;
            continue;
        }
        if fa == 0.0 {
            found.push(a);
        } else if fa * fb < 0.0 {
            found.push(regula_falsi(f, (a, fa), (b, fb)));
        }
        i += 1;
    }
}

/// Where `|f|` dips at `middle` between `left` and `right` (same signs):
/// the bottom by successive parabolic interpolation (4 steps); two roots
/// if `f` changes sign there, one double-root candidate if it comes within
/// [`TANGENT`] of the sides' values of zero.
fn dip(
    f: &dyn Fn(f64) -> f64,
    left: (f64, f64),
    middle: (f64, f64),
    right: (f64, f64),
    found: &mut Found,
) {
    let (mut a, mut m, mut b) = (left, middle, right);
    for _ in 0..4 {
        // The vertex of the parabola through the three points.
        let (p, q) = ((m.0 - a.0) * (m.1 - b.1), (m.0 - b.0) * (m.1 - a.1));
        let denominator = 2.0 * (p - q);
        if denominator == 0.0 {
            break;
        }
        let t = m.0 - ((m.0 - a.0) * p - (m.0 - b.0) * q) / denominator;
        if !(t > a.0 && t < b.0) {
            break;
        }
        let bottom = (t, f(t));
        if bottom.1 * m.1 <= 0.0 {
            found.push(regula_falsi(f, a, bottom));
            found.push(regula_falsi(f, bottom, b));
            return;
        }
        if bottom.1.abs() >= m.1.abs() {
            break;
        }
        (a, b) = if t < m.0 { (a, m) } else { (m, b) };
        m = bottom;
    }
    if m.1.abs() <= TANGENT * left.1.abs().min(right.1.abs()) {
        // The parabola's curvature: twice the second divided difference.
        let slope = |(t0, f0): (f64, f64), (t1, f1): (f64, f64)| (f1 - f0) / (t1 - t0);
        let curvature = 2.0 * (slope(m, b) - slope(a, m)) / (b.0 - a.0);
        found.push_double(m.0, m.1.abs(), curvature);
    }
}

/// The zero of `f` between `a` and `b` where it changes sign: the
/// Illinois regula falsi ([`illinois`]) to 1e-15 rad, the
/// end where `|f|` is smaller.
fn regula_falsi(f: &dyn Fn(f64) -> f64, (a, fa): (f64, f64), (b, fb): (f64, f64)) -> f64 {
    let ends = illinois((a, fa, ()), (b, fb, ()), 1e-15, |t, _| Some((f(t), ())));
    match ends {
        Some(((ta, fa, ()), (tb, fb, ()))) => {
            if fa.abs() <= fb.abs() {
                ta
            } else {
                tb
            }
        }
        // (Never: `f` is defined everywhere.)
        None => 0.5 * (a + b),
    }
}

/// The real roots in `[0, 2 pi)` of `a0 + sum_k (a_k cos k t + b_k sin k t)`
/// (`k = 1..8`, `a = cosines`, `b = sines`; `sines[0]` unused) by the
/// certified isolation of the module docs (**Roots**), with `function` (the
/// same polynomial, evaluated directly) scanned where the samples are
/// quiet; written into `roots` (at most its length), how many. (The
/// isolation's entry point for its tests; `Elimination::solve` keeps its
/// table.)
#[cfg(test)]
pub(crate) fn trigonometric_roots(
    cosines: [f64; HARMONICS + 1],
    sines: [f64; HARMONICS + 1],
    function: &dyn Fn(f64) -> f64,
    roots: &mut [f64],
) -> usize {
    let mut table = [(1.0, 0.0); ROOT_SAMPLES];
    for (j, entry) in table.iter_mut().enumerate() {
        let (s, c) = sin_cos(TAU * j as f64 / ROOT_SAMPLES as f64);
        *entry = (c, s);
    }
    let mut sines = sines;
    sines[0] = 0.0;
    Trigonometric { cosines, sines }.roots(&table, function, roots)
}

/// A bound on the `order`-th derivative of `a0 + sum_k (a_k cos k t + b_k
/// sin k t)` over every `t`: `sum_k k^order (|a_k| + |b_k|)` (per rad^order).
pub(crate) fn derivative_bound(cosines: &[f64], sines: &[f64], order: i32) -> f64 {
    (1..cosines.len())
        .map(|k| (k as f64).powi(order) * (cosines[k].abs() + sines[k].abs()))
        .sum()
}

/// The errors of cubic Hermite interpolation (values and slopes at both
/// ends) over an interval of `h` rad of a function whose fourth derivative
/// is at most `fourth` in magnitude: `(fourth h^4 / 384, fourth h^3 / 72)`,
/// on the values and on the slope (per rad).
pub(crate) fn hermite_error_bounds(fourth: f64, h: f64) -> (f64, f64) {
    (fourth * h.powi(4) / 384.0, fourth * h.powi(3) / 72.0)
}

/// Smallest interval [`Trigonometric::isolate`] halves, rad.
const SMALLEST_INTERVAL: f64 = 1e-9;

/// A point of the polynomial: angle (rad), value, slope.
struct Knot {
    t: f64,
    value: f64,
    slope: f64,
}

/// Roots found so far (the buffer of [`Trigonometric::roots`]) and the
/// bounds on the polynomial's fourth and second derivatives.
struct Found<'a> {
    roots: &'a mut [f64],
    count: usize,
    fourth: f64,
    /// The bound on the polynomial's second derivative.
    second: f64,
    /// [`ROUNDING`] of the largest sample.
    noise: f64,
}

impl Found<'_> {
    fn push(&mut self, t: f64) {
        if self.count < self.roots.len() {
            self.roots[self.count] = t;
            self.count += 1;
        }
    }

    /// A double root at `t` where the function, of curvature `curvature`,
    /// comes within `gap` of zero without crossing (two real roots made a
    /// complex pair by rounding, or nearly meeting): pushed as the two
    /// roots the parabola would have at that depth, `t -+ sqrt(2 gap /
    /// |curvature|)`, each then polished apart on the chain (from `t`
    /// itself, where the two solutions' Jacobian is singular, Gauss-Newton
    /// would not separate them).
    fn push_double(&mut self, t: f64, gap: f64, curvature: f64) {
        let half_gap = (2.0 * gap / curvature.abs()).sqrt();
        if half_gap.is_finite() && half_gap < 1e-2 {
            self.push(t - half_gap);
            self.push(t + half_gap);
        } else {
            self.push(t);
        }
    }
}

/// The cubic Hermite interpolant between two knots, in `s in [0, 1]`:
/// `H(s) = c0 + c1 s + c2 s^2 + c3 s^3`.
struct Hermite {
    h: f64,
    coefficients: [f64; 4],
}

impl Hermite {
    fn new(start: &Knot, end: &Knot) -> Hermite {
        let h = end.t - start.t;
        let (v0, v1, d0, d1) = (start.value, end.value, start.slope * h, end.slope * h);
        Hermite {
            h,
            coefficients: [
                v0,
                d0,
                3.0 * (v1 - v0) - 2.0 * d0 - d1,
                2.0 * (v0 - v1) + d0 + d1,
            ],
        }
    }

    fn value(&self, s: f64) -> f64 {
        let [a, b, c, d] = self.coefficients;
        a + s * (b + s * (c + s * d))
    }

    /// `dH/dt` at `s`.
    fn slope(&self, s: f64) -> f64 {
        let [_, b, c, d] = self.coefficients;
        (b + s * (2.0 * c + 3.0 * s * d)) / self.h
    }

    /// Smallest and largest of `f` over `s = 0`, `s = 1` and `inside`
    /// (those in `(0, 1)`).
    fn range(f: impl Fn(f64) -> f64, inside: [Option<f64>; 2]) -> (f64, f64) {
        let (a, b) = (f(0.0), f(1.0));
        let (mut low, mut high) = (a.min(b), a.max(b));
        for s in inside.into_iter().flatten() {
            if s > 0.0 && s < 1.0 {
                let v = f(s);
                low = low.min(v);
                high = high.max(v);
            }
        }
        (low, high)
    }

    /// Smallest and largest value on `[0, 1]`.
    fn value_range(&self) -> (f64, f64) {
        Hermite::range(|s| self.value(s), self.slope_zeros())
    }

    /// The `s` in `[0, 1]` where `|H|` is smallest (an end or a zero of the
    /// slope), with `H` there.
    fn nearest_zero(&self) -> (f64, f64) {
        let mut best = (0.0, self.value(0.0));
        for s in [Some(1.0)].into_iter().chain(self.slope_zeros()).flatten() {
            let value = self.value(s);
            if (0.0..=1.0).contains(&s) && value.abs() < best.1.abs() {
                best = (s, value);
            }
        }
        best
    }

    /// The zeros of the slope, `3 c3 s^2 + 2 c2 s + c1 = 0` (any `s`).
    /// Written without cancellation: with `c3` small beside `c2` (an
    /// interpolant nearly a parabola, as over a symmetric dip), `(-c2 +-
    /// sqrt(...)) / (3 c3)` would lose the zero near the vertex.
    fn slope_zeros(&self) -> [Option<f64>; 2] {
        let [_, b, c, d] = self.coefficients;
        let discriminant = c * c - 3.0 * d * b;
        if d != 0.0 && discriminant >= 0.0 {
            let q = -(c + c.signum() * discriminant.sqrt());
            if q == 0.0 {
                // c = 0 and b = 0: a double zero at s = 0.
                return [Some(0.0), None];
            }
            [Some(q / (3.0 * d)), Some(b / q)]
        } else if d == 0.0 && c != 0.0 {
            [Some(-b / (2.0 * c)), None]
        } else {
            [None, None]
        }
    }

    /// Smallest and largest `dH/dt` on `[0, 1]` (the ends and the vertex).
    fn slope_range(&self) -> (f64, f64) {
        let [_, _, c, d] = self.coefficients;
        let vertex = (d != 0.0).then(|| -c / (3.0 * d));
        Hermite::range(|s| self.slope(s), [vertex, None])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::analytic::structure::{ArmStructure, Motion};
    use crate::ik::analytic::test_random::{point, unit};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Which consecutive pair (0-based first joint) is made special.
    #[derive(Clone, Copy, Debug)]
    enum Special {
        None,
        Intersecting(usize),
        Parallel(usize),
    }

    fn random_arm(rng: &mut ChaCha8Rng, special: Special) -> ArmStructure {
        let mut points: Vec<_> = (0..6).map(|_| point(rng) * 2.0).collect();
        let mut axes: Vec<_> = (0..6).map(|_| unit(rng)).collect();
        match special {
            Special::None => {}
            Special::Intersecting(i) => points[i + 1] = points[i],
            Special::Parallel(i) => axes[i + 1] = axes[i],
        }
        let home = Pose::new(rotation(&unit(rng), 0.8), point(rng));
        ArmStructure::from_lines(points, axes, vec![Motion::Rotation; 6], home)
    }

    fn random_q(rng: &mut ChaCha8Rng) -> [f64; 6] {
        std::array::from_fn(|_| rng.gen_range(-3.1..3.1))
    }

    /// A random general arm, its chain, elimination and a configuration.
    fn random_case(rng: &mut ChaCha8Rng) -> (ArmStructure, Chain, Elimination, [f64; 6]) {
        let s = random_arm(rng, Special::None);
        let chain = Chain::of(&s).unwrap();
        let elimination = Elimination::new(&chain, Cut::Tip).unwrap();
        (s, chain, elimination, random_q(rng))
    }

    /// Raghavan and Roth's claim the method rests on: the fourteen
    /// functions are linear in `(1, cos, sin)` of each joint, so the fits on
    /// the grid reproduce them at any angles (a wrong function or a wrong
    /// grid inversion fails here).
    #[test]
    fn the_fits_reproduce_both_sides_at_random_angles() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..20 {
            let (s, chain, elimination, q) = random_case(&mut rng);
            let goal = s.forward_kinematics(&q) * chain.home_inverse;
            let right = elimination.fit_right(&goal);
            let (c, h) = (&chain.c, &chain.h);
            let r = |k: usize| rotation(&h[k], q[k]);
            let e = |k: usize, x: &Vector3<f64>| c[k] + r(k) * (x - c[k]);
            let point = e(2, &e(3, &e(4, &c[5])));
            let direction = r(2) * r(3) * r(4) * h[5];
            let exact = elimination.functions(&point, &direction);
            let m345 = tensor3(q[2], q[3], q[4]);
            // m1 (x) m2 is the first block of (1, 1, 0) (x) m1 (x) m2.
            let m12 = tensor3(0.0, q[0], q[1]);
            for (n, value) in exact.iter().enumerate() {
                let left: f64 = elimination.left[n]
                    .iter()
                    .zip(&m345)
                    .map(|(a, b)| a * b)
                    .sum();
                let right: f64 = right[n].iter().zip(&m12[..9]).map(|(a, b)| a * b).sum();
                assert!((left - value).abs() < 1e-12, "left {n}: {left} vs {value}");
                assert!(
                    (right - value).abs() < 1e-12,
                    "right {n}: {right} vs {value}"
                );
            }
        }
    }

    /// `det Sigma(q3)` vanishes at the generating configuration's `q3`, and
    /// its harmonics above 8 vanish (Manocha and Canny's factor), so 17
    /// samples give it exactly: checked with 25.
    #[test]
    fn the_determinant_is_of_degree_8_and_vanishes_at_the_solution() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        for _ in 0..20 {
            let (s, chain, elimination, q) = random_case(&mut rng);
            let system = elimination.system(&(s.forward_kinematics(&q) * chain.home_inverse));
            let det = |t: f64| system.determinant(t);
            let samples: Vec<f64> = (0..25).map(|j| det(TAU * j as f64 / 25.0)).collect();
            let largest = samples.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for k in 0..=12 {
                let (mut a, mut b) = (0.0, 0.0);
                for (j, v) in samples.iter().enumerate() {
                    let (s, c) = sin_cos(TAU * (j * k) as f64 / 25.0);
                    a += v * c;
                    b += v * s;
                }
                let size = a.hypot(b) / 25.0;
                if k > HARMONICS {
                    assert!(size < 1e-12 * largest, "harmonic {k}: {size} of {largest}");
                }
            }
            assert!(
                det(q[2]).abs() < 1e-10 * largest,
                "{} of {largest}",
                det(q[2])
            );
        }
    }

    /// The shifted-structure determinant against the dense 12 x 12
    /// elimination of the same `Sigma`, on random equations (and on equations
    /// whose first block is singular).
    #[test]
    fn the_shifted_determinant_agrees_with_the_dense_one() {
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        for trial in 0..200 {
            let mut a: [[f64; 9]; 6] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
            if trial % 10 == 0 {
                // A0's third column a multiple of its first.
                for row in a.iter_mut() {
                    row[2] = 0.5 * row[0];
                }
            }
            let mut sigma = [[0.0; 12]; 12];
            for (k, row) in a.iter().enumerate() {
                sigma[k][..9].copy_from_slice(row);
                sigma[6 + k][3..].copy_from_slice(row);
            }
            let dense = dense_determinant(&mut sigma);
            let shifted = shifted_determinant(&a);
            assert!(
                (dense - shifted).abs() <= 1e-12 * dense.abs().max(1e-3),
                "trial {trial}: {dense} vs {shifted}"
            );
        }
    }

    /// The roots of the polynomial: the trigonometric polynomial with
    /// roots at chosen angles (a product of `sin((t - r)/2)` pairs) gives
    /// them all back, including two roots 1e-4 rad apart.
    #[test]
    fn the_polynomial_roots_are_found() {
        let table = Elimination::new(
            &Chain::of(&random_arm(
                &mut ChaCha8Rng::seed_from_u64(5),
                Special::None,
            ))
            .unwrap(),
            Cut::Tip,
        )
        .unwrap()
        .root_table;
        let chosen = [0.3, 0.3001, 1.7, 2.9, 4.0, 4.4, 5.5, 6.1];
        // prod 2 sin((t - r)/2) over an even count is a trigonometric
        // polynomial of degree count/2; sampled and read by the DFT.
        let value = |t: f64| {
            chosen
                .iter()
                .map(|r| 2.0 * ((t - r) / 2.0).sin())
                .product::<f64>()
        };
        let samples = std::array::from_fn(|j| value(TAU * j as f64 / DET_SAMPLES as f64));
        let polynomial = Trigonometric::of_samples(&samples, &harmonic_table());
        let mut roots = [0.0; 20];
        let count = polynomial.roots(&table, &value, &mut roots);
        assert_eq!(count, chosen.len(), "{:?}", &roots[..count]);
        // Rounding of the interpolation (a few epsilon of the largest
        // sample) moves a root by that over the slope there: 1e-15 rad for
        // a simple root, 1e-11 for each of the pair 1e-4 apart.
        let largest = samples.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (found, expected) in roots[..count].iter().zip(&chosen) {
            let slope = chosen
                .iter()
                .filter(|r| *r != expected)
                .map(|r| 2.0 * ((expected - r) / 2.0).sin())
                .product::<f64>();
            // (At least 1e-14: the refinement stops at steps of 1e-15 rad.)
            let tolerance = (8.0 * f64::EPSILON * largest / slope.abs()).max(1e-14);
            assert!(
                (found - expected).abs() < tolerance,
                "{found} vs {expected}"
            );
        }
    }

    /// Every layout of one special pair, forwards or (pairs at 1-2) on the
    /// reversed chain, and the general arm: the generating configuration is
    /// among the solutions, each of which reproduces the pose.
    #[test]
    fn random_arms_of_every_pair_layout_are_solved() {
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        let mut layouts = vec![Special::None];
        for i in 0..5 {
            layouts.push(Special::Intersecting(i));
            layouts.push(Special::Parallel(i));
        }
        for special in layouts {
            for _ in 0..4 {
                let s = random_arm(&mut rng, special);
                let (s, reversed) = match Elimination::new(&Chain::of(&s).unwrap(), Cut::Tip) {
                    Some(_) => (s, false),
                    None => (s.reversed(), true),
                };
                let chain = Chain::of(&s).unwrap();
                let elimination = Elimination::new(&chain, Cut::Tip)
                    .unwrap_or_else(|| panic!("{special:?}: neither direction applies"));
                if matches!(special, Special::None) {
                    assert!(!reversed, "the general arm needs no reversal");
                }
                for _ in 0..10 {
                    let q = random_q(&mut rng);
                    let target = s.forward_kinematics(&q);
                    let mut found = Candidates::new();
                    elimination.solve(&target, &mut found);
                    for candidate in found.as_slice().iter().filter(|c| c.exact) {
                        let pose = s.forward_kinematics(&candidate.q[..6]);
                        assert!((pose.translation - target.translation).norm() < 1e-10);
                        assert!((pose.rotation - target.rotation).norm() < 1e-10);
                    }
                    let recovered = found.as_slice().iter().any(|c| {
                        c.exact
                            && c.q
                                .iter()
                                .zip(&q)
                                .all(|(a, b)| wrap_angle(a - b).abs() < 1e-6)
                    });
                    assert!(
                        recovered,
                        "{special:?} reversed {reversed}: {q:?} not found"
                    );
                }
            }
        }
    }

    /// A spherical wrist makes `det Sigma` vanish identically, in both
    /// directions: set-up says so rather than returning wrong roots.
    #[test]
    fn a_spherical_wrist_is_refused() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut s = random_arm(&mut rng, Special::None);
        s.points[4] = s.points[3];
        s.points[5] = s.points[3];
        assert!(Elimination::new(&Chain::of(&s).unwrap(), Cut::Tip).is_none());
        assert!(Elimination::new(&Chain::of(&s.reversed()).unwrap(), Cut::Tip).is_none());
    }
}
