//! Seed 002's continuous path on every seed 002 scenario
//! (`scenarios/seed002-arm4.toml`, `scenarios/seed002-panda.toml`), its
//! error measured by the test itself: at the check points the planner
//! documents (`k / (c + 1)` of every segment), which must be what the
//! planner reports and what its verdict rests on, and between them, at
//! points of the test's own choosing, which must be within the tolerance
//! the study claims.

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::rotation_angle;
use armkit::study::{
    BoundaryKind, ContinuousPathStudy, LawKind, OrientationKind, PathGoal, PathScope,
};
use armkit::trajectory::{
    plan_continuous_path, CartesianTrajectory, ContinuousPathOptions, PathError, PathStatus,
    PathTolerance, Segmentation, Trajectory,
};
use armkit::Model;

/// The study of each seed 002 scenario file (the same options).
fn scenarios() -> Vec<(&'static str, ContinuousPathStudy)> {
    let arm4 = ContinuousPathStudy::default();
    let panda = ContinuousPathStudy {
        robot: "panda".into(),
        start: vec![0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8],
        goal: PathGoal::Pose([
            0.4840068820263855,
            0.26832815729997467,
            0.2788636984784265,
            -2.940127636212154,
            0.1000106961641452,
            0.38532485926664456,
        ]),
        duration: 2.0,
        law: LawKind::Linear,
        acceleration_time: None,
        orientation: OrientationKind::RpyLinear,
        boundary: BoundaryKind::FiniteDifference,
        tolerance: 1e-4,
        orientation_tolerance: 1e-3,
        scope: PathScope::Paper,
        ..ContinuousPathStudy::default()
    };
    vec![("seed002-arm4", arm4), ("seed002-panda", panda)]
}

/// The largest errors of `trajectory` against `path` at the fractions
/// `fractions` of every segment, each computed here: the joint positions
/// sampled, their forward kinematics, the distance and rotation angle to
/// the path's pose. Also: the worst segment's error by segment.
fn errors_at(
    model: &Model,
    trajectory: &Trajectory,
    path: &CartesianTrajectory,
    fractions: &[f64],
) -> Vec<PathError> {
    let mut data = Data::new(model);
    trajectory
        .knots()
        .windows(2)
        .map(|w| {
            let mut worst = PathError::default();
            for &f in fractions {
                let t = w[0] + (w[1] - w[0]) * f;
                let q = trajectory.sample(t).unwrap().position;
                let reached = *forward_kinematics(model, &mut data, &q).unwrap();
                let target = path.pose_at(t);
                worst.position = worst
                    .position
                    .max((reached.translation - target.translation).norm());
                worst.orientation = worst.orientation.max(rotation_angle(
                    &(reached.rotation * target.rotation.transpose()),
                ));
            }
            worst
        })
        .collect()
}

fn largest(errors: &[PathError]) -> PathError {
    errors.iter().fold(PathError::default(), |m, e| PathError {
        position: m.position.max(e.position),
        orientation: m.orientation.max(e.orientation),
    })
}

fn within(error: &PathError, tolerance: &PathTolerance, factor: f64) -> bool {
    match *tolerance {
        PathTolerance::Position(p) => error.position <= factor * p,
        PathTolerance::Pose {
            position,
            orientation,
        } => error.position <= factor * position && error.orientation <= factor * orientation,
    }
}

/// On every scenario, with 1, 2 and 3 check points per segment, adaptive
/// and fixed segmentation and both orientation laws: the planner's reported
/// error is the error at its documented check points, computed here; its
/// verdict is that error against the tolerance, segment by segment; and
/// with three check points the error between them, at 64 points per
/// segment of the test's choosing (none a check point), stays within 1.5
/// times the tolerance (the study's own claim, at 100 points, is 1).
#[test]
fn the_path_error_measured_independently_matches_the_planners_report_on_every_scenario() {
    let between: Vec<f64> = (0..64).map(|k| (k as f64 + 0.37) / 64.0).collect();
    for (name, study) in scenarios() {
        let model = armkit::robots::by_name(&study.robot).unwrap();
        let task = study.resolved_task(&model);
        let (mut ik, _) = study.path_ik(&model, task).unwrap();
        let orientations = match task {
            armkit::trajectory::IkTask::Pose => {
                vec![OrientationKind::RpyLinear, OrientationKind::Slerp]
            }
            armkit::trajectory::IkTask::Position => vec![OrientationKind::RpyLinear],
        };
        for orientation in orientations {
            let path = study.path(&model, orientation).unwrap();
            for checks in [1, 2, 3] {
                for segmentation in [None, Some(Segmentation::Fixed(5))] {
                    let mut options: ContinuousPathOptions = study.options(task);
                    options.checks_per_segment = checks;
                    if let Some(s) = segmentation {
                        options.segmentation = s;
                    }
                    let what = format!(
                        "{name} {orientation:?}, {checks} check(s), {:?}",
                        options.segmentation
                    );
                    let report =
                        plan_continuous_path(&model, &path, &mut *ik, &study.start, &options)
                            .unwrap();
                    let fractions: Vec<f64> = (1..=checks)
                        .map(|k| k as f64 / (checks + 1) as f64)
                        .collect();
                    let at_checks = errors_at(&model, &report.trajectory, &path, &fractions);
                    let checked = largest(&at_checks);
                    let reported = report.checked_error;
                    assert!(
                        (checked.position - reported.position).abs() <= 1e-12
                            && (checked.orientation - reported.orientation).abs() <= 1e-12,
                        "{what}: reported {reported:?}, measured at the check points {checked:?}"
                    );
                    let all_met = at_checks.iter().all(|e| within(e, &options.tolerance, 1.0));
                    assert_eq!(
                        report.status == PathStatus::ToleranceMet,
                        all_met,
                        "{what}: status {:?}",
                        report.status
                    );
                    if segmentation.is_none() {
                        assert_eq!(report.status, PathStatus::ToleranceMet, "{what}");
                        let interior =
                            largest(&errors_at(&model, &report.trajectory, &path, &between));
                        println!(
                            "{what}: {} segments, reported {:.3e} m / {:.3e} rad, between the checks {:.3e} m / {:.3e} rad",
                            report.trajectory.segment_count(),
                            reported.position,
                            reported.orientation,
                            interior.position,
                            interior.orientation
                        );
                        if checks == 3 {
                            assert!(
                                within(&interior, &options.tolerance, 1.5),
                                "{what}: between the check points {interior:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// The study's own interior figure (its check "at 100 points inside every
/// segment") is the error there, computed here, on every scenario.
#[test]
fn the_studys_interior_error_is_the_error_inside_the_segments() {
    let inside: Vec<f64> = (1..=100).map(|k| k as f64 / 101.0).collect();
    for (name, study) in scenarios() {
        let model = armkit::robots::by_name(&study.robot).unwrap();
        let (planned, _) = study.plan(&model).unwrap();
        let measured = largest(&errors_at(
            &model,
            &planned.report.trajectory,
            &planned.path,
            &inside,
        ));
        assert!(
            (measured.position - planned.interior.position).abs() <= 1e-12
                && (measured.orientation - planned.interior.orientation).abs() <= 1e-12,
            "{name}: study {:?}, measured {measured:?}",
            planned.interior
        );
        let tolerance = study.path_tolerance(study.resolved_task(&model));
        assert!(within(&measured, &tolerance, 1.0), "{name}: {measured:?}");
    }
}
