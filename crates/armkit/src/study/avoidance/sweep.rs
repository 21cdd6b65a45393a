//! The miss sweep of seed 004's study: parallel lines that pass through the
//! singular pose or miss it by a little, each tracked by plain resolved
//! rate, the avoidance (its regions planned jointly, and the greedy plan as
//! a labelled comparison), DLS, DLS clamped to the joint speed bound, SRI
//! and the singularity separation with a damped reciprocal (the paper's
//! reference [9]), with the error floor of a wrist-branch switch on each line.

use super::{place, AvoidanceStudy};
use crate::error::Result;
use crate::kinematics::Data;
use crate::singularity::{
    classify, line_through, AvoidanceOptions, Baselines, ClassifyOptions, Manipulator, Method,
    MethodSummary, PathTracker, RegionPlan, SingularGap, SingularityKind, SEPARATION,
};
use crate::study::{Check, Series};
use crate::tracking::TrackingStatus;

/// The misses of seed 004's sweep (m and rad, along the direction the
/// Jacobian loses at the singular pose): through it, and 1, 3, 10 and 30 mm
/// either side.
pub const SEED004_MISS_SWEEP: [f64; 9] =
    [-0.03, -0.01, -0.003, -0.001, 0.0, 0.001, 0.003, 0.01, 0.03];

/// The wrist's middle joint (`q5`, 0-based 4) of a PUMA-type 6R arm: its
/// zero is the wrist singularity.
const WRIST_JOINT: usize = 4;
/// Half-width of the time window around mid-path where the floor is
/// sought, s (the lines pass the singular pose at mid-path).
const FLOOR_WINDOW: f64 = 1.0;

/// True when `through` is a wrist singularity of the manipulator's arm
/// (6 joints, [`classify`] names it).
fn is_wrist_singular(manipulator: &Manipulator<'_>, through: &[f64]) -> Result<bool> {
    let arm = manipulator.arm();
    if arm.dof() != 6 || through.len() != 6 {
        return Ok(false);
    }
    let classification = classify(
        arm,
        &mut Data::new(arm),
        through,
        &ClassifyOptions::default(),
    )?;
    Ok(classification.kinds.contains(&SingularityKind::Wrist))
}

/// One line of the miss sweep: every method's summary and status.
#[derive(Clone, Debug, PartialEq)]
pub struct MissLine {
    /// Offset of the line from the singular pose (m and rad).
    pub miss: f64,
    /// Plain resolved rate.
    pub plain: MethodSummary,
    /// Seed 004's avoidance with the study's first `k`, its regions planned
    /// jointly ([`RegionPlan::Joint`]).
    pub avoidance: MethodSummary,
    /// The same avoidance with the greedy region plan ([`RegionPlan::Greedy`]),
    /// a labelled comparison.
    pub avoidance_greedy: MethodSummary,
    /// Damped least squares (Nakamura).
    pub damped_least_squares: MethodSummary,
    /// Damped least squares with its rates scaled to the joint speed bound
    /// `eps_dq / h` ([`Method::ClampedDampedLeastSquares`]).
    pub clamped_damped_least_squares: MethodSummary,
    /// Singularity-robust inverse (Chiaverini).
    pub singularity_robust: MethodSummary,
    /// Singularity separation with a damped reciprocal
    /// ([`Method::SeparatedDampedReciprocal`], seed 004's reference [9]).
    pub separation: MethodSummary,
    /// Status of each method, in the order of [`MissLine::methods`].
    pub statuses: [TrackingStatus; 7],
    /// Least-squares knots of the avoidance's regions (knots the arm could
    /// not reach within `eps_dq` per period).
    pub bounded_knots: usize,
    /// Regions whose joint plan was kept (it lowered the greedy plan's
    /// largest error).
    pub joint_planned_regions: usize,
    /// The error floor of a wrist-branch switch: the distance from the
    /// line to the wrist-singular poses ([`PathTracker::singular_gap`] with
    /// joint 5 held at its value in the study's `through`); `None` when
    /// `through` is not a wrist singularity.
    pub floor: Option<SingularGap>,
}

