//! Analytic IK by subproblem decomposition: on random poses (FK of random
//! configurations within the limits) every exact solution reproduces the
//! pose to 1e-10 by forward kinematics, and the generating configuration is
//! among the solutions (angles modulo 2 pi) on every pose; on built-in
//! robots, URDF models and random arms of each class.

use crate::common;

use armkit::ik::analytic::{
    AnalyticOptions, AnalyticSolver, ArmClass, ChainEnd, Parameter, Positioning,
};
use armkit::ik::closed_form::Fit;
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Matrix3, Pose, Rotation3, Vector3};
use armkit::model::{JointSpec, ModelBuilder};
use armkit::Model;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Poses per robot in the normal suite (10x fewer than the ignored test).
const POSES: usize = 1000;

fn urdf(file: &str, tip: &str) -> Model {
    let selection = armkit::urdf::ChainSelection::between("base_link", tip);
    armkit::urdf::load(common::data_path(file), &selection).unwrap()
}

/// The iiwa14 of tests/data/urdf with its 0.436 mm shoulder and elbow
/// offsets (x of joints 2 and 4) removed: an exact spherical shoulder,
/// elbow and wrist (the URDF as shipped is not, see
/// `the_iiwa14_urdf_is_not_exactly_srs`).
fn ideal_iiwa14() -> Model {
    let text = std::fs::read_to_string(common::data_path("urdf/iiwa14.urdf"))
        .unwrap()
        .replace("xyz=\"-0.00043624 0 0.36\"", "xyz=\"0 0 0.36\"")
        .replace("xyz=\"0.00043624 0 0.42\"", "xyz=\"0 0 0.42\"");
    let selection = armkit::urdf::ChainSelection::between("base_link", "tool0");
    armkit::urdf::parse_str(&text, "iiwa14-ideal", &selection).unwrap()
}

/// What one robot's check found.
struct Tally {
    poses: usize,
    recovered: usize,
    worst_error: f64,
    solutions: usize,
}

/// Solves `poses` random poses; asserts every exact solution's FK error is
/// within 1e-10 and counts the poses whose generating configuration is
/// among the solutions. `parameter` maps a configuration to the redundancy
/// parameter of a 7-DOF arm.
fn check(
    model: &Model,
    solver: &mut AnalyticSolver,
    poses: usize,
    seed: u64,
    parameter: &dyn Fn(&AnalyticSolver, &[f64]) -> Option<f64>,
) -> Tally {
    let mut rng = common::rng(seed);
    let mut data = Data::new(model);
    let mut tally = Tally {
        poses,
        recovered: 0,
        worst_error: 0.0,
        solutions: 0,
    };
    for _ in 0..poses {
        let mut q = common::random_configuration(model, &mut rng);
        if let Some(Parameter::FixedJoint { joint, value }) = solver.parameter() {
            q[joint] = value;
        }
        let target = *forward_kinematics(model, &mut data, &q).unwrap();
        if let Some(value) = parameter(solver, &q) {
            solver.set_parameter_value(value).unwrap();
        }
        let start = model.neutral_configuration();
        let solutions = solver.solve(&target, &start).unwrap().to_vec();
        tally.solutions += solutions.len();
        for s in &solutions {
            model.check_limits(s.q()).unwrap();
            let pose = forward_kinematics(model, &mut data, s.q()).unwrap();
            let e = armkit::ik::pose_error(&target, pose);
            let error = e.norm();
            if s.fit == Fit::Exact {
                assert!(error <= 2e-10, "{}: {error:e} at {:?}", model.name(), s.q());
                tally.worst_error = tally.worst_error.max(error);
            }
        }
        let found = solutions.iter().any(|s| {
            s.fit == Fit::Exact
                && s.q().iter().zip(&q).all(|(a, b)| {
                    let d = a - b;
                    (d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round()).abs() < 1e-6
                })
        });
        tally.recovered += usize::from(found);
    }
    tally
}

fn no_parameter(_: &AnalyticSolver, _: &[f64]) -> Option<f64> {
    None
}

fn elbow_angle(solver: &AnalyticSolver, q: &[f64]) -> Option<f64> {
    Some(solver.elbow_angle(q).unwrap())
}

fn assert_all_recovered(name: &str, tally: &Tally) {
    assert_eq!(
        tally.recovered, tally.poses,
        "{name}: generating configuration found on {}/{} poses",
        tally.recovered, tally.poses
    );
    assert!(tally.solutions >= tally.poses, "{name}: too few solutions");
}

fn solver(model: &Model) -> AnalyticSolver {
    AnalyticSolver::new(model, AnalyticOptions::default()).unwrap()
}

#[test]
fn built_in_and_urdf_arms_are_classified() {
    let cases = [
        (
            armkit::robots::by_name("puma560").unwrap(),
            "spherical_wrist",
        ),
        (armkit::robots::by_name("ur5").unwrap(), "three_parallel"),
        (urdf("urdf/ur5.urdf", "tool0"), "three_parallel"),
        (
            armkit::robots::by_name("stanford").unwrap(),
            "spherical_wrist_prismatic_3",
        ),
        (
            armkit::robots::by_name("space6r").unwrap(),
            "spherical_wrist",
        ),
    ];
    for (model, class) in cases {
        let s = solver(&model);
        assert!(
            s.class().as_str().starts_with(class),
            "{}: {}",
            model.name(),
            s.class()
        );
    }
    let iiwa = ideal_iiwa14();
    let s = AnalyticSolver::with_parameter(
        &iiwa,
        AnalyticOptions::default(),
        Parameter::ElbowAngle(0.0),
    )
    .unwrap();
    assert_eq!(s.class(), ArmClass::SphericalShoulderElbowWrist);
}

#[test]
fn puma560_every_pose() {
    let model = armkit::robots::by_name("puma560").unwrap();
    let tally = check(&model, &mut solver(&model), POSES, 1, &no_parameter);
    assert_all_recovered("puma560", &tally);
}

#[test]
fn ur5_every_pose() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let tally = check(&model, &mut solver(&model), POSES, 2, &no_parameter);
    assert_all_recovered("ur5", &tally);
}

#[test]
fn ur5_urdf_every_pose() {
    let model = urdf("urdf/ur5.urdf", "tool0");
    let tally = check(&model, &mut solver(&model), POSES, 3, &no_parameter);
    assert_all_recovered("ur5 urdf", &tally);
}

#[test]
fn stanford_every_pose() {
    let model = armkit::robots::by_name("stanford").unwrap();
    let tally = check(&model, &mut solver(&model), POSES, 4, &no_parameter);
    assert_all_recovered("stanford", &tally);
}

#[test]
fn iiwa14_elbow_angle_every_pose() {
    let model = ideal_iiwa14();
    let mut s = AnalyticSolver::with_parameter(
        &model,
        AnalyticOptions::default(),
        Parameter::ElbowAngle(0.0),
    )
    .unwrap();
    let tally = check(&model, &mut s, POSES, 5, &elbow_angle);
    assert_all_recovered("iiwa14", &tally);
}

