//! Seed 000's Table 1 as a study: the deflection of the gantry's beam
//! under two equal carriage loads, against the printed values.

use super::{Check, Series, StudyReport};
use crate::beam::{weight, PointLoad, SimplySupportedBeam, TwoCarriageBeam, SEED000_TABLE1};
use crate::error::Result;
use crate::seeds::SEED000_GRAVITY;

/// The paper's tolerance between its theory and its simulation (Table 1).
pub const TABLE1_TOLERANCE: f64 = 0.04;

/// Seed 000, sec 3.1, Table 1: the 10 m beam ([`SimplySupportedBeam::seed000`])
/// under two loads of `mass` kg at each printed case's positions; one check
/// per case (relative error against the paper within its own 4 %).
///
/// ```
/// use armkit::study::BeamTableStudy;
/// let study = BeamTableStudy::default(); // 400 kg, g = 10 m/s^2 as the paper
/// let rows = study.rows().unwrap();
/// assert!((rows[0].under_each[0] - 0.0046).abs() < 0.0001); // case a=3.3, b=3.3
/// assert!(study.run().unwrap().all_passed());
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(default, deny_unknown_fields))]
pub struct BeamTableStudy {
    /// Mass per carriage, kg. Default 400 (seed 000).
    pub mass: f64,
    /// Gravity, m/s^2. Default [`SEED000_GRAVITY`] (10: the printed values).
    pub gravity: f64,
}

impl Default for BeamTableStudy {
    fn default() -> Self {
        BeamTableStudy {
            mass: crate::beam::SEED000_CARRIAGE_MASS,
            gravity: SEED000_GRAVITY,
        }
    }
}

/// One computed row of Table 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Table1Row {
    /// The paper's label of the case.
    pub label: &'static str,
    /// Load positions from the left support, m.
    pub positions: [f64; 2],
    /// The paper's deflection under the loads, m.
    pub paper: f64,
    /// Ours, under each load, m (equal for the printed symmetric cases).
    pub under_each: [f64; 2],
    /// Ours at mid-span, m.
    pub midspan: f64,
}

impl Table1Row {
    /// `(ours - paper) / paper`, ours under the first load.
    pub fn relative_error(&self) -> f64 {
        (self.under_each[0] - self.paper) / self.paper
    }

    /// True when within the paper's own 4 % ([`TABLE1_TOLERANCE`]).
    pub fn within_tolerance(&self) -> bool {
        self.relative_error().abs() < TABLE1_TOLERANCE
    }
}

impl BeamTableStudy {
    /// The three rows. Errors: a mass or gravity not finite and > 0.
    pub fn rows(&self) -> Result<Vec<Table1Row>> {
        let force = weight(self.mass, self.gravity)?;
        let gantry = TwoCarriageBeam::new(SimplySupportedBeam::seed000(), [force, force])?;
        SEED000_TABLE1
            .iter()
            .map(|case| {
                let loads = [
                    PointLoad::new(case.positions[0], force),
                    PointLoad::new(case.positions[1], force),
                ];
                Ok(Table1Row {
                    label: case.label,
                    positions: case.positions,
                    paper: case.paper,
                    under_each: gantry.deflections(case.positions)?,
                    midspan: gantry.beam.deflection(0.5 * gantry.beam.length(), &loads)?,
                })
            })
            .collect()
    }

    /// One check per case, and the rows as a series (paper and ours against
    /// the first load's position).
    pub fn run(&self) -> Result<StudyReport> {
        let rows = self.rows()?;
        let checks = rows
            .iter()
            .map(|r| {
                Check::at_most(
                    format!("Table 1 case {}: |ours - paper| / paper", r.label),
                    r.relative_error().abs(),
                    TABLE1_TOLERANCE,
                    "",
                )
            })
            .collect();
        let series = Series::new(
            "table1",
            "Seed 000, Table 1: deflection under the loads",
            "first load position (m)",
            "deflection (m)",
            rows.iter().map(|r| r.positions[0]).collect(),
        )
        .with("paper", rows.iter().map(|r| r.paper).collect())
        .with("ours", rows.iter().map(|r| r.under_each[0]).collect());
        Ok(StudyReport {
            checks,
            findings: Vec::new(),
            series: vec![series],
            notes: vec![format!(
                "Table 1 is reproduced with g = {SEED000_GRAVITY} m/s^2 (only g in [9.948, 10.089) \
                 rounds to all three printed values); the printed values are the deflection under \
                 the loads, not at mid-span, and case a=3.3, b=3.3 means 3.3 m from each end."
            )],
        })
    }
}
