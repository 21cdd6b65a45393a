//! `--urdf PATH [--base LINK] [--tip LINK]` on the `fk` and `jacobian`
//! commands, against the Pinocchio reference files.

use crate::common::*;

/// Sample `index` of a reference file: (q as text, pose rows, Jacobian rows).
fn sample(file: &str, index: usize) -> (String, Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let path = format!("{}/../../tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let sample = &value["samples"][index];
    let q: Vec<f64> = serde_json::from_value(sample["q"].clone()).unwrap();
    let text = q
        .iter()
        .map(|v| format!("{v:.17e}"))
        .collect::<Vec<_>>()
        .join(",");
    (
        text,
        serde_json::from_value(sample["pose"].clone()).unwrap(),
        serde_json::from_value(sample["jacobian"].clone()).unwrap(),
    )
}

fn max_difference(a: &serde_json::Value, b: &[Vec<f64>]) -> f64 {
    let a: Vec<Vec<f64>> = serde_json::from_value(a.clone()).unwrap();
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(ra, rb)| {
            assert_eq!(ra.len(), rb.len());
            ra.iter().zip(rb).map(|(x, y)| (x - y).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn fk_of_the_ur5_urdf_matches_pinocchio() {
    for index in [0, 117] {
        let (q, pose, _) = sample("reference_ur5.json", index);
        let output = armkit(&[
            "fk",
            "--urdf",
            "tests/data/urdf/ur5.urdf",
            "--base",
            "base_link",
            "--tip",
            "tool0",
            "--q",
            &q,
            "--json",
        ]);
        let value = json(&output);
        assert_eq!(value["robot"], "ur5");
        let error = max_difference(&value["pose"], &pose);
        assert!(error < 1e-12, "sample {index}: pose error {error:e}");
    }
}

#[test]
fn jacobian_of_the_panda_urdf_matches_pinocchio() {
    let (q, _, jacobian) = sample("reference_panda.json", 5);
    let output = armkit(&[
        "jacobian",
        "--urdf",
        "tests/data/urdf/panda.urdf",
        "--base",
        "panda_link0",
        "--tip",
        "panda_link8",
        "--q",
        &q,
        "--json",
    ]);
    let error = max_difference(&json(&output)["jacobian"], &jacobian);
    assert!(error < 1e-9, "Jacobian error {error:e}");
}

#[test]
fn the_default_chain_needs_one_leaf_and_the_error_lists_them() {
    let output = armkit(&[
        "fk",
        "--urdf",
        "tests/data/urdf/panda.urdf",
        "--q",
        "0,0,0,-1,0,1,0",
    ]);
    assert!(!output.status.success());
    assert_eq!(
        stderr(&output),
        "error: tests/data/urdf/panda.urdf: the tree below the base link `panda_link0` has 3 leaf links \
         (`panda_hand_tcp`, `panda_leftfinger`, `panda_rightfinger`): choose the tip link"
    );
    // The tip alone is enough: the base defaults to the root.
    let output = armkit(&[
        "fk",
        "--urdf",
        "tests/data/urdf/iiwa14.urdf",
        "--tip",
        "tool0",
        "--q",
        "0,0,0,0,0,0,0",
        "--json",
    ]);
    let position: Vec<f64> = serde_json::from_value(json(&output)["position"].clone()).unwrap();
    // All joints at zero: the iiwa stands straight up, 0.36 + 0.42 + 0.4 + 0.126 m.
    let expected = [0.0, 0.0, 1.306];
    assert!(
        position
            .iter()
            .zip(expected)
            .all(|(a, b)| (a - b).abs() < 1e-12),
        "{position:?}"
    );
}

#[test]
fn urdf_errors_are_one_line_with_the_file_and_element() {
    let output = armkit(&[
        "fk",
        "--urdf",
        "tests/data/urdf/ur5.urdf",
        "--base",
        "base_link",
        "--tip",
        "flange",
        "--q",
        "0,0,0,0,0,0",
    ]);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.starts_with(
            "error: tests/data/urdf/ur5.urdf: the tip link `flange` does not exist; the links are: base_link,"
        ),
        "{message}"
    );
    assert_eq!(message.lines().count(), 1);
    // --base needs --urdf.
    let output = armkit(&["fk", "--robot", "ur5", "--base", "x", "--q", "0,0,0,0,0,0"]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("--urdf"), "{}", stderr(&output));
}

/// `armkit info` lists the chain, which joints mimic which, and the limits;
/// `fk` takes the independent joints only.
#[test]
fn info_lists_mimic_joints_and_the_limits_they_impose() {
    let output = armkit(&[
        "info",
        "--urdf",
        "tests/data/urdf/mimicbot.urdf",
        "--base",
        "base",
        "--tip",
        "fingertip",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.starts_with("robot mimicbot: 9 chain joints, 7 independent (dof)"),
        "{text}"
    );
    assert!(text.contains("middle_joint  revolute           -0.2          1.2         3  mimics knuckle: 0.8 * q[6] + 0.1"), "{text}");
    assert!(text.contains("distal_joint  revolute           -0.5          0.9         2  mimics knuckle: -0.96 * q[6] - 0.12"), "{text}");
    assert!(
        text.contains("q[6] knuckle       revolute           -0.3     0.395833  2.083333"),
        "{text}"
    );

    let value = json(&armkit(&[
        "info",
        "--urdf",
        "tests/data/urdf/mimicbot.urdf",
        "--tip",
        "finger_b_tip",
        "--json",
    ]));
    assert_eq!(value["dof"], 7);
    assert_eq!(value["joints"][6]["name"], "finger_a_joint");
    assert_eq!(value["chain_joints"][6]["name"], "finger_b_joint");
    assert_eq!(value["couplings"][0]["kind"], "mimic");
    assert_eq!(value["couplings"][0]["multiplier"], 0.75);
    assert_eq!(value["chain_joints"][5]["lower"], serde_json::Value::Null);

    // The gantry's beam is listed as an additive coupling.
    let text = stdout(&armkit(&["info", "--robot", "gantry9-flex"]));
    assert!(text.contains("q[2] + f(q[1] = q2)"), "{text}");
    assert!(
        text.contains("coupling: q3 adds the deflection w of a simply supported 10 m beam"),
        "{text}"
    );

    // fk takes the 7 independent joints.
    let value = json(&armkit(&[
        "fk",
        "--urdf",
        "tests/data/urdf/mimicbot.urdf",
        "--tip",
        "fingertip",
        "--q",
        "0,0,0,0,0,0,0.2",
        "--json",
    ]));
    assert!(value.is_object(), "{value}");
}

#[test]
fn info_on_a_urdf_with_several_leaves_prints_the_tree() {
    let output = armkit(&["info", "--urdf", "tests/data/urdf/panda.urdf"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.starts_with("robot panda: 13 links, 12 joints, 3 leaf links: a tree, not one chain;"),
        "{text}"
    );
    // Depth shows as indentation: the hand below link 8, the fingers below the hand.
    assert!(
        text.contains("\n  panda_link0 -> panda_link1  [revolute panda_joint1]\n"),
        "{text}"
    );
    assert!(
        text.contains("    panda_hand -> panda_leftfinger  [prismatic panda_finger_joint1]\n"),
        "{text}"
    );
    assert!(
        text.ends_with("leaf links (tips): panda_hand_tcp, panda_leftfinger, panda_rightfinger\n"),
        "{text}"
    );
    let tree = json(&armkit(&[
        "info",
        "--urdf",
        "tests/data/urdf/panda.urdf",
        "--json",
    ]));
    assert_eq!(tree["roots"], serde_json::json!(["panda_link0"]));
    assert_eq!(tree["joints"].as_array().unwrap().len(), 12);
    // A tip chooses the chain: the chain's table, with its frames named.
    let output = armkit(&[
        "info",
        "--urdf",
        "tests/data/urdf/panda.urdf",
        "--tip",
        "panda_link8",
    ]);
    let text = stdout(&output);
    assert!(
        text.contains("frames: the URDF's base link frame"),
        "{text}"
    );
}

#[test]
fn fk_all_frames_of_the_urdfs_equal_pinocchio_joint_placements() {
    let path = format!(
        "{}/../../tests/data/reference_frames.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for chain in reference["chains"].as_array().unwrap() {
        let urdf = format!("tests/data/{}", chain["urdf"].as_str().unwrap());
        for sample in chain["samples"].as_array().unwrap().iter().take(3) {
            let q: Vec<f64> = serde_json::from_value(sample["q"].clone()).unwrap();
            let q = q
                .iter()
                .map(|v| format!("{v:.17e}"))
                .collect::<Vec<_>>()
                .join(",");
            let value = json(&armkit(&[
                "fk",
                "--urdf",
                &urdf,
                "--base",
                chain["base"].as_str().unwrap(),
                "--tip",
                chain["tip"].as_str().unwrap(),
                "--q",
                &q,
                "--all-frames",
                "--allow-out-of-limits",
                "--json",
            ]));
            let frames = value["frames"].as_array().unwrap();
            let placements = sample["placements"].as_array().unwrap();
            assert_eq!(frames.len(), placements.len());
            for ((frame, placement), name) in frames
                .iter()
                .zip(placements)
                .zip(chain["joint_names"].as_array().unwrap())
            {
                assert_eq!(&frame["name"], name);
                let rows: Vec<Vec<f64>> = serde_json::from_value(frame["pose"].clone()).unwrap();
                let expected: Vec<f64> = serde_json::from_value(placement.clone()).unwrap();
                let worst = rows
                    .concat()
                    .iter()
                    .zip(&expected)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                assert!(worst < 1e-12, "{name}: {worst:e}");
            }
        }
    }
    // The text form: one line per frame, named.
    let output = armkit(&["fk", "--robot", "ur5", "--q", "0,0,0,0,0,0", "--all-frames"]);
    let text = stdout(&output);
    assert!(
        text.contains("link frames in the world frame, one per joint"),
        "{text}"
    );
    assert_eq!(
        text.lines().filter(|l| l.starts_with("  q")).count(),
        6,
        "{text}"
    );
}
