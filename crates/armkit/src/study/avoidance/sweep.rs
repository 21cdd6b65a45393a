//! The miss sweep of seed 004's study: parallel lines that pass through the
//! singular pose or miss it by a little, each tracked by plain resolved
//! rate, the avoidance, DLS and SRI.

use super::{place, AvoidanceStudy};
use crate::error::Result;
use crate::singularity::{
    line_through, AvoidanceOptions, Baselines, Manipulator, Method, MethodSummary, PathTracker,
};
use crate::study::{Check, Series};
use crate::tracking::TrackingStatus;

/// The misses of seed 004's sweep (m and rad, along the direction the
/// Jacobian loses at the singular pose): through it, and 1, 3, 10 and 30 mm
/// either side.
pub const SEED004_MISS_SWEEP: [f64; 9] =
    [-0.03, -0.01, -0.003, -0.001, 0.0, 0.001, 0.003, 0.01, 0.03];

/// One line of the miss sweep: every method's summary and status.
#[derive(Clone, Debug, PartialEq)]
pub struct MissLine {
    /// Offset of the line from the singular pose (m and rad).
    pub miss: f64,
    /// Plain resolved rate.
    pub plain: MethodSummary,
    /// Seed 004's avoidance with the study's first `k`.
    pub avoidance: MethodSummary,
    /// Damped least squares (Nakamura).
    pub damped_least_squares: MethodSummary,
    /// Singularity-robust inverse (Chiaverini).
    pub singularity_robust: MethodSummary,
    /// Status of plain, avoidance, dls, sri.
    pub statuses: [TrackingStatus; 4],
    /// Least-squares knots of the avoidance's regions (knots the arm could
    /// not reach within `eps_dq` per period).
    pub bounded_knots: usize,
}

impl MissLine {
    /// `(label, summary)` of plain, avoidance, dls, sri.
    pub fn methods(&self) -> [(&'static str, &MethodSummary); 4] {
        [
            ("plain", &self.plain),
            ("avoidance", &self.avoidance),
            ("dls", &self.damped_least_squares),
            ("sri", &self.singularity_robust),
        ]
    }

    /// True when the avoidance's largest position and orientation errors
    /// are at most `other`'s.
    pub fn avoidance_errs_no_more_than(&self, other: &MethodSummary) -> bool {
        self.avoidance.max_position_error <= other.max_position_error
            && self.avoidance.max_orientation_error <= other.max_orientation_error
    }
}

/// The lines of the miss sweep, in the order of the study's `miss_sweep`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MissSweep {
    /// The avoidance's method on every line.
    pub avoidance: Option<Method>,
    /// One entry per miss.
    pub lines: Vec<MissLine>,
}

impl MissSweep {
    /// Tracks every line of `study.miss_sweep` with the four methods
    /// (`manipulator` with its base at `study.through`).
    pub(super) fn run(
        study: &AvoidanceStudy,
        manipulator: Manipulator<'_>,
        options: AvoidanceOptions,
        baselines: &Baselines,
    ) -> Result<MissSweep> {
        let Some(&k) = study.ks.first() else {
            return Ok(MissSweep::default());
        };
        let avoidance = Method::Avoidance { k };
        let mut lines = Vec::with_capacity(study.miss_sweep.len());
        for &miss in &study.miss_sweep {
            let line = line_through(&manipulator, &study.through, &study.direction, miss)?;
            let tracker = PathTracker::new(
                place(manipulator, &line),
                line.task(study.duration, study.acceleration_time),
                options,
            )?;
            let runs = [
                tracker.run(&Method::Plain)?,
                tracker.run(&avoidance)?,
                tracker.run(&Method::DampedLeastSquares(baselines.nakamura))?,
                tracker.run(&Method::SingularityRobust(baselines.chiaverini))?,
            ];
            lines.push(MissLine {
                miss,
                plain: runs[0].summary,
                avoidance: runs[1].summary,
                damped_least_squares: runs[2].summary,
                singularity_robust: runs[3].summary,
                statuses: [
                    runs[0].status,
                    runs[1].status,
                    runs[2].status,
                    runs[3].status,
                ],
                bounded_knots: runs[1].regions.iter().map(|r| r.bounded_knots).sum(),
            });
        }
        Ok(MissSweep {
            avoidance: Some(avoidance),
            lines,
        })
    }

