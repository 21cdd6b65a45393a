//! Seed 004: singularity detection and avoidance along a straight pose line
//! on space6r (fixed base and attitude held), the DLS and SRI baselines,
//! singular configurations and their classification, and the manipulability
//! ellipsoid.

use armkit::kinematics::singular_values;
use armkit::math::{Matrix6, Pose, Vector3};
use armkit::robots::space6r_free_floating;
use armkit::singularity::{
    calibrate_determinant_threshold, classify, find_singularities, line_through,
    manipulability_ellipsoid, nearest_singularity, seed004_path, AvoidanceOptions, Baselines,
    ClassifyOptions, Comparison, DetectionOptions, JacobianPart, LineTask, Manipulator, Method,
    PathTracker, SearchOptions, SearchStatus, SearchTarget, SingularityKind, SEED004_THROUGH,
};
use armkit::space::{center_of_mass, SpaceData};
use armkit::tracking::{TrackingOptions, TrackingStatus};
use armkit::trajectory::clamped_cubic_spline;
use armkit::{jacobian, Data, JacobianFrame};

const KS: [usize; 3] = [1, 5, 10];

fn print_table(title: &str, comparison: &Comparison) {
    println!("{title}\n{comparison}");
}

fn compare(manipulator: Manipulator<'_>, task: LineTask) -> Comparison {
    let options = AvoidanceOptions::default();
    let tracker = PathTracker::new(manipulator, task, options).unwrap();
    tracker
        .compare(&Baselines::for_detection(&options.detection), &KS)
        .unwrap()
}

/// The seed-004 claims, common to both bases.
fn check_seed_claims(comparison: &Comparison) {
    let plain = &comparison.plain;
    assert_eq!(plain.status, TrackingStatus::Completed);
    for run in &comparison.k_sweep {
        let s = &run.summary;
        // Plain tracking's peak joint rate at least 10 times avoidance's.
        assert!(
            plain.summary.peak_joint_rate >= 10.0 * s.peak_joint_rate,
            "{}: plain {} vs {}",
            run.method.label(),
            plain.summary.peak_joint_rate,
            s.peak_joint_rate
        );
        // The avoidance's rates stay below space6r's 0.5 rad/s limit.
        assert!(s.peak_joint_rate < 0.5, "{}", s.peak_joint_rate);
        // Final pose error at most 1e-6.
        assert!(s.final_position_error <= 1e-6, "{}", s.final_position_error);
        assert!(
            s.final_orientation_error <= 1e-6,
            "{}",
            s.final_orientation_error
        );
        // One region, around the middle of the motion (the paper: 8.8 s to 11.2 s).
        assert_eq!(run.regions.len(), 1, "{}", run.method.label());
        let region = &run.regions[0];
        assert!(
            (8.7..9.1).contains(&region.start_time),
            "{}",
            region.start_time
        );
        assert!(
            (11.1..11.6).contains(&region.end_time),
            "{}",
            region.end_time
        );
        assert_eq!(region.ik_failures, 0);
        assert!(region.max_knot_error.0 <= 1e-8 && region.max_knot_error.1 <= 1e-8);
    }
    // The trade-off: the error grows with k while the IK solves fall.
    let sweep = &comparison.k_sweep;
    for pair in sweep.windows(2) {
        let (a, b) = (&pair[0].summary, &pair[1].summary);
        assert!(
            a.max_position_error <= b.max_position_error,
            "{} {}",
            a.max_position_error,
            b.max_position_error
        );
        assert!(a.max_orientation_error <= b.max_orientation_error);
        assert!(a.ik_solves > b.ik_solves);
    }
    // Plain tracking crosses the singularity with joints 4 and 6 spinning:
    // they carry the peak, joints 1 to 3 do not.
    let peak = |j: usize| {
        plain.joint_rates[j]
            .iter()
            .fold(0.0f64, |m, r| m.max(r.abs()))
    };
    let wrist = peak(3).max(peak(5));
    assert_eq!(wrist, plain.summary.peak_joint_rate);
    assert!((0..3).all(|j| peak(j) < 0.1 * wrist));
    // The baselines keep moving too, with errors far above the avoidance's.
    for run in [
        &comparison.damped_least_squares,
        &comparison.singularity_robust,
    ] {
        assert_eq!(run.status, TrackingStatus::Completed);
        assert!(run.summary.peak_joint_rate < 0.5);
        assert!(run.summary.max_position_error > 10.0 * sweep[2].summary.max_position_error);
    }
}

#[test]
fn fixed_base_seed_path_plain_avoidance_and_baselines() {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = seed004_path(&manipulator).unwrap();
    let comparison = compare(manipulator, line.task(20.0, 4.0));
    print_table("space6r, fixed base", &comparison);
    check_seed_claims(&comparison);
    // The plain run's error along the region, as it is: it stays bounded
    // (the plain inverse is exact until 0.05 s from the singular pose).
    assert!(comparison.plain.summary.max_position_error < 1e-3);
    // Errors inside the region for each k (mean over its samples), reported.
    for run in &comparison.k_sweep {
        println!(
            "{}: mean error in region {:.3e} m, {:.3e} rad",
            run.method.label(),
            run.summary.mean_region_position_error,
            run.summary.mean_region_orientation_error
        );
    }
}

#[test]
fn the_paper_rule_for_the_threshold_on_the_plain_run() {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = seed004_path(&manipulator).unwrap();
    let options = AvoidanceOptions::default();
    let tracker = PathTracker::new(manipulator, line.task(20.0, 4.0), options).unwrap();
    let plain = tracker.run(&Method::Plain).unwrap();
    let eps_dq = options.detection.joint_step_threshold;
    let calibrated = calibrate_determinant_threshold(&plain, eps_dq).unwrap();
    let below: Vec<f64> = plain
        .time
        .iter()
        .zip(&plain.determinant)
        .filter(|(_, d)| **d < calibrated)
        .map(|(t, _)| *t)
        .collect();
    println!(
        "calibrated threshold {calibrated:.3e} m^3: region {:.2} s .. {:.2} s",
        below[0],
        below[below.len() - 1]
    );
    assert!((1e-4..3e-4).contains(&calibrated), "{calibrated}");
    assert!(below[0] > 9.9 && below[below.len() - 1] < 10.1);
    // The default threshold is |det J| of the plain run near 8.8 s.
    let at = |t: f64| plain.determinant[(t / 0.01).round() as usize];
    let default = options.detection.determinant_threshold;
    assert!(at(8.8) > default && at(8.9) < default);
    // The singular pose is at mid-path: |det J| has its minimum at 10 s.
    let (i_min, _) = plain
        .determinant
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .unwrap();
    assert!(
        (plain.time[i_min] - 10.0).abs() < 0.02,
        "{}",
        plain.time[i_min]
    );
}

