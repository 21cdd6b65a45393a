//! Planning the knots of a singular region the arm cannot follow exactly
//! all at once: a sequential second-order-cone program over the stacked
//! knot vector, solved by Clarabel.
//!
//! # Why the knots must be planned together
//!
//! A line that misses a wrist singularity by `d` (m and rad, along the
//! direction the Jacobian loses there) turns the wrist's tilt vector (`q5`
//! and the direction `q4` gives it) by about pi within a time of about
//! `d / v` (`v` the path's speed in that direction): joints 4 and 6 must
//! flip at a rate growing as `1 / d`. With the joint rates bounded (`eps_dq`
//! per control period) there are two ways through:
//!
//! * stay on the wrist branch and flip late: the error grows with the lag,
//!   many times `d` when the flip takes longer than the passage;
//! * cross `q5 = 0` (switch wrist branch, joints 4 and 6 barely moving): the
//!   tilt passes through zero while the target's passes at `d`, so the error
//!   at the crossing is at least the distance from the target to the singular
//!   poses, about `d` ([`crate::study::AvoidanceStudy`] computes it: the
//!   floor of any branch-switching plan).
//!
//! The greedy plan (each knot the nearest pose within `eps_dq` per period of
//! the last, [`RegionPlan::Greedy`]) sees the flip only when it is already
//! late: it starts turning joints 4 and 6 the wrong way, then crosses and has
//! to turn them back, and errs about `2 d`. [`RegionPlan::Joint`] chooses
//! all the region's knots together.
//!
//! # The joint plan
//!
//! Knots `q_1 .. q_{N-1}` (the entry knot `q_0`, the current state, is
//! fixed; so is the exit knot `q_N`, an exact IK solution where the motion is
//! regular again, unless the region ends at the path's end) minimise
//!
//! ```text
//! max_i |e_i(q_i)|  +  mu / (N e_ref) sum_i |e_i(q_i)|^2
//! subject to  |q_i - q_{i-1}| <= eps_dq (t_i - t_{i-1}) / h   (every joint)
//!             joint limits
//! ```
//!
//! with `e_i` the pose error of knot `i` from its planned pose (position in
//! m and rotation vector in rad, one 6-vector), `e_ref` the greedy plan's
//! largest error and `mu` = 0.1: the largest error is what the study
//! compares with the damped methods, the small sum of squares keeps the
//! other knots near their poses instead of anywhere below the maximum.
//! Each iteration linearises `e_i(q_i + dq_i) ~ e_i - J_i dq_i` (`J` or the
//! generalized `J*`), bounds `|dq| <= Delta` (trust region), writes the
//! maximum as an epigraph variable `s` with one second-order cone
//! `|e_i - J_i dq_i| <= s` per knot, and solves the cone program with
//! Clarabel. A step is kept when the true merit (forward kinematics at the
//! new knots) falls by at least a tenth of the predicted fall; the trust
//! region (0.2 rad at first) grows after a good step and shrinks after a
//! rejected one; at most 8 programs per region. The
//! constraints are linear in the knots, so every iterate is feasible: the
//! rate bound holds throughout. The plan starts from the greedy knots
//! (feasible), and the greedy plan is kept if the joint one does not lower
//! the largest error: the result is never worse than the greedy plan.
//!
//! To keep the program small, a region of more than 48 intervals is planned
//! on every `s`-th knot (the nodes; at most 48 free), the knots between
//! following the nodes linearly in time: a node step within the speed bound
//! over the nodes' time apart keeps every period's step within `eps_dq`.
//! The errors are bounded at the nodes and midway between them; the largest
//! error compared with the greedy plan's is taken over every knot.
//!
//! # What it reaches, and what it does not
//!
//! The program is solved locally, from the greedy knots: it improves the
//! plan within the greedy plan's way through. On space6r's lines missing
//! the singular pose by 1 and 3 mm the greedy plan crosses `q5 = 0` late;
//! the joint plan crosses at the closest approach and errs the floor (the
//! distance to the singular poses) to within a few percent, about half the
//! greedy plan's error. At 10 and 30 mm the greedy plan stays on its branch
//! and lags the flip; the joint plan can spread the lag but not start it
//! earlier than the region's entry (the detection), so it gains less or
//! nothing there. It does not try the other way through (a branch switch
//! where the greedy plan lags), whose error is at least the floor.

use super::plant::Plant;
use crate::error::{Error, Result};
use crate::ik::pose_error;
use crate::math::{DVector, Matrix6xX, Pose, Vector6};

