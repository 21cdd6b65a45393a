//! `armkit redundancy`: the four-way comparison from the command line,
//! checked against the library, its files, and its errors.

use crate::common::*;

use armkit::math::{Pose, Vector3};
use armkit::redundancy::{
    compare_distributions, ComparisonCase, Distribution, DistributionOptions, JointWeights, Load,
    TorqueFloor, SEED000_PRIORITY_WEIGHTS,
};
use armkit::redundancy::{energy_along_motion, TorqueModel};
use armkit::trajectory::{CartesianTrajectory, TimeLaw};

#[test]
fn default_gantry_comparison_matches_the_library_and_writes_files() {
    let out = scratch("default");
    let value = json(&armkit(&[
        "redundancy",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    // The same comparison through the library.
    let model = armkit::robots::by_name("gantry9").unwrap();
    let q0 = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    let mut data = armkit::Data::new(&model);
    let start = *armkit::forward_kinematics(&model, &mut data, &q0).unwrap();
    let goal = Pose::from_translation(Vector3::new(0.4, 0.3, -0.3)) * start;
    let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 4.0).unwrap();
    let load = Load::payload(50.0).with_seed001_gravity();
    // Seed 001's baseline (joints locked so that six remain), then the
    // labelled extra with the rail and beam alone locked.
    let mut cases = ComparisonCase::four_way(
        9,
        load,
        TorqueFloor::default(),
        JointWeights::new(&SEED000_PRIORITY_WEIGHTS).unwrap(),
        &[0, 1, 2],
    )
    .unwrap();
    cases.push(ComparisonCase {
        name: "locked-variant".into(),
        distribution: Distribution::Weights(JointWeights::uniform(9).with_locked(&[0, 1]).unwrap()),
    });
    let expected = compare_distributions(
        &model,
        &q0,
        &path,
        &load,
        &cases,
        &DistributionOptions::default(),
    )
    .unwrap();
    let rows = value["distributions"].as_array().unwrap();
    assert_eq!(rows.len(), 5);
    for (row, want) in rows.iter().zip(&expected) {
        assert_eq!(row["name"], want.name.as_str());
        assert_eq!(row["status"], "completed");
        let energy = row["energy"].as_f64().unwrap();
        assert!((energy - want.summary.energy).abs() <= 1e-12 * want.summary.energy);
        // F under the full dynamics of the same run.
        let samples = &want.report.samples;
        let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
        let q: Vec<Vec<f64>> = samples.iter().map(|s| s.q.clone()).collect();
        let q_dot: Vec<Vec<f64>> = samples.iter().map(|s| s.joint_rates.clone()).collect();
        let dynamic = energy_along_motion(&model, &times, &q, &q_dot, &load, TorqueModel::Dynamic)
            .unwrap()
            .energy;
        let got = row["energy_dynamic"].as_f64().unwrap();
        assert!(
            (got - dynamic).abs() <= 1e-12 * dynamic,
            "{got} vs {dynamic}"
        );
        let travel: Vec<f64> = serde_json::from_value(row["travel"].clone()).unwrap();
        for (a, b) in travel.iter().zip(&want.summary.travel) {
            assert!((a - b).abs() < 1e-12);
        }
    }
    assert_eq!(value["lowest_energy"], "energy-optimal");
    assert_eq!(value["gravity"], true);
    assert_eq!(value["locked"], serde_json::json!([1, 2, 3]));
    assert_eq!(value["locked_variant"], serde_json::json!([1, 2]));
    // Under the full dynamics the baseline wins (the energy-optimal weights
    // come from the static torques).
    assert_eq!(value["lowest_energy_dynamic"], "locked");
    // Files: summary (header + 5 rows), samples (header + 5 x 401 rows), plots.
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(summary.starts_with("distribution,status,energy_W2s,energy_dynamic_W2s,"));
    assert_eq!(summary.lines().count(), 6);
    let samples = std::fs::read_to_string(out.join("samples.csv")).unwrap();
    assert!(samples.starts_with("distribution,time_s,q1,"));
    assert_eq!(samples.lines().count(), 1 + 5 * 401);
    for name in [
        "energy_rate",
        "energy_cumulative",
        "travel",
        "joints_minimum-norm",
        "joints_energy-optimal",
        "joints_priorities",
        "joints_locked",
        "joints_locked-variant",
    ] {
        let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("<polyline"),
            "{name}"
        );
    }
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn table_names_every_distribution_and_the_lowest_energy() {
    let out = scratch("table");
    let output = armkit(&["redundancy", "--out", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    for name in [
        "minimum-norm",
        "energy-optimal",
        "priorities",
        "locked",
        "locked-variant",
    ] {
        assert!(text.contains(name), "{text}");
    }
    assert!(
        text.contains("lowest F (seed 001, eq 9): energy-optimal"),
        "{text}"
    );
    assert!(
        text.contains("static torques: energy-optimal ")
            && text.contains("% below locked")
            && text.contains("dynamic torques: locked "),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn panda_with_a_null_space_objective_and_the_partitioned_form() {
    let out = scratch("panda");
    let run = |formulation: &str| {
        json(&armkit(&[
            "redundancy",
            "--robot",
            "panda",
            "--duration",
            "2",
            "--secondary",
            "joint-limits",
            "--formulation",
            formulation,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]))
    };
    let a = run("least-norm");
    let b = run("partitioned");
    // The built-in Panda carries Franka's link masses: their weights load the joints.
    assert_eq!(a["gravity"], true);
    for (x, y) in a["distributions"]
        .as_array()
        .unwrap()
        .iter()
        .zip(b["distributions"].as_array().unwrap())
    {
        assert_eq!(x["status"], "completed");
        let (ex, ey) = (x["energy"].as_f64().unwrap(), y["energy"].as_f64().unwrap());
        assert!((ex - ey).abs() < 1e-9 * ex.max(1e-12), "{ex} vs {ey}");
    }
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn bad_arguments_get_clear_errors() {
    let out = scratch("errors");
    let dir = out.to_str().unwrap();
    let cases: [(&[&str], &str); 7] = [
        (
            &["--durations", "4,-1"],
            "error: --durations: every duration must be > 0 s, got -1",
        ),
        (
            &["--durations", "4,x"],
            "error: --durations: value 2: `x` is not a number",
        ),
        (
            &["--lock", "1,10"],
            "error: --lock: joint 10 is not a joint number in 1..=9",
        ),
        (
            &["--priorities", "100,10,10,1,1,1,1,1,0"],
            "error: invalid argument `weights`: weight of joint 8 must be finite and > 0, got 0",
        ),
        (&["--q0", "1,2,3"], "error: --q: expected 9 values, got 3"),
        (
            &["--robot", "ur5"],
            "error: ur5: 6 joints; redundancy needs more than 6",
        ),
        (
            &["--torque-floor", "2"],
            "error: invalid argument `torque_floor`: relative fraction must be in (0, 1], got 2",
        ),
    ];
    for (extra, message) in cases {
        let mut args = vec!["redundancy", "--out", dir];
        args.extend_from_slice(extra);
        let output = armkit(&args);
        assert!(!output.status.success(), "{extra:?} succeeded");
        assert_eq!(stderr(&output), message, "{extra:?}");
    }
    let _ = std::fs::remove_dir_all(out);
}

/// `--durations` reaches the library's sweep: the JSON lists one point per
/// duration (sorted), the crossover where the dynamic-torque margin turns
/// positive between them, and `none` turns the sweep off.
#[test]
fn durations_run_the_sweep_and_none_turns_it_off() {
    let out = scratch("durations");
    let dir = out.to_str().unwrap();
    let value = json(&armkit(&[
        "redundancy",
        "--out",
        dir,
        "--json",
        "--durations",
        "16,4",
    ]));
    let points = value["sweep"]["points"].as_array().unwrap();
    let durations: Vec<f64> = points
        .iter()
        .map(|p| p["duration"].as_f64().unwrap())
        .collect();
    assert_eq!(durations, [4.0, 16.0]);
    let margins: Vec<f64> = points
        .iter()
        .map(|p| p["margin_dynamic_percent"].as_f64().unwrap())
        .collect();
    // At 4 s the baseline wins under dynamic torques, at 16 s the
    // energy-optimal distribution: the crossover lies between.
    assert!(margins[0] < 0.0 && margins[1] > 0.0, "{margins:?}");
    let crossover = value["sweep"]["crossover_s"].as_f64().unwrap();
    assert!(crossover > 4.0 && crossover < 16.0, "{crossover}");
    let value = json(&armkit(&[
        "redundancy",
        "--out",
        dir,
        "--json",
        "--durations",
        "none",
    ]));
    assert!(value["sweep"].is_null(), "{}", value["sweep"]);
    let _ = std::fs::remove_dir_all(out);
}