#[test]
fn iiwa14_fixed_elbow_joint_every_pose() {
    let model = ideal_iiwa14();
    let parameter = Parameter::FixedJoint {
        joint: 2,
        value: 0.4,
    };
    let mut s =
        AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), parameter).unwrap();
    assert!(matches!(
        s.class(),
        ArmClass::SphericalWrist {
            end: ChainEnd::Tip,
            positioning: Positioning::IntersectingFirstSecond
        }
    ));
    let tally = check(&model, &mut s, POSES, 6, &no_parameter);
    assert_all_recovered("iiwa14 q3 fixed", &tally);
}

#[test]
fn the_iiwa14_urdf_is_not_exactly_srs() {
    // Joints 2 and 4 sit 0.436 mm off the axis of joints 1, 3, 5, 7: the
    // shoulder axes do not meet, so neither the elbow-angle solver nor the
    // fixed-elbow-joint route applies; the error says which class it is.
    let model = urdf("urdf/iiwa14.urdf", "tool0");
    let error = AnalyticSolver::with_parameter(
        &model,
        AnalyticOptions::default(),
        Parameter::ElbowAngle(0.0),
    )
    .unwrap_err()
    .to_string();
    assert!(error.contains("no analytic solver"), "{error}");
}

/// Asserts the generating configuration was found on at least 99.9 % of poses.
fn assert_search_recovered(name: &str, tally: &Tally) {
    assert!(
        tally.recovered as f64 >= 0.999 * tally.poses as f64,
        "{name}: generating configuration found on {}/{} poses",
        tally.recovered,
        tally.poses
    );
}

#[test]
fn iiwa14_urdf_with_the_elbow_joint_held_general_axes() {
    let model = urdf("urdf/iiwa14.urdf", "tool0");
    let parameter = Parameter::FixedJoint {
        joint: 2,
        value: 0.4,
    };
    let mut s =
        AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), parameter).unwrap();
    assert_eq!(s.class().as_str(), "spherical_wrist_general_axes");
    let tally = check(&model, &mut s, POSES, 8, &no_parameter);
    assert_search_recovered("iiwa14 urdf q3 held", &tally);
}

#[test]
fn panda_with_the_last_joint_fixed_every_pose() {
    let model = armkit::robots::by_name("panda").unwrap();
    let parameter = Parameter::FixedJoint {
        joint: 6,
        value: 0.3,
    };
    let mut s =
        AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), parameter).unwrap();
    assert!(matches!(
        s.class(),
        ArmClass::SphericalWrist {
            end: ChainEnd::Base,
            ..
        }
    ));
    let tally = check(&model, &mut s, POSES, 7, &no_parameter);
    assert_all_recovered("panda q7 fixed", &tally);
}

/// The first or last joint held at several values, changed by
/// `set_parameter_value` on one solver (the target is moved, the plan kept).
#[test]
fn an_end_joint_held_at_changing_values() {
    let cases = [
        (armkit::robots::by_name("panda").unwrap(), 6),
        (ideal_iiwa14(), 0),
        (ideal_iiwa14(), 6),
    ];
    for (model, joint) in cases {
        let parameter = Parameter::FixedJoint { joint, value: 0.0 };
        let mut s =
            AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), parameter).unwrap();
        let class = s.class();
        for (k, value) in [-2.5, -0.4, 0.9, 2.7].into_iter().enumerate() {
            s.set_parameter_value(value).unwrap();
            assert_eq!(s.class(), class);
            let tally = check(&model, &mut s, POSES / 4, 40 + k as u64, &no_parameter);
            let name = format!("{} joint {} held at {value}", model.name(), joint + 1);
            assert_all_recovered(&name, &tally);
        }
    }
}

// ---------------------------------------------------------------- random arms

fn unit(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        if v.norm() > 0.2 && v.norm() < 1.0 {
            return v.normalize();
        }
    }
}

fn point(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-0.5..0.5),
        rng.gen_range(-0.5..0.5),
        rng.gen_range(-0.5..0.5),
    )
}

fn sign(rng: &mut ChaCha8Rng) -> f64 {
    if rng.gen_bool(0.5) {
        1.0
    } else {
        -1.0
    }
}

/// A model from lines at zero configuration (point, unit axis, sliding?) and
/// a home pose; revolute joints in [-pi, pi], prismatic ones in [0, 1] m.
fn model_from_lines(name: &str, lines: &[(Vector3<f64>, Vector3<f64>, bool)], home: Pose) -> Model {
    use std::f64::consts::PI;
    let mut builder = ModelBuilder::new(name);
    let mut previous = Vector3::zeros();
    for (i, (c, h, slides)) in lines.iter().enumerate() {
        let spec = if *slides {
            JointSpec::prismatic(format!("q{}", i + 1), 0.0, 1.0)
        } else {
            JointSpec::revolute(format!("q{}", i + 1), -PI, PI)
        };
        builder = builder.joint(
            spec.with_origin(Pose::from_translation(c - previous))
                .with_axis(*h),
        );
        previous = *c;
    }
    builder
        .fixed(Pose::new(home.rotation, home.translation - previous))
        .build()
        .unwrap()
}

fn random_home(rng: &mut ChaCha8Rng) -> Pose {
    let r = Rotation3::from_euler_angles(
        rng.gen_range(-3.0..3.0),
        rng.gen_range(-1.5..1.5),
        rng.gen_range(-3.0..3.0),
    );
    Pose::new(r.into_inner(), point(rng) * 2.0)
}

type Lines = Vec<(Vector3<f64>, Vector3<f64>, bool)>;

/// Lines of a random spherical-wrist arm (wrist at the tip).
fn spherical_wrist_lines(rng: &mut ChaCha8Rng, positioning: Positioning) -> Lines {
    let w = point(rng) + Vector3::new(0.0, 0.0, 1.0);
    let mut lines: Lines = (0..3).map(|_| (point(rng), unit(rng), false)).collect();
    match positioning {
        Positioning::ParallelSecondThird => lines[2].1 = lines[1].1 * sign(rng),
        Positioning::ParallelFirstSecond => lines[1].1 = lines[0].1 * sign(rng),
        Positioning::IntersectingFirstSecond => lines[1].0 = lines[0].0,
        Positioning::IntersectingSecondThird => lines[2].0 = lines[1].0,
        Positioning::PrismaticThird => {
            lines[1].0 = lines[0].0;
            lines[2].2 = true;
        }
        Positioning::General => {}
    }
    for _ in 0..3 {
        lines.push((w, unit(rng), false));
    }
    lines
}

/// Lines of a random arm with axes 2-3-4 parallel and 5-6 intersecting.
fn three_parallel_lines(rng: &mut ChaCha8Rng) -> Lines {
    let k = unit(rng);
    let meet = point(rng);
    vec![
        (point(rng), unit(rng), false),
        (point(rng), k * sign(rng), false),
        (point(rng) * 2.0, k * sign(rng), false),
        (point(rng) * 2.0, k * sign(rng), false),
        (meet, unit(rng), false),
        (meet, unit(rng), false),
    ]
}

