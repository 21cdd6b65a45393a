//! Dynamics of coupled models in their independent joints: mimic-joint
//! chains (URDF and built) and the flexible gantry (`d3' = d3 + w(d2)`,
//! seed 000 eq 4).
//!
//! Checked against the same chain built without the coupling, with the map
//! applied by hand from finite differences of `Model::chain_positions`
//! (`tau = M' RNEA_free(c(q), M v, M a + Md v)`, `M` and `Md v` by central
//! differences), and for consistency: M symmetric positive definite with
//! the RNEA's columns, ABA inverting the RNEA, gravity torques as the
//! gradient of the potential energy, the power balance
//! `tau' v = d/dt (T + U)`, and energy conservation in free motion (RK4).
//! Also the beam curve's second derivative against finite differences.

use crate::common::{data_path, random_configuration, random_link, rng};
use armkit::beam::CarriageDeflection;
use armkit::dynamics::simulate::{Integrator, SimulationOptions, Simulator};
use armkit::dynamics::{
    aba, gravity_torques, kinetic_energy, mass_matrix, mass_matrix_inverse, potential_energy, rnea,
    DynamicsData,
};
use armkit::math::{DMatrix, Vector3};
use armkit::model::{CouplingCurve, JointSpec, MimicJoint, ModelBuilder};
use armkit::urdf::{load, ChainSelection};
use armkit::Model;
use rand::Rng;

/// A random chain of `dof` joints; `mimic` adds mimic joints (joint 2
/// follows joint 0, the last follows joint 2: a mimic of a mimic).
fn random_chain(seed: u64, dof: usize, mimic: bool) -> Model {
    let mut r = rng(seed);
    let mut builder = ModelBuilder::new(format!("chain{seed}"));
    for j in 0..dof {
        builder = builder.joint(random_link(&mut r, |_| {
            if j == 1 {
                JointSpec::prismatic(format!("j{j}"), -5.0, 5.0)
            } else {
                JointSpec::revolute(format!("j{j}"), -30.0, 30.0)
            }
        }));
    }
    if mimic {
        builder = builder
            .mimic(MimicJoint::new("j2", "j0", -0.7, 0.1))
            .mimic(MimicJoint::new(format!("j{}", dof - 1), "j2", 1.5, -0.2));
    }
    builder.build().unwrap()
}

fn mimicbot(tip: &str) -> Model {
    load(
        data_path("urdf/mimicbot.urdf"),
        &ChainSelection::between("base", tip),
    )
    .unwrap()
}

/// Coupled models with masses: the flexible gantry, mimicbot's finger (a
/// mimic of a mimic) and gripper (leader off the chain), random chains.
fn coupled_models() -> Vec<Model> {
    let mut models = vec![
        armkit::robots::by_name("gantry9-flex").unwrap(),
        mimicbot("fingertip"),
        mimicbot("finger_b_tip"),
    ];
    for seed in 0..3 {
        models.push(random_chain(seed, 5 + seed as usize, true));
    }
    for model in &models {
        assert!(model.coupling().is_some(), "{}", model.name());
    }
    models
}

fn random_vector(r: &mut impl Rng, n: usize, scale: f64) -> Vec<f64> {
    (0..n).map(|_| r.gen_range(-scale..scale)).collect()
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(1.0_f64, |m, t| m.max(t.abs()))
}

#[test]
fn beam_curvature_is_the_derivative_of_its_slope() {
    let curve = CarriageDeflection::seed000();
    let length = curve.beam.length();
    let h = 1e-5;
    for k in 1..40 {
        let x = length * k as f64 / 40.0;
        let (_, plus) = curve.value_and_slope(x + h);
        let (_, minus) = curve.value_and_slope(x - h);
        let finite = (plus - minus) / (2.0 * h);
        let exact = curve.second_derivative(x).unwrap();
        assert!(
            (finite - exact).abs() < 1e-6 * exact.abs().max(1e-9),
            "x = {x}: {finite} vs {exact}"
        );
    }
    // Off the span the deflection is clamped: no curvature; NaN stays NaN.
    assert_eq!(curve.second_derivative(-0.1), Some(0.0));
    assert_eq!(curve.second_derivative(length + 0.1), Some(0.0));
    assert!(curve.second_derivative(f64::NAN).unwrap().is_nan());
}

