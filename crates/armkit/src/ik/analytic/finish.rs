//! From candidates to solutions: joint order restored, angles wrapped into
//! the limits (every representative, or the nearest; a candidate with none
//! inside is dropped first), duplicates merged, each remaining candidate
//! checked by forward kinematics, sorted exact first, each group by
//! distance to the caller's configuration.

use super::chain::{Candidate, LineForwardKinematics, LineKinematics, MAX_CANDIDATES, MAX_JOINTS};
use super::ranges::{representatives, representatives_bound, Range};
use super::structure::ArmStructure;
use super::{AnalyticOptions, Fit, EXACT_TOLERANCE};
use crate::error::Result;
use crate::ik::pose_error::pose_error;
use crate::kinematics::{forward_kinematics, Data};
#[cfg(test)]
use crate::math::Vector3;
use crate::math::{Matrix3, Pose};
use crate::model::{JointKind, Model};

/// Which 2 pi multiples of a rotation joint's angle are returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Representatives {
    /// Every multiple within the joint's limits (a range over 2 pi gives
    /// two or three); the nearest to the current value for joints without
    /// finite limits.
    Every,
    /// Only the multiple within the limits nearest the current value.
    Nearest,
}

/// How a solution's fit is decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Verification {
    /// By forward kinematics of the returned joint values, independent of
    /// the subproblems: exact when the pose is within [`EXACT_TOLERANCE`]
    /// (1e-10 m and rad) of the target, with both errors reported. The
    /// pose is the product of exponentials of the model's joint lines (read
    /// at set-up from the model's forward kinematics at zero, prepared in
    /// joint-local frames, and compared at set-up with the model's forward
    /// kinematics on 6 configurations, to 1e-12 m per metre of the arm's
    /// length scale and 1e-12 rad); where they disagree, the model's own
    /// forward kinematics. Position error `|p - p_target|` (m); orientation
    /// error the angle of `R R_target'` (rad, from the Frobenius norm of
    /// `R - R_target`, accurate near 0). The default.
    ForwardKinematics,
    /// By the subproblems alone: exact when every subproblem on the way had
    /// an exact solution (to their relative tolerance 1e-9); the errors are
    /// not measured (NaN). About twice as fast; what IK-Geo's timings measure.
    Subproblems,
}

fn fit_of(exact: bool) -> Fit {
    if exact {
        Fit::Exact
    } else {
        Fit::Approximate
    }
}

/// Largest joint-space gap (rad or m, every joint, angles modulo 2 pi)
/// between two candidates merged as duplicates (tangent cases of the
/// subproblems give the same solution twice).
pub(crate) const DUPLICATE_TOLERANCE: f64 = 1e-9;

/// How many configurations the joint lines' forward kinematics is compared
/// on with the model's at set-up (see [`Verification::ForwardKinematics`]).
pub(crate) const LINE_CHECK_CONFIGURATIONS: usize = 6;

/// Largest disagreement (m per metre of the arm's length scale, and rad)
/// between the joint lines' and the model's forward kinematics at set-up
/// for the lines to be used in the check (two orders below
/// [`EXACT_TOLERANCE`]).
pub(crate) const LINE_CHECK_TOLERANCE: f64 = 1e-12;

/// One analytic solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticSolution {
    values: [f64; MAX_JOINTS],
    dof: usize,
    /// Exact (within 1e-10 m and rad by forward kinematics), or the
    /// least-squares answer of a pose out of reach.
    pub fit: Fit,
    /// Position error of `FK(q)` from the target, m (NaN with
    /// [`Verification::Subproblems`]).
    pub position_error: f64,
    /// Orientation error of `FK(q)` from the target, rad (NaN with
    /// [`Verification::Subproblems`]).
    pub orientation_error: f64,
    /// Squared joint-space distance to the configuration given to the solve.
    distance2: f64,
}

impl AnalyticSolution {
    /// Joint positions, rad or m, one per joint.
    pub fn q(&self) -> &[f64] {
        &self.values[..self.dof]
    }
}

/// How [`Verification::ForwardKinematics`] computes a candidate's pose.
/// Built once per solver and read on every solve: the prepared lines are
/// kept inline rather than boxed.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
enum PoseCheck {
    /// The joint lines' product of exponentials, prepared (agrees with the
    /// model's forward kinematics, checked at set-up).
    Lines(LineForwardKinematics),
    /// The model's forward kinematics (the lines disagree with it, or the
    /// model has no lines).
    Model(Data),
}

