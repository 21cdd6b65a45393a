//! `armkit mpc`, run as a user would.

mod common;
use common::*;

use std::process::Output;

fn json(output: &Output) -> serde_json::Value {
    serde_json::from_slice(&output.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}); stderr: {}", stderr(output)))
}

#[test]
fn gantry9_reaches_a_target_and_reports_json() {
    let dir = scratch("gantry");
    let out = dir.to_str().unwrap();
    let output = armkit(&[
        "mpc",
        "--robot",
        "gantry9",
        "--target",
        "4,2,4.5,pi,0,0",
        "--start",
        "5,2,1,0,0.3,0.3,0,0.5,0",
        "--horizon",
        "10",
        "--control-horizon",
        "2",
        "--dt",
        "0.05",
        "--weights",
        "position",
        "--out",
        out,
        "--json",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let v = json(&output);
    assert_eq!(v["converged"], true);
    assert!(v["final_position_error"].as_f64().unwrap() <= 1e-4);
    assert_eq!(v["max_velocity_violation"].as_f64().unwrap(), 0.0);
    assert_eq!(v["max_position_violation"].as_f64().unwrap(), 0.0);
    let steps = v["steps"].as_u64().unwrap();
    assert!(steps > 10 && steps < 2000, "{steps}");
    // CSV: header, then one row per step plus the final state.
    let csv = std::fs::read_to_string(dir.join("mpc.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("t_s,q_q1,"), "{header}");
    assert!(header.ends_with("status,qp_iterations"), "{header}");
    assert_eq!(lines.count() as u64, steps + 1);
    for name in [
        "end_effector",
        "rotary_velocities",
        "rotary_angles",
        "prismatic_velocities",
        "prismatic_positions",
    ] {
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
        assert!(svg.starts_with("<svg"), "{name}");
    }
}

#[test]
fn an_unreachable_target_exits_3_without_crossing_a_limit() {
    let output = armkit(&[
        "mpc",
        "--robot",
        "ur5",
        "--target",
        "3,0,0,0,0,0",
        "--weights",
        "position",
        "--max-steps",
        "150",
        "--json",
    ]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let v = json(&output);
    assert_eq!(v["converged"], false);
    assert!(v["final_position_error"].as_f64().unwrap() > 1.0);
    assert_eq!(v["max_velocity_violation"].as_f64().unwrap(), 0.0);
    assert_eq!(v["max_position_violation"].as_f64().unwrap(), 0.0);
}

#[test]
fn seed000_examples_print_their_checks() {
    let output = armkit(&["mpc", "--example", "all", "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let v = json(&output);
    let examples = v["examples"].as_array().unwrap();
    let ids: Vec<&str> = examples.iter().map(|e| e["id"].as_str().unwrap()).collect();
    assert_eq!(
        ids,
        ["ex1", "ex2", "ex2-paper-weights", "ex3", "ex3-undamped"]
    );
    for e in examples {
        for check in e["checks"].as_array().unwrap() {
            assert_eq!(check["passed"], true, "{}: {}", e["id"], check);
        }
    }
    let text = armkit(&["mpc", "--example", "2"]);
    assert!(text.status.success());
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert!(
        stdout.contains("[pass] prismatic joints travel less than 1 mm"),
        "{stdout}"
    );
    assert!(stdout.contains("orientation not tracked"), "{stdout}");
}

#[test]
fn bad_arguments_are_named() {
    let output = armkit(&["mpc", "--robot", "ur5", "--target", "1,2,3"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("--target: expected 6 values, got 3"),
        "{}",
        stderr(&output)
    );
    let output = armkit(&[
        "mpc",
        "--robot",
        "ur5",
        "--target",
        "0.3,0,0.3,0,0,0",
        "--control-horizon",
        "12",
    ]);
    assert!(
        stderr(&output).contains("control_horizon"),
        "{}",
        stderr(&output)
    );
    let output = armkit(&["mpc", "--example", "7"]);
    assert!(
        stderr(&output).contains("unknown example `7`"),
        "{}",
        stderr(&output)
    );
    let output = armkit(&[
        "mpc",
        "--robot",
        "ur5",
        "--target",
        "0.3,0,0.3,0,0,0",
        "--priorities",
        "1,1",
    ]);
    assert!(
        stderr(&output).contains("--priorities: expected 6 values, got 2"),
        "{}",
        stderr(&output)
    );
}