/// How the knots of a singular region are chosen when the arm cannot follow
/// the planned poses exactly (some knot's IK solution would move a joint
/// more than `eps_dq` per control period since the last knot). Regions
/// whose knots are all exact are planned the same way by both.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum RegionPlan {
    /// All knots of the region together (module documentation of
    /// [`super`], "near misses"): the sequential cone program minimising the
    /// largest knot error under the joint-step bound, started from the
    /// greedy knots and never worse than them. Default.
    #[default]
    Joint,
    /// Knot by knot: each knot the nearest pose within `eps_dq` per period
    /// of the last one (Levenberg-Marquardt on the box). Reacts late to a
    /// near miss; kept as the labelled comparison.
    Greedy,
    /// Seed 004's step 3 as printed: every knot the Newton-Raphson solution
    /// of its planned pose (to `eps_T`), however far it moves a joint from
    /// the last knot; no joint-step bound on the knots. Exact knots on a
    /// line that misses the singular pose: the fit then turns the wrist flip
    /// into whatever joint rates it takes.
    Exact,
}

impl RegionPlan {
    /// `joint` or `greedy`.
    pub fn as_str(&self) -> &'static str {
        match self {
            RegionPlan::Joint => "joint",
            RegionPlan::Greedy => "greedy",
            RegionPlan::Exact => "exact",
        }
    }
}

impl std::str::FromStr for RegionPlan {
    type Err = crate::error::Error;

    /// `joint`, `greedy` or `exact`; the error (named `region_plan`) lists
    /// them.
    fn from_str(name: &str) -> Result<Self> {
        [RegionPlan::Joint, RegionPlan::Greedy, RegionPlan::Exact]
            .into_iter()
            .find(|plan| plan.as_str() == name)
            .ok_or_else(|| {
                Error::invalid_argument(
                    "region_plan",
                    format!("expected \"joint\", \"greedy\" or \"exact\", got \"{name}\""),
                )
            })
    }
}

impl std::fmt::Display for RegionPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Weight `mu` of the sum of squares against the largest error.
const SUM_WEIGHT: f64 = 0.1;
/// Cone programs per region at most.
const MAX_PROGRAMS: usize = 8;
/// First trust-region radius, rad or m per joint.
const FIRST_TRUST_RADIUS: f64 = 0.2;
/// Stop when the predicted fall of the merit is below this fraction of it.
const PREDICTED_FALL_TOLERANCE: f64 = 1e-3;
/// Free nodes of the program at most: a longer region is planned on every
/// `s`-th knot, the knots between following linearly in time.
const MAX_NODES: usize = 48;

/// The knots to plan: targets, step radii, limits.
pub(super) struct KnotProblem<'a> {
    /// Planned pose of every knot, inertial frame (knot 0 first).
    pub targets: &'a [Pose],
    /// Knot times, s.
    pub times: &'a [f64],
    /// `eps_dq / h`: the joint speed bound (rad/s or m/s).
    pub rate_bound: f64,
    /// Lower and upper joint limits (infinite where none).
    pub limits: &'a (Vec<f64>, Vec<f64>),
    /// True when the last knot is free (the region ends at the path's end).
    pub free_last: bool,
}

/// What the joint plan did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct JointPlanOutcome {
    /// Cone programs solved.
    pub programs: usize,
    /// Largest knot error of the greedy plan (6-vector norm, m and rad).
    pub greedy_max_error: f64,
    /// Largest knot error of the joint plan (every knot).
    pub max_error: f64,
}

/// The program's layout: the nodes (knot indices) whose positions are the
/// variables, and the knots whose errors it bounds, each as a blend of its
/// two neighbouring nodes.
struct Layout {
    /// Node knot indices, increasing, from 0 to the last knot.
    nodes: Vec<usize>,
    /// True when the last node is fixed (the exit knot); the entry always is.
    last_fixed: bool,
    /// Error knots: `(knot, node a, node b, alpha)` with the knot at
    /// `(1 - alpha) node_a + alpha node_b`.
    samples: Vec<(usize, usize, usize, f64)>,
}

