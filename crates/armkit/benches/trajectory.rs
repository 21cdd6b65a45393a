//! Criterion benchmarks of the trajectory module: sampling (target: at most
//! 50 ns per joint per sample) and planning (profiles, spline, seed 002's
//! continuous path on arm4 and panda).
//!
//! `cargo bench -p armkit --bench trajectory -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Pose, Vector3};
use armkit::trajectory::clamped_cubic_spline;
use armkit::trajectory::TrajectoryLimits;
use armkit::trajectory::{self, ProfileShape};
use armkit::trajectory::{plan_continuous_path, ContinuousPathOptions, PathIk, PathTolerance};
use armkit::trajectory::{CartesianTrajectory, LinePath, TimeLaw};
use armkit::trajectory::{ClosedFormPathIk, IkTask, NumericPathIk};
use armkit::trajectory::{JointState, Trajectory};
use criterion::{criterion_group, criterion_main, Criterion};

/// Sampling times spread over the trajectory (a fixed, irregular sequence).
fn times(traj: &Trajectory, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| traj.start_time() + traj.duration() * ((k * 7919) % count) as f64 / count as f64)
        .collect()
}

fn bench_sampling(c: &mut Criterion) {
    let panda = armkit::robots::by_name("panda").unwrap();
    let limits = TrajectoryLimits::from_model(&panda);
    let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let qf = [1.0, 0.4, -0.5, -1.2, 0.7, 1.2, -0.3];
    let quintic = trajectory::minimum_time(ProfileShape::Quintic, &q0, &qf, &limits).unwrap();
    let trapezoid = trajectory::minimum_time(ProfileShape::Trapezoidal, &q0, &qf, &limits).unwrap();
    // A 7-joint spline with 200 segments: the binary search over knots counts.
    let knot_times: Vec<f64> = (0..=200).map(|i| i as f64 * 0.05).collect();
    let points: Vec<Vec<f64>> = knot_times
        .iter()
        .map(|t| (0..7).map(|j| (t * (1.0 + j as f64 * 0.3)).sin()).collect())
        .collect();
    let spline = clamped_cubic_spline(&knot_times, &points, &[0.0; 7], &[0.0; 7]).unwrap();
    let mut group = c.benchmark_group("trajectory_sample_into_panda_7_joints");
    for (name, traj) in [
        ("quintic_1_segment", &quintic),
        ("trapezoid_3_segments", &trapezoid),
        ("spline_200_segments", &spline),
    ] {
        let ts = times(traj, 1024);
        let mut out = JointState::zeros(7);
        let mut k = 0;
        group.bench_function(name, |b| {
            b.iter(|| {
                k = (k + 1) & 1023;
                traj.sample_into(black_box(ts[k]), &mut out).unwrap();
                black_box(&out);
            })
        });
    }
    group.finish();
}

fn bench_planning(c: &mut Criterion) {
    let panda = armkit::robots::by_name("panda").unwrap();
    let limits = TrajectoryLimits::from_model(&panda);
    let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let qf = [1.0, 0.4, -0.5, -1.2, 0.7, 1.2, -0.3];
    let mut group = c.benchmark_group("trajectory_plan_panda_7_joints");
    group.bench_function("trapezoid_20s_4s", |b| {
        b.iter(|| trajectory::trapezoidal(black_box(&q0), black_box(&qf), 20.0, 4.0).unwrap())
    });
    for shape in [ProfileShape::Trapezoidal, ProfileShape::Quintic] {
        group.bench_function(format!("minimum_time_{shape:?}"), |b| {
            b.iter(|| {
                trajectory::minimum_time(shape, black_box(&q0), black_box(&qf), &limits).unwrap()
            })
        });
    }
    let knot_times: Vec<f64> = (0..=50).map(|i| i as f64 * 0.1).collect();
    let points: Vec<Vec<f64>> = knot_times
        .iter()
        .map(|t| (0..7).map(|j| (t * (1.0 + j as f64 * 0.3)).sin()).collect())
        .collect();
    group.bench_function("clamped_spline_50_segments", |b| {
        b.iter(|| {
            clamped_cubic_spline(black_box(&knot_times), &points, &[0.0; 7], &[0.0; 7]).unwrap()
        })
    });
    group.finish();
}

