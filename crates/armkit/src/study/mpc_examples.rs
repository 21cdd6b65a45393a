//! Seed 000's MPC examples as a study (wrapping [`crate::mpc::scenario`]).

use super::{Check, Series, StudyReport};
use crate::error::Result;
use crate::mpc::qp::QpSolverKind;
use crate::mpc::scenario::{simulate, Seed000Example, SimulationOptions};
use crate::mpc::PlantModel;

/// One of seed 000's motion-planning examples (sec 4.4) on the flexible
/// gantry: the incremental MPC run to the target on a chosen plant, with
/// what armkit promises as checks ([`Seed000Example::checks`]), the paper's
/// claims as findings ([`Seed000Example::findings`]), and the joint motion
/// and hand error as series.
///
/// ```no_run
/// use armkit::mpc::scenario::Seed000Example;
/// use armkit::study::MpcExampleStudy;
/// let report = MpcExampleStudy::new(Seed000Example::SmallMove).run().unwrap();
/// assert!(report.all_passed()); // the prismatic joints stay put (< 1 mm)
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MpcExampleStudy {
    /// The example.
    pub example: Seed000Example,
    /// The QP solver; `None`: the example's default.
    pub solver: Option<QpSolverKind>,
    /// How the joints follow the commands. Default [`PlantModel::Exact`];
    /// with prismatic joints of 1 mm position resolution Example 2 settles
    /// and Example 3 keeps oscillating.
    pub plant: PlantModel,
}

impl MpcExampleStudy {
    /// The example with its default solver.
    pub fn new(example: Seed000Example) -> Self {
        MpcExampleStudy {
            example,
            solver: None,
            plant: PlantModel::Exact,
        }
    }

    /// Runs the example.
    pub fn run(&self) -> Result<StudyReport> {
        let model = Seed000Example::model()?;
        let mut options = self.example.options();
        if let Some(solver) = self.solver {
            options.solver = solver;
        }
        let run = simulate(
            &model,
            options,
            &self.example.start(),
            &self.example.target(),
            &SimulationOptions {
                plant: self.plant,
                ..self.example.simulation()
            },
        )?;
        let findings = self.example.findings(&run)?;
        let checks = self
            .example
            .checks(&run)
            .into_iter()
            .map(|c| Check::holds(c.name, c.passed, c.detail))
            .collect();
        let time: Vec<f64> = run.samples.iter().map(|s| s.time).collect();
        let mut joints = Series::new(
            "joints",
            format!("Seed 000, {}: joint positions", self.example.title()),
            "t (s)",
            "rad or m",
            time.clone(),
        );
        for (j, name) in run.joint_names.iter().enumerate() {
            joints = joints.with(name.clone(), run.samples.iter().map(|s| s.q[j]).collect());
        }
        let error = Series::new(
            "position_error",
            format!("Seed 000, {}: hand position error", self.example.title()),
            "t (s)",
            "m",
            time,
        )
        .with(
            "position error",
            run.samples.iter().map(|s| s.position_error).collect(),
        );
        Ok(StudyReport {
            checks,
            findings,
            series: vec![joints, error],
            notes: Vec::new(),
        })
    }
}
