//! The URDF corpus: every URDF file of example-robot-data 6.0.0
//! (tests/data/urdf_corpus, see its README) and every root-to-leaf chain with
//! two or more moving joints, against Pinocchio's forward kinematics and
//! Jacobians (scripts/make_urdf_corpus.py; mimic joints expanded there).
//! Every chain loads and matches (FK 1e-9, Jacobian 1e-8), except the
//! chains the reference marks as refused, which must fail with an error
//! naming the rule and the joint.

use crate::common::*;
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::urdf::{parse_str, ChainSelection};

const POSE_TOLERANCE: f64 = 1e-9;
const JACOBIAN_TOLERANCE: f64 = 1e-8;

#[test]
fn every_chain_of_the_corpus_loads_and_matches_pinocchio_or_is_refused_by_rule() {
    let reference: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(data_path("urdf_corpus/reference.json")).unwrap(),
    )
    .unwrap();
    let files = reference["files"].as_array().unwrap();
    let (mut chains, mut matched, mut refused, mut mimic_chains) = (0, 0, 0, 0);
    let (mut worst_pose, mut worst_jacobian) = (0.0f64, 0.0f64);
    let mut refusals = Vec::new();
    for file in files {
        let name = file["file"].as_str().unwrap();
        let text = std::fs::read_to_string(data_path(&format!("urdf_corpus/{name}"))).unwrap();
        if let Some(why) = file["pinocchio_error"].as_str() {
            // Pinocchio (urdfdom) refuses the file: so must armkit.
            let err = parse_str(&text, name, &ChainSelection::default()).unwrap_err();
            refusals.push(format!("{name}: Pinocchio: {}; armkit: {err}", why.trim()));
            continue;
        }
        for chain in file["chains"].as_array().unwrap() {
            chains += 1;
            let (base, tip) = (
                chain["base"].as_str().unwrap(),
                chain["tip"].as_str().unwrap(),
            );
            let selection = ChainSelection::between(base, tip);
            let result = parse_str(&text, name, &selection);
            if let Some(rule) = chain["refused"].as_str() {
                let joint = chain["joint"].as_str().unwrap();
                let message = result.unwrap_err().to_string();
                assert!(
                    message.contains(rule) && message.contains(&format!("`{joint}`")),
                    "{name} {base} -> {tip}: expected `{rule}` about `{joint}`, got: {message}"
                );
                refused += 1;
                refusals.push(format!("{name} {base} -> {tip}: {message}"));
                continue;
            }
            let model = result.unwrap_or_else(|e| panic!("{name} {base} -> {tip}: {e}"));
            let names: Vec<String> = serde_json::from_value(chain["joint_names"].clone()).unwrap();
            let model_names: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
            assert_eq!(model_names, names, "{name} {base} -> {tip}");
            if !chain["mimic"].as_array().unwrap().is_empty() {
                mimic_chains += 1;
                assert!(model.has_mimic_joints(), "{name} {base} -> {tip}");
            }
            let mut data = Data::new(&model);
            for sample in chain["samples"].as_array().unwrap() {
                let q: Vec<f64> = serde_json::from_value(sample["q"].clone()).unwrap();
                let pose_rows: [[f64; 4]; 4] =
                    serde_json::from_value(sample["pose"].clone()).unwrap();
                let jacobian_rows: Vec<Vec<f64>> =
                    serde_json::from_value(sample["jacobian"].clone()).unwrap();
                let pose = *forward_kinematics(&model, &mut data, &q).unwrap();
                let pose_error = pose_error(&pose, &pose_rows);
                let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
                let jacobian_error = jacobian_error(j, &jacobian_rows);
                assert!(
                    pose_error < POSE_TOLERANCE && jacobian_error < JACOBIAN_TOLERANCE,
                    "{name} {base} -> {tip} at {q:?}: pose {pose_error:e}, Jacobian {jacobian_error:e}"
                );
                worst_pose = worst_pose.max(pose_error);
                worst_jacobian = worst_jacobian.max(jacobian_error);
            }
            matched += 1;
        }
    }
    println!(
        "{} files, {chains} chains: {matched} match Pinocchio ({mimic_chains} with mimic joints; worst pose {worst_pose:.1e}, Jacobian {worst_jacobian:.1e}), {refused} refused",
        files.len()
    );
    for line in &refusals {
        println!("  refused: {line}");
    }
    assert_eq!(matched + refused, chains);
    assert!(
        mimic_chains > 0 && matched > 500,
        "{matched} matched, {mimic_chains} with mimic joints"
    );
}
