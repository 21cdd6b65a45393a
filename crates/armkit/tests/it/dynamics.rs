//! Rigid-body dynamics: RNEA, CRBA, ABA, gravity and Coriolis
//! torques against Pinocchio 4.1's reference data through the URDF loader,
//! and consistency checks on every built-in with masses and on random arms:
//! M symmetric positive definite, M's columns from the RNEA, ABA inverting
//! the RNEA, gravity torques as the gradient of the potential energy (finite
//! differences), the inverse of M, and energy conservation in simulation.

use crate::common::{data_path, random_configuration, random_link, rng};
use armkit::dynamics::simulate::{Integrator, JointFriction, SimulationOptions, Simulator};
use armkit::dynamics::{
    aba, coriolis_torques, gravity_torques, kinetic_energy, mass_matrix, mass_matrix_inverse,
    nonlinear_effects, potential_energy, rnea, DynamicsData,
};
use armkit::math::{DMatrix, Pose, Vector3};
use armkit::model::{JointSpec, LinkInertia, ModelBuilder};
use armkit::urdf::{load, ChainSelection};
use armkit::Model;
use rand::Rng;

struct DynamicsSample {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    tau: Vec<f64>,
    mass_matrix: Vec<Vec<f64>>,
    gravity: Vec<f64>,
    coriolis: Vec<f64>,
    tau_in: Vec<f64>,
    ddq: Vec<f64>,
    kinetic_energy: f64,
}

fn reference(file: &str) -> (Vec<f64>, String, String, String, Vec<DynamicsSample>) {
    let text = std::fs::read_to_string(data_path(file)).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let vector = |v: &serde_json::Value| -> Vec<f64> { serde_json::from_value(v.clone()).unwrap() };
    let samples = value["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| DynamicsSample {
            q: vector(&s["q"]),
            v: vector(&s["v"]),
            a: vector(&s["a"]),
            tau: vector(&s["tau"]),
            mass_matrix: serde_json::from_value(s["mass_matrix"].clone()).unwrap(),
            gravity: vector(&s["gravity"]),
            coriolis: vector(&s["coriolis"]),
            tau_in: vector(&s["tau_in"]),
            ddq: vector(&s["ddq"]),
            kinetic_energy: s["kinetic_energy"].as_f64().unwrap(),
        })
        .collect();
    (
        vector(&value["gravity"]),
        // The stripped copy in tests/data/urdf is named after the robot
        // (the file's `urdf` field gives the package's original name).
        format!("{}.urdf", value["robot"].as_str().unwrap()),
        value["base"].as_str().unwrap().to_string(),
        value["tip"].as_str().unwrap().to_string(),
        samples,
    )
}

/// A tolerance `|x - y| <= relative |y| + absolute`.
#[derive(Clone, Copy)]
struct Tolerance {
    relative: f64,
    absolute: f64,
}

/// The URDF loader against Pinocchio on the same file.
const SAME_MODEL: Tolerance = Tolerance {
    relative: 1e-9,
    absolute: 1e-10,
};

/// A built-in (DH frames, typed constants) against Pinocchio on the URDF of
/// the same robot.
const SAME_ROBOT: Tolerance = Tolerance {
    relative: 1e-6,
    absolute: 1e-9,
};

/// Largest violation of the tolerance, as a multiple of its bound (<= 1 passes).
fn violation(x: &[f64], y: &[f64], tolerance: Tolerance) -> f64 {
    assert_eq!(x.len(), y.len());
    x.iter()
        .zip(y)
        .map(|(x, y)| (x - y).abs() / (tolerance.relative * y.abs() + tolerance.absolute))
        .fold(0.0, f64::max)
}

/// The URDF chain of a reference file, as armkit loads it.
fn reference_urdf_model(file: &str) -> Model {
    let (_, urdf, base, tip, _) = reference(file);
    load(
        data_path(&format!("urdf/{urdf}")),
        &ChainSelection::between(base, tip),
    )
    .unwrap()
}

fn check_against_pinocchio(file: &str) {
    check_model_against_pinocchio(&reference_urdf_model(file), file, SAME_MODEL);
}