impl PoseCheck {
    fn of(model: &Model) -> PoseCheck {
        let lines = ArmStructure::of_model(model).ok().and_then(|structure| {
            LineKinematics::new(&structure).filter(|l| lines_agree(model, &structure, l))
        });
        match lines {
            Some(lines) => PoseCheck::Lines(LineForwardKinematics::new(lines)),
            None => PoseCheck::Model(Data::new(model)),
        }
    }

    /// `(position error, orientation error)` of `q`'s pose from `target`.
    fn errors(&mut self, model: &Model, target: &Pose, q: &[f64]) -> Result<(f64, f64)> {
        match self {
            PoseCheck::Lines(lines) => {
                let pose = &lines.pose(q);
                Ok((
                    (pose.translation - target.translation).norm(),
                    rotation_gap(&pose.rotation, &target.rotation),
                ))
            }
            PoseCheck::Model(data) => {
                let pose = forward_kinematics(model, data, q)?;
                let e = pose_error(target, pose);
                Ok((e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm()))
            }
        }
    }

    fn reset(&mut self) {
        if let PoseCheck::Lines(lines) = self {
            lines.reset();
        }
    }
}

/// True when the prepared lines reproduce the model's forward kinematics
/// on [`LINE_CHECK_CONFIGURATIONS`] fixed configurations (angles spread
/// over (-pi, pi], slides over +-0.5 m) to [`LINE_CHECK_TOLERANCE`].
fn lines_agree(model: &Model, structure: &ArmStructure, lines: &LineKinematics) -> bool {
    let dof = model.dof();
    if lines.dof() != dof {
        return false;
    }
    let mut data = Data::new(model);
    let mut check = LineForwardKinematics::new(*lines);
    let mut q = [0.0; MAX_JOINTS];
    for k in 0..LINE_CHECK_CONFIGURATIONS {
        for (j, (value, joint)) in q.iter_mut().zip(model.joints()).enumerate() {
            // A fixed spread of values in [-1, 1), different per joint and configuration.
            let unit = (((k * 7 + j * 5 + 3) % 13) as f64) / 6.5 - 1.0;
            *value = match joint.kind {
                JointKind::Prismatic => 0.5 * unit,
                _ => std::f64::consts::PI * unit + 0.1 * k as f64,
            };
        }
        let Ok(expected) = forward_kinematics(model, &mut data, &q[..dof]) else {
            return false;
        };
        let pose = &check.pose(&q[..dof]);
        let position = (pose.translation - expected.translation).norm();
        let orientation = rotation_gap(&pose.rotation, &expected.rotation);
        if !(position <= LINE_CHECK_TOLERANCE * structure.scale
            && orientation <= LINE_CHECK_TOLERANCE)
        {
            return false;
        }
    }
    true
}

/// The angle (rad, in `[0, pi]`) of the rotation `a b'` taking `b` onto
/// `a`, accurate over the whole range. Below 1 rad from
/// `|a - b|_F = 2 sqrt(2) sin(angle / 2)` (no product; the inverse sine is
/// well conditioned there, and an exact solution's tiny angle keeps every
/// digit); otherwise `atan2` of the skew and symmetric parts of `a b'`
/// (accurate near pi, where the inverse sine is not).
fn rotation_gap(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    let half_sine = (a - b).norm() / (2.0 * std::f64::consts::SQRT_2);
    // sin(1/2): angles below 1 rad.
    if half_sine < 0.479_425_538_604_203 {
        // asin(x) = x + x^3 / 6 + 3 x^5 / 40 + ...: the first two terms are
        // exact to double precision below 1e-4.
        let half_angle = if half_sine < 1e-4 {
            half_sine + half_sine * half_sine * half_sine / 6.0
        } else {
            half_sine.asin()
        };
        return 2.0 * half_angle;
    }
    let m = a * b.transpose();
    let sine = 0.5
        * ((m[(2, 1)] - m[(1, 2)]).powi(2)
            + (m[(0, 2)] - m[(2, 0)]).powi(2)
            + (m[(1, 0)] - m[(0, 1)]).powi(2))
        .sqrt();
    super::subproblems::atan2(sine, 0.5 * (m.trace() - 1.0))
}

/// The finishing stage's workspace, sized once for a model.
#[derive(Clone, Debug)]
pub(crate) struct Finisher {
    check: PoseCheck,
    options: AnalyticOptions,
    ranges: [Range; MAX_JOINTS],
    solutions: Vec<AnalyticSolution>,
    /// `(distance2 bits, index in solutions)` of the current solve, sorted
    /// to reorder `solutions` in place (moving the small keys, not the
    /// solutions, while sorting). The distances are sums of squares (`+0`
    /// or more, or NaN), whose bit patterns order as their values.
    order: Vec<(u64, usize)>,
    /// Distinct candidates of the current solve (model order, angles in (-pi, pi]).
    accepted: [[f64; MAX_JOINTS]; MAX_CANDIDATES],
}

