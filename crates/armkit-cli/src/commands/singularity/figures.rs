//! The figures and the animation of `armkit singularity`.

use armkit::math::{Pose, Vector3};
use armkit::singularity::MethodRun;

use super::{Plant, Study};
use crate::common::CliResult;
use crate::plot::Figure;
use crate::report::Animation;

/// Samples where `|det J|` is below the threshold.
fn singular_mask(run: &MethodRun, threshold: f64) -> Vec<bool> {
    run.determinant
        .iter()
        .map(|d| d.is_nan() || *d < threshold)
        .collect()
}

/// The figures: joint rates per method (Figs 5-6) with the singular region
/// marked, position and orientation error against time for each k (Figs
/// 7-8), and |det J| against time.
pub(super) fn figures(study: &Study) -> Vec<(String, Figure)> {
    let c = &study.outcome.comparison;
    let arm = study.plant.arm();
    let threshold = study.outcome.options.detection.determinant_threshold;
    let mut figures = Vec::new();
    let runs = [
        ("joint_rates_plain", &c.plain),
        ("joint_rates_avoidance", &c.avoidance),
        ("joint_rates_dls", &c.damped_least_squares),
        ("joint_rates_sri", &c.singularity_robust),
    ]
    .into_iter()
    .chain(
        c.separation
            .iter()
            .map(|run| ("joint_rates_separation", run)),
    );
    for (stem, run) in runs {
        let mut figure = Figure::new(
            format!(
                "{}: joint rates ({}, {})",
                run.method.label(),
                arm.name(),
                study.base.text()
            ),
            "t (s)",
            "joint rate (rad/s)",
            run.time.clone(),
        );
        for (joint, rates) in arm.joints().iter().zip(&run.joint_rates) {
            figure = figure.with_series(joint.name.clone(), rates.clone());
        }
        // The region as a box as tall as the largest rate (plotters has no
        // shading in our Figure; the CSV column is 0 outside the region).
        let height = run.summary.peak_joint_rate;
        let marker = singular_mask(run, threshold)
            .into_iter()
            .map(|s| if s { height } else { 0.0 })
            .collect();
        figure = figure.with_series("singular region (|det J| < threshold)", marker);
        figures.push((stem.to_string(), figure));
    }
    let x = c
        .k_sweep
        .first()
        .map(|r| r.time.clone())
        .unwrap_or_default();
    // In micrometres and microradians: the errors are far below the plot
    // axis' resolution in metres and radians.
    let micro = |v: &[f64]| v.iter().map(|e| e * 1e6).collect::<Vec<f64>>();
    let mut position = Figure::new(
        "Avoidance: position error against time for each k (seed 004, Fig 7)",
        "t (s)",
        "position error (µm)",
        x.clone(),
    );
    let mut orientation = Figure::new(
        "Avoidance: orientation error against time for each k (seed 004, Fig 8)",
        "t (s)",
        "orientation error (µrad)",
        x,
    );
    for (k, run) in study.outcome.ks.iter().zip(&c.k_sweep) {
        position = position.with_series(format!("k={k} (µm)"), micro(&run.position_error));
        orientation =
            orientation.with_series(format!("k={k} (µrad)"), micro(&run.orientation_error));
    }
    figures.push(("position_error_k".into(), position));
    figures.push(("orientation_error_k".into(), orientation));
    let mut determinant = Figure::new(
        format!(
            "|det J| along the path ({}, {})",
            arm.name(),
            study.base.text()
        ),
        "t (s)",
        "|det J| (m^3)",
        c.plain.time.clone(),
    );
    for run in c.methods() {
        determinant = determinant.with_series(run.method.label(), run.determinant.clone());
    }
    determinant = determinant.with_series("threshold", vec![threshold; c.plain.time.len()]);
    figures.push(("determinant".into(), determinant));
    for series in study.outcome.sweep.series() {
        let mut figure = Figure::new(series.title, series.x_label, series.y_label, series.x);
        for (label, values) in series.columns {
            figure = figure.with_series(label, values);
        }
        figures.push((series.name, figure));
    }
    figures
}

/// The avoidance run's motion, base included on a held system.
pub(super) fn animation(study: &Study) -> CliResult<Animation> {
    let run = &study.outcome.comparison.avoidance;
    let arm = study.plant.arm();
    let configurations: Vec<Vec<f64>> = (0..run.time.len())
        .map(|i| run.joint_positions.iter().map(|q| q[i]).collect())
        .collect();
    let mut animation = Animation::from_configurations(arm, &run.time, &configurations)?;
    if let Plant::Held(system) = &study.plant {
        // The arm's frame is the base's mount frame; the base keeps its
        // attitude and moves with the arm (zero linear momentum).
        let mount = system.base().mount;
        let worlds: Vec<Pose> = run
            .base_position
            .iter()
            .map(|base| Pose::new(study.outcome.line.base.rotation, Vector3::from(*base)) * mount)
            .collect();
        animation.place_frames(&worlds);
        animation.draw_base_body(system.base());
    }
    // The singular region coloured on the 3-D path (seed 004's detection).
    animation.path_flags = run.in_region.clone();
    Ok(animation)
}
