//! The `robots`, `fk` and `jacobian` commands, run as a user would.

use crate::common::*;

/// The first reference sample of a reference file: (q as text, pose rows, Jacobian rows).
fn first_sample(file: &str) -> (String, Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let path = format!("{}/../../tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let sample = &value["samples"][0];
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
        .flat_map(|(ra, rb)| ra.iter().zip(rb).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn robots_lists_every_builtin() {
    let output = armkit(&["robots", "--json"]);
    let list = json(&output);
    let names: Vec<&str> = list
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "puma560",
            "ur5",
            "ur5-urdf",
            "panda",
            "stanford",
            "arm4",
            "space6r",
            "gantry9",
            "gantry9-flex"
        ]
    );
    assert_eq!(list[7]["dof"], 9);
    // The two UR5s name their frames: the DH base, and the URDF's base_link.
    assert!(list[1]["frames"]
        .as_str()
        .unwrap()
        .starts_with("DH base frame"));
    assert!(list[2]["frames"]
        .as_str()
        .unwrap()
        .starts_with("the UR URDF's base_link"));
    // Same configuration, same pose as the URDF, and ur5's turned 180 deg.
    let pose = |args: &[&str]| {
        let value = json(&armkit(args));
        serde_json::from_value::<Vec<f64>>(value["position"].clone()).unwrap()
    };
    let q = "0.3,-1.1,0.9,-0.4,1.2,0.5";
    let builtin = pose(&["fk", "--robot", "ur5-urdf", "--q", q, "--json"]);
    let urdf = pose(&[
        "fk",
        "--urdf",
        "tests/data/urdf/ur5.urdf",
        "--base",
        "base_link",
        "--tip",
        "tool0",
        "--q",
        q,
        "--json",
    ]);
    let dh = pose(&["fk", "--robot", "ur5", "--q", q, "--json"]);
    for k in 0..3 {
        assert!((builtin[k] - urdf[k]).abs() < 1e-9, "{builtin:?} {urdf:?}");
    }
    assert!((builtin[0] + dh[0]).abs() < 1e-9 && (builtin[1] + dh[1]).abs() < 1e-9);
}

#[test]
fn fk_and_jacobian_json_match_the_reference() {
    for (robot, file) in [
        ("puma560", "reference_puma560_dh.json"),
        ("stanford", "reference_stanford_dh.json"),
    ] {
        let (q, pose, jac) = first_sample(file);
        let fk = json(&armkit(&["fk", "--robot", robot, "--q", &q, "--json"]));
        assert!(max_difference(&fk["pose"], &pose) < 1e-12, "{robot}");
        let j = json(&armkit(&[
            "jacobian", "--robot", robot, "--q", &q, "--json",
        ]));
        assert!(max_difference(&j["jacobian"], &jac) < 1e-9, "{robot}");
    }
}

#[test]
fn robot_file_takes_a_reference_json() {
    let (q, pose, _) = first_sample("reference_panda_mdh_rtb.json");
    let fk = json(&armkit(&[
        "fk",
        "--robot-file",
        "tests/data/reference_panda_mdh_rtb.json",
        "--q",
        &q,
        "--json",
    ]));
    assert!(max_difference(&fk["pose"], &pose) < 1e-12);
}

#[test]
fn text_output_gives_matrix_position_and_rpy() {
    let output = armkit(&["fk", "--robot", "ur5", "--q", "0,0,0,0,0,0"]);
    assert!(output.status.success());
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(text.contains("position (m):"), "{text}");
    assert!(text.contains("roll pitch yaw"), "{text}");
}

#[test]
fn bad_input_is_a_one_line_error_with_a_non_zero_exit() {
    let cases: [(&[&str], &str); 6] = [
        (&["fk", "--robot", "ur5", "--q", "0,0,0"], "error: --q: expected 6 values, got 3"),
        (&["fk", "--robot", "ur5", "--q", "0,0,zero,0,0,0"], "error: --q: value 3: `zero` is not a number"),
        (&["fk", "--robot", "r2d2", "--q", "0"], "error: unknown robot `r2d2`; the built-in robots are: puma560, ur5, ur5-urdf, panda, stanford, arm4, space6r, gantry9, gantry9-flex"),
        (
            &["fk", "--robot", "panda", "--q", "0,0,0,0,0,0,0"],
            "error: joint 3 (`q4`) = 0 is outside its limits [-3.0718, -0.0698] (pass --allow-out-of-limits to evaluate anyway)",
        ),
        (&["fk", "--robot-file", "no/such/file.toml", "--q", "0"], "error: no/such/file.toml: cannot read the file"),
        (&["jacobian", "--q", "0"], "error: no robot given: use --robot NAME, --robot-file PATH or --urdf PATH"),
    ];
    for (args, expected) in cases {
        let output = armkit(args);
        assert!(!output.status.success(), "{args:?} succeeded");
        let message = stderr(&output);
        assert!(message.starts_with(expected), "{args:?}: got {message:?}");
        assert_eq!(message.lines().count(), 1, "{message}");
    }
}

#[test]
fn out_of_limits_is_allowed_on_request() {
    let output = armkit(&[
        "fk",
        "--robot",
        "panda",
        "--q",
        "0,0,0,0,0,0,0",
        "--allow-out-of-limits",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn malformed_description_file_is_an_error() {
    let dir = std::env::temp_dir().join(format!("armkit-cli-fk-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.toml");
    std::fs::write(
        &path,
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = \"oops\"\na = 0.0\nalpha = 0.0\n",
    )
    .unwrap();
    let output = armkit(&["fk", "--robot-file", path.to_str().unwrap(), "--q", "0"]);
    let message = stderr(&output);
    assert!(!output.status.success());
    assert!(
        message.contains("bad.toml") && message.contains("line 4"),
        "{message}"
    );
}

#[test]
fn a_value_starting_with_a_minus_sign_needs_no_equals_sign() {
    let spaced = armkit(&["fk", "--robot", "ur5", "--q", "-0.5,0.1,0,0,0,0", "--json"]);
    assert!(spaced.status.success(), "{}", stderr(&spaced));
    let joined = armkit(&["fk", "--robot", "ur5", "--q=-0.5,0.1,0,0,0,0", "--json"]);
    assert_eq!(json(&spaced), json(&joined));
}

#[test]
fn a_closed_output_pipe_ends_the_command_quietly() {
    // `armkit fk ... | head -c 0`: the reader is gone before armkit writes.
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_armkit"))
        .args(["fk", "--robot", "ur5", "--q", "0,0,0,0,0,0"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_ne!(output.status.code(), Some(101), "{stderr}");
}
