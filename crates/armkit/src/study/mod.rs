//! Seed studies as library values: what a study checks, the series it
//! plots, and its notes ([`StudyReport`]).
//!
//! Each seed study is a type with plain options (serde with the `io`
//! feature) and `run() -> Result<StudyReport>`: the CLI's scenarios and
//! commands map their flags onto those options and only format the report.
//! One file per study:
//!
//! | study | seed | what it reproduces |
//! |---|---|---|
//! | [`BeamTableStudy`] | 000, sec 3.1 | Table 1: beam deflection under two carriages, to the printed digits; where the beam bends most |
//! | [`MpcExampleStudy`] | 000, sec 4.4 | the MPC examples on the flexible gantry |
//! | [`DistributionStudy`] | 001 (+ 000's priorities) | one motion distributed four ways, energy measure eq 9 |
//! | [`ContinuousPathStudy`] | 002, sec 3 | a line by the continuous-path method, Fig 6's segmentation, the paper's variants, torques |
//! | [`AvoidanceStudy`] | 004, sec 2 | singularity avoidance vs plain, DLS, SRI, separation [9] (Table 1, Figs 5-8) |
//! | [`SpaceRobotStudy`] | 004, sec 1 | the free-floating space robot: momenta, centre of mass, `J*` |
//!
//! ```
//! use armkit::study::{Check, StudyReport};
//! let mut report = StudyReport::default();
//! report.checks.push(Check::at_most("position error", 2e-4, 1e-3, "m"));
//! report.checks.push(Check::holds("the run completes", true, "completed"));
//! assert!(report.all_passed());
//! assert_eq!(report.checks[0].to_string(), "[pass] position error: 2.000e-4 m <= 1.000e-3 m");
//! ```

use std::fmt;

mod avoidance;
mod beam_table;
mod continuous_path;
mod distribution;
mod finding;
mod mpc_examples;
mod space_robot;

pub use avoidance::{
    interpolating_polynomial_rate, AsPrintedLine, AvoidanceOutcome, AvoidanceStudy, EpsRegion,
    MissLine, MissSweep, ThresholdRule, FITTED_DETERMINANT_THRESHOLD, SEED004_EPS_SWEEP,
    SEED004_MISS_SWEEP,
};
pub use beam_table::{
    BeamTableStudy, Table1Row, TABLE1_ROUNDING, TABLE1_SIMULATION, TABLE1_SPAN_GRID,
    TABLE1_TOLERANCE,
};
pub use continuous_path::{
    violation_text, BoundaryKind, ContinuousPathOutcome, ContinuousPathStudy, IkKind, LawKind,
    OrientationKind, PathGoal, PathScope, PlannedPath, SchemeKind, SchemeRun, SweepRow, TaskKind,
    TorqueOutcome, TorqueStudy, ARM4_LINE_END, ARM4_LINE_START, MEASURE_POINTS,
};
pub use distribution::{
    DistributionOutcome, DistributionStudy, DurationPoint, DurationSweep, FormulationKind,
    InstantComparison, InstantRival, ResolvedDistribution, SecondaryKind, TorqueEnergies,
    ZeroWeightLock, DISTRIBUTION_NOTE, DURATION_FACTORS, MODERATE_SPEED_MARGIN, VARIANT_NAME,
};
pub use finding::{count_findings, Finding, FindingCounts, FindingStatus};
pub use mpc_examples::{
    ExampleCheck, MpcExampleStudy, PrismaticSettling, Seed000Example, DIRECTION_FLOOR,
    OSCILLATION_DIRECTION_CHANGES, REACHED_TOLERANCE, SEED000_PRIORITIES,
    SEED000_SPREAD_PRIORITIES, SEED000_START,
};
pub use space_robot::{SpaceRobotStudy, SPACE6R_START};

/// How a check's value is compared with its threshold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// Passes when `value <= threshold`.
    AtMost,
    /// Passes when `value >= threshold`.
    AtLeast,
}

impl Comparison {
    /// `<=` or `>=`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Comparison::AtMost => "<=",
            Comparison::AtLeast => ">=",
        }
    }
}

impl fmt::Display for Comparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What a check's passing tells.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CheckKind {
    /// It tests a result: it could fail if the method or the claim were
    /// wrong.
    #[default]
    Evidence,
    /// It holds by construction of the implementation (a base placed to keep
    /// the centre of mass, a bound the knots enforce, a plan kept only where
    /// it is better): kept as a test of the code, listed apart, never
    /// evidence for a paper's claim.
    Invariant,
}

/// One verifiable claim of a study: a measured value against a threshold.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is checked, in words.
    pub name: String,
    /// The measured value.
    pub value: f64,
    /// The threshold it is compared with.
    pub threshold: f64,
    /// How.
    pub comparison: Comparison,
    /// Unit of value and threshold (may be empty).
    pub unit: String,
    /// The measured figures in words, for checks that are a yes/no claim
    /// (may be empty).
    pub detail: String,
    /// Evidence or an invariant of the implementation.
    pub kind: CheckKind,
}

