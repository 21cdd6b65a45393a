//! The tables of `armkit singularity`: one row per method, the regions, the error against k.

use armkit::singularity::MethodRun;

use super::Study;
use crate::report::Table;

/// The runs of the table: plain, avoidance (first k), dls, sri,
/// separation, then the other k of the sweep.
pub(super) fn table_runs(study: &Study) -> Vec<&MethodRun> {
    let c = &study.outcome.comparison;
    let mut runs: Vec<&MethodRun> = c.methods();
    runs.extend(c.k_sweep.iter().filter(|r| r.method != c.avoidance.method));
    runs
}

/// Table 1: one row per method.
pub(super) fn methods_table(study: &Study) -> Table {
    let mut table = Table::new(
        "Tracking the line: one row per method (errors from the planned pose)",
        &[
            "method",
            "peak joint rate (rad/s)",
            "max position error (m)",
            "max orientation error (rad)",
            "final position error (m)",
            "final orientation error (rad)",
            "time in singular region (s)",
            "IK solves",
            "status",
        ],
    );
    for run in table_runs(study) {
        let s = &run.summary;
        table.push(vec![
            run.method.label(),
            format!("{:.4}", s.peak_joint_rate),
            format!("{:.3e}", s.max_position_error),
            format!("{:.3e}", s.max_orientation_error),
            format!("{:.3e}", s.final_position_error),
            format!("{:.3e}", s.final_orientation_error),
            format!("{:.2}", s.time_in_singular_region),
            s.ik_solves.to_string(),
            run.status.to_string(),
        ]);
    }
    table
}

/// Table 2: the singular regions the avoidance method planned through.
pub(super) fn regions_table(study: &Study) -> Table {
    let mut table = Table::new(
        "Singular regions planned through by the avoidance method",
        &[
            "method",
            "start (s)",
            "end (s)",
            "trigger",
            "knots",
            "IK solves",
            "IK failures",
            "least-squares knots",
            "max knot error (m, rad)",
        ],
    );
    for run in &study.outcome.comparison.k_sweep {
        for region in &run.regions {
            table.push(vec![
                run.method.label(),
                format!("{:.2}", region.start_time),
                format!("{:.2}", region.end_time),
                region.trigger.as_str().to_string(),
                region.knot_times.len().to_string(),
                region.ik_solves.to_string(),
                region.ik_failures.to_string(),
                region.bounded_knots.to_string(),
                format!(
                    "{:.1e}, {:.1e}",
                    region.max_knot_error.0, region.max_knot_error.1
                ),
            ]);
        }
    }
    table
}

/// Table 3: the error against k (seed 004 Figs 7-8).
pub(super) fn k_table(study: &Study) -> Table {
    let mut table = Table::new(
        "Avoidance: tracking error against the knot stride k (seed 004, Figs 7-8)",
        &[
            "k",
            "IK solves",
            "max position error (m)",
            "max orientation error (rad)",
            "mean position error in region (m)",
            "mean orientation error in region (rad)",
        ],
    );
    for (k, run) in study
        .outcome
        .ks
        .iter()
        .zip(&study.outcome.comparison.k_sweep)
    {
        let s = &run.summary;
        table.push(vec![
            k.to_string(),
            s.ik_solves.to_string(),
            format!("{:.3e}", s.max_position_error),
            format!("{:.3e}", s.max_orientation_error),
            format!("{:.3e}", s.mean_region_position_error),
            format!("{:.3e}", s.mean_region_orientation_error),
        ]);
    }
    table
}

/// Table 4: the lines missing the singular pose, every method's peak joint
/// rate and largest errors, and the floor of a wrist-branch switch.
pub(super) fn sweep_table(study: &Study) -> Table {
    let sweep = &study.outcome.sweep;
    let mut headers = vec!["miss (mm)"];
    if let Some(first) = sweep.lines.first() {
        headers.extend(first.methods().iter().map(|(name, _)| *name));
    }
    headers.extend(["floor (m / rad)", "least-squares knots"]);
    let mut table = Table::new(
        format!(
            "Lines missing the singular pose: peak joint rate (rad/s) and largest position (m) / \
             orientation (rad) error; {} for the avoidance (regions planned jointly; greedy: \
             knot by knot); dls clamped: DLS scaled to the avoidance's joint speed bound; floor: \
             the distance from the line to the wrist-singular poses",
            sweep.avoidance_label()
        ),
        &headers,
    );
    for line in &sweep.lines {
        let mut row = vec![format!("{:+}", line.miss * 1e3)];
        for (_, s) in line.methods() {
            row.push(format!(
                "{:.3}, {:.2e} / {:.2e}",
                s.peak_joint_rate, s.max_position_error, s.max_orientation_error
            ));
        }
        row.push(line.floor.map_or("-".into(), |f| {
            format!("{:.2e} / {:.2e}", f.position, f.orientation)
        }));
        row.push(line.bounded_knots.to_string());
        table.push(row);
    }
    table
}
