//! `armkit singularity`: seed 004's line through a wrist singularity from the
//! command line, checked against the library, its files, its scenario and
//! its errors.

use crate::common::*;

use armkit::math::Pose;
use armkit::singularity::{
    calibrate_determinant_threshold, seed004_path, AvoidanceOptions, Baselines, Manipulator,
    Method, PathTracker,
};

fn relative_difference(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

/// The method rows of the `--json` output, by label.
fn method<'a>(value: &'a serde_json::Value, label: &str) -> &'a serde_json::Value {
    value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["method"] == label)
        .unwrap_or_else(|| panic!("no method {label} in {value}"))
}

#[test]
fn default_json_matches_the_library_on_the_held_space6r() {
    let value = json(&armkit(&["singularity", "--json"]));
    assert_eq!(value["robot"], "space6r");
    assert_eq!(value["base"], "attitude-held");
    assert_eq!(value["k"], serde_json::json!([1, 5, 10]));
    // The same comparison through the library.
    let system = armkit::robots::space6r_free_floating().unwrap();
    let line = seed004_path(&Manipulator::AttitudeHeld {
        system: &system,
        base: Pose::identity(),
    })
    .unwrap();
    // The threshold by seed 004's rule: calibrated on the plain run.
    let fitted = AvoidanceOptions::default();
    let placed = Manipulator::AttitudeHeld {
        system: &system,
        base: line.base,
    };
    let plain = PathTracker::new(placed, line.task(20.0, 4.0), fitted)
        .unwrap()
        .run(&Method::Plain)
        .unwrap();
    let calibrated =
        calibrate_determinant_threshold(&plain, fitted.detection.joint_step_threshold).unwrap();
    assert_eq!(value["determinant_threshold"].as_f64().unwrap(), calibrated);
    let mut options = fitted;
    options.detection.determinant_threshold = calibrated;
    let tracker = PathTracker::new(placed, line.task(20.0, 4.0), options).unwrap();
    let labels: Vec<&str> = value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    assert_eq!(
        labels,
        [
            "plain",
            "avoidance k=1",
            "dls",
            "sri",
            "separation",
            "avoidance k=5",
            "avoidance k=10"
        ]
    );
    // Three of the runs, redone through the library (all six would double
    // this test's time in debug builds); the baselines keep the fitted
    // threshold's damping region.
    let baselines = Baselines::for_detection(&fitted.detection);
    for which in [
        Method::Plain,
        Method::Avoidance { k: 1 },
        Method::DampedLeastSquares(baselines.nakamura),
    ] {
        let run = tracker.run(&which).unwrap();
        let row = method(&value, &run.method.label());
        assert_eq!(row["status"], "completed", "{row}");
        for (key, want) in [
            ("peak_joint_rate", run.summary.peak_joint_rate),
            ("max_position_error", run.summary.max_position_error),
            ("max_orientation_error", run.summary.max_orientation_error),
            ("final_position_error", run.summary.final_position_error),
            (
                "time_in_singular_region",
                run.summary.time_in_singular_region,
            ),
        ] {
            let got = row[key].as_f64().unwrap();
            assert!(
                relative_difference(got, want) <= 1e-12,
                "{} {key}: {got} vs {want}",
                run.method.label()
            );
        }
        assert_eq!(
            row["ik_solves"].as_u64().unwrap() as usize,
            run.summary.ik_solves
        );
        assert_eq!(row["regions"].as_array().unwrap().len(), run.regions.len());
    }
    // The avoidance against plain tracking: at most a tenth of its peak
    // joint rate, the goal reached, the first region straddling mid-path.
    let plain = method(&value, "plain");
    let avoidance = method(&value, "avoidance k=1");
    assert!(
        plain["peak_joint_rate"].as_f64().unwrap()
            >= 10.0 * avoidance["peak_joint_rate"].as_f64().unwrap()
    );
    assert!(avoidance["final_position_error"].as_f64().unwrap() <= 1e-6);
    assert!(avoidance["final_orientation_error"].as_f64().unwrap() <= 1e-6);
    let region = &avoidance["regions"][0];
    let (start, end) = (
        region["start_time"].as_f64().unwrap(),
        region["end_time"].as_f64().unwrap(),
    );
    assert!(
        start > 0.0 && start < 10.0 && end > 10.0 && end < 20.0,
        "the region straddles mid-path: {start}..{end}"
    );
    // The miss sweep: nine lines, the avoidance within eps_dq / h on each.
    let sweep = value["miss_sweep"].as_array().unwrap();
    assert_eq!(sweep.len(), 9);
    for line in sweep {
        let avoidance = &line["methods"][1];
        assert_eq!(avoidance["method"], "avoidance");
        assert!(avoidance["peak_joint_rate"].as_f64().unwrap() <= 0.5 * (1.0 + 1e-9));
        // DLS clamped to the same speed, and the floor of a wrist-branch
        // switch: about the miss (the line is offset along the lost direction).
        let clamped = &line["methods"][4];
        assert_eq!(clamped["method"], "dls clamped");
        assert!(clamped["peak_joint_rate"].as_f64().unwrap() <= 0.5 * (1.0 + 1e-9));
        let miss = line["miss"].as_f64().unwrap().abs();
        let floor = line["floor"]["pose_error"].as_f64().unwrap();
        assert!((floor - miss).abs() <= 0.05 * miss + 1e-7, "{line}");
        // The joint plan is kept only where it errs less than the greedy one.
        let greedy = &line["methods"][2];
        assert_eq!(greedy["method"], "avoidance greedy");
        assert!(
            avoidance["max_pose_error"].as_f64().unwrap()
                <= greedy["max_pose_error"].as_f64().unwrap() * (1.0 + 1e-9)
        );
    }
    assert_eq!(value["threshold_rule"], "calibrated (seed 004's rule)");
    let findings = value["findings"].as_array().unwrap();
    assert!(
        findings
            .iter()
            .any(|f| f["claim"].as_str().unwrap().contains("Fig 5")),
        "{findings:?}"
    );
    let checks = value["checks"].as_array().unwrap();
    assert!(checks.len() >= 5);
    assert!(checks.iter().all(|c| c["pass"] == true), "{checks:?}");
    assert!(value["files"].as_array().unwrap().is_empty());
}

