//! Forward kinematics and Jacobian timings on ur5, panda and gantry9.
//!
//! Run: `cargo bench -p armkit --bench kinematics`.

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench_robot(c: &mut Criterion, name: &str) {
    let model = armkit::robots::by_name(name).unwrap();
    let mut data = Data::new(&model);
    let q: Vec<f64> = model
        .joints()
        .iter()
        .enumerate()
        .map(|(j, joint)| joint.limits.midpoint() + 0.1 * (j as f64 + 1.0))
        .collect();
    c.bench_function(&format!("fk/{name}"), |b| {
        b.iter(|| {
            forward_kinematics(&model, &mut data, black_box(&q)).unwrap();
        })
    });
    c.bench_function(&format!("fk+jacobian/{name}"), |b| {
        b.iter(|| {
            jacobian(&model, &mut data, black_box(&q), JacobianFrame::World).unwrap();
        })
    });
}

fn kinematics(c: &mut Criterion) {
    for name in ["ur5", "panda", "gantry9"] {
        bench_robot(c, name);
    }
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
