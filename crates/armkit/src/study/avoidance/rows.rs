//! Seed 004's rows about which joints the singularity moves (Figs 5-6),
//! the `eps_dq` sweep (sec 2.3.1) and the Runge phenomenon of eq 30's one
//! polynomial against the C2 fit (eqs 33-42).

use super::{AvoidanceOutcome, AvoidanceStudy};
use crate::error::Result;
use crate::singularity::{Manipulator, Method, MethodRun, PathTracker};
use crate::study::{Finding, FindingStatus};

/// The joints the paper names as jumping (Figs 5-6): 4 and 6 (0-based 3 and 5).
const PAPER_JUMPING: [usize; 2] = [3, 5];
/// "Unaffected" (Fig 6, joints 1 to 3): a joint's largest change of rate
/// from one period to the next inside the region at most this many times
/// its largest change anywhere else on the path.
const UNAFFECTED_FACTOR: f64 = 2.0;
/// "Runge phenomenon" (sec 2.3.2, eq 30): the polynomial's peak joint rate
/// at least this many times the C2 fit's over the same region.
const RUNGE_FACTOR: f64 = 10.0;

/// The `eps_dq` values of seed 004's sweep (rad per 0.01 s period): half,
/// once, twice and four times the default 0.005 (space6r's 0.5 rad/s).
pub const SEED004_EPS_SWEEP: [f64; 4] = [0.0025, 0.005, 0.01, 0.02];

/// The avoidance (the study's first `k`) on the study's line with one
/// `eps_dq` of the sweep (seed 004, sec 2.3.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EpsRegion {
    /// `eps_dq`: the joint step threshold, rad (or m) per control period.
    pub joint_step_threshold: f64,
    /// The `|det J|` threshold by the study's rule with this `eps_dq` (m^3
    /// for a 6R arm): under seed 004's rule it is calibrated from where the
    /// plain run's steps exceed `eps_dq`.
    pub determinant_threshold: f64,
    /// Entry of the first and exit of the last singular region, s; `None`
    /// when no region was entered.
    pub region: Option<(f64, f64)>,
    /// Total time inside the regions (the sum of their spans), s.
    pub region_length: f64,
}

impl EpsRegion {
    /// The regions of `run`, the avoidance with `eps_dq` =
    /// `joint_step_threshold` (rad or m per period) and the `|det J|`
    /// threshold `determinant_threshold`.
    pub(super) fn of_run(
        joint_step_threshold: f64,
        determinant_threshold: f64,
        run: &MethodRun,
    ) -> EpsRegion {
        EpsRegion {
            joint_step_threshold,
            determinant_threshold,
            region: run.region_span(),
            region_length: run.region_time(),
        }
    }
}