/// Lines of a random arm with axes 2-3-4 parallel and axes 1, 5, 6
/// general: random points, so no consecutive pair intersects.
fn three_parallel_offset_lines(rng: &mut ChaCha8Rng) -> Lines {
    let k = unit(rng);
    vec![
        (point(rng), unit(rng), false),
        (point(rng), k * sign(rng), false),
        (point(rng) * 2.0, k * sign(rng), false),
        (point(rng) * 2.0, k * sign(rng), false),
        (point(rng), unit(rng), false),
        (point(rng), unit(rng), false),
    ]
}

fn random_arm_check(
    seed: u64,
    lines: impl Fn(&mut ChaCha8Rng) -> Lines,
    reverse: bool,
    expected: &str,
) {
    let mut rng = common::rng(seed);
    for arm in 0..20 {
        let mut lines = lines(&mut rng);
        if reverse {
            lines.reverse();
        }
        let model = model_from_lines(&format!("random{arm}"), &lines, random_home(&mut rng));
        let mut s = solver(&model);
        assert!(
            s.class().as_str().starts_with(expected),
            "arm {arm}: {} (expected {expected})",
            s.class()
        );
        let tally = check(&model, &mut s, POSES / 10, seed * 100 + arm, &no_parameter);
        assert_all_recovered(&format!("random arm {arm} ({})", s.class()), &tally);
    }
}

#[test]
fn random_spherical_wrist_arms() {
    let classes = [
        (
            Positioning::ParallelSecondThird,
            "spherical_wrist_parallel_2_3",
            "spherical_base_parallel_5_4",
        ),
        (
            Positioning::ParallelFirstSecond,
            "spherical_wrist_parallel_1_2",
            "spherical_base_parallel_6_5",
        ),
        (
            Positioning::IntersectingFirstSecond,
            "spherical_wrist_intersecting_1_2",
            "spherical_base_intersecting_6_5",
        ),
        (
            Positioning::IntersectingSecondThird,
            "spherical_wrist_intersecting_2_3",
            "spherical_base_intersecting_5_4",
        ),
        (
            Positioning::PrismaticThird,
            "spherical_wrist_prismatic_3",
            "spherical_base_prismatic_4",
        ),
    ];
    for (i, (positioning, tip, base)) in classes.into_iter().enumerate() {
        let seed = 10 + i as u64;
        random_arm_check(
            seed,
            |rng| spherical_wrist_lines(rng, positioning),
            false,
            tip,
        );
        random_arm_check(
            seed + 50,
            |rng| spherical_wrist_lines(rng, positioning),
            true,
            base,
        );
    }
}

#[test]
fn random_general_position_spherical_wrist_arms() {
    // No special pair among the first three axes: the 1-D search class.
    let lines = |rng: &mut ChaCha8Rng| {
        let w = point(rng) + Vector3::new(0.0, 0.0, 1.0);
        let mut lines: Lines = (0..3).map(|_| (point(rng), unit(rng), false)).collect();
        for _ in 0..3 {
            lines.push((w, unit(rng), false));
        }
        lines
    };
    for (seed, reverse, class) in [
        (60, false, "spherical_wrist_general_axes"),
        (61, true, "spherical_base_general_axes"),
    ] {
        let mut rng = common::rng(seed);
        let mut tally = Tally {
            poses: 0,
            recovered: 0,
            worst_error: 0.0,
            solutions: 0,
        };
        for arm in 0..20 {
            let mut lines = lines(&mut rng);
            if reverse {
                lines.reverse();
            }
            let model = model_from_lines(&format!("general{arm}"), &lines, random_home(&mut rng));
            let mut s = solver(&model);
            assert_eq!(s.class().as_str(), class);
            let one = check(&model, &mut s, POSES / 10, seed * 100 + arm, &no_parameter);
            tally.poses += one.poses;
            tally.recovered += one.recovered;
        }
        assert_search_recovered(class, &tally);
    }
}

#[test]
fn random_three_parallel_arms() {
    random_arm_check(20, three_parallel_lines, false, "three_parallel_2_3_4");
    random_arm_check(21, three_parallel_lines, true, "three_parallel_3_4_5");
}

#[test]
fn random_three_parallel_arms_without_an_intersecting_pair() {
    for (seed, reverse, class) in [
        (22, false, "three_parallel_2_3_4"),
        (23, true, "three_parallel_3_4_5"),
    ] {
        // The class names are prefixes of the UR classes': check them whole.
        let mut rng = common::rng(seed);
        let lines = three_parallel_offset_lines(&mut rng);
        let model = model_from_lines("offset", &lines, random_home(&mut rng));
        let model = if reverse {
            let mut reversed = lines.clone();
            reversed.reverse();
            model_from_lines("offset", &reversed, random_home(&mut rng))
        } else {
            model
        };
        assert_eq!(solver(&model).class().as_str(), class);
        random_arm_check(seed, three_parallel_offset_lines, reverse, class);
    }
}

/// The UR5's lines with axis 6 moved `offset` m along the common normal of
/// axes 5 and 6, so that they no longer intersect.
fn ur5_with_an_offset_wrist(offset: f64) -> Model {
    let ur5 = armkit::robots::by_name("ur5").unwrap();
    let structure = armkit::ik::analytic::structure::ArmStructure::of_model(&ur5).unwrap();
    let mut lines: Lines = (0..6)
        .map(|i| (structure.points[i], structure.axes[i], false))
        .collect();
    let normal = structure.axes[4].cross(&structure.axes[5]).normalize();
    lines[5].0 += normal * offset;
    model_from_lines("ur5-offset-wrist", &lines, structure.home)
}

#[test]
fn a_ur5_with_an_offset_wrist_is_the_three_parallel_class_without_a_pair() {
    let ur5 = armkit::robots::by_name("ur5").unwrap();
    assert_eq!(
        solver(&ur5).class().as_str(),
        "three_parallel_2_3_4_intersecting_5_6"
    );
    let model = ur5_with_an_offset_wrist(0.04);
    let mut s = solver(&model);
    assert_eq!(
        s.class(),
        ArmClass::ThreeParallelOffset { end: ChainEnd::Tip }
    );
    let tally = check(&model, &mut s, POSES, 24, &no_parameter);
    assert_all_recovered("ur5 offset wrist", &tally);
    // Up to 8 solutions: more than 4 on average.
    assert!(tally.solutions > 4 * POSES, "{} solutions", tally.solutions);
    // Out of reach: least-squares answers, said so.
    let far = Pose::from_translation(Vector3::new(100.0, 0.0, 0.5));
    let solutions = s.solve(&far, &model.neutral_configuration()).unwrap();
    assert!(!solutions.is_empty());
    assert!(solutions
        .iter()
        .all(|s| s.fit == Fit::Approximate && s.position_error > 90.0));
    // Bad input takes the same paths as every class.
    let start = model.neutral_configuration();
    let mut skewed = Pose::identity();
    skewed.rotation[(0, 1)] = 0.3;
    let error = s.solve(&skewed, &start).unwrap_err().to_string();
    assert!(error.contains("not a proper rotation"), "{error}");
    let nan = Pose::from_translation(Vector3::new(0.3, f64::NAN, 0.0));
    let error = s.solve(&nan, &start).unwrap_err().to_string();
    assert!(error.contains("non-finite"), "{error}");
}

