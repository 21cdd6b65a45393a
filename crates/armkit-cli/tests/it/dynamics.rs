//! The `dynamics` command, run as a user would: its JSON equals Pinocchio's
//! reference values on the panda URDF, and the text form names every term.

use crate::common::*;

fn join(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| format!("{v:.17e}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn max_difference(a: &serde_json::Value, b: &serde_json::Value) -> f64 {
    let flatten = |v: &serde_json::Value| -> Vec<f64> {
        match v.as_array().unwrap().first() {
            Some(serde_json::Value::Array(_)) => {
                let rows: Vec<Vec<f64>> = serde_json::from_value(v.clone()).unwrap();
                rows.concat()
            }
            _ => serde_json::from_value(v.clone()).unwrap(),
        }
    };
    let (a, b) = (flatten(a), flatten(b));
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs() / (1.0 + y.abs()))
        .fold(0.0, f64::max)
}

#[test]
fn json_equals_pinocchio_on_the_panda_urdf() {
    let path = format!(
        "{}/../../tests/data/reference_dynamics_panda.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let sample = &reference["samples"][3];
    let vector = |key: &str| -> Vec<f64> { serde_json::from_value(sample[key].clone()).unwrap() };
    let (q, v, a, tau) = (vector("q"), vector("v"), vector("a"), vector("tau_in"));
    let output = armkit(&[
        "dynamics",
        "--urdf",
        "tests/data/urdf/panda.urdf",
        "--base",
        "panda_link0",
        "--tip",
        "panda_link8",
        "--q",
        &join(&q),
        "--v",
        &join(&v),
        "--a",
        &join(&a),
        "--tau",
        &join(&tau),
        "--json",
    ]);
    let result = json(&output);
    for key in ["tau", "mass_matrix", "gravity", "coriolis", "ddq"] {
        let error = max_difference(&result[key], &sample[key]);
        assert!(error < 1e-9, "{key}: off by {error:e}");
    }
}

#[test]
fn text_names_every_term_and_ddq_only_with_tau() {
    let q = ["--q", "0.1,-0.4,0.8,0.2,0.5,-0.3"];
    let output = armkit(&[&["dynamics", "--robot", "space6r"], &q[..]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    for term in [
        "tau = M(q) a",
        "mass matrix M(q) (6 x 6)",
        "gravity torques g(q)",
        "C(q, v) v",
    ] {
        assert!(text.contains(term), "{term} missing from\n{text}");
    }
    assert!(!text.contains("ABA"), "{text}");
    let output = armkit(
        &[
            &[
                "dynamics",
                "--robot",
                "space6r",
                "--tau",
                "0,0,0,0,0,0",
                "--json",
            ],
            &q[..],
        ]
        .concat(),
    );
    let result = json(&output);
    // Motors off under gravity: the arm falls.
    assert!(result["ddq"]
        .as_array()
        .unwrap()
        .iter()
        .any(|x| x.as_f64().unwrap().abs() > 1e-3));
    let output = armkit(
        &[
            &[
                "dynamics",
                "--robot",
                "space6r",
                "--tau",
                "0,0,0,0,0,0",
                "--gravity",
                "0,0,0",
                "--json",
            ],
            &q[..],
        ]
        .concat(),
    );
    let result = json(&output);
    // Gravity off, at rest, no torque: no acceleration.
    let ddq: Vec<f64> = serde_json::from_value(result["ddq"].clone()).unwrap();
    assert!(ddq.iter().all(|x| x.abs() < 1e-12), "{ddq:?}");
    let gravity: Vec<f64> = serde_json::from_value(result["gravity"].clone()).unwrap();
    assert!(gravity.iter().all(|x| x.abs() < 1e-12), "{gravity:?}");
}

const PANDA_MOVE: [&str; 12] = [
    "traj",
    "joint",
    "--urdf",
    "tests/data/urdf/panda.urdf",
    "--base",
    "panda_link0",
    "--tip",
    "panda_link8",
    "--from",
    "0,-0.5,0,-2,0,1.5,0",
    "--to",
    "1.5,0.5,-1,-1,1,2.5,1",
];

#[test]
fn traj_reports_torques_and_fits_them_to_the_urdf_effort_limits() {
    let args = [
        &PANDA_MOVE[..],
        &["--duration", "0.3", "--torques", "--json"],
    ]
    .concat();
    let summary = json(&armkit(&args));
    assert_eq!(summary["torques"]["status"], "exceeds-limits");
    let peaks = summary["torques"]["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 7);
    assert_eq!(peaks[0]["limit"], 87.0);
    assert!(peaks[0]["ratio"].as_f64().unwrap() > 1.0);

    let dir = scratch("torque-plots");
    let plots = dir.to_str().unwrap();
    let args = [
        &PANDA_MOVE[..],
        &[
            "--duration",
            "0.3",
            "--fit-torque-limits",
            "--plots",
            plots,
            "--json",
        ],
    ]
    .concat();
    // The fit meets the effort limits, but the slowed move is still faster
    // than the Panda's velocity limits: exit 3, said on stderr.
    let (summary, reason) = json_unmet(&armkit(&args));
    assert!(reason.contains("velocity limits not met"), "{reason}");
    let torques = &summary["torques"];
    assert_eq!(torques["status"], "exceeds-velocity-limits");
    let factor = torques["time_scaling_factor"].as_f64().unwrap();
    assert!(factor > 1.0);
    let duration = summary["duration_s"].as_f64().unwrap();
    assert!(
        (duration - 0.3 * factor).abs() < 1e-9,
        "{duration} vs {factor}"
    );
    let worst = torques["peaks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["ratio"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert!(worst <= 1.0 && worst > 0.999, "{worst}");
    let svg = std::fs::read_to_string(dir.join("torques.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("joint torques"));
}

#[test]
fn coupled_models_work_in_their_independent_joints() {
    // mimicbot's finger: 9 chain joints, 7 independent (a mimic of a mimic).
    let q = "0.1,-0.4,0.8,0.2,0.5,-0.3,0.3";
    let output = armkit(&[
        "dynamics",
        "--urdf",
        "tests/data/urdf/mimicbot.urdf",
        "--base",
        "base",
        "--tip",
        "fingertip",
        "--q",
        q,
        "--v",
        "0.2,0.1,-0.3,0.4,0,0.1,0.5",
        "--a",
        "1,-0.5,0.3,0,0.2,0.1,-1",
        "--tau",
        "1,2,3,0.5,0.2,0.1,0.01",
        "--json",
    ]);
    let result = json(&output);
    for key in ["tau", "gravity", "coriolis", "ddq"] {
        assert_eq!(result[key].as_array().unwrap().len(), 7, "{key}");
    }
    assert_eq!(result["mass_matrix"].as_array().unwrap().len(), 7);
    // The flexible gantry: its dynamics in its independent joints.
    let output = armkit(&[
        "dynamics",
        "--robot",
        "gantry9-flex",
        "--q",
        "1,2,0.5,0,0,0,0,0,0",
        "--v",
        "0,1,0,0,0,0,0,0,0",
        "--json",
    ]);
    let result = json(&output);
    assert_eq!(result["tau"].as_array().unwrap().len(), 9);
}

/// The chain and the first two samples of `reference_dynamics_<chain>.json`
/// (Pinocchio on a published URDF).
fn published(chain: &str) -> (Vec<String>, Vec<serde_json::Value>) {
    let path = format!(
        "{}/../../tests/data/reference_dynamics_{chain}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let text = |key: &str| reference[key].as_str().unwrap().to_string();
    let args = vec![
        "dynamics".to_string(),
        "--urdf".to_string(),
        format!("tests/data/{}", text("urdf")),
        "--base".to_string(),
        text("base"),
        "--tip".to_string(),
        text("tip"),
    ];
    (args, reference["samples"].as_array().unwrap()[..2].to_vec())
}

#[test]
fn singular_mass_matrix_gives_inverse_dynamics_and_refuses_forward_dynamics() {
    // The AL5D's point masses lie on the joint axes: M is singular at every
    // configuration (q = 0 and another).
    let (chain, samples) = published("al5d");
    for sample in &samples {
        let vector =
            |key: &str| -> Vec<f64> { serde_json::from_value(sample[key].clone()).unwrap() };
        let state = [
            "--q".to_string(),
            join(&vector("q")),
            "--v".to_string(),
            join(&vector("v")),
            "--a".to_string(),
            join(&vector("a")),
        ];
        let args: Vec<&str> = chain.iter().chain(&state).map(String::as_str).collect();
        let result = json(&armkit(&[&args[..], &["--json"]].concat()));
        for key in ["tau", "mass_matrix", "gravity"] {
            let error = max_difference(&result[key], &sample[key]);
            assert!(error < 1e-9, "{key}: off by {error:e}");
        }
        for json_flag in [&[][..], &["--json"][..]] {
            let output = armkit(&[&args[..], &["--tau", "0.1,0.1,0.1,0.1"], json_flag].concat());
            assert_eq!(output.status.code(), Some(1), "{}", stdout(&output));
            assert!(stdout(&output).is_empty(), "{}", stdout(&output));
            let message = stderr(&output);
            assert_eq!(message.lines().count(), 1, "{message}");
            assert!(
                message.contains("the mass matrix is singular at joint 3 (`j4`)"),
                "{message}"
            );
        }
    }
}

#[test]
fn massless_links_between_joints_have_dynamics() {
    // The human model's leg: massless links between the hip's and the
    // ankle's joints, M positive definite.
    let (chain, samples) = published("human_leg");
    let sample = &samples[1];
    let vector = |key: &str| -> Vec<f64> { serde_json::from_value(sample[key].clone()).unwrap() };
    let state = [
        "--q".to_string(),
        join(&vector("q")),
        "--v".to_string(),
        join(&vector("v")),
        "--a".to_string(),
        join(&vector("a")),
        "--tau".to_string(),
        join(&vector("tau")),
        "--json".to_string(),
    ];
    let args: Vec<&str> = chain.iter().chain(&state).map(String::as_str).collect();
    let result = json(&armkit(&args));
    for key in ["tau", "mass_matrix", "gravity"] {
        let error = max_difference(&result[key], &sample[key]);
        assert!(error < 1e-9, "{key}: off by {error:e}");
    }
    // Forward dynamics undoes inverse dynamics.
    let error = max_difference(&result["ddq"], &sample["a"]);
    assert!(error < 1e-9, "ddq: off by {error:e}");
}