/// arm4's 0.3 m line (as in tests/it/trajectory.rs): y = -0.30 m, x from
/// -0.15 to 0.15 m, roll 0.3 rad and pitch 0.4 rad at both ends; start configuration.
fn arm4_line() -> (armkit::Model, CartesianTrajectory, Vec<f64>) {
    let model = armkit::robots::by_name("arm4").unwrap();
    let mut data = Data::new(&model);
    let mut reach = |x: f64, guess: [f64; 2]| -> Vec<f64> {
        let mut q = vec![guess[0], guess[1], 0.3, 0.4];
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
        q
    };
    let qa = reach(-0.15, [0.6, -0.9]);
    let qb = reach(0.15, [qa[0], qa[1]]);
    let a = *forward_kinematics(&model, &mut data, &qa).unwrap();
    let b = *forward_kinematics(&model, &mut data, &qb).unwrap();
    let timing = TimeLaw::Trapezoidal {
        acceleration_time: 0.5,
    }
    .timing(2.0)
    .unwrap();
    let path = CartesianTrajectory::new(LinePath::new(a, b).unwrap(), timing).unwrap();
    (model, path, qa)
}

/// panda's 0.3 m line (as in tests/it/trajectory.rs).
fn panda_line() -> (armkit::Model, CartesianTrajectory, Vec<f64>) {
    let model = armkit::robots::by_name("panda").unwrap();
    let start = vec![0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let a = *forward_kinematics(&model, &mut Data::new(&model), &start).unwrap();
    let offset = Vector3::new(0.0, 0.3, -0.15).normalize() * 0.3;
    let b = Pose::new(
        Pose::rot_z(0.4).rotation * a.rotation,
        a.translation + offset,
    );
    let timing = TimeLaw::Quintic.timing(2.0).unwrap();
    let path = CartesianTrajectory::new(LinePath::new(a, b).unwrap(), timing).unwrap();
    (model, path, start)
}

fn bench_continuous_path(c: &mut Criterion) {
    let mut group = c.benchmark_group("trajectory_continuous_path_0.3m_line_0.1mm");
    group.sample_size(10);
    let (arm4, arm4_path, arm4_start) = arm4_line();
    let (panda, panda_path, panda_start) = panda_line();
    let position = ContinuousPathOptions {
        tolerance: PathTolerance::Position(1e-4),
        ..Default::default()
    };
    let pose = ContinuousPathOptions {
        tolerance: PathTolerance::Pose {
            position: 1e-4,
            orientation: 1e-3,
        },
        ..Default::default()
    };
    let mut closed_form = ClosedFormPathIk::new(&arm4, IkTask::Position).unwrap();
    let mut arm4_numeric = NumericPathIk::for_path(&arm4, IkTask::Position).unwrap();
    let mut panda_numeric = NumericPathIk::for_path(&panda, IkTask::Pose).unwrap();
    let mut plan = |name: &str,
                    (model, path, start): (&armkit::Model, &CartesianTrajectory, &[f64]),
                    ik: &mut dyn PathIk,
                    options: &ContinuousPathOptions| {
        group.bench_function(name, |b| {
            b.iter(|| plan_continuous_path(model, path, &mut *ik, start, options).unwrap())
        });
    };
    plan(
        "arm4_closed_form_ik",
        (&arm4, &arm4_path, &arm4_start),
        &mut closed_form,
        &position,
    );
    plan(
        "arm4_numeric_ik",
        (&arm4, &arm4_path, &arm4_start),
        &mut arm4_numeric,
        &position,
    );
    plan(
        "panda_numeric_ik",
        (&panda, &panda_path, &panda_start),
        &mut panda_numeric,
        &pose,
    );
    group.finish();
}

criterion_group!(
    benches,
    bench_sampling,
    bench_planning,
    bench_continuous_path
);
criterion_main!(benches);
