//! `armkit mpc`, run as a user would.

use crate::common::*;

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
    // The cause, on stderr and in the JSON.
    assert!(
        stderr(&output).contains("not converged: unreachable: no configuration within the joint limits reaches the target"),
        "{}",
        stderr(&output)
    );
    let v = json(&output);
    assert_eq!(v["converged"], false);
    assert_eq!(v["status"], "unreachable");
    assert!(v["status_detail"]
        .as_str()
        .unwrap()
        .starts_with("unreachable"));
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
        [
            "ex1",
            "ex1-rigid-model",
            "ex1-link-error",
            "ex2",
            "ex2-paper-weights",
            "ex2-strict",
            "ex3",
            "ex3-undamped"
        ]
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

/// With 1 mm prismatic resolution Example 3 keeps oscillating (its checks
/// say so and pass) and its finding is reproduced with a deviation; on the
/// exact plant the same finding is not reproduced. Bad plant flags name
/// the flag.
#[test]
fn prismatic_resolution_makes_example_3_oscillate() {
    let finding = |v: &serde_json::Value| -> String {
        v["examples"][0]["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["claim"].as_str().unwrap().contains("keeps oscillating"))
            .map(|f| f["status"].as_str().unwrap().to_string())
            .unwrap()
    };
    let output = armkit(&[
        "mpc",
        "--example",
        "3",
        "--prismatic-resolution",
        "0.001",
        "--json",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let v = json(&output);
    let e = &v["examples"][0];
    assert_eq!(
        e["plant"],
        "prismatic joints: position resolution 1 mm; rotary joints: exact"
    );
    assert_eq!(e["converged"], false);
    let checks = e["checks"].as_array().unwrap();
    assert!(checks.iter().all(|c| c["passed"] == true), "{checks:?}");
    assert!(checks
        .iter()
        .any(|c| c["name"].as_str().unwrap().starts_with("keeps oscillating")));
    assert_eq!(finding(&v), "reproduced with deviation");
    let exact = json(&armkit(&["mpc", "--example", "3", "--json"]));
    assert_eq!(exact["examples"][0]["plant"], "exact plant (q += T u)");
    assert_eq!(finding(&exact), "not reproduced");
    for (flag, value) in [
        ("--prismatic-resolution", "-1"),
        ("--prismatic-deadband", "inf"),
    ] {
        let output = armkit(&["mpc", "--example", "2", flag, value]);
        assert_eq!(output.status.code(), Some(1));
        assert!(
            stderr(&output).contains(&format!("{flag}: must be finite and >= 0")),
            "{}",
            stderr(&output)
        );
    }
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

#[test]
fn json_reports_solve_times_and_the_solver_for_m_1_and_5() {
    for solver in ["active-set", "clarabel"] {
        for m in ["1", "5"] {
            let output = armkit(&[
                "mpc",
                "--example",
                "1",
                "--control-horizon",
                m,
                "--solver",
                solver,
                "--json",
            ]);
            assert!(output.status.success(), "{}", stderr(&output));
            let v = json(&output);
            let e = &v["examples"][0];
            assert_eq!(e["solver"], solver);
            assert_eq!(e["control_horizon"].as_u64().unwrap().to_string(), m);
            assert_eq!(e["fallback_solves"], 0);
            let times = &e["solve_time_us"];
            let (median, p99, max) = (
                times["median"].as_f64().unwrap(),
                times["p99"].as_f64().unwrap(),
                times["max"].as_f64().unwrap(),
            );
            assert!(
                median > 0.0 && median <= p99 && p99 <= max,
                "{solver} M={m}: {times}"
            );
            // Every planner step was timed (the hold steps included).
            assert_eq!(
                times["steps"].as_u64().unwrap(),
                e["steps"].as_u64().unwrap() + 20
            );
            for check in e["checks"].as_array().unwrap() {
                assert_eq!(check["passed"], true, "{solver} M={m}: {check}");
            }
        }
    }
}

#[test]
fn a_target_the_plain_planner_misses_is_reached_with_the_goal_posture() {
    // A full-pose Panda target (the FK of a configuration within the
    // limits) that seed 000's plain planner does not reach from mid-range:
    // it stops against a joint limit and says which; the default goal
    // posture reaches it.
    let target = "-0.364789,0.167542,1.190217,-0.172271,0.626948,1.715823";
    let plain = armkit(&[
        "mpc", "--robot", "panda", "--target", target, "--reach", "off", "--json",
    ]);
    assert_eq!(plain.status.code(), Some(3), "{}", stderr(&plain));
    let v = json(&plain);
    assert_eq!(v["status"], "joint-limit", "{v}");
    assert!(
        stderr(&plain).contains("joint limit: stopped at the"),
        "{}",
        stderr(&plain)
    );
    let helped = armkit(&["mpc", "--robot", "panda", "--target", target, "--json"]);
    assert!(helped.status.success(), "{}", stderr(&helped));
    let v = json(&helped);
    assert_eq!(v["status"], "converged");
    assert_eq!(v["reach"], "goal-posture");
    assert_eq!(v["max_position_violation"].as_f64().unwrap(), 0.0);
    assert_eq!(v["max_velocity_violation"].as_f64().unwrap(), 0.0);
}

/// Every flag that would change a seed 000 example's own settings is
/// refused with `--example`, naming the flag (never silently ignored).
#[test]
fn example_refuses_the_flags_it_would_ignore() {
    for (flag, value) in [
        ("--dt", "0.01"),
        ("--velocity-weight", "0"),
        ("--priorities", "1,1,1,1,1,1,1,1,1"),
        ("--horizon", "5"),
        ("--weights", "pose"),
        ("--terminal-factor", "5"),
        ("--start", "2,0.89,0.76,1.57,0.5,0.5,0,0.5,0"),
        ("--priority-mode", "strict"),
    ] {
        let output = armkit(&["mpc", "--example", "2", flag, value]);
        assert!(!output.status.success(), "{flag} accepted");
        let err = stderr(&output);
        assert!(
            err.contains(flag) && err.contains("--example"),
            "{flag}: {err}"
        );
    }
}

/// `--priority-mode strict` on the user's robot: the rotary joints (R = 1)
/// first, the prismatic ones (R = 10, 100) for what remains; the run
/// reaches the target within the limits, and the solver says it is strict.
#[test]
fn strict_priority_runs_on_a_target() {
    let run = |mode: &str| {
        let output = armkit(&[
            "mpc",
            "--robot",
            "gantry9",
            "--target",
            "2,1.8,4.5,0,0,0",
            "--start",
            "2,0.89,0.76,1.5708,0.5,0.5,0,0.5,0",
            "--weights",
            "position",
            "--priorities",
            "100,10,10,1,1,1,1,1,1",
            "--reach",
            "off",
            "--priority-mode",
            mode,
            "--json",
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        json(&output)
    };
    let strict = run("strict");
    assert_eq!(strict["converged"], true);
    assert_eq!(strict["solver"], "active-set (strict priority)");
    assert_eq!(strict["max_velocity_violation"].as_f64().unwrap(), 0.0);
    assert_eq!(run("weighted")["solver"], "active-set");
    let bad = armkit(&[
        "mpc",
        "--robot",
        "gantry9",
        "--target",
        "2,1.8,4.5,0,0,0",
        "--priority-mode",
        "lexical",
    ]);
    assert!(!bad.status.success());
    assert!(stderr(&bad).contains("--priority-mode"), "{}", stderr(&bad));
}

/// Model mismatch on the user's robot: planned on gantry9 (rigid beam)
/// while gantry9-flex moves, and planned with links 5 % too long; both
/// reach the target on the plant within the tolerance. Bad values name
/// the flag.
#[test]
fn a_planner_model_that_is_not_the_plant_still_reaches_the_target() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "mpc",
            "--robot",
            "gantry9",
            "--target",
            "4,5.5,4.5,0,0,0",
            "--start",
            "2,0.89,0.76,1.5708,0.5,0.5,0,0.5,0",
            "--weights",
            "position",
            "--reach",
            "off",
            "--json",
        ];
        args.extend_from_slice(extra);
        armkit(&args)
    };
    for extra in [
        &["--plant-robot", "gantry9-flex"][..],
        &["--link-length-error", "0.05"][..],
        &[
            "--link-length-error",
            "-0.05",
            "--plant-robot",
            "gantry9-flex",
        ][..],
    ] {
        let output = run(extra);
        assert!(output.status.success(), "{extra:?}: {}", stderr(&output));
        let v = json(&output);
        assert_eq!(v["converged"], true, "{extra:?}");
        assert!(
            v["final_position_error"].as_f64().unwrap() <= 1e-4,
            "{extra:?}"
        );
    }
    for (extra, message) in [
        (
            &["--plant-robot", "panda"][..],
            "--plant-robot: panda has 7 joints",
        ),
        (
            &["--link-length-error", "-1"][..],
            "--link-length-error: must be finite and > -1",
        ),
        (&["--plant-robot", "nosuchbot"][..], "nosuchbot"),
    ] {
        let output = run(extra);
        assert!(!output.status.success(), "{extra:?} accepted");
        assert!(
            stderr(&output).contains(message),
            "{extra:?}: {}",
            stderr(&output)
        );
    }
    let output = armkit(&["mpc", "--example", "1", "--plant-robot", "gantry9"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("--plant-robot"),
        "{}",
        stderr(&output)
    );
}
