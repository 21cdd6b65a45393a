//! Scenarios as users write them: every method table
//! runs on the user's own robot (a built-in, a DH file or a URDF) with the
//! target or path the command line takes, and produces a report whose
//! checks are what armkit promises for any robot (converged, errors within
//! tolerance, limits respected), not seed-paper claims. Each test asserts
//! the report's checks and values, and where it can, recomputes a value
//! from the report's own data (the animation's end-effector track) instead
//! of trusting the check. Bad scenario input gets a file:line error naming
//! the key.

use crate::common;

use std::path::{Path, PathBuf};

use armkit_cli::report::{Check, Report};
use armkit_cli::scenario;

/// The repository root (relative paths in the scenarios are taken from it).
fn root() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).to_path_buf()
}

fn run(text: &str) -> Report {
    let scenario = scenario::parse(text, "user.toml", &root()).unwrap();
    scenario.run().unwrap()
}

fn error(text: &str) -> String {
    match scenario::parse(text, "user.toml", &root()) {
        Err(e) => e.0,
        Ok(scenario) => scenario.run().unwrap_err().0,
    }
}

fn check<'a>(report: &'a Report, name: &str) -> &'a Check {
    report
        .checks
        .iter()
        .find(|c| c.name.starts_with(name))
        .unwrap_or_else(|| panic!("no check `{name}` in {:#?}", report.checks))
}

fn assert_all_pass(report: &Report) {
    for c in &report.checks {
        assert!(c.passed(), "{}: {c}", report.name);
    }
}

/// The end effector's position in the last frame of the report's animation.
fn final_hand(report: &Report) -> [f64; 3] {
    let animation = report.animation.as_ref().unwrap();
    *animation.frames.last().unwrap().last().unwrap()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

const PANDA_MPC: &str = "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[mpc]\n\
                         target = \"0.4,0.2,0.5,3.14,0,0\"\n";

#[test]
fn mpc_runs_on_a_builtin_robot_to_the_users_target() {
    let report = run(PANDA_MPC);
    assert_all_pass(&report);
    assert!(
        report.description.starts_with("panda moves"),
        "{}",
        report.description
    );
    assert_eq!(report.checks.len(), 5, "{:#?}", report.checks);
    assert!(check(&report, "final position error").value <= 1e-4);
    assert!(check(&report, "final orientation error").value <= 1e-3);
    assert_eq!(
        check(&report, "largest excess over a joint velocity").value,
        0.0
    );
    assert_eq!(
        check(&report, "largest excess over a joint position").value,
        0.0
    );
    // The hand really went there: the animation's last frame, from the
    // recorded configurations by the report's own forward kinematics.
    let animation = report.animation.as_ref().unwrap();
    let first = *animation.frames[0].last().unwrap();
    let last = final_hand(&report);
    assert!(distance(last, [0.4, 0.2, 0.5]) <= 1e-4, "{last:?}");
    assert!(distance(first, [0.4, 0.2, 0.5]) > 0.1, "{first:?}");
    // Seed 000's figures exist for the robot's rotary joints only.
    let stems: Vec<&str> = report.figures.iter().map(|(s, _)| s.as_str()).collect();
    assert!(stems.contains(&"rotary_velocities"), "{stems:?}");
    assert!(!stems.contains(&"prismatic_velocities"), "{stems:?}");
}

#[test]
fn mpc_runs_on_a_urdf_robot_with_a_list_target_and_position_weights() {
    let report = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nurdf = \"tests/data/urdf/ur5.urdf\"\n\
         base = \"base_link\"\ntip = \"tool0\"\n[mpc]\n\
         target = [0.3, 0.3, 0.4, 3.14159, 0.0, 0.0]\nweights = \"position\"\n\
         start = \"0,-1.2,1.2,-1.57,-1.57,0\"\n",
    );
    assert_all_pass(&report);
    // Position only: no orientation check.
    assert!(report
        .checks
        .iter()
        .all(|c| !c.name.contains("orientation")));
    assert!(distance(final_hand(&report), [0.3, 0.3, 0.4]) <= 1e-4);
}