/// `tau = M' RNEA_free(c(q), M v, M a + Md v)` with the map `c` differenced.
fn hand_mapped_rnea(
    coupled: &Model,
    free: &Model,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    gravity: Vector3<f64>,
) -> Vec<f64> {
    let n = coupled.dof();
    let nc = coupled.chain_joints().len();
    assert_eq!(free.dof(), nc);
    let chain = |q: &[f64]| {
        let mut c = vec![0.0; nc];
        coupled.chain_positions(q, &mut c).unwrap();
        c
    };
    let h = 1e-4;
    let mut map = DMatrix::zeros(nc, n);
    for i in 0..n {
        let mut plus = q.to_vec();
        let mut minus = q.to_vec();
        plus[i] += h;
        minus[i] -= h;
        let (cp, cm) = (chain(&plus), chain(&minus));
        for j in 0..nc {
            map[(j, i)] = (cp[j] - cm[j]) / (2.0 * h);
        }
    }
    // d^2/dt^2 c(q + t v) at t = 0 is Md v: second differences with a
    // step large against round-off, Richardson-extrapolated (h^2 term out).
    let second_difference = |h: f64| {
        let plus: Vec<f64> = q.iter().zip(v).map(|(x, d)| x + h * d).collect();
        let minus: Vec<f64> = q.iter().zip(v).map(|(x, d)| x - h * d).collect();
        let (cp, c0, cm) = (chain(&plus), chain(q), chain(&minus));
        (0..nc)
            .map(|j| (cp[j] - 2.0 * c0[j] + cm[j]) / (h * h))
            .collect::<Vec<f64>>()
    };
    let (coarse, fine) = (second_difference(1e-2), second_difference(5e-3));
    let c0 = chain(q);
    let map_v = &map * DMatrix::from_column_slice(n, 1, v);
    let map_a = &map * DMatrix::from_column_slice(n, 1, a);
    let chain_a: Vec<f64> = (0..nc)
        .map(|j| map_a[j] + (4.0 * fine[j] - coarse[j]) / 3.0)
        .collect();
    let mut data = DynamicsData::new(free)
        .unwrap()
        .with_gravity(gravity)
        .unwrap();
    let tau_chain = rnea(free, &mut data, &c0, map_v.as_slice(), &chain_a).unwrap();
    (map.transpose() * DMatrix::from_column_slice(nc, 1, tau_chain))
        .as_slice()
        .to_vec()
}

