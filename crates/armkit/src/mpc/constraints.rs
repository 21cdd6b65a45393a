//! The QP's constraints (seed 000 eqs 17-19): the constant constraint matrix
//! in the increments, the bounds rewritten every sample, and the last check
//! on the applied input.

use crate::error::{Error, Result};
use crate::model::{JointLimits, Model};

use super::options::MpcOptions;
use super::prediction;
use super::qp::CscMatrix;

/// The joint limits the planner enforces and the constraint rows they give.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointBounds {
    /// Per joint, `+inf` when unlimited.
    pub velocity_limit: Vec<f64>,
    pub lower: Vec<f64>,
    pub upper: Vec<f64>,
    /// Joints with a velocity limit (one QP row per control step each).
    pub velocity_rows: Vec<usize>,
    /// Joints with a position limit (one QP row per constrained sample each).
    pub position_rows: Vec<usize>,
    /// Predicted samples `i` whose joint positions are constrained.
    pub position_steps: Vec<usize>,
}

impl JointBounds {
    /// The limits of `overrides` (one per joint) or else of `model`.
    pub fn new(
        model: &Model,
        overrides: Option<&[JointLimits]>,
        horizon: usize,
        control_horizon: usize,
    ) -> Result<Self> {
        let dof = model.dof();
        let limits: Vec<JointLimits> = match overrides {
            Some(l) if l.len() != dof => {
                return Err(Error::DimensionMismatch {
                    what: "joint_limits",
                    expected: dof,
                    got: l.len(),
                })
            }
            Some(l) => l.to_vec(),
            None => model.joints().iter().map(|j| j.limits).collect(),
        };
        super::options::check_joint_limits(&limits)?;
        let velocity_limit: Vec<f64> = limits
            .iter()
            .map(|l| l.velocity.unwrap_or(f64::INFINITY))
            .collect();
        let lower: Vec<f64> = limits.iter().map(|l| l.lower).collect();
        let upper: Vec<f64> = limits.iter().map(|l| l.upper).collect();
        Ok(JointBounds {
            velocity_rows: (0..dof)
                .filter(|&j| velocity_limit[j].is_finite())
                .collect(),
            position_rows: (0..dof)
                .filter(|&j| lower[j].is_finite() || upper[j].is_finite())
                .collect(),
            position_steps: constrained_steps(horizon, control_horizon),
            velocity_limit,
            lower,
            upper,
        })
    }

    /// The constant constraint matrix for `dof` joints (eq 19).
    pub fn matrix(&self, dof: usize, control_horizon: usize, sample_time: f64) -> CscMatrix {
        constraint_matrix(
            dof,
            control_horizon,
            sample_time,
            &self.velocity_rows,
            &self.position_rows,
            &self.position_steps,
        )
    }