#[test]
fn an_unreachable_target_is_a_failed_check_not_an_error() {
    let report = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[mpc]\n\
         target = \"3,0,0.5,3.14,0,0\"\nmax_steps = 200\n",
    );
    let converged = check(&report, "converges");
    assert!(!converged.passed(), "{converged}");
    assert!(
        converged.detail.contains("200 steps"),
        "{}",
        converged.detail
    );
    assert!(check(&report, "final position error").value > 1.0);
    // Limits are still respected on the way.
    assert!(check(&report, "largest excess over a joint velocity").passed());
    assert!(check(&report, "largest excess over a joint position").passed());
}

#[test]
fn the_examples_still_run_seed_000() {
    let report = run("name = \"u\"\ntitle = \"t\"\n[mpc]\nexample = \"ex1\"\n");
    assert!(
        report.description.contains("gantry9-flex"),
        "{}",
        report.description
    );
    assert_all_pass(&report);
}

#[test]
fn continuous_path_runs_on_the_users_robot_and_line() {
    let report = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[continuous_path]\n\
         from = \"0,-0.3,0,-2.2,0,2.0,0.8\"\nto_pose = \"0.5,0.2,0.4,3.14159,0,0\"\n",
    );
    assert_all_pass(&report);
    assert!(check(&report, "position error at 100 points").value <= 1e-4);
    assert!(check(&report, "orientation error at the check points").value <= 1e-3);
    assert!(check(&report, "within the robot's joint").passed());
    assert!(distance(final_hand(&report), [0.5, 0.2, 0.4]) <= 1e-4);
}

#[test]
fn redundancy_runs_on_a_users_redundant_robot() {
    let report = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[redundancy]\n\
         q0 = \"0,-0.3,0,-2.2,0,2.0,0.8\"\nmove = [0.1, 0.1, -0.1]\npayload = 20.0\n",
    );
    assert_all_pass(&report);
    assert!(
        report.description.starts_with("panda:"),
        "{}",
        report.description
    );
    for name in ["minimum-norm", "energy-optimal", "priorities", "locked"] {
        assert!(check(&report, &format!("{name}: largest tracking error")).value <= 1e-3);
        assert!(check(&report, &format!("{name}: the run completes")).passed());
    }
    // Which run spends the least F is seed 001's claim: on a user's robot it
    // is a finding (with its verdict), never a check that could fail the run.
    assert!(!report
        .checks
        .iter()
        .any(|c| c.name.contains("lowest F") && c.kind == armkit::study::CheckKind::Evidence));
    assert!(
        report
            .findings
            .iter()
            .any(|f| f.claim.starts_with("seed 001, secs 1, 2 and 4") && f.measured.contains("F =")),
        "{:#?}",
        report.findings
    );
}

#[test]
fn singularity_runs_on_a_users_arm_with_a_fixed_base() {
    let report = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"puma560\"\n[singularity]\n\
         base = \"fixed\"\nthrough = \"0.3,0.5,-0.4,0.2,0,0.1\"\n\
         direction = \"0.2,-0.1,0.1,0,0.4,0\"\nk = \"1,5\"\n",
    );
    assert_all_pass(&report);
    assert!(
        report.description.starts_with("puma560 on a fixed base"),
        "{}",
        report.description
    );
    assert!(check(&report, "avoidance k=1: final position error").value <= 1e-6);
    assert!(check(&report, "avoidance k=1: final orientation error").value <= 1e-6);
    assert!(check(&report, "dls: the run completes").passed());
}