#[test]
fn coupled_rnea_equals_the_free_chain_with_the_map_applied_by_hand() {
    let gravity = Vector3::new(0.4, -0.3, -9.81);
    let mut pairs = vec![(
        armkit::robots::by_name("gantry9-flex").unwrap(),
        armkit::robots::by_name("gantry9").unwrap(),
    )];
    for seed in 0..3 {
        let dof = 5 + seed as usize;
        pairs.push((
            random_chain(seed, dof, true),
            random_chain(seed, dof, false),
        ));
    }
    // mimicbot, and the same file with its <mimic> elements removed.
    let text = std::fs::read_to_string(data_path("urdf/mimicbot.urdf")).unwrap();
    let free_text: String = text
        .lines()
        .filter(|line| !line.contains("<mimic"))
        .map(|line| format!("{line}\n"))
        .collect();
    assert_eq!(text.matches("<mimic").count(), 3);
    let dir = std::env::temp_dir().join(format!("armkit-dynamics-coupled-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let free_path = dir.join("mimicbot_free.urdf");
    std::fs::write(&free_path, free_text).unwrap();
    for tip in ["fingertip", "finger_b_tip"] {
        let free = load(&free_path, &ChainSelection::between("base", tip)).unwrap();
        assert!(free.coupling().is_none());
        pairs.push((mimicbot(tip), free));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    let mut r = rng(40);
    for (coupled, free) in &pairs {
        let n = coupled.dof();
        let mut data = DynamicsData::new(coupled)
            .unwrap()
            .with_gravity(gravity)
            .unwrap();
        for _ in 0..5 {
            let q = random_configuration(coupled, &mut r);
            // Large velocities make the beam's curvature term visible.
            let v = random_vector(&mut r, n, 2.0);
            let a = random_vector(&mut r, n, 2.0);
            let tau = rnea(coupled, &mut data, &q, &v, &a).unwrap().to_vec();
            let expected = hand_mapped_rnea(coupled, free, &q, &v, &a, gravity);
            let scale = max_abs(&expected);
            for j in 0..n {
                assert!(
                    (tau[j] - expected[j]).abs() < 1e-6 * scale,
                    "{}: tau[{j}] = {} but by hand {}",
                    coupled.name(),
                    tau[j],
                    expected[j]
                );
            }
        }
    }
}

#[test]
fn beam_curvature_term_is_included() {
    // Only d2 moving, at constant speed: without the w'' d2_dot^2 term the
    // carriage's vertical acceleration (and the torque it costs) would be
    // missing; the difference from the rigid gantry's mapped torques is that
    // term's share, checked against the hand map above (nonzero here).
    let flex = armkit::robots::by_name("gantry9-flex").unwrap();
    let mut data = DynamicsData::new(&flex)
        .unwrap()
        .with_gravity(Vector3::zeros())
        .unwrap();
    let mut q = flex.neutral_configuration();
    q[1] = 0.7;
    let mut v = vec![0.0; 9];
    v[1] = 3.0;
    let a = vec![0.0; 9];
    let tau = rnea(&flex, &mut data, &q, &v, &a).unwrap().to_vec();
    let expected = hand_mapped_rnea(
        &flex,
        &armkit::robots::by_name("gantry9").unwrap(),
        &q,
        &v,
        &a,
        Vector3::zeros(),
    );
    // The vertical joint (d3) holds the carriage's mass times w'' v^2.
    assert!(tau[2].abs() > 1e-6, "{}", tau[2]);
    for j in 0..9 {
        assert!(
            (tau[j] - expected[j]).abs() < 1e-6 * max_abs(&expected),
            "tau[{j}] = {} but by hand {}",
            tau[j],
            expected[j]
        );
    }
}

#[test]
fn coupled_mass_matrix_is_symmetric_positive_definite_with_rnea_columns() {
    let mut r = rng(41);
    for model in coupled_models() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model).unwrap();
        let mut zero_gravity = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::zeros())
            .unwrap();
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let m = mass_matrix(&model, &mut data, &q).unwrap().clone();
            assert_eq!(m.shape(), (n, n));
            assert!((&m - m.transpose()).amax() < 1e-12 * m.amax());
            assert!(m.clone().cholesky().is_some(), "{}", model.name());
            let zeros = vec![0.0; n];
            for j in 0..n {
                let mut e = zeros.clone();
                e[j] = 1.0;
                let column = rnea(&model, &mut zero_gravity, &q, &zeros, &e).unwrap();
                for i in 0..n {
                    assert!((column[i] - m[(i, j)]).abs() < 1e-12 * m.amax().max(1.0));
                }
            }
            let inverse = mass_matrix_inverse(&model, &mut data, &q).unwrap();
            assert!((inverse * &m - DMatrix::identity(n, n)).amax() < 1e-8);
        }
    }
}

#[test]
fn coupled_aba_inverts_rnea() {
    let mut r = rng(42);
    for model in coupled_models() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model).unwrap();
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let v = random_vector(&mut r, n, 1.5);
            let tau = random_vector(&mut r, n, 5.0);
            let ddq = aba(&model, &mut data, &q, &v, &tau).unwrap().to_vec();
            let back = rnea(&model, &mut data, &q, &v, &ddq).unwrap();
            for j in 0..n {
                assert!(
                    (back[j] - tau[j]).abs() < 1e-9 * max_abs(&tau),
                    "{}: {} vs {}",
                    model.name(),
                    back[j],
                    tau[j]
                );
            }
        }
    }
}

#[test]
fn coupled_gravity_torques_are_the_gradient_of_the_potential_energy() {
    let mut r = rng(43);
    for model in coupled_models() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::new(0.3, -1.2, -9.81))
            .unwrap();
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let g = gravity_torques(&model, &mut data, &q).unwrap().to_vec();
            let h = 1e-6;
            for j in 0..n {
                let mut plus = q.clone();
                let mut minus = q.clone();
                plus[j] += h;
                minus[j] -= h;
                let derivative = (potential_energy(&model, &mut data, &plus).unwrap()
                    - potential_energy(&model, &mut data, &minus).unwrap())
                    / (2.0 * h);
                assert!(
                    (derivative - g[j]).abs() < 1e-6 * max_abs(&g),
                    "{}: dU/dq[{j}] = {derivative} but g = {}",
                    model.name(),
                    g[j]
                );
            }
        }
    }
}

