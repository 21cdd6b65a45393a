//! One sample of the simulated plant ([`armkit::mpc::Plant::advance`]) on
//! the 9-joint gantry: exact integration and 1 mm prismatic resolution
//! with a deadband and velocity quantisation.
//!
//! Run: `cargo bench -p armkit --bench plant`.

use std::hint::black_box;

use armkit::mpc::{ActuatorPrecision, Plant, PlantModel};
use criterion::{criterion_group, criterion_main, Criterion};

fn bench_plant(c: &mut Criterion) {
    let model = armkit::robots::gantry9_flex().unwrap();
    let kinds: Vec<_> = model.joints().iter().map(|j| j.kind).collect();
    let limited = PlantModel::LimitedPrecision {
        prismatic: ActuatorPrecision {
            position_resolution: 1e-3,
            deadband: 1e-3,
            velocity_resolution: 1e-4,
        },
        rotary: ActuatorPrecision::EXACT,
    };
    for (name, plant_model) in [("exact", PlantModel::Exact), ("limited", limited)] {
        let mut q = model.neutral_configuration();
        let mut plant = Plant::new(plant_model, &kinds, &q).unwrap();
        let u = vec![0.013; q.len()];
        c.bench_function(&format!("plant_advance/gantry9-flex/{name}"), |b| {
            b.iter(|| {
                plant
                    .advance(black_box(&mut q), black_box(&u), 0.05)
                    .unwrap();
            })
        });
    }
}

criterion_group!(benches, bench_plant);
criterion_main!(benches);
