//! The report of `armkit singularity` (and of a scenario's `[singularity]` table).

use super::figures::{animation, figures};
use super::tables::{k_table, methods_table, regions_table, sweep_table};
use super::{study, SingularityArgs, Study};
use crate::common::CliResult;
use crate::report::{join, Report};

/// The comparison as a report (a scenario's `[singularity]` table, and the
/// command's `--out`).
pub fn report(args: &SingularityArgs) -> CliResult<Report> {
    build_report(&study(args)?)
}

pub(super) fn build_report(study: &Study) -> CliResult<Report> {
    let avoidance = study.outcome.comparison.avoidance.method.label();
    Ok(Report {
        name: "singularity".into(),
        title: format!(
            "Singularity avoidance along a straight line on {} (seed 004)",
            study.plant.arm().name()
        ),
        description: format!(
            "{}. Methods: plain resolved rate (J^-1 of the commanded twist, seed 004 eq 28); seed 004's \
             avoidance (the singular region detected by the determinant and joint-step tests, Newton-Raphson \
             IK of every k-th planned pose inside it, warm-started, and the C2 piecewise cubic of eqs 33-42 \
             through the solutions; tracking resumes after); damped least squares with Nakamura's adaptive \
             damping; Chiaverini's singularity-robust inverse with numerical filtering. The animation shows \
             {avoidance}.",
            study.heading
        ),
        checks: study.outcome.checks(),
        findings: study.outcome.findings(),
        tables: vec![
            methods_table(study),
            regions_table(study),
            k_table(study),
            sweep_table(study),
        ],
        figures: figures(study),
        notes: [
            study.outcome.notes(),
            vec![format!(
                "The line: the straight pose line whose midpoint is the pose at q = ({}) and whose \
                 extent is the end-effector motion of the joint displacement ({}) there \
                 (armkit::singularity::line_through); the start configuration is found by \
                 continuation from the midpoint, so it lies on the branch through the singularity.",
                join(&study.through, 3),
                join(&study.direction, 3)
            ),
            "Time in the singular region counts the control periods whose start state has |det J| \
             below the threshold, for each method as it crossed the region. The joint-rate plots mark \
             that region with a box as tall as the largest rate."
                .into()],
        ]
        .concat(),
        animation: Some(animation(study)?),
    })
}