/// `T + U` at a state.
fn energy(model: &Model, data: &mut DynamicsData, q: &[f64], v: &[f64]) -> f64 {
    kinetic_energy(model, data, q, v).unwrap() + potential_energy(model, data, q).unwrap()
}

#[test]
fn power_balance_tau_v_is_the_rate_of_energy() {
    // d/dt (T + U) = dE/dq v + dE/dv ddq, ddq = ABA(q, v, tau), must be tau' v.
    let mut r = rng(44);
    for model in coupled_models() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::new(0.0, 0.5, -9.81))
            .unwrap();
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let v = random_vector(&mut r, n, 1.5);
            let tau = random_vector(&mut r, n, 5.0);
            let ddq = aba(&model, &mut data, &q, &v, &tau).unwrap().to_vec();
            // The five-point stencil along the line (q + s v, v + s ddq):
            // truncation O(h^4), and round-off ~ eps |U| / h, which on the
            // gantry (|U| ~ 2e5 J) is 4e-5 at h = 1e-6 but 4e-7 at h = 1e-4.
            let h = 1e-4;
            let mut at = |s: f64| {
                let q: Vec<f64> = q.iter().zip(&v).map(|(x, d)| x + s * d).collect();
                let v: Vec<f64> = v.iter().zip(&ddq).map(|(x, d)| x + s * d).collect();
                energy(&model, &mut data, &q, &v)
            };
            let rate = (8.0 * (at(h) - at(-h)) - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h);
            let power: f64 = tau.iter().zip(&v).map(|(t, x)| t * x).sum();
            let scale = power.abs().max(1.0);
            assert!(
                (rate - power).abs() < 1e-5 * scale,
                "{}: dE/dt = {rate} but tau' v = {power}",
                model.name()
            );
        }
    }
}

#[test]
fn coupled_free_motion_conserves_energy() {
    // Gravity off, tau = 0, RK4 with a 1 ms step over 0.5 s.
    for model in coupled_models() {
        let n = model.dof();
        let options = SimulationOptions {
            time_step: 1e-3,
            integrator: Integrator::RungeKutta4,
            friction: None,
        };
        let mut sim = Simulator::new(&model, options).unwrap();
        sim.data_mut().set_gravity(Vector3::zeros()).unwrap();
        let mut data = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::zeros())
            .unwrap();
        let mut r = rng(45);
        let mut q = random_configuration(&model, &mut r);
        let mut v = random_vector(&mut r, n, 1.0);
        let zero = vec![0.0; n];
        let initial = kinetic_energy(&model, &mut data, &q, &v).unwrap();
        let mut worst: f64 = 0.0;
        for _ in 0..500 {
            sim.step(&model, &mut q, &mut v, &zero).unwrap();
            let energy = kinetic_energy(&model, &mut data, &q, &v).unwrap();
            worst = worst.max((energy - initial).abs() / initial);
        }
        println!(
            "{}: RK4, h = 1 ms, 0.5 s: relative energy drift {worst:.2e}",
            model.name()
        );
        assert!(worst < 1e-6, "{}: drift {worst:e}", model.name());
    }
}

#[test]
fn coupled_workspace_is_not_used_with_another_model() {
    let flex = armkit::robots::by_name("gantry9-flex").unwrap();
    let rigid = armkit::robots::by_name("gantry9").unwrap();
    let mut rigid_data = DynamicsData::new(&rigid).unwrap();
    let err = gravity_torques(&flex, &mut rigid_data, &flex.neutral_configuration())
        .unwrap_err()
        .to_string();
    assert!(err.contains("another model"), "{err}");
    let finger = mimicbot("fingertip");
    let mut finger_data = DynamicsData::new(&finger).unwrap();
    let err = gravity_torques(&rigid, &mut finger_data, &rigid.neutral_configuration())
        .unwrap_err()
        .to_string();
    assert!(err.contains("another model"), "{err}");
}
