//! Every solution of a 6R arm by algebraic elimination: Raghavan and Roth's
//! fourteen equations (1993) in Manocha and Canny's matrix form (1994),
//! derived here for the product-of-exponentials chain of [`super::structure`]
//! (the papers write Denavit-Hartenberg frames). One method for every 6R
//! arm the closed forms do not take: a general arm, or one intersecting or
//! one parallel pair of consecutive axes anywhere. No sampling of the pose
//! equations: the solutions' third joint
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
//! side of `G`, joint 5 eliminated; special pairs at both ends), and it
//! accepts a chain only when two of three probe poses (forward kinematics
//! of fixed generic configurations) give back their configurations;
//! otherwise the arm has no analytic solver.
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

mod system;
#[cfg(test)]
mod tests;
pub(super) mod trigonometric;

use self::system::{
    coefficients_along, half_angle_form, householder, monomials_in, normalize, tensor3, NullSpace,
    System,
};
use self::trigonometric::{root_table, Trigonometric};
use super::chain::{Candidates, Chain};
use super::polish::{chain_pose, settle_root_within, Settle};
use super::subproblems::{any_normal, rotation, subproblem1};
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
        let mut elimination = Elimination {
            chain: *chain,
            cut,
            home,
            scale,
            left: [[0.0; 27]; FUNCTIONS],
            turned_back,
            det_table: harmonic_table(),
            root_table: root_table(),
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
        let normal = any_normal(&h[e]);
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
