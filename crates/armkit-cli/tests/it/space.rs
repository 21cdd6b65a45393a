//! `armkit space jacobian | simulate | track`: the free-floating space robot
//! from the command line, checked against the library and on its outputs.

use crate::common::*;

use std::path::PathBuf;

use armkit::math::Pose;
use armkit::robots::space6r_free_floating;
use armkit::space::{generalized_jacobian, BaseMode, SpaceData};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armkit-space-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

const Q: &str = "0.3,0.8,-0.6,0.4,0.9,-0.3";

#[test]
fn jacobian_matches_the_library_in_both_modes() {
    let model = space6r_free_floating().unwrap();
    let mut data = SpaceData::new(&model);
    let q = [0.3, 0.8, -0.6, 0.4, 0.9, -0.3];
    for (flag, mode) in [
        ("attitude-held", BaseMode::AttitudeHeld),
        ("free", BaseMode::FreeFloating),
        ("free-floating", BaseMode::FreeFloating),
    ] {
        let value = json(&armkit(&[
            "space",
            "jacobian",
            "--base-mode",
            flag,
            "--q",
            Q,
            "--json",
        ]));
        let expected =
            generalized_jacobian(&model, &mut data, &Pose::identity(), &q, mode).unwrap();
        let rows: Vec<Vec<f64>> =
            serde_json::from_value(value["generalized_jacobian"].clone()).unwrap();
        for (r, row) in rows.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                assert!((v - expected[(r, c)]).abs() < 1e-12, "{flag} ({r}, {c})");
            }
        }
        assert_eq!(value["robot"], "space6r");
        assert!((value["total_mass"].as_f64().unwrap() - 518.0).abs() < 1e-9);
    }
}

#[test]
fn bad_systems_get_clear_errors() {
    let output = armkit(&["space", "jacobian", "--robot", "puma560", "--q", Q]);
    assert!(!output.status.success());
    assert_eq!(
        stderr(&output),
        "error: invalid model: link 0 (`q1`), field `inertia`: no mass properties: a \
         free-floating system needs the mass, centre of mass and inertia of every link"
    );
    let output = armkit(&["space", "jacobian", "--base-mass", "-5", "--q", Q]);
    assert_eq!(
        stderr(&output),
        "error: invalid model `satellite`: base body, field `mass`: must be finite and > 0 kg, got -5"
    );
    let output = armkit(&["space", "jacobian", "--base-inertia", "1,-2,3", "--q", Q]);
    assert!(
        stderr(&output).contains("field `inertia`: must be positive definite"),
        "{}",
        stderr(&output)
    );
    let output = armkit(&[
        "space",
        "track",
        "--goal",
        "0.5,0,1.8,0,0,0",
        "--accel-time",
        "15",
    ]);
    assert_eq!(
        stderr(&output),
        "error: --accel-time: must be in [0, duration / 2] = [0, 10] s, got 15"
    );
}

#[test]
fn simulate_writes_a_csv_with_the_centre_of_mass_fixed() {
    let path = scratch("simulate.csv");
    let value = json(&armkit(&[
        "space",
        "simulate",
        "--base-mode",
        "free",
        "--duration",
        "20",
        "--dt",
        "0.01",
        "--seed",
        "4",
        "--output",
        path.to_str().unwrap(),
        "--plots",
        scratch("simulate-plots").to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(value["steps"], 2000);
    for name in ["com_drift", "momentum", "base_position", "base_attitude"] {
        let svg =
            std::fs::read_to_string(scratch("simulate-plots").join(format!("{name}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("t (s)"), "{name}");
    }
    assert!(value["max_com_drift"].as_f64().unwrap() < 1e-9);
    assert!(value["max_angular_momentum"].as_f64().unwrap() < 1e-10);
    assert!(value["base_rotation"].as_f64().unwrap() > 1e-3);
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "t");
    let drift = header.iter().position(|h| *h == "com_drift").unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2001);
    for row in &rows {
        assert_eq!(row.len(), header.len());
        assert!(row[drift].parse::<f64>().unwrap() < 1e-9);
    }
    let last_t: f64 = rows.last().unwrap()[0].parse().unwrap();
    assert!((last_t - 20.0).abs() < 1e-9);
}

#[test]
fn track_follows_the_straight_line() {
    let path = scratch("track.csv");
    let value = json(&armkit(&[
        "space",
        "track",
        "--base-mode",
        "attitude-held",
        "--goal",
        "0.6,-0.3,1.9,0.5,0.5,0.3",
        "--duration",
        "10",
        "--accel-time",
        "2",
        "--output",
        path.to_str().unwrap(),
        "--plots",
        scratch("track-plots").to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(value["status"], "completed");
    for name in ["tracking_error", "joint_rates"] {
        let svg =
            std::fs::read_to_string(scratch("track-plots").join(format!("{name}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("Tracking error") == (name == "tracking_error")
        );
    }
    assert_eq!(value["samples"], 1001);
    assert!(value["max_position_error"].as_f64().unwrap() < 1e-4);
    assert!(value["max_orientation_error"].as_f64().unwrap() < 1e-4);
    let text = std::fs::read_to_string(&path).unwrap();
    let last: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    // ee_x, ee_y, ee_z follow t, 6 q, 6 rates, 6 base cells.
    let ee = &last[19..22];
    for (a, b) in ee.iter().zip([0.6, -0.3, 1.9]) {
        assert!((a - b).abs() < 1e-4, "{ee:?}");
    }
}
