//! The cost of the flexible beam: forward kinematics and FK + coupled
//! Jacobian of `gantry9-flex` (d3' = d3 + w(d2), J = J0 M) against the rigid
//! `gantry9`, and the beam formulas alone.
//!
//! Run: `cargo bench -p armkit --bench beam`.

use armkit::beam::{PointLoad, SimplySupportedBeam, TwoCarriageBeam};
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::robots;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn gantry(c: &mut Criterion) {
    for (label, model) in [
        ("rigid", robots::gantry9().unwrap()),
        ("flex", robots::gantry9_flex().unwrap()),
    ] {
        let mut data = Data::new(&model);
        // Mid-range, nudged so no joint sits at a special value.
        let q: Vec<f64> = model
            .joints()
            .iter()
            .enumerate()
            .map(|(j, joint)| joint.limits.midpoint() + 0.1 * (j as f64 + 1.0))
            .collect();
        c.bench_function(&format!("gantry9/{label}/fk"), |b| {
            b.iter(|| {
                forward_kinematics(&model, &mut data, black_box(&q)).unwrap();
            })
        });
        c.bench_function(&format!("gantry9/{label}/fk+jacobian"), |b| {
            b.iter(|| {
                jacobian(&model, &mut data, black_box(&q), JacobianFrame::World).unwrap();
            })
        });
    }
}

fn formulas(c: &mut Criterion) {
    let beam = SimplySupportedBeam::seed000();
    let loads = [PointLoad::new(3.3, 4000.0), PointLoad::new(6.7, 4000.0)];
    c.bench_function("beam/deflection_two_loads", |b| {
        b.iter(|| beam.deflection(black_box(4.2), black_box(&loads)).unwrap())
    });
    let two = TwoCarriageBeam::seed000();
    c.bench_function("beam/two_carriage_deflection_jacobian", |b| {
        b.iter(|| two.deflection_jacobian(black_box([3.3, 6.7])).unwrap())
    });
}

criterion_group!(benches, gantry, formulas);
criterion_main!(benches);
