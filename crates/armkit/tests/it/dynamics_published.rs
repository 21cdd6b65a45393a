//! Dynamics on published URDFs whose mass properties are unusual, against
//! Pinocchio 4.1 (`tests/data/make_reference_dynamics_published.py`):
//! the Lynxmotion AL5D (point masses on the joint axes: `M(q)` singular
//! everywhere), the human model's leg (massless links between joints) and
//! Bolt's leg (a foot of zero mass with an inertia tensor). Inverse
//! dynamics, the mass matrix and gravity are defined on all three; forward
//! dynamics is refused on the singular chain at every configuration, and the
//! decision is relative to the mass matrix's scale.

use crate::common::{self, data_path, random_configuration, rng};
use armkit::dynamics::{
    aba, gravity_torques, mass_matrix, mass_matrix_inverse, rnea, DynamicsData,
    MASS_MATRIX_THRESHOLD,
};
use armkit::math::{Pose, Vector3};
use armkit::model::{JointSpec, LinkInertia, ModelBuilder};
use armkit::urdf::{load, ChainSelection};
use armkit::{Error, Model};
use rand::Rng;

/// The brief's bound on inverse dynamics and the mass matrix (N m, kg m^2).
const TOLERANCE: f64 = 1e-8;

struct Sample {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    tau: Vec<f64>,
    mass_matrix: Vec<Vec<f64>>,
    gravity: Vec<f64>,
}

/// The chain of `reference_dynamics_<chain>.json`, and its samples.
fn reference(chain: &str) -> (Model, Vec<Sample>) {
    let file = format!("reference_dynamics_{chain}.json");
    let text = std::fs::read_to_string(data_path(&file)).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let vector = |v: &serde_json::Value| -> Vec<f64> { serde_json::from_value(v.clone()).unwrap() };
    let text = |key: &str| value[key].as_str().unwrap().to_string();
    let model = load(
        data_path(&text("urdf")),
        &ChainSelection::between(text("base"), text("tip")),
    )
    .unwrap();
    let names: Vec<String> = serde_json::from_value(value["joint_names"].clone()).unwrap();
    let ours: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(ours, names, "{chain}: joint order");
    assert_eq!(vector(&value["gravity"]), [0.0, 0.0, -9.81]);
    let samples = value["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| Sample {
            q: vector(&s["q"]),
            v: vector(&s["v"]),
            a: vector(&s["a"]),
            tau: vector(&s["tau"]),
            mass_matrix: serde_json::from_value(s["mass_matrix"].clone()).unwrap(),
            gravity: vector(&s["gravity"]),
        })
        .collect();
    (model, samples)
}

/// RNEA, CRBA and gravity torques within [`TOLERANCE`] of Pinocchio's.
fn check_against_pinocchio(chain: &str) {
    let (model, samples) = reference(chain);
    assert_eq!(samples.len(), 6);
    let mut data = DynamicsData::new(&model).unwrap();
    let mut worst = [0.0_f64; 3];
    for s in &samples {
        let m = mass_matrix(&model, &mut data, &s.q).unwrap();
        // Row-major, as the file.
        let m: Vec<f64> = m.transpose().as_slice().to_vec();
        let checks = [
            common::max_abs_difference(rnea(&model, &mut data, &s.q, &s.v, &s.a).unwrap(), &s.tau),
            common::max_abs_difference(&m, &s.mass_matrix.concat()),
            common::max_abs_difference(
                gravity_torques(&model, &mut data, &s.q).unwrap(),
                &s.gravity,
            ),
        ];
        for (w, c) in worst.iter_mut().zip(checks) {
            *w = w.max(c);
        }
    }
    for (name, w) in ["tau", "mass_matrix", "gravity"].iter().zip(worst) {
        println!("{chain}: {name}: largest difference from Pinocchio {w:.1e}");
        assert!(w <= TOLERANCE, "{chain}: {name} off by {w:e}");
    }
}

#[test]
fn al5d_inverse_dynamics_and_mass_matrix_equal_pinocchio() {
    check_against_pinocchio("al5d");
}

#[test]
fn human_leg_with_massless_links_equals_pinocchio() {
    check_against_pinocchio("human_leg");
}

#[test]
fn bolt_leg_keeps_the_zero_mass_foot_tensor_as_pinocchio() {
    check_against_pinocchio("bolt_leg");
    // The foot's tensor is in the lower leg's body: its mass is the lower
    // leg's alone, the trace of its tensor (about the same centre of mass)
    // the lower leg's plus the foot's.
    let (model, _) = reference("bolt_leg");
    let shin = model.chain_joints()[2].inertia.unwrap();
    assert_eq!(shin.mass, 0.03117243);
    let (leg, foot) = (
        0.00011487 + 0.00011556 + 0.0000022,
        0.00000057 + 0.00000084 + 0.00000053,
    );
    assert!((shin.inertia.trace() - (leg + foot)).abs() < 1e-15);
}