#[test]
fn space_runs_on_a_users_arm_and_base_body() {
    let report = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nurdf = \"tests/data/urdf/ur5.urdf\"\n\
         base = \"base_link\"\ntip = \"tool0\"\n[space]\nbase_mass = \"200\"\nduration = 2.0\n",
    );
    assert_all_pass(&report);
    assert!(
        report.description.starts_with("ur5 on a 200 kg base body"),
        "{}",
        report.description
    );
    assert!(check(&report, "free-floating: centre-of-mass drift").value <= 1e-9);
    assert!(check(&report, "free-floating: angular momentum").value <= 1e-4);
    assert!(check(&report, "attitude held: the base keeps its attitude").value <= 1e-12);
    assert!(check(&report, "free-floating: the base translates").value > 1e-4);
    // The UR5's six joints are animated (base centre of mass first).
    let frame = &report.animation.as_ref().unwrap().frames[0];
    assert!(frame.len() >= 7, "{}", frame.len());
}

#[test]
fn space_without_a_robot_is_still_seed_004s() {
    let report = run("name = \"u\"\ntitle = \"t\"\n[space]\nduration = 1.0\n");
    assert!(
        report
            .description
            .starts_with("space6r on its 400 kg satellite"),
        "{}",
        report.description
    );
    assert_all_pass(&report);
}

#[test]
fn every_example_scenario_runs_and_passes() {
    let dir = root().join("examples/scenarios");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 6, "{files:?}");
    let out = common::scratch("examples");
    for file in files {
        let output = common::armkit(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            output.status.success(),
            "{}: {}\n{}",
            file.display(),
            common::stderr(&output),
            common::stdout(&output)
        );
        let name = file.file_stem().unwrap().to_str().unwrap();
        let summary: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(name).join("summary.json")).unwrap(),
        )
        .unwrap();
        let checks = summary["checks"].as_array().unwrap();
        assert!(checks.len() >= 4, "{name}: {checks:?}");
        assert!(
            checks.iter().all(|c| c["pass"] == true),
            "{name}: {checks:?}"
        );
    }
}

