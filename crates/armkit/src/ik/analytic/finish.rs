//! From candidates to solutions: joint order restored, each candidate
//! checked by the model's forward kinematics, duplicates merged, angles
//! wrapped into the limits (every representative, or the nearest), sorted
//! by distance to the caller's configuration.

use super::chain::{Candidate, MAX_CANDIDATES, MAX_JOINTS};
use super::{AnalyticOptions, Fit, RangeFilter, EXACT_TOLERANCE};
use crate::error::Result;
use crate::ik::pose_error::pose_error;
use crate::kinematics::{forward_kinematics, Data};
use crate::math::Pose;
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
    /// By the model's forward kinematics: exact when within
    /// [`EXACT_TOLERANCE`] (1e-10 m and rad), with both errors reported.
    /// The default.
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
pub const DUPLICATE_TOLERANCE: f64 = 1e-9;

/// Most representatives of one joint angle kept per candidate.
const MAX_REPRESENTATIVES: usize = 8;

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

/// The finishing stage's workspace, sized once for a model.
#[derive(Clone, Debug)]
pub(crate) struct Finisher {
    data: Data,
    options: AnalyticOptions,
    solutions: Vec<AnalyticSolution>,
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
        Finisher {
            data: Data::new(model),
            options,
            solutions: Vec::with_capacity(capacity),
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
        let dof = model.dof();
        let mut accepted = [[0.0; MAX_JOINTS]; MAX_CANDIDATES];
        let mut count = 0;
        for candidate in candidates {
            let q = model_order(candidate, dof, reverse, fixed);
            if accepted[..count]
                .iter()
                .any(|a| same_configuration(model, &a[..dof], &q[..dof]))
            {
                continue;
            }
            if count < MAX_CANDIDATES {
                accepted[count] = q;
                count += 1;
            }
            let (fit, position_error, orientation_error) = match self.options.verification {
                Verification::ForwardKinematics => {
                    let pose = forward_kinematics(model, &mut self.data, &q[..dof])?;
                    let e = pose_error(target, pose);
                    let position_error = e.fixed_rows::<3>(0).norm();
                    let orientation_error = e.fixed_rows::<3>(3).norm();
                    let exact =
                        position_error <= EXACT_TOLERANCE && orientation_error <= EXACT_TOLERANCE;
                    (fit_of(exact), position_error, orientation_error)
                }
                Verification::Subproblems => (fit_of(candidate.exact), f64::NAN, f64::NAN),
            };
            let solution = AnalyticSolution {
                values: q,
                dof,
                fit,
                position_error,
                orientation_error,
                distance2: 0.0,
            };
            self.expand(model, solution, current);
        }
        sort_by_distance(&mut self.solutions);
        Ok(&self.solutions)
    }

    /// Pushes every allowed representative combination of `solution`.
    fn expand(&mut self, model: &Model, solution: AnalyticSolution, current: &[f64]) {
        let dof = solution.dof;
        let mut choices = [[0.0; MAX_REPRESENTATIVES]; MAX_JOINTS];
        let mut counts = [0usize; MAX_JOINTS];
        for j in 0..dof {
            counts[j] =
                self.representatives(model, j, solution.values[j], current[j], &mut choices[j]);
            if counts[j] == 0 {
                return;
            }
        }
        // Odometer over the per-joint choices.
        let mut index = [0usize; MAX_JOINTS];
        loop {
            let mut s = solution;
            s.distance2 = 0.0;
            for j in 0..dof {
                s.values[j] = choices[j][index[j]];
                s.distance2 += (s.values[j] - current[j]) * (s.values[j] - current[j]);
            }
            self.solutions.push(s);
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
        }
    }

    /// The values of joint `j` to return for `value`; how many.
    fn representatives(
        &self,
        model: &Model,
        j: usize,
        value: f64,
        current: f64,
        out: &mut [f64; MAX_REPRESENTATIVES],
    ) -> usize {
        use std::f64::consts::TAU;
        let joint = &model.joints()[j];
        let limits = &joint.limits;
        if joint.kind == JointKind::Prismatic {
            let keep = self.options.limits == RangeFilter::IgnoreLimits || limits.contains(value);
            out[0] = value;
            return usize::from(keep);
        }
        let nearest = value + TAU * ((current - value) / TAU).round();
        let unbounded = limits.lower == f64::NEG_INFINITY && limits.upper == f64::INFINITY;
        if self.options.limits == RangeFilter::IgnoreLimits || unbounded {
            out[0] = nearest;
            return 1;
        }
        if !limits.is_bounded() {
            // Half-bounded range: the nearest multiple, else the one just inside.
            out[0] = if limits.contains(nearest) {
                nearest
            } else if limits.lower.is_finite() {
                value + TAU * ((limits.lower - value) / TAU).ceil()
            } else {
                value + TAU * ((limits.upper - value) / TAU).floor()
            };
            return usize::from(limits.contains(out[0]));
        }
        let first = ((limits.lower - value) / TAU).ceil();
        let last = ((limits.upper - value) / TAU).floor();
        let mut count = 0;
        let mut k = first;
        while k <= last && count < MAX_REPRESENTATIVES {
            out[count] = value + TAU * k;
            count += 1;
            k += 1.0;
        }
        if self.options.representatives == super::Representatives::Nearest && count > 1 {
            let best = out[..count]
                .iter()
                .copied()
                .min_by(|a, b| (a - current).abs().total_cmp(&(b - current).abs()))
                .unwrap_or(out[0]);
            out[0] = best;
            count = 1;
        }
        count
    }
}

/// Joint values in model order.
fn model_order(
    candidate: &Candidate,
    dof: usize,
    reverse: bool,
    fixed: Option<(usize, f64)>,
) -> [f64; MAX_JOINTS] {
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

/// True when two configurations agree to [`DUPLICATE_TOLERANCE`] (angles modulo 2 pi).
fn same_configuration(model: &Model, a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).zip(model.joints()).all(|((x, y), joint)| {
        let gap = if joint.kind.is_rotational() {
            crate::math::wrap_angle(x - y)
        } else {
            x - y
        };
        gap.abs() <= DUPLICATE_TOLERANCE
    })
}

/// Upper bound on the representatives of an angle within `[lower, upper]`.
fn representatives_bound(lower: f64, upper: f64) -> usize {
    if lower.is_finite() && upper.is_finite() {
        let span = ((upper - lower) / std::f64::consts::TAU).floor();
        (span as usize + 1).clamp(1, MAX_REPRESENTATIVES)
    } else {
        1
    }
}

/// Sorts solutions by joint-space (Euclidean) distance to `current`
/// (unstable sort: allocates nothing).
pub(crate) fn sort_nearest(solutions: &mut [AnalyticSolution], current: &[f64]) {
    for s in solutions.iter_mut() {
        s.distance2 = s
            .q()
            .iter()
            .zip(current)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>();
    }
    sort_by_distance(solutions);
}

/// Sorts by the stored distances.
fn sort_by_distance(solutions: &mut [AnalyticSolution]) {
    solutions.sort_unstable_by(|a, b| a.distance2.total_cmp(&b.distance2));
}