/// The heavy version: 10 000 poses of the offset-wrist UR5 and 200 random
/// arms of 100 poses at each end.
#[test]
#[ignore]
fn three_parallel_without_a_pair_heavy() {
    let model = ur5_with_an_offset_wrist(0.04);
    let mut s = solver(&model);
    let tally = check(&model, &mut s, 10 * POSES, 25, &no_parameter);
    assert_all_recovered("ur5 offset wrist", &tally);
    for (seed, reverse) in [(26, false), (27, true)] {
        let mut rng = common::rng(seed);
        for arm in 0..200 {
            let mut lines = three_parallel_offset_lines(&mut rng);
            if reverse {
                lines.reverse();
            }
            let model = model_from_lines("offset", &lines, random_home(&mut rng));
            let mut s = solver(&model);
            let tally = check(&model, &mut s, POSES / 10, seed * 1000 + arm, &no_parameter);
            assert_all_recovered(&format!("random arm {arm} ({})", s.class()), &tally);
        }
    }
}

#[test]
fn random_shoulder_elbow_wrist_arms() {
    let mut rng = common::rng(30);
    for arm in 0..20 {
        let (s, e, w) = (
            point(&mut rng),
            point(&mut rng) + Vector3::z(),
            point(&mut rng) + Vector3::z() * 2.0,
        );
        let lines: Lines = vec![
            (s, unit(&mut rng), false),
            (s, unit(&mut rng), false),
            (s, (e - s).normalize(), false),
            (e, unit(&mut rng), false),
            (e, (w - e).normalize(), false),
            (w, unit(&mut rng), false),
            (w, unit(&mut rng), false),
        ];
        let model = model_from_lines(&format!("srs{arm}"), &lines, random_home(&mut rng));
        let mut solver = AnalyticSolver::with_parameter(
            &model,
            AnalyticOptions::default(),
            Parameter::ElbowAngle(0.0),
        )
        .unwrap();
        assert_eq!(solver.class(), ArmClass::SphericalShoulderElbowWrist);
        let tally = check(&model, &mut solver, POSES / 10, 3000 + arm, &elbow_angle);
        assert_all_recovered(&format!("random srs arm {arm}"), &tally);
    }
}

#[test]
fn a_spherical_wrist_arm_with_a_shoulder_offset() {
    // KUKA KR-type: vertical axis 1, shoulder 2 offset 0.35 m forward and
    // 0.1 m sideways from it (skew to axis 1), elbow 3 parallel to 2, wrist.
    let lines: Lines = vec![
        (Vector3::zeros(), Vector3::z(), false),
        (Vector3::new(0.35, 0.1, 0.675), Vector3::y(), false),
        (Vector3::new(0.35, 0.1, 1.825), Vector3::y(), false),
        (Vector3::new(0.35, 0.0, 1.86), Vector3::x(), false),
        (Vector3::new(1.55, 0.0, 1.86), Vector3::y(), false),
        (Vector3::new(1.55, 0.0, 1.86), Vector3::x(), false),
    ];
    let home = Pose::new(Matrix3::identity(), Vector3::new(1.765, 0.0, 1.86));
    let model = model_from_lines("offset-wrist", &lines, home);
    let mut s = solver(&model);
    assert_eq!(s.class().as_str(), "spherical_wrist_parallel_2_3");
    let tally = check(&model, &mut s, POSES, 40, &no_parameter);
    assert_all_recovered("offset wrist", &tally);
}

#[test]
fn unreachable_poses_get_least_squares_solutions() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut s = solver(&model);
    let far = Pose::from_translation(Vector3::new(100.0, 0.0, 0.5));
    let solutions = s.solve(&far, &model.neutral_configuration()).unwrap();
    assert!(!solutions.is_empty());
    assert!(solutions
        .iter()
        .all(|s| s.fit == Fit::Approximate && s.position_error > 90.0));
}

#[test]
fn bad_input_is_rejected_with_a_clear_error() {
    let model = armkit::robots::by_name("puma560").unwrap();
    let mut s = solver(&model);
    let start = model.neutral_configuration();
    let mut skewed = Pose::identity();
    skewed.rotation[(0, 1)] = 0.3;
    let error = s.solve(&skewed, &start).unwrap_err().to_string();
    assert!(error.contains("not a proper rotation"), "{error}");
    let nan = Pose::from_translation(Vector3::new(f64::NAN, 0.0, 0.0));
    let error = s.solve(&nan, &start).unwrap_err().to_string();
    assert!(error.contains("non-finite"), "{error}");
    let error = s
        .solve(&Pose::identity(), &start[..3])
        .unwrap_err()
        .to_string();
    assert!(error.contains("current"), "{error}");
    let panda = armkit::robots::by_name("panda").unwrap();
    let error = AnalyticSolver::new(&panda, AnalyticOptions::default())
        .unwrap_err()
        .to_string();
    assert!(error.contains("7 joints"), "{error}");
    let error = AnalyticSolver::with_parameter(
        &panda,
        AnalyticOptions::default(),
        Parameter::ElbowAngle(0.0),
    )
    .unwrap_err()
    .to_string();
    assert!(error.contains("no analytic solver"), "{error}");
}

#[test]
fn every_representative_within_wide_ranges() {
    // UR5 joints 1, 2, 4, 5, 6 span 4 pi: each solution comes with every
    // 2 pi multiple inside; the nearest-only option returns one each.
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut data = Data::new(&model);
    let q = [0.3, -1.2, 1.4, -0.5, 1.2, 0.4];
    let target = *forward_kinematics(&model, &mut data, &q).unwrap();
    let every = solver(&model).solve(&target, &q).unwrap().len();
    let options = AnalyticOptions {
        representatives: armkit::ik::analytic::Representatives::Nearest,
        ..AnalyticOptions::default()
    };
    let nearest = AnalyticSolver::new(&model, options)
        .unwrap()
        .solve(&target, &q)
        .unwrap()
        .len();
    assert_eq!(nearest, 8);
    assert_eq!(every, 8 * 32);
}

