//! Helpers shared by the integration tests.
#![allow(dead_code)]

use armkit::kinematics::{forward_kinematics, Data, JacobianFrame};
use armkit::math::{Matrix6xX, Pose, Vector3};
use armkit::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Path of a file in the repository's `tests/data`.
pub fn data_path(name: &str) -> String {
    format!("{}/../../tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// One reference sample: joint positions, tip pose, Jacobian.
pub struct Sample {
    pub q: Vec<f64>,
    pub pose: [[f64; 4]; 4],
    pub jacobian: Vec<Vec<f64>>,
}

/// The samples of a reference file in `tests/data`.
pub fn reference_samples(file: &str) -> Vec<Sample> {
    let text = std::fs::read_to_string(data_path(file)).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| Sample {
            q: serde_json::from_value(s["q"].clone()).unwrap(),
            pose: serde_json::from_value(s["pose"].clone()).unwrap(),
            jacobian: serde_json::from_value(s["jacobian"].clone()).unwrap(),
        })
        .collect()
}

/// Largest entry-wise difference between a pose and reference rows.
pub fn pose_error(pose: &Pose, rows: &[[f64; 4]; 4]) -> f64 {
    let m = pose.to_matrix4();
    (0..4)
        .flat_map(|r| (0..4).map(move |c| (r, c)))
        .map(|(r, c)| (m[(r, c)] - rows[r][c]).abs())
        .fold(0.0, f64::max)
}

/// Largest entry-wise difference between a Jacobian and reference rows.
pub fn jacobian_error(j: &Matrix6xX<f64>, rows: &[Vec<f64>]) -> f64 {
    let mut worst: f64 = 0.0;
    for (r, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), j.ncols());
        for (c, v) in row.iter().enumerate() {
            worst = worst.max((j[(r, c)] - v).abs());
        }
    }
    worst
}

/// A seeded RNG for reproducible randomized tests.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A configuration drawn uniformly within the limits (unbounded joints in [-pi, pi]).
pub fn random_configuration(model: &Model, rng: &mut impl Rng) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| {
            let (lo, hi) = if j.limits.is_bounded() {
                (j.limits.lower, j.limits.upper)
            } else {
                (-std::f64::consts::PI, std::f64::consts::PI)
            };
            rng.gen_range(lo..=hi)
        })
        .collect()
}

/// Central finite-difference Jacobian of the end-effector pose (world frame):
/// linear rows from the position, angular rows from the rotation's log.
pub fn finite_difference_jacobian(model: &Model, q: &[f64], step: f64) -> Matrix6xX<f64> {
    finite_difference_jacobian_in(model, q, step, JacobianFrame::World)
}

/// Central finite-difference Jacobian of the end-effector pose in the axes
/// of `frame`: the velocity of the end-effector origin (`R' dp` in tool
/// axes) and the angular velocity (from `R+ R-'` in world axes, `R-' R+`
/// in tool axes, each `exp(2h [w]) + O(h^3)`).
pub fn finite_difference_jacobian_in(
    model: &Model,
    q: &[f64],
    step: f64,
    frame: JacobianFrame,
) -> Matrix6xX<f64> {
    let mut data = Data::new(model);
    let rotation = forward_kinematics(model, &mut data, q).unwrap().rotation;
    let mut jac = Matrix6xX::zeros(model.dof());
    for j in 0..model.dof() {
        let mut plus = q.to_vec();
        let mut minus = q.to_vec();
        plus[j] += step;
        minus[j] -= step;
        let tp = *forward_kinematics(model, &mut data, &plus).unwrap();
        let tm = *forward_kinematics(model, &mut data, &minus).unwrap();
        let mut linear = (tp.translation - tm.translation) / (2.0 * step);
        // For so small an angle the skew part of the relative rotation (sin
        // of the angle times the axis) is the angle times the axis to 1e-12
        // relative, where acos of the trace would lose half the digits.
        let relative = match frame {
            JacobianFrame::World => tp.rotation * tm.rotation.transpose(),
            JacobianFrame::EndEffector => {
                linear = rotation.transpose() * linear;
                tm.rotation.transpose() * tp.rotation
            }
        };
        let skew = (relative - relative.transpose()) * 0.5;
        let angular = Vector3::new(skew[(2, 1)], skew[(0, 2)], skew[(1, 0)]) / (2.0 * step);
        jac.fixed_view_mut::<3, 1>(0, j).copy_from(&linear);
        jac.fixed_view_mut::<3, 1>(3, j).copy_from(&angular);
    }
    jac
}

/// A random link for the dynamics tests: `kind(rng)` picks the joint (and
/// may draw from `rng`); its axis, origin (within 0.4 m, any rotation) and
/// mass properties (0.5-5 kg, centre of mass within 0.2 m, a positive
/// definite inertia with principal moments 0.01-0.1 kg m^2) are random.
pub fn random_link(
    r: &mut ChaCha8Rng,
    kind: impl FnOnce(&mut ChaCha8Rng) -> armkit::model::JointSpec,
) -> armkit::model::JointSpec {
    use armkit::math::{Matrix3, Rotation3};
    let mut unit = || {
        Vector3::new(
            r.gen_range(-1.0..1.0),
            r.gen_range(-1.0..1.0),
            r.gen_range(-1.0..1.0),
        )
    };
    let axis = unit();
    let offset = unit() * 0.4;
    let com = unit() * 0.2;
    let rotation = Rotation3::from_euler_angles(
        r.gen_range(-3.0..3.0),
        r.gen_range(-1.5..1.5),
        r.gen_range(-3.0..3.0),
    );
    let principal = Vector3::new(
        r.gen_range(0.01..0.1),
        r.gen_range(0.01..0.1),
        r.gen_range(0.01..0.1),
    );
    let inertia = rotation * Matrix3::from_diagonal(&principal) * rotation.transpose();
    let spec = kind(r);
    spec.with_axis(axis)
        .with_origin(Pose::new(rotation.into_inner(), offset))
        .with_inertia(armkit::model::LinkInertia {
            mass: r.gen_range(0.5..5.0),
            com,
            inertia,
        })
}

/// The largest absolute difference between two equally long slices.
pub fn max_abs_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
