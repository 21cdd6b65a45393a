//! Criterion benchmarks of the trajectory module: sampling (target: at most
//! 50 ns per joint per sample) and planning (profiles, spline, seed 002's
//! continuous path on arm4 and panda).
//!
//! `cargo bench -p armkit --bench trajectory -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use armkit::trajectory::limits::TrajectoryLimits;
use armkit::trajectory::profile::{self, ProfileShape};
use armkit::trajectory::spline::clamped_cubic_spline;
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
    let quintic = profile::minimum_time(ProfileShape::Quintic, &q0, &qf, &limits).unwrap();
    let trapezoid = profile::minimum_time(ProfileShape::Trapezoidal, &q0, &qf, &limits).unwrap();
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
        b.iter(|| profile::trapezoidal(black_box(&q0), black_box(&qf), 20.0, 4.0).unwrap())
    });
    for shape in [ProfileShape::Trapezoidal, ProfileShape::Quintic] {
        group.bench_function(format!("minimum_time_{shape:?}"), |b| {
            b.iter(|| {
                profile::minimum_time(shape, black_box(&q0), black_box(&qf), &limits).unwrap()
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

criterion_group!(benches, bench_sampling, bench_planning);
criterion_main!(benches);
