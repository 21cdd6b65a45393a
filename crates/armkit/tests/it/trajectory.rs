//! Trajectory generation: boundary conditions, continuity, limits, Cartesian
//! paths, and seed 002's continuous-path method on arm4 and panda.
//!
//! Run with `--nocapture` to see the figures (segments, path errors, times).

use crate::common;

use std::f64::consts::PI;

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{DMatrix, DVector, Pose, Vector3};
use armkit::trajectory::clamped_cubic_spline;
use armkit::trajectory::{self, JointState, Trajectory};
use armkit::trajectory::{
    check_limits, peak_rates, scale_to_limits, LimitKind, TimeScaling, TrajectoryLimits,
};
use armkit::trajectory::{
    interpolate_via_points, measure_path_error, plan_continuous_path, BoundaryRates,
    ContinuousPathOptions, ContinuousPathReport, PathStatus, PathTolerance, SegmentScheme,
    Segmentation, ViaVelocity,
};
use armkit::trajectory::{path_ik_for, IkTask, NumericPathIk};
use armkit::trajectory::{
    ArcOrientation, ArcPath, CartesianPath, CartesianTrajectory, FnPath, LinePath, OrientationLaw,
    TimeLaw,
};
use armkit::{Error, Model};
use rand::Rng;

const BC: f64 = 1e-12;

fn random_state(rng: &mut impl Rng, dof: usize) -> JointState {
    let mut v = || {
        (0..dof)
            .map(|_| rng.gen_range(-2.0..2.0))
            .collect::<Vec<f64>>()
    };
    JointState::new(v(), v(), v())
}

fn segment_state(traj: &Trajectory, segment: usize, phi: f64) -> JointState {
    let mut s = JointState::zeros(traj.dof());
    traj.sample_segment_into(segment, phi, &mut s).unwrap();
    s
}

/// Largest |a - b| / max(1, |b|).
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs().max(1.0))
        .fold(0.0, f64::max)
}

fn message(result: Result<impl std::fmt::Debug, Error>) -> String {
    result.unwrap_err().to_string()
}

// ---------------------------------------------------------------- profiles

#[test]
fn cubic_and_quintic_meet_their_boundary_conditions() {
    let mut rng = common::rng(1);
    let mut worst = [0.0f64; 2];
    for _ in 0..20 {
        let duration = rng.gen_range(0.1..10.0);
        let mut start = random_state(&mut rng, 7);
        let mut end = random_state(&mut rng, 7);
        let quintic = trajectory::quintic(&start, &end, duration).unwrap();
        let (a, b) = (
            segment_state(&quintic, 0, 0.0),
            segment_state(&quintic, 0, 1.0),
        );
        // sample(t) at the ends is the segment's ends.
        assert_eq!(quintic.sample(0.0).unwrap(), a);
        assert_eq!(quintic.sample(duration).unwrap(), quintic.end_state());
        assert_eq!(quintic.end_state(), b);
        for (got, want) in [
            (&a.position, &start.position),
            (&a.velocity, &start.velocity),
            (&a.acceleration, &start.acceleration),
            (&b.position, &end.position),
            (&b.velocity, &end.velocity),
            (&b.acceleration, &end.acceleration),
        ] {
            worst[1] = worst[1].max(rel_diff(got, want));
        }
        start.acceleration.fill(0.0);
        end.acceleration.fill(0.0);
        let cubic = trajectory::cubic(&start, &end, duration).unwrap();
        let (a, b) = (segment_state(&cubic, 0, 0.0), segment_state(&cubic, 0, 1.0));
        for (got, want) in [
            (&a.position, &start.position),
            (&a.velocity, &start.velocity),
            (&b.position, &end.position),
            (&b.velocity, &end.velocity),
        ] {
            worst[0] = worst[0].max(rel_diff(got, want));
        }
    }
    println!(
        "boundary conditions, worst error: cubic {:.1e}, quintic {:.1e}",
        worst[0], worst[1]
    );
    assert!(worst[0] < BC && worst[1] < BC, "{worst:?}");
}

#[test]
fn profiles_match_finite_differences_of_their_positions() {
    // Velocity and acceleration are the exact derivatives of the position.
    let q0 = [0.2, -1.0, 0.5];
    let qf = [1.4, 0.3, 0.5];
    let trajectories = [
        trajectory::rest_to_rest(trajectory::ProfileShape::Cubic, &q0, &qf, 3.0, None).unwrap(),
        trajectory::rest_to_rest(trajectory::ProfileShape::Quintic, &q0, &qf, 3.0, None).unwrap(),
        trajectory::trapezoidal(&q0, &qf, 3.0, 1.0).unwrap(),
    ];
    let h = 1e-5;
    for traj in &trajectories {
        for k in 1..30 {
            let t = 3.0 * k as f64 / 30.0 + 0.0123;
            let (m, c, p) = (
                traj.sample(t - h).unwrap(),
                traj.sample(t).unwrap(),
                traj.sample(t + h).unwrap(),
            );
            for j in 0..3 {
                let v = (p.position[j] - m.position[j]) / (2.0 * h);
                let a = (p.velocity[j] - m.velocity[j]) / (2.0 * h);
                assert!(
                    (v - c.velocity[j]).abs() < 1e-8,
                    "t {t} joint {j}: {v} vs {}",
                    c.velocity[j]
                );
                assert!(
                    (a - c.acceleration[j]).abs() < 1e-7,
                    "t {t} joint {j}: {a} vs {}",
                    c.acceleration[j]
                );
            }
        }
    }
}

#[test]
fn trapezoid_seed004_meets_boundaries_and_is_c1_at_every_knot() {
    // Seed 004's timing: 20 s with 4 s of acceleration and deceleration.
    let q0 = [0.1, -0.4, 1.0, 0.0, 2.0, -1.5];
    let qf = [1.7, 0.4, -1.0, 0.0, 2.5, 1.5];
    let traj = trajectory::trapezoidal(&q0, &qf, 20.0, 4.0).unwrap();
    assert_eq!(traj.knots(), &[0.0, 4.0, 16.0, 20.0]);
    let start = segment_state(&traj, 0, 0.0);
    let end = segment_state(&traj, 2, 1.0);
    assert!(
        common::max_abs_difference(&start.position, &q0) < BC
            && common::max_abs_difference(&end.position, &qf) < BC
    );
    assert!(start
        .velocity
        .iter()
        .chain(&end.velocity)
        .all(|v| v.abs() < BC));
    for j in 0..6 {
        let cruise = (qf[j] - q0[j]) / 16.0; // d / (T - ta)
        let mid = traj.sample(10.0).unwrap();
        assert!((mid.velocity[j] - cruise).abs() < BC);
        assert!((start.acceleration[j] - cruise / 4.0).abs() < BC);
        assert!((end.acceleration[j] + cruise / 4.0).abs() < BC);
    }
    // Every segment's ends: at 4 s and 16 s the cruise velocity, positions
    // a ramp (v ta / 2) from the ends, on both sides of the knot.
    for (segment, phi, offset) in [(0, 1.0, 2.0), (1, 0.0, 2.0), (1, 1.0, 14.0), (2, 0.0, 14.0)] {
        let s = segment_state(&traj, segment, phi);
        for j in 0..6 {
            let cruise = (qf[j] - q0[j]) / 16.0;
            assert!((s.velocity[j] - cruise).abs() < BC);
            assert!((s.position[j] - (q0[j] + cruise * offset)).abs() < BC);
        }
    }
    // Continuous position and velocity at 4 s and 16 s (acceleration steps by design).
    let [dq, dv, _] = traj.knot_discontinuities();
    assert!(dq < BC && dv < BC, "{dq} {dv}");
    // A triangular profile (ta = T/2) has two segments.
    let triangle = trajectory::trapezoidal(&q0, &qf, 2.0, 1.0).unwrap();
    assert_eq!(triangle.segment_count(), 2);
    assert!(common::max_abs_difference(&triangle.end_state().position, &qf) < BC);
}