#[test]
fn subproblem_verification_agrees_with_forward_kinematics() {
    use armkit::ik::analytic::Verification;
    for name in ["ur5", "puma560", "stanford"] {
        let model = armkit::robots::by_name(name).unwrap();
        let fast = AnalyticOptions {
            verification: Verification::Subproblems,
            ..AnalyticOptions::default()
        };
        let mut checked = solver(&model);
        let mut quick = AnalyticSolver::new(&model, fast).unwrap();
        for (q, target) in armkit::ik::benchmark_targets(&model, 200, 9).unwrap() {
            let a = checked.solve(&target, &q).unwrap().to_vec();
            let b = quick.solve(&target, &q).unwrap().to_vec();
            assert_eq!(a.len(), b.len(), "{name}");
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x.q(), y.q());
                assert_eq!(x.fit, y.fit, "{name}");
                assert!(y.position_error.is_nan());
            }
        }
    }
}

#[test]
fn the_numeric_solver_rejects_targets_beyond_reach_at_once() {
    use armkit::ik::{IkOptions, IkSolver, IkStatus, ReachBound};
    for name in ["ur5", "panda", "puma560", "stanford"] {
        let model = armkit::robots::by_name(name).unwrap();
        let reach = ReachBound::of_model(&model);
        // The bound holds on random configurations (it is an upper bound).
        let mut data = Data::new(&model);
        let mut rng = common::rng(11);
        for _ in 0..2000 {
            let q = common::random_configuration(&model, &mut rng);
            let pose = forward_kinematics(&model, &mut data, &q).unwrap();
            assert!(!reach.excludes(pose), "{name}");
        }
        let mut far = Pose::identity();
        far.translation = reach.centre() + Vector3::new(reach.radius() * 1.001 + 1e-6, 0.0, 0.0);
        let mut solver = IkSolver::new(&model, IkOptions::default()).unwrap();
        let report = solver.solve(&far, &model.neutral_configuration()).unwrap();
        assert_eq!(report.status, IkStatus::NotConverged);
        assert_eq!(report.iterations, 0, "{name}");
        assert!(
            report.elapsed.as_micros() < 1000,
            "{name}: {:?}",
            report.elapsed
        );
    }
}

#[test]
fn auto_is_exact_on_every_pose_of_ur5_and_panda() {
    use armkit::ik::{AutoSolver, IkOptions, IkRoute, IkStatus};
    for name in ["ur5", "panda", "puma560"] {
        let model = armkit::robots::by_name(name).unwrap();
        let options = IkOptions {
            time_budget: None,
            max_restarts: 200,
            ..IkOptions::default()
        };
        let mut auto = AutoSolver::new(&model, options).unwrap();
        let start = model.neutral_configuration();
        let mut analytic = 0;
        for (_, target) in armkit::ik::benchmark_targets(&model, 300, 42).unwrap() {
            let solved = auto.solve(&target, &start).unwrap();
            assert_eq!(solved.report.status, IkStatus::Converged, "{name}");
            model.check_limits(&solved.report.q).unwrap();
            assert!(solved.report.position_error <= 1e-6);
            analytic += usize::from(solved.route != IkRoute::Numeric);
        }
        // 6R arms always take the analytic route; the Panda when joint 7's
        // start value admits a solution within the limits, else numeric.
        if name != "panda" {
            assert_eq!(analytic, 300, "{name}");
        } else {
            assert!(analytic > 50, "{name}: {analytic}");
        }
    }
}

#[test]
#[ignore = "10 000 poses per robot: cargo test --release -p armkit --test it -- --ignored ik_analytic::"]
fn ten_thousand_poses_per_robot() {
    let cases: Vec<(Model, Option<Parameter>)> = vec![
        (armkit::robots::by_name("puma560").unwrap(), None),
        (armkit::robots::by_name("ur5").unwrap(), None),
        (urdf("urdf/ur5.urdf", "tool0"), None),
        (armkit::robots::by_name("stanford").unwrap(), None),
        (ideal_iiwa14(), Some(Parameter::ElbowAngle(0.0))),
    ];
    for (i, (model, parameter)) in cases.into_iter().enumerate() {
        let mut s = match parameter {
            Some(p) => {
                AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), p).unwrap()
            }
            None => solver(&model),
        };
        let f: &dyn Fn(&AnalyticSolver, &[f64]) -> Option<f64> = if parameter.is_some() {
            &elbow_angle
        } else {
            &no_parameter
        };
        let tally = check(&model, &mut s, 10 * POSES, 100 + i as u64, f);
        assert_all_recovered(model.name(), &tally);
    }
    // The 1-D search class: the iiwa14 URDF with joint 3 held.
    let model = urdf("urdf/iiwa14.urdf", "tool0");
    let parameter = Parameter::FixedJoint {
        joint: 2,
        value: 0.4,
    };
    let mut s =
        AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), parameter).unwrap();
    let tally = check(&model, &mut s, 10 * POSES, 200, &no_parameter);
    assert_search_recovered("iiwa14 urdf q3 held", &tally);
}

// ------------------------------------------------- one-pair and general 6R

/// Lines of a random 6R arm whose only special pair is axes `first`,
/// `first + 1` (0-based) meeting in one point.
fn one_pair_lines(rng: &mut ChaCha8Rng, first: usize) -> Lines {
    let mut lines: Lines = (0..6)
        .map(|_| (point(rng) * 2.0, unit(rng), false))
        .collect();
    lines[first + 1].0 = lines[first].0;
    lines
}

/// Solves POSES / 10 poses on each of `arms` random arms from `lines`;
/// every exact solution is checked by FK (in `check`); returns the tally
/// over all poses.
fn random_search_arms(
    seed: u64,
    arms: u64,
    poses: usize,
    lines: &dyn Fn(&mut ChaCha8Rng) -> Lines,
    expected: &str,
    options: AnalyticOptions,
) -> Tally {
    let mut rng = common::rng(seed);
    let mut tally = Tally {
        poses: 0,
        recovered: 0,
        worst_error: 0.0,
        solutions: 0,
    };
    for arm in 0..arms {
        let lines = lines(&mut rng);
        let model = model_from_lines(&format!("pair{arm}"), &lines, random_home(&mut rng));
        let mut s = AnalyticSolver::new(&model, options).unwrap();
        assert_eq!(s.class().as_str(), expected, "arm {arm}");
        let one = check(&model, &mut s, poses, seed * 100 + arm, &no_parameter);
        tally.poses += one.poses;
        tally.recovered += one.recovered;
        tally.solutions += one.solutions;
        tally.worst_error = tally.worst_error.max(one.worst_error);
    }
    println!(
        "{expected}: generating configuration on {}/{} poses ({:.2} %), {:.1} solutions per pose, worst FK error {:.1e}",
        tally.recovered,
        tally.poses,
        100.0 * tally.recovered as f64 / tally.poses as f64,
        tally.solutions as f64 / tally.poses as f64,
        tally.worst_error
    );
    tally
}

