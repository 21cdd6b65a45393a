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
/// Each pass takes the overshoot over `T` off `u`, and one or two ulps of
/// `u` more (`|u| eps`): recomputing `(upper - q) / T` minus the overshoot
/// can round back to the same `u` and never get within.
fn guard_position(q: f64, mut u: f64, t: f64, lower: f64, upper: f64) -> f64 {
    for _ in 0..4 {
        let next = q + t * u;
        if q <= upper && next > upper {
            u = u - (next - upper) / t - u.abs() * f64::EPSILON;
        } else if q >= lower && next < lower {
            u = u + (lower - next) / t + u.abs() * f64::EPSILON;
        } else {
            break;
        }
    }
    u
}

#[cfg(test)]
#[path = "constraints_tests.rs"]
mod tests;
