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
}

impl FindingStatus {
    /// `reproduced`, `reproduced with deviation` or `not reproduced`.
    pub fn as_str(&self) -> &'static str {
        match self {
            FindingStatus::Reproduced => "reproduced",
            FindingStatus::ReproducedWithDeviation => "reproduced with deviation",
            FindingStatus::NotReproduced => "not reproduced",
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
        }
    }
}

/// `[status] claim: measured`.
impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}] {}: {}", self.status, self.claim, self.measured)
    }
}

/// How many findings have each status: (reproduced, with deviation, not
/// reproduced).
pub fn count_findings(findings: &[Finding]) -> (usize, usize, usize) {
    let count = |status| findings.iter().filter(|f| f.status == status).count();
    (
        count(FindingStatus::Reproduced),
        count(FindingStatus::ReproducedWithDeviation),
        count(FindingStatus::NotReproduced),
    )
}
