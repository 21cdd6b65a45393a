//! `armkit ik` and `armkit bench-ik`, run as a user would.

mod common;
use common::*;

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Pose;

fn urdf(name: &str) -> String {
    format!(
        "{}/../../tests/data/urdf/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// The pose argument "x,y,z,roll,pitch,yaw" of FK(q).
fn pose_argument(robot: &str, q: &[f64]) -> (String, Pose) {
    let model = armkit::robots::by_name(robot).unwrap();
    let mut data = Data::new(&model);
    let pose = *forward_kinematics(&model, &mut data, q).unwrap();
    let (r, p, y) = pose.rpy();
    let t = pose.translation;
    // 17 significant digits: the pose round-trips to ~1e-16.
    let text = format!(
        "{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e}",
        t.x, t.y, t.z, r, p, y
    );
    (text, Pose::from_xyz_rpy([t.x, t.y, t.z], [r, p, y]))
}

fn q_of(value: &serde_json::Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

fn fk_error(robot: &str, q: &[f64], target: &Pose) -> f64 {
    let model = armkit::robots::by_name(robot).unwrap();
    let mut data = Data::new(&model);
    let pose = forward_kinematics(&model, &mut data, q).unwrap();
    let e = armkit::ik::pose_error(target, pose);
    e.fixed_rows::<3>(0).norm().max(e.fixed_rows::<3>(3).norm())
}

#[test]
fn numeric_ik_json_reaches_the_pose() {
    let (pose, target) = pose_argument("ur5", &[0.4, -1.1, 1.3, -0.6, 1.4, 0.2]);
    for solver in ["lm", "nr", "dls", "sri"] {
        let output = armkit(&[
            "ik", "--robot", "ur5", "--pose", &pose, "--solver", solver, "--json",
        ]);
        assert!(output.status.success(), "{solver}: {}", stderr(&output));
        let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        assert_eq!(json["status"], "converged");
        assert_eq!(json["solver"], solver);
        let q = q_of(&json["q"]);
        assert_eq!(q.len(), 6);
        assert!(fk_error("ur5", &q, &target) <= 1e-6);
        assert!(json["position_error"].as_f64().unwrap() <= 1e-6);
        assert!(json["iterations"].as_u64().is_some());
    }
}

#[test]
fn numeric_ik_text_shows_the_report() {
    let (pose, _) = pose_argument("panda", &[0.3, -0.4, 0.2, -2.0, 0.1, 1.8, 0.5]);
    let output = armkit(&[
        "ik",
        "--robot",
        "panda",
        "--pose",
        &pose,
        "--start",
        "0,0,0,-1.5,0,1.5,0",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("panda: inverse kinematics (lm)"), "{text}");
    assert!(text.contains("status: converged"), "{text}");
    assert!(
        text.contains("iterations:") && text.contains("restarts:"),
        "{text}"
    );
}

#[test]
fn unreachable_target_exits_3_with_the_best_effort() {
    let output = armkit(&["ik", "--robot", "ur5", "--pose", "3,0,0.3,0,0,0", "--json"]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["status"], "not_converged");
    let q = q_of(&json["q"]);
    let model = armkit::robots::by_name("ur5").unwrap();
    model.check_limits(&q).unwrap();
    assert!(json["position_error"].as_f64().unwrap() > 1.5);
}

#[test]
fn closed_form_lists_every_solution() {
    let q0 = [0.3, 0.6, -1.9, 0.4, 0.8, -0.5];
    let (pose, target) = pose_argument("puma560", &q0);
    let start = "0.3,0.6,-1.9,0.4,0.8,-0.5";
    let output = armkit(&[
        "ik",
        "--robot",
        "puma560",
        "--pose",
        &pose,
        "--solver",
        "closed-form",
        "--start",
        start,
        "--json",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["status"], "converged");
    let solutions = json["solutions"].as_array().unwrap();
    assert!(solutions.len() >= 2, "{json}");
    for s in solutions {
        assert!(fk_error("puma560", &q_of(s), &target) <= 1e-9);
    }
    // q is the nearest solution: the start itself.
    let q = q_of(&json["q"]);
    for (a, b) in q.iter().zip(q0) {
        assert!((a - b).abs() < 1e-6);
    }
    let text = stdout(&armkit(&[
        "ik",
        "--robot",
        "puma560",
        "--pose",
        &pose,
        "--solver",
        "closed-form",
        "--start",
        start,
    ]));
    assert!(
        text.contains("solution(s) within the joint limits"),
        "{text}"
    );
    assert!(text.contains("1: [") && text.contains("exact"), "{text}");
}

#[test]
fn closed_form_on_an_unfit_robot_is_an_error() {
    let output = armkit(&[
        "ik",
        "--robot",
        "panda",
        "--pose",
        "0.4,0,0.5,0,0,0",
        "--solver",
        "closed-form",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("`panda` has no closed-form solver"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn bad_arguments_are_named() {
    let output = armkit(&["ik", "--robot", "ur5", "--pose", "1,2,3"]);
    assert_eq!(stderr(&output), "error: --pose: expected 6 values, got 3");
    let output = armkit(&[
        "ik",
        "--robot",
        "ur5",
        "--pose",
        "0.3,0,0.3,0,0,0",
        "--start",
        "0,0",
    ]);
    assert_eq!(stderr(&output), "error: --start: expected 6 values, got 2");
}

#[test]
fn urdf_robot_is_solved() {
    let model = armkit::urdf::load(
        urdf("iiwa14.urdf"),
        &armkit::urdf::ChainSelection::between("base_link", "tool0"),
    )
    .unwrap();
    let mut data = Data::new(&model);
    let pose =
        *forward_kinematics(&model, &mut data, &[0.2, 0.5, -0.3, -1.2, 0.4, 0.8, 0.1]).unwrap();
    let (r, p, y) = pose.rpy();
    let t = pose.translation;
    let text = format!(
        "{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e}",
        t.x, t.y, t.z, r, p, y
    );
    let path = urdf("iiwa14.urdf");
    let output = armkit(&[
        "ik",
        "--urdf",
        &path,
        "--base",
        "base_link",
        "--tip",
        "tool0",
        "--pose",
        &text,
        "--json",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["status"], "converged");
    assert_eq!(q_of(&json["q"]).len(), 7);
}

#[test]
fn bench_ik_prints_the_table() {
    let output = armkit(&[
        "bench-ik",
        "--robot",
        "ur5",
        "--targets",
        "40",
        "--solver",
        "lm,closed-form",
    ]);
    // ur5 has no closed-form solver: the error names it.
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("no closed-form solver"));
    let output = armkit(&[
        "bench-ik",
        "--robot",
        "puma560",
        "--targets",
        "40",
        "--solver",
        "lm,closed-form,dls",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.contains("| robot | solver | success | mean (us) | median (us) | p99 (us)"),
        "{text}"
    );
    assert!(
        text.contains("| puma560 | lm | 100.00 % (40/40) |"),
        "{text}"
    );
    assert!(
        text.contains("| puma560 | closed-form | 100.00 % (40/40) |"),
        "{text}"
    );
    assert!(text.contains("| puma560 | dls |"), "{text}");
    let output = armkit(&[
        "bench-ik",
        "--robot",
        "gantry9",
        "--targets",
        "30",
        "--json",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let row = &json["rows"][0];
    assert_eq!(row["solver"], "lm");
    assert_eq!(row["success_rate"].as_f64().unwrap(), 1.0);
    assert!(row["p99_us"].as_f64().unwrap() >= row["median_us"].as_f64().unwrap());
}