impl Check {
    /// A check that passes when `value <= threshold`.
    pub fn at_most(name: impl Into<String>, value: f64, threshold: f64, unit: &str) -> Self {
        Check {
            name: name.into(),
            value,
            threshold,
            comparison: Comparison::AtMost,
            unit: unit.into(),
            detail: String::new(),
            kind: CheckKind::Evidence,
        }
    }

    /// The same check marked as an invariant of the implementation
    /// ([`CheckKind::Invariant`]): true by construction, not evidence.
    pub fn invariant(mut self) -> Self {
        self.kind = CheckKind::Invariant;
        self
    }

    /// True for an invariant of the implementation.
    pub fn is_invariant(&self) -> bool {
        self.kind == CheckKind::Invariant
    }

    /// A check that passes when `value >= threshold`.
    pub fn at_least(name: impl Into<String>, value: f64, threshold: f64, unit: &str) -> Self {
        Check {
            comparison: Comparison::AtLeast,
            ..Check::at_most(name, value, threshold, unit)
        }
    }

    /// A yes/no claim: value 1 when it holds, 0 when not, threshold 1, with
    /// the figures behind it in `detail`.
    pub fn holds(name: impl Into<String>, holds: bool, detail: impl Into<String>) -> Self {
        let mut check = Check::at_least(name, if holds { 1.0 } else { 0.0 }, 1.0, "");
        check.detail = detail.into();
        check
    }

    /// True when the value meets the threshold (NaN never does).
    pub fn passed(&self) -> bool {
        match self.comparison {
            Comparison::AtMost => self.value <= self.threshold,
            Comparison::AtLeast => self.value >= self.threshold,
        }
    }
}

/// `[pass] name: value unit <= threshold unit`, or `[fail] name: detail`
/// for a yes/no claim.
impl fmt::Display for Check {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verdict = if self.passed() { "pass" } else { "fail" };
        if !self.detail.is_empty() {
            return write!(f, "[{verdict}] {}: {}", self.name, self.detail);
        }
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        write!(
            f,
            "[{verdict}] {}: {:.3e}{unit} {} {:.3e}{unit}",
            self.name, self.value, self.comparison, self.threshold
        )
    }
}

/// A plotted series set: columns of values against one abscissa.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Series {
    /// File stem (letters, digits, `_`): the CLI writes `<name>.csv` and `.svg`.
    pub name: String,
    /// Title of the figure.
    pub title: String,
    /// Label of the abscissa, with its unit.
    pub x_label: String,
    /// Label of the ordinate, with its unit.
    pub y_label: String,
    /// The abscissa.
    pub x: Vec<f64>,
    /// `(label, values)`, each as long as `x`.
    pub columns: Vec<(String, Vec<f64>)>,
}

impl Series {
    /// An empty series set over `x`.
    pub fn new(
        name: impl Into<String>,
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        x: Vec<f64>,
    ) -> Self {
        Series {
            name: name.into(),
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x,
            columns: Vec::new(),
        }
    }

    /// The same set with one more column.
    pub fn with(mut self, label: impl Into<String>, values: Vec<f64>) -> Self {
        self.columns.push((label.into(), values));
        self
    }

    /// The column labelled `label`.
    pub fn column(&self, label: &str) -> Option<&[f64]> {
        self.columns
            .iter()
            .find(|(l, _)| l == label)
            .map(|(_, v)| v.as_slice())
    }
}

/// What a study produced: its checks (what armkit promises; each must
/// pass), its findings (the paper's claims and whether they hold here, kept
/// apart from the checks), the series behind its figures, and plain
/// statements.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct StudyReport {
    /// The checks, each pass or fail.
    pub checks: Vec<Check>,
    /// The paper's claims, each reproduced, reproduced with a deviation, or
    /// not reproduced.
    pub findings: Vec<Finding>,
    /// The figures' data.
    pub series: Vec<Series>,
    /// Notes shown with the report.
    pub notes: Vec<String>,
}

impl StudyReport {
    /// Number of checks that pass.
    pub fn passed(&self) -> usize {
        self.checks.iter().filter(|c| c.passed()).count()
    }

    /// True when every check passes.
    pub fn all_passed(&self) -> bool {
        self.passed() == self.checks.len()
    }

    /// The check named `name`.
    pub fn check(&self, name: &str) -> Option<&Check> {
        self.checks.iter().find(|c| c.name == name)
    }

    /// The series set named `name`.
    pub fn series(&self, name: &str) -> Option<&Series> {
        self.series.iter().find(|s| s.name == name)
    }
}
