//! Checks of the command line's own input formats (scenario files, number
//! lists and poses) on arbitrary bytes: an `Err` is fine, a panic is a crash.

use std::path::Path;

use armkit_cli::common::{parse_numbers, parse_pose};

/// A scenario file (`armkit run FILE.toml`), parsed and validated (the robot
/// it names is loaded) but not run.
pub fn scenario(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // scenario::load reads UTF-8 text.
    };
    // A scenario may name a robot file by absolute path; reading a device
    // (/dev/zero, /dev/stdin) blocks or never ends by nature, not by a bug of
    // the parser, so such names are left out.
    if ["/dev", "/proc", "/sys"].iter().any(|p| text.contains(p)) {
        return;
    }
    // Relative robot files resolve in a folder that does not exist.
    let _ = armkit_cli::scenario::parse(text, "<fuzz>.toml", Path::new("/nonexistent-fuzz-dir"));
}

/// A number list (`--q 0.1,pi/2,90deg`) and a pose (`--pose x,y,z,r,p,y`):
/// what parses is finite, and a pose's rotation is orthonormal.
pub fn cli_numbers(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // clap hands the commands UTF-8 strings.
    };
    if let Ok(values) = parse_numbers(text, "--q") {
        assert!(
            values.iter().all(|v| v.is_finite()),
            "parse_numbers({text:?}) = {values:?} is not finite"
        );
    }
    if let Ok(pose) = parse_pose(text, "--pose") {
        let rows = pose.to_rows();
        assert!(
            rows.iter().flatten().all(|v| v.is_finite()),
            "parse_pose({text:?}) is not finite: {rows:?}"
        );
        let r = pose.rotation;
        let error = (r.transpose() * r - armkit::math::Matrix3::identity())
            .abs()
            .max();
        assert!(
            error < 1e-12 && (r.determinant() - 1.0).abs() < 1e-12,
            "parse_pose({text:?}): the rotation is not orthonormal (|R'R - I| = {error:e}, det = {})",
            r.determinant()
        );
    }
}

/// The keys a method table may hold (every method's, and a few it does not
/// take), for [`scenario_tables`].
const METHOD_KEYS: &[(&str, &[&str])] = &[
    ("beam", &["mass", "gravity", "samples", "load"]),
    (
        "mpc",
        &[
            "target",
            "start",
            "horizon",
            "control_horizon",
            "dt",
            "weights",
            "terminal_factor",
            "priorities",
            "velocity_weight",
            "solver",
            "reach",
            "max_steps",
            "prismatic_resolution",
            "prismatic_deadband",
            "example",
        ],
    ),
    (
        "redundancy",
        &[
            "q0",
            "move",
            "rotate",
            "duration",
            "payload",
            "no_gravity",
            "priorities",
            "lock",
            "torque_floor",
            "dt",
            "gain",
            "damping",
            "secondary",
            "secondary_gain",
            "formulation",
        ],
    ),
    (
        "continuous_path",
        &[
            "from",
            "to_pose",
            "to_q",
            "duration",
            "law",
            "accel_time",
            "tolerance",
            "segments",
            "max_segments",
            "torques",
            "fit_torque_limits",
            "speed_up",
            "dynamics",
        ],
    ),
    (
        "singularity",
        &[
            "base",
            "through",
            "direction",
            "miss",
            "miss_sweep",
            "duration",
            "accel_time",
            "k",
            "determinant_threshold",
            "joint_step_threshold",
            "dt",
        ],
    ),
    (
        "space",
        &[
            "base_mass",
            "base_inertia",
            "duration",
            "dt",
            "seed",
            "amplitude",
        ],
    ),
];

/// Values that sit on the edges of the checks.
const EDGE_VALUES: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "0",
    "-1",
    "1e300",
    "1e-300",
    "0.5",
    "true",
    "false",
    "\"\"",
    "\"0.4,0.2,0.5,0,0,0\"",
    "\"heavy\"",
    "[1, 2]",
    "[]",
    "{}",
    "18446744073709551615",
    "100000000000",
];

/// A scenario built from the bytes: one method table (first byte), a robot
/// (second byte: none or a built-in) and keys of that method with values
/// from the edges of the checks (a byte pair per key), so that the fuzzer
/// spends its time on the keys and their values rather than on TOML syntax.
/// Parsed and validated like [`scenario`], never run: an `Err` is fine, a
/// panic is a crash.
pub fn scenario_tables(data: &[u8]) {
    let [method, robot, rest @ ..] = data else {
        return;
    };
    let (name, keys) = METHOD_KEYS[usize::from(*method) % METHOD_KEYS.len()];
    let mut text = String::from("name = \"fuzz\"\ntitle = \"t\"\n");
    let robots = ["", "ur5", "panda", "gantry9", "space6r"];
    match robots[usize::from(*robot) % robots.len()] {
        "" => {}
        builtin => text.push_str(&format!("[robot]\nbuiltin = \"{builtin}\"\n")),
    }
    text.push_str(&format!("[{name}]\n"));
    let mut seen = Vec::new();
    for pair in rest.chunks_exact(2) {
        let key = keys[usize::from(pair[0]) % keys.len()];
        if seen.contains(&key) {
            continue; // TOML refuses a repeated key before armkit sees it.
        }
        seen.push(key);
        let value = EDGE_VALUES[usize::from(pair[1]) % EDGE_VALUES.len()];
        text.push_str(&format!("{key} = {value}\n"));
    }
    let _ = armkit_cli::scenario::parse(&text, "<fuzz>.toml", Path::new("/nonexistent-fuzz-dir"));
}