fn check_model_against_pinocchio(model: &Model, file: &str, tolerance: Tolerance) {
    let (gravity, _, _, _, samples) = reference(file);
    assert_eq!(samples.len(), 50);
    let violation = |x: &[f64], y: &[f64]| violation(x, y, tolerance);
    let mut data = DynamicsData::new(model)
        .unwrap()
        .with_gravity(Vector3::from_column_slice(&gravity))
        .unwrap();
    let mut worst = [0.0_f64; 6];
    for s in &samples {
        let checks = [
            violation(rnea(model, &mut data, &s.q, &s.v, &s.a).unwrap(), &s.tau),
            violation(
                mass_matrix(model, &mut data, &s.q)
                    .unwrap()
                    .transpose()
                    .as_slice(),
                &s.mass_matrix.concat(),
            ),
            violation(gravity_torques(model, &mut data, &s.q).unwrap(), &s.gravity),
            violation(
                coriolis_torques(model, &mut data, &s.q, &s.v).unwrap(),
                &s.coriolis,
            ),
            violation(
                aba(model, &mut data, &s.q, &s.v, &s.tau_in).unwrap(),
                &s.ddq,
            ),
            violation(
                &[kinetic_energy(model, &mut data, &s.q, &s.v).unwrap()],
                &[s.kinetic_energy],
            ),
        ];
        for (w, c) in worst.iter_mut().zip(checks) {
            *w = w.max(c);
        }
    }
    let names = [
        "tau",
        "mass_matrix",
        "gravity",
        "coriolis",
        "ddq",
        "kinetic_energy",
    ];
    for (name, w) in names.iter().zip(worst) {
        let (relative, absolute) = (tolerance.relative, tolerance.absolute);
        println!(
            "{} vs {file}: {name}: worst error {w:.2e} x ({relative:e} relative + {absolute:e})",
            model.name()
        );
        assert!(
            w <= 1.0,
            "{} vs {file}: {name} off by {w} x ({relative:e} relative + {absolute:e})",
            model.name()
        );
    }
}

/// The built-in Panda carries the URDF's (Franka's) mass properties in its
/// modified-DH frames, which are the URDF's link frames: its dynamics are
/// Pinocchio's on the URDF (hand and fingers locked, folded into link 7).
#[test]
fn builtin_panda_equals_pinocchio_on_the_panda_urdf() {
    let model = armkit::robots::panda().unwrap();
    check_model_against_pinocchio(&model, "reference_dynamics_panda.json", SAME_ROBOT);
}

/// The built-in UR5 carries Universal Robots' published centres of mass,
/// which the URDF does not (it puts them on the joint origins): so the
/// built-in's DH frames are checked with the URDF's own bodies moved into
/// them, against Pinocchio on the URDF. The DH base is `base_link` turned by
/// 180 deg about z (and lowered by the tables' 0.3 mm difference in d1); the
/// bodies are carried over through each model's own FK.
#[test]
fn builtin_ur5_frames_with_the_urdf_bodies_equal_pinocchio_on_the_ur5_urdf() {
    use armkit::kinematics::{forward_kinematics, link_frames, Data};
    let file = "reference_dynamics_ur5.json";
    let urdf = reference_urdf_model(file);
    let builtin = armkit::robots::ur5().unwrap();
    let q0 = vec![0.0; 6];
    let mut urdf_data = Data::new(&urdf);
    forward_kinematics(&urdf, &mut urdf_data, &q0).unwrap();
    let mut dh_data = Data::new(&builtin);
    let mut dh_frames = vec![Pose::identity(); 6];
    link_frames(&builtin, &mut dh_data, &q0, &mut dh_frames).unwrap();
    let (convention, links) = builtin.dh_table().unwrap();
    // The DH table's d1 (RTB's 0.089459 m) is 0.3 mm above the URDF's
    // 0.089159 m: the bodies move with the chain above joint 1, so the DH base
    // sits that much lower in `base_link` (joint 1's own body slides along
    // its axis, which changes nothing).
    let dz = urdf_data.joint_frames()[1].translation.z - dh_data.joint_frames()[1].translation.z;
    let dh_base_in_urdf = Pose::trans_z(dz) * Pose::rot_z(std::f64::consts::PI);
    let links: Vec<_> = links
        .iter()
        .enumerate()
        .map(|(j, link)| {
            // The body in `base_link`, then in DH frame j (its link frame).
            let dh_frame = dh_frames[j];
            let body = urdf.chain_joints()[j]
                .inertia
                .unwrap()
                .transformed(&urdf_data.joint_frames()[j]);
            link.with_inertia(body.transformed(&(dh_base_in_urdf * dh_frame).inverse()))
        })
        .collect();
    let moved = Model::from_dh("ur5 with the URDF's bodies", convention, &links).unwrap();
    check_model_against_pinocchio(&moved, file, SAME_ROBOT);
    // The masses are the same in both sources; the centres of mass are not.
    let builtin_masses: Vec<f64> = builtin
        .chain_joints()
        .iter()
        .map(|j| j.inertia.unwrap().mass)
        .collect();
    let urdf_masses: Vec<f64> = urdf
        .chain_joints()
        .iter()
        .map(|j| j.inertia.unwrap().mass)
        .collect();
    assert_eq!(builtin_masses, urdf_masses);
    // The built-in's own bodies do run, and hold the arm up against gravity.
    let mut data = DynamicsData::new(&builtin).unwrap();
    let q = [0.3, -1.0, 1.2, -0.4, 1.1, 0.2];
    let g = gravity_torques(&builtin, &mut data, &q).unwrap().to_vec();
    assert!(g[1].abs() > 10.0, "shoulder holding torque {g:?}");
    let ddq = aba(&builtin, &mut data, &q, &[0.0; 6], &g).unwrap();
    assert!(ddq.iter().all(|a| a.abs() < 1e-9), "{ddq:?}");
}

#[test]
fn panda_urdf_equals_pinocchio() {
    check_against_pinocchio("reference_dynamics_panda.json");
}

