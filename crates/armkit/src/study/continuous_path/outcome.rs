//! What [`super::ContinuousPathStudy::outcome`] ran, and its report:
//! checks (what armkit promises), findings (the paper's claims), series.

use std::time::Duration;

use super::scope::{violation_text, PathScope};
use crate::math::rotation_angle;
use crate::study::{Check, Finding, FindingStatus, Series, StudyReport};
use crate::trajectory::CartesianTrajectory;
use crate::trajectory::{ContinuousPathReport, PathError, PathStatus, PathTolerance};
use crate::trajectory::{IkTask, LimitViolation};
use crate::trajectory::{TorqueReport, TorqueScaling, TorqueStatus};

/// One planned run of the line.
#[derive(Debug)]
pub struct PlannedPath {
    /// What the run is (the orientation law, or the variant).
    pub label: String,
    /// The timed Cartesian line it follows.
    pub path: CartesianTrajectory,
    /// The planner's report.
    pub report: ContinuousPathReport,
    /// Largest error at [`super::MEASURE_POINTS`] points inside every
    /// segment (independent of the check points).
    pub interior: PathError,
    /// Planning time (loaded machine: an upper bound).
    pub planning: Duration,
}

/// The cubic-quintic scheme on a fixed number of segments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchemeRun {
    /// Segment count.
    pub segments: usize,
    /// Whether its check points meet the tolerance.
    pub status: PathStatus,
    /// Largest error at 100 points inside every segment.
    pub interior: PathError,
    /// The recursion's growth, [`crate::trajectory::rate_amplification`]
    /// (about 1 for a stable scheme).
    pub amplification: f64,
}

/// One row of the error-against-segments sweep (fixed segmentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepRow {
    /// Segment count.
    pub segments: usize,
    /// Largest error at the segment midpoints (what Fig 6 looks at).
    pub midpoint: PathError,
    /// Largest error at 100 points inside every segment.
    pub interior: PathError,
}

/// The torque check of the planned motion.
#[derive(Clone, Debug, PartialEq)]
pub struct TorqueOutcome {
    /// The model whose inertias and limits were used.
    pub dynamics_robot: String,
    /// How many times faster the planned motion was played before the check.
    pub speed_up: f64,
    /// The planned duration, s.
    pub planned_duration: f64,
    /// Before and after the uniform slow-down.
    pub scaling: TorqueScaling,
    /// Largest relative difference between the slowed-down torques by RNEA
    /// and the scaling law `g + (tau - g) / k^2`.
    pub law_error: f64,
    /// The status 0.1 % faster than the slow-down found (`None` when no
    /// slow-down was needed).
    pub faster_status: Option<TorqueStatus>,
    /// With a separate dynamics model: the largest change of its end
    /// effector's offset from the planning model's over the knots (m + rad).
    pub model_mismatch: Option<f64>,
}

impl TorqueOutcome {
    /// Largest `|tau| / limit` over the joints with a limit (0 if none).
    pub fn worst_ratio(report: &TorqueReport) -> f64 {
        report
            .peaks
            .iter()
            .filter_map(|p| p.ratio())
            .fold(0.0, f64::max)
    }
}

/// Everything [`super::ContinuousPathStudy::outcome`] ran.
#[derive(Debug)]
pub struct ContinuousPathOutcome {
    /// The planning model's name.
    pub robot: String,
    /// What was run and is graded (`Paper` or `Armkit`, resolved).
    pub scope: PathScope,
    /// Position or pose.
    pub task: IkTask,
    /// The tolerance of every run.
    pub tolerance: PathTolerance,
    /// The IK's description.
    pub ik_method: &'static str,
    /// Check points per segment of the main run.
    pub checks_per_segment: usize,
    /// The main run.
    pub main: PlannedPath,
    /// The other orientation law (pose tasks), labelled as a comparison.
    pub other_orientation: Option<PlannedPath>,
    /// The main run's options with the paper's midpoint-only test (`None`
    /// when the main run already checks only the midpoint).
    pub midpoint_only: Option<PlannedPath>,
    /// The cubic-quintic scheme at the asked segment counts.
    pub cubic_quintic: Vec<SchemeRun>,
    /// The error against the number of segments.
    pub sweep: Vec<SweepRow>,
    /// Joint position, velocity and acceleration limit violations of the
    /// main run, sorted by start time.
    pub limit_violations: Vec<LimitViolation>,
    /// The torque check, if asked for.
    pub torques: Option<TorqueOutcome>,
    /// Seed 002's claims beyond the path: on a model of the seed's
    /// structure its closed-form inverse kinematics (eqs 10-18) and
    /// forward-kinematics example (sec 2.1); on pose tasks the reading of
    /// the orientation angles (eqs 20-22).
    pub seed002_findings: Vec<Finding>,
}

