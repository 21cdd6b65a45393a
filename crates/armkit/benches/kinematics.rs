//! Forward kinematics and Jacobian timings on ur5, panda and gantry9 (no
//! coupling: the coupling map's identity shape) and gantry9-flex (the beam's
//! additive coupling). The mimic shape is timed in `benches/urdf.rs`.
//!
//! `fk/<robot>` and `fk+jacobian/<robot>` time one call;
//! `fk-batch/<robot>/<batch>` and `jacobian-batch/<robot>/<batch>` one
//! batched call of `<batch>` configurations on one thread (time per batch:
//! divide by the batch size for the time per configuration).
//!
//! Run: `cargo bench -p armkit --bench kinematics`.
//!
//! Each call takes the next of 1024 random configurations within the limits
//! (seeded), as Pinocchio's benchmark in `../shared/peers` does, so that the
//! timing does not profit from one branch pattern in the trigonometry.

use armkit::kinematics::{
    forward_kinematics, forward_kinematics_batch, jacobian, jacobian_batch, BatchData, Data,
    JacobianFrame, POSE_VALUES,
};
use criterion::{criterion_group, criterion_main, Criterion};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

fn random_configurations(model: &armkit::Model, count: usize) -> Vec<Vec<f64>> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    (0..count)
        .map(|_| {
            model
                .joints()
                .iter()
                .map(|joint| {
                    let (lower, upper) = (joint.limits.lower, joint.limits.upper);
                    if lower.is_finite() && upper.is_finite() {
                        rng.gen_range(lower..=upper)
                    } else {
                        rng.gen_range(-std::f64::consts::PI..=std::f64::consts::PI)
                    }
                })
                .collect()
        })
        .collect()
}

fn bench_robot(c: &mut Criterion, name: &str) {
    let model = armkit::robots::by_name(name).unwrap();
    let mut data = Data::new(&model);
    let configurations = random_configurations(&model, 1024);
    let mut next = configurations.iter().cycle();
    c.bench_function(&format!("fk/{name}"), |b| {
        b.iter(|| {
            let q = next.next().unwrap();
            forward_kinematics(&model, &mut data, black_box(q)).unwrap();
        })
    });
    c.bench_function(&format!("fk+jacobian/{name}"), |b| {
        b.iter(|| {
            let q = next.next().unwrap();
            jacobian(&model, &mut data, black_box(q), JacobianFrame::World).unwrap();
        })
    });
}

/// Batched FK and Jacobians of `batch` configurations (the first `batch`
/// of the 1024) into preallocated buffers.
fn bench_batch(c: &mut Criterion, name: &str, batch: usize) {
    let model = armkit::robots::by_name(name).unwrap();
    let mut data = BatchData::new(&model);
    let q: Vec<f64> = random_configurations(&model, batch).concat();
    let mut poses = vec![0.0; batch * POSE_VALUES];
    let mut jacobians = vec![0.0; batch * 6 * model.dof()];
    c.bench_function(&format!("fk-batch/{name}/{batch}"), |b| {
        b.iter(|| forward_kinematics_batch(&model, &mut data, black_box(&q), &mut poses).unwrap())
    });
    c.bench_function(&format!("jacobian-batch/{name}/{batch}"), |b| {
        b.iter(|| {
            jacobian_batch(
                &model,
                &mut data,
                black_box(&q),
                JacobianFrame::World,
                &mut jacobians,
            )
            .unwrap()
        })
    });
}

fn kinematics(c: &mut Criterion) {
    for name in ["ur5", "panda", "gantry9", "gantry9-flex"] {
        bench_robot(c, name);
    }
    for name in ["ur5", "panda"] {
        for batch in [64, 1024] {
            bench_batch(c, name, batch);
        }
    }
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