/// `aba` and `mass_matrix_inverse` refuse `model` at `q`, naming `joint`.
fn assert_refused(model: &Model, data: &mut DynamicsData, q: &[f64], v: &[f64], joint: &str) {
    let tau = vec![0.5; model.dof()];
    for result in [
        aba(model, data, q, v, &tau).map(|x| x.to_vec()),
        mass_matrix_inverse(model, data, q).map(|m| m.as_slice().to_vec()),
    ] {
        match result {
            Err(Error::Numerical { reason, .. }) => assert!(
                reason.contains("singular at joint") && reason.contains(joint),
                "{}: {reason}",
                model.name()
            ),
            other => panic!("{} at q = {q:?}: {other:?}", model.name()),
        }
    }
}

#[test]
fn al5d_forward_dynamics_is_refused_at_every_configuration() {
    let (model, samples) = reference("al5d");
    let mut data = DynamicsData::new(&model).unwrap();
    let mut r = rng(32);
    let mut tried = 0;
    for s in &samples {
        assert_refused(&model, &mut data, &s.q, &s.v, "`j4`");
        tried += 1;
    }
    for _ in 0..2000 {
        let q = random_configuration(&model, &mut r);
        let v: Vec<f64> = (0..model.dof()).map(|_| r.gen_range(-2.0..2.0)).collect();
        assert_refused(&model, &mut data, &q, &v, "`j4`");
        tried += 1;
    }
    println!("al5d: forward dynamics refused at all {tried} configurations");
}

#[test]
fn forward_dynamics_where_the_mass_matrix_is_regular_undoes_inverse_dynamics() {
    for chain in ["human_leg", "bolt_leg"] {
        let (model, samples) = reference(chain);
        let mut data = DynamicsData::new(&model).unwrap();
        for s in &samples {
            let ddq = aba(&model, &mut data, &s.q, &s.v, &s.tau).unwrap().to_vec();
            let scale = s.a.iter().fold(1.0_f64, |m, a| m.max(a.abs()));
            assert!(
                common::max_abs_difference(&ddq, &s.a) <= 1e-9 * scale,
                "{chain}: {ddq:?} vs {:?}",
                s.a
            );
        }
    }
}

/// Two joints about z, 1 m apart; the first link a point mass `mass` at the
/// second joint, the second a point mass `mass` at `offset` from its axis:
/// `M = [[mass (1 + (1 + e)^2), ...], [..., mass e^2]]` (lengths times
/// `length`), the second pivot `mass (e length)^2`.
fn two_point_masses(mass: f64, length: f64, offset: f64) -> Model {
    let point = |x: f64| LinkInertia::point_mass(mass, Vector3::new(x * length, 0.0, 0.0));
    ModelBuilder::new("two-point-masses")
        .joint(JointSpec::revolute("first", -3.0, 3.0).with_inertia(point(1.0)))
        .joint(
            JointSpec::revolute("second", -3.0, 3.0)
                .with_origin(Pose::from_translation(Vector3::new(length, 0.0, 0.0)))
                .with_inertia(point(offset)),
        )
        .build()
        .unwrap()
}

/// The decision depends on the pivot relative to `M`'s largest diagonal
/// entry only: a pivot ten times above the threshold gives accelerations,
/// ten times below an error, whatever the units of mass and length.
#[test]
fn the_singularity_threshold_is_relative_to_the_mass_matrix_scale() {
    let q = [0.3, 0.0];
    for (mass, length) in [(1.0, 1.0), (1e-6, 1.0), (1e3, 1e-3), (1e-3, 1e2)] {
        for (factor, regular) in [(10.0, true), (0.1, false)] {
            // Pivot e^2 against the largest diagonal entry about 1 + (1 + e)^2.
            let offset = (factor * MASS_MATRIX_THRESHOLD * 2.0).sqrt();
            let model = two_point_masses(mass, length, offset);
            let mut data = DynamicsData::new(&model).unwrap();
            let m = mass_matrix(&model, &mut data, &q).unwrap().clone();
            let largest = m[(0, 0)].max(m[(1, 1)]);
            let pivot = m[(1, 1)];
            assert!((pivot / largest / (factor * MASS_MATRIX_THRESHOLD) - 1.0).abs() < 0.01);
            if regular {
                aba(&model, &mut data, &q, &[0.0, 0.0], &[0.0, 1.0]).unwrap();
                mass_matrix_inverse(&model, &mut data, &q).unwrap();
            } else {
                assert_refused(&model, &mut data, &q, &[0.0, 0.0], "`second`");
            }
        }
    }
}