fn ratio(error: &PathError, tolerance: &PathTolerance) -> f64 {
    match *tolerance {
        PathTolerance::Position(p) => error.position / p,
        PathTolerance::Pose {
            position,
            orientation,
        } => (error.position / position).max(error.orientation / orientation),
    }
}

fn error_text(error: &PathError, task: IkTask) -> String {
    match task {
        IkTask::Position => format!("{:.3e} m", error.position),
        IkTask::Pose => format!("{:.3e} m / {:.3e} rad", error.position, error.orientation),
    }
}

impl ContinuousPathOutcome {
    /// The position tolerance, m, and the orientation one (pose tasks), rad.
    fn tolerances(&self) -> (f64, Option<f64>) {
        match self.tolerance {
            PathTolerance::Position(p) => (p, None),
            PathTolerance::Pose {
                position,
                orientation,
            } => (position, Some(orientation)),
        }
    }

    /// The tolerance in words.
    fn tolerance_text(&self) -> String {
        match self.tolerances() {
            (p, None) => format!("{p:.1e} m"),
            (p, Some(o)) => format!("{p:.1e} m / {o:.1e} rad"),
        }
    }

    /// The checks: the main run within the tolerance at its check points and
    /// at 100 points per segment, continuous at the knots, within the joint
    /// limits; the comparison run within the tolerance; the torque check.
    pub fn checks(&self) -> Vec<Check> {
        let (position, orientation) = self.tolerances();
        let main = &self.main;
        let mut checks = vec![
            Check::at_most(
                "position error at the check points",
                main.report.checked_error.position,
                position,
                "m",
            ),
            Check::at_most(
                "position error at 100 points inside every segment (measured separately)",
                main.interior.position,
                position,
                "m",
            ),
        ];
        if let Some(tolerance) = orientation {
            checks.push(Check::at_most(
                "orientation error at the check points",
                main.report.checked_error.orientation,
                tolerance,
                "rad",
            ));
            checks.push(Check::at_most(
                "orientation error at 100 points inside every segment",
                main.interior.orientation,
                tolerance,
                "rad",
            ));
        }
        let jumps = main.report.trajectory.knot_discontinuities();
        checks.push(Check::at_most(
            "largest position jump at a knot",
            jumps[0],
            1e-12,
            "rad or m",
        ));
        checks.push(Check::at_most(
            "largest velocity jump at a knot",
            jumps[1],
            1e-9,
            "rad/s or m/s",
        ));
        let status = main.report.status;
        checks.push(Check::holds(
            "the plan meets the tolerance at every check point",
            status == PathStatus::ToleranceMet,
            format!(
                "{status} with {} segments ({} check point(s) per segment, tolerance {}, largest error {})",
                main.report.trajectory.segment_count(),
                self.checks_per_segment,
                self.tolerance_text(),
                error_text(&main.report.checked_error, self.task)
            ),
        ));
        let violations = &self.limit_violations;
        let mut detail: Vec<String> = violations.iter().take(3).map(violation_text).collect();
        if violations.len() > 3 {
            detail.push(format!("{} more", violations.len() - 3));
        }
        checks.push(Check::holds(
            "within the robot's joint position, velocity and acceleration limits",
            violations.is_empty(),
            if violations.is_empty() {
                "no violation".to_string()
            } else {
                format!("{} violation(s): {}", violations.len(), detail.join("; "))
            },
        ));
        if let Some(other) = &self.other_orientation {
            checks.push(Check::holds(
                format!("{}: tolerance met at the check points", other.label),
                other.report.status == PathStatus::ToleranceMet,
                format!(
                    "{}, {} segments, {}",
                    other.report.status,
                    other.report.trajectory.segment_count(),
                    error_text(&other.report.checked_error, self.task)
                ),
            ));
        }
        if let Some(torques) = &self.torques {
            checks.extend(torque_checks(torques));
        }
        checks
    }

