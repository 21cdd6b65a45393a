//! `armkit ik` and `armkit bench-ik`, run as a user would.

use crate::common::*;

use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Pose;

fn urdf(name: &str) -> String {
    format!(
        "{}/../../tests/data/urdf/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// The pose argument "x,y,z,roll,pitch,yaw" of FK(q) of a built-in robot,
/// and the pose it parses to.
fn pose_argument(robot: &str, q: &[f64]) -> (String, Pose) {
    let model = armkit::robots::by_name(robot).unwrap();
    let text = fk_text(&model, q);
    let pose = *forward_kinematics(&model, &mut Data::new(&model), q).unwrap();
    let (r, p, y) = pose.rpy();
    let t = pose.translation;
    (text, Pose::from_xyz_rpy([t.x, t.y, t.z], [r, p, y]))
}

/// The pose argument "x,y,z,roll,pitch,yaw" of `model`'s FK at `q`, 17
/// significant digits (the pose round-trips to ~1e-16).
fn fk_text(model: &armkit::Model, q: &[f64]) -> String {
    let pose = *forward_kinematics(model, &mut Data::new(model), q).unwrap();
    let (r, p, y) = pose.rpy();
    let t = pose.translation;
    format!(
        "{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e}",
        t.x, t.y, t.z, r, p, y
    )
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
        "--solver",
        "lm",
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
    for solver in ["closed-form", "analytic"] {
        let output = armkit(&[
            "ik",
            "--robot",
            "gantry9",
            "--pose",
            "0.4,0,0.5,0,0,0",
            "--solver",
            solver,
        ]);
        assert_eq!(output.status.code(), Some(1));
        assert!(
            stderr(&output).contains("`gantry9` has no analytic solver: class other"),
            "{}",
            stderr(&output)
        );
    }
}

#[test]
fn explain_prints_the_class() {
    for (robot, class) in [
        ("ur5", "class: three_parallel_2_3_4_intersecting_5_6"),
        ("puma560", "class: spherical_wrist_parallel_2_3"),
        ("stanford", "class: spherical_wrist_prismatic_3"),
        (
            "panda",
            "class: spherical_base_intersecting_6_5 (with joint 7 held",
        ),
        ("gantry9", "class: other"),
    ] {
        let output = armkit(&["ik", "--robot", robot, "--explain"]);
        assert!(output.status.success(), "{}", stderr(&output));
        let text = stdout(&output);
        assert!(text.contains(class), "{robot}: {text}");
        assert!(text.contains("axes 1 and 2:"), "{text}");
    }
}

/// A DH file of a UR5 whose wrist axes 5 and 6 do not meet (a5 = 0.04 m).
const UR5_OFFSET_WRIST_DH: &str = r#"
name = "ur5-offset-wrist"
convention = "standard"
[[links]]
type = "R"
d = 0.089459
a = 0.0
alpha = 1.5707963267948966
[[links]]
type = "R"
d = 0.0
a = -0.425
alpha = 0.0
[[links]]
type = "R"
d = 0.0
a = -0.39225
alpha = 0.0
[[links]]
type = "R"
d = 0.10915
a = 0.0
alpha = 1.5707963267948966
[[links]]
type = "R"
d = 0.09465
a = 0.04
alpha = -1.5707963267948966
[[links]]
type = "R"
d = 0.0823
a = 0.0
alpha = 0.0
"#;

#[test]
fn explain_and_solve_a_three_parallel_arm_without_an_intersecting_pair() {
    let dir = std::env::temp_dir().join(format!("armkit-ik-offset-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ur5-offset-wrist.toml");
    std::fs::write(&file, UR5_OFFSET_WRIST_DH).unwrap();
    let path = file.to_str().unwrap();
    let output = armkit(&[
        "ik",
        "--robot-file",
        path,
        "--solver",
        "analytic",
        "--explain",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("class: three_parallel_2_3_4\n"), "{text}");
    assert!(text.contains("subproblem 6"), "{text}");
    let model = armkit::description::load(&file).unwrap();
    let q = [0.4, -1.1, 1.3, -0.6, 1.4, 0.2];
    let pose = fk_text(&model, &q);
    let json = analytic_json(path, &pose, &[]);
    assert_eq!(json["class"], "three_parallel_2_3_4");
    let fits = json["solution_fits"].as_array().unwrap();
    assert!(fits.len() >= 4, "{fits:?}");
    assert!(fits.iter().all(|f| f["fit"] == "exact"), "{fits:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A DH file of a 6R arm whose axes 2 and 3 are parallel (alpha 2 = 0)
/// and whose other consecutive axes are skew (every a non-zero).
const PARALLEL_PAIR_DH: &str = r#"
name = "parallel-pair"
convention = "standard"
[[links]]
type = "R"
d = 0.3
a = 0.1
alpha = 1.2
[[links]]
type = "R"
d = 0.05
a = 0.4
alpha = 0.0
[[links]]
type = "R"
d = 0.02
a = 0.05
alpha = 1.5707963267948966
[[links]]
type = "R"
d = 0.35
a = 0.03
alpha = -1.3
[[links]]
type = "R"
d = 0.02
a = 0.04
alpha = 1.1
[[links]]
type = "R"
d = 0.1
a = 0.0
alpha = 0.0
"#;

/// `armkit ik --robot-file path --pose pose --solver analytic --json`
/// with `extra` flags: the parsed output (the command must succeed).
fn analytic_json(path: &str, pose: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "ik",
        "--robot-file",
        path,
        "--pose",
        pose,
        "--solver",
        "analytic",
        "--json",
    ];
    args.extend_from_slice(extra);
    let output = armkit(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    serde_json::from_slice(&output.stdout).unwrap()
}

/// A DH file of a made-up 6R arm whose only special pair is axes 1-2
/// parallel (alpha1 = 0, a1 != 0): solved by elimination.
const PARALLEL_PAIR_1_2_DH: &str = r#"
name = "parallel-pair-1-2"
convention = "standard"
[[links]]
type = "R"
d = 0.3
a = 0.4
alpha = 0.0
[[links]]
type = "R"
d = 0.05
a = 0.1
alpha = 1.2
[[links]]
type = "R"
d = 0.02
a = 0.05
alpha = 1.5707963267948966
[[links]]
type = "R"
d = 0.35
a = 0.03
alpha = -1.3
[[links]]
type = "R"
d = 0.02
a = 0.04
alpha = 1.1
[[links]]
type = "R"
d = 0.1
a = 0.0
alpha = 0.0
"#;

#[test]
fn explain_and_solve_a_parallel_pair_arm_by_elimination() {
    explain_and_solve_a_parallel_pair_arm(
        "parallel-pair",
        PARALLEL_PAIR_DH,
        "one_pair_parallel_2_3",
    );
}

#[test]
fn explain_and_solve_a_parallel_1_2_pair_arm_by_elimination() {
    explain_and_solve_a_parallel_pair_arm(
        "parallel-pair-1-2",
        PARALLEL_PAIR_1_2_DH,
        "one_pair_parallel_1_2",
    );
}

/// `armkit ik --explain` names `class` (one parallel pair) for the DH
/// file `dh` and the method, elimination; `--solver analytic` returns only
/// exact solutions, the generating configuration nearest the start first
/// (the retired `--search 1d` is a case of `bad_inputs`).
fn explain_and_solve_a_parallel_pair_arm(name: &str, dh: &str, class: &str) {
    let dir = std::env::temp_dir().join(format!("armkit-ik-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, dh).unwrap();
    let path = file.to_str().unwrap();
    let output = armkit(&["ik", "--robot-file", path, "--explain"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains(&format!("class: {class}\n")), "{text}");
    assert!(
        text.contains("one parallel pair of consecutive axes"),
        "{text}"
    );
    assert!(
        text.contains("method (--solver analytic, --search elimination): no closed-form class: algebraic elimination"),
        "{text}"
    );
    let model = armkit::description::load(&file).unwrap();
    let q = [0.4, -1.1, 1.3, -0.6, 1.4, 0.2];
    let pose = fk_text(&model, &q);
    let json = analytic_json(
        path,
        &pose,
        &[
            "--search",
            "elimination",
            "--start",
            "0.4,-1.1,1.3,-0.6,1.4,0.2",
        ],
    );
    assert_eq!(json["class"], class);
    let fits = json["solution_fits"].as_array().unwrap();
    assert!(!fits.is_empty());
    assert!(fits.iter().all(|f| f["fit"] == "exact"), "{fits:?}");
    // Nearest the start first: the generating configuration.
    let first: Vec<f64> = json["solutions"][0]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        first.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9),
        "{first:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A DH file of a made-up 6R arm whose only special pair is axes 3-4
/// meeting (a3 = 0): elimination with the pair in the middle.
const PAIR_3_4_DH: &str = r#"
name = "pair-3-4"
convention = "standard"
[[links]]
type = "R"
d = 0.3
a = 0.1
alpha = 1.2
[[links]]
type = "R"
d = 0.1
a = 0.4
alpha = 0.7
[[links]]
type = "R"
d = 0.05
a = 0.0
alpha = 1.5707963267948966
[[links]]
type = "R"
d = 0.35
a = 0.08
alpha = -1.1
[[links]]
type = "R"
d = 0.1
a = 0.06
alpha = 0.9
[[links]]
type = "R"
d = 0.08
a = 0.0
alpha = 0.0
"#;

#[test]
fn explain_and_solve_an_arm_with_only_axes_3_4_meeting() {
    let dir = std::env::temp_dir().join(format!("armkit-ik-pair34-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("pair-3-4.toml");
    std::fs::write(&file, PAIR_3_4_DH).unwrap();
    let path = file.to_str().unwrap();
    let output = armkit(&[
        "ik",
        "--robot-file",
        path,
        "--solver",
        "analytic",
        "--explain",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.contains("class: one_pair_intersecting_3_4\n"),
        "{text}"
    );
    assert!(text.contains("axes 3 and 4"), "{text}");
    let model = armkit::description::load(&file).unwrap();
    let q = [0.4, -1.1, 1.3, -0.6, 1.4, 0.2];
    let pose = fk_text(&model, &q);
    let json = analytic_json(path, &pose, &[]);
    assert_eq!(json["class"], "one_pair_intersecting_3_4");
    let fits = json["solution_fits"].as_array().unwrap();
    assert!(fits.iter().all(|f| f["fit"] == "exact"), "{fits:?}");
    // The generating configuration is among the solutions.
    let solutions = json["solutions"].as_array().unwrap();
    assert!(
        solutions.iter().any(|s| {
            let s = s.as_array().unwrap();
            s.iter()
                .zip(&q)
                .all(|(a, b)| armkit::math::wrap_angle(a.as_f64().unwrap() - b).abs() < 1e-8)
        }),
        "{solutions:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn analytic_json_lists_every_solution_with_the_class() {
    let q0 = [0.4, -1.1, 1.3, -0.6, 1.4, 0.2];
    let (pose, target) = pose_argument("ur5", &q0);
    let output = armkit(&[
        "ik",
        "--robot",
        "ur5",
        "--pose",
        &pose,
        "--solver",
        "analytic",
        "--start",
        "0.4,-1.1,1.3,-0.6,1.4,0.2",
        "--json",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["class"], "three_parallel_2_3_4_intersecting_5_6");
    assert_eq!(json["status"], "converged");
    let solutions = json["solutions"].as_array().unwrap();
    let fits = json["solution_fits"].as_array().unwrap();
    // By default each distinct solution once: the 8 branches, no two the
    // same modulo 2 pi.
    assert_eq!(solutions.len(), 8, "{json}");
    assert_eq!(solutions.len(), fits.len());
    for (s, f) in solutions.iter().zip(fits) {
        assert!(fk_error("ur5", &q_of(s), &target) <= 1e-9);
        assert_eq!(f["fit"], "exact");
    }
    for (i, a) in solutions.iter().enumerate() {
        for b in &solutions[..i] {
            let same = q_of(a).iter().zip(q_of(b)).all(|(x, y)| {
                let d = x - y;
                (d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round()).abs() < 1e-6
            });
            assert!(!same, "{a} and {b} are one solution");
        }
    }
    let q = q_of(&json["q"]);
    assert!(q.iter().zip(q0).all(|(a, b)| (a - b).abs() < 1e-9), "{q:?}");
    // Every 2 pi multiple within the +-2 pi limits on request.
    let output = armkit(&[
        "ik",
        "--robot",
        "ur5",
        "--pose",
        &pose,
        "--solver",
        "analytic",
        "--start",
        "0.4,-1.1,1.3,-0.6,1.4,0.2",
        "--representatives",
        "every",
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let every = json["solutions"].as_array().unwrap();
    assert!(every.len() >= 8 * 16, "{}", every.len());
    for s in every {
        assert!(fk_error("ur5", &q_of(s), &target) <= 1e-9);
    }
}

/// `--solver` takes the library's vocabulary (`armkit::ik::SolverName`),
/// the names Python's `solver=` takes (its test checks the same list).
#[test]
fn solver_names_are_the_library_vocabulary() {
    use armkit::ik::{SolverName, SOLVER_ALIASES};
    use armkit_cli::commands::ik::SolverArg;
    use clap::ValueEnum;
    let cli: Vec<String> = SolverArg::value_variants()
        .iter()
        .map(|v| v.to_possible_value().unwrap().get_name().to_string())
        .collect();
    let library: Vec<String> = SolverName::ALL.iter().map(|s| s.to_string()).collect();
    assert_eq!(cli, library);
    for v in SolverArg::value_variants() {
        assert_eq!(
            v.solver().as_str(),
            v.to_possible_value().unwrap().get_name()
        );
    }
    for (alias, solver) in SOLVER_ALIASES {
        let arg = SolverArg::from_str(alias, false).unwrap();
        assert_eq!(arg.solver(), solver, "{alias}");
    }
}

/// The analytic solver's flags with another solver are refused, naming the
/// flag and the solver.
#[test]
fn analytic_flags_with_another_solver_are_errors() {
    let (pose, _) = pose_argument("ur5", &[0.4, -1.1, 1.3, -0.6, 1.4, 0.2]);
    for (flag, value) in [("--representatives", "every"), ("--search", "1d")] {
        for solver in ["lm", "auto"] {
            let output = armkit(&[
                "ik", "--robot", "ur5", "--pose", &pose, "--solver", solver, flag, value,
            ]);
            assert_eq!(output.status.code(), Some(1));
            assert!(
                stderr(&output).contains(&format!(
                    "{flag}: only with --solver analytic (the {solver} solver does not take it)"
                )),
                "{}",
                stderr(&output)
            );
        }
    }
}

#[test]
fn seven_dof_arms_by_a_held_joint_or_a_sweep() {
    let q0 = [0.3, -0.4, 0.2, -2.0, 0.1, 1.8, 0.5];
    let (pose, target) = pose_argument("panda", &q0);
    let args = |extra: &[&str]| {
        let mut a = vec![
            "ik", "--robot", "panda", "--pose", &pose, "--solver", "analytic", "--json",
        ];
        a.extend_from_slice(extra);
        a.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        let refs: Vec<&str> = a.iter().map(|s| s.as_str()).collect();
        let output = armkit(&refs);
        assert!(output.status.success(), "{}", stderr(&output));
        serde_json::from_slice::<serde_json::Value>(&output.stdout).unwrap()
    };
    let held = run(&["--fixed-joint", "7", "--parameter", "0.5"]);
    let solutions: Vec<Vec<f64>> = held["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .map(q_of)
        .collect();
    assert!(solutions
        .iter()
        .any(|q| q.iter().zip(q0).all(|(a, b)| (a - b).abs() < 1e-8)));
    for q in &solutions {
        assert!(fk_error("panda", q, &target) <= 1e-9);
        assert_eq!(q[6], 0.5);
    }
    let swept = run(&["--fixed-joint", "7", "--sweep", "8"]);
    let swept = swept["solutions"].as_array().unwrap();
    let held_values: std::collections::BTreeSet<String> =
        swept.iter().map(|q| format!("{:.6}", q_of(q)[6])).collect();
    assert!(held_values.len() >= 3, "{held_values:?}");
    for q in swept {
        assert!(fk_error("panda", &q_of(q), &target) <= 1e-9);
    }
}

#[test]
fn auto_takes_the_analytic_route_where_it_can() {
    let (pose, target) = pose_argument("ur5", &[0.4, -1.1, 1.3, -0.6, 1.4, 0.2]);
    let output = armkit(&["ik", "--robot", "ur5", "--pose", &pose, "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["solver"], "auto");
    assert_eq!(json["route"], "analytic");
    assert!(fk_error("ur5", &q_of(&json["q"]), &target) <= 1e-9);
    let (pose, _) = pose_argument("gantry9", &[0.5, 0.5, 0.2, 0.1, -0.5, 0.9, 0.2, 0.4, 0.1]);
    let output = armkit(&["ik", "--robot", "gantry9", "--pose", &pose, "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["route"], "numeric");
}

#[test]
fn not_converging_says_why_on_stderr() {
    let output = armkit(&["ik", "--robot", "ur5", "--pose", "100,0,0.5,0,0,0"]);
    assert_eq!(output.status.code(), Some(3));
    let reason = stderr(&output);
    assert!(
        reason.starts_with("ik: unreachable: the target is 100.0"),
        "{reason}"
    );
    assert_eq!(reason.lines().count(), 1, "{reason}");
    // Within the reach ball but not reachable with this orientation.
    let output = armkit(&[
        "ik",
        "--robot",
        "ur5",
        "--pose",
        "0,0,1.05,0,0,0",
        "--solver",
        "lm",
        "--budget-ms",
        "1",
    ]);
    assert_eq!(output.status.code(), Some(3));
    let reason = stderr(&output);
    assert!(
        reason.starts_with("ik: not converged: best position error"),
        "{reason}"
    );
    assert_eq!(reason.lines().count(), 1, "{reason}");
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
    let text = fk_text(&model, &[0.2, 0.5, -0.3, -1.2, 0.4, 0.8, 0.1]);
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
        "lm,analytic,auto",
        // A wall-clock budget large enough that a loaded machine cannot cut
        // a solve short: the assertion is about success, not speed.
        "--budget-ms",
        "1000",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    for solver in ["lm", "analytic", "auto"] {
        assert!(
            text.contains(&format!("| ur5 | {solver} | 100.00 % (40/40) |")),
            "{text}"
        );
    }
    let output = armkit(&[
        "bench-ik",
        "--robot",
        "gantry9",
        "--targets",
        "5",
        "--solver",
        "analytic",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("no analytic solver"));
    // The redundancy options reach the analytic solver: the Panda with its
    // first joint held solves (a held end joint only moves the target).
    let output = armkit(&[
        "bench-ik",
        "--robot",
        "panda",
        "--targets",
        "20",
        "--solver",
        "analytic",
        "--fixed-joint",
        "1",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("| panda | analytic |"),
        "{}",
        stdout(&output)
    );
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
        text.contains("| puma560 | analytic | 100.00 % (40/40) |"),
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

/// A general 6R arm (no two consecutive axes meet or are parallel).
const GENERAL_6R_DH: &str = r#"
name = "general-6r"
convention = "standard"
[[links]]
type = "R"
d = 0.3
a = 0.1
alpha = 1.2
[[links]]
type = "R"
d = 0.05
a = 0.4
alpha = 0.3
[[links]]
type = "R"
d = -0.04
a = 0.35
alpha = -0.9
[[links]]
type = "R"
d = 0.2
a = 0.03
alpha = 1.4
[[links]]
type = "R"
d = 0.02
a = 0.04
alpha = 1.1
[[links]]
type = "R"
d = 0.1
a = 0.02
alpha = 0.7
"#;

/// `--explain --json` says solvable for an arm only elimination (the
/// default method) solves, and `--solver analytic` solves it.
#[test]
fn explain_json_is_solvable_where_elimination_solves() {
    let dir = std::env::temp_dir().join(format!("armkit-ik-general-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("general-6r.toml");
    std::fs::write(&file, GENERAL_6R_DH).unwrap();
    let path = file.to_str().unwrap();
    let output = armkit(&["ik", "--robot-file", path, "--explain", "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert!(
        json["class"].as_str().unwrap().starts_with("general_6r"),
        "{json}"
    );
    assert_eq!(json["solvable"], true, "{json}");
    let model = armkit::description::load(&file).unwrap();
    let q = [0.4, -1.1, 1.3, -0.6, 1.4, 0.2];
    let pose = fk_text(&model, &q);
    let json = analytic_json(path, &pose, &[]);
    assert_eq!(json["status"], "converged");
}

/// A held joint's value outside its limits is an error naming the flag.
#[test]
fn held_joint_outside_its_limits_is_an_error() {
    let output = armkit(&[
        "ik",
        "--robot",
        "panda",
        "--pose",
        "0.4,0.1,0.5,3.14,0,0",
        "--solver",
        "analytic",
        "--fixed-joint",
        "7",
        "--parameter",
        "10",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("--parameter: the held joint 7's value 10 is outside its limits"),
        "{}",
        stderr(&output)
    );
}