/// The columns of a CSV file: header and rows of cells.
fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

#[test]
fn the_table_csv_svg_and_report_agree() {
    let out = scratch("files");
    let output = armkit(&["singularity", "--out", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    // summary.csv: one row per method.
    let (header, rows) = read_csv(&out.join("summary.csv"));
    assert_eq!(
        header[..5],
        [
            "method",
            "status",
            "peak_joint_rate",
            "max_position_error_m",
            "max_orientation_error_rad"
        ]
    );
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let value = |label: &str, name: &str| -> f64 {
        rows.iter().find(|r| r[0] == label).unwrap()[column(name)]
            .parse()
            .unwrap()
    };
    let labels: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(
        labels,
        [
            "plain",
            "avoidance k=1",
            "dls",
            "sri",
            "separation",
            "avoidance k=5",
            "avoidance k=10"
        ]
    );
    // The printed table: every header, a row per method agreeing with
    // summary.csv to the digits printed.
    for header in [
        "peak joint rate (rad/s)",
        "max position error (m)",
        "final orientation error (rad)",
        "time in singular region (s)",
        "IK solves",
        "Singular regions planned through",
        "error against the knot stride k",
    ] {
        assert!(text.contains(header), "missing {header}:\n{text}");
    }
    for label in &labels {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("{label} ")))
            .unwrap_or_else(|| panic!("no row {label}:\n{text}"));
        let cells: Vec<&str> = line[label.len()..].split_whitespace().collect();
        let printed = |i: usize| -> f64 { cells[i].parse().unwrap() };
        let peak = value(label, "peak_joint_rate");
        assert!((printed(0) - peak).abs() <= 5e-5, "{label}: {line}");
        for (i, name) in [
            (1, "max_position_error_m"),
            (2, "max_orientation_error_rad"),
            (3, "final_position_error_m"),
            (4, "final_orientation_error_rad"),
        ] {
            assert!(
                relative_difference(printed(i), value(label, name)) <= 1e-3,
                "{label} {name}: {line}"
            );
        }
        assert!((printed(5) - value(label, "time_in_singular_region_s")).abs() <= 5e-3);
        assert_eq!(printed(6), value(label, "ik_solves"));
        assert!(line.ends_with("completed"), "{line}");
    }
    assert!(!text.contains("[FAIL]"), "{text}");
    assert!(
        text.contains("[reproduced with deviation] seed 004, Fig 6"),
        "{text}"
    );
    assert!(text.contains("report.html"));
    let plain_peak = value("plain", "peak_joint_rate");
    let avoidance_peak = value("avoidance k=1", "peak_joint_rate");
    assert!(
        plain_peak / avoidance_peak >= 10.0,
        "{plain_peak} / {avoidance_peak}"
    );
    assert!(value("avoidance k=1", "final_position_error_m") <= 1e-6);
    assert!(value("avoidance k=1", "final_orientation_error_rad") <= 1e-6);
    assert!(value("avoidance k=1", "ik_solves") > value("avoidance k=10", "ik_solves"));
    assert!(value("plain", "time_in_singular_region_s") > 0.0);
    // The joint-rate figure's CSV holds the samples the peak comes from.
    let (rates_header, rate_rows) = read_csv(&out.join("joint_rates_plain.csv"));
    assert_eq!(
        rates_header[..7],
        ["t (s)", "q1", "q2", "q3", "q4", "q5", "q6"]
    );
    assert!(rates_header[7].starts_with("singular region"));
    assert!(rate_rows.len() > 100);
    let peak_from_csv = rate_rows
        .iter()
        .flat_map(|r| r[1..7].iter().map(|c| c.parse::<f64>().unwrap().abs()))
        .fold(0.0, f64::max);
    assert!(relative_difference(peak_from_csv, plain_peak) <= 1e-12);
    // The region marker is non-zero exactly on some middle stretch.
    let marked: Vec<f64> = rate_rows
        .iter()
        .filter(|r| r[7].parse::<f64>().unwrap() > 0.0)
        .map(|r| r[0].parse().unwrap())
        .collect();
    assert!(!marked.is_empty());
    let duration: f64 = rate_rows.last().unwrap()[0].parse().unwrap();
    assert!(marked[0] > 0.0 && *marked.last().unwrap() < duration);
    // Errors against k: one column per k; |det J| with the threshold.
    let (error_header, _) = read_csv(&out.join("position_error_k.csv"));
    assert_eq!(error_header.len(), 4, "{error_header:?}");
    let (det_header, det_rows) = read_csv(&out.join("determinant.csv"));
    assert_eq!(det_header.last().unwrap(), "threshold");
    assert_eq!(det_rows.len(), rate_rows.len());
    for name in [
        "joint_rates_plain",
        "joint_rates_avoidance",
        "joint_rates_dls",
        "joint_rates_sri",
        "position_error_k",
        "orientation_error_k",
        "determinant",
    ] {
        let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("<polyline"),
            "{name}.svg"
        );
    }
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("id=\"animation\""));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["passed"], summary["total"]);
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn fixed_base_and_options_are_used() {
    let value = json(&armkit(&[
        "singularity",
        "--json",
        "--base",
        "fixed",
        "--k",
        "2,4",
        "--dt",
        "0.02",
    ]));
    assert_eq!(value["base"], "fixed");
    assert_eq!(value["dt"], 0.02);
    let labels: Vec<&str> = value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    assert_eq!(
        labels,
        [
            "plain",
            "avoidance k=2",
            "dls",
            "sri",
            "separation",
            "avoidance k=4"
        ]
    );
    let plain = method(&value, "plain")["peak_joint_rate"].as_f64().unwrap();
    let avoidance = method(&value, "avoidance k=2")["peak_joint_rate"]
        .as_f64()
        .unwrap();
    assert!(avoidance < plain, "{avoidance} vs {plain}");
    // A higher threshold widens the region.
    let threshold = value["determinant_threshold"].as_f64().unwrap();
    let wider = json(&armkit(&[
        "singularity",
        "--json",
        "--base",
        "fixed",
        "--k",
        "2,4",
        "--dt",
        "0.02",
        "--determinant-threshold",
        &(2.0 * threshold).to_string(),
    ]));
    let time = |v: &serde_json::Value| {
        method(v, "plain")["time_in_singular_region"]
            .as_f64()
            .unwrap()
    };
    assert!(
        time(&wider) > time(&value),
        "{} vs {}",
        time(&wider),
        time(&value)
    );
}