impl Layout {
    fn new(problem: &KnotProblem<'_>) -> Layout {
        let last = problem.times.len() - 1;
        let stride = last.div_ceil(MAX_NODES).max(1);
        let mut nodes: Vec<usize> = (0..last).step_by(stride).collect();
        nodes.push(last);
        // Errors at every node and midway between nodes (every knot when
        // the stride is 1 or 2).
        let mut samples = Vec::new();
        for (a, w) in nodes.windows(2).enumerate() {
            let (i, j) = (w[0], w[1]);
            let (ti, tj) = (problem.times[i], problem.times[j]);
            let step = ((j - i) / 2).max(1);
            for knot in (i..j).step_by(step).chain(std::iter::once(j)) {
                if knot == 0 || (knot == j && a + 2 < nodes.len()) {
                    // The entry is fixed; an inner node is sampled once, as
                    // the start of the next interval.
                    continue;
                }
                let alpha = (problem.times[knot] - ti) / (tj - ti);
                samples.push((knot, a, a + 1, alpha));
            }
        }
        Layout {
            nodes,
            last_fixed: !problem.free_last,
            samples,
        }
    }

    /// Variable slot of node `a` (`None` for a fixed node).
    fn slot(&self, a: usize) -> Option<usize> {
        if a == 0 || (self.last_fixed && a + 1 == self.nodes.len()) {
            None
        } else {
            Some(a - 1)
        }
    }

    fn free_nodes(&self) -> usize {
        self.nodes.len() - 1 - usize::from(self.last_fixed)
    }

    /// Every knot from the nodes, linearly in time.
    fn interpolate(&self, times: &[f64], node_q: &[Vec<f64>], knots: &mut [Vec<f64>]) {
        for (a, w) in self.nodes.windows(2).enumerate() {
            let (i, j) = (w[0], w[1]);
            for knot in i..=j {
                let alpha = (times[knot] - times[i]) / (times[j] - times[i]);
                for (q, (qa, qb)) in knots[knot]
                    .iter_mut()
                    .zip(node_q[a].iter().zip(&node_q[a + 1]))
                {
                    *q = qa + alpha * (qb - qa);
                }
            }
        }
    }
}

/// Pose errors (6-vectors) of the given knots and, with `jacobians`, their
/// Jacobians.
fn knot_errors(
    plant: &mut Plant<'_>,
    problem: &KnotProblem<'_>,
    knots: &[Vec<f64>],
    which: impl Iterator<Item = usize>,
    errors: &mut Vec<Vector6<f64>>,
    mut jacobians: Option<&mut Vec<Matrix6xX<f64>>>,
) -> Result<()> {
    errors.clear();
    if let Some(j) = jacobians.as_deref_mut() {
        j.clear();
    }
    for i in which {
        plant.evaluate(&knots[i])?;
        errors.push(pose_error(&problem.targets[i], plant.pose()));
        if let Some(j) = jacobians.as_deref_mut() {
            j.push(plant.jacobian().clone());
        }
    }
    Ok(())
}

/// `max |e| + weight sum |e|^2`.
fn merit(errors: &[Vector6<f64>], weight: f64) -> f64 {
    let max = errors.iter().map(|e| e.norm()).fold(0.0, f64::max);
    max + weight * errors.iter().map(|e| e.norm_squared()).sum::<f64>()
}

/// Largest error norm.
fn largest(errors: &[Vector6<f64>]) -> f64 {
    errors.iter().map(|e| e.norm()).fold(0.0, f64::max)
}