    /// The label of the avoidance run (`avoidance k=1`).
    pub fn avoidance_label(&self) -> String {
        self.avoidance
            .map(|m| m.label())
            .unwrap_or_else(|| "avoidance".into())
    }

    /// The sweep's figures against the miss (mm): peak joint rate (rad/s),
    /// largest position error (m) and largest orientation error (rad), one
    /// column per method.
    pub fn series(&self) -> Vec<Series> {
        if self.lines.is_empty() {
            return Vec::new();
        }
        let x: Vec<f64> = self.lines.iter().map(|l| l.miss * 1e3).collect();
        let figure = |name: &str, title: &str, y: &str, value: fn(&MethodSummary) -> f64| {
            let mut series = Series::new(name, title, "miss (mm)", y, x.clone());
            for m in 0..4 {
                let label = self.lines[0].methods()[m].0;
                let values = self.lines.iter().map(|l| value(l.methods()[m].1)).collect();
                series = series.with(label, values);
            }
            series
        };
        vec![
            figure(
                "miss_sweep_peak_rate",
                "Peak joint rate against the miss of the singular pose",
                "peak joint rate (rad/s)",
                |s| s.peak_joint_rate,
            ),
            figure(
                "miss_sweep_position_error",
                "Largest position error against the miss of the singular pose",
                "largest position error (m)",
                |s| s.max_position_error,
            ),
            figure(
                "miss_sweep_orientation_error",
                "Largest orientation error against the miss of the singular pose",
                "largest orientation error (rad)",
                |s| s.max_orientation_error,
            ),
        ]
    }

    /// The rate bound of the avoidance's knots: `eps_dq / h` (rad/s or m/s).
    pub fn rate_bound(options: &AvoidanceOptions) -> f64 {
        options.detection.joint_step_threshold / options.tracking.dt
    }

    /// The checks: the avoidance completes every line, and its peak joint
    /// rate stays within `eps_dq / h` on every line.
    pub fn checks(&self, options: &AvoidanceOptions) -> Vec<Check> {
        if self.lines.is_empty() {
            return Vec::new();
        }
        let label = self.avoidance_label();
        let detail = |value: fn(&MissLine) -> String| {
            self.lines
                .iter()
                .map(|l| format!("{:+} mm: {}", l.miss * 1e3, value(l)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let peak = self
            .lines
            .iter()
            .map(|l| l.avoidance.peak_joint_rate)
            .fold(0.0, f64::max);
        let mut bound = Check::at_most(
            format!("miss sweep: {label}'s peak joint rate on every line (eps_dq / h)"),
            peak,
            // The knots move at most eps_dq per period; the last bit covers
            // the rounding of q_fit(t + h) - q.
            Self::rate_bound(options) * (1.0 + 1e-9),
            "rad/s",
        );
        bound.detail = format!(
            "{} <= {:.4} rad/s",
            detail(|l| format!("{:.4}", l.avoidance.peak_joint_rate)),
            Self::rate_bound(options)
        );
        if !bound.passed() {
            bound.detail = format!("[exceeded] {}", bound.detail);
        }
        vec![
            Check::holds(
                format!("miss sweep: {label} completes every line"),
                self.lines
                    .iter()
                    .all(|l| l.statuses[1] == TrackingStatus::Completed),
                detail(|l| l.statuses[1].to_string()),
            ),
            bound,
        ]
    }

    /// One note: the sweep's table in words.
    pub fn notes(&self) -> Vec<String> {
        if self.lines.is_empty() {
            return Vec::new();
        }
        let rows = self
            .lines
            .iter()
            .map(|l| {
                let cells = l
                    .methods()
                    .iter()
                    .map(|(name, s)| {
                        format!(
                            "{name} {:.3} rad/s, {:.2e} m / {:.2e} rad",
                            s.peak_joint_rate, s.max_position_error, s.max_orientation_error
                        )
                    })
                    .collect::<Vec<_>>()
                    .join("; ");
                format!(
                    "{:+} mm: {cells} ({} least-squares knots)",
                    l.miss * 1e3,
                    l.bounded_knots
                )
            })
            .collect::<Vec<_>>()
            .join(" | ");
        vec![format!(
            "Lines missing the singular pose (peak joint rate, largest position / orientation \
             error; {} for the avoidance): {rows}. A knot the arm cannot reach within eps_dq per \
             period of the last is the least-squares knot, the nearest pose within that reach.",
            self.avoidance_label()
        )]
    }
}