    /// The paper's claims this run touches, each with its figures.
    pub fn findings(&self) -> Vec<Finding> {
        let mut findings = Vec::new();
        if self.scope == PathScope::Armkit {
            return findings;
        }
        if let Some(finding) = self.orientation_finding() {
            findings.push(finding);
        }
        findings.push(self.midpoint_finding());
        if let Some(finding) = self.sweep_finding() {
            findings.push(finding);
        }
        if let Some(finding) = self.cubic_quintic_finding() {
            findings.push(finding);
        }
        findings.extend(self.seed002_findings.iter().cloned());
        let jumps = self.main.report.trajectory.knot_discontinuities();
        if self.main.report.trajectory.segment_count() >= 2 {
            findings.push(Finding::new(
                "seed 002, eqs 23-28: the via-velocity scheme (quartic ends, cubic middles) moves every \
                 joint with continuous position and velocity",
                format!(
                    "largest jumps at the {} knots: position {:.1e}, velocity {:.1e}; acceleration jumps by \
                     up to {:.3e} (the scheme is C1, as the paper's constraints make it)",
                    self.main.report.trajectory.segment_count() - 1,
                    jumps[0],
                    jumps[1],
                    jumps[2]
                ),
                FindingStatus::from_holds(jumps[0] <= 1e-12 && jumps[1] <= 1e-9),
            ));
        }
        findings
    }

    fn orientation_finding(&self) -> Option<Finding> {
        let other = self.other_orientation.as_ref()?;
        let (paper, slerp) = if self.main.label.starts_with("paper") {
            (&self.main, other)
        } else {
            (other, &self.main)
        };
        let tolerance = &self.tolerance;
        let holds = paper.report.status == PathStatus::ToleranceMet
            && ratio(&paper.interior, tolerance) <= 1.0;
        Some(Finding::new(
            "seed 002, eqs 20-22: the orientation angles move linearly in time from the start's to the goal's, \
             and the continuous-path method follows them within the tolerance",
            format!(
                "angles linear in time: {}, {} segments, error at 100 points per segment {} (tolerance {}); \
                 slerp (comparison, not the paper's): {} segments, {}; the two orientation laws part by up to \
                 {:.3e} rad",
                paper.report.status,
                paper.report.trajectory.segment_count(),
                error_text(&paper.interior, self.task),
                self.tolerance_text(),
                slerp.report.trajectory.segment_count(),
                error_text(&slerp.interior, self.task),
                orientation_gap(&paper.path, &slerp.path)
            ),
            FindingStatus::from_holds(holds),
        ))
    }

    fn midpoint_finding(&self) -> Finding {
        let midpoint = self.midpoint_only.as_ref().unwrap_or(&self.main);
        let factor = ratio(&midpoint.interior, &self.tolerance);
        let mut measured = format!(
            "the midpoint-only test stops at {} segments ({}) with midpoint errors <= {}, but the error at \
             100 points per segment is {} ({factor:.1}x the tolerance)",
            midpoint.report.trajectory.segment_count(),
            midpoint.report.status,
            error_text(&midpoint.report.checked_error, self.task),
            error_text(&midpoint.interior, self.task),
        );
        if self.midpoint_only.is_some() {
            measured += &format!(
                "; armkit's check points ({} segments) leave {}",
                self.main.report.trajectory.segment_count(),
                error_text(&self.main.interior, self.task)
            );
        }
        Finding::new(
            "seed 002, Fig 6: inserting midpoints until every segment's midpoint is within the tolerance \
             brings the whole path within it",
            measured,
            FindingStatus::from_holds(midpoint.report.status == PathStatus::ToleranceMet && factor <= 1.0),
        )
    }

