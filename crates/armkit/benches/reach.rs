//! Reachability map queries on the UR5 (0.1 m cells, 200 approach
//! directions): the interpolated pose query, the raw bin, the capability
//! lookup and the nearest reachable cell, over 1024 fixed poses in the
//! map's box.
//!
//! Run: `cargo bench -p armkit --bench reach -- --warm-up-time 1 --measurement-time 3`.

use armkit::math::{Pose, Vector3};
use armkit::reach::{self, Builder, MapSpec};
use criterion::{criterion_group, criterion_main, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

fn queries(c: &mut Criterion) {
    let model = armkit::robots::by_name("ur5").unwrap();
    let spec = MapSpec::for_model(&model, 0.1, 200, Builder::InverseKinematics);
    let map = reach::build(&model, &spec, 2, &mut |_, _| {}).unwrap();
    let layout = map.layout();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let poses: Vec<Pose> = (0..1024)
        .map(|_| {
            let p = Vector3::from_fn(|i, _| {
                layout.origin()[i] + rng.gen_range(0.0..layout.dims()[i] as f64 * 0.1)
            });
            let r = Pose::rot_z(rng.gen_range(-3.0..3.0)) * Pose::rot_x(rng.gen_range(-3.0..3.0));
            Pose {
                rotation: r.rotation,
                translation: p,
            }
        })
        .collect();
    let mut i = 0;
    let mut next = || {
        i = (i + 1) % poses.len();
        &poses[i]
    };
    c.bench_function("reach/query/ur5", |b| {
        b.iter(|| black_box(map.query(black_box(next()))))
    });
    let mut j = 0;
    c.bench_function("reach/bin/ur5", |b| {
        b.iter(|| {
            j = (j + 1) % poses.len();
            black_box(map.bin_reachable(black_box(&poses[j])))
        })
    });
    let mut k = 0;
    c.bench_function("reach/nearest_cell/ur5", |b| {
        b.iter(|| {
            k = (k + 1) % poses.len();
            let t = poses[k].translation;
            black_box(map.nearest_reachable_cell(black_box([t.x, t.y, t.z])))
        })
    });
}

criterion_group!(benches, queries);
criterion_main!(benches);