#[test]
fn a_path_that_stays_away_from_the_singularity_is_the_same_with_and_without_avoidance() {
    // The line offset from the singular pose by a miss of -0.05 (on this
    // line, positive misses of 0.05 and more leave the reachable workspace).
    let value = json(&armkit(&[
        "singularity",
        "--json",
        "--base",
        "fixed",
        "--miss",
        "-0.05",
        "--k",
        "1",
    ]));
    let plain = method(&value, "plain");
    let avoidance = method(&value, "avoidance k=1");
    let threshold = value["determinant_threshold"].as_f64().unwrap();
    let closest = plain["min_determinant"].as_f64().unwrap();
    assert!(
        closest > threshold,
        "the path comes within the threshold ({closest} < {threshold}): offset it further"
    );
    assert!(avoidance["regions"].as_array().unwrap().is_empty());
    assert_eq!(avoidance["ik_solves"], 0);
    for key in [
        "peak_joint_rate",
        "max_position_error",
        "max_orientation_error",
        "final_position_error",
        "final_orientation_error",
    ] {
        assert_eq!(avoidance[key], plain[key], "{key}");
    }
    assert_eq!(plain["time_in_singular_region"], 0.0);
}

#[test]
fn the_scenario_runs_and_every_check_passes() {
    let out = scratch("scenario");
    let output = armkit(&[
        "run",
        "scenarios/seed004-singularity.toml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let dir = out.join("seed004-singularity");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["scenario"], "seed004-singularity");
    assert!(summary["total"].as_u64().unwrap() >= 5);
    assert_eq!(summary["passed"], summary["total"], "{summary}");
    assert!(dir.join("report.html").exists());
    assert!(dir.join("joint_rates_plain.svg").exists());
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn bad_input_is_an_error_naming_the_option() {
    for (args, option) in [
        (&["--k", "0"][..], "--k"),
        (&["--k", "1,2.5"], "--k"),
        (&["--k", "-3"], "--k"),
        (&["--k", ""], "--k"),
        (&["--determinant-threshold", "0"], "--determinant-threshold"),
        (
            &["--determinant-threshold", "-1"],
            "--determinant-threshold",
        ),
        (
            &["--determinant-threshold", "NaN"],
            "--determinant-threshold",
        ),
        (&["--joint-step-threshold", "0"], "--joint-step-threshold"),
        (&["--joint-step-threshold", "inf"], "--joint-step-threshold"),
        (&["--dt", "nan"], "--dt"),
        (&["--dt", "-0.01"], "--dt"),
        (&["--dt", "1e-9"], "--dt"),
        (&["--dt", "30"], "--dt"),
        (&["--duration", "0"], "--duration"),
        (&["--accel-time", "15"], "--accel-time"),
        (&["--miss", "nan"], "--miss"),
        (&["--miss-sweep", "0,nan"], "--miss-sweep"),
        (&["--miss-sweep", ""], "--miss-sweep"),
        (&["--through", "1,2,3"], "--through"),
        (&["--direction", "1,2,3,4,5,x"], "--direction"),
        (&["--robot", "ur5"], "--base attitude-held"),
        (&["--base", "fixed", "--robot", "ur5"], "--through"),
        (&["--region-plan", "printed"], "--region-plan"),
        (&["--feedback", "closed"], "--feedback"),
        (&["--as-printed-miss", "nan"], "--as-printed-miss"),
        (&["--as-printed-miss", "few"], "--as-printed-miss"),
        (&["--as-printed-eps-dq", "0"], "--as-printed-eps-dq"),
        (&["--open-loop-runs", "yes"], "--open-loop-runs"),
    ] {
        let mut argv = vec!["singularity"];
        argv.extend_from_slice(args);
        let output = armkit(&argv);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(
            message.starts_with("error: ") && message.contains(option),
            "{args:?}: {message}"
        );
        assert_eq!(message.lines().count(), 1, "{message}");
    }
    // A line that leaves the workspace is out of reach.
    let output = armkit(&[
        "singularity",
        "--direction",
        "0,40,40,0,0.8,0",
        "--base",
        "fixed",
    ]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(message.contains("out of reach"), "{message}");
}

/// `--region-plan exact`, `--feedback open-loop`, the as-printed line and
/// the open-loop runs on a fixed-base arm: each in the JSON with its
/// figures and its rows; `none` / `off` leave them out.
#[test]
fn as_printed_line_exact_plan_and_open_loop_from_the_command_line() {
    let base = [
        "singularity",
        "--json",
        "--base",
        "fixed",
        "--miss-sweep",
        "0",
        "--k",
        "1,5",
    ];
    let run = |extra: &[&str]| {
        let mut argv = base.to_vec();
        argv.extend_from_slice(extra);
        json(&armkit(&argv))
    };
    let value = run(&["--as-printed-miss", "0.003", "--as-printed-eps-dq", "5"]);
    assert_eq!(value["region_plan"], "joint");
    assert_eq!(value["feedback"], "next-pose");
    let printed = &value["as_printed"];
    assert_eq!(printed["miss"], 0.003);
    let eps = printed["joint_step_threshold"].as_f64().unwrap();
    assert!((eps - 5f64.to_radians() * 0.01).abs() < 1e-12, "{printed}");
    let rows = printed["methods"].as_array().unwrap();
    let peak = |name: &str| {
        rows.iter().find(|m| m["method"] == name).unwrap()["peak_joint_rate"]
            .as_f64()
            .unwrap()
    };
    // Exact knots on the near miss: the wrist flips beyond eps_dq per period.
    assert!(peak("avoidance k=1") > eps / 0.01, "{printed}");
    let findings = value["findings"].as_array().unwrap();
    let claims: Vec<&str> = findings
        .iter()
        .map(|f| f["claim"].as_str().unwrap())
        .collect();
    assert!(claims
        .iter()
        .any(|c| c.contains("the method as printed on a near-miss line")));
    assert_eq!(value["open_loop"].as_array().unwrap().len(), 2);
    assert!(claims.iter().any(|c| c.contains("open-loop tracker")));
    // The main runs with the plan as printed and without feedback.
    let changed = run(&[
        "--region-plan",
        "exact",
        "--feedback",
        "open-loop",
        "--as-printed-miss",
        "none",
        "--open-loop-runs",
        "off",
    ]);
    assert_eq!(changed["region_plan"], "exact");
    assert_eq!(changed["feedback"], "open-loop");
    assert!(changed["as_printed"].is_null());
    assert!(changed["open_loop"].as_array().unwrap().is_empty());
    let regions = method(&changed, "avoidance k=1")["regions"]
        .as_array()
        .unwrap();
    assert!(!regions.is_empty() && regions.iter().all(|r| r["plan"] == "exact"));
    // Open loop: plain's error is no longer corrected each period.
    let open = method(&changed, "plain")["final_position_error"]
        .as_f64()
        .unwrap();
    let closed = method(&value, "plain")["final_position_error"]
        .as_f64()
        .unwrap();
    assert!(open > 100.0 * closed.max(1e-12), "{open} vs {closed}");
}