#[test]
fn bad_scenario_input_names_the_key_at_its_line() {
    let head = "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[mpc]\n";
    // A method that needs a target, without one.
    assert_eq!(
        error(&format!("{head}horizon = 10\n")),
        "user.toml: line 5, column 1: [mpc]: missing `target` (Target pose \
         \"x,y,z,roll,pitch,yaw\" (m, rad; R = Rz(yaw) Ry(pitch) Rx(roll)))"
    );
    // A target of the wrong type: located at the key while the run parses it.
    assert_eq!(
        error(&format!("{head}target = 3\n")),
        "user.toml: line 6, column 1: [mpc]: `target`: expected 6 values, got 1"
    );
    // An unknown key: the keys the table takes are listed.
    let unknown = error(&format!(
        "{head}target = \"0.4,0.2,0.5,3.14,0,0\"\nhorizn = 5\n"
    ));
    assert!(
        unknown.starts_with(
            "user.toml: line 7, column 1: [mpc]: unknown key `horizn`; the keys of [mpc] are: "
        ),
        "{unknown}"
    );
    assert!(
        unknown.contains(" horizon,") && unknown.contains(" target,"),
        "{unknown}"
    );
    assert!(!unknown.contains("robot_file"), "{unknown}");
    // A number of the wrong type.
    assert_eq!(
        error(&format!("{head}target = \"0.4,0.2,0.5,3.14,0,0\"\nhorizon = \"ten\"\n")),
        "user.toml: line 7, column 1: [mpc]: invalid value 'ten' for `horizon`: invalid digit found in string"
    );
    // A value the library refuses, located at its key.
    assert_eq!(
        error(&format!(
            "{head}target = \"0.4,0.2,0.5,3.14,0,0\"\nhorizon = 0\n"
        )),
        "user.toml: line 7, column 1: [mpc]: invalid argument `horizon`: must be at least 1"
    );
    // [mpc] on no robot and no example.
    assert_eq!(
        error("name = \"u\"\ntitle = \"t\"\n[mpc]\ntarget = \"0.4,0.2,0.5,3.14,0,0\"\n"),
        "user.toml: line 3, column 1: [mpc] runs the MPC on your robot to `target`: add a [robot] \
         table (`builtin`, `file` or `urdf`), or give `example` to run one of seed 000's examples \
         (ex1, ex2, ex3, ex1-rigid-model, ex1-link-error, ex2-paper-weights, ex2-strict, ex3-undamped)"
    );
    // `example` with the user's robot.
    assert_eq!(
        error(&format!("{head}example = \"ex1\"\n")),
        "user.toml: line 6, column 1: [mpc]: the argument `example` cannot be used with [robot] `builtin`"
    );
    // A line without a robot.
    assert_eq!(
        error("name = \"u\"\ntitle = \"t\"\n[continuous_path]\nfrom = \"0,0,0,0\"\n"),
        "user.toml: line 3, column 1: [continuous_path] plans a line for your robot: add a [robot] \
         table (`builtin`, `file` or `urdf`)"
    );
    // Joint values of the wrong count for the user's robot.
    let from = error(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[continuous_path]\n\
         from = \"0,0,0\"\nto_pose = \"0.5,0.2,0.4,3.14159,0,0\"\n",
    );
    assert!(
        from.starts_with("user.toml: line 6, column 1: [continuous_path]: `from`: "),
        "{from}"
    );
    // Robots a method cannot take.
    assert_eq!(
        error("name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\n[beam]\n"),
        "user.toml: line 4, column 11: [beam] takes no [robot]: it runs seed 000's own gantry \
         beam (remove the [robot] table)"
    );
    assert_eq!(
        error(
            "name = \"u\"\ntitle = \"t\"\n[robot]\nurdf = \"tests/data/urdf/ur5.urdf\"\n\
             base = \"base_link\"\ntip = \"tool0\"\n[singularity]\nbase = \"fixed\"\n"
        ),
        "user.toml: line 4, column 8: [singularity] takes [robot] `builtin` or `file` (a DH \
         description): `armkit singularity` has no URDF input"
    );
    assert_eq!(
        error("name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\ntip = \"tool0\"\n[space]\n"),
        "user.toml: line 5, column 7: [robot] `base` and `tip` choose the chain of a URDF: they need `urdf`"
    );
    // An arm without mass properties on a free-floating base: at [robot].
    let massless = error(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"puma560\"\n[space]\nduration = 1.0\n",
    );
    assert!(
        massless.starts_with("user.toml: line 3, column 1: [space]: invalid model:")
            && massless.contains("mass properties"),
        "{massless}"
    );
}

#[test]
fn a_dh_file_robot_works_for_mpc_and_singularity() {
    let robot =
        "name = \"u\"\ntitle = \"t\"\n[robot]\nfile = \"tests/data/reference_puma560_dh.json\"\n";
    let mpc = run(&format!(
        "{robot}[mpc]\ntarget = \"0.4,0.2,0.3,3.14,0,0\"\n"
    ));
    assert_all_pass(&mpc);
    assert!(distance(final_hand(&mpc), [0.4, 0.2, 0.3]) <= 1e-4);
    let singularity = run(&format!(
        "{robot}[singularity]\nbase = \"fixed\"\nthrough = \"0.3,0.5,-0.4,0.2,0,0.1\"\n\
         direction = \"0.2,-0.1,0.1,0,0.4,0\"\nk = \"1\"\n"
    ));
    assert_all_pass(&singularity);
    assert!(check(&singularity, "avoidance k=1: final position error").value <= 1e-6);
}

const PANDA_LINE: &str = "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n\
                          [continuous_path]\nfrom = \"0,-0.3,0,-2.2,0,2.0,0.8\"\n";