    /// Bounds of eqs 17-18 in terms of the increments, written into
    /// `lower_out`/`upper_out`. Velocity rows: for `l < M`, `vmin - v_old <=
    /// sum_{m<=l} du(m) <= vmax - v_old`. Position rows: for the constrained
    /// samples `i`, `q(k+i) = q + i T v_old + T sum_l c(i,l) du(l)` within
    /// `[lo_i, hi_i]`, the limits, relaxed for a joint outside them to what
    /// it reaches returning at [`MpcOptions::recovery_speed`] of its speed
    /// limit. Returns whether
    /// a joint is outside its limits.
    pub fn fill(
        &self,
        q: &[f64],
        previous_velocity: &[f64],
        options: &MpcOptions,
        lower_out: &mut [f64],
        upper_out: &mut [f64],
    ) -> bool {
        let (t, control_horizon, recovery) = (
            options.sample_time,
            options.control_horizon,
            options.recovery_speed,
        );
        let nv = self.velocity_rows.len();
        for l in 0..control_horizon {
            for (k, &j) in self.velocity_rows.iter().enumerate() {
                let row = l * nv + k;
                let v = self.velocity_limit[j];
                lower_out[row] = -v - previous_velocity[j];
                upper_out[row] = v - previous_velocity[j];
            }
        }
        let offset = control_horizon * nv;
        let np = self.position_rows.len();
        let mut outside = false;
        for (s, &i) in self.position_steps.iter().enumerate() {
            let it = i as f64 * t;
            for (k, &j) in self.position_rows.iter().enumerate() {
                let row = offset + s * np + k;
                let (mut lo, mut hi) = (self.lower[j], self.upper[j]);
                let reach = it * recovery * self.velocity_limit[j];
                if q[j] > hi {
                    outside = true;
                    hi = hi.max(q[j] - reach);
                }
                if q[j] < lo {
                    outside = true;
                    lo = lo.min(q[j] + reach);
                }
                // An unbounded side gets a bound the joint cannot reach
                // within the horizon, so every bound stays finite and modest.
                let far = it * self.velocity_limit[j].min(1e3) + 1.0;
                if !lo.is_finite() {
                    lo = q[j] - far;
                }
                if !hi.is_finite() {
                    hi = q[j] + far;
                }
                let drift = q[j] + it * previous_velocity[j];
                lower_out[row] = lo - drift;
                upper_out[row] = hi - drift;
            }
        }
        outside
    }

    /// Interval of inputs for joint `j` at position `qj` that respect the
    /// velocity limit and keep the joint within its position limits one
    /// sample `t` ahead; a joint already outside may only move back (or hold).
    pub fn step_interval(&self, j: usize, qj: f64, t: f64) -> (f64, f64) {
        let v = self.velocity_limit[j];
        let (lower, upper) = (self.lower[j], self.upper[j]);
        let hi = if qj > upper {
            0.0
        } else {
            v.min((upper - qj) / t)
        };
        let lo = if qj < lower {
            0.0
        } else {
            (-v).max((lower - qj) / t)
        };
        (lo, hi.max(lo))
    }

    /// The input applied for the planned `planned` velocity of joint `j` at
    /// `qj`: clamped into [`JointBounds::step_interval`] and guarded
    /// against floating-point overshoot.
    pub fn applied(&self, j: usize, qj: f64, planned: f64, t: f64) -> f64 {
        let (lo, hi) = self.step_interval(j, qj, t);
        guard_position(qj, planned.max(lo).min(hi), t, self.lower[j], self.upper[j])
    }
}

/// The predicted samples whose joint positions the QP constrains:
/// `1, ..., M` and `N`. The input changes only at the first `M` samples and
/// is then held, so the predicted joint positions are piecewise linear in
/// the sample index with breakpoints at `1..=M` and end at `N`: within the
/// (constant) limits at these samples means within them at all `N` samples
/// and in between (seed 000 eq 18 over the whole horizon, with `M + 1`
/// instead of `N` rows per joint).
pub(crate) fn constrained_steps(horizon: usize, control_horizon: usize) -> Vec<usize> {
    let mut steps: Vec<usize> = (1..=control_horizon).collect();
    if horizon > control_horizon {
        steps.push(horizon);
    }
    steps
}