    fn sweep_finding(&self) -> Option<Finding> {
        if self.sweep.len() < 2 {
            return None;
        }
        let errors: Vec<f64> = self.sweep.iter().map(|r| r.interior.position).collect();
        let falling = errors.windows(2).all(|w| w[1] < w[0]);
        let (first, last) = (self.sweep[0], self.sweep[self.sweep.len() - 1]);
        let order = (first.interior.position / last.interior.position).ln()
            / (last.segments as f64 / first.segments as f64).ln();
        let rows: Vec<String> = self
            .sweep
            .iter()
            .map(|r| format!("n = {}: {:.3e} m", r.segments, r.interior.position))
            .collect();
        Some(Finding::new(
            "seed 002, sec 3: the larger the number of segments n, the more precise the interpolation",
            format!(
                "position error at 100 points per segment, {}; {} with every larger n; error ~ n^-{order:.2} \
                 from n = {} to {}",
                rows.join(", "),
                if falling { "falls" } else { "does not fall" },
                first.segments,
                last.segments
            ),
            FindingStatus::from_holds(falling),
        ))
    }

    fn cubic_quintic_finding(&self) -> Option<Finding> {
        if self.cubic_quintic.is_empty() {
            return None;
        }
        let within = |r: &SchemeRun| ratio(&r.interior, &self.tolerance) <= 1.0;
        let rows: Vec<String> = self
            .cubic_quintic
            .iter()
            .map(|r| {
                format!(
                    "n = {}: error {} ({:.1}x the tolerance), rate amplification {:.3e}",
                    r.segments,
                    error_text(&r.interior, self.task),
                    ratio(&r.interior, &self.tolerance),
                    r.amplification
                )
            })
            .collect();
        let status = if self.cubic_quintic.iter().all(within) {
            FindingStatus::Reproduced
        } else if within(&self.cubic_quintic[0]) {
            FindingStatus::ReproducedWithDeviation
        } else {
            FindingStatus::NotReproduced
        };
        Some(Finding::new(
            "seed 002, sec 3: cubic segments with a quintic last one (no via-velocity constraints) plan the \
             continuous path, finer with more segments",
            format!(
                "{}; the recursion multiplies the carried rate errors by up to 3.73 per segment, so more \
                 segments make it worse",
                rows.join("; ")
            ),
            status,
        ))
    }

    /// The error against the number of segments (log10 of the position
    /// errors, m), and the torques.
    pub fn series(&self) -> Vec<Series> {
        let mut series = Vec::new();
        if !self.sweep.is_empty() {
            // log10 of the errors: they span four decades over n = 2..64.
            let (tolerance, _) = self.tolerances();
            let log = |f: fn(&SweepRow) -> f64| self.sweep.iter().map(|r| f(r).log10()).collect();
            series.push(
                Series::new(
                    "error_vs_segments",
                    "Seed 002: path error against the number of segments (log10)",
                    "segments n",
                    "log10 of the largest position error (m)",
                    self.sweep.iter().map(|r| r.segments as f64).collect(),
                )
                .with("at 100 points per segment", log(|r| r.interior.position))
                .with(
                    "at the segment midpoints (Fig 6)",
                    log(|r| r.midpoint.position),
                )
                .with("tolerance", vec![tolerance.log10(); self.sweep.len()]),
            );
        }
        if let Some(torques) = &self.torques {
            series.push(torque_series(
                "torques",
                &format!("{}: joint torques as played", torques.dynamics_robot),
                &torques.scaling.before,
            ));
            series.push(torque_series(
                "torques_scaled",
                &format!(
                    "{}: joint torques after the uniform slow-down (x{:.4})",
                    torques.dynamics_robot, torques.scaling.factor
                ),
                &torques.scaling.after,
            ));
        }
        series
    }