impl Finisher {
    pub(crate) fn new(model: &Model, options: AnalyticOptions) -> Finisher {
        // Room for every representative of every candidate.
        let per_candidate: usize = model
            .joints()
            .iter()
            .map(|j| representatives_bound(j.limits.lower, j.limits.upper))
            .product();
        let capacity = (MAX_CANDIDATES * per_candidate).min(1 << 16);
        let mut ranges = [Range::Nearest; MAX_JOINTS];
        for (j, range) in ranges.iter_mut().enumerate().take(model.dof()) {
            *range = Range::of(model, j, &options);
        }
        Finisher {
            check: PoseCheck::of(model),
            options,
            ranges,
            solutions: Vec::with_capacity(capacity),
            order: Vec::with_capacity(capacity),
            accepted: [[0.0; MAX_JOINTS]; MAX_CANDIDATES],
        }
    }

    /// Checks, wraps, filters and sorts `candidates` (chain order; reversed
    /// when `reverse`, with `fixed = (joint, value)` inserted).
    pub(crate) fn finish(
        &mut self,
        model: &Model,
        candidates: &[Candidate],
        reverse: bool,
        fixed: Option<(usize, f64)>,
        target: &Pose,
        current: &[f64],
    ) -> Result<&[AnalyticSolution]> {
        self.solutions.clear();
        self.check.reset();
        let dof = model.dof();
        let all_ranges = self.ranges;
        let ranges = &all_ranges[..dof];
        let current = &current[..dof];
        let mut count = 0;
        'candidates: for candidate in candidates {
            // Each joint's value wrapped into its range's form (angles into
            // (-pi, pi]) and its first representative within the range: a
            // candidate with none is dropped before anything else.
            let mut q = model_order(candidate, dof, reverse, fixed);
            let mut values = q;
            let mut distance2 = 0.0;
            let mut single = true;
            for j in 0..dof {
                let r = representatives(ranges[j], q[j], current[j]);
                if r.count == 0 {
                    continue 'candidates;
                }
                q[j] = r.wrapped;
                values[j] = r.first;
                single &= r.count == 1;
                distance2 += (r.first - current[j]) * (r.first - current[j]);
            }
            for a in &self.accepted[..count] {
                if same_configuration(ranges, a, &q) {
                    continue 'candidates;
                }
            }
            if count < MAX_CANDIDATES {
                self.accepted[count] = q;
                count += 1;
            }
            let (fit, position_error, orientation_error) = match self.options.verification {
                Verification::ForwardKinematics => {
                    let (position_error, orientation_error) =
                        self.check.errors(model, target, &q[..dof])?;
                    let exact =
                        position_error <= EXACT_TOLERANCE && orientation_error <= EXACT_TOLERANCE;
                    (fit_of(exact), position_error, orientation_error)
                }
                Verification::Subproblems => (fit_of(candidate.exact), f64::NAN, f64::NAN),
            };
            let solution = AnalyticSolution {
                values,
                dof,
                fit,
                position_error,
                orientation_error,
                distance2,
            };
            self.solutions.push(solution);
            if !single {
                self.expand(solution, &q, ranges, current);
            }
        }
        self.sort();
        Ok(&self.solutions)
    }

    /// Pushes the other representative combinations of `solution` (its
    /// first already pushed; `wrapped` its joint values wrapped as the
    /// ranges read them): joint `j`'s are `wrapped[j] + 2 pi (k_j + i)` for
    /// `i` below its count (see [`representatives`]), in odometer order,
    /// joint 1 fastest.
    fn expand(
        &mut self,
        solution: AnalyticSolution,
        wrapped: &[f64; MAX_JOINTS],
        ranges: &[Range],
        current: &[f64],
    ) {
        use std::f64::consts::TAU;
        let dof = current.len();
        let mut first = [0.0; MAX_JOINTS];
        let mut counts = [1usize; MAX_JOINTS];
        for (j, (range, c)) in ranges.iter().zip(current).enumerate() {
            let r = representatives(*range, wrapped[j], *c);
            (first[j], counts[j]) = (r.k, r.count);
        }
        let mut s = solution;
        let mut index = [0usize; MAX_JOINTS];
        loop {
            let mut j = 0;
            loop {
                if j == dof {
                    return;
                }
                index[j] += 1;
                if index[j] < counts[j] {
                    break;
                }
                index[j] = 0;
                j += 1;
            }
            s.distance2 = 0.0;
            for (j, c) in current.iter().enumerate() {
                s.values[j] = wrapped[j] + TAU * (first[j] + index[j] as f64);
                s.distance2 += (s.values[j] - c) * (s.values[j] - c);
            }
            self.solutions.push(s);
        }
    }

    /// Sorts the solutions, exact ones first, each group by distance: the keys are sorted
    /// (unstable: allocates nothing, the key buffer is sized at set-up),
    /// then the solutions are moved once along the permutation's cycles.
    fn sort(&mut self) {
        let n = self.solutions.len();
        if n < 2 {
            return;
        }
        self.order.clear();
        self.order.extend(
            self.solutions
                .iter()
                .enumerate()
                .map(|(i, s)| (sort_key(s), i)),
        );
        // Ties broken by the order found: deterministic (the keys are
        // distinct, so any sort gives this one order).
        sort_keys(&mut self.order);
        // Position p takes the solution at order[p].1; a visited position
        // is marked by usize::MAX.
        const DONE: usize = usize::MAX;
        for start in 0..n {
            let source = self.order[start].1;
            if source == start || source == DONE {
                continue;
            }
            let saved = self.solutions[start];
            let mut p = start;
            loop {
                let source = self.order[p].1;
                self.order[p].1 = DONE;
                if source == start {
                    self.solutions[p] = saved;
                    break;
                }
                self.solutions[p] = self.solutions[source];
                p = source;
            }
        }
    }
}

