//! Redundancy-resolution timings on gantry9 (9 joints) and panda (7 joints):
//! one weighted least-norm solve (exact, toward a preferred velocity,
//! adaptive damping), seed 001's partitioned form and its best partition,
//! energy weights from torques, and a whole tracking run.
//!
//! Run: `cargo bench -p armkit --bench redundancy`.

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Matrix6xX, Pose, Vector3, Vector6};
use armkit::redundancy::{
    best_partition, joint_torques, Damping, Distribution, DistributionOptions, JointWeights, Load,
    PartitionedSolver, ResolvedRateTracker, SolverOptions, TorqueFloor, WeightedLeastNorm,
    SEED000_PRIORITY_WEIGHTS,
};
use armkit::trajectory::{CartesianTrajectory, TimeLaw};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn jacobian_at(name: &str, q: &[f64]) -> Matrix6xX<f64> {
    let model = armkit::robots::by_name(name).unwrap();
    let mut data = Data::new(&model);
    jacobian(&model, &mut data, q, JacobianFrame::World)
        .unwrap()
        .clone()
}

const GANTRY_Q: [f64; 9] = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
const PANDA_Q: [f64; 7] = [0.1, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7];

fn solves(c: &mut Criterion) {
    let twist = Vector6::new(0.1, 0.05, -0.05, 0.0, 0.1, 0.0);
    for (name, j) in [
        ("gantry9", jacobian_at("gantry9", &GANTRY_Q)),
        ("panda", jacobian_at("panda", &PANDA_Q)),
    ] {
        let dof = j.ncols();
        let weights = if dof == 9 {
            JointWeights::new(&SEED000_PRIORITY_WEIGHTS).unwrap()
        } else {
            JointWeights::uniform(dof)
        };
        let mut exact = WeightedLeastNorm::new(dof, SolverOptions::default()).unwrap();
        c.bench_function(&format!("weighted_least_norm/{name}"), |b| {
            b.iter(|| {
                black_box(
                    exact
                        .solve(black_box(&j), &weights, black_box(&twist))
                        .unwrap()
                        .solved()
                        .unwrap()[0],
                );
            })
        });
        let preferred = vec![0.01; dof];
        c.bench_function(&format!("weighted_least_norm_toward/{name}"), |b| {
            b.iter(|| {
                black_box(
                    exact
                        .solve_toward(black_box(&j), &weights, &twist, &preferred)
                        .unwrap()
                        .solved()
                        .unwrap()[0],
                );
            })
        });
        let mut damped = WeightedLeastNorm::new(
            dof,
            SolverOptions {
                damping: Damping::Adaptive {
                    threshold: 0.1,
                    max: 0.05,
                },
                ..SolverOptions::default()
            },
        )
        .unwrap();
        c.bench_function(&format!("weighted_least_norm_adaptive/{name}"), |b| {
            b.iter(|| {
                black_box(
                    damped
                        .solve(black_box(&j), &weights, &twist)
                        .unwrap()
                        .solved()
                        .unwrap()[0],
                );
            })
        });
        let partition = best_partition(&j, None, 1e10).unwrap().partition;
        let mut partitioned = PartitionedSolver::new(dof, 1e10).unwrap();
        c.bench_function(&format!("partitioned_seed001/{name}"), |b| {
            b.iter(|| {
                black_box(
                    partitioned
                        .solve(black_box(&j), &weights, &twist, &partition)
                        .unwrap()[0],
                );
            })
        });
        c.bench_function(&format!("best_partition/{name}"), |b| {
            b.iter(|| black_box(best_partition(black_box(&j), None, 1e10).unwrap()))
        });
    }
}

fn energy(c: &mut Criterion) {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let load = Load::payload(50.0).with_seed001_gravity();
    let mut torques = [0.0; 9];
    let mut weights = JointWeights::uniform(9);
    c.bench_function(
        "energy_weights/gantry9 (FK + J + J'w + gravity + weights)",
        |b| {
            b.iter(|| {
                joint_torques(&model, &mut data, black_box(&GANTRY_Q), &load, &mut torques)
                    .unwrap();
                weights
                    .set_from_torques(&torques, TorqueFloor::default())
                    .unwrap();
                black_box(weights.values()[0]);
            })
        },
    );
}

fn tracking(c: &mut Criterion) {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let start = *forward_kinematics(&model, &mut data, &GANTRY_Q).unwrap();
    let goal = Pose::from_translation(Vector3::new(0.4, 0.3, -0.3)) * start;
    let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 4.0).unwrap();
    let load = Load::payload(50.0).with_seed001_gravity();
    let mut tracker = ResolvedRateTracker::new(
        &model,
        Distribution::Energy {
            load,
            floor: TorqueFloor::default(),
        },
        DistributionOptions::default(),
    )
    .unwrap();
    c.bench_function("tracking/gantry9 energy-optimal, 400 steps", |b| {
        b.iter(|| black_box(tracker.run(&model, &GANTRY_Q, &path).unwrap().status))
    });
}

/// The shared kernels and the bare tracking loop (hot paths of the
/// velocity-level layer): the damped least-squares rates of a 6 x 9
/// Jacobian, and a 100-period least-squares run on a fixed base recording
/// every sample.
fn kernels(c: &mut Criterion) {
    use armkit::linalg::{damped_least_squares_rates, GRAM_THRESHOLD};
    use armkit::tracking::{track_samples, FixedBase, LeastSquares, TrackingOptions};
    let j = jacobian_at("gantry9", &GANTRY_Q);
    let twist = Vector6::new(0.1, 0.05, -0.05, 0.0, 0.1, 0.0);
    let mut rates = [0.0; 9];
    c.bench_function("linalg/damped_least_squares_rates gantry9", |b| {
        b.iter(|| {
            damped_least_squares_rates(black_box(&j), &twist, 0.01, GRAM_THRESHOLD, &mut rates)
                .is_singular()
        })
    });
    let model = armkit::robots::by_name("ur5").unwrap();
    let q0 = [0.3, -1.2, 1.4, -1.5, -1.4, 0.2];
    let mut data = Data::new(&model);
    let start = *forward_kinematics(&model, &mut data, &q0).unwrap();
    let goal = Pose::from_translation(Vector3::new(0.0, 0.1, 0.05)) * start;
    let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 1.0).unwrap();
    c.bench_function("tracking/ur5 least squares, 100 periods", |b| {
        b.iter(|| {
            let mut plant = FixedBase::new(&model, &mut data, &q0).unwrap();
            let report = track_samples(
                &mut plant,
                &mut LeastSquares { damping: 0.0 },
                &path,
                &TrackingOptions::default(),
            )
            .unwrap();
            black_box(report.status)
        })
    });
}

criterion_group!(benches, solves, energy, tracking, kernels);
criterion_main!(benches);