#[test]
fn attitude_held_seed_path() {
    let system = space6r_free_floating().unwrap();
    let at_through = Manipulator::AttitudeHeld {
        system: &system,
        base: Pose::identity(),
    };
    let line = seed004_path(&at_through).unwrap();
    let manipulator = Manipulator::AttitudeHeld {
        system: &system,
        base: line.base,
    };
    let comparison = compare(manipulator, line.task(20.0, 4.0));
    print_table("space6r, attitude held (J*)", &comparison);
    check_seed_claims(&comparison);
    // Zero linear momentum: the centre of mass stays where it started, with
    // the base translating (and its attitude held).
    let mut data = SpaceData::new(&system);
    for run in comparison.methods() {
        let com_at = |i: usize, data: &mut SpaceData| {
            let q: Vec<f64> = run.joint_positions.iter().map(|s| s[i]).collect();
            let p = run.base_position[i];
            let base = Pose::new(line.base.rotation, Vector3::new(p[0], p[1], p[2]));
            center_of_mass(&system, data, &base, &q).unwrap()
        };
        let start = com_at(0, &mut data);
        let mut moved = 0.0f64;
        let mut drift = 0.0f64;
        for i in 0..run.time.len() {
            drift = drift.max((com_at(i, &mut data) - start).norm());
            let p = run.base_position[i];
            moved = moved.max((Vector3::new(p[0], p[1], p[2]) - line.base.translation).norm());
        }
        assert!(
            drift < 1e-6,
            "{}: centre of mass drift {drift}",
            run.method.label()
        );
        assert!(moved > 0.01, "{}: base moved {moved}", run.method.label());
    }
}

#[test]
fn a_path_far_from_singularities_is_the_same_with_and_without_avoidance() {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    // Through a regular configuration (q5 = 1.1), a short move.
    let line = line_through(
        &manipulator,
        &[0.2, 0.9, -0.6, 0.4, 1.1, 0.3],
        &[0.2, -0.1, 0.15, 0.1, 0.1, -0.1],
        0.0,
    )
    .unwrap();
    let tracker = PathTracker::new(
        manipulator,
        line.task(5.0, 1.0),
        AvoidanceOptions::default(),
    )
    .unwrap();
    let plain = tracker.run(&Method::Plain).unwrap();
    for k in KS {
        let avoid = tracker.run(&Method::Avoidance { k }).unwrap();
        assert!(avoid.regions.is_empty());
        assert!(avoid.in_region.iter().all(|r| !r));
        assert_eq!(avoid.summary.ik_solves, 0);
        assert_eq!(avoid.joint_positions, plain.joint_positions);
        assert_eq!(avoid.joint_rates, plain.joint_rates);
    }
    let det_min = plain
        .determinant
        .iter()
        .fold(f64::INFINITY, |m, d| m.min(*d));
    assert!(det_min > 0.01, "{det_min}");
    assert!(plain.summary.max_position_error < 1e-5);
}

fn error_message<T: std::fmt::Debug>(result: armkit::Result<T>) -> String {
    result.unwrap_err().to_string()
}

