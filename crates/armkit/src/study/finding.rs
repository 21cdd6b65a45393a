//! A paper's claim and how it fared when armkit ran it: kept apart from the
//! checks, which are what armkit promises and must all pass.

use std::fmt;

/// How a paper's claim fared in armkit's run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "snake_case"))]
pub enum FindingStatus {
    /// The claim holds here as the paper states it.
    Reproduced,
    /// The claim holds here with a deviation the finding states (a
    /// different constant, a weaker margin, another setting).
    ReproducedWithDeviation,
    /// The claim does not hold here; the finding gives the figures.
    NotReproduced,
    /// armkit does not test the claim; the finding's text says why (a
    /// method armkit does not run, data the paper does not print).
    NotAttempted,
}

impl FindingStatus {
    /// `reproduced`, `reproduced with deviation`, `not reproduced` or `not
    /// attempted`.
    pub fn as_str(&self) -> &'static str {
        match self {
            FindingStatus::Reproduced => "reproduced",
            FindingStatus::ReproducedWithDeviation => "reproduced with deviation",
            FindingStatus::NotReproduced => "not reproduced",
            FindingStatus::NotAttempted => "not attempted",
        }
    }

    /// `Reproduced` when the claim holds as measured, `NotReproduced` when
    /// not.
    ///
    /// ```
    /// use armkit::study::FindingStatus;
    /// assert_eq!(FindingStatus::from_holds(true), FindingStatus::Reproduced);
    /// assert_eq!(FindingStatus::from_holds(false), FindingStatus::NotReproduced);
    /// let deviation = FindingStatus::ReproducedWithDeviation;
    /// assert_eq!(deviation.if_holds(true), deviation);
    /// assert_eq!(deviation.if_holds(false), FindingStatus::NotReproduced);
    /// ```
    pub fn from_holds(holds: bool) -> Self {
        FindingStatus::Reproduced.if_holds(holds)
    }

    /// `self` when the claim holds as measured (e.g. `ReproducedWithDeviation`
    /// for a claim that holds only with a stated deviation), `NotReproduced`
    /// when not.
    pub fn if_holds(self, holds: bool) -> Self {
        if holds {
            self
        } else {
            FindingStatus::NotReproduced
        }
    }
}

impl fmt::Display for FindingStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One claim of a paper, what armkit measured, and the verdict.
///
/// ```
/// use armkit::study::{Finding, FindingStatus};
/// let finding = Finding::new(
///     "seed 000, Fig 5 text: the largest deflection is under the loads",
///     "mid-span 0.005289 m > under the loads 0.004574 m",
///     FindingStatus::NotReproduced,
/// );
/// assert_eq!(
///     finding.to_string(),
///     "[not reproduced] seed 000, Fig 5 text: the largest deflection is under the loads: \
///      mid-span 0.005289 m > under the loads 0.004574 m"
/// );
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// The paper's claim, with where it is stated (seed, section, figure).
    pub claim: String,
    /// armkit's figures behind the verdict (and the paper's, where printed).
    pub measured: String,
    /// The verdict.
    pub status: FindingStatus,
    /// Where the same evidence is already counted (a scenario or a claim),
    /// when this finding restates it: shown, never counted twice.
    pub same_evidence_as: Option<String>,
}

impl Finding {
    /// A finding from its claim, the measured figures and the verdict.
    pub fn new(
        claim: impl Into<String>,
        measured: impl Into<String>,
        status: FindingStatus,
    ) -> Self {
        Finding {
            claim: claim.into(),
            measured: measured.into(),
            status,
            same_evidence_as: None,
        }
    }

    /// The same finding marked as restating the evidence counted at
    /// `counted_at` (a scenario or a claim): [`count_findings`] skips it.
    pub fn same_evidence_as(mut self, counted_at: impl Into<String>) -> Self {
        self.same_evidence_as = Some(counted_at.into());
        self
    }
}

/// `[status] claim: measured`.
impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}] {}: {}", self.status, self.claim, self.measured)
    }
}

/// How many independent findings have each status; findings marked
/// [`Finding::same_evidence_as`] are counted apart, in `duplicates`.
///
/// ```
/// use armkit::study::{count_findings, Finding, FindingStatus};
/// let findings = [
///     Finding::new("a", "x", FindingStatus::Reproduced),
///     Finding::new("a", "x", FindingStatus::Reproduced).same_evidence_as("scenario-1"),
///     Finding::new("b", "no model", FindingStatus::NotAttempted),
/// ];
/// let counts = count_findings(&findings);
/// assert_eq!((counts.reproduced, counts.not_attempted, counts.duplicates), (1, 1, 1));
/// assert_eq!(counts.independent(), 2);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FindingCounts {
    /// Reproduced as stated.
    pub reproduced: usize,
    /// Reproduced with a stated deviation.
    pub with_deviation: usize,
    /// Not reproduced.
    pub not_reproduced: usize,
    /// Not attempted (with the reason).
    pub not_attempted: usize,
    /// Findings restating evidence counted elsewhere (not in the four above).
    pub duplicates: usize,
}

impl FindingCounts {
    /// The independent claims: the four verdicts' sum.
    pub fn independent(&self) -> usize {
        self.reproduced + self.with_deviation + self.not_reproduced + self.not_attempted
    }
}

/// The counts of `findings` by verdict ([`FindingCounts`]).
pub fn count_findings(findings: &[Finding]) -> FindingCounts {
    let count = |status| {
        findings
            .iter()
            .filter(|f| f.status == status && f.same_evidence_as.is_none())
            .count()
    };
    FindingCounts {
        reproduced: count(FindingStatus::Reproduced),
        with_deviation: count(FindingStatus::ReproducedWithDeviation),
        not_reproduced: count(FindingStatus::NotReproduced),
        not_attempted: count(FindingStatus::NotAttempted),
        duplicates: findings
            .iter()
            .filter(|f| f.same_evidence_as.is_some())
            .count(),
    }
}