/// Plans the region's knots jointly from `knots` (the greedy plan,
/// feasible; see the module documentation) and writes the joint plan into
/// `planned` (same shape). The caller keeps whichever errs less.
pub(super) fn plan_jointly(
    plant: &mut Plant<'_>,
    problem: &KnotProblem<'_>,
    knots: &[Vec<f64>],
    planned: &mut [Vec<f64>],
) -> Result<JointPlanOutcome> {
    let count = knots.len();
    if count < 2 || problem.times.len() != count || problem.targets.len() != count {
        return Err(Error::invalid_argument(
            "knots",
            "a region plan needs at least two knots, with a time and a pose each",
        ));
    }
    let n = plant.dof();
    let layout = Layout::new(problem);
    let mut errors = Vec::with_capacity(count);
    knot_errors(plant, problem, knots, 1..count, &mut errors, None)?;
    let greedy_max_error = largest(&errors);
    let mut outcome = JointPlanOutcome {
        programs: 0,
        greedy_max_error,
        max_error: f64::INFINITY,
    };
    if greedy_max_error <= 0.0 || layout.free_nodes() == 0 {
        return Ok(outcome);
    }
    let mut node_q: Vec<Vec<f64>> = layout.nodes.iter().map(|&i| knots[i].clone()).collect();
    layout.interpolate(problem.times, &node_q, planned);
    let samples = || layout.samples.iter().map(|s| s.0);
    let weight = SUM_WEIGHT / (layout.samples.len() as f64 * greedy_max_error);
    let mut jacobians = Vec::with_capacity(layout.samples.len());
    knot_errors(
        plant,
        problem,
        planned,
        samples(),
        &mut errors,
        Some(&mut jacobians),
    )?;
    let mut current = merit(&errors, weight);
    let mut trust = FIRST_TRUST_RADIUS;
    let mut trial_nodes = node_q.clone();
    let mut trial = planned.to_vec();
    let mut trial_errors = Vec::with_capacity(errors.len());
    let mut step = vec![0.0; layout.free_nodes() * n];
    while outcome.programs < MAX_PROGRAMS {
        outcome.programs += 1;
        let Some(predicted) = solve_program(
            problem, &layout, &node_q, &errors, &jacobians, weight, trust, &mut step,
        )?
        else {
            break;
        };
        let predicted_fall = current - predicted;
        if predicted_fall <= PREDICTED_FALL_TOLERANCE * current {
            break;
        }
        for (a, node) in trial_nodes.iter_mut().enumerate() {
            if let Some(slot) = layout.slot(a) {
                for (j, q) in node.iter_mut().enumerate() {
                    *q = node_q[a][j] + step[slot * n + j];
                }
            }
        }
        layout.interpolate(problem.times, &trial_nodes, &mut trial);
        knot_errors(plant, problem, &trial, samples(), &mut trial_errors, None)?;
        let fall = current - merit(&trial_errors, weight);
        if fall >= 0.1 * predicted_fall {
            node_q.clone_from_slice(&trial_nodes);
            planned.clone_from_slice(&trial);
            knot_errors(
                plant,
                problem,
                planned,
                samples(),
                &mut errors,
                Some(&mut jacobians),
            )?;
            current = merit(&errors, weight);
            if fall >= 0.75 * predicted_fall {
                trust *= 2.0;
            }
        } else {
            trust *= 0.25;
        }
    }
    knot_errors(plant, problem, planned, 1..count, &mut errors, None)?;
    outcome.max_error = largest(&errors);
    Ok(outcome)
}

