//! Forward kinematics and Jacobians against the Robotics Toolbox reference
//! files, through the built-in robots and through the description-file loader.

use crate::common::*;
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::Model;

const POSE_TOLERANCE: f64 = 1e-12;
const JACOBIAN_TOLERANCE: f64 = 1e-9;

fn check_against_reference(model: &Model, file: &str) {
    let samples = reference_samples(file);
    assert_eq!(samples.len(), 200);
    let mut data = Data::new(model);
    let (mut worst_pose, mut worst_jacobian) = (0.0f64, 0.0f64);
    for sample in &samples {
        let pose = *forward_kinematics(model, &mut data, &sample.q).unwrap();
        worst_pose = worst_pose.max(pose_error(&pose, &sample.pose));
        let j = jacobian(model, &mut data, &sample.q, JacobianFrame::World).unwrap();
        worst_jacobian = worst_jacobian.max(jacobian_error(j, &sample.jacobian));
    }
    assert!(
        worst_pose < POSE_TOLERANCE,
        "{file}: pose error {worst_pose:e}"
    );
    assert!(
        worst_jacobian < JACOBIAN_TOLERANCE,
        "{file}: Jacobian error {worst_jacobian:e}"
    );
}

#[test]
fn builtin_robots_match_the_robotics_toolbox() {
    for (robot, file) in [
        ("puma560", "reference_puma560_dh.json"),
        ("ur5", "reference_ur5_dh.json"),
        ("stanford", "reference_stanford_dh.json"),
        ("panda", "reference_panda_mdh_rtb.json"),
    ] {
        check_against_reference(&armkit::robots::by_name(robot).unwrap(), file);
    }
}

#[test]
fn description_files_loaded_from_the_reference_json_match() {
    for file in [
        "reference_puma560_dh.json",
        "reference_ur5_dh.json",
        "reference_stanford_dh.json",
        "reference_panda_mdh_rtb.json",
    ] {
        let model = armkit::description::load(data_path(file)).unwrap();
        check_against_reference(&model, file);
    }
}

#[test]
fn the_dh_block_alone_loads_as_json_and_as_toml() {
    let text = std::fs::read_to_string(data_path("reference_panda_mdh_rtb.json")).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let dh_json = serde_json::to_string_pretty(&value["dh"]).unwrap();
    let model =
        armkit::description::parse_str(&dh_json, armkit::description::Format::Json, "dh.json")
            .unwrap();
    check_against_reference(&model, "reference_panda_mdh_rtb.json");
    let dh_toml = toml::to_string(&value["dh"]).unwrap();
    let model =
        armkit::description::parse_str(&dh_toml, armkit::description::Format::Toml, "dh.toml")
            .unwrap();
    check_against_reference(&model, "reference_panda_mdh_rtb.json");
}

#[test]
fn builtin_limits_match_the_reference_limits() {
    for (robot, file) in [
        ("puma560", "reference_puma560_dh.json"),
        ("stanford", "reference_stanford_dh.json"),
        ("panda", "reference_panda_mdh_rtb.json"),
    ] {
        let model = armkit::robots::by_name(robot).unwrap();
        let text = std::fs::read_to_string(data_path(file)).unwrap();
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        let lower: Vec<f64> =
            serde_json::from_value(value["joint_limits"]["lower"].clone()).unwrap();
        let upper: Vec<f64> =
            serde_json::from_value(value["joint_limits"]["upper"].clone()).unwrap();
        for (j, joint) in model.joints().iter().enumerate() {
            assert!(
                (joint.limits.lower - lower[j]).abs() < 1e-12,
                "{robot} joint {j}"
            );
            assert!(
                (joint.limits.upper - upper[j]).abs() < 1e-12,
                "{robot} joint {j}"
            );
        }
    }
}