#[test]
fn ur5_urdf_equals_pinocchio() {
    check_against_pinocchio("reference_dynamics_ur5.json");
}

/// A random serial arm: random joint kinds (one in four prismatic), axes,
/// origins and mass properties (positive definite inertias).
fn random_arm(seed: u64, dof: usize) -> Model {
    let mut r = rng(seed);
    let mut builder = ModelBuilder::new(format!("random{seed}"));
    for j in 0..dof {
        builder = builder.joint(random_link(&mut r, |r| {
            if r.gen_range(0..4) == 0 {
                JointSpec::prismatic(format!("p{j}"), -0.5, 0.5)
            } else {
                JointSpec::revolute(format!("r{j}"), -3.0, 3.0)
            }
        }));
    }
    builder.build().unwrap()
}

/// Every built-in with mass properties and no coupling, and random arms.
fn models_with_masses() -> Vec<Model> {
    let mut models: Vec<Model> = armkit::robots::names()
        .map(|name| armkit::robots::by_name(name).unwrap())
        .filter(|m| m.has_inertias() && m.coupling().is_none())
        .collect();
    let builtins: Vec<&str> = models.iter().map(|m| m.name()).collect();
    assert_eq!(
        builtins,
        ["ur5", "ur5-urdf", "panda", "space6r", "gantry9"],
        "built-ins with masses changed"
    );
    for seed in 0..4 {
        models.push(random_arm(seed, 3 + seed as usize * 2));
    }
    models
}

fn random_vector(r: &mut impl Rng, n: usize, scale: f64) -> Vec<f64> {
    (0..n).map(|_| r.gen_range(-scale..scale)).collect()
}

#[test]
fn mass_matrix_is_symmetric_positive_definite_with_rnea_columns() {
    let mut r = rng(18);
    for model in models_with_masses() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model).unwrap();
        let mut no_gravity = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::zeros())
            .unwrap();
        for _ in 0..10 {
            let q = random_configuration(&model, &mut r);
            let m = mass_matrix(&model, &mut data, &q).unwrap().clone();
            let scale = m.amax();
            assert!(
                (&m - m.transpose()).amax() <= 1e-14 * scale,
                "{}: not symmetric",
                model.name()
            );
            let eigen = m.clone().symmetric_eigenvalues();
            assert!(eigen.min() > 0.0, "{}: eigenvalues {eigen}", model.name());
            for j in 0..n {
                let mut e = vec![0.0; n];
                e[j] = 1.0;
                let column = rnea(&model, &mut no_gravity, &q, &vec![0.0; n], &e).unwrap();
                for i in 0..n {
                    assert!(
                        (column[i] - m[(i, j)]).abs() <= 1e-12 * scale,
                        "{}: M[{i}][{j}] = {} but RNEA gives {}",
                        model.name(),
                        m[(i, j)],
                        column[i]
                    );
                }
            }
            // The inverse.
            let inverse = mass_matrix_inverse(&model, &mut data, &q).unwrap().clone();
            let identity = &m * &inverse;
            assert!(
                (identity - DMatrix::identity(n, n)).amax() < 1e-9,
                "{}",
                model.name()
            );
        }
    }
}

/// A random arm whose joint `j` is prismatic where `prismatic(j)` says so.
fn arm_of_kinds(seed: u64, dof: usize, prismatic: impl Fn(usize) -> bool) -> Model {
    let mut r = rng(seed);
    let mut builder = ModelBuilder::new(format!("kinds{seed}"));
    for j in 0..dof {
        builder = builder.joint(random_link(&mut r, |_| {
            if prismatic(j) {
                JointSpec::prismatic(format!("p{j}"), -0.5, 0.5)
            } else {
                JointSpec::revolute(format!("r{j}"), -3.0, 3.0)
            }
        }));
    }
    builder.build().unwrap()
}

/// The CRBA treats the tip, the middle levels and the base row differently
/// (one pass from the tip, the base row from `S_0` seen in frame 1): chains of
/// one to four joints, all prismatic, all revolute and alternating, against
/// the RNEA's columns `M e_j = RNEA(q, 0, e_j)` without gravity, to 1e-12 of
/// the largest entry.
#[test]
fn mass_matrix_of_short_and_prismatic_chains_equals_rnea_columns() {
    let mut r = rng(1818);
    let mut models = Vec::new();
    for dof in 1..=4 {
        models.push(arm_of_kinds(100 + dof as u64, dof, |_| false));
        models.push(arm_of_kinds(200 + dof as u64, dof, |_| true));
        models.push(arm_of_kinds(300 + dof as u64, dof, |j| j % 2 == 0));
        models.push(arm_of_kinds(400 + dof as u64, dof, |j| j % 2 == 1));
    }
    models.push(arm_of_kinds(500, 8, |j| j % 3 == 1));
    for model in models {
        let n = model.dof();
        let mut data = DynamicsData::new(&model).unwrap();
        let mut no_gravity = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::zeros())
            .unwrap();
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let m = mass_matrix(&model, &mut data, &q).unwrap().clone();
            let scale = m.amax();
            assert!(scale > 0.0, "{}: zero mass matrix", model.name());
            for j in 0..n {
                let mut e = vec![0.0; n];
                e[j] = 1.0;
                let column = rnea(&model, &mut no_gravity, &q, &vec![0.0; n], &e).unwrap();
                for i in 0..n {
                    assert!(
                        (column[i] - m[(i, j)]).abs() <= 1e-12 * scale,
                        "{} ({n} joints): M[{i}][{j}] = {} but RNEA gives {}",
                        model.name(),
                        m[(i, j)],
                        column[i]
                    );
                }
            }
        }
    }
}