    /// Plain statements: what each run is.
    pub fn notes(&self) -> Vec<String> {
        let mut notes = vec![];
        if self.scope == PathScope::Armkit {
            notes.push(format!(
                "The line is planned with the {} and {} check point(s) per segment; the error at 100 points \
                 per segment is measured separately. Graded: armkit's promises only (seed 002's variants and \
                 claims run with scope = \"paper\").",
                self.main.label, self.checks_per_segment
            ));
        } else {
            notes.push(format!(
            "The main run uses the {} and {} check point(s) per segment; the error at 100 points per segment is \
             measured separately. Seed 002 checks only each segment's midpoint (Fig 6): with eq 23's \
             backward-difference via velocities the error vanishes near the midpoint and peaks near the quarter \
             points.",
                self.main.label, self.checks_per_segment
            ));
        }
        if let Some(other) = &self.other_orientation {
            notes.push(format!(
                "\"{}\": the same line and options with the other orientation law, for comparison.",
                other.label
            ));
        }
        if let Some(torques) = &self.torques {
            notes.push(format!(
                "Torques by inverse dynamics (RNEA, gravity 9.81 m/s^2 along -z) on {}, {} samples{}. A uniform \
                 slow-down by k divides the motion's part of the torques by k^2 and keeps gravity's.",
                torques.dynamics_robot,
                torques.scaling.before.times.len(),
                if torques.speed_up == 1.0 {
                    String::new()
                } else {
                    format!(
                        "; the planned {:.3} s motion is played {} times faster first, to ask how fast the path \
                         can run under the torque limits alone (the joint velocity limits are checked on the \
                         planned motion only)",
                        torques.planned_duration, torques.speed_up
                    )
                }
            ));
        }
        notes
    }

    /// The study's report.
    pub fn report(&self) -> StudyReport {
        StudyReport {
            checks: self.checks(),
            findings: self.findings(),
            series: self.series(),
            notes: self.notes(),
        }
    }
}

/// The largest angle between the orientations of two timed paths, rad, at
/// 201 evenly spaced times.
fn orientation_gap(a: &CartesianTrajectory, b: &CartesianTrajectory) -> f64 {
    (0..=200)
        .map(|k| {
            let t = a.start_time() + a.duration() * k as f64 / 200.0;
            let (ra, rb) = (a.pose_at(t).rotation, b.pose_at(t).rotation);
            rotation_angle(&(ra * rb.transpose()))
        })
        .fold(0.0, f64::max)
}

fn torque_checks(torques: &TorqueOutcome) -> Vec<Check> {
    let after = &torques.scaling.after;
    // The slow-down is defined to meet the limits: those two hold by
    // construction; the scaling law and the smallest factor are tested.
    let mut checks = vec![
        Check::at_most(
            format!(
                "largest |tau| / limit after the uniform slow-down (x{:.4})",
                torques.scaling.factor
            ),
            TorqueOutcome::worst_ratio(after),
            1.0,
            "",
        )
        .invariant(),
        Check::holds(
            "every joint with a torque limit stays within it after the slow-down",
            after.status == TorqueStatus::WithinLimits,
            format!("{}", after.status),
        )
        .invariant(),
        Check::at_most(
            "slowed-down torques by RNEA against g + (tau - g) / k^2 (relative, samples off the knots)",
            torques.law_error,
            1e-9,
            "",
        ),
    ];
    if let Some(status) = torques.faster_status {
        checks.push(Check::holds(
            "0.1 % faster than the slow-down found exceeds a limit (the factor is the smallest)",
            status == TorqueStatus::ExceedsLimits,
            format!("{status}"),
        ));
    }
    if let Some(mismatch) = torques.model_mismatch {
        checks.push(Check::at_most(
            format!(
                "{}'s joints move as the planning model's (change of the end-effector offset over the knots)",
                torques.dynamics_robot
            ),
            mismatch,
            1e-9,
            "m + rad",
        ));
    }
    checks
}

fn torque_series(name: &str, title: &str, report: &TorqueReport) -> Series {
    let mut series = Series::new(name, title, "t (s)", "tau (N m or N)", report.times.clone());
    for (j, peak) in report.peaks.iter().enumerate() {
        series = series.with(
            format!("joint {} ({})", j + 1, peak.name),
            report.torques.iter().map(|tau| tau[j]).collect(),
        );
    }
    series
}