/// Every intersecting-pair layout (5-6, 4-5 and 3-4 as built, 1-2 and 2-3
/// on the reversed lines) on `arms` arms x `poses` poses, solved with
/// `options`; the recovery over all.
fn one_pair_tally(seed: u64, arms: u64, poses: usize, options: AnalyticOptions) -> Tally {
    let cases = [
        (4, false, "one_pair_intersecting_5_6"),
        (4, true, "one_pair_intersecting_1_2"),
        (3, false, "one_pair_intersecting_4_5"),
        (3, true, "one_pair_intersecting_2_3"),
        (2, false, "one_pair_intersecting_3_4"),
    ];
    let mut total = Tally {
        poses: 0,
        recovered: 0,
        worst_error: 0.0,
        solutions: 0,
    };
    for (i, (first, reverse, class)) in cases.into_iter().enumerate() {
        let lines = move |rng: &mut ChaCha8Rng| {
            let mut lines = one_pair_lines(rng, first);
            if reverse {
                lines.reverse();
            }
            lines
        };
        let tally = random_search_arms(seed + i as u64, arms, poses, &lines, class, options);
        total.poses += tally.poses;
        total.recovered += tally.recovered;
        total.solutions += tally.solutions;
        total.worst_error = total.worst_error.max(tally.worst_error);
    }
    println!(
        "one-pair arms: generating configuration on {}/{} poses, {:.2} solutions per pose, worst FK error {:.1e}",
        total.recovered,
        total.poses,
        total.solutions as f64 / total.poses as f64,
        total.worst_error
    );
    total
}

#[test]
fn random_one_pair_arms_by_elimination() {
    let tally = one_pair_tally(70, 10, POSES / 10, AnalyticOptions::default());
    assert_search_recovered("one-pair arms", &tally);
}

/// 20 000 poses: 40 arms x 100 poses for each of the five layouts.
#[test]
#[ignore = "slow: cargo test --release -p armkit --test it -- --ignored ik_analytic:: --nocapture"]
fn many_random_one_pair_arms_by_elimination() {
    let tally = one_pair_tally(410, 40, 100, AnalyticOptions::default());
    assert_search_recovered("one-pair arms", &tally);
}

/// Lines of a random 6R arm whose only special pair is axes `first`,
/// `first + 1` (0-based) parallel (same or opposite direction, two distinct
/// lines).
fn parallel_pair_lines(rng: &mut ChaCha8Rng, first: usize) -> Lines {
    let mut lines: Lines = (0..6)
        .map(|_| (point(rng) * 2.0, unit(rng), false))
        .collect();
    lines[first + 1].1 = lines[first].1 * sign(rng);
    lines
}

/// The parallel-pair cases: pair (0-based first joint), lines reversed,
/// the class. Pairs 2-3 and 4-5 are built both ways (4-5 is solved on the
/// reversed chain).
const PARALLEL_CASES: [(usize, bool, &str); 5] = [
    (1, false, "one_pair_parallel_2_3"),
    (3, false, "one_pair_parallel_4_5"),
    (1, true, "one_pair_parallel_4_5"),
    (3, true, "one_pair_parallel_2_3"),
    (2, false, "one_pair_parallel_3_4"),
];

/// The parallel pairs at an end of the chain (1-2 solved as built, 5-6 on
/// the reversed chain), each built both ways.
const END_PARALLEL_CASES: [(usize, bool, &str); 4] = [
    (0, false, "one_pair_parallel_1_2"),
    (4, false, "one_pair_parallel_5_6"),
    (0, true, "one_pair_parallel_5_6"),
    (4, true, "one_pair_parallel_1_2"),
];