#[test]
fn aba_inverts_rnea_and_matches_m_inverse() {
    let mut r = rng(19);
    for model in models_with_masses() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model).unwrap();
        for _ in 0..10 {
            let q = random_configuration(&model, &mut r);
            let v = random_vector(&mut r, n, 2.0);
            let tau = random_vector(&mut r, n, 50.0);
            let ddq = aba(&model, &mut data, &q, &v, &tau).unwrap().to_vec();
            let back = rnea(&model, &mut data, &q, &v, &ddq).unwrap().to_vec();
            let scale = tau.iter().fold(1.0_f64, |m, t| m.max(t.abs()));
            for j in 0..n {
                assert!(
                    (back[j] - tau[j]).abs() < 1e-9 * scale,
                    "{}: RNEA(ABA(tau))[{j}] = {} vs {}",
                    model.name(),
                    back[j],
                    tau[j]
                );
            }
            // ddq = M^-1 (tau - nle) from the CRBA and the RNEA: a second algorithm.
            let nle = nonlinear_effects(&model, &mut data, &q, &v)
                .unwrap()
                .to_vec();
            let inverse = mass_matrix_inverse(&model, &mut data, &q).unwrap().clone();
            let rhs = DMatrix::from_fn(n, 1, |i, _| tau[i] - nle[i]);
            let expected = inverse * rhs;
            for j in 0..n {
                let tolerance = 1e-8 * expected.amax().max(1.0);
                assert!((ddq[j] - expected[j]).abs() < tolerance, "{}", model.name());
            }
            // The kinetic energy equals v' M v / 2.
            let m = mass_matrix(&model, &mut data, &q).unwrap().clone();
            let vv = DMatrix::from_column_slice(n, 1, &v);
            let quadratic = 0.5 * (vv.transpose() * m * &vv)[(0, 0)];
            let energy = kinetic_energy(&model, &mut data, &q, &v).unwrap();
            assert!(
                (energy - quadratic).abs() < 1e-12 * quadratic.max(1.0),
                "{}",
                model.name()
            );
        }
    }
}

#[test]
fn gravity_torques_are_the_gradient_of_the_potential_energy() {
    let mut r = rng(20);
    for model in models_with_masses() {
        let n = model.dof();
        let mut data = DynamicsData::new(&model)
            .unwrap()
            .with_gravity(Vector3::new(0.3, -1.2, -9.81))
            .unwrap();
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let g = gravity_torques(&model, &mut data, &q).unwrap().to_vec();
            let scale = g.iter().fold(1.0_f64, |m, t| m.max(t.abs()));
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
                    (derivative - g[j]).abs() < 1e-6 * scale,
                    "{}: dU/dq[{j}] = {derivative} but g = {}",
                    model.name(),
                    g[j]
                );
            }
            // g + C v is the RNEA with a = 0.
            let v = random_vector(&mut r, n, 1.0);
            let c = coriolis_torques(&model, &mut data, &q, &v)
                .unwrap()
                .to_vec();
            let nle = nonlinear_effects(&model, &mut data, &q, &v)
                .unwrap()
                .to_vec();
            for j in 0..n {
                assert!((nle[j] - g[j] - c[j]).abs() < 1e-10 * scale);
            }
        }
    }
}

/// Total energy `T + U` over a simulated motion with gravity on and no
/// torque (or gravity off): the largest relative drift.
fn energy_drift(model: &Model, integrator: Integrator, time_step: f64, duration: f64) -> f64 {
    let n = model.dof();
    let options = SimulationOptions {
        time_step,
        integrator,
        friction: None,
    };
    let mut sim = Simulator::new(model, options).unwrap();
    sim.data_mut().set_gravity(Vector3::zeros()).unwrap();
    let mut data = DynamicsData::new(model)
        .unwrap()
        .with_gravity(Vector3::zeros())
        .unwrap();
    let mut r = rng(21);
    let mut q = random_configuration(model, &mut r);
    let mut v = random_vector(&mut r, n, 1.0);
    let zero = vec![0.0; n];
    let initial = kinetic_energy(model, &mut data, &q, &v).unwrap();
    let mut worst: f64 = 0.0;
    let steps = (duration / time_step).round() as usize;
    for _ in 0..steps {
        sim.step(model, &mut q, &mut v, &zero).unwrap();
        let energy = kinetic_energy(model, &mut data, &q, &v).unwrap();
        worst = worst.max((energy - initial).abs() / initial);
    }
    worst
}

