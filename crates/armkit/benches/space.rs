//! Free-floating space robot timings on space6r (seed 004): the generalized
//! Jacobian in both base modes (target: at most 1 us attitude-held) and one
//! simulation step.
//!
//! Run: `cargo bench -p armkit --bench space -- --warm-up-time 1 --measurement-time 3`.

use armkit::math::Pose;
use armkit::robots::space6r_free_floating;
use armkit::space::{
    center_of_mass, generalized_jacobian, step, BaseMode, FreeFloatingState, SpaceData,
};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn space(c: &mut Criterion) {
    let model = space6r_free_floating().unwrap();
    let mut data = SpaceData::new(&model);
    let base = Pose::from_xyz_rpy([0.1, -0.2, 0.3], [0.2, 0.1, -0.3]);
    let q = [0.4, 0.9, -0.7, 0.3, 0.8, -0.5];
    c.bench_function(
        "center_of_mass/space6r (forward kinematics of every body)",
        |b| {
            b.iter(|| {
                center_of_mass(&model, &mut data, black_box(&base), black_box(&q)).unwrap();
            })
        },
    );
    for (label, mode) in [
        ("attitude-held", BaseMode::AttitudeHeld),
        ("free-floating", BaseMode::FreeFloating),
    ] {
        c.bench_function(&format!("generalized_jacobian/space6r/{label}"), |b| {
            b.iter(|| {
                generalized_jacobian(&model, &mut data, black_box(&base), black_box(&q), mode)
                    .unwrap();
            })
        });
        let rates = [0.1, -0.2, 0.3, 0.1, 0.2, -0.1];
        let mut state = FreeFloatingState::new(base, q.to_vec());
        c.bench_function(&format!("step/space6r/{label}"), |b| {
            b.iter(|| {
                // Tiny steps: the state stays near the start over the run.
                step(&model, &mut data, &mut state, black_box(&rates), 1e-9, mode).unwrap();
            })
        });
    }
}

criterion_group!(benches, space);
criterion_main!(benches);