/// The constant constraint matrix of eq 19 in the increments `dU` (column
/// `l dof + j` is increment `l` of joint `j`): velocity rows (eq 17) `l = 0..M-1`
/// for each velocity-limited joint, ones on increments `0..=l`; position rows
/// (eq 18) for each sample `i` of `steps` and each position-limited joint,
/// `T c(i, l)` on increments `l < min(i, M)`. Only the bounds change from
/// sample to sample.
pub(crate) fn constraint_matrix(
    dof: usize,
    control_horizon: usize,
    sample_time: f64,
    velocity_rows: &[usize],
    position_rows: &[usize],
    steps: &[usize],
) -> CscMatrix {
    let nv = velocity_rows.len();
    let np = position_rows.len();
    let rows = control_horizon * nv + steps.len() * np;
    let cols = dof * control_horizon;
    let mut col_ptr = Vec::with_capacity(cols + 1);
    let mut row_indices = Vec::new();
    let mut values = Vec::new();
    col_ptr.push(0);
    for l in 0..control_horizon {
        for j in 0..dof {
            if let Some(k) = velocity_rows.iter().position(|&v| v == j) {
                for step in l..control_horizon {
                    row_indices.push(step * nv + k);
                    values.push(1.0);
                }
            }
            if let Some(k) = position_rows.iter().position(|&p| p == j) {
                for (s, &i) in steps.iter().enumerate() {
                    if i > l {
                        row_indices.push(control_horizon * nv + s * np + k);
                        values.push(sample_time * prediction::increment_coefficient(i, l));
                    }
                }
            }
            col_ptr.push(row_indices.len());
        }
    }
    CscMatrix {
        rows,
        cols,
        col_ptr,
        row_indices,
        values,
    }
}