impl MissLine {
    /// `(label, summary)` of plain, avoidance, avoidance greedy, dls,
    /// dls clamped, sri, separation.
    pub fn methods(&self) -> [(&'static str, &MethodSummary); 7] {
        [
            ("plain", &self.plain),
            ("avoidance", &self.avoidance),
            ("avoidance greedy", &self.avoidance_greedy),
            ("dls", &self.damped_least_squares),
            ("dls clamped", &self.clamped_damped_least_squares),
            ("sri", &self.singularity_robust),
            (SEPARATION, &self.separation),
        ]
    }

    /// True when the avoidance's largest position and orientation errors
    /// are at most `other`'s.
    pub fn avoidance_errs_no_more_than(&self, other: &MethodSummary) -> bool {
        self.avoidance.max_position_error <= other.max_position_error
            && self.avoidance.max_orientation_error <= other.max_orientation_error
    }

    /// Largest 6-vector error (m and rad) of the avoidance, and of the
    /// greedy plan: `max |e|` over the samples.
    pub fn plan_errors(&self) -> (f64, f64) {
        (
            self.avoidance.max_pose_error,
            self.avoidance_greedy.max_pose_error,
        )
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
    /// Tracks every line of `study.miss_sweep` with every method
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
        let clamped = Method::ClampedDampedLeastSquares {
            damping: baselines.nakamura,
            max_rate: Self::rate_bound(&options),
        };
        let greedy_options = AvoidanceOptions {
            region_plan: RegionPlan::Greedy,
            ..options
        };
        let wrist = is_wrist_singular(&manipulator, &study.through)?;
        let mut lines = Vec::with_capacity(study.miss_sweep.len());
        for &miss in &study.miss_sweep {
            let line = line_through(&manipulator, &study.through, &study.direction, miss)?;
            let placed = place(manipulator, &line);
            let task = line.task(study.duration, study.acceleration_time);
            let tracker = PathTracker::new(placed, task.clone(), options)?;
            let greedy = PathTracker::new(placed, task, greedy_options)?;
            let runs = [
                tracker.run(&Method::Plain)?,
                tracker.run(&avoidance)?,
                greedy.run(&avoidance)?,
                tracker.run(&Method::DampedLeastSquares(baselines.nakamura))?,
                tracker.run(&clamped)?,
                tracker.run(&Method::SingularityRobust(baselines.chiaverini))?,
                tracker.run(&Method::SeparatedDampedReciprocal(baselines.reciprocal))?,
            ];
            let floor = if wrist {
                Some(tracker.singular_gap(
                    WRIST_JOINT,
                    study.through[WRIST_JOINT],
                    &study.through,
                    0.5 * study.duration,
                    FLOOR_WINDOW,
                )?)
            } else {
                None
            };
            lines.push(MissLine {
                miss,
                plain: runs[0].summary,
                avoidance: runs[1].summary,
                avoidance_greedy: runs[2].summary,
                damped_least_squares: runs[3].summary,
                clamped_damped_least_squares: runs[4].summary,
                singularity_robust: runs[5].summary,
                separation: runs[6].summary,
                statuses: std::array::from_fn(|m| runs[m].status),
                bounded_knots: runs[1].regions.iter().map(|r| r.bounded_knots).sum(),
                joint_planned_regions: runs[1]
                    .regions
                    .iter()
                    .filter(|r| r.plan == RegionPlan::Joint)
                    .count(),
                floor,
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
    /// largest position error (m), largest orientation error (rad) and
    /// largest 6-vector pose error (m and rad, with the floor of a
    /// wrist-branch switch), one column per method.
    pub fn series(&self) -> Vec<Series> {
        let Some(first) = self.lines.first() else {
            return Vec::new();
        };
        let x: Vec<f64> = self.lines.iter().map(|l| l.miss * 1e3).collect();
        let figure = |name: &str, title: &str, y: &str, value: fn(&MethodSummary) -> f64| {
            let mut series = Series::new(name, title, "miss (mm)", y, x.clone());
            for m in 0..first.methods().len() {
                let label = first.methods()[m].0;
                let values = self.lines.iter().map(|l| value(l.methods()[m].1)).collect();
                series = series.with(label, values);
            }
            series
        };
        let mut pose = figure(
            "miss_sweep_pose_error",
            "Largest pose error (position and rotation vector together) against the miss",
            "largest pose error (m and rad)",
            |s| s.max_pose_error,
        );
        if self.lines.iter().all(|l| l.floor.is_some()) {
            pose = pose.with(
                "floor (branch switch)",
                self.lines
                    .iter()
                    .map(|l| l.floor.map_or(f64::NAN, |f| f.norm))
                    .collect(),
            );
        }
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
            pose,
        ]
    }

    /// The rate bound of the avoidance's knots: `eps_dq / h` (rad/s or m/s).
    pub fn rate_bound(options: &AvoidanceOptions) -> f64 {
        options.detection.joint_step_threshold / options.tracking.dt
    }

    /// `-30 mm: a, -10 mm: b, ...`.
    fn per_line(&self, value: impl Fn(&MissLine) -> String) -> String {
        self.lines
            .iter()
            .map(|l| format!("{:+} mm: {}", l.miss * 1e3, value(l)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The checks: the avoidance completes every line, its peak joint rate
    /// stays within `eps_dq / h` on every line (no knot dropped: every knot
    /// is kept within that bound), and its joint region plan errs no more
    /// than the greedy plan on any line.
    pub fn checks(&self, options: &AvoidanceOptions) -> Vec<Check> {
        if self.lines.is_empty() {
            return Vec::new();
        }
        let label = self.avoidance_label();
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
            self.per_line(|l| format!("{:.4}", l.avoidance.peak_joint_rate)),
            Self::rate_bound(options)
        );
        if !bound.passed() {
            bound.detail = format!("[exceeded] {}", bound.detail);
        }
        // The joint plan is kept only where it lowers the greedy plan's
        // largest knot error; the run's largest error then cannot grow.
        let ratio = self
            .lines
            .iter()
            .map(|l| {
                let (joint, greedy) = l.plan_errors();
                if greedy > 0.0 {
                    joint / greedy
                } else {
                    1.0
                }
            })
            .fold(0.0, f64::max);
        let mut plan = Check::at_most(
            format!(
                "miss sweep: {label}'s joint region plan errs no more than the greedy plan \
                 (largest pose error, joint / greedy)"
            ),
            ratio,
            1.0 + 1e-9,
            "",
        );
        plan.detail = self.per_line(|l| {
            let (joint, greedy) = l.plan_errors();
            format!("{joint:.2e} / {greedy:.2e}")
        });
        vec![
            Check::holds(
                format!("miss sweep: {label} completes every line"),
                self.lines
                    .iter()
                    .all(|l| l.statuses[1] == TrackingStatus::Completed),
                self.per_line(|l| l.statuses[1].to_string()),
            ),
            // The knots enforce the bound and the joint plan is kept only
            // where it is better: both hold by construction.
            bound.invariant(),
            plan.invariant(),
        ]
    }

    /// One note: how to read the sweep (its figures are in [`Self::lines`],
    /// which a report shows as a table; the note does not repeat them).
    pub fn notes(&self) -> Vec<String> {
        if self.lines.is_empty() {
            return Vec::new();
        }
        vec![format!(
            "Lines missing the singular pose by {} distances (their peak joint rates and largest errors, \
             {} for the avoidance, are in the table of that name). A region the arm cannot follow exactly \
             (least-squares knots: the nearest pose within eps_dq per period) is planned jointly: all its \
             knots chosen together to minimise the largest error under the joint-step bound, from the \
             greedy knots, kept where it errs less ('avoidance greedy': the knot-by-knot plan). The floor \
             is the distance from the line to the wrist-singular poses (q5 held at 0): the error of any \
             plan that switches wrist branch, as a rate-bounded plan must on a near miss.",
            self.lines.len(),
            self.avoidance_label()
        )]
    }
}
