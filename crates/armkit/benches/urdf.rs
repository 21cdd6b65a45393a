//! FK and FK + Jacobian of the Panda loaded from URDF (panda_link0 to
//! panda_link8), beside the built-in DH Panda (`robots::panda()`): a URDF
//! model runs on the same FK loop, so the timings should be in the same
//! ballpark. Also the time to load the URDF file, and mimic joints: the
//! mimicbot finger chain (9 chain joints, 7 independent: FK expands `q`, the
//! Jacobian folds the mimic columns) beside the same chain with the mimic
//! joints made independent (9 dof, no folding).
//!
//! Run: `cargo bench -p armkit --bench urdf`.

use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::urdf::{self, ChainSelection};
use armkit::Model;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn panda_urdf_path() -> String {
    format!(
        "{}/../../tests/data/urdf/panda.urdf",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn panda_selection() -> ChainSelection {
    ChainSelection::between("panda_link0", "panda_link8")
}

fn bench_model(c: &mut Criterion, label: &str, model: &Model) {
    let mut data = Data::new(model);
    let q: Vec<f64> = model
        .joints()
        .iter()
        .enumerate()
        .map(|(j, joint)| joint.limits.midpoint() + 0.1 * (j as f64 + 1.0))
        .collect();
    c.bench_function(&format!("fk/{label}"), |b| {
        b.iter(|| {
            forward_kinematics(model, &mut data, black_box(&q)).unwrap();
        })
    });
    c.bench_function(&format!("fk+jacobian/{label}"), |b| {
        b.iter(|| {
            jacobian(model, &mut data, black_box(&q), JacobianFrame::World).unwrap();
        })
    });
}

fn panda_urdf_vs_dh(c: &mut Criterion) {
    let from_urdf = urdf::load(panda_urdf_path(), &panda_selection()).unwrap();
    let from_dh = armkit::robots::panda().unwrap();
    bench_model(c, "panda-urdf", &from_urdf);
    bench_model(c, "panda-dh", &from_dh);
    let text = std::fs::read_to_string(panda_urdf_path()).unwrap();
    c.bench_function("load/panda-urdf", |b| {
        b.iter(|| urdf::parse_str(black_box(&text), "panda.urdf", &panda_selection()).unwrap())
    });
}

fn mimic_joints(c: &mut Criterion) {
    let path = format!(
        "{}/../../tests/data/urdf/mimicbot.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    let selection = ChainSelection::between("base", "fingertip");
    let with_mimic = urdf::parse_str(&text, "mimicbot.urdf", &selection).unwrap();
    let independent: String = text
        .lines()
        .filter(|line| !line.trim_start().starts_with("<mimic"))
        .collect::<Vec<_>>()
        .join("\n");
    let without_mimic = urdf::parse_str(&independent, "mimicbot.urdf", &selection).unwrap();
    bench_model(c, "mimicbot-finger", &with_mimic);
    bench_model(c, "mimicbot-finger-no-mimic", &without_mimic);
}

criterion_group!(benches, panda_urdf_vs_dh, mimic_joints);
criterion_main!(benches);