#[test]
fn trapezoid_with_equal_endpoints_stays_put() {
    let q = [0.3, -0.2, 1.1];
    let traj = trajectory::trapezoidal(&q, &q, 5.0, 1.0).unwrap();
    for k in 0..=50 {
        let s = traj.sample(5.0 * k as f64 / 50.0).unwrap();
        assert_eq!(s.position, q.to_vec());
        assert!(s.velocity.iter().chain(&s.acceleration).all(|&v| v == 0.0));
    }
    // Minimum time of a zero-length move: zero, and still a valid trajectory.
    let limits = TrajectoryLimits::new(vec![1.0; 3], vec![1.0; 3]).unwrap();
    for shape in [
        trajectory::ProfileShape::Trapezoidal,
        trajectory::ProfileShape::Quintic,
    ] {
        let traj = trajectory::minimum_time(shape, &q, &q, &limits).unwrap();
        assert_eq!(traj.duration(), 0.0);
        let s = traj.sample(0.7).unwrap();
        assert_eq!(s.position, q.to_vec());
        assert!(s.velocity.iter().chain(&s.acceleration).all(|&v| v == 0.0));
    }
}

#[test]
fn bad_durations_are_clear_errors() {
    let (q0, qf) = ([0.0, 1.0], [1.0, 0.0]);
    assert_eq!(
        message(trajectory::trapezoidal(&q0, &qf, 0.0, 0.0)),
        "invalid argument `duration`: must be in [0.001, 1e6] s, got 0 s"
    );
    assert_eq!(
        message(trajectory::trapezoidal(&q0, &qf, -2.0, 0.5)),
        "invalid argument `duration`: must be in [0.001, 1e6] s, got -2 s"
    );
    // The range holds for every profile, at both ends.
    let (rest0, rest1) = (JointState::at_rest(&q0), JointState::at_rest(&qf));
    for duration in [1e-300, 9.99e-4, 1.000001e6, 1e300] {
        let expected = format!(
            "invalid argument `duration`: must be in [0.001, 1e6] s, got {} s",
            armkit::error::brief(duration)
        );
        assert_eq!(
            message(trajectory::cubic(&rest0, &rest1, duration)),
            expected
        );
        assert_eq!(
            message(trajectory::quintic(&rest0, &rest1, duration)),
            expected
        );
        assert_eq!(
            message(trajectory::trapezoidal(&q0, &qf, duration, duration / 4.0)),
            expected
        );
    }
    for duration in [1e-3, 1e6] {
        assert!(trajectory::cubic(&rest0, &rest1, duration).is_ok());
        assert!(trajectory::trapezoidal(&q0, &qf, duration, duration / 4.0).is_ok());
    }
    assert_eq!(
        message(trajectory::trapezoidal(&q0, &qf, 10.0, 6.0)),
        "invalid argument `acceleration_time`: must be at most half the duration (5 s) so that \
         acceleration and deceleration do not overlap, got 6 s"
    );
    assert_eq!(
        message(trajectory::trapezoidal(&q0, &qf, 10.0, 0.0)),
        "invalid argument `acceleration_time`: must be finite and > 0 s, got 0 s"
    );
    let rest = JointState::at_rest(&q0);
    assert!(
        message(trajectory::quintic(&rest, &JointState::at_rest(&qf), -1.0)).contains("`duration`")
    );
    assert!(message(trajectory::cubic(
        &rest,
        &JointState::at_rest(&qf),
        f64::NAN
    ))
    .contains("`duration`"));
    assert_eq!(
        message(trajectory::trapezoidal(&q0, &[1.0], 1.0, 0.2)),
        "qf: expected 2 values, got 1"
    );
    let accelerating = JointState::new(vec![0.0, 1.0], vec![0.0; 2], vec![1.0, 0.0]);
    assert!(message(trajectory::cubic(&accelerating, &rest, 1.0))
        .contains("cannot meet a boundary acceleration"));
    assert!(message(Trajectory::stationary(&q0, 0.0, -1.0)).contains("`duration`"));
}

#[test]
fn a_minimum_time_move_shorter_than_the_shortest_profile_is_stretched_within_its_limits() {
    // 1e-9 rad at 2 rad/s and 10 rad/s^2 takes 2e-5 s: planned in MIN_DURATION.
    let limits = TrajectoryLimits::new(vec![2.0], vec![10.0]).unwrap();
    let traj = trajectory::minimum_time(
        trajectory::ProfileShape::Trapezoidal,
        &[0.0],
        &[1e-9],
        &limits,
    )
    .unwrap();
    assert_eq!(traj.duration(), trajectory::MIN_DURATION);
    assert!(check_limits(&traj, &limits).unwrap().is_empty());
    let end = traj.sample(traj.duration()).unwrap();
    assert!((end.position[0] - 1e-9).abs() < 1e-20);
}