#[test]
fn free_motion_conserves_energy() {
    // Gravity off, tau = 0: the kinetic energy is constant. RK4 with a 1 ms
    // step over 1 s; the drift (reported in the README) is measured here.
    for model in models_with_masses() {
        let drift = energy_drift(&model, Integrator::RungeKutta4, 1e-3, 1.0);
        println!(
            "{}: RK4, h = 1 ms, 1 s: relative energy drift {drift:.2e}",
            model.name()
        );
        assert!(drift < 1e-7, "{}: RK4 drift {drift:e}", model.name());
        let drift = energy_drift(&model, Integrator::SemiImplicitEuler, 1e-3, 1.0);
        println!(
            "{}: semi-implicit Euler, h = 1 ms, 1 s: relative energy drift {drift:.2e}",
            model.name()
        );
        assert!(
            drift < 2e-2,
            "{}: semi-implicit Euler drift {drift:e}",
            model.name()
        );
    }
}

#[test]
fn friction_dissipates_energy() {
    let model = armkit::robots::by_name("space6r").unwrap();
    let friction = JointFriction {
        viscous: vec![0.5; 6],
        coulomb: vec![0.1; 6],
    };
    let options = SimulationOptions {
        friction: Some(friction),
        ..Default::default()
    };
    let mut sim = Simulator::new(&model, options).unwrap();
    sim.data_mut().set_gravity(Vector3::zeros()).unwrap();
    let mut data = DynamicsData::new(&model)
        .unwrap()
        .with_gravity(Vector3::zeros())
        .unwrap();
    let mut q = vec![0.2, -0.3, 0.5, 0.1, 0.4, -0.2];
    let mut v = vec![0.5, -0.4, 0.3, 0.6, -0.2, 0.8];
    let mut last = kinetic_energy(&model, &mut data, &q, &v).unwrap();
    for _ in 0..50 {
        for _ in 0..10 {
            sim.step(&model, &mut q, &mut v, &[0.0; 6]).unwrap();
        }
        let energy = kinetic_energy(&model, &mut data, &q, &v).unwrap();
        assert!(
            energy < last,
            "friction must take energy out: {energy} after {last}"
        );
        last = energy;
    }
}