/// One cone program of the joint plan: writes the step of the free nodes
/// into `step` and returns the predicted merit, or `None` when Clarabel
/// finds no solution.
///
/// Variables `[dq_1 .. dq_M, s]` (`M` free nodes of `n` joints, `s` the
/// epigraph of the largest linearised error). Clarabel's form `A x + z = b`,
/// `z` in the cones: the non-negative rows (step bounds between nodes,
/// trust region and limits), then one second-order cone
/// `(s, e_i - J_i ((1 - alpha) dq_a + alpha dq_b))` per error knot.
#[allow(clippy::too_many_arguments)]
fn solve_program(
    problem: &KnotProblem<'_>,
    layout: &Layout,
    node_q: &[Vec<f64>],
    errors: &[Vector6<f64>],
    jacobians: &[Matrix6xX<f64>],
    weight: f64,
    trust: f64,
    step: &mut [f64],
) -> Result<Option<f64>> {
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{
        DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
    };
    let n = node_q.first().map_or(0, |k| k.len());
    let free = layout.free_nodes();
    let variables = free * n + 1;
    let s_index = free * n;
    // The blend of an error knot: (slot, weight) of its two nodes.
    let blend = |&(_, a, b, alpha): &(usize, usize, usize, f64)| {
        [(layout.slot(a), 1.0 - alpha), (layout.slot(b), alpha)]
    };
    // Objective: s + weight sum |e_i - J_i B_i dq|^2; Clarabel's P is the
    // Hessian, 2 weight sum B_i' J_i' J_i B_i.
    let (mut pi, mut pj, mut pv) = (Vec::new(), Vec::new(), Vec::new());
    let mut gradient = vec![0.0; variables];
    gradient[s_index] = 1.0;
    for (sample, (e, jac)) in layout.samples.iter().zip(errors.iter().zip(jacobians)) {
        let gram = jac.transpose() * jac;
        let linear = jac.transpose() * e;
        let parts = blend(sample);
        for &(slot_c, w_c) in &parts {
            let Some(slot_c) = slot_c else { continue };
            for c in 0..n {
                gradient[slot_c * n + c] -= 2.0 * weight * w_c * linear[c];
                for &(slot_r, w_r) in &parts {
                    let Some(slot_r) = slot_r else { continue };
                    for r in 0..n {
                        let (row, col) = (slot_r * n + r, slot_c * n + c);
                        if row <= col {
                            pi.push(row);
                            pj.push(col);
                            pv.push(2.0 * weight * w_r * w_c * gram[(r, c)]);
                        }
                    }
                }
            }
        }
    }
    for v in 0..free * n {
        pi.push(v);
        pj.push(v);
        pv.push(1e-12);
    }
    let hessian = CscMatrix::new_from_triplets(variables, variables, pi, pj, pv);
    let (mut ai, mut aj, mut av, mut b) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    // One row `entries . x <= bound` (the row index is b's length).
    let mut push_le = |entries: &[(usize, f64)], bound: f64, b: &mut Vec<f64>| {
        for &(col, value) in entries {
            ai.push(b.len());
            aj.push(col);
            av.push(value);
        }
        b.push(bound);
    };
    // Step bounds between consecutive nodes: the joint speed bound over
    // their time apart (the knots between follow linearly, so each period's
    // step is within eps_dq).
    for (a, w) in layout.nodes.windows(2).enumerate() {
        let radius = problem.rate_bound * (problem.times[w[1]] - problem.times[w[0]]);
        for (j, (next, last)) in node_q[a + 1].iter().zip(&node_q[a]).enumerate() {
            let difference = next - last;
            let radius = radius.max(difference.abs());
            let mut entries = Vec::with_capacity(2);
            if let Some(slot) = layout.slot(a + 1) {
                entries.push((slot * n + j, 1.0));
            }
            if let Some(slot) = layout.slot(a) {
                entries.push((slot * n + j, -1.0));
            }
            if entries.is_empty() {
                continue;
            }
            push_le(&entries, radius - difference, &mut b);
            let negated: Vec<(usize, f64)> = entries.iter().map(|&(c, v)| (c, -v)).collect();
            push_le(&negated, radius + difference, &mut b);
        }
    }
    // Trust region and joint limits (a limit never bounds a node already
    // beyond it more tightly than where it is).
    let (lower, upper) = problem.limits;
    for (a, q) in node_q.iter().enumerate() {
        let Some(slot) = layout.slot(a) else { continue };
        for j in 0..n {
            let col = slot * n + j;
            let up = trust.min((upper[j] - q[j]).max(0.0));
            let down = trust.min((q[j] - lower[j]).max(0.0));
            push_le(&[(col, 1.0)], up, &mut b);
            push_le(&[(col, -1.0)], down, &mut b);
        }
    }
    let nonnegative = b.len();
    // Cones: z = (s, e_i - J_i B_i dq) = b - A x, A = (-1 on s; J_i B_i).
    for (sample, (e, jac)) in layout.samples.iter().zip(errors.iter().zip(jacobians)) {
        push_le(&[(s_index, -1.0)], 0.0, &mut b);
        let parts = blend(sample);
        for r in 0..6 {
            let mut entries = Vec::with_capacity(2 * n);
            for &(slot, w) in &parts {
                if let Some(slot) = slot {
                    entries.extend((0..n).map(|c| (slot * n + c, w * jac[(r, c)])));
                }
            }
            push_le(&entries, e[r], &mut b);
        }
    }
    let rows = b.len();
    let a = CscMatrix::new_from_triplets(rows, variables, ai, aj, av);
    let mut cones = vec![SupportedConeT::NonnegativeConeT(nonnegative)];
    cones.extend(
        layout
            .samples
            .iter()
            .map(|_| SupportedConeT::SecondOrderConeT(7)),
    );
    // A set-up failure leaves the plan as it is (no step), like a program
    // without a solution.
    let Ok(settings) = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(60)
        .build()
    else {
        return Ok(None);
    };
    let Ok(mut solver) = DefaultSolver::new(&hessian, &gradient, &a, &b, &cones, settings) else {
        return Ok(None);
    };
    solver.solve();
    let solution = &solver.solution;
    if !matches!(
        solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    ) || solution.x.len() != variables
        || solution.x.iter().any(|x| !x.is_finite())
    {
        return Ok(None);
    }
    step.copy_from_slice(&solution.x[..free * n]);
    // The predicted merit: the largest and the summed linearised errors.
    let mut linearised = Vec::with_capacity(errors.len());
    for (sample, (e, jac)) in layout.samples.iter().zip(errors.iter().zip(jacobians)) {
        let mut dq = DVector::zeros(n);
        for (slot, w) in blend(sample) {
            if let Some(slot) = slot {
                dq += DVector::from_column_slice(&step[slot * n..(slot + 1) * n]) * w;
            }
        }
        let moved = jac * dq;
        linearised.push(e - Vector6::from_iterator(moved.iter().copied()));
    }
    Ok(Some(merit(&linearised, weight)))
}