#[test]
fn minimum_time_profiles_touch_the_binding_limit() {
    // One joint, closed forms: trapezoid T = d/v + v/a (or 2 sqrt(d/a) if
    // triangular), cubic T = max(1.5 d/v, sqrt(6 d/a)), quintic
    // T = max(1.875 d/v, sqrt(10/sqrt(3) d/a)).
    let cases = [(2.0, 1.0, 2.0), (0.2, 1.0, 2.0), (1.0, 3.0, 0.5)];
    for (d, v, a) in cases {
        let limits = TrajectoryLimits::new(vec![v], vec![a]).unwrap();
        let trapezoid =
            trajectory::minimum_time(trajectory::ProfileShape::Trapezoidal, &[0.0], &[d], &limits)
                .unwrap();
        let expected = if d >= v * v / a {
            d / v + v / a
        } else {
            2.0 * (d / a).sqrt()
        };
        assert!(
            (trapezoid.duration() - expected).abs() < 1e-12,
            "{d} {v} {a}"
        );
        let cubic =
            trajectory::minimum_time(trajectory::ProfileShape::Cubic, &[0.0], &[d], &limits)
                .unwrap();
        let expected = (1.5 * d / v).max((6.0 * d / a).sqrt());
        assert!((cubic.duration() - expected).abs() < 1e-12);
        let quintic =
            trajectory::minimum_time(trajectory::ProfileShape::Quintic, &[0.0], &[d], &limits)
                .unwrap();
        let expected = (1.875 * d / v).max((10.0 / 3f64.sqrt() * d / a).sqrt());
        assert!((quintic.duration() - expected).abs() < 1e-12);
    }
    // Many joints: synchronized, within every limit, one limit active.
    let mut rng = common::rng(2);
    let model = armkit::robots::by_name("panda").unwrap();
    let limits = TrajectoryLimits::from_model(&model);
    for _ in 0..20 {
        let q0 = common::random_configuration(&model, &mut rng);
        let qf = common::random_configuration(&model, &mut rng);
        for shape in [
            trajectory::ProfileShape::Trapezoidal,
            trajectory::ProfileShape::Cubic,
            trajectory::ProfileShape::Quintic,
        ] {
            let traj = trajectory::minimum_time(shape, &q0, &qf, &limits).unwrap();
            assert!(
                check_limits(&traj, &limits).unwrap().is_empty(),
                "{shape:?}"
            );
            let peaks = peak_rates(&traj);
            let usage = (0..7)
                .map(|j| {
                    (peaks.velocity[j] / limits.velocity[j])
                        .max(peaks.acceleration[j] / limits.acceleration[j])
                })
                .fold(0.0, f64::max);
            assert!(
                (usage - 1.0).abs() < 1e-9,
                "{shape:?}: largest limit usage {usage}"
            );
            assert!(common::max_abs_difference(&traj.end_state().position, &qf) < BC);
        }
    }
    let unlimited = TrajectoryLimits::new(vec![1.0], vec![f64::INFINITY]).unwrap();
    assert!(message(trajectory::minimum_time(
        trajectory::ProfileShape::Trapezoidal,
        &[0.0],
        &[1.0],
        &unlimited
    ))
    .contains("limits.acceleration[0]"));
}

// ---------------------------------------------------------------- spline

#[test]
fn clamped_spline_interpolates_and_is_c2() {
    let mut rng = common::rng(3);
    let mut times = vec![0.5];
    for _ in 0..9 {
        let last = *times.last().unwrap();
        times.push(last + rng.gen_range(0.05..2.0));
    }
    let points: Vec<Vec<f64>> = times
        .iter()
        .map(|_| (0..6).map(|_| rng.gen_range(-3.0..3.0)).collect())
        .collect();
    let v0: Vec<f64> = (0..6).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let vf: Vec<f64> = (0..6).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let spline = clamped_cubic_spline(&times, &points, &v0, &vf).unwrap();
    assert_eq!(spline.start_time(), 0.5);
    for i in 0..spline.segment_count() {
        assert!(
            common::max_abs_difference(&segment_state(&spline, i, 0.0).position, &points[i]) < BC
        );
        assert!(
            common::max_abs_difference(&segment_state(&spline, i, 1.0).position, &points[i + 1])
                < BC * 10.0
        );
    }
    assert!(common::max_abs_difference(&spline.start_state().velocity, &v0) < BC * 100.0);
    assert!(common::max_abs_difference(&spline.end_state().velocity, &vf) < BC * 100.0);
    let [dq, dv, da] = spline.knot_discontinuities();
    println!("spline knot jumps: position {dq:.1e}, velocity {dv:.1e}, acceleration {da:.1e}");
    assert!(dq < BC * 10.0 && dv < 1e-11 && da < 1e-9, "{dq} {dv} {da}");
}

#[test]
fn clamped_spline_reproduces_a_cubic() {
    // Samples of a cubic with its exact end slopes: the spline is that cubic.
    let f = |t: f64| 0.3 - 1.2 * t + 0.7 * t * t - 0.15 * t * t * t;
    let df = |t: f64| -1.2 + 1.4 * t - 0.45 * t * t;
    let times = [0.0, 0.4, 1.5, 1.9, 3.0, 4.2];
    let points: Vec<[f64; 1]> = times.iter().map(|&t| [f(t)]).collect();
    let spline = clamped_cubic_spline(&times, &points, &[df(0.0)], &[df(4.2)]).unwrap();
    for k in 0..=100 {
        let t = 4.2 * k as f64 / 100.0;
        assert!((spline.sample(t).unwrap().position[0] - f(t)).abs() < 1e-13);
    }
    assert!(message(clamped_cubic_spline(
        &[0.0, 1.0, 1.0],
        &points[..3],
        &[0.0],
        &[0.0]
    ))
    .contains("strictly increasing"));
    assert!(
        message(clamped_cubic_spline(&[0.0], &points[..1], &[0.0], &[0.0])).contains("at least 2")
    );
}

// ---------------------------------------------------------------- seed 002 schemes

/// Random via points (6 joints) at uneven times.
fn random_via_points(rng: &mut impl Rng, n: usize) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mut times = vec![0.0];
    for _ in 0..n {
        let last = *times.last().unwrap();
        times.push(last + rng.gen_range(0.2..1.0));
    }
    let points = times
        .iter()
        .map(|_| (0..6).map(|_| rng.gen_range(-2.0..2.0)).collect())
        .collect();
    (times, points)
}