#[test]
fn bad_input_is_a_clear_error() {
    let model = armkit::robots::by_name("space6r").unwrap();
    let mut data = DynamicsData::new(&model).unwrap();
    let q = [0.0; 6];
    let err = rnea(&model, &mut data, &q, &[0.0; 5], &q)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("joint_velocities") && err.contains("expected 6"),
        "{err}"
    );
    let mut v = [0.0; 6];
    v[2] = f64::NAN;
    let err = aba(&model, &mut data, &q, &v, &q).unwrap_err().to_string();
    assert!(err.contains("joint_velocities[2] is not finite"), "{err}");
    let err = aba(&model, &mut data, &q, &q, &[1.0; 7])
        .unwrap_err()
        .to_string();
    assert!(err.contains("joint_torques"), "{err}");
    let err = mass_matrix(&model, &mut data, &[f64::INFINITY; 6])
        .unwrap_err()
        .to_string();
    assert!(err.contains("joint_positions[0] is not finite"), "{err}");
    let err = data
        .set_gravity(Vector3::new(0.0, f64::NAN, 0.0))
        .unwrap_err()
        .to_string();
    assert!(err.contains("gravity[1]"), "{err}");
    // Workspace for another model.
    let ur5 = armkit::robots::by_name("gantry9").unwrap();
    let err = rnea(&ur5, &mut data, &[0.0; 9], &[0.0; 9], &[0.0; 9])
        .unwrap_err()
        .to_string();
    assert!(err.contains("another model"), "{err}");
    // No masses: the first link is named.
    let puma = armkit::robots::by_name("puma560").unwrap();
    let err = DynamicsData::new(&puma).unwrap_err().to_string();
    assert!(
        err.contains("link 0") && err.contains("no mass properties"),
        "{err}"
    );
    // A rigid model's workspace used with the coupled gantry (its chain
    // motion needs the coupling's buffers).
    let flex = armkit::robots::by_name("gantry9-flex").unwrap();
    let gantry = armkit::robots::by_name("gantry9").unwrap();
    let mut gantry_data = DynamicsData::new(&gantry).unwrap();
    let err = gravity_torques(&flex, &mut gantry_data, &flex.neutral_configuration())
        .unwrap_err()
        .to_string();
    assert!(err.contains("another model"), "{err}");
    // Options.
    let err = Simulator::new(
        &model,
        SimulationOptions {
            time_step: 0.0,
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("time_step"), "{err}");
    let friction = JointFriction {
        viscous: vec![0.1; 6],
        coulomb: vec![-1.0; 6],
    };
    let err = Simulator::new(
        &model,
        SimulationOptions {
            friction: Some(friction),
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("friction.coulomb") && err.contains(">= 0"),
        "{err}"
    );
}

#[test]
fn a_workspace_follows_the_model_it_is_used_with() {
    // Two arms of the same size with different joints and masses: a
    // workspace made for one gives the other's dynamics when used with it
    // (the mass properties are read again), and the first's after that.
    let (first, second) = (random_arm(11, 5), random_arm(12, 5));
    let mut r = rng(13);
    let q = random_vector(&mut r, 5, 1.0);
    let v = random_vector(&mut r, 5, 1.0);
    let a = random_vector(&mut r, 5, 1.0);
    let mut shared = DynamicsData::new(&first).unwrap();
    let own = |model: &Model| {
        let mut data = DynamicsData::new(model).unwrap();
        let tau = rnea(model, &mut data, &q, &v, &a).unwrap().to_vec();
        let m = mass_matrix(model, &mut data, &q).unwrap().clone();
        (tau, m)
    };
    let (tau_first, m_first) = own(&first);
    let (tau_second, m_second) = own(&second);
    assert!(
        violation(&tau_first, &tau_second, SAME_MODEL) > 1e-3,
        "the arms differ"
    );
    for (model, tau, m) in [
        (&second, &tau_second, &m_second),
        (&first, &tau_first, &m_first),
        (&second, &tau_second, &m_second),
    ] {
        let shared_tau = rnea(model, &mut shared, &q, &v, &a).unwrap().to_vec();
        assert_eq!(&shared_tau, tau, "{}", model.name());
        assert_eq!(mass_matrix(model, &mut shared, &q).unwrap(), m);
    }
}

#[test]
fn an_overflowing_result_is_an_error() {
    // A revolute joint, then a prismatic one at a finite position near
    // f64::MAX: the second body's moment about the first axis overflows.
    let mut r = rng(21);
    let model = ModelBuilder::new("far")
        .joint(random_link(&mut r, |_| {
            JointSpec::revolute("r0", -3.0, 3.0)
        }))
        .joint(random_link(&mut r, |_| {
            JointSpec::prismatic("p1", -1.0, 1.0)
        }))
        .build()
        .unwrap();
    let mut data = DynamicsData::new(&model).unwrap();
    let (q, v) = ([0.3, 1e308], [2.0, 0.0]);
    let err = rnea(&model, &mut data, &q, &v, &v).unwrap_err().to_string();
    assert!(err.contains("overflowed"), "{err}");
    let err = mass_matrix(&model, &mut data, &q).unwrap_err().to_string();
    assert!(err.contains("overflowed"), "{err}");
    assert!(aba(&model, &mut data, &q, &v, &v).is_err());
    // The same workspace still works at a sane configuration.
    assert!(rnea(&model, &mut data, &[0.3, 0.2], &v, &v).is_ok());
    // In body frames, a far translation along gantry9's first (prismatic)
    // joint is no overflow: the torques do not depend on it.
    let gantry = armkit::robots::by_name("gantry9").unwrap();
    let mut data = DynamicsData::new(&gantry).unwrap();
    let n = gantry.dof();
    let (v, a) = (vec![0.5; n], vec![-0.3; n]);
    let mut q = gantry.neutral_configuration();
    let near = rnea(&gantry, &mut data, &q, &v, &a).unwrap().to_vec();
    q[0] = 1e308;
    let far = rnea(&gantry, &mut data, &q, &v, &a).unwrap().to_vec();
    assert_eq!(near, far);
}

#[test]
fn one_link_pendulum_matches_closed_form() {
    // A point mass m at distance l on a horizontal revolute axis (y):
    // M = m l^2, g(q) = m g l sin(q) for q measured from hanging down.
    let (m, l, g) = (2.0, 0.7, 9.81);
    let model = ModelBuilder::new("pendulum")
        .joint(
            JointSpec::revolute("swing", -3.0, 3.0)
                .with_axis(Vector3::y())
                .with_inertia(LinkInertia::point_mass(m, Vector3::new(0.0, 0.0, -l))),
        )
        .build()
        .unwrap();
    let mut data = DynamicsData::new(&model).unwrap();
    let q = 0.4;
    let mm = mass_matrix(&model, &mut data, &[q]).unwrap()[(0, 0)];
    assert!((mm - m * l * l).abs() < 1e-14);
    let torque = gravity_torques(&model, &mut data, &[q]).unwrap()[0];
    assert!((torque - m * g * l * q.sin()).abs() < 1e-13, "{torque}");
    let ddq = aba(&model, &mut data, &[q], &[1.3], &[0.0]).unwrap()[0];
    assert!((ddq + g / l * q.sin()).abs() < 1e-13, "{ddq}");
}

#[test]
fn effort_limits_are_read_from_urdf_and_dh_files() {
    let panda = load(
        data_path("urdf/panda.urdf"),
        &ChainSelection::between("panda_link0", "panda_link8"),
    )
    .unwrap();
    let efforts: Vec<Option<f64>> = panda.joints().iter().map(|j| j.limits.effort).collect();
    let expected = [87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0].map(Some);
    assert_eq!(efforts, expected);
    let text = "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\n\
                qlim = [-1, 1]\ntlim = 35.5\nmass = 2.0\n";
    let model =
        armkit::description::parse_str(text, armkit::description::Format::Toml, "<t>").unwrap();
    assert_eq!(model.joints()[0].limits.effort, Some(35.5));
    let bad = text.replace("35.5", "-3");
    let err = armkit::description::parse_str(&bad, armkit::description::Format::Toml, "<t>")
        .unwrap_err()
        .to_string();
    assert!(err.contains("tlim") && err.contains("> 0"), "{err}");
}

#[test]
fn time_scaling_brings_torques_within_limits_tightly() {
    use armkit::trajectory::{rest_to_rest, ProfileShape};
    use armkit::trajectory::{
        scale_to_torque_limits, torque_profile, TorqueCheckOptions, TorqueStatus,
    };
    let panda = load(
        data_path("urdf/panda.urdf"),
        &ChainSelection::between("panda_link0", "panda_link8"),
    )
    .unwrap();
    let q0 = [0.0, -0.5, 0.0, -2.0, 0.0, 1.5, 0.0];
    let qf = [1.5, 0.5, -1.0, -1.0, 1.0, 2.5, 1.0];
    // 0.3 s is far too fast for the Panda's motors.
    let traj = rest_to_rest(ProfileShape::Quintic, &q0, &qf, 0.3, None).unwrap();
    let options = TorqueCheckOptions::default();
    let scaled = scale_to_torque_limits(&panda, &traj, &options).unwrap();
    assert_eq!(scaled.before.status, TorqueStatus::ExceedsLimits);
    assert_eq!(scaled.after.status, TorqueStatus::WithinLimits);
    assert!(scaled.factor > 1.5, "factor {}", scaled.factor);
    assert!((scaled.trajectory.duration() - 0.3 * scaled.factor).abs() < 1e-12);
    // Tight: some joint sits at its limit after scaling, and a slightly
    // faster version exceeds it.
    let worst = scaled
        .after
        .peaks
        .iter()
        .map(|p| p.ratio().unwrap())
        .fold(0.0, f64::max);
    assert!(worst > 1.0 - 1e-6 && worst <= 1.0, "{worst}");
    let faster = traj.time_scaled(scaled.factor * (1.0 - 1e-4)).unwrap();
    let report = torque_profile(&panda, &faster, &options).unwrap();
    assert_eq!(report.status, TorqueStatus::ExceedsLimits);
    // The scaling law: at the same point of the path tau_k = g + (tau - g) / k^2,
    // checked against the RNEA run on the scaled trajectory.
    let k2 = scaled.factor * scaled.factor;
    for (i, (before, after)) in scaled
        .before
        .torques
        .iter()
        .zip(&scaled.after.torques)
        .enumerate()
    {
        let g = &scaled.before.gravity[i];
        for j in 0..7 {
            let predicted = g[j] + (before[j] - g[j]) / k2;
            assert!((predicted - after[j]).abs() < 1e-9 * (1.0 + before[j].abs()));
        }
    }
    // Gravity alone above a limit: no timing helps, reported, unchanged.
    let tight = TorqueCheckOptions {
        limits: Some(vec![87.0, 1.0, 87.0, 87.0, 12.0, 12.0, 12.0]),
        ..Default::default()
    };
    let scaled = scale_to_torque_limits(&panda, &traj, &tight).unwrap();
    assert_eq!(scaled.after.status, TorqueStatus::GravityExceedsLimits);
    assert_eq!(scaled.factor, 1.0);
    // Bad options.
    let err = torque_profile(
        &panda,
        &traj,
        &TorqueCheckOptions {
            samples: 1,
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("samples"), "{err}");
    let err = torque_profile(
        &panda,
        &traj,
        &TorqueCheckOptions {
            limits: Some(vec![1.0; 3]),
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("torque_limits") && err.contains("expected 7"),
        "{err}"
    );
}

#[test]
fn dynamic_torques_at_rest_equal_the_static_holding_torques() {
    // Two independent implementations: redundancy's centre-of-mass Jacobians
    // plus J' w, and this module's RNEA plus J' w.
    use armkit::redundancy::Load;
    use armkit::redundancy::{EnergyTorques, TorqueModel};
    let mut r = rng(22);
    for model in models_with_masses() {
        let n = model.dof();
        let mut workspace = EnergyTorques::new(&model).unwrap();
        let load = Load::payload(50.0).with_gravity(Vector3::new(0.5, -0.2, -9.81));
        let zero = vec![0.0; n];
        for _ in 0..5 {
            let q = random_configuration(&model, &mut r);
            let (mut fixed, mut moving) = (vec![0.0; n], vec![0.0; n]);
            workspace
                .torques(
                    &model,
                    &q,
                    &zero,
                    &zero,
                    &load,
                    TorqueModel::Static,
                    &mut fixed,
                )
                .unwrap();
            workspace
                .torques(
                    &model,
                    &q,
                    &zero,
                    &zero,
                    &load,
                    TorqueModel::Dynamic,
                    &mut moving,
                )
                .unwrap();
            let scale = fixed.iter().fold(1.0_f64, |m, t| m.max(t.abs()));
            for j in 0..n {
                assert!(
                    (fixed[j] - moving[j]).abs() < 1e-10 * scale,
                    "{}: joint {j}",
                    model.name()
                );
            }
        }
    }
}

#[test]
fn seed001_energy_under_static_and_dynamic_torques() {
    // The four-way comparison of the redundancy study on gantry9: the static
    // measure equals the study's own, the dynamic one adds the inertia.
    use armkit::redundancy::{
        compare_distributions, ComparisonCase, DistributionOptions, JointWeights, Load,
        TorqueFloor, SEED000_PRIORITY_WEIGHTS,
    };
    use armkit::redundancy::{energy_along_motion, TorqueModel};
    use armkit::trajectory::{CartesianTrajectory, TimeLaw};
    let model = armkit::robots::by_name("gantry9").unwrap();
    let q0 = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    let mut data = armkit::Data::new(&model);
    let start = *armkit::forward_kinematics(&model, &mut data, &q0).unwrap();
    let goal = Pose::from_translation(Vector3::new(0.4, 0.3, -0.3)) * start;
    let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 4.0).unwrap();
    let load = Load::payload(50.0).with_seed001_gravity();
    let priorities = JointWeights::new(&SEED000_PRIORITY_WEIGHTS).unwrap();
    let cases =
        ComparisonCase::four_way(9, load, TorqueFloor::default(), priorities, &[0, 1]).unwrap();
    let results = compare_distributions(
        &model,
        &q0,
        &path,
        &load,
        &cases,
        &DistributionOptions::default(),
    )
    .unwrap();
    for result in &results {
        let samples = &result.report.samples;
        let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
        let q: Vec<Vec<f64>> = samples.iter().map(|s| s.q.clone()).collect();
        let q_dot: Vec<Vec<f64>> = samples.iter().map(|s| s.joint_rates.clone()).collect();
        let fixed =
            energy_along_motion(&model, &times, &q, &q_dot, &load, TorqueModel::Static).unwrap();
        let moving =
            energy_along_motion(&model, &times, &q, &q_dot, &load, TorqueModel::Dynamic).unwrap();
        println!(
            "{:15} F static {:.4e} W^2 s, dynamic {:.4e} W^2 s ({:+.2} %)",
            result.name,
            fixed.energy,
            moving.energy,
            100.0 * (moving.energy / fixed.energy - 1.0)
        );
        assert!((fixed.energy - result.summary.energy).abs() < 1e-9 * fixed.energy);
        assert!(moving.energy > 0.0 && (moving.energy - fixed.energy).abs() > 1e-12 * fixed.energy);
    }
    // Bad input.
    let err = energy_along_motion(
        &model,
        &[0.0],
        &[q0.to_vec()],
        &[vec![0.0; 9]],
        &load,
        TorqueModel::Dynamic,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("at least 2 samples"), "{err}");
    let err = energy_along_motion(
        &model,
        &[0.0, 0.0],
        &[q0.to_vec(), q0.to_vec()],
        &[vec![0.0; 9], vec![0.0; 9]],
        &load,
        TorqueModel::Dynamic,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("increase strictly"), "{err}");
}

/// Instruction-count probe (not a check): `ARMKIT_PROBE_CALLS=N` calls of
/// each of RNEA, CRBA and ABA on the UR5 URDF. Under callgrind, the
/// difference between two runs with different N, divided by the difference
/// in N, is the instructions per call, free of set-up:
/// `ARMKIT_PROBE_CALLS=20000 valgrind --tool=callgrind --callgrind-out-file=/tmp/cg.20k <test binary> --ignored --exact instruction_count_probe`
/// (then 10000), and `callgrind_annotate` each file's total.
/// `ARMKIT_PROBE_ONLY=rnea|crba|aba` runs one algorithm.
#[test]
#[ignore]
fn instruction_count_probe() {
    let calls: usize = std::env::var("ARMKIT_PROBE_CALLS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let only = std::env::var("ARMKIT_PROBE_ONLY").unwrap_or_default();
    let model = load(
        data_path("urdf/ur5.urdf"),
        &ChainSelection::between("base_link", "tool0"),
    )
    .unwrap();
    let mut data = DynamicsData::new(&model).unwrap();
    let q = [0.1, -0.4, 0.8, 0.2, 0.5, -0.3];
    let v = [0.2, 0.1, -0.3, 0.4, 0.0, 0.1];
    let a = [1.0, -0.5, 0.3, 0.0, 0.2, 0.1];
    let mut sum = 0.0;
    for i in 0..calls {
        let mut q = q;
        q[0] += i as f64 * 1e-9;
        let q = std::hint::black_box(q);
        if only.is_empty() || only == "rnea" {
            sum += rnea(&model, &mut data, &q, &v, &a).unwrap()[0];
        }
        if only.is_empty() || only == "crba" {
            sum += mass_matrix(&model, &mut data, &q).unwrap()[(0, 0)];
        }
        if only.is_empty() || only == "aba" {
            sum += aba(&model, &mut data, &q, &v, &a).unwrap()[0];
        }
    }
    println!("{sum}");
}