#[test]
fn a_users_continuous_path_grades_only_armkits_promises() {
    let report = run(&format!(
        "{PANDA_LINE}to_pose = \"0.5,0.2,0.4,3.14159,0,0\"\n"
    ));
    assert_all_pass(&report);
    // No seed 002 claim, variant or sweep on the user's robot.
    assert!(report.findings.is_empty(), "{:#?}", report.findings);
    assert!(
        !report.description.contains("seed 002") && !report.description.contains("paper"),
        "{}",
        report.description
    );
    let tables: Vec<&str> = report.tables.iter().map(|t| t.title.as_str()).collect();
    assert_eq!(tables, ["Plan"]);
    assert!(report
        .checks
        .iter()
        .all(|c| !c.name.contains("comparison") && !c.name.contains("midpoint")));
    assert!(check(&report, "the plan meets the tolerance").passed());
    // The paper's scope, asked for, adds the variants and the claims.
    let paper = run(&format!(
        "{PANDA_LINE}to_pose = \"0.5,0.2,0.4,3.14159,0,0\"\nscope = \"paper\"\n\
         sweep_segments = [4, 8]\ncubic_quintic_segments = [4]\n"
    ));
    assert!(
        paper
            .findings
            .iter()
            .any(|f| f.claim.starts_with("seed 002, Fig 6")),
        "{:#?}",
        paper.findings
    );
    assert_eq!(paper.tables.len(), 3);
    assert!(paper.checks.iter().any(|c| c.name.contains("(comparison)")));
    // Seed 002's own arm gets the paper's grading by default.
    let arm4 = run(
        "name = \"u\"\ntitle = \"t\"\n[robot]\nbuiltin = \"arm4\"\n[continuous_path]\n\
         from = [0.33824988933280115, -1.9358832167391893, 0.3, 0.4]\n\
         to_q = [1.2655451073344133, -1.935883216739189, 0.3, 0.4]\n\
         law = \"trapezoidal\"\naccel_time = 0.5\nsweep_segments = [4, 8]\n",
    );
    assert!(arm4.findings.iter().any(|f| f.claim.contains("eqs 10-18")));
}

#[test]
fn a_continuous_path_that_fails_names_the_point_and_the_cause_and_still_reports() {
    // The tool turned sideways at 0.3 m: the Panda's wrist runs into joint
    // 4's and joint 5's limits at the goal (the last knot).
    let report = run(&format!("{PANDA_LINE}to_pose = \"0.3,0,0.4,0,1.57,0\"\n"));
    let failed = check(
        &report,
        "every path point is solved within the joint limits",
    );
    assert!(!failed.passed());
    for part in [
        "knot 4 of knots 0..4, t = 2.000000 s",
        "position [0.300000, 0.000000, 0.400000] m",
        "blocked by joint 4 at its lower limit -3.0718 and joint 5 at its upper limit 2.8973",
    ] {
        assert!(failed.detail.contains(part), "{part}: {}", failed.detail);
    }
    assert!(!failed.detail.contains("out of reach"), "{}", failed.detail);
    // The report holds what was asked for, and the run exits 3 with it written.
    let plan = &report.tables[0];
    assert!(plan
        .rows
        .iter()
        .any(|r| r[0] == "status" && r[1] == "not planned"));
    assert!(plan
        .rows
        .iter()
        .any(|r| r[0] == "goal" && r[1].starts_with("[0.3000, 0.0000, 0.4000] m")));
    let out = common::scratch("failing-line");
    let file = out.join("failing.toml");
    std::fs::write(
        &file,
        format!("{PANDA_LINE}to_pose = \"0.3,0,0.4,0,1.57,0\"\n").replace("\"u\"", "\"failing\""),
    )
    .unwrap();
    let output = common::armkit(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(3), "{}", common::stderr(&output));
    assert!(out.join("failing/report.html").is_file());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("failing/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["checks"][0]["pass"], false);
    // A joint limit broken along a planned line: which joint, which limit, when.
    let report = run(&format!(
        "{PANDA_LINE}to_pose = \"-0.3,-0.4,0.3,3.14159,0,0\"\n"
    ));
    let limits = check(&report, "within the robot's joint position");
    assert!(!limits.passed());
    assert!(
        limits
            .detail
            .contains("joint 2 exceeds its acceleration limit -7.5 (rad/s^2 or m/s^2) from "),
        "{}",
        limits.detail
    );
}