#[test]
fn seed002_schemes_meet_every_boundary_condition() {
    let mut rng = common::rng(4);
    for n in [1, 2, 3, 6] {
        let (times, points) = random_via_points(&mut rng, n);
        let start = random_state(&mut rng, 6);
        let end = random_state(&mut rng, 6);
        let boundary = BoundaryRates::Given {
            start: start.clone(),
            end: end.clone(),
        };
        for scheme in [
            SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference),
            SegmentScheme::QuarticCubicQuartic(ViaVelocity::CentralDifference),
            SegmentScheme::CubicQuinticLast,
        ] {
            let traj = interpolate_via_points(scheme, &times, &points, &boundary).unwrap();
            assert_eq!(traj.segment_count(), n);
            // Every segment starts and ends on its via points; start and end
            // velocity and acceleration as given (relative to max(1, |value|)).
            let mut worst = 0.0f64;
            for i in 0..n {
                worst = worst.max(rel_diff(&segment_state(&traj, i, 0.0).position, &points[i]));
                worst = worst.max(rel_diff(
                    &segment_state(&traj, i, 1.0).position,
                    &points[i + 1],
                ));
            }
            let (a, b) = (traj.start_state(), traj.end_state());
            for (got, want) in [
                (&a.velocity, &start.velocity),
                (&a.acceleration, &start.acceleration),
                (&b.velocity, &end.velocity),
                (&b.acceleration, &end.acceleration),
            ] {
                worst = worst.max(rel_diff(got, want));
            }
            // The C2 scheme carries amplified rates (see the amplification
            // test): its end conditions are exact relative to those.
            let scale = (0..n)
                .map(|i| {
                    let s = segment_state(&traj, i, 0.0);
                    s.velocity
                        .iter()
                        .chain(&s.acceleration)
                        .fold(1.0f64, |m, v| m.max(v.abs()))
                })
                .fold(1.0, f64::max);
            println!(
                "{scheme:?}, {n} segments: worst boundary condition error {worst:.1e} \
                 (largest rate carried {scale:.1e}, relative {:.1e})",
                worst / scale
            );
            assert!(worst / scale < BC, "{scheme:?} n {n}: {worst:e}");
            if scheme != SegmentScheme::CubicQuinticLast {
                assert!(worst < BC, "{scheme:?} n {n}: {worst:e}");
            }
            let [dq, dv, da] = traj.knot_discontinuities();
            assert!(dq < BC * 10.0 && dv < 1e-10, "{scheme:?}: {dq} {dv}");
            match scheme {
                SegmentScheme::CubicQuinticLast => assert!(da < 1e-9, "C2 promised: {da}"),
                SegmentScheme::QuarticCubicQuartic(estimate) => {
                    // The via velocities are eq 23's (or the central) differences.
                    for i in 1..n {
                        let left = segment_state(&traj, i - 1, 1.0);
                        for (j, v) in left.velocity.iter().enumerate() {
                            let back =
                                (points[i][j] - points[i - 1][j]) / (times[i] - times[i - 1]);
                            let next =
                                (points[i + 1][j] - points[i][j]) / (times[i + 1] - times[i]);
                            let (hb, hn) = (times[i] - times[i - 1], times[i + 1] - times[i]);
                            let expected = match estimate {
                                ViaVelocity::BackwardDifference => back,
                                ViaVelocity::CentralDifference => {
                                    (hn * back + hb * next) / (hb + hn)
                                }
                            };
                            assert!((v - expected).abs() < 1e-11);
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn finite_difference_boundary_rates_follow_eqs_23_24() {
    let times = [0.0, 0.5, 1.5, 2.0];
    let points = [vec![0.0], vec![1.0], vec![1.5], vec![3.0]];
    let traj = interpolate_via_points(
        SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference),
        &times,
        &points,
        &BoundaryRates::FiniteDifference,
    )
    .unwrap();
    // End: v3 = (3 - 1.5) / 0.5 = 3, v2 = 0.5 / 1 = 0.5, a3 = (3 - 0.5) / 0.5 = 5.
    let end = traj.end_state();
    assert!((end.velocity[0] - 3.0).abs() < 1e-12 && (end.acceleration[0] - 5.0).abs() < 1e-11);
    // Start: v0 = 1 / 0.5 = 2, a0 = (0.5 - 2) / 0.5 = -3.
    let start = traj.start_state();
    assert!((start.velocity[0] - 2.0).abs() < 1e-12 && (start.acceleration[0] + 3.0).abs() < 1e-11);
}

#[test]
fn cubic_quintic_last_scheme_amplifies_errors_by_2_plus_sqrt3_per_segment() {
    // Two plans differing only in the start velocity: the difference of the
    // velocities carried to knot k grows like (2 + sqrt 3)^k on even knots.
    let n = 12;
    let times: Vec<f64> = (0..=n).map(|i| i as f64 * 0.1).collect();
    let points: Vec<Vec<f64>> = times.iter().map(|t| vec![t.sin()]).collect();
    let plan = |v0: f64| {
        let start = JointState::new(vec![0.0], vec![v0], vec![0.0]);
        let boundary = BoundaryRates::Given {
            start,
            end: JointState::at_rest(&[0.0]),
        };
        interpolate_via_points(SegmentScheme::CubicQuinticLast, &times, &points, &boundary).unwrap()
    };
    let (a, b) = (plan(1.0), plan(1.0 + 1e-9));
    let diff = |k: usize| {
        (segment_state(&a, k, 0.0).velocity[0] - segment_state(&b, k, 0.0).velocity[0]).abs()
    };
    let ratio = diff(n - 1) / diff(n - 2);
    println!(
        "cubic-quintic-last: error growth per segment {ratio:.4} (2 + sqrt 3 = {:.4})",
        2.0 + 3f64.sqrt()
    );
    assert!((ratio - (2.0 + 3f64.sqrt())).abs() < 1e-3, "{ratio}");
}

// ---------------------------------------------------------------- limits

#[test]
fn limit_violations_are_located_exactly() {
    // Quintic rest to rest over d = 1 in T = 1: v = 30 s^2 (1 - s)^2, peak
    // 1.875 at 0.5; a = 60 s (1 - s)(1 - 2 s), peak 10/sqrt(3) at 0.5 -+ sqrt(3)/6.
    let traj = trajectory::quintic(
        &JointState::at_rest(&[0.0]),
        &JointState::at_rest(&[1.0]),
        1.0,
    )
    .unwrap();
    let limits = TrajectoryLimits {
        lower: vec![-1.0],
        upper: vec![0.9],
        velocity: vec![1.5],
        acceleration: vec![5.0],
    };
    let violations = check_limits(&traj, &limits).unwrap();
    let velocity: Vec<_> = violations
        .iter()
        .filter(|v| v.kind == LimitKind::Velocity)
        .collect();
    assert_eq!(velocity.len(), 1);
    let v = velocity[0];
    // 30 s^2 (1 - s)^2 = 1.5  <=>  s (1 - s) = sqrt(0.05).
    let root = 0.5 - (0.25 - 0.05f64.sqrt()).sqrt();
    assert!((v.start_time - root).abs() < 1e-12 && (v.end_time - (1.0 - root)).abs() < 1e-12);
    assert!((v.peak_value - 1.875).abs() < 1e-12 && (v.peak_time - 0.5).abs() < 1e-7);
    let acceleration: Vec<_> = violations
        .iter()
        .filter(|v| v.kind == LimitKind::Acceleration)
        .collect();
    assert_eq!(acceleration.len(), 2);
    assert!(acceleration[0].peak_value > 0.0 && acceleration[1].peak_value < 0.0);
    assert!((acceleration[0].peak_value - 10.0 / 3f64.sqrt()).abs() < 1e-12);
    assert!((acceleration[0].peak_time - (0.5 - 3f64.sqrt() / 6.0)).abs() < 1e-7);
    let position: Vec<_> = violations
        .iter()
        .filter(|v| v.kind == LimitKind::Position)
        .collect();
    assert_eq!(position.len(), 1);
    assert!((position[0].end_time - 1.0).abs() < 1e-12 && position[0].bound == 0.9);
    // A violation that spans a knot is one interval: a trapezoid's cruise.
    let trapezoid = trajectory::trapezoidal(&[0.0], &[1.0], 2.0, 0.5).unwrap();
    let limits = TrajectoryLimits::new(vec![0.6], vec![10.0]).unwrap();
    let violations = check_limits(&trapezoid, &limits).unwrap();
    assert_eq!(violations.len(), 1, "{violations:?}");
    let v = &violations[0];
    // v(t) = t / 0.75 on the ramp: exceeds 0.6 from t = 0.45 to 1.55.
    assert!((v.start_time - 0.45).abs() < 1e-12 && (v.end_time - 1.55).abs() < 1e-12);
}

#[test]
fn time_scaling_meets_the_limits_and_keeps_the_path() {
    let mut rng = common::rng(5);
    let (times, points) = random_via_points(&mut rng, 8);
    let spline = clamped_cubic_spline(&times, &points, &[0.0; 6], &[0.0; 6]).unwrap();
    let limits = TrajectoryLimits::new(vec![0.5; 6], vec![1.0; 6]).unwrap();
    assert!(!check_limits(&spline, &limits).unwrap().is_empty());
    let scaled = scale_to_limits(&spline, &limits, TimeScaling::SlowDownOnly).unwrap();
    assert!(scaled.factor > 1.0);
    assert!(check_limits(&scaled.trajectory, &limits)
        .unwrap()
        .is_empty());
    assert!((scaled.trajectory.duration() - scaled.factor * spline.duration()).abs() < 1e-12);
    // Same path: position at scaled time = position at original time.
    for k in 0..=40 {
        let t = spline.start_time() + spline.duration() * k as f64 / 40.0;
        let ts = spline.start_time() + (t - spline.start_time()) * scaled.factor;
        let (a, b) = (
            spline.sample(t).unwrap(),
            scaled.trajectory.sample(ts).unwrap(),
        );
        assert!(common::max_abs_difference(&a.position, &b.position) < 1e-12);
        assert!(
            common::max_abs_difference(
                &a.velocity
                    .iter()
                    .map(|v| v / scaled.factor)
                    .collect::<Vec<_>>(),
                &b.velocity
            ) < 1e-12
        );
    }
    // Within limits: SlowDownOnly leaves it alone, Tight speeds it up.
    let slow = scaled.trajectory.time_scaled(2.0).unwrap();
    assert_eq!(
        scale_to_limits(&slow, &limits, TimeScaling::SlowDownOnly)
            .unwrap()
            .factor,
        1.0
    );
    let tight = scale_to_limits(&slow, &limits, TimeScaling::Tight).unwrap();
    assert!((tight.factor - 0.5).abs() < 1e-12);
}

// ---------------------------------------------------------------- Cartesian paths

/// Central differences of a Cartesian trajectory's pose (twist) and twist
/// (acceleration) against its analytic values.
fn check_cartesian_derivatives(traj: &CartesianTrajectory, tolerance: f64) {
    let h = 1e-5;
    let (t0, duration) = (traj.start_time(), traj.duration());
    for k in 1..20 {
        let t = t0 + duration * (k as f64 / 20.0 + 0.013);
        let (m, c, p) = (
            traj.sample(t - h).unwrap(),
            traj.sample(t).unwrap(),
            traj.sample(t + h).unwrap(),
        );
        let v = (p.pose.translation - m.pose.translation) / (2.0 * h);
        let w = armkit::math::rotation_log(&(p.pose.rotation * m.pose.rotation.transpose()))
            / (2.0 * h);
        let dv = (p.twist - m.twist) / (2.0 * h);
        let fd = Vector3::new(v.x, v.y, v.z);
        assert!(
            (fd - c.twist.fixed_rows::<3>(0)).norm() < tolerance,
            "t {t}: v {fd:?} vs {:?}",
            c.twist
        );
        assert!(
            (w - c.twist.fixed_rows::<3>(3)).norm() < tolerance,
            "t {t}: w {w:?} vs {:?}",
            c.twist
        );
        assert!(
            (dv - c.acceleration).norm() < tolerance * 10.0,
            "t {t}: {dv:?} vs {:?}",
            c.acceleration
        );
    }
}

#[test]
fn line_arc_and_user_curve_derivatives_match_finite_differences() {
    let start = Pose::from_xyz_rpy([0.4, -0.1, 0.3], [0.1, -0.2, 0.3]);
    let end = Pose::from_xyz_rpy([0.5, 0.2, 0.1], [-0.4, 0.3, 1.2]);
    let timing = TimeLaw::Quintic.timing(2.0).unwrap();
    let line =
        CartesianTrajectory::new(LinePath::new(start, end).unwrap(), timing.clone()).unwrap();
    check_cartesian_derivatives(&line, 1e-7);
    let arc = ArcPath::new(
        start,
        Vector3::new(0.3, 0.0, 0.3),
        Vector3::new(0.2, 0.1, 1.0),
        2.0,
        ArcOrientation::FollowArc,
    )
    .unwrap();
    check_cartesian_derivatives(
        &CartesianTrajectory::new(arc, timing.clone()).unwrap(),
        1e-7,
    );
    let trapezoid = TimeLaw::Trapezoidal {
        acceleration_time: 0.5,
    }
    .timing(2.0)
    .unwrap();
    check_cartesian_derivatives(&CartesianTrajectory::new(arc, trapezoid).unwrap(), 1e-7);
    // A helix given as a user curve: finite-difference derivatives by default.
    let helix = FnPath(|s: f64| {
        Pose::new(
            Pose::rot_z(3.0 * s).rotation,
            Vector3::new(0.2 * (3.0 * s).cos(), 0.2 * (3.0 * s).sin(), 0.1 * s),
        )
    });
    let d = helix.derivatives(0.4);
    let expected = [-0.6 * 1.2f64.sin(), 0.6 * 1.2f64.cos(), 0.1, 0.0, 0.0, 3.0];
    for (k, e) in expected.iter().enumerate() {
        assert!((d.first[k] - e).abs() < 1e-7, "{k}: {} vs {e}", d.first[k]);
    }
    assert!((d.second[0] + 1.8 * 1.2f64.cos()).abs() < 1e-6 && d.second[5].abs() < 1e-6);
    // One-sided differences at the ends.
    let d = helix.derivatives(1.0);
    assert!(
        (d.first[0] + 0.6 * 3f64.sin()).abs() < 1e-6,
        "{}",
        d.first[0]
    );
    assert!(
        (d.second[1] + 1.8 * 3f64.sin()).abs() < 1e-5,
        "{}",
        d.second[1]
    );
    check_cartesian_derivatives(&CartesianTrajectory::new(helix, timing).unwrap(), 1e-6);
}

#[test]
fn seed002_angles_linear_in_time() {
    let start = Pose::from_xyz_rpy([0.4, 0.0, 0.3], [0.1, -0.2, 3.0]);
    let end = Pose::from_xyz_rpy([0.4, 0.3, 0.3], [0.3, 0.4, -3.0]);
    let timing = TimeLaw::Trapezoidal {
        acceleration_time: 1.0,
    }
    .timing(4.0)
    .unwrap();
    let traj = CartesianTrajectory::new(LinePath::new(start, end).unwrap(), timing)
        .unwrap()
        .with_orientation_law(OrientationLaw::RpyLinearInTime);
    for k in 0..=8 {
        let t = 0.5 * k as f64;
        let (r, p, y) = traj.pose_at(t).rpy();
        let f = t / 4.0;
        // Yaw goes the short way, from 3.0 through pi to -3.0.
        let yaw = armkit::math::wrap_angle(3.0 + f * (2.0 * PI - 6.0));
        assert!(
            (r - (0.1 + 0.2 * f)).abs() < 1e-12 && (p - (-0.2 + 0.6 * f)).abs() < 1e-12,
            "t {t}"
        );
        assert!(
            armkit::math::wrap_angle(y - yaw).abs() < 1e-12,
            "t {t}: {y} vs {yaw}"
        );
    }
    check_cartesian_derivatives(&traj, 1e-7);
}

#[test]
fn arc_through_three_points() {
    let start = Pose::from_xyz_rpy([1.0, 0.0, 0.5], [0.0, 0.0, 0.0]);
    let via = Vector3::new(0.0, 1.0, 0.5);
    let end = Vector3::new(-1.0, 0.0, 0.5);
    let arc = ArcPath::through(start, via, end, ArcOrientation::Constant).unwrap();
    let (centre, axis, angle) = arc.geometry();
    assert!((centre - Vector3::new(0.0, 0.0, 0.5)).norm() < 1e-15);
    assert!(
        (axis - Vector3::z()).norm() < 1e-15
            && (angle - PI).abs() < 1e-15
            && (arc.radius() - 1.0).abs() < 1e-15
    );
    assert!(
        (arc.pose(0.5).translation - via).norm() < 1e-15
            && (arc.pose(1.0).translation - end).norm() < 1e-15
    );
    // Going the long way round: 270 degrees through (0, -1).
    let long = ArcPath::through(
        start,
        Vector3::new(0.0, -1.0, 0.5),
        Vector3::new(0.0, 1.0, 0.5),
        ArcOrientation::Constant,
    )
    .unwrap();
    assert!(
        (long.geometry().2 - 1.5 * PI).abs() < 1e-14,
        "{:?}",
        long.geometry()
    );
    assert!((long.pose(1.0).translation - Vector3::new(0.0, 1.0, 0.5)).norm() < 1e-14);
    assert!(message(ArcPath::through(
        start,
        Vector3::new(2.0, 0.0, 0.5),
        Vector3::new(3.0, 0.0, 0.5),
        ArcOrientation::Constant
    ))
    .contains("collinear"));
    let bad_timing = trajectory::trapezoidal(&[0.0], &[2.0], 1.0, 0.2).unwrap();
    assert!(message(CartesianTrajectory::new(arc, bad_timing)).contains("from s = 0 to s = 1"));
}

// ---------------------------------------------------------------- continuous path

/// Which task rows a test IK solves.
#[derive(Clone, Copy)]
enum Task {
    Position,
    Pose,
}

/// Test-local IK: Newton from `previous` with minimum-norm steps (so the
/// solution is the one continuously connected to `previous`); an error when
/// it does not converge to 1e-12 or leaves the joint limits.
fn newton_ik(
    model: &Model,
    target: &Pose,
    previous: &[f64],
    task: Task,
) -> Result<Vec<f64>, Error> {
    let rows = match task {
        Task::Position => 3,
        Task::Pose => 6,
    };
    let mut data = Data::new(model);
    let mut q = DVector::from_column_slice(previous);
    for _ in 0..50 {
        let j = jacobian(model, &mut data, q.as_slice(), JacobianFrame::World)?.clone();
        let pose = *data.end_effector_pose();
        let dp = target.translation - pose.translation;
        let dr = armkit::math::rotation_log(&(target.rotation * pose.rotation.transpose()));
        let e = DVector::from_iterator(rows, dp.iter().chain(dr.iter()).copied().take(rows));
        if e.norm() < 1e-12 {
            model.check_limits(q.as_slice())?;
            return Ok(q.as_slice().to_vec());
        }
        let jr: DMatrix<f64> = j.rows(0, rows).into_owned();
        let jjt = &jr * jr.transpose() + DMatrix::identity(rows, rows) * 1e-12;
        let step = jr.transpose()
            * jjt
                .lu()
                .solve(&e)
                .ok_or_else(|| Error::invalid_argument("target", "singular"))?;
        let scale = (0.3 / step.norm()).min(1.0);
        q += step * scale;
    }
    Err(Error::invalid_argument("target", "Newton did not converge"))
}

struct LineCase {
    model: Model,
    path: CartesianTrajectory,
    start: Vec<f64>,
    task: Task,
    tolerance: PathTolerance,
}

/// arm4: a 0.3 m line in the horizontal plane y = -0.30 m, x from -0.15 to
/// +0.15 m, at the tool height of roll 0.3 rad and pitch 0.4 rad. The end
/// configurations share the roll and pitch joints and reach the end points
/// exactly (Newton on joints 1-2 only), so both end poses are FK poses; in
/// between, the slerped orientation is not reachable (arm4 reaches a 4-D
/// subset of SE(3)) and the tolerance is on position only.
fn arm4_line() -> LineCase {
    let model = armkit::robots::by_name("arm4").unwrap();
    let mut data = Data::new(&model);
    let (roll, pitch) = (0.3, 0.4);
    let height = forward_kinematics(&model, &mut data, &[0.0, 0.0, roll, pitch])
        .unwrap()
        .translation
        .z;
    let mut reach = |x: f64, guess: [f64; 2]| -> Vec<f64> {
        let mut q = vec![guess[0], guess[1], roll, pitch];
        for _ in 0..50 {
            let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
                .unwrap()
                .clone();
            let p = data.end_effector_pose().translation;
            let e = nalgebra::Vector2::new(x - p.x, -0.30 - p.y);
            let j2 = nalgebra::Matrix2::new(j[(0, 0)], j[(0, 1)], j[(1, 0)], j[(1, 1)]);
            let step = j2.lu().solve(&e).unwrap();
            q[0] += step[0];
            q[1] += step[1];
        }
        let p = forward_kinematics(&model, &mut data, &q)
            .unwrap()
            .translation;
        assert!((p - Vector3::new(x, -0.30, height)).norm() < 1e-13);
        q
    };
    let qa = reach(-0.15, [0.6, -0.9]);
    let qb = reach(0.15, [qa[0], qa[1]]);
    let a = *forward_kinematics(&model, &mut data, &qa).unwrap();
    let b = *forward_kinematics(&model, &mut data, &qb).unwrap();
    assert!(((b.translation - a.translation).norm() - 0.3).abs() < 1e-12);
    let timing = TimeLaw::Trapezoidal {
        acceleration_time: 0.5,
    }
    .timing(2.0)
    .unwrap();
    let path = CartesianTrajectory::new(LinePath::new(a, b).unwrap(), timing).unwrap();
    LineCase {
        model,
        path,
        start: qa,
        task: Task::Position,
        tolerance: PathTolerance::Position(1e-4),
    }
}

/// panda: from its ready-like pose, 0.3 m along y and -0.15 m along z with a
/// 0.4 rad turn of the tool about the world z axis; full pose tolerance
/// (0.1 mm, 1 mrad).
fn panda_line() -> LineCase {
    let model = armkit::robots::by_name("panda").unwrap();
    let mut data = Data::new(&model);
    let start = vec![0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let a = *forward_kinematics(&model, &mut data, &start).unwrap();
    let offset = Vector3::new(0.0, 0.3, -0.15).normalize() * 0.3;
    let b = Pose::new(
        Pose::rot_z(0.4).rotation * a.rotation,
        a.translation + offset,
    );
    let timing = TimeLaw::Quintic.timing(2.0).unwrap();
    let path = CartesianTrajectory::new(LinePath::new(a, b).unwrap(), timing).unwrap();
    LineCase {
        model,
        path,
        start,
        task: Task::Pose,
        tolerance: PathTolerance::Pose {
            position: 1e-4,
            orientation: 1e-3,
        },
    }
}

fn plan(case: &LineCase, options: &ContinuousPathOptions) -> (ContinuousPathReport, f64) {
    let (model, task) = (&case.model, case.task);
    let mut ik = |target: &Pose, previous: &[f64]| newton_ik(model, target, previous, task);
    let clock = std::time::Instant::now();
    let report = plan_continuous_path(model, &case.path, &mut ik, &case.start, options).unwrap();
    (report, clock.elapsed().as_secs_f64())
}

fn within(error: &armkit::trajectory::PathError, tolerance: &PathTolerance) -> bool {
    match *tolerance {
        PathTolerance::Position(p) => error.position <= p,
        PathTolerance::Pose {
            position,
            orientation,
        } => error.position <= position && error.orientation <= orientation,
    }
}

#[test]
fn adaptive_segmentation_meets_the_tolerance_on_arm4_and_panda() {
    let mut interior_errors = Vec::new();
    for (name, case) in [("arm4", arm4_line()), ("panda", panda_line())] {
        for scheme in [
            SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference),
            SegmentScheme::QuarticCubicQuartic(ViaVelocity::CentralDifference),
        ] {
            for checks_per_segment in [1, 3] {
                let options = ContinuousPathOptions {
                    scheme,
                    tolerance: case.tolerance,
                    checks_per_segment,
                    ..Default::default()
                };
                let (report, seconds) = plan(&case, &options);
                let interior =
                    measure_path_error(&case.model, &report.trajectory, &case.path, 100).unwrap();
                println!(
                    "{name} {scheme:?}, {checks_per_segment} check(s)/segment: {} segments, {} passes, {} IK solves, \
                     checked error {:.3e} m / {:.3e} rad, 100-point error {:.3e} m / {:.3e} rad, {:.2} ms with the test's IK",
                    report.trajectory.segment_count(),
                    report.passes,
                    report.ik_solves,
                    report.checked_error.position,
                    report.checked_error.orientation,
                    interior.position,
                    interior.orientation,
                    seconds * 1e3
                );
                assert_eq!(report.status, PathStatus::ToleranceMet);
                assert!(within(&report.checked_error, &case.tolerance));
                let segments = report.trajectory.segment_count();
                assert_eq!(report.configurations.len(), segments + 1);
                // The knots are the IK solutions.
                for (i, q) in report.configurations.iter().enumerate() {
                    let at = if i < segments {
                        segment_state(&report.trajectory, i, 0.0)
                    } else {
                        report.trajectory.end_state()
                    };
                    assert!(common::max_abs_difference(&at.position, q) < BC);
                }
                let [dq, dv, da] = report.trajectory.knot_discontinuities();
                println!("    knot jumps: position {dq:.1e}, velocity {dv:.1e}, acceleration {da:.1e} (C1 scheme)");
                assert!(dq < BC && dv < 1e-10);
                interior_errors.push((name, scheme, checks_per_segment, interior, case.tolerance));
            }
        }
    }
    // Between the check points (100 per segment): with quarter points and
    // midpoint checked, within 1.5 times the tolerance on every case.
    for (name, scheme, checks, interior, tolerance) in interior_errors {
        if checks == 3 {
            let relaxed = match tolerance {
                PathTolerance::Position(p) => PathTolerance::Position(1.5 * p),
                PathTolerance::Pose {
                    position,
                    orientation,
                } => PathTolerance::Pose {
                    position: 1.5 * position,
                    orientation: 1.5 * orientation,
                },
            };
            assert!(
                within(&interior, &relaxed),
                "{name} {scheme:?}: {interior:?}"
            );
        }
    }
}

/// Lines of 0.3 m with a 0.1 mm tolerance, planned with the
/// library's IK (arm4: closed form, position only; panda: numeric, full pose).
#[test]
fn seed002_lines_with_the_library_ik() {
    let cases = [
        ("arm4", arm4_line(), IkTask::Position, false),
        ("arm4", arm4_line(), IkTask::Position, true),
        ("panda", panda_line(), IkTask::Pose, true),
    ];
    for (name, case, task, numeric) in cases {
        let (mut ik, method): (Box<dyn armkit::trajectory::PathIk>, &str) = if numeric {
            (
                Box::new(NumericPathIk::for_path(&case.model, task).unwrap()),
                "numeric",
            )
        } else {
            path_ik_for(&case.model, task).unwrap()
        };
        for checks_per_segment in [1, 3] {
            let options = ContinuousPathOptions {
                tolerance: case.tolerance,
                checks_per_segment,
                ..Default::default()
            };
            let clock = std::time::Instant::now();
            let report =
                plan_continuous_path(&case.model, &case.path, &mut *ik, &case.start, &options)
                    .unwrap();
            let seconds = clock.elapsed().as_secs_f64();
            let interior =
                measure_path_error(&case.model, &report.trajectory, &case.path, 100).unwrap();
            println!(
                "{name} ({method} IK), {checks_per_segment} check(s)/segment: {:?}, {} segments, {} IK solves, \
                 checked error {:.3e} m / {:.3e} rad, 100-point error {:.3e} m / {:.3e} rad, planning {:.2} ms",
                report.status,
                report.trajectory.segment_count(),
                report.ik_solves,
                report.checked_error.position,
                report.checked_error.orientation,
                interior.position,
                interior.orientation,
                seconds * 1e3
            );
            assert_eq!(report.status, PathStatus::ToleranceMet);
            assert!(within(&report.checked_error, &case.tolerance));
            let [dq, dv, _] = report.trajectory.knot_discontinuities();
            assert!(dq < BC && dv < 1e-10);
            if checks_per_segment == 3 {
                let PathTolerance::Pose {
                    position,
                    orientation,
                } = case.tolerance
                else {
                    assert!(interior.position <= 1.5 * 1e-4, "{name}: {interior:?}");
                    continue;
                };
                assert!(
                    interior.position <= 1.5 * position
                        && interior.orientation <= 1.5 * orientation
                );
            }
        }
    }
}

#[test]
fn library_ik_reports_points_out_of_reach() {
    for (case, task) in [
        (arm4_line(), IkTask::Position),
        (panda_line(), IkTask::Pose),
    ] {
        let a = case.path.pose_at(0.0);
        let b = Pose::new(a.rotation, a.translation + Vector3::new(0.0, -2.0, 0.0));
        let path = CartesianTrajectory::new(
            LinePath::new(a, b).unwrap(),
            TimeLaw::Quintic.timing(2.0).unwrap(),
        )
        .unwrap();
        let (mut ik, _) = path_ik_for(&case.model, task).unwrap();
        let options = ContinuousPathOptions {
            tolerance: case.tolerance,
            ..Default::default()
        };
        let text = message(plan_continuous_path(
            &case.model,
            &path,
            &mut *ik,
            &case.start,
            &options,
        ));
        println!("{text}");
        assert!(
            text.starts_with("invalid argument `path`: IK failed at the path point (knot ")
                && text.contains(", t = "),
            "{text}"
        );
    }
}

#[test]
fn cubic_quintic_last_scheme_on_the_lines() {
    // The seed's C2 scheme: report what it does (see the amplification test).
    for (name, case) in [("arm4", arm4_line()), ("panda", panda_line())] {
        for segmentation in [
            Segmentation::Fixed(4),
            Segmentation::Fixed(8),
            Segmentation::Adaptive {
                initial: 4,
                max: 64,
            },
        ] {
            let options = ContinuousPathOptions {
                scheme: SegmentScheme::CubicQuinticLast,
                segmentation,
                tolerance: case.tolerance,
                ..Default::default()
            };
            let (report, _) = plan(&case, &options);
            let interior =
                measure_path_error(&case.model, &report.trajectory, &case.path, 100).unwrap();
            println!(
                "{name} CubicQuinticLast {segmentation:?}: {:?}, {} segments, checked error {:.3e} m, 100-point error {:.3e} m",
                report.status,
                report.trajectory.segment_count(),
                report.checked_error.position,
                interior.position
            );
            let [_, dv, da] = report.trajectory.knot_discontinuities();
            assert!(dv < 1e-9 && da < 1e-6, "{dv} {da}");
        }
    }
}

/// The adaptive segmentation with the cubic-quintic
/// scheme refines until the recursion overflows; that is the scheme's
/// outcome (status `scheme_diverged`, the last finite pass returned), not an
/// error. The rate amplification shows the growth; the quartic-cubic scheme
/// keeps it near 1.
#[test]
fn cubic_quintic_adaptive_divergence_is_a_status() {
    use armkit::trajectory::rate_amplification;
    let case = arm4_line();
    let options = ContinuousPathOptions {
        scheme: SegmentScheme::CubicQuinticLast,
        segmentation: Segmentation::Adaptive {
            initial: 4,
            max: 4096,
        },
        tolerance: case.tolerance,
        ..Default::default()
    };
    let (report, _) = plan(&case, &options);
    assert_eq!(report.status, PathStatus::SchemeDiverged);
    assert_eq!(report.status.to_string(), "scheme_diverged");
    assert!(!within(&report.checked_error, &case.tolerance));
    let segments = report.trajectory.segment_count();
    assert_eq!(report.configurations.len(), segments + 1);
    assert!(segments > 256, "{segments}");
    let amplification = rate_amplification(&report.trajectory);
    assert!(amplification > 1e10, "{amplification:e}");
    // Fixed 4, 8, 16 segments: growing amplification; quartic-cubic near 1.
    let mut previous = 0.0;
    for n in [4, 8, 16] {
        let fixed = ContinuousPathOptions {
            segmentation: Segmentation::Fixed(n),
            ..options.clone()
        };
        let a = rate_amplification(&plan(&case, &fixed).0.trajectory);
        assert!(a > previous, "n = {n}: {a} after {previous}");
        previous = a;
        let stable = ContinuousPathOptions {
            scheme: SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference),
            ..fixed
        };
        let a = rate_amplification(&plan(&case, &stable).0.trajectory);
        assert!(a <= 1.0 + 1e-9, "quartic-cubic n = {n}: {a}");
    }
    assert!(previous > 1e4, "{previous}");
    assert_eq!(PathStatus::ToleranceMet.as_str(), "tolerance_met");
    assert_eq!(PathStatus::ToleranceNotMet.to_string(), "tolerance_not_met");
}

#[test]
fn fixed_segmentation_reports_the_tolerance_honestly() {
    let case = panda_line();
    let options = ContinuousPathOptions {
        segmentation: Segmentation::Fixed(1),
        tolerance: case.tolerance,
        ..Default::default()
    };
    let (report, _) = plan(&case, &options);
    assert_eq!(report.trajectory.segment_count(), 1);
    assert_eq!(report.status, PathStatus::ToleranceNotMet);
    assert!(!within(&report.checked_error, &case.tolerance));
    // A segment limit below what the tolerance needs: not met either.
    let options = ContinuousPathOptions {
        segmentation: Segmentation::Adaptive { initial: 2, max: 3 },
        tolerance: case.tolerance,
        ..Default::default()
    };
    let (report, _) = plan(&case, &options);
    assert!(report.trajectory.segment_count() <= 3);
    assert_eq!(report.status, PathStatus::ToleranceNotMet);
}

#[test]
fn a_path_point_out_of_reach_is_a_clear_error() {
    let case = panda_line();
    let model = &case.model;
    // A 3 m line: far out of reach after the first metre.
    let a = case.path.pose_at(0.0);
    let b = Pose::new(a.rotation, a.translation + Vector3::new(3.0, 0.0, 0.0));
    let path = CartesianTrajectory::new(
        LinePath::new(a, b).unwrap(),
        TimeLaw::Quintic.timing(2.0).unwrap(),
    )
    .unwrap();
    let mut ik = |target: &Pose, previous: &[f64]| newton_ik(model, target, previous, Task::Pose);
    let text = message(plan_continuous_path(
        model,
        &path,
        &mut ik,
        &case.start,
        &ContinuousPathOptions::default(),
    ));
    println!("{text}");
    // The point is named (which knot, when, where) before the IK's cause.
    assert!(
        text.starts_with("invalid argument `path`: IK failed at the path point (knot "),
        "{text}"
    );
    assert!(text.contains(" of knots 0..4, t = "), "{text}");
    // Options and sizes are checked first.
    let bad = ContinuousPathOptions {
        tolerance: PathTolerance::Position(0.0),
        ..Default::default()
    };
    assert!(message(plan_continuous_path(
        model,
        &case.path,
        &mut ik,
        &case.start,
        &bad
    ))
    .contains("tolerance.position"));
    assert!(message(plan_continuous_path(
        model,
        &case.path,
        &mut ik,
        &[0.0; 3],
        &ContinuousPathOptions::default()
    ))
    .contains("expected 7 values, got 3"));
}

#[test]
fn sampling_is_clamped_and_checked() {
    let traj = trajectory::trapezoidal(&[0.0, 1.0], &[1.0, 0.0], 2.0, 0.5).unwrap();
    assert_eq!(traj.sample(-1.0).unwrap(), traj.start_state());
    assert_eq!(traj.sample(5.0).unwrap(), traj.end_state());
    assert!(message(traj.sample(f64::NAN)).contains("t[0] is not finite"));
    let mut small = JointState::zeros(1);
    assert_eq!(
        message(traj.sample_into(0.5, &mut small)),
        "out.position: expected 2 values, got 1"
    );
    let shifted = traj.shifted_to(10.0).unwrap();
    assert_eq!(shifted.sample(10.5).unwrap(), traj.sample(0.5).unwrap());
}

#[test]
fn trajectory_limits_speak_the_models_joint_limits() {
    use armkit::trajectory::TrajectoryLimits;
    for name in ["panda", "gantry9", "ur5"] {
        let model = armkit::robots::by_name(name).unwrap();
        let limits = TrajectoryLimits::from_model(&model);
        for (j, joint) in model.joints().iter().enumerate() {
            // Effort limits need the dynamics (`torque_profile` checks them):
            // the trajectory's limits hold the kinematic ones.
            let kinematic = armkit::model::JointLimits {
                effort: None,
                ..joint.limits
            };
            assert_eq!(limits.joint(j), Some(kinematic), "{name} joint {j}");
        }
        assert_eq!(limits.joint(model.dof()), None);
        let per_joint: Vec<_> = model.joints().iter().map(|j| j.limits).collect();
        assert_eq!(TrajectoryLimits::from_joint_limits(&per_joint), limits);
    }
}
