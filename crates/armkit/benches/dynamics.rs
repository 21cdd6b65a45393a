//! Rigid-body dynamics timings: RNEA, the mass matrix (CRBA) and
//! ABA on the ur5 and panda URDF chains, the models Pinocchio's benchmark in
//! `../shared/peers` (`bench_cpp.py`: `rnea_ns`, `crba_ns`, `aba_ns`) loads.
//!
//! Also the coupled models (mimicbot's finger, gantry9-flex),
//! which work in their independent joints.
//!
//! Run: `cargo bench -p armkit --bench dynamics`.
//!
//! Each call takes the next of 1024 random states (positions within the
//! limits, velocities in [-1, 1], accelerations in [-2, 2], torques in [-10, 10];
//! seeded), as Pinocchio's benchmark does.

use armkit::dynamics::{aba, mass_matrix, rnea, DynamicsData};
use armkit::urdf::{load, ChainSelection};
use criterion::{criterion_group, criterion_main, Criterion};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

struct State {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    tau: Vec<f64>,
}

fn random_states(model: &armkit::Model, count: usize) -> Vec<State> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let n = model.dof();
    (0..count)
        .map(|_| {
            let q = model
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
                .collect();
            let mut uniform = |scale: f64| -> Vec<f64> {
                (0..n).map(|_| rng.gen_range(-scale..=scale)).collect()
            };
            State {
                q,
                v: uniform(1.0),
                a: uniform(2.0),
                tau: uniform(10.0),
            }
        })
        .collect()
}

fn bench_robot(c: &mut Criterion, name: &str, base: &str, tip: &str) {
    let path = format!(
        "{}/../../tests/data/urdf/{name}.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    let model = load(path, &ChainSelection::between(base, tip)).unwrap();
    bench_model(c, name, &model);
}

/// RNEA, CRBA and ABA on `model`, labelled `name`.
fn bench_model(c: &mut Criterion, name: &str, model: &armkit::Model) {
    let model = model.clone();
    let mut data = DynamicsData::new(&model).unwrap();
    let states = random_states(&model, 1024);
    let mut next = states.iter().cycle();
    c.bench_function(&format!("rnea/{name}"), |b| {
        b.iter(|| {
            let s = next.next().unwrap();
            rnea(&model, &mut data, black_box(&s.q), &s.v, &s.a).unwrap();
        })
    });
    c.bench_function(&format!("crba/{name}"), |b| {
        b.iter(|| {
            let s = next.next().unwrap();
            mass_matrix(&model, &mut data, black_box(&s.q)).unwrap();
        })
    });
    c.bench_function(&format!("aba/{name}"), |b| {
        b.iter(|| {
            let s = next.next().unwrap();
            aba(&model, &mut data, black_box(&s.q), &s.v, &s.tau).unwrap();
        })
    });
}

fn dynamics(c: &mut Criterion) {
    bench_robot(c, "ur5", "base_link", "tool0");
    bench_robot(c, "panda", "panda_link0", "panda_link8");
    // Coupled models: a mimic-joint finger (9 chain joints, 7
    // independent; forward dynamics by Cholesky) and the flexible gantry.
    bench_robot(c, "mimicbot", "base", "fingertip");
    let flex = armkit::robots::by_name("gantry9-flex").unwrap();
    bench_model(c, "gantry9-flex", &flex);
}

criterion_group!(benches, dynamics);
criterion_main!(benches);
