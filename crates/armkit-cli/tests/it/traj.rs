//! `armkit traj`, run as a user would.

use crate::common::*;

/// Rows of a CSV file as numbers, after checking the header.
fn read_csv(path: &std::path::Path, header: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), header);
    lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

const PANDA_FROM: &str = "0,-0.3,0,-2.2,0,2,0.8";
const PANDA_TO: &str = "1,0.4,-0.5,-1.2,0.7,1.2,-0.3";

#[test]
fn joint_trapezoid_writes_csv_and_plots() {
    let dir = scratch("joint");
    let csv = dir.join("traj.csv");
    let plots = dir.join("plots");
    let output = armkit(&[
        "traj",
        "joint",
        "--robot",
        "arm4",
        "--from",
        "0,0,0,0",
        "--to",
        "1,-0.5,pi/2,0.2",
        "--profile",
        "trapezoidal",
        "--duration",
        "2",
        "--accel-time",
        "0.5",
        "--dt",
        "0.1",
        "--csv",
        csv.to_str().unwrap(),
        "--plots",
        plots.to_str().unwrap(),
        "--json",
    ]);
    let summary = json(&output);
    assert_eq!(summary["duration_s"], 2.0);
    assert_eq!(summary["segments"], 3);
    let header = "t,q1,q2,q3,q4,qd1,qd2,qd3,qd4,qdd1,qdd2,qdd3,qdd4,x,y,z,roll,pitch,yaw";
    let rows = read_csv(&csv, header);
    assert_eq!(rows.len(), 21);
    let last = rows.last().unwrap();
    assert_eq!(last[0], 2.0);
    let goal = [1.0, -0.5, std::f64::consts::FRAC_PI_2, 0.2];
    for j in 0..4 {
        assert!((last[1 + j] - goal[j]).abs() < 1e-12);
        assert!(last[5 + j].abs() < 1e-12, "ends at rest");
    }
    // Cruise velocity d / (T - ta) at t = 1 s.
    assert!((rows[10][5] - 1.0 / 1.5).abs() < 1e-12);
    // The pose columns are forward kinematics: arm4 at q = 0 puts the tool at (0.08, -0.45, 0.3).
    assert!(
        (rows[0][13] - 0.08).abs() < 1e-12
            && (rows[0][14] + 0.45).abs() < 1e-12
            && (rows[0][15] - 0.3).abs() < 1e-12
    );
    for name in ["positions", "velocities", "accelerations"] {
        let svg = std::fs::read_to_string(plots.join(format!("{name}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("joint 4"), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn joint_minimum_time_respects_the_robot_limits() {
    for profile in ["trapezoidal", "cubic", "quintic"] {
        let output = armkit(&[
            "traj",
            "joint",
            "--robot",
            "panda",
            "--from",
            PANDA_FROM,
            "--to",
            PANDA_TO,
            "--profile",
            profile,
            "--json",
        ]);
        let summary = json(&output);
        assert_eq!(summary["minimum_time"], true);
        assert!(
            summary["limit_violations"].as_array().unwrap().is_empty(),
            "{profile}"
        );
        let duration = summary["duration_s"].as_f64().unwrap();
        assert!(duration > 0.3 && duration < 2.0, "{profile}: {duration}");
        // Joint 1 moves 1 rad at most 2.175 rad/s: peak velocity within.
        let peak = summary["peak_velocity"][0].as_f64().unwrap();
        assert!(peak <= 2.175 * (1.0 + 1e-9), "{peak}");
    }
    // Text output names the files and the limits check.
    let output = armkit(&[
        "traj", "joint", "--robot", "panda", "--from", PANDA_FROM, "--to", PANDA_FROM,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("0.000000 s") && text.contains("within the robot's"),
        "{text}"
    );
}

#[test]
fn joint_errors_are_clear() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "traj", "joint", "--robot", "panda", "--from", PANDA_FROM, "--to", PANDA_TO,
        ];
        args.extend_from_slice(extra);
        let output = armkit(&args);
        assert!(!output.status.success());
        stderr(&output)
    };
    assert_eq!(
        run(&["--duration", "-1"]),
        "error: invalid argument `duration`: must be in [0.001, 1e6] s, got -1 s"
    );
    assert_eq!(
        run(&["--profile", "trapezoidal", "--duration", "2", "--accel-time", "1.5"]),
        "error: invalid argument `acceleration_time`: must be at most half the duration (1 s) so that \
         acceleration and deceleration do not overlap, got 1.5 s"
    );
    assert!(run(&["--profile", "trapezoidal", "--duration", "2"])
        .contains("needs an acceleration time"));
    assert!(run(&["--accel-time", "1"]).contains("--accel-time needs --duration"));
    assert!(run(&["--dt", "0"]).contains("--dt: must be finite and > 0"));
    let output = armkit(&[
        "traj", "joint", "--robot", "panda", "--from", "0,0", "--to", PANDA_TO,
    ]);
    assert_eq!(stderr(&output), "error: --from: expected 7 values, got 2");
}

#[test]
fn line_follows_the_path_within_the_tolerance() {
    let dir = scratch("line");
    let csv = dir.join("line.csv");
    // Panda: 0.3 m along y from the pose of PANDA_FROM, same orientation.
    let output = armkit(&[
        "traj",
        "line",
        "--robot",
        "panda",
        "--from",
        PANDA_FROM,
        "--to-pose",
        "0.4840068820263855,0.3,0.4130277771284139,3.141592653589793,-0.1,0.0",
        "--csv",
        csv.to_str().unwrap(),
        "--json",
    ]);
    let summary = json(&output);
    assert_eq!(summary["status"], "tolerance_met");
    assert!(summary["checked_error_m"].as_f64().unwrap() <= 1e-4);
    assert!(summary["checked_error_rad"].as_f64().unwrap() <= 1e-3);
    assert!(summary["error_100_points_m"].as_f64().unwrap() <= 1.5e-4);
    assert!(summary["segments"].as_u64().unwrap() >= 4);
    assert!(summary["ik"].as_str().unwrap().starts_with("numeric"));
    let header = "t,q1,q2,q3,q4,q5,q6,q7,qd1,qd2,qd3,qd4,qd5,qd6,qd7,qdd1,qdd2,qdd3,qdd4,qdd5,qdd6,qdd7,x,y,z,roll,pitch,yaw";
    let rows = read_csv(&csv, header);
    assert_eq!(rows.len(), 201);
    let last = rows.last().unwrap();
    assert!(
        (last[22] - 0.4840068820263855).abs() < 1e-6 && (last[23] - 0.3).abs() < 1e-6,
        "{last:?}"
    );
    assert!(last[8..22].iter().all(|v| v.abs() < 1e-9), "ends at rest");
    // arm4 (4 joints): the task is the position; closed-form IK.
    let output = armkit(&[
        "traj",
        "line",
        "--robot",
        "arm4",
        "--from",
        "0.5,-1,0.3,0.4",
        "--to-q",
        "0.9,-1.5,0.3,0.4",
        "--law",
        "trapezoidal",
        "--json",
    ]);
    let summary = json(&output);
    assert_eq!(summary["status"], "tolerance_met");
    assert!(summary["ik"].as_str().unwrap().starts_with("seed 002"));
    assert!(summary["error_100_points_m"].as_f64().unwrap() <= 1.5e-4);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn line_errors_and_unmet_tolerance() {
    // Out of reach: a clear error naming the path point.
    let output = armkit(&[
        "traj",
        "line",
        "--robot",
        "panda",
        "--from",
        PANDA_FROM,
        "--to-pose",
        "2,0,0.4,3.14159,0,0",
    ]);
    assert!(!output.status.success());
    let text = stderr(&output);
    assert!(
        text.starts_with("error: invalid argument `path`: IK failed at the path point (knot ")
            && text.contains("numeric IK from the previous configuration did not converge")
            && text.contains("no joint at a limit: the point is beyond the arm's reach"),
        "{text}"
    );
    // One fixed segment cannot meet 0.1 mm: exit code 3, trajectory still written.
    let output = armkit(&[
        "traj",
        "line",
        "--robot",
        "panda",
        "--from",
        PANDA_FROM,
        "--to-q",
        PANDA_TO,
        "--segments",
        "1",
        "--json",
    ]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let summary: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(summary["status"], "tolerance_not_met");
    let output = armkit(&[
        "traj",
        "line",
        "--robot",
        "panda",
        "--from",
        PANDA_FROM,
        "--to-q",
        PANDA_TO,
        "--accel-time",
        "0.5",
    ]);
    assert_eq!(
        stderr(&output),
        "error: --accel-time is for --law trapezoidal"
    );
}

/// The torque check on a seed 002 line: the Panda's torques (Franka's inertias and
/// effort limits from the built-in panda.urdf) with the line played 20 times
/// faster, then slowed down uniformly until every torque is within its limit.
#[test]
fn line_torques_are_fitted_to_the_panda_limits() {
    let args = [
        "traj",
        "line",
        "--robot",
        "panda",
        "--from",
        PANDA_FROM,
        "--to-pose",
        "0.4840068820263855,0.3,0.4130277771284139,3.141592653589793,-0.1,0.0",
        "--law",
        "linear",
        "--orientation",
        "rpy-linear",
        "--boundary",
        "finite-difference",
        "--dynamics",
        "panda-urdf",
        "--speed-up",
        "20",
        "--fit-torque-limits",
        "--json",
    ];
    let refused = |args: &[&str]| {
        let output = armkit(args);
        assert!(!output.status.success());
        stderr(&output)
    };
    // The fit meets the effort limits; the joints still exceed their
    // velocity limits at that duration: exit 3, the reason on stderr.
    let (summary, reason) = json_unmet(&armkit(&args));
    assert!(reason.contains("velocity limits not met"), "{reason}");
    assert_eq!(summary["status"], "tolerance_met");
    let torques = &summary["torques"];
    assert_eq!(torques["status"], "exceeds-velocity-limits");
    let factor = torques["time_scaling_factor"].as_f64().unwrap();
    assert!(factor > 1.0, "{factor}");
    // The written trajectory is the slowed-down one: 2 s / 20 * factor.
    let duration = summary["duration_s"].as_f64().unwrap();
    assert!(
        (duration - 0.1 * factor).abs() < 1e-9,
        "{duration} vs {factor}"
    );
    let peaks = torques["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 7);
    let worst = peaks
        .iter()
        .map(|p| p["ratio"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert!(worst <= 1.0 && worst > 0.999, "tight: {worst}");
    // Without --torques the dynamics choice is refused; the built-in panda's
    // own masses (Franka's, in its DH frames) give the same torques.
    let mut no_check = args.to_vec();
    no_check.retain(|a| *a != "--fit-torque-limits");
    let err = refused(&no_check);
    assert!(
        err.contains("needs --torques or --fit-torque-limits"),
        "{err}"
    );
    let mut own = args.to_vec();
    own.retain(|a| *a != "--dynamics" && *a != "panda-urdf");
    let (builtin, _) = json_unmet(&armkit(&own));
    let builtin_factor = builtin["torques"]["time_scaling_factor"].as_f64().unwrap();
    assert!(
        (builtin_factor - factor).abs() <= 1e-6 * factor,
        "{builtin_factor} vs {factor}"
    );
}