#[test]
fn bad_input_is_an_error_naming_the_argument() {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = seed004_path(&manipulator).unwrap();
    let task = line.task(20.0, 4.0);
    let tracker = PathTracker::new(manipulator, task.clone(), AvoidanceOptions::default()).unwrap();
    // k = 0.
    let message = error_message(tracker.run(&Method::Avoidance { k: 0 }));
    assert!(
        message.contains("`k`") && message.contains("1..=1000000"),
        "{message}"
    );
    let message = error_message(tracker.compare(
        &Baselines::for_detection(&DetectionOptions::default()),
        &[5, 0],
    ));
    assert!(message.contains("k"), "{message}");
    let message = error_message(
        tracker.compare(&Baselines::for_detection(&DetectionOptions::default()), &[]),
    );
    assert!(message.contains("ks"), "{message}");
    // Thresholds <= 0 and NaN.
    for (value, field) in [
        (0.0, "determinant_threshold"),
        (-1.0, "determinant_threshold"),
        (f64::NAN, "determinant_threshold"),
    ] {
        let mut options = AvoidanceOptions::default();
        options.detection.determinant_threshold = value;
        let message = error_message(PathTracker::new(manipulator, task.clone(), options));
        assert!(message.contains(field), "{message}");
    }
    for value in [0.0, -0.1, f64::NAN] {
        let mut options = AvoidanceOptions::default();
        options.detection.joint_step_threshold = value;
        let message = error_message(PathTracker::new(manipulator, task.clone(), options));
        assert!(message.contains("joint_step_threshold"), "{message}");
    }
    for (options, field) in [
        (
            AvoidanceOptions {
                tracking: TrackingOptions {
                    dt: 0.0,
                    ..TrackingOptions::default()
                },
                ..AvoidanceOptions::default()
            },
            "dt",
        ),
        (
            AvoidanceOptions {
                ik_tolerance: f64::NAN,
                ..AvoidanceOptions::default()
            },
            "ik_tolerance",
        ),
        (
            AvoidanceOptions {
                ik_max_iterations: 0,
                ..AvoidanceOptions::default()
            },
            "ik_max_iterations",
        ),
    ] {
        let message = error_message(PathTracker::new(manipulator, task.clone(), options));
        assert!(message.contains(field), "{message}");
    }
    // NaN in the start, a wrong size, bad timing.
    let mut bad = task.clone();
    bad.start[2] = f64::NAN;
    let message = error_message(PathTracker::new(
        manipulator,
        bad,
        AvoidanceOptions::default(),
    ));
    assert!(message.contains("start"), "{message}");
    let mut bad = task.clone();
    bad.start.pop();
    let message = error_message(PathTracker::new(
        manipulator,
        bad,
        AvoidanceOptions::default(),
    ));
    assert!(message.contains("start"), "{message}");
    let mut bad = task.clone();
    bad.acceleration_time = 15.0;
    let message = error_message(PathTracker::new(
        manipulator,
        bad,
        AvoidanceOptions::default(),
    ));
    assert!(message.contains("acceleration"), "{message}");
    let mut bad = task.clone();
    bad.goal.translation.x = f64::NAN;
    let message = error_message(PathTracker::new(
        manipulator,
        bad,
        AvoidanceOptions::default(),
    ));
    assert!(message.contains("goal"), "{message}");
    // A path out of reach: a goal 3 m away (space6r reaches about 1.9 m).
    let mut far = task.clone();
    far.goal.translation += Vector3::new(3.0, 0.0, 0.0);
    let message = error_message(PathTracker::new(
        manipulator,
        far,
        AvoidanceOptions::default(),
    ));
    assert!(
        message.contains("goal") && message.contains("out of reach"),
        "{message}"
    );
    // Baselines with bad parameters.
    let mut baselines = Baselines::for_detection(&DetectionOptions::default());
    baselines.nakamura.max_damping = -1.0;
    let message = error_message(tracker.compare(&baselines, &KS));
    assert!(message.contains("max_damping"), "{message}");
    // line_through: NaN, and a line whose start is out of reach.
    let message = error_message(line_through(&manipulator, &[f64::NAN; 6], &[0.0; 6], 0.0));
    assert!(message.contains("through"), "{message}");
    let message = error_message(line_through(
        &manipulator,
        &SEED004_THROUGH,
        &[40.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        0.0,
    ));
    assert!(
        message.contains("out of reach") || message.contains("joint_direction"),
        "{message}"
    );
}

/// The avoidance's joints follow the C2 cubic through the knots: rebuilt
/// from the run's knot times and positions, the fit has continuous
/// positions, rates and accelerations at every knot, its rates are the
/// finite differences of its positions, and the run's samples lie on it.
#[test]
fn the_c2_fit_is_continuous_and_the_run_follows_it() {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = seed004_path(&manipulator).unwrap();
    let tracker = PathTracker::new(
        manipulator,
        line.task(20.0, 4.0),
        AvoidanceOptions::default(),
    )
    .unwrap();
    let (_, h) = tracker.steps();
    let run = tracker.run(&Method::Avoidance { k: 10 }).unwrap();
    let region = &run.regions[0];
    let index = |t: f64| (t / h).round() as usize;
    let knots: Vec<Vec<f64>> = region
        .knot_times
        .iter()
        .map(|&t| run.joint_positions.iter().map(|s| s[index(t)]).collect())
        .collect();
    let entry = index(region.start_time);
    let start_rates: Vec<f64> = run.joint_rates.iter().map(|s| s[entry - 1]).collect();
    let exit = index(region.end_time);
    // The fit ends at the plain rates of the planned twist at the exit knot.
    let planned = tracker.trajectory().sample(region.end_time).unwrap().twist;
    let mut data = Data::new(&arm);
    let j_exit = jacobian(
        &arm,
        &mut data,
        &knots[knots.len() - 1],
        JacobianFrame::World,
    )
    .unwrap()
    .clone();
    let end_rates: Vec<f64> = Matrix6::from_column_slice(j_exit.as_slice())
        .lu()
        .solve(&planned)
        .unwrap()
        .iter()
        .copied()
        .collect();
    let fit = clamped_cubic_spline(&region.knot_times, &knots, &start_rates, &end_rates).unwrap();
    for (i, &t) in region.knot_times.iter().enumerate().skip(1) {
        if i + 1 == region.knot_times.len() {
            break;
        }
        let before = fit.sample(t - 1e-9).unwrap();
        let after = fit.sample(t + 1e-9).unwrap();
        for j in 0..6 {
            assert!((before.position[j] - after.position[j]).abs() < 1e-9);
            assert!((before.velocity[j] - after.velocity[j]).abs() < 1e-7);
            assert!(
                (before.acceleration[j] - after.acceleration[j]).abs() < 1e-6,
                "joint {j} at {t}: {} vs {}",
                before.acceleration[j],
                after.acceleration[j]
            );
        }
        // Rates and accelerations against central differences.
        let d = 1e-4;
        let (minus, plus, here) = (
            fit.sample(t - d).unwrap(),
            fit.sample(t + d).unwrap(),
            fit.sample(t).unwrap(),
        );
        for j in 0..6 {
            let rate = (plus.position[j] - minus.position[j]) / (2.0 * d);
            assert!(
                (rate - here.velocity[j]).abs() < 1e-7,
                "{rate} {}",
                here.velocity[j]
            );
            let accel = (plus.velocity[j] - minus.velocity[j]) / (2.0 * d);
            assert!((accel - here.acceleration[j]).abs() < 1e-5);
        }
    }
    // The run's samples inside the region lie on the fit, and its rates are
    // the fit's finite differences over one period.
    let mut off = 0.0f64;
    for i in entry..exit {
        let state = fit.sample(run.time[i]).unwrap();
        for j in 0..6 {
            off = off.max((run.joint_positions[j][i] - state.position[j]).abs());
            let next = fit.sample(run.time[i + 1]).unwrap();
            let fd = (next.position[j] - run.joint_positions[j][i]) / h;
            assert!((run.joint_rates[j][i] - fd).abs() < 1e-9);
        }
    }
    assert!(off < 1e-12, "{off}");
    // Rates continuous at entry and exit: no jump above 1e-3 rad/s per period.
    for j in 0..6 {
        for i in [entry - 1, entry, exit - 1, exit] {
            let jump = (run.joint_rates[j][i + 1] - run.joint_rates[j][i]).abs();
            assert!(jump < 1e-3, "joint {j} at sample {i}: jump {jump}");
        }
    }
}

#[test]
fn classify_spherical_wrist_singularities_of_puma560_and_space6r() {
    let options = ClassifyOptions::default();
    for name in ["puma560", "space6r"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut data = Data::new(&model);
        // A regular configuration.
        let regular = classify(
            &model,
            &mut data,
            &[0.3, 0.5, -0.4, 0.2, 0.7, 0.1],
            &options,
        )
        .unwrap();
        assert!(regular.kinds.is_empty(), "{name}: {:?}", regular.kinds);
        assert_eq!(regular.rank, 6);
        let factors = regular.factors.unwrap();
        assert!(
            factors.wrist.abs() > 0.1
                && factors.elbow.abs() > 0.01
                && factors.shoulder.abs() > 0.01
        );
        // Wrist: q5 = 0.
        let wrist = classify(
            &model,
            &mut data,
            &[0.3, 0.5, -0.4, 0.2, 0.0, 0.1],
            &options,
        )
        .unwrap();
        assert_eq!(wrist.kinds, vec![SingularityKind::Wrist], "{name}");
        assert_eq!(wrist.rank, 5);
        // Elbow and shoulder, found by the search.
        let search = SearchOptions::default();
        let start = [0.3, 0.5, -0.4, 0.2, 0.7, 0.1];
        for kind in [SingularityKind::Elbow, SingularityKind::Shoulder] {
            let found =
                nearest_singularity(&model, &mut data, &start, SearchTarget::Kind(kind), &search)
                    .unwrap();
            assert_eq!(
                found.status,
                SearchStatus::Converged,
                "{name} {kind:?}: {:?} measure {} after {}",
                found.q,
                found.measure,
                found.iterations
            );
            assert_eq!(found.classification.kinds, vec![kind], "{name}");
            assert_eq!(found.classification.rank, 5, "{name} {kind:?}");
            let c = found.classification.factors.unwrap().centre;
            let frames: Vec<Pose> = {
                jacobian(&model, &mut data, &found.q, JacobianFrame::World).unwrap();
                data.joint_frames().to_vec()
            };
            match kind {
                SingularityKind::Elbow => {
                    // Stretched or folded: the wrist centre's velocity from
                    // joint 2 is parallel to that from joint 3.
                    let u2 = frames[1]
                        .rotation
                        .column(2)
                        .cross(&(c - frames[1].translation));
                    let u3 = frames[2]
                        .rotation
                        .column(2)
                        .cross(&(c - frames[2].translation));
                    assert!(u2.cross(&u3).norm() < 1e-6 * u2.norm() * u3.norm());
                }
                _ => {
                    // Shoulder: the wrist centre's distance from axis 1 is the
                    // shoulder offset (PUMA 0.15005 m along axis 2, space6r 0.15 m).
                    let z1 = frames[0].rotation.column(2).into_owned();
                    let r = c - frames[0].translation;
                    let radial = (r - z1 * r.dot(&z1)).norm();
                    let offset = if name == "puma560" { 0.15005 } else { 0.15 };
                    assert!((radial - offset).abs() < 1e-6, "{name}: {radial}");
                }
            }
            println!(
                "{name} {kind:?}: q {:?}, {} iterations",
                found.q, found.iterations
            );
        }
        // Every singularity found from random starts has a name: the three
        // factors make up det J.
        let found = find_singularities(&model, SearchTarget::Any, 12, 7, &search).unwrap();
        assert!(found.len() >= 8, "{name}: {} of 12", found.len());
        for f in &found {
            assert!(!f.classification.kinds.is_empty());
            assert!(
                !f.classification
                    .kinds
                    .contains(&SingularityKind::Unclassified),
                "{name}: {:?}",
                f.classification
            );
            assert!(f.classification.rank < 6);
        }
    }
    // The seed path's through configuration is a wrist singularity.
    let arm = armkit::robots::space6r().unwrap();
    let mut data = Data::new(&arm);
    let through = classify(&arm, &mut data, &SEED004_THROUGH, &options).unwrap();
    assert_eq!(through.kinds, vec![SingularityKind::Wrist]);
}

/// The UR family has no spherical wrist, but its determinant,
/// `s3 s5 a2 a3 (a2 c2 + a3 c23 + d5 s234)`, factors the same way: q5 = 0 is
/// a wrist singularity, q3 = 0 an elbow one, and the point where axes 5 and 6
/// meet in the plane through axis 1 parallel to axis 2 a shoulder one.
#[test]
fn ur5_singularities_are_classified_wrist_elbow_shoulder() {
    let ur5 = armkit::robots::ur5().unwrap();
    let mut data = Data::new(&ur5);
    let options = ClassifyOptions::default();
    let wrist = classify(&ur5, &mut data, &[0.3, -1.0, 1.2, 0.2, 0.0, 0.1], &options).unwrap();
    assert!(wrist.factors.is_some());
    assert_eq!(wrist.kinds, vec![SingularityKind::Wrist]);
    assert_eq!(wrist.rank, 5);
    let elbow = classify(&ur5, &mut data, &[0.3, -1.0, 0.0, 0.2, 0.8, 0.1], &options).unwrap();
    assert_eq!(elbow.kinds, vec![SingularityKind::Elbow]);
    assert_eq!(elbow.rank, 5);
    let regular = classify(&ur5, &mut data, &[0.3, -1.0, 1.2, 0.2, 0.8, 0.1], &options).unwrap();
    assert!(regular.kinds.is_empty() && regular.rank == 6);
    let f = regular.factors.unwrap();
    // The factors are the sines of q5 and q3, up to sign.
    assert!((f.wrist.abs() - 0.8_f64.sin().abs()).abs() < 1e-12, "{f:?}");
    assert!((f.elbow.abs() - 1.2_f64.sin().abs()).abs() < 1e-12, "{f:?}");
    let search = SearchOptions::default();
    // The shoulder: the point where axes 5 and 6 meet ends up on the plane
    // through axis 1 (z) parallel to axis 2: its in-plane radius from axis 1
    // vanishes, as a2 c2 + a3 c23 + d5 s234 = 0 says.
    let shoulder = nearest_singularity(
        &ur5,
        &mut data,
        &[0.3, -1.0, 1.2, 0.2, 0.8, 0.1],
        SearchTarget::Kind(SingularityKind::Shoulder),
        &search,
    )
    .unwrap();
    assert!(
        shoulder
            .classification
            .kinds
            .contains(&SingularityKind::Shoulder),
        "{:?}",
        shoulder.classification
    );
    assert!(shoulder.classification.rank < 6);
    let q = &shoulder.q;
    let (a2, a3, d5) = (-0.425, -0.39225, 0.09465);
    let radius = a2 * q[1].cos() + a3 * (q[1] + q[2]).cos() + d5 * (q[1] + q[2] + q[3]).sin();
    assert!(radius.abs() < 1e-6, "{radius} at {q:?}");
    // Every singularity found from random starts has a name.
    let found = find_singularities(&ur5, SearchTarget::Any, 6, 3, &search).unwrap();
    assert!(found.len() >= 4, "{}", found.len());
    for f in &found {
        assert!(!f.classification.kinds.is_empty());
        assert!(
            !f.classification
                .kinds
                .contains(&SingularityKind::Unclassified),
            "{:?}",
            f.classification
        );
        assert!(f.classification.rank < 6);
    }
    // An arm of neither class: a kind search is refused, naming it.
    let panda = armkit::robots::panda().unwrap();
    let mut panda_data = Data::new(&panda);
    let message = error_message(nearest_singularity(
        &panda,
        &mut panda_data,
        &panda.neutral_configuration(),
        SearchTarget::Kind(SingularityKind::Wrist),
        &search,
    ));
    assert!(
        message.contains("spherical wrist") && message.contains("panda"),
        "{message}"
    );
    let message = error_message(classify(&ur5, &mut data, &[0.0; 5], &options));
    assert!(message.contains("q"), "{message}");
    let message = error_message(classify(
        &ur5,
        &mut data,
        &[0.0; 6],
        &ClassifyOptions { tolerance: 0.0 },
    ));
    assert!(message.contains("tolerance"), "{message}");
}

#[test]
fn manipulability_ellipsoids_are_the_singular_values_and_vectors_of_each_part() {
    for name in ["puma560", "ur5", "space6r"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut data = Data::new(&model);
        for q in [
            [0.3, 0.5, -0.4, 0.2, 0.7, 0.1],
            [-1.0, 0.2, 0.9, -0.6, 1.3, 2.0],
            [0.3, 0.5, -0.4, 0.2, 0.0, 0.1],
        ] {
            let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
                .unwrap()
                .clone();
            for (part, rows) in [
                (JacobianPart::Translational, 0),
                (JacobianPart::Rotational, 3),
            ] {
                let e = manipulability_ellipsoid(&j, part).unwrap();
                let block = j.fixed_rows::<3>(rows).into_owned();
                let expected = singular_values(&block);
                let gram = &block * block.transpose();
                for (i, (axis, radius)) in e.axes.iter().zip(e.radii).enumerate() {
                    assert!((radius - expected[i]).abs() < 1e-7, "{name} {part:?}");
                    assert!((axis.norm() - 1.0).abs() < 1e-12);
                    for other in &e.axes[..i] {
                        assert!(axis.dot(other).abs() < 1e-9);
                    }
                    // J_p J_p' a = r^2 a.
                    let image = gram * axis;
                    assert!((image - axis * radius.powi(2)).norm() < 1e-9);
                }
                assert!((e.volume_measure() - expected.iter().product::<f64>()).abs() < 1e-9);
            }
        }
    }
    // A part that cannot move along z: its smallest radius is zero along z.
    let mut j = armkit::math::Matrix6xX::zeros(2);
    j[(0, 0)] = 2.0;
    j[(1, 1)] = 0.5;
    let e = manipulability_ellipsoid(&j, JacobianPart::Translational).unwrap();
    assert_eq!(e.radii, [2.0, 0.5, 0.0]);
    assert!((e.axes[2].z.abs() - 1.0).abs() < 1e-12);
    assert_eq!(e.isotropy(), 0.0);
    j[(3, 0)] = f64::NAN;
    let message = error_message(manipulability_ellipsoid(&j, JacobianPart::Rotational));
    assert!(message.contains("jacobian"), "{message}");
}

/// The largest joint step of a run over one control period (rad).
fn largest_step(run: &armkit::singularity::MethodRun, dt: f64) -> f64 {
    run.joint_rates
        .iter()
        .flatten()
        .fold(0.0f64, |m, r| m.max((r * dt).abs()))
}

#[test]
fn a_near_miss_keeps_every_knot_within_the_arm_speed() {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    // 10 mm off the singular pose: exact tracking flips the wrist at
    // 1.4 rad/s, beyond eps_dq / h = 0.5 rad/s (space6r's speed limit).
    let line = line_through(
        &manipulator,
        &SEED004_THROUGH,
        &armkit::singularity::SEED004_DIRECTION,
        0.01,
    )
    .unwrap();
    let options = AvoidanceOptions::default();
    let eps_dq = options.detection.joint_step_threshold;
    let tracker = PathTracker::new(manipulator, line.task(20.0, 4.0), options).unwrap();
    let plain = tracker.run(&Method::Plain).unwrap();
    assert!(largest_step(&plain, 0.01) > 2.0 * eps_dq);
    let avoid = tracker.run(&Method::Avoidance { k: 1 }).unwrap();
    assert_eq!(avoid.status, TrackingStatus::Completed);
    let bounded: usize = avoid.regions.iter().map(|r| r.bounded_knots).sum();
    let knots: usize = avoid.regions.iter().map(|r| r.knot_times.len()).sum();
    println!(
        "miss 10 mm: {bounded} least-squares knots of {knots}, peak {:.4} rad/s, max error {:.3e} m \
         / {:.3e} rad",
        avoid.summary.peak_joint_rate,
        avoid.summary.max_position_error,
        avoid.summary.max_orientation_error
    );
    // No knot is dropped: every IK solve is a knot of the fit.
    for region in &avoid.regions {
        assert_eq!(region.knot_times.len(), region.ik_solves + 1);
    }
    assert!(bounded > 10, "{bounded}");
    // Every step within eps_dq (rounding aside), and back on the path at the end.
    assert!(largest_step(&avoid, 0.01) <= eps_dq * (1.0 + 1e-9));
    assert!(avoid.summary.final_position_error <= 1e-6);
    assert!(avoid.summary.final_orientation_error <= 1e-6);
    // The least-squares knots are the nearest poses: a bound that allows the
    // flip (eps_dq = 0.05 rad per period, 5 rad/s) gives exact knots only.
    let mut fast = options;
    fast.detection.joint_step_threshold = 0.05;
    let tracker = PathTracker::new(manipulator, line.task(20.0, 4.0), fast).unwrap();
    let fast_run = tracker.run(&Method::Avoidance { k: 1 }).unwrap();
    assert!(!fast_run.regions.is_empty());
    assert!(fast_run.regions.iter().all(|r| r.bounded_knots == 0));
    assert!(
        fast_run.summary.max_position_error < 1e-5,
        "{}",
        fast_run.summary.max_position_error
    );
}

#[test]
fn the_study_calibrates_sweeps_the_miss_and_states_the_paper_claims() {
    use armkit::study::{AvoidanceStudy, FindingStatus, FITTED_DETERMINANT_THRESHOLD};
    let arm = armkit::robots::space6r().unwrap();
    let study = AvoidanceStudy {
        base: armkit::singularity::BaseKind::Fixed,
        miss_sweep: vec![0.0, 0.003],
        ..AvoidanceStudy::default()
    };
    let outcome = study.compare(Manipulator::FixedBase(&arm)).unwrap();
    // The paper's rule is the default threshold: the largest |det J| where
    // plain tracking steps a joint by more than eps_dq.
    let threshold = outcome.options.detection.determinant_threshold;
    let line = seed004_path(&Manipulator::FixedBase(&arm)).unwrap();
    let plain = PathTracker::new(
        Manipulator::FixedBase(&arm),
        line.task(20.0, 4.0),
        AvoidanceOptions::default(),
    )
    .unwrap()
    .run(&Method::Plain)
    .unwrap();
    assert_eq!(
        Some(threshold),
        calibrate_determinant_threshold(&plain, 0.005)
    );
    assert!((1e-4..3e-4).contains(&threshold), "{threshold}");
    // The fitted variant is run beside it, with a region near the paper's.
    let fitted = outcome.fitted.as_ref().unwrap();
    let region = &fitted.regions[0];
    assert!(
        (8.5..9.1).contains(&region.start_time),
        "{}",
        region.start_time
    );
    let note = outcome.threshold_note();
    assert!(
        note.contains("not the paper's rule")
            && note.contains(&FITTED_DETERMINANT_THRESHOLD.to_string()),
        "{note}"
    );
    // The sweep: one line per miss, the avoidance within eps_dq / h.
    assert_eq!(outcome.sweep.lines.len(), 2);
    for line in &outcome.sweep.lines {
        assert!(line.avoidance.peak_joint_rate <= 0.5 * (1.0 + 1e-9));
    }
    assert_eq!(outcome.sweep.lines[0].bounded_knots, 0);
    assert!(outcome.sweep.lines[1].bounded_knots > 0);
    let checks = outcome.checks();
    assert!(checks.iter().all(|c| c.passed()), "{checks:#?}");
    // Findings: the claims with their figures and verdicts.
    let findings = outcome.findings();
    let verdict = |claim: &str| {
        findings
            .iter()
            .find(|f| f.claim.contains(claim))
            .unwrap_or_else(|| panic!("no finding on {claim}: {findings:#?}"))
    };
    let fig5 = verdict("Fig 5");
    let (baseline, first) = outcome.plain_jumps_at();
    let first = first.unwrap();
    assert!(baseline > 0.0);
    assert!(
        fig5.measured.contains(&format!("{first:.2} s")),
        "{}",
        fig5.measured
    );
    assert_eq!(
        fig5.status == FindingStatus::Reproduced,
        (first - 8.8).abs() <= 0.3
    );
    assert_eq!(verdict("sec 3").status, FindingStatus::NotReproduced);
    // Figs 7-8: the entry errors are equal for every k here (the runs share
    // the tracking before the entry), so the entry ordering does not hold.
    assert_eq!(
        verdict("on entering the region").status,
        FindingStatus::NotReproduced
    );
    let inside = verdict("inside the region");
    let means: Vec<f64> = outcome
        .comparison
        .k_sweep
        .iter()
        .map(|r| r.summary.mean_region_position_error)
        .collect();
    let rising = means.windows(2).all(|w| w[1] > w[0]) && means[0] <= 0.5 * means[2];
    // Resolved at seed 004's eps_T = 1e-8: k = 1, 5, 10 give clearly rising errors.
    assert!(rising, "{means:?}");
    // The errors compared lie at the IK tolerance: no evidence either way.
    let largest = means.iter().fold(0.0, |m: f64, e| m.max(*e));
    assert_eq!(
        inside.status == FindingStatus::NotReproduced,
        largest < 100.0 * outcome.options.ik_tolerance,
        "{}",
        inside.measured
    );
    assert!(findings
        .iter()
        .all(|f| !f.claim.contains("more computation")));
    assert!(checks
        .iter()
        .any(|c| c.is_invariant() && c.name.contains("fewer IK solves")));
    assert_eq!(verdict("conclusion 3").status, FindingStatus::Reproduced);
    assert!(verdict("conclusion 1").measured.contains("miss sweep"));
}

/// A line missing the wrist singularity by d = 1 or 3 mm.
/// The regions planned jointly keep every step within eps_dq and drop no
/// knot, err about the floor (the distance to the wrist-singular poses,
/// about d: the line is offset by d along the direction J loses there) and
/// about half the greedy plan; DLS clamped to the same speed stays within it.
#[test]
fn a_near_miss_planned_jointly_errs_the_floor() {
    use armkit::ik::NakamuraDamping;
    use armkit::singularity::{RegionPlan, SEED004_DIRECTION};
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let options = AvoidanceOptions::default();
    let eps_dq = options.detection.joint_step_threshold;
    let greedy_options = AvoidanceOptions {
        region_plan: RegionPlan::Greedy,
        ..options
    };
    for miss in [-0.003, 0.001] {
        let line = line_through(&manipulator, &SEED004_THROUGH, &SEED004_DIRECTION, miss).unwrap();
        let task = line.task(20.0, 4.0);
        let tracker = PathTracker::new(manipulator, task.clone(), options).unwrap();
        let joint = tracker.run(&Method::Avoidance { k: 1 }).unwrap();
        let greedy = PathTracker::new(manipulator, task, greedy_options)
            .unwrap()
            .run(&Method::Avoidance { k: 1 })
            .unwrap();
        let floor = tracker
            .singular_gap(4, 0.0, &SEED004_THROUGH, 10.0, 1.0)
            .unwrap();
        let d = miss.abs();
        println!(
            "miss {miss}: joint {:.3e}, greedy {:.3e}, floor {:.3e} (at {:.2} s)",
            joint.summary.max_pose_error, greedy.summary.max_pose_error, floor.norm, floor.time
        );
        assert_eq!(joint.status, TrackingStatus::Completed);
        for region in &joint.regions {
            assert_eq!(region.knot_times.len(), region.ik_solves + 1);
        }
        assert!(joint.regions.iter().any(|r| r.plan == RegionPlan::Joint));
        assert!(greedy.regions.iter().all(|r| r.plan == RegionPlan::Greedy));
        assert!(largest_step(&joint, 0.01) <= eps_dq * (1.0 + 1e-9));
        assert!(joint.summary.final_position_error <= 1e-6);
        // The floor: about d, near mid-path.
        assert!((floor.norm - d).abs() < 0.05 * d, "{floor:?}");
        assert!((floor.time - 10.0).abs() < 0.5, "{floor:?}");
        // The joint plan errs about the floor, the greedy one far more.
        let error = joint.summary.max_pose_error;
        assert!(
            error >= 0.95 * floor.norm && error <= 1.1 * floor.norm,
            "{error}"
        );
        assert!(error < 0.7 * greedy.summary.max_pose_error, "{error}");
        // DLS clamped to eps_dq / h: within it, and equal to DLS when DLS is.
        let nakamura = Baselines::for_detection(&options.detection).nakamura;
        let clamped = tracker
            .run(&Method::ClampedDampedLeastSquares {
                damping: nakamura,
                max_rate: eps_dq / 0.01,
            })
            .unwrap();
        assert!(clamped.summary.peak_joint_rate <= eps_dq / 0.01 * (1.0 + 1e-12));
        let dls = tracker.run(&Method::DampedLeastSquares(nakamura)).unwrap();
        if dls.summary.peak_joint_rate <= eps_dq / 0.01 {
            assert_eq!(dls.summary, clamped.summary);
        } else {
            assert!(clamped.summary.max_pose_error > dls.summary.max_pose_error);
        }
    }
    // Bad input: a rate bound that is not positive, a joint out of range.
    let line = seed004_path(&manipulator).unwrap();
    let tracker = PathTracker::new(manipulator, line.task(20.0, 4.0), options).unwrap();
    let bad = tracker.run(&Method::ClampedDampedLeastSquares {
        damping: NakamuraDamping::default(),
        max_rate: 0.0,
    });
    assert!(error_message(bad).contains("max_rate"));
    let bad = tracker.singular_gap(6, 0.0, &SEED004_THROUGH, 10.0, 1.0);
    assert!(error_message(bad).contains("joint"));
    let bad = tracker.singular_gap(4, 0.0, &SEED004_THROUGH, 10.0, f64::NAN);
    assert!(error_message(bad).contains("window"));
}

/// Seed 004's reference [9] (singularity separation with a damped
/// reciprocal) on a Jacobian whose step is worked by hand: arm block
/// `A = 2 I`, wrist linear block 0 (the wrist centre is the end effector),
/// `C` with one entry, wrist block `D = diag(1, 0.5, 0.01)`.
#[test]
fn the_separation_step_damps_only_the_smallest_wrist_reciprocal() {
    use armkit::ik::{separated_damped_reciprocal_step, DampedReciprocal};
    use armkit::math::{Matrix6xX, Vector6};
    let mut j = Matrix6xX::<f64>::zeros(6);
    for i in 0..3 {
        j[(i, i)] = 2.0;
    }
    j[(3, 0)] = 1.0;
    j[(3, 3)] = 1.0;
    j[(4, 4)] = 0.5;
    j[(5, 5)] = 0.01;
    let twist = Vector6::new(0.2, 0.4, -0.6, 1.0, 0.5, 0.02);
    let mut dq = [0.0; 6];
    let damping = DampedReciprocal::default(); // epsilon 0.05, lambda_max 0.05
    let sigma = separated_damped_reciprocal_step(&j, &twist, &damping, &mut dq).unwrap();
    // Arm: dq_a = v / 2. Wrist: w - C dq_a = (0.9, 0.5, 0.02); sigma = 0.01
    // < 0.05, lambda^2 = 0.05^2 (1 - 0.2^2) = 0.0024, reciprocal
    // 0.01 / (0.0001 + 0.0024) = 4 (the exact one: 100); the other two exact.
    let by_hand = [0.1, 0.2, -0.3, 0.9, 1.0, 0.08];
    assert!((sigma - 0.01).abs() < 1e-15, "{sigma}");
    for (got, want) in dq.iter().zip(by_hand) {
        assert!((got - want).abs() < 1e-12, "{dq:?} vs {by_hand:?}");
    }
    // Errors name what is wrong.
    let narrow = Matrix6xX::<f64>::zeros(5);
    let mut five = [0.0; 5];
    let message = separated_damped_reciprocal_step(&narrow, &twist, &damping, &mut five)
        .unwrap_err()
        .to_string();
    assert!(message.contains("6"), "{message}");
    let bad = DampedReciprocal {
        threshold: 0.0,
        ..damping
    };
    let message = separated_damped_reciprocal_step(&j, &twist, &bad, &mut dq)
        .unwrap_err()
        .to_string();
    assert!(message.contains("DampedReciprocal.threshold"), "{message}");
}

/// On space6r (tool offset: the end effector is not the wrist centre) the
/// separation finds the wrist centre from the Jacobian: at a regular pose it
/// is the exact inverse; near the wrist singularity its arm joints keep the
/// exact inverse's rates (the wrist block decoupled) while the wrist rates
/// are damped.
#[test]
fn the_separation_step_on_space6r_decouples_the_wrist() {
    use armkit::ik::{
        damped_least_squares_step, separated_damped_reciprocal_step, DampedReciprocal,
    };
    use armkit::math::Vector6;
    let arm = armkit::robots::space6r().unwrap();
    let mut data = Data::new(&arm);
    let twist = Vector6::new(0.05, -0.02, 0.03, 0.1, -0.2, 0.15);
    let damping = DampedReciprocal::default();
    let (mut exact, mut separated) = ([0.0; 6], [0.0; 6]);
    for (q5, damped) in [(0.9, false), (1e-3, true)] {
        let q = [0.4, 1.2, -0.5, 0.6, q5, -0.3];
        let j = jacobian(&arm, &mut data, &q, JacobianFrame::World)
            .unwrap()
            .clone();
        damped_least_squares_step(&j, &twist, 0.0, &mut exact).unwrap();
        let sigma = separated_damped_reciprocal_step(&j, &twist, &damping, &mut separated).unwrap();
        assert_eq!(sigma < damping.threshold, damped, "sigma {sigma}");
        for i in 0..3 {
            assert!(
                // The exact inverse at q5 = 1e-3 carries cond(J) ~ 1e4 times
                // the rounding error.
                (exact[i] - separated[i]).abs() <= 1e-7 * exact[i].abs().max(1.0),
                "q5 = {q5}: arm joint {i}: {exact:?} vs {separated:?}"
            );
        }
        let (wrist_exact, wrist_separated) = (
            exact[3..].iter().fold(0.0f64, |m, r| m.max(r.abs())),
            separated[3..].iter().fold(0.0f64, |m, r| m.max(r.abs())),
        );
        if damped {
            assert!(
                wrist_separated < 0.1 * wrist_exact,
                "{exact:?} vs {separated:?}"
            );
        } else {
            for i in 3..6 {
                assert!(
                    (exact[i] - separated[i]).abs() <= 1e-9,
                    "{exact:?} vs {separated:?}"
                );
            }
        }
    }
}

/// Seed 004's rows on the joints, the eps_dq sweep, eq 30's polynomial and
/// the reference-[9] comparator: each verdict against the figures
/// recomputed here from the runs.
#[test]
fn the_study_rows_on_joints_eps_dq_runge_and_the_reference_method() {
    use armkit::study::{interpolating_polynomial_rate, AvoidanceStudy, FindingStatus};
    let arm = armkit::robots::space6r().unwrap();
    let study = AvoidanceStudy {
        base: armkit::singularity::BaseKind::Fixed,
        miss_sweep: vec![0.0, 0.003],
        ..AvoidanceStudy::default()
    };
    let outcome = study.compare(Manipulator::FixedBase(&arm)).unwrap();
    let findings = outcome.findings();
    let verdict = |claim: &str| {
        findings
            .iter()
            .find(|f| f.claim.contains(claim))
            .unwrap_or_else(|| panic!("no finding on {claim}: {findings:#?}"))
    };
    let eps = outcome.options.detection.joint_step_threshold;
    let h = outcome.options.tracking.dt;
    // Jumping joints: plain's steps above eps_dq, joint by joint.
    let plain = &outcome.comparison.plain;
    let jumping: Vec<usize> = (0..6)
        .filter(|&j| plain.joint_rates[j].iter().any(|r| (r * h).abs() > eps))
        .collect();
    let jumps = verdict("the joints that jump");
    assert_eq!(
        jumps.status == FindingStatus::Reproduced,
        jumping == [3, 5],
        "{jumps}"
    );
    // Joints 1 to 3: the largest period-to-period change of their rates
    // inside the region against anywhere else.
    let avoidance = &outcome.comparison.avoidance;
    let unaffected = (0..3).all(|j| {
        let rates = &avoidance.joint_rates[j];
        let (mut inside, mut outside) = (0.0f64, 0.0f64);
        for i in 0..rates.len() - 2 {
            let change = (rates[i + 1] - rates[i]).abs();
            if avoidance.in_region[i] || avoidance.in_region[i + 1] {
                inside = inside.max(change);
            } else {
                outside = outside.max(change);
            }
        }
        inside <= 2.0 * outside
    });
    let joints = verdict("joints 1 to 3 are unaffected");
    assert_eq!(
        joints.status == FindingStatus::Reproduced,
        unaffected,
        "{joints}"
    );
    // eps_dq sweep: one row per value; on space6r the region never grows
    // (on the PUMA 560 it does: the user scenarios show it), and the verdict
    // is whether it shrinks at every step.
    assert_eq!(outcome.eps_sweep.len(), study.joint_step_sweep.len());
    let lengths: Vec<f64> = outcome.eps_sweep.iter().map(|r| r.region_length).collect();
    assert!(
        lengths.windows(2).all(|w| w[1] <= w[0] + 1e-9),
        "{lengths:?}"
    );
    let shrinking = verdict("the larger eps_dq");
    assert_eq!(
        shrinking.status == FindingStatus::Reproduced,
        lengths.windows(2).all(|w| w[1] < w[0]),
        "{shrinking}"
    );
    assert!(!outcome
        .checks()
        .iter()
        .any(|c| c.name.contains("eps_dq sweep")));
    // The row of the default eps_dq is the study's own run.
    let own = outcome
        .eps_sweep
        .iter()
        .find(|r| r.joint_step_threshold == eps)
        .unwrap();
    let span = (
        avoidance.regions[0].start_time,
        avoidance.regions.last().unwrap().end_time,
    );
    assert_eq!(own.region, Some(span));
    // Runge: the polynomial through the first k's knots against its run.
    let (k, run) = (study.ks[0], &outcome.comparison.k_sweep[0]);
    let samples: Vec<usize> = run.regions[0]
        .knot_times
        .iter()
        .map(|t| (t / h).round() as usize)
        .collect();
    let nodes: Vec<f64> = samples.iter().map(|&i| (i - samples[0]) as f64).collect();
    let (mut polynomial, mut fit) = (0.0f64, 0.0f64);
    for j in 0..6 {
        let values: Vec<f64> = samples.iter().map(|&i| run.joint_positions[j][i]).collect();
        for i in samples[0]..*samples.last().unwrap() {
            let x = (i - samples[0]) as f64 + 0.5;
            polynomial =
                polynomial.max((interpolating_polynomial_rate(&nodes, &values, x) / h).abs());
            fit = fit.max(run.joint_rates[j][i].abs());
        }
    }
    let runge = verdict("Runge");
    let row = format!("{k} | {} | {polynomial:.3e} | {fit:.3e}", samples.len());
    assert!(runge.measured.contains(&row), "{row}: {runge}");
    if polynomial >= 10.0 * fit {
        assert_eq!(runge.status, FindingStatus::Reproduced, "{runge}");
    }
    if runge.status == FindingStatus::Reproduced {
        assert!(
            runge.measured.contains("Runge shown for k = ") && !runge.measured.contains("k = none")
        );
    }
    // Conclusion 1: one finding per comparator, each naming it; the
    // reference [9] run on every line of the sweep.
    let reference = verdict("comparator: separation");
    let damped = verdict("comparator: DLS and SRI");
    let no_worse = |other: fn(&armkit::study::MissLine) -> &armkit::singularity::MethodSummary| {
        outcome
            .sweep
            .lines
            .iter()
            .all(|l| l.avoidance_errs_no_more_than(other(l)))
    };
    assert_eq!(
        reference.status == FindingStatus::Reproduced,
        no_worse(|l| &l.separation),
        "{reference}"
    );
    assert_eq!(
        damped.status == FindingStatus::Reproduced,
        no_worse(|l| &l.damped_least_squares) && no_worse(|l| &l.singularity_robust),
        "{damped}"
    );
    let separation = outcome.comparison.separation.as_ref().unwrap();
    assert_eq!(separation.method.label(), "separation");
    assert_eq!(separation.status, TrackingStatus::Completed);
}

/// The plan as printed ([`RegionPlan::Exact`]) keeps every Newton knot on a
/// 3 mm near miss: no least-squares knot, the pose tracked to the IK's
/// accuracy, and the wrist flipping faster than the eps_dq bound the other
/// plans keep (the joint plan stays within it on the same line).
#[test]
fn the_exact_region_plan_keeps_newton_knots_beyond_the_rate_bound() {
    use armkit::singularity::{RegionPlan, SEED004_DIRECTION};
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = line_through(&manipulator, &SEED004_THROUGH, &SEED004_DIRECTION, 0.003).unwrap();
    let task = line.task(20.0, 4.0);
    let options = AvoidanceOptions::default();
    let eps_dq = options.detection.joint_step_threshold;
    let run = |plan: RegionPlan| {
        let options = AvoidanceOptions {
            region_plan: plan,
            ..options
        };
        PathTracker::new(manipulator, task.clone(), options)
            .unwrap()
            .run(&Method::Avoidance { k: 1 })
            .unwrap()
    };
    let exact = run(RegionPlan::Exact);
    let joint = run(RegionPlan::Joint);
    assert_eq!(exact.status, TrackingStatus::Completed);
    assert!(!exact.regions.is_empty());
    assert!(exact
        .regions
        .iter()
        .all(|r| r.plan == RegionPlan::Exact && r.bounded_knots == 0));
    assert!(joint.regions.iter().any(|r| r.bounded_knots > 0));
    assert!(largest_step(&exact, 0.01) > 5.0 * eps_dq);
    assert!(largest_step(&joint, 0.01) <= eps_dq * (1.0 + 1e-9));
    // Exact knots: the error stays orders below the joint plan's (about
    // the 3 mm miss).
    assert!(exact.summary.max_pose_error < 1e-5, "{:?}", exact.summary);
    assert!(joint.summary.max_pose_error > 1e-3, "{:?}", joint.summary);
    // The plans by name, and a bad one named.
    for plan in [RegionPlan::Joint, RegionPlan::Greedy, RegionPlan::Exact] {
        assert_eq!(plan.as_str().parse::<RegionPlan>().unwrap(), plan);
    }
    let err = "printed".parse::<RegionPlan>().unwrap_err().to_string();
    assert!(
        err.contains("region_plan") && err.contains("exact"),
        "{err}"
    );
}

/// Open loop (`V = V_d`) lets the discrete steps' error accumulate; the
/// next-pose feedback of seed 004 (eqs 26-27) corrects it every period.
#[test]
fn open_loop_tracking_accumulates_the_error_next_pose_feedback_removes() {
    use armkit::singularity::SEED004_DIRECTION;
    use armkit::tracking::Feedback;
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = line_through(&manipulator, &SEED004_THROUGH, &SEED004_DIRECTION, 0.03).unwrap();
    let task = line.task(20.0, 4.0);
    let run = |feedback: Feedback| {
        let mut options = AvoidanceOptions::default();
        options.tracking.feedback = feedback;
        PathTracker::new(manipulator, task.clone(), options)
            .unwrap()
            .run(&Method::Plain)
            .unwrap()
    };
    let open = run(Feedback::OpenLoop);
    let closed = run(Feedback::NextPose);
    assert_eq!(open.status, TrackingStatus::Completed);
    assert_eq!(Feedback::OpenLoop.to_string(), "open-loop");
    // Open loop: the error grows along the path (the second half's largest
    // above the first quarter's) and ends far above the closed loop's.
    let quarter = open.position_error.len() / 4;
    let early = open.position_error[..quarter]
        .iter()
        .fold(0.0, |m: f64, e| m.max(*e));
    assert!(open.summary.final_position_error > 2.0 * early, "{early}");
    assert!(
        open.summary.final_position_error > 100.0 * closed.summary.final_position_error.max(1e-12),
        "{:?} {:?}",
        open.summary,
        closed.summary
    );
}