/// `eps_dq | threshold | region | length` per run of an `eps_dq` sweep.
fn eps_table(sweep: &[EpsRegion]) -> String {
    let rows = sweep
        .iter()
        .map(|r| {
            let span = r
                .region
                .map_or("no region".into(), |(a, b)| format!("{a:.2} to {b:.2} s"));
            format!(
                "{:.4} | {:.3e} | {span} | {:.2} s",
                r.joint_step_threshold, r.determinant_threshold, r.region_length
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    format!("eps_dq (rad per period) | |det J| threshold (m^3) | region | length: {rows}")
}

/// Seed 004, sec 2.3.1, "the larger eps_dq, the smaller the singular
/// region", judged on `sweep` (ascending `eps_dq`): reproduced when the
/// region shrinks at every step, with a deviation when it shrinks overall
/// and never grows. `claim` names the claim and where it ran, `conditions`
/// the runs' settings.
pub(super) fn eps_finding(claim: &str, sweep: &[EpsRegion], conditions: &str) -> Finding {
    let lengths: Vec<f64> = sweep.iter().map(|r| r.region_length).collect();
    let strictly = lengths.windows(2).all(|w| w[1] < w[0]);
    let never_grows = lengths.windows(2).all(|w| w[1] <= w[0] + 1e-9);
    let shrinks = lengths
        .first()
        .zip(lengths.last())
        .is_some_and(|(a, b)| b < a);
    let (status, verdict) = if strictly {
        (
            FindingStatus::Reproduced,
            "the region shrinks at every step",
        )
    } else if never_grows && shrinks {
        (
            FindingStatus::ReproducedWithDeviation,
            "it shrinks overall but not at every step",
        )
    } else {
        (
            FindingStatus::NotReproduced,
            "it does not shrink as eps_dq grows",
        )
    };
    Finding::new(
        claim,
        format!("{} ({conditions}): {verdict}", eps_table(sweep)),
        status,
    )
}

impl AvoidanceStudy {
    /// The avoidance with the first `k` on the study's line for each
    /// `eps_dq` of `joint_step_sweep`, the `|det J|` threshold set by the
    /// study's rule with that `eps_dq` (`manipulator` as for
    /// [`AvoidanceStudy::compare`]).
    pub(super) fn eps_sweep(&self, manipulator: Manipulator<'_>) -> Result<Vec<EpsRegion>> {
        let Some(&k) = self.ks.first() else {
            return Ok(Vec::new());
        };
        let line = crate::singularity::line_through(
            &manipulator,
            &self.through,
            &self.direction,
            self.miss,
        )?;
        let task = line.task(self.duration, self.acceleration_time);
        let placed = super::place(manipulator, &line);
        let mut rows = Vec::with_capacity(self.joint_step_sweep.len());
        for &eps in &self.joint_step_sweep {
            let study = AvoidanceStudy {
                joint_step_threshold: eps,
                ..self.clone()
            };
            let (threshold, _) = study.determinant_threshold(manipulator)?;
            let tracker = PathTracker::new(placed, task.clone(), study.options(threshold))?;
            let run = tracker.run(&Method::Avoidance { k })?;
            rows.push(EpsRegion::of_run(eps, threshold, &run));
        }
        Ok(rows)
    }
}

/// Per joint, the largest change of rate from one period to the next
/// touching a planned period of `regions` (a run's `in_region`), and the
/// largest anywhere else (rad/s per period). The last sample's zero rate
/// is left out.
fn rate_changes(run: &MethodRun, regions: &[bool]) -> Vec<(f64, f64)> {
    run.joint_rates
        .iter()
        .map(|rates| {
            let periods = rates.len().saturating_sub(1);
            let mut inside: f64 = 0.0;
            let mut outside: f64 = 0.0;
            for i in 0..periods.saturating_sub(1) {
                let change = (rates[i + 1] - rates[i]).abs();
                let touches = regions.get(i).copied().unwrap_or(false)
                    || regions.get(i + 1).copied().unwrap_or(false);
                if touches {
                    inside = inside.max(change);
                } else {
                    outside = outside.max(change);
                }
            }
            (inside, outside)
        })
        .collect()
}

/// `inside / outside`, infinite when only the inside moves.
fn ratio((inside, outside): (f64, f64)) -> f64 {
    if outside > 0.0 {
        inside / outside
    } else if inside > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// The derivative at `x` of the one polynomial through `(nodes[j],
/// values[j])` (Lagrange, in barycentric form; `x` not a node): seed 004's
/// eq 30 read as the interpolating polynomial of all the region's knots.
/// The barycentric weights are scaled by their largest (a common factor,
/// which cancels) so that degrees in the hundreds stay in range.
pub fn interpolating_polynomial_rate(nodes: &[f64], values: &[f64], x: f64) -> f64 {
    let n = nodes.len();
    let logs: Vec<(f64, f64)> = (0..n)
        .map(|j| {
            (0..n)
                .filter(|&k| k != j)
                .fold((0.0, 1.0), |(log, sign), k| {
                    let d = nodes[j] - nodes[k];
                    (log - d.abs().ln(), sign * d.signum())
                })
        })
        .collect();
    let top = logs.iter().fold(f64::NEG_INFINITY, |m, l| m.max(l.0));
    let (mut num, mut den, mut num_rate, mut den_rate) = (0.0, 0.0, 0.0, 0.0);
    for ((node, value), (log, sign)) in nodes.iter().zip(values).zip(&logs) {
        let w = sign * (log - top).exp();
        let d = x - node;
        num += w * value / d;
        den += w / d;
        num_rate -= w * value / (d * d);
        den_rate -= w / (d * d);
    }
    (num_rate * den - num * den_rate) / (den * den)
}

/// One row of the Runge comparison: a run of the `k` sweep.
struct RungeRow {
    k: usize,
    knots: usize,
    polynomial: f64,
    fit: f64,
}

impl AvoidanceOutcome {
    /// Seed 004's rows on the joints (Figs 5-6: joints 1 to 3 unaffected,
    /// 4 and 6 jumping), the `eps_dq` sweep (sec 2.3.1) and eq 30's Runge
    /// phenomenon against the C2 fit.
    pub(super) fn joint_and_fit_findings(&self) -> Vec<Finding> {
        let mut findings = vec![self.unaffected_finding(), self.jumping_finding()];
        if self.eps_sweep.len() > 1 {
            findings.push(self.eps_finding());
        }
        if let Some(finding) = self.runge_finding() {
            findings.push(finding);
        }
        findings
    }

    fn eps_finding(&self) -> Finding {
        eps_finding(
            "seed 004, sec 2.3.1: the larger eps_dq, the smaller the singular region",
            &self.eps_sweep,
            &format!(
                "{}, {}; the threshold by the study's rule for each eps_dq",
                self.comparison.avoidance.method.label(),
                self.threshold
            ),
        )
    }

    /// Per joint, `(plain's largest step, rad per period)`.
    fn plain_steps(&self) -> Vec<f64> {
        let h = self.options.tracking.dt;
        self.comparison
            .plain
            .joint_rates
            .iter()
            .map(|rates| rates.iter().fold(0.0, |m: f64, r| m.max((r * h).abs())))
            .collect()
    }

    fn jumping_finding(&self) -> Finding {
        let eps = self.options.detection.joint_step_threshold;
        let steps = self.plain_steps();
        let jumping: Vec<usize> = (0..steps.len()).filter(|&j| steps[j] > eps).collect();
        let table = steps
            .iter()
            .enumerate()
            .map(|(j, s)| format!("joint {}: {s:.3e}", j + 1))
            .collect::<Vec<_>>()
            .join(", ");
        let names = if jumping.is_empty() {
            "none".to_string()
        } else {
            jumping
                .iter()
                .map(|j| (j + 1).to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        Finding::new(
            "seed 004, Figs 5-6: the joints that jump at the singularity are 4 and 6",
            format!(
                "plain tracking's largest joint step per period (rad; a jump: above eps_dq = \
                 {eps} rad): {table}; jumping: {names}"
            ),
            FindingStatus::from_holds(jumping == PAPER_JUMPING),
        )
    }

    fn unaffected_finding(&self) -> Finding {
        let c = &self.comparison;
        let avoidance = &c.avoidance;
        let regions = &avoidance.in_region;
        let claim = "seed 004, Fig 6: with the avoidance, the rates of joints 1 to 3 are \
                     unaffected by the singular region";
        if !regions.iter().any(|&r| r) {
            return Finding::new(
                claim,
                format!("{} entered no singular region", avoidance.method.label()),
                FindingStatus::NotReproduced,
            );
        }
        let ratios = |run: &MethodRun| -> Vec<f64> {
            rate_changes(run, regions).into_iter().map(ratio).collect()
        };
        let (avoid, plain) = (ratios(avoidance), ratios(&c.plain));
        let cells = |values: &[f64]| {
            values
                .iter()
                .enumerate()
                .map(|(j, r)| format!("{}: {r:.2}", j + 1))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let holds = avoid.iter().take(3).all(|r| *r <= UNAFFECTED_FACTOR);
        Finding::new(
            claim,
            format!(
                "largest change of a joint's rate from one period to the next inside the region, \
                 over its largest anywhere else on the path (unaffected: at most \
                 {UNAFFECTED_FACTOR} for joints 1 to 3): {} joint {}; plain on the same periods \
                 joint {}",
                avoidance.method.label(),
                cells(&avoid),
                cells(&plain)
            ),
            FindingStatus::from_holds(holds),
        )
    }

    fn runge_rows(&self) -> Vec<RungeRow> {
        let h = self.options.tracking.dt;
        let mut rows = Vec::new();
        for (k, run) in self.ks.iter().zip(&self.comparison.k_sweep) {
            let Some(region) = run.regions.first() else {
                continue;
            };
            let index = |t: f64| (t / h).round() as usize;
            let samples: Vec<usize> = region.knot_times.iter().map(|&t| index(t)).collect();
            let (Some(&first), Some(&last)) = (samples.first(), samples.last()) else {
                continue;
            };
            if samples.len() < 3 || last >= run.time.len() {
                continue;
            }
            // Times in periods from the entry (the weights' scale).
            let nodes: Vec<f64> = samples.iter().map(|&i| (i - first) as f64).collect();
            let (mut polynomial, mut fit): (f64, f64) = (0.0, 0.0);
            for (positions, rates) in run.joint_positions.iter().zip(&run.joint_rates) {
                let values: Vec<f64> = samples.iter().map(|&i| positions[i]).collect();
                for (offset, fit_rate) in rates[first..last].iter().enumerate() {
                    let x = offset as f64 + 0.5;
                    let rate = interpolating_polynomial_rate(&nodes, &values, x) / h;
                    polynomial = polynomial.max(rate.abs());
                    fit = fit.max(fit_rate.abs());
                }
            }
            rows.push(RungeRow {
                k: *k,
                knots: samples.len(),
                polynomial,
                fit,
            });
        }
        rows
    }

    fn runge_finding(&self) -> Option<Finding> {
        let rows = self.runge_rows();
        if rows.is_empty() {
            return None;
        }
        let runge = |r: &RungeRow| r.polynomial >= RUNGE_FACTOR * r.fit;
        let shown: Vec<String> = rows
            .iter()
            .filter(|r| runge(r))
            .map(|r| r.k.to_string())
            .collect();
        let table = rows
            .iter()
            .map(|r| {
                format!(
                    "{} | {} | {:.3e} | {:.3e}",
                    r.k, r.knots, r.polynomial, r.fit
                )
            })
            .collect::<Vec<_>>()
            .join("; ");
        Some(Finding::new(
            "seed 004, sec 2.3.2: eq 30's joint rates can show the Runge phenomenon, which the \
             C2 fit (eqs 33-42) avoids",
            format!(
                "the first region's knots of each k, through one interpolating polynomial \
                 (eq 30; degree knots - 1, rates at mid-period) and through the C2 fit (the run's \
                 rates), peak joint rate over the region (rad/s); Runge: the polynomial's at \
                 least {RUNGE_FACTOR} times the fit's. k | knots | polynomial | C2 fit: {table}. \
                 Runge shown for k = {} (the paper: \"in some special cases\")",
                if shown.is_empty() {
                    "none".to_string()
                } else {
                    shown.join(", ")
                }
            ),
            FindingStatus::from_holds(!shown.is_empty()),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::interpolating_polynomial_rate;

    #[test]
    fn the_polynomial_rate_is_exact_on_a_cubic_and_runge_on_runge_s_function() {
        // A cubic through 5 nodes is its own interpolant: p'(x) = 3x^2 - 2.
        let nodes = [0.0, 1.0, 2.0, 3.0, 4.0];
        let values: Vec<f64> = nodes.iter().map(|x| x * x * x - 2.0 * x + 1.0).collect();
        for x in [0.5, 1.7, 3.5] {
            let want = 3.0 * x * x - 2.0;
            assert!((interpolating_polynomial_rate(&nodes, &values, x) - want).abs() < 1e-9);
        }
        // Runge's 1 / (1 + 25 t^2) on 21 equispaced nodes of [-1, 1]: the
        // interpolant's slope near the ends dwarfs the function's (|f'| <= 3.25).
        let nodes: Vec<f64> = (0..21).map(|i| -1.0 + 0.1 * i as f64).collect();
        let values: Vec<f64> = nodes.iter().map(|t| 1.0 / (1.0 + 25.0 * t * t)).collect();
        let slope = interpolating_polynomial_rate(&nodes, &values, -0.95).abs();
        assert!(slope > 100.0, "{slope}");
    }
}