/// The sort key of `s`: its distance's bits (a sum of squares, `+0` or
/// more, or NaN: the sign bit clear, so the bits order as the values), with
/// the sign bit set for a least-squares solution, so that every exact
/// solution comes before every approximate one (an engineer asks for the
/// nearest answer that reaches the pose, not the nearest miss).
fn sort_key(s: &AnalyticSolution) -> u64 {
    let approximate = u64::from(s.fit != Fit::Exact) << 63;
    s.distance2.to_bits() | approximate
}

/// Sorts distinct keys ascending: by insertion (keys packed into one
/// `u128`, compared branch-free) for the few of one pose's solutions, by
/// the library's unstable sort for many (every representative).
fn sort_keys(keys: &mut [(u64, usize)]) {
    const FEW: usize = 16;
    if keys.len() > FEW {
        keys.sort_unstable();
        return;
    }
    let packed = |(bits, index): (u64, usize)| (u128::from(bits) << 64) | index as u128;
    for i in 1..keys.len() {
        let key = keys[i];
        let value = packed(key);
        let mut j = i;
        while j > 0 && packed(keys[j - 1]) > value {
            keys[j] = keys[j - 1];
            j -= 1;
        }
        keys[j] = key;
    }
}

/// Joint values in model order.
fn model_order(
    candidate: &Candidate,
    dof: usize,
    reverse: bool,
    fixed: Option<(usize, f64)>,
) -> [f64; MAX_JOINTS] {
    if !reverse && fixed.is_none() {
        return candidate.q;
    }
    let solved = if fixed.is_some() { dof - 1 } else { dof };
    let mut chain = [0.0; MAX_JOINTS];
    for (i, slot) in chain.iter_mut().take(solved).enumerate() {
        *slot = if reverse {
            candidate.q[solved - 1 - i]
        } else {
            candidate.q[i]
        };
    }
    let mut q = [0.0; MAX_JOINTS];
    match fixed {
        Some((joint, value)) => {
            let mut source = 0;
            for (i, slot) in q.iter_mut().take(dof).enumerate() {
                if i == joint {
                    *slot = value;
                } else {
                    *slot = chain[source];
                    source += 1;
                }
            }
        }
        None => q = chain,
    }
    q
}

/// True when two configurations (angles in (-pi, pi]) agree to
/// [`DUPLICATE_TOLERANCE`], angles modulo 2 pi. Compared from the last
/// joint: candidates of one solve share their first joints in runs.
#[inline]
fn same_configuration(ranges: &[Range], a: &[f64], b: &[f64]) -> bool {
    use std::f64::consts::TAU;
    let n = ranges.len().min(a.len()).min(b.len());
    for j in (0..n).rev() {
        let gap = (a[j] - b[j]).abs();
        if !(gap <= DUPLICATE_TOLERANCE
            || (ranges[j].is_rotation() && gap >= TAU - DUPLICATE_TOLERANCE))
        {
            return false;
        }
    }
    true
}