/// Shrinks `u` so that `q + T u` stays within `[lower, upper]` in floating
/// point when `q` is (a clamp to `(upper - q) / T` can overshoot by an ulp).
fn guard_position(q: f64, mut u: f64, t: f64, lower: f64, upper: f64) -> f64 {
    for _ in 0..4 {
        let next = q + t * u;
        if q <= upper && next > upper {
            u = (upper - q) / t - (next - upper).abs() / t;
        } else if q >= lower && next < lower {
            u = (lower - q) / t + (lower - next).abs() / t;
        } else {
            break;
        }
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{DhConvention, DhLink};

    const T: f64 = 0.05;

    /// A planar 2R arm: joint 0 within `[-1, 0.5]` rad at 2 rad/s, joint 1
    /// within `[-2, 2]` rad without a speed limit.
    fn arm() -> Model {
        let links = [
            DhLink::revolute(0.0, 0.4, 0.0)
                .with_limits(-1.0, 0.5)
                .with_velocity_limit(2.0),
            DhLink::revolute(0.0, 0.3, 0.0).with_limits(-2.0, 2.0),
        ];
        Model::from_dh("planar2", DhConvention::Standard, &links).unwrap()
    }

    fn options(horizon: usize, control_horizon: usize) -> MpcOptions {
        MpcOptions {
            horizon,
            control_horizon,
            sample_time: T,
            ..MpcOptions::default()
        }
    }

    /// The joint positions at samples `1..=N` of the plan `du` (eq 14
    /// simulated directly: `u(k) = u(k-1) + du(k)` for `k < M`, then held;
    /// `q(k+1) = q(k) + T u(k)`), one vector per sample.
    fn predicted_positions(
        q: &[f64],
        v_old: &[f64],
        du: &[f64],
        horizon: usize,
        control_horizon: usize,
    ) -> Vec<Vec<f64>> {
        let dof = q.len();
        let (mut position, mut u) = (q.to_vec(), v_old.to_vec());
        let mut out = Vec::new();
        for k in 0..horizon {
            for j in 0..dof {
                if k < control_horizon {
                    u[j] += du[k * dof + j];
                }
                position[j] += T * u[j];
            }
            out.push(position.clone());
        }
        out
    }

    /// Whether `du` meets every row of the QP's constraints at `q`, `v_old`.
    fn rows_hold(
        bounds: &JointBounds,
        opts: &MpcOptions,
        q: &[f64],
        v_old: &[f64],
        du: &[f64],
    ) -> bool {
        let dof = q.len();
        let a = bounds.matrix(dof, opts.control_horizon, opts.sample_time);
        let mut lower = vec![0.0; a.rows];
        let mut upper = vec![0.0; a.rows];
        bounds.fill(q, v_old, opts, &mut lower, &mut upper);
        let mut value = vec![0.0; a.rows];
        for (c, &x) in du.iter().enumerate().take(a.cols) {
            for k in a.col_ptr[c]..a.col_ptr[c + 1] {
                value[a.row_indices[k]] += a.values[k] * x;
            }
        }
        (0..a.rows).all(|r| value[r] >= lower[r] - 1e-12 && value[r] <= upper[r] + 1e-12)
    }

    /// The increments that give the joint velocities `u(0..N)` of joint
    /// `joint` (the others keep `v_old`), or `None` where the sequence is
    /// not held constant from `M - 1` on.
    fn increments_for(
        velocities: &[f64],
        joint: usize,
        v_old: &[f64],
        control_horizon: usize,
    ) -> Option<Vec<f64>> {
        let dof = v_old.len();
        let held = velocities[control_horizon - 1];
        if velocities[control_horizon..].iter().any(|&u| u != held) {
            return None;
        }
        let mut du = vec![0.0; dof * control_horizon];
        let mut previous = v_old[joint];
        for (l, &u) in velocities[..control_horizon].iter().enumerate() {
            du[l * dof + joint] = u - previous;
            previous = u;
        }
        Some(du)
    }

    /// A plan whose joint 0 crosses its upper limit at one predicted sample
    /// only, anywhere in the horizon (the limit binding mid-horizon), breaks
    /// a constraint row; the same plan scaled to stay within the limit
    /// meets them all. Every sample whose crossing a plan can isolate is
    /// tried: `1..M-1` (a bump up and back), `M` when `M = N` (the last
    /// input, held), and `N` when `N > M` (a slow drift from `M - 1` on).
    #[test]
    fn a_limit_crossed_at_any_single_sample_breaks_a_row() {
        let model = arm();
        let (upper, gap) = (0.5, 0.02);
        let v_old = [0.0, 0.1];
        let q = [upper - gap, 0.3];
        let mut tried = 0;
        for (n, m) in [(10, 10), (10, 5), (6, 1), (5, 4), (4, 4), (8, 2)] {
            let opts = options(n, m);
            let bounds = JointBounds::new(&model, None, n, m).unwrap();
            for s in 1..=n {
                for (scale, crosses) in [(1.01, true), (0.99, false)] {
                    let h = scale * gap;
                    let mut velocities = vec![0.0; n];
                    if s < m {
                        // Up to the limit over sample s, back over s + 1
                        // (and on down, held, when s + 1 is the last input).
                        velocities[s - 1] = h / T;
                        let back = if s + 1 < m { s + 1..s + 1 } else { s..n };
                        velocities[s] = -h / T;
                        velocities[back].iter_mut().for_each(|u| *u = -h / T);
                    } else if s == m && m == n {
                        velocities[s - 1] = h / T;
                    } else if s == n {
                        let rate = h / ((n - m + 1) as f64 * T);
                        velocities[m - 1..].iter_mut().for_each(|u| *u = rate);
                    } else {
                        continue;
                    }
                    let Some(du) = increments_for(&velocities, 0, &v_old, m) else {
                        continue;
                    };
                    let positions = predicted_positions(&q, &v_old, &du, n, m);
                    let over: Vec<usize> =
                        (1..=n).filter(|&i| positions[i - 1][0] > upper).collect();
                    if crosses {
                        assert_eq!(over, vec![s], "N = {n}, M = {m}: {positions:?}");
                    } else {
                        assert!(over.is_empty());
                    }
                    assert_eq!(
                        rows_hold(&bounds, &opts, &q, &v_old, &du),
                        !crosses,
                        "N = {n}, M = {m}: a plan reaching {:.4} rad at sample {s} only (limit {upper})",
                        positions[s - 1][0]
                    );
                    tried += 1;
                }
            }
        }
        // Each horizon pair's isolable samples, twice (crossing and not).
        assert_eq!(tried, 2 * (10 + 5 + 1 + 4 + 4 + 2));
    }

    /// The rows hold exactly when every predicted sample is within the
    /// limits and every input within its speed limit: random plans near
    /// the upper limit of joint 0, both horizons equal and not.
    #[test]
    fn the_rows_hold_exactly_when_every_sample_is_within_the_limits() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(37);
        let model = arm();
        let (mut feasible, mut infeasible, mut last_only) = (0, 0, 0);
        for (n, m) in [(10, 10), (10, 5), (6, 1), (5, 4), (4, 4)] {
            let opts = options(n, m);
            let bounds = JointBounds::new(&model, None, n, m).unwrap();
            for _ in 0..4000 {
                let q = [0.5 - rng.gen_range(0.0..0.05), rng.gen_range(-1.9..1.9)];
                let v_old = [rng.gen_range(-0.5..0.5), rng.gen_range(-0.5..0.5)];
                let du: Vec<f64> = (0..2 * m).map(|_| rng.gen_range(-0.3..0.3)).collect();
                let positions = predicted_positions(&q, &v_old, &du, n, m);
                let within_positions = positions
                    .iter()
                    .all(|p| p[0] >= -1.0 && p[0] <= 0.5 && p[1] >= -2.0 && p[1] <= 2.0);
                let mut u = v_old[0];
                let within_speed = (0..m).all(|l| {
                    u += du[2 * l];
                    u.abs() <= 2.0
                });
                let expected = within_positions && within_speed;
                if expected {
                    feasible += 1;
                } else {
                    infeasible += 1;
                }
                if within_speed
                    && positions[..n - 1].iter().all(|p| p[0] <= 0.5)
                    && positions[n - 1][0] > 0.5
                {
                    last_only += 1;
                }
                assert_eq!(
                    rows_hold(&bounds, &opts, &q, &v_old, &du),
                    expected,
                    "N = {n}, M = {m}, q {q:?}, v_old {v_old:?}, du {du:?}: {positions:?}"
                );
            }
        }
        // Both outcomes, and plans crossing at the last sample only, occur.
        assert!(
            feasible > 1000 && infeasible > 1000,
            "{feasible} {infeasible}"
        );
        assert!(last_only > 20, "{last_only}");
    }

    /// With two speed-limited joints (2 and 3 rad/s, positions far from
    /// their limits), an input of either joint beyond its speed limit at any
    /// single control sample `l < M`, of either sign, breaks a row, and the
    /// same plan 1 % within the limit meets every row (eq 17: each joint's
    /// velocity rows at every control sample, none sharing another's bounds).
    #[test]
    fn a_speed_limit_crossed_by_either_joint_at_any_input_breaks_a_row() {
        let model = arm();
        let limits = [
            JointLimits {
                velocity: Some(2.0),
                ..JointLimits::position(-10.0, 10.0)
            },
            JointLimits {
                velocity: Some(3.0),
                ..JointLimits::position(-10.0, 10.0)
            },
        ];
        let (q, v_old) = ([0.0, 0.0], [0.0, 0.0]);
        let mut tried = 0;
        for (n, m) in [(10, 10), (10, 5), (6, 1), (5, 4)] {
            let opts = options(n, m);
            let bounds = JointBounds::new(&model, Some(&limits), n, m).unwrap();
            assert_eq!(bounds.velocity_rows, vec![0, 1]);
            for (joint, limit) in limits.iter().enumerate() {
                let speed = limit.velocity.unwrap();
                for l in 0..m {
                    for sign in [1.0, -1.0] {
                        for (scale, crosses) in [(1.01, true), (0.99, false)] {
                            let mut velocities = vec![0.0; n];
                            let end = if l + 1 == m { n } else { l + 1 };
                            velocities[l..end]
                                .iter_mut()
                                .for_each(|u| *u = sign * scale * speed);
                            let du = increments_for(&velocities, joint, &v_old, m).unwrap();
                            assert_eq!(
                                rows_hold(&bounds, &opts, &q, &v_old, &du),
                                !crosses,
                                "N = {n}, M = {m}: joint {joint} at {:.3} rad/s over input {l} only (limit {speed})",
                                sign * scale * speed
                            );
                            tried += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(tried, 2 * 2 * 2 * (10 + 5 + 1 + 4));
    }
}