/// [`parallel_pair_tally`] recovers the generating configuration on
/// >= 99.9 % of the poses.
fn parallel_pairs_recovered(
    name: &str,
    cases: &[(usize, bool, &'static str)],
    sizes: (u64, u64, usize),
    options: AnalyticOptions,
) {
    assert_search_recovered(name, &parallel_pair_tally(cases, sizes, options));
}

/// Every case of `cases` on `arms` arms x `poses` poses, solved with
/// `options`; the recovery over all.
fn parallel_pair_tally(
    cases: &[(usize, bool, &'static str)],
    (seed, arms, poses): (u64, u64, usize),
    options: AnalyticOptions,
) -> Tally {
    let mut total = Tally {
        poses: 0,
        recovered: 0,
        worst_error: 0.0,
        solutions: 0,
    };
    for (i, &(first, reverse, class)) in cases.iter().enumerate() {
        let lines = move |rng: &mut ChaCha8Rng| {
            let mut lines = parallel_pair_lines(rng, first);
            if reverse {
                lines.reverse();
            }
            lines
        };
        let tally = random_search_arms(seed + i as u64, arms, poses, &lines, class, options);
        total.poses += tally.poses;
        total.recovered += tally.recovered;
        total.solutions += tally.solutions;
        total.worst_error = total.worst_error.max(tally.worst_error);
    }
    println!(
        "parallel-pair arms: generating configuration on {}/{} poses, worst FK error {:.1e}",
        total.recovered, total.poses, total.worst_error
    );
    total
}

#[test]
fn random_parallel_pair_arms_by_elimination() {
    parallel_pairs_recovered(
        "parallel-pair arms",
        &PARALLEL_CASES,
        (300, 10, 20),
        AnalyticOptions::default(),
    );
}

#[test]
#[ignore = "slow: cargo test --release -p armkit --test it -- --ignored ik_analytic:: --nocapture"]
fn many_random_parallel_pair_arms_by_elimination() {
    parallel_pairs_recovered(
        "parallel-pair arms",
        &PARALLEL_CASES,
        (310, 40, 100),
        AnalyticOptions::default(),
    );
}

#[test]
fn random_end_parallel_pair_arms_by_elimination() {
    parallel_pairs_recovered(
        "end parallel-pair arms",
        &END_PARALLEL_CASES,
        (340, 6, 20),
        AnalyticOptions::default(),
    );
}

#[test]
#[ignore = "slow: cargo test --release -p armkit --test it -- --ignored ik_analytic:: --nocapture"]
fn many_random_end_parallel_pair_arms_by_elimination() {
    parallel_pairs_recovered(
        "end parallel-pair arms",
        &END_PARALLEL_CASES,
        (350, 50, 100),
        AnalyticOptions::default(),
    );
}

#[test]
fn parallel_pair_detection_takes_only_its_class() {
    let mut rng = common::rng(320);
    let class_of = |lines: &Lines, rng: &mut ChaCha8Rng| {
        let model = model_from_lines("arm", lines, random_home(rng));
        match AnalyticSolver::new(&model, AnalyticOptions::default()) {
            Ok(s) => s.class().as_str().to_string(),
            Err(e) => format!("refused: {e}"),
        }
    };
    for _ in 0..5 {
        // Each position, built as such.
        for (first, class) in [
            (0, "one_pair_parallel_1_2"),
            (1, "one_pair_parallel_2_3"),
            (2, "one_pair_parallel_3_4"),
            (3, "one_pair_parallel_4_5"),
            (4, "one_pair_parallel_5_6"),
        ] {
            let lines = parallel_pair_lines(&mut rng, first);
            assert_eq!(class_of(&lines, &mut rng), class);
        }
        // A pair in the middle wins over one at an end.
        let mut lines = parallel_pair_lines(&mut rng, 2);
        lines[1].1 = lines[0].1;
        assert_eq!(class_of(&lines, &mut rng), "one_pair_parallel_3_4");
        // An intersecting pair the one-pair search handles wins.
        let mut lines = parallel_pair_lines(&mut rng, 1);
        lines[5].0 = lines[4].0;
        assert_eq!(class_of(&lines, &mut rng), "one_pair_intersecting_5_6");
        // Three parallel axes (2-3-4) are the closed-form class.
        let mut lines = parallel_pair_lines(&mut rng, 1);
        lines[3].1 = lines[2].1;
        assert_eq!(class_of(&lines, &mut rng), "three_parallel_2_3_4");
        // Axes 1-2-3 parallel: each pair has a parallel neighbour, so no
        // 1-D search takes the arm.
        let mut lines = parallel_pair_lines(&mut rng, 1);
        lines[0].1 = lines[1].1;
        let found = class_of(&lines, &mut rng);
        assert!(
            found == "other_special_pairs" || found.contains("class other_special_pairs "),
            "{found}"
        );
        // Axes 1-2 and 5-6 parallel: the 1-2 search, over joint 6 only
        // (its search over joint 3 would turn axis 6 about itself).
        let mut lines = parallel_pair_lines(&mut rng, 0);
        lines[5].1 = lines[4].1;
        assert_eq!(class_of(&lines, &mut rng), "one_pair_parallel_1_2");
        // The pair on one line (a degenerate arm): no 1-D search takes it.
        let mut lines = parallel_pair_lines(&mut rng, 1);
        lines[2].0 = lines[1].0 + lines[1].1 * 0.3;
        let found = class_of(&lines, &mut rng);
        assert!(
            found == "other_special_pairs" || found.contains("class other_special_pairs "),
            "{found}"
        );
        // A spherical wrist with parallel 2-3 stays closed form.
        let lines = spherical_wrist_lines(&mut rng, Positioning::ParallelSecondThird);
        assert_eq!(class_of(&lines, &mut rng), "spherical_wrist_parallel_2_3");
    }
}

#[test]
fn auto_takes_the_numeric_route_on_parallel_pair_arms() {
    let mut rng = common::rng(330);
    for (first, class) in [(1, "one_pair_parallel_2_3"), (0, "one_pair_parallel_1_2")] {
        let model = model_from_lines(
            "parallel",
            &parallel_pair_lines(&mut rng, first),
            random_home(&mut rng),
        );
        assert_eq!(solver(&model).class().as_str(), class);
        assert_auto_takes_the_numeric_route(&model, class);
    }
}

#[test]
fn parallel_end_pairs_and_pairs_at_both_ends_are_solved_by_elimination() {
    let mut rng = common::rng(80);
    // Parallel 1-2 only.
    let mut lines: Lines = (0..6)
        .map(|_| (point(&mut rng), unit(&mut rng), false))
        .collect();
    lines[1].1 = lines[0].1;
    let model = model_from_lines("parallel", &lines, random_home(&mut rng));
    let mut s = solver(&model);
    assert_eq!(s.class().as_str(), "one_pair_parallel_1_2");
    let tally = check(&model, &mut s, 20, 81, &no_parameter);
    assert_all_recovered("parallel 1-2", &tally);
    // Parallel 1-2 and 5-6: every generating configuration on these poses.
    lines[5].1 = -lines[4].1;
    let model = model_from_lines("parallel_ends", &lines, random_home(&mut rng));
    let mut s = solver(&model);
    assert_eq!(s.class().as_str(), "one_pair_parallel_1_2");
    assert!(s.method().contains("elimination"), "{}", s.method());
    let tally = check(&model, &mut s, 20, 82, &no_parameter);
    assert_all_recovered("parallel 1-2 and 5-6", &tally);
    // Parallel 1-2-3: every pair has a parallel neighbour: elimination with
    // the loop cut between joints 1 and 6 (every generating configuration
    // on these poses).
    lines[2].1 = lines[0].1;
    let model = model_from_lines("parallel123", &lines, random_home(&mut rng));
    let mut s = solver(&model);
    assert_eq!(s.class().as_str(), "other_special_pairs");
    assert!(s.method().contains("elimination"), "{}", s.method());
    let tally = check(&model, &mut s, 20, 83, &no_parameter);
    assert_all_recovered("parallel 1-2-3", &tally);
}

#[test]
fn a_general_6r_arm_is_solved_by_elimination() {
    let mut rng = common::rng(90);
    let lines: Lines = (0..6)
        .map(|_| (point(&mut rng), unit(&mut rng), false))
        .collect();
    let model = model_from_lines("general", &lines, random_home(&mut rng));
    let mut s = AnalyticSolver::new(&model, AnalyticOptions::default()).unwrap();
    assert_eq!(s.class(), ArmClass::General);
    assert!(s.method().contains("elimination"), "{}", s.method());
    let tally = check(&model, &mut s, 50, 91, &no_parameter);
    assert_all_recovered("general 6R by elimination", &tally);
}

fn general_lines(rng: &mut ChaCha8Rng) -> Lines {
    (0..6)
        .map(|_| (point(rng) * 2.0, unit(rng), false))
        .collect()
}

/// `arms` random general 6R arms x 100 poses by elimination: the
/// generating configuration on >= 99.9 % of the poses.
fn general_arms_by_elimination(seed: u64, arms: u64) {
    let tally = random_search_arms(
        seed,
        arms,
        POSES / 10,
        &general_lines,
        "general_6r",
        AnalyticOptions::default(),
    );
    assert_search_recovered("general 6R arms by elimination", &tally);
}

#[test]
fn random_general_6r_arms_by_elimination() {
    general_arms_by_elimination(97, 10);
}

/// 20 000 poses: 200 arms x 100 poses.
#[test]
#[ignore = "slow: cargo test --release -p armkit --test it -- --ignored ik_analytic:: --nocapture"]
fn many_random_general_6r_arms_by_elimination() {
    general_arms_by_elimination(98, 200);
}

#[test]
fn auto_takes_the_numeric_route_on_arms_without_a_closed_form() {
    // Elimination (and the one-pair search) is slower than a numeric
    // solve: the automatic route leaves these arms to the analytic solver's
    // explicit callers.
    let mut rng = common::rng(77);
    let pair = one_pair_lines(&mut rng, 4);
    let general = general_lines(&mut rng);
    for (lines, class) in [(pair, "one_pair"), (general, "general_6r")] {
        let model = model_from_lines("arm", &lines, random_home(&mut rng));
        assert!(solver(&model).class().as_str().starts_with(class));
        assert_auto_takes_the_numeric_route(&model, class);
    }
}

/// `model`'s automatic solver has no analytic route and solves a pose
/// numerically (`class` names the arm in the message).
fn assert_auto_takes_the_numeric_route(model: &Model, class: &str) {
    use armkit::ik::{AutoSolver, IkOptions, IkRoute};
    let mut auto = AutoSolver::new(model, IkOptions::default()).unwrap();
    assert_eq!(auto.class(), None, "{class}");
    let mut data = Data::new(model);
    let q = [0.3, -0.4, 0.5, 0.2, -0.6, 0.1];
    let target = *forward_kinematics(model, &mut data, &q).unwrap();
    let solved = auto.solve(&target, &model.neutral_configuration()).unwrap();
    assert_eq!(solved.route, IkRoute::Numeric, "{class}");
}

/// Random lines of every layout elimination takes: general, one
/// intersecting or parallel pair at each place along the chain, and
/// special pairs at both ends (each kind at each end).
fn elimination_layouts(rng: &mut ChaCha8Rng) -> Vec<(String, Lines)> {
    let mut layouts = vec![("general".to_string(), general_lines(rng))];
    for first in 0..5 {
        layouts.push((format!("meet {first}"), one_pair_lines(rng, first)));
        layouts.push((format!("parallel {first}"), parallel_pair_lines(rng, first)));
    }
    for (first_parallel, last_parallel) in
        [(true, true), (true, false), (false, true), (false, false)]
    {
        let mut lines = general_lines(rng);
        match first_parallel {
            true => lines[1].1 = lines[0].1 * sign(rng),
            false => lines[1].0 = lines[0].0,
        }
        match last_parallel {
            true => lines[5].1 = lines[4].1 * sign(rng),
            false => lines[5].0 = lines[4].0,
        }
        layouts.push((format!("ends {first_parallel} {last_parallel}"), lines));
    }
    layouts
}

/// Elimination checked against an independent oracle, multi-start
/// Levenberg-Marquardt converged to 1e-12 m and rad (so a configuration
/// it reports is within about 1e-12 / sigma_min rad of an exact one, far
/// inside the 1e-6 rad match even near a singular configuration): on a
/// random arm of every layout elimination takes, every configuration LM
/// reaches from 40 random starts per pose is among elimination's exact
/// solutions (joint angles to 1e-6 rad, modulo 2 pi), and elimination
/// finds the generating configuration of every pose.
#[test]
fn elimination_finds_every_solution_multi_start_lm_finds() {
    use armkit::ik::{IkMethod, IkOptions, IkSolver};
    let mut rng = common::rng(500);
    let same = |a: &[f64], b: &[f64]| {
        a.iter().zip(b).all(|(x, y)| {
            let d = x - y;
            (d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round()).abs() < 1e-6
        })
    };
    let lm = IkOptions {
        method: IkMethod::from_short_name("lm").unwrap(),
        position_tolerance: 1e-12,
        orientation_tolerance: 1e-12,
        max_iterations: 200,
        time_budget: None,
        max_restarts: 0,
        ..IkOptions::default()
    };
    let (mut found, mut eliminated) = (0, 0);
    let mut missed = Vec::new();
    for (layout, lines) in elimination_layouts(&mut rng) {
        let model = model_from_lines("layout", &lines, random_home(&mut rng));
        let mut elimination = solver(&model);
        assert!(
            elimination.method().contains("elimination"),
            "{layout}: {}",
            elimination.method()
        );
        let mut oracle = IkSolver::new(&model, lm).unwrap();
        let mut data = Data::new(&model);
        for _ in 0..15 {
            let q = common::random_configuration(&model, &mut rng);
            let target = *forward_kinematics(&model, &mut data, &q).unwrap();
            let exact: Vec<Vec<f64>> = elimination
                .solve(&target, &q)
                .unwrap()
                .iter()
                .filter(|s| s.fit == Fit::Exact)
                .map(|s| s.q().to_vec())
                .collect();
            eliminated += exact.len();
            assert!(exact.iter().any(|p| same(p, &q)), "{layout}: {q:?}");
            for _ in 0..40 {
                let start = common::random_configuration(&model, &mut rng);
                let report = oracle.solve(&target, &start).unwrap();
                if report.converged() {
                    found += 1;
                    if !exact.iter().any(|p| same(p, &report.q)) {
                        missed.push(format!("{layout}: {:?}", report.q));
                    }
                }
            }
        }
    }
    println!(
        "of {found} LM solutions elimination misses {}; elimination: {eliminated} exact solutions",
        missed.len()
    );
    assert!(found > 1000, "LM converged {found} times");
    assert!(
        missed.is_empty(),
        "{} of {found} LM solutions not among elimination's: {missed:#?}",
        missed.len()
    );
}

/// The example robots (`examples/robots/`, the README's bench-ik rows):
/// every one of `armkit bench-ik`'s 10 000 targets (seed 42) has an exact
/// solution by elimination. Each file has one target whose only two
/// solutions share joint 3 to 4e-5 rad (near a singular configuration):
/// there the polynomial's two roots become a complex pair by rounding, and
/// were found only once the double root was split and polished apart.
#[test]
fn the_example_robots_bench_targets_are_all_solved() {
    for name in ["one-pair-5-6", "general-6r"] {
        let path = format!(
            "{}/../../examples/robots/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let model = armkit::description::load(std::path::Path::new(&path)).unwrap();
        let targets = armkit::ik::benchmark_targets(&model, 10_000, 42).unwrap();
        let mut s = solver(&model);
        let start = model.neutral_configuration();
        let unsolved: Vec<usize> = targets
            .iter()
            .enumerate()
            .filter(|(_, (_, target))| {
                !s.solve(target, &start)
                    .unwrap()
                    .iter()
                    .any(|s| s.fit == Fit::Exact)
            })
            .map(|(k, _)| k)
            .collect();
        assert!(unsolved.is_empty(), "{name}: targets {unsolved:?} unsolved");
    }
}

/// Special pairs at both ends (1-2 and 5-6, each intersecting or
/// parallel): elimination with the loop cut between joints 1 and 6 takes
/// every combination, and recovers the generating configuration of each
/// pose.
#[test]
fn special_pairs_at_both_ends_are_solved_by_elimination() {
    let mut rng = common::rng(85);
    for (first_parallel, last_parallel) in
        [(true, true), (true, false), (false, true), (false, false)]
    {
        for arm in 0..3 {
            let mut lines: Lines = (0..6)
                .map(|_| (point(&mut rng) * 2.0, unit(&mut rng), false))
                .collect();
            match first_parallel {
                true => lines[1].1 = lines[0].1 * sign(&mut rng),
                false => lines[1].0 = lines[0].0,
            }
            match last_parallel {
                true => lines[5].1 = lines[4].1 * sign(&mut rng),
                false => lines[5].0 = lines[4].0,
            }
            let model = model_from_lines("ends", &lines, random_home(&mut rng));
            let mut s = solver(&model);
            let what = format!("{first_parallel} {last_parallel} arm {arm}: {}", s.class());
            assert!(s.method().contains("elimination"), "{what}: {}", s.method());
            let tally = check(&model, &mut s, 30, 86 + arm, &no_parameter);
            println!("{what}: {}/{}", tally.recovered, tally.poses);
            assert_all_recovered(&what, &tally);
        }
    }
}