/// Sorts solutions exact first, each group by joint-space (Euclidean)
/// distance to `current` (unstable sort: allocates nothing).
pub(crate) fn sort_nearest(solutions: &mut [AnalyticSolution], current: &[f64]) {
    for s in solutions.iter_mut() {
        s.distance2 = s
            .q()
            .iter()
            .zip(current)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>();
    }
    solutions.sort_unstable_by_key(sort_key);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The lines' forward kinematics is used for every built-in arm it can
    /// describe, and reproduces the model's on random configurations; the
    /// others (more than 7 joints, couplings) fall back to the model's.
    #[test]
    fn line_kinematics_match_the_model_on_random_configurations() {
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let mut lines_used = 0;
        for name in crate::robots::names() {
            let model = crate::robots::by_name(name).unwrap();
            let describable = model.dof() <= MAX_JOINTS && model.coupling().is_none();
            let mut check = PoseCheck::of(&model);
            let PoseCheck::Lines(_) = check else {
                assert!(!describable, "{name}: lines not used");
                continue;
            };
            assert!(describable, "{name}");
            lines_used += 1;
            let scale = ArmStructure::of_model(&model).unwrap().scale;
            let mut data = Data::new(&model);
            for _ in 0..300 {
                let q: Vec<f64> = model
                    .joints()
                    .iter()
                    .map(|j| match j.kind {
                        JointKind::Prismatic => rng.gen_range(-1.0..1.0),
                        _ => rng.gen_range(-7.0..7.0),
                    })
                    .collect();
                let expected = *forward_kinematics(&model, &mut data, &q).unwrap();
                let PoseCheck::Lines(lines) = &mut check else {
                    unreachable!()
                };
                let pose = lines.pose(&q);
                let position = (pose.translation - expected.translation).norm();
                let orientation =
                    crate::math::rotation_angle(&(pose.rotation * expected.rotation.transpose()));
                assert!(position <= 1e-13 * scale, "{name}: {position:e} m");
                assert!(orientation <= 1e-13, "{name}: {orientation:e} rad");
            }
        }
        assert!(lines_used >= 5, "{lines_used}");
    }

    /// The set-up comparison rejects lines that do not describe the model.
    #[test]
    fn lines_that_disagree_with_the_model_are_rejected() {
        let model = crate::robots::by_name("puma560").unwrap();
        let mut structure = ArmStructure::of_model(&model).unwrap();
        let good = LineKinematics::new(&structure).unwrap();
        assert!(lines_agree(&model, &structure, &good));
        structure.points[2].x += 1e-9;
        let bad = LineKinematics::new(&structure).unwrap();
        assert!(!lines_agree(&model, &structure, &bad));
    }

    /// The reported errors are those of the model's forward kinematics and
    /// [`pose_error`] on targets off the solutions (orientation errors over
    /// the whole range up to pi).
    #[test]
    fn reported_errors_match_the_model_forward_kinematics() {
        let mut rng = ChaCha8Rng::seed_from_u64(18);
        for name in ["puma560", "ur5", "stanford"] {
            let model = crate::robots::by_name(name).unwrap();
            let mut solver =
                super::super::AnalyticSolver::new(&model, AnalyticOptions::default()).unwrap();
            let mut data = Data::new(&model);
            for (k, (q, target)) in crate::ik::benchmark_targets(&model, 100, 5)
                .unwrap()
                .into_iter()
                .enumerate()
            {
                // Moved and turned by up to 0.3 m and (for the last ones) nearly pi.
                let angle = if k < 90 {
                    0.5 * rng.r#gen::<f64>()
                } else {
                    std::f64::consts::PI - 0.002
                };
                let axis = nalgebra::Unit::new_normalize(Vector3::new(
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                ));
                let turn = nalgebra::Rotation3::from_axis_angle(&axis, angle).into_inner();
                let shift = Vector3::new(rng.r#gen(), rng.r#gen(), rng.r#gen()) * 0.1;
                let moved = Pose::new(turn * target.rotation, target.translation + shift);
                for solution in solver.solve(&moved, &q).unwrap().to_vec() {
                    let pose = forward_kinematics(&model, &mut data, solution.q()).unwrap();
                    let e = pose_error(&moved, pose);
                    let (position, orientation) =
                        (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
                    assert!(
                        (solution.position_error - position).abs() <= 1e-12,
                        "{name}: {} vs {position}",
                        solution.position_error
                    );
                    assert!(
                        (solution.orientation_error - orientation).abs() <= 1e-12,
                        "{name}: {} vs {orientation}",
                        solution.orientation_error
                    );
                }
            }
        }
    }
}
