//! The bad-input matrix: every bad input below goes through the `armkit`
//! binary, and each must end with a clear error (exit 1 with one `error:`
//! line, or clap's usage error, exit 2), never a panic, a crash or a silent
//! success. The table of inputs and messages is `docs/bad-inputs.md`; this
//! test rebuilds it and fails when the committed file differs, so the file
//! cannot go stale. After a deliberate change of messages, regenerate it:
//!
//!     ARMKIT_BLESS=1 cargo test -p armkit-cli --release --test it -- bad_inputs::

use std::path::{Path, PathBuf};
use std::process::Command;

/// One bad input: where it belongs, what is wrong, the command line.
struct Case {
    area: &'static str,
    what: &'static str,
    args: &'static [&'static str],
    /// Expected exit code: 1 (armkit's error), 2 (clap's usage error), 3
    /// (ran, goal not met, best effort printed).
    exit: i32,
}

const fn case(
    area: &'static str,
    what: &'static str,
    args: &'static [&'static str],
    exit: i32,
) -> Case {
    Case {
        area,
        what,
        args,
        exit,
    }
}

/// Fixture files, written into a scratch folder in which every case runs.
const FILES: &[(&str, &str)] = &[
    // DH description files.
    ("empty-links.toml", "convention = \"standard\"\nlinks = []\n"),
    (
        "bad-convention.toml",
        "convention = \"sideways\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\n",
    ),
    (
        "bad-joint-type.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"X\"\nd = 0\na = 1\nalpha = 0\n",
    ),
    (
        "missing-field.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\nalpha = 0\n",
    ),
    (
        "misspelt-field.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\nlenght = 2\n",
    ),
    ("toml-syntax.toml", "convention = \"standard\n[[links]]\n"),
    (
        "qlim-reversed.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\nqlim = [1.0, -1.0]\n",
    ),
    (
        "qlim-nan.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\nqlim = [nan, 1.0]\n",
    ),
    (
        "d-infinite.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = inf\na = 1\nalpha = 0\n",
    ),
    (
        "huge-lengths.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"P\"\nd = 1e308\na = 1e308\nalpha = 0\nqlim = [0, 1e308]\n[[links]]\ntype = \"R\"\nd = 1e308\na = 1e308\nalpha = 0\n",
    ),
    (
        "negative-mass.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\nmass = -1.0\n",
    ),
    (
        "com-without-mass.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\ncom = [0, 0, 0]\n",
    ),
    (
        "base-not-rigid.toml",
        "convention = \"standard\"\nbase = [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\n",
    ),
    ("json-truncated.json", "{\"convention\": \"standard\", \"links\": ["),
    (
        "json-wrong-type.json",
        "{\"convention\": \"standard\", \"links\": \"R\"}",
    ),
    (
        "json-dh-block.json",
        "{\"robot\": \"r\", \"dh\": {\"convention\": \"standard\"}}",
    ),
    ("empty.toml", ""),
    // A general 6R arm: no intersecting or parallel consecutive axes.
    (
        "general-6r.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0.3\na = 0.1\nalpha = 0.7\n[[links]]\ntype = \"R\"\nd = 0.05\na = 0.4\nalpha = -1.1\n[[links]]\ntype = \"R\"\nd = 0.1\na = 0.35\nalpha = 0.9\n[[links]]\ntype = \"R\"\nd = 0.25\na = 0.05\nalpha = -0.6\n[[links]]\ntype = \"R\"\nd = 0.02\na = 0.07\nalpha = 1.2\n[[links]]\ntype = \"R\"\nd = 0.1\na = 0.03\nalpha = 0.5\n",
    ),
    // URDF files.
    ("not-xml.urdf", "hello"),
    ("not-robot.urdf", "<sdf version=\"1.6\"/>"),
    ("unclosed.urdf", "<robot name=\"r\"><link name=\"a\">"),
    ("no-links.urdf", "<robot name=\"r\"/>"),
    (
        "unknown-child.urdf",
        "<robot name=\"r\"><link name=\"a\"/><joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>",
    ),
    (
        "cycle.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j1\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint><joint name=\"j2\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint></robot>",
    ),
    (
        "two-leaves.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><joint name=\"j1\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint><joint name=\"j2\" type=\"continuous\"><parent link=\"a\"/><child link=\"c\"/></joint></robot>",
    ),
    (
        "zero-axis.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 0\"/></joint></robot>",
    ),
    (
        "short-origin.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"1 2\"/></joint></robot>",
    ),
    (
        "nan-origin.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"nan 0 0\"/></joint></robot>",
    ),
    (
        "limit-reversed.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"1\" upper=\"-1\" effort=\"1\" velocity=\"1\"/></joint></robot>",
    ),
    (
        "revolute-without-limit.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>",
    ),
    (
        "only-fixed-joints.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>",
    ),
    (
        "unknown-joint-type.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"hinge\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>",
    ),
    (
        "mimic-leader-missing.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"ghost\"/></joint></robot>",
    ),
    (
        "mimic-cycle.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><link name=\"e\"/><link name=\"f\"/><joint name=\"j3\" type=\"revolute\"><parent link=\"a\"/><child link=\"e\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j4\"/></joint><joint name=\"j4\" type=\"revolute\"><parent link=\"a\"/><child link=\"f\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j3\"/></joint><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j3\"/></joint></robot>",
    ),
    (
        "mimic-infinite-multiplier.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j1\" multiplier=\"inf\"/></joint></robot>",
    ),
    (
        "mimic-no-range.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j1\" offset=\"3\"/></joint></robot>",
    ),
    (
        "mimic-masses.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link><link name=\"c\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><origin xyz=\"0.3 0 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j1\" multiplier=\"0.5\"/></joint></robot>",
    ),
    (
        "mimic-ok.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j1\" multiplier=\"2\"/></joint></robot>",
    ),
    // Scenario files.
    ("scenario-syntax.toml", "name = \n"),
    ("scenario-no-name.toml", "title = \"t\"\n[beam]\n"),
    (
        "scenario-bad-name.toml",
        "name = \"../up\"\ntitle = \"t\"\n[beam]\n",
    ),
    ("scenario-no-method.toml", "name = \"s\"\ntitle = \"t\"\n"),
    (
        "scenario-two-methods.toml",
        "name = \"s\"\ntitle = \"t\"\n[beam]\n[mpc]\n",
    ),
    (
        "scenario-unknown-table.toml",
        "name = \"s\"\ntitle = \"t\"\n[beams]\n",
    ),
    (
        "scenario-unknown-option.toml",
        "name = \"s\"\ntitle = \"t\"\n[beam]\nmas = 3.0\n",
    ),
    (
        "scenario-bad-value.toml",
        "name = \"s\"\ntitle = \"t\"\n[beam]\nmass = \"heavy\"\n",
    ),
    (
        "scenario-table-value.toml",
        "name = \"s\"\ntitle = \"t\"\n[beam]\nmass = { kg = 3 }\n",
    ),
    (
        "scenario-negative-mass.toml",
        "name = \"s\"\ntitle = \"t\"\n[beam]\nmass = -400.0\n",
    ),
    (
        "scenario-unknown-robot.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"r2d2\"\n[redundancy]\n",
    ),
    (
        "scenario-two-robots.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\nfile = \"x.toml\"\n[redundancy]\n",
    ),
    (
        "scenario-missing-robot-file.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nfile = \"nope.toml\"\n[redundancy]\n",
    ),
    (
        "scenario-bad-robot-file.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nfile = \"bad-convention.toml\"\n[redundancy]\n",
    ),
    (
        "scenario-bad-urdf.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nurdf = \"cycle.urdf\"\n[redundancy]\n",
    ),
    (
        "scenario-unknown-example.toml",
        "name = \"s\"\ntitle = \"t\"\n[mpc]\nexample = \"ex9\"\n",
    ),
    (
        "scenario-robot-for-beam.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\n[beam]\n",
    ),
    // Scenarios as users write them.
    (
        "scenario-mpc-no-target.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[mpc]\nhorizon = 10\n",
    ),
    (
        "scenario-mpc-target-number.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[mpc]\ntarget = 3\n",
    ),
    (
        "scenario-redundancy-payload-nan.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"gantry9\"\n[redundancy]\npayload = nan\n",
    ),
    (
        "scenario-mpc-boolean-horizon.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\n[mpc]\nhorizon = true\ntarget = \"0.4,0.2,0.5,0,0,0\"\n",
    ),
    (
        "scenario-switch-number.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"gantry9\"\n[redundancy]\nno_gravity = 3\n",
    ),
    (
        "scenario-singularity-tiny-dt.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"space6r\"\n[singularity]\ndt = 1e-12\n",
    ),
    (
        "scenario-mpc-no-robot.toml",
        "name = \"s\"\ntitle = \"t\"\n[mpc]\ntarget = \"0.4,0.2,0.5,3.14,0,0\"\n",
    ),
    (
        "scenario-mpc-example-and-robot.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[mpc]\nexample = \"ex1\"\n",
    ),
    (
        "scenario-line-no-robot.toml",
        "name = \"s\"\ntitle = \"t\"\n[continuous_path]\nfrom = \"0,0,0,0\"\n",
    ),
    (
        "scenario-line-short-from.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"panda\"\n[continuous_path]\nfrom = \"0,0,0\"\nto_pose = \"0.5,0.2,0.4,3.14159,0,0\"\n",
    ),
    (
        "scenario-singularity-urdf.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nurdf = \"mimic-ok.urdf\"\n[singularity]\nbase = \"fixed\"\n",
    ),
    (
        "scenario-tip-without-urdf.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"ur5\"\ntip = \"tool0\"\n[space]\n",
    ),
    (
        "scenario-space-massless-arm.toml",
        "name = \"s\"\ntitle = \"t\"\n[robot]\nbuiltin = \"puma560\"\n[space]\nduration = 1.0\n",
    ),
    // Dynamics: an inertia that is not positive semi-definite, a link without mass.
    (
        "indefinite-inertia.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\nmass = 1.0\ninertia = [0.1, 0.1, -0.05, 0, 0, 0]\n",
    ),
    (
        "second-link-massless.toml",
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\nmass = 1.0\n[[links]]\ntype = \"R\"\nd = 0\na = 1\nalpha = 0\n",
    ),    (
        "point-mass-on-axis.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"><inertial><origin xyz=\"0.3 0 0\"/><mass value=\"1\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link><link name=\"c\"><inertial><mass value=\"1\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link><joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><origin xyz=\"0.3 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>",
    ),
];

/// Every case. Joint values for ur5 are 6, gantry9 9.
const CASES: &[Case] = &[
    // Robot selection.
    case("robot", "no robot", &["fk", "--q", "0"], 1),
    case(
        "robot",
        "unknown built-in",
        &["fk", "--robot", "r2d2", "--q", "0"],
        1,
    ),
    case(
        "robot",
        "two robot sources",
        &["fk", "--robot", "ur5", "--robot-file", "x.toml", "--q", "0"],
        2,
    ),
    case(
        "robot",
        "--tip without --urdf",
        &[
            "fk",
            "--robot",
            "ur5",
            "--tip",
            "tool0",
            "--q",
            "0,0,0,0,0,0",
        ],
        1,
    ),
    case(
        "robot",
        "missing description file",
        &["fk", "--robot-file", "nope.toml", "--q", "0"],
        1,
    ),
    case(
        "robot",
        "missing URDF",
        &["fk", "--urdf", "nope.urdf", "--q", "0"],
        1,
    ),
    // Numbers and poses.
    case(
        "numbers",
        "too few joint values",
        &["fk", "--robot", "ur5", "--q", "1,2,3"],
        1,
    ),
    case(
        "numbers",
        "too many joint values",
        &["fk", "--robot", "ur5", "--q", "0,0,0,0,0,0,0"],
        1,
    ),
    case(
        "numbers",
        "empty list",
        &["fk", "--robot", "ur5", "--q", ""],
        1,
    ),
    case(
        "numbers",
        "empty entry",
        &["fk", "--robot", "ur5", "--q", "0,,0,0,0,0"],
        1,
    ),
    case(
        "numbers",
        "not a number",
        &["fk", "--robot", "ur5", "--q", "0,0,x,0,0,0"],
        1,
    ),
    case(
        "numbers",
        "NaN",
        &["fk", "--robot", "ur5", "--q", "0,0,0,nan,0,0"],
        1,
    ),
    case(
        "numbers",
        "infinity",
        &["fk", "--robot", "ur5", "--q", "0,0,0,0,inf,0"],
        1,
    ),
    case(
        "numbers",
        "overflow to infinity",
        &["fk", "--robot", "ur5", "--q", "1e400,0,0,0,0,0"],
        1,
    ),
    case(
        "numbers",
        "pi over zero",
        &["fk", "--robot", "ur5", "--q", "0,0,0,0,0,pi/0"],
        1,
    ),
    case(
        "numbers",
        "bad unit",
        &["fk", "--robot", "ur5", "--q", "90degrees,0,0,0,0,0"],
        1,
    ),
    case(
        "numbers",
        "bad pi expression",
        &["fk", "--robot", "ur5", "--q", "pi*pi,0,0,0,0,0"],
        1,
    ),
    case(
        "numbers",
        "outside the joint limits",
        &["fk", "--robot", "ur5", "--q", "0,0,0,0,0,10"],
        1,
    ),
    case(
        "numbers",
        "pose with three values",
        &["ik", "--robot", "ur5", "--pose", "0.4,0.1,0.5"],
        1,
    ),
    case(
        "numbers",
        "pose with NaN",
        &["ik", "--robot", "ur5", "--pose", "0.4,0.1,nan,0,0,0"],
        1,
    ),
    // jacobian.
    case(
        "jacobian",
        "wrong joint count",
        &["jacobian", "--robot", "ur5", "--q", "1"],
        1,
    ),
    case(
        "jacobian",
        "unknown frame",
        &[
            "jacobian",
            "--robot",
            "ur5",
            "--q",
            "0,0,0,0,0,0",
            "--frame",
            "tool",
        ],
        2,
    ),
    // ik.
    case(
        "ik",
        "start of the wrong size",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--start",
            "0,0",
        ],
        1,
    ),
    case(
        "ik",
        "negative tolerance",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--position-tolerance",
            "-1",
        ],
        1,
    ),
    case(
        "ik",
        "NaN tolerance",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--orientation-tolerance",
            "nan",
        ],
        1,
    ),
    case(
        "ik",
        "unknown solver",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "magic",
        ],
        2,
    ),
    case(
        "ik",
        "closed form for a robot without one",
        &[
            "ik",
            "--robot",
            "gantry9",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "closed-form",
        ],
        1,
    ),
    case(
        "ik",
        "analytic solver asked for a class it cannot handle",
        &[
            "ik",
            "--robot",
            "gantry9",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
        ],
        1,
    ),
    case(
        "ik",
        "retired --search 1d (the value named)",
        &[
            "ik",
            "--robot-file",
            "general-6r.toml",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--search",
            "1d",
        ],
        1,
    ),
    case(
        "ik",
        "unknown --search value",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--search",
            "3d",
        ],
        2,
    ),
    case(
        "ik",
        "no pose and no --explain",
        &["ik", "--robot", "ur5"],
        1,
    ),
    case(
        "ik",
        "held joint out of range",
        &[
            "ik",
            "--robot",
            "panda",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--fixed-joint",
            "9",
        ],
        1,
    ),
    case(
        "ik",
        "held joint on a 6-joint arm",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--fixed-joint",
            "2",
        ],
        1,
    ),
    case(
        "ik",
        "NaN redundancy parameter",
        &[
            "ik",
            "--robot",
            "panda",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--fixed-joint",
            "7",
            "--parameter",
            "nan",
        ],
        1,
    ),
    case(
        "ik",
        "sweep of zero values",
        &[
            "ik",
            "--robot",
            "panda",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--sweep",
            "0",
        ],
        1,
    ),
    case(
        "ik",
        "bench-ik with --sweep (it times one parameter value)",
        &[
            "bench-ik",
            "--robot",
            "panda",
            "--targets",
            "5",
            "--solver",
            "analytic",
            "--sweep",
            "4",
        ],
        1,
    ),
    case(
        "ik",
        "bench-ik --fixed-joint without the analytic solver",
        &[
            "bench-ik",
            "--robot",
            "panda",
            "--targets",
            "5",
            "--solver",
            "lm",
            "--fixed-joint",
            "7",
        ],
        1,
    ),
    case(
        "ik",
        "bench-ik --search 2d without the analytic solver",
        &[
            "bench-ik",
            "--robot",
            "ur5",
            "--targets",
            "5",
            "--search",
            "2d",
        ],
        1,
    ),
    case(
        "ik",
        "retired --search 2d (the value named)",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--search",
            "2d",
        ],
        1,
    ),
    case(
        "ik",
        "target beyond the sum of the link lengths (reason on stderr)",
        &["ik", "--robot", "ur5", "--pose", "100,0,0.5,0,0,0"],
        3,
    ),
    case(
        "ik",
        "unreachable target (not an error: best effort, exit 3)",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "5,0,0,0,0,0",
            "--budget-ms",
            "2",
        ],
        3,
    ),
    // traj.
    case(
        "traj",
        "from of the wrong size",
        &[
            "traj",
            "joint",
            "--robot",
            "ur5",
            "--from",
            "0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "2",
        ],
        1,
    ),
    case(
        "traj",
        "negative duration",
        &[
            "traj",
            "joint",
            "--robot",
            "ur5",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "-2",
        ],
        1,
    ),
    case(
        "traj",
        "NaN duration",
        &[
            "traj",
            "joint",
            "--robot",
            "ur5",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "nan",
        ],
        1,
    ),
    case(
        "traj",
        "trapezoid acceleration time over half the duration",
        &[
            "traj",
            "joint",
            "--robot",
            "ur5",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--profile",
            "trapezoidal",
            "--duration",
            "2",
            "--accel-time",
            "1.5",
        ],
        1,
    ),
    case(
        "traj",
        "zero sample step",
        &[
            "traj",
            "joint",
            "--robot",
            "ur5",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "2",
            "--dt",
            "0",
        ],
        1,
    ),
    case(
        "traj",
        "target outside the limits",
        &[
            "traj",
            "joint",
            "--robot",
            "ur5",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "0,0,0,0,0,10",
            "--duration",
            "2",
        ],
        1,
    ),
    case(
        "traj",
        "line: pose of five values",
        &[
            "traj",
            "line",
            "--robot",
            "ur5",
            "--from",
            "0,-1,1,0,1,0",
            "--to-pose",
            "0.4,0.1,0.5,0,0",
            "--duration",
            "2",
        ],
        1,
    ),
    case(
        "traj",
        "line: zero tolerance",
        &[
            "traj",
            "line",
            "--robot",
            "ur5",
            "--from",
            "0,-1,1,0,1,0",
            "--to-q",
            "0.1,-1,1,0,1,0",
            "--duration",
            "2",
            "--tolerance",
            "0",
        ],
        1,
    ),
    case(
        "traj",
        "line: zero segments",
        &[
            "traj",
            "line",
            "--robot",
            "arm4",
            "--from",
            "0,0.5,0.5,0",
            "--to-q",
            "0.1,0.5,0.5,0",
            "--duration",
            "2",
            "--segments",
            "0",
        ],
        1,
    ),
    case(
        "traj",
        "line: --dynamics without a torque check",
        &[
            "traj",
            "line",
            "--robot",
            "panda",
            "--from",
            "0,-0.3,0,-2.2,0,2,0.8",
            "--to-pose",
            "0.484,0.3,0.413,3.14159,-0.1,0",
            "--dynamics",
            "panda-urdf",
        ],
        1,
    ),
    case(
        "traj",
        "line: zero speed-up of the torque check",
        &[
            "traj",
            "line",
            "--robot",
            "panda",
            "--from",
            "0,-0.3,0,-2.2,0,2,0.8",
            "--to-pose",
            "0.484,0.3,0.413,3.14159,-0.1,0",
            "--torques",
            "--dynamics",
            "panda-urdf",
            "--speed-up",
            "0",
        ],
        1,
    ),
    case(
        "traj",
        "line: torque check on a robot without masses",
        &[
            "traj",
            "line",
            "--robot",
            "arm4",
            "--from",
            "0,0.5,0.5,0",
            "--to-q",
            "0.1,0.5,0.5,0",
            "--torques",
        ],
        1,
    ),
    case(
        "traj",
        "line: both targets",
        &[
            "traj",
            "line",
            "--robot",
            "ur5",
            "--from",
            "0,-1,1,0,1,0",
            "--to-q",
            "0.1,-1,1,0,1,0",
            "--to-pose",
            "0.4,0.1,0.5,0,0,0",
            "--duration",
            "2",
        ],
        2,
    ),
    // mpc.
    case(
        "mpc",
        "target of the wrong size",
        &["mpc", "--robot", "ur5", "--target", "0.4,0.1"],
        1,
    ),
    case(
        "mpc",
        "a convergence tolerance of zero",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,3.14,0,0",
            "--position-tolerance",
            "0",
        ],
        1,
    ),
    case(
        "mpc",
        "zero horizon",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--horizon",
            "0",
        ],
        1,
    ),
    case(
        "mpc",
        "control horizon over the horizon",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--horizon",
            "5",
            "--control-horizon",
            "6",
        ],
        1,
    ),
    case(
        "mpc",
        "zero sample time",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--dt",
            "0",
        ],
        1,
    ),
    case(
        "mpc",
        "unknown weights",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--weights",
            "heavy",
        ],
        1,
    ),
    case(
        "mpc",
        "priorities of the wrong size",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--priorities",
            "1,2",
        ],
        1,
    ),
    case(
        "mpc",
        "negative priority",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--priorities",
            "1,1,1,1,1,-1",
        ],
        1,
    ),
    case(
        "mpc",
        "NaN velocity weight",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--velocity-weight",
            "nan",
        ],
        1,
    ),
    case("mpc", "unknown example", &["mpc", "--example", "ex9"], 1),
    case(
        "mpc",
        "unknown reach aid",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--reach",
            "magic",
        ],
        2,
    ),
    case(
        "mpc",
        "unknown QP solver",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--solver",
            "qpoases",
        ],
        2,
    ),
    case(
        "mpc",
        "target out of reach",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "3,0,0,0,0,0",
            "--max-steps",
            "100",
        ],
        3,
    ),
    case("mpc", "no target", &["mpc", "--robot", "ur5"], 2),
    case(
        "mpc",
        "negative prismatic resolution",
        &["mpc", "--example", "3", "--prismatic-resolution", "-0.001"],
        1,
    ),
    case(
        "mpc",
        "NaN prismatic deadband",
        &[
            "mpc",
            "--robot",
            "gantry9",
            "--target",
            "4,2,4.5,0,0,0",
            "--prismatic-deadband",
            "nan",
        ],
        1,
    ),
    // redundancy.
    case(
        "redundancy",
        "q0 of the wrong size",
        &["redundancy", "--robot", "gantry9", "--q0", "1,2,3"],
        1,
    ),
    case(
        "redundancy",
        "move of two values",
        &["redundancy", "--robot", "gantry9", "--move", "0.1,0.2"],
        1,
    ),
    case(
        "redundancy",
        "zero duration",
        &["redundancy", "--robot", "gantry9", "--duration", "0"],
        1,
    ),
    case(
        "redundancy",
        "NaN payload",
        &["redundancy", "--robot", "gantry9", "--payload", "nan"],
        1,
    ),
    case(
        "redundancy",
        "negative priority",
        &[
            "redundancy",
            "--robot",
            "gantry9",
            "--priorities",
            "1,1,1,1,1,1,1,1,-1",
        ],
        1,
    ),
    case(
        "redundancy",
        "lock a joint that does not exist",
        &["redundancy", "--robot", "gantry9", "--lock", "12"],
        1,
    ),
    case(
        "redundancy",
        "unstable gain",
        &["redundancy", "--robot", "gantry9", "--gain", "1000"],
        1,
    ),
    case(
        "redundancy",
        "negative damping",
        &["redundancy", "--robot", "gantry9", "--damping", "-1"],
        1,
    ),
    case(
        "redundancy",
        "a robot with no spare joint",
        &["redundancy", "--robot", "arm4"],
        1,
    ),
    // beam.
    case(
        "beam",
        "negative mass",
        &["beam", "table1", "--mass", "-400"],
        1,
    ),
    case(
        "beam",
        "NaN gravity",
        &["beam", "table1", "--gravity", "nan"],
        1,
    ),
    case(
        "beam",
        "one sample",
        &[
            "beam",
            "error-along-beam",
            "--samples",
            "1",
            "--out",
            "beam-out",
        ],
        1,
    ),
    case(
        "beam",
        "q of the wrong size",
        &[
            "beam",
            "error-along-beam",
            "--q",
            "1,2",
            "--out",
            "beam-out",
        ],
        1,
    ),
    // space.
    case(
        "space",
        "study with a zero duration",
        &["space", "study", "--duration", "0"],
        1,
    ),
    case(
        "space",
        "study start with 2 joints",
        &["space", "study", "--start", "0.1,0.2"],
        1,
    ),
    case(
        "space",
        "robot without mass properties",
        &[
            "space",
            "jacobian",
            "--robot",
            "puma560",
            "--q",
            "0,0,0,0,0,0",
        ],
        1,
    ),
    case(
        "space",
        "zero base mass",
        &[
            "space",
            "jacobian",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--base-mass",
            "0",
        ],
        1,
    ),
    case(
        "space",
        "base inertia of two values",
        &[
            "space",
            "jacobian",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--base-inertia",
            "1,2",
        ],
        1,
    ),
    case(
        "space",
        "NaN base pose",
        &[
            "space",
            "jacobian",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--base-pose",
            "0,0,nan,0,0,0",
        ],
        1,
    ),
    case(
        "space",
        "negative duration",
        &[
            "space",
            "simulate",
            "--robot",
            "space6r",
            "--duration",
            "-1",
        ],
        1,
    ),
    case(
        "space",
        "zero time step",
        &["space", "simulate", "--robot", "space6r", "--dt", "0"],
        1,
    ),
    case(
        "space",
        "NaN amplitude",
        &[
            "space",
            "simulate",
            "--robot",
            "space6r",
            "--amplitude",
            "nan",
        ],
        1,
    ),
    case(
        "space",
        "goal of the wrong size",
        &["space", "track", "--robot", "space6r", "--goal", "1,2,3"],
        1,
    ),
    case(
        "space",
        "negative damping",
        &[
            "space",
            "track",
            "--robot",
            "space6r",
            "--goal",
            "1,0.2,0.8,0,0,0",
            "--damping",
            "-1",
        ],
        1,
    ),
    case(
        "space",
        "acceleration time over half the duration",
        &[
            "space",
            "track",
            "--robot",
            "space6r",
            "--goal",
            "1,0.2,0.8,0,0,0",
            "--duration",
            "2",
            "--accel-time",
            "1.5",
        ],
        1,
    ),
    // manipulability.
    case(
        "manipulability",
        "zero tolerance",
        &[
            "manipulability",
            "--robot",
            "puma560",
            "--q",
            "0,0,0,0,0,0",
            "--tolerance",
            "0",
        ],
        1,
    ),
    // Description files.
    case(
        "description",
        "empty chain",
        &["fk", "--robot-file", "empty-links.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "unknown convention",
        &["fk", "--robot-file", "bad-convention.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "unknown joint type",
        &["fk", "--robot-file", "bad-joint-type.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "missing field",
        &["fk", "--robot-file", "missing-field.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "misspelt field",
        &["fk", "--robot-file", "misspelt-field.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "TOML syntax error",
        &["fk", "--robot-file", "toml-syntax.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "limits reversed",
        &["fk", "--robot-file", "qlim-reversed.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "NaN limit",
        &["fk", "--robot-file", "qlim-nan.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "infinite length",
        &["fk", "--robot-file", "d-infinite.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "lengths so large that FK overflows",
        &["fk", "--robot-file", "huge-lengths.toml", "--q", "1e308,0"],
        1,
    ),
    case(
        "description",
        "negative mass",
        &["fk", "--robot-file", "negative-mass.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "centre of mass without a mass",
        &["fk", "--robot-file", "com-without-mass.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "base is not a rigid transform",
        &["fk", "--robot-file", "base-not-rigid.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "truncated JSON",
        &["fk", "--robot-file", "json-truncated.json", "--q", "0"],
        1,
    ),
    case(
        "description",
        "JSON field of the wrong type",
        &["fk", "--robot-file", "json-wrong-type.json", "--q", "0"],
        1,
    ),
    case(
        "description",
        "reference JSON whose dh block has no links",
        &["fk", "--robot-file", "json-dh-block.json", "--q", "0"],
        1,
    ),
    case(
        "description",
        "empty file",
        &["fk", "--robot-file", "empty.toml", "--q", "0"],
        1,
    ),
    case(
        "description",
        "a directory",
        &["fk", "--robot-file", ".", "--q", "0"],
        1,
    ),
    // URDF files.
    case(
        "urdf",
        "not XML",
        &["fk", "--urdf", "not-xml.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "root is not <robot>",
        &["fk", "--urdf", "not-robot.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "unclosed element",
        &["fk", "--urdf", "unclosed.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "no links",
        &["fk", "--urdf", "no-links.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "joint to an unknown link",
        &["fk", "--urdf", "unknown-child.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "a cycle",
        &["fk", "--urdf", "cycle.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "two leaves, no --tip",
        &["fk", "--urdf", "two-leaves.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "--tip that does not exist",
        &["fk", "--urdf", "two-leaves.urdf", "--tip", "z", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "--base below --tip",
        &[
            "fk",
            "--urdf",
            "two-leaves.urdf",
            "--base",
            "b",
            "--tip",
            "c",
            "--q",
            "0",
        ],
        1,
    ),
    case(
        "urdf",
        "zero axis",
        &["fk", "--urdf", "zero-axis.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "origin of two values",
        &["fk", "--urdf", "short-origin.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "NaN origin",
        &["fk", "--urdf", "nan-origin.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "limits reversed",
        &["fk", "--urdf", "limit-reversed.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "revolute joint without <limit>",
        &["fk", "--urdf", "revolute-without-limit.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "no moving joint",
        &["fk", "--urdf", "only-fixed-joints.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "unknown joint type",
        &["fk", "--urdf", "unknown-joint-type.urdf", "--q", "0"],
        1,
    ),
    // Scenario files.
    case(
        "scenario",
        "missing file",
        &["run", "nope.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "TOML syntax error",
        &["run", "scenario-syntax.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "no name",
        &["run", "scenario-no-name.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "name that is a path",
        &["run", "scenario-bad-name.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "no method table",
        &["run", "scenario-no-method.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "two method tables",
        &["run", "scenario-two-methods.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "unknown table",
        &["run", "scenario-unknown-table.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "unknown option",
        &["run", "scenario-unknown-option.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "option of the wrong type",
        &["run", "scenario-bad-value.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "option given a table",
        &["run", "scenario-table-value.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "negative mass",
        &["run", "scenario-negative-mass.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "unknown robot",
        &["run", "scenario-unknown-robot.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "two robot sources",
        &["run", "scenario-two-robots.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "missing robot file",
        &[
            "run",
            "scenario-missing-robot-file.toml",
            "--out",
            "run-out",
        ],
        1,
    ),
    case(
        "scenario",
        "bad robot file",
        &["run", "scenario-bad-robot-file.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "bad URDF",
        &["run", "scenario-bad-urdf.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "unknown MPC example",
        &["run", "scenario-unknown-example.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "a robot for a method with its own",
        &["run", "scenario-robot-for-beam.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[mpc] on a robot without a target",
        &["run", "scenario-mpc-no-target.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[mpc] target of the wrong type",
        &["run", "scenario-mpc-target-number.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[mpc] target without a robot",
        &["run", "scenario-mpc-no-robot.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[mpc] example with a robot",
        &[
            "run",
            "scenario-mpc-example-and-robot.toml",
            "--out",
            "run-out",
        ],
        1,
    ),
    case(
        "scenario",
        "[continuous_path] without a robot",
        &["run", "scenario-line-no-robot.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[continuous_path] start of the wrong length",
        &["run", "scenario-line-short-from.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[singularity] on a URDF",
        &["run", "scenario-singularity-urdf.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[robot] tip without a URDF",
        &["run", "scenario-tip-without-urdf.toml", "--out", "run-out"],
        1,
    ),
    case(
        "scenario",
        "[space] arm without mass properties",
        &[
            "run",
            "scenario-space-massless-arm.toml",
            "--out",
            "run-out",
        ],
        1,
    ),
    // dynamics.
    case(
        "dynamics",
        "robot without masses",
        &["dynamics", "--robot", "puma560", "--q", "0,0,0,0,0,0"],
        1,
    ),
    case(
        "dynamics",
        "a link without mass (file)",
        &[
            "dynamics",
            "--robot-file",
            "second-link-massless.toml",
            "--q",
            "0,0",
        ],
        1,
    ),
    case(
        "dynamics",
        "mimic chain: one value per chain joint instead of per independent joint",
        &["dynamics", "--urdf", "mimic-masses.urdf", "--q", "0,0"],
        1,
    ),
    case(
        "dynamics",
        "mimic chain without masses",
        &["dynamics", "--urdf", "mimic-ok.urdf", "--q", "0"],
        1,
    ),
    case(
        "dynamics",
        "negative mass (file)",
        &["dynamics", "--robot-file", "negative-mass.toml", "--q", "0"],
        1,
    ),
    case(
        "dynamics",
        "inertia not positive semi-definite (file)",
        &[
            "dynamics",
            "--robot-file",
            "indefinite-inertia.toml",
            "--q",
            "0",
        ],
        1,
    ),
    case(
        "dynamics",
        "NaN velocity",
        &[
            "dynamics",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--v",
            "0,nan,0,0,0,0",
        ],
        1,
    ),
    case(
        "dynamics",
        "accelerations of the wrong size",
        &[
            "dynamics",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--a",
            "1,2",
        ],
        1,
    ),
    case(
        "dynamics",
        "torques of the wrong size",
        &[
            "dynamics",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--tau",
            "1,2,3,4,5,6,7",
        ],
        1,
    ),
    case(
        "dynamics",
        "traj torques on a robot without masses",
        &[
            "traj",
            "joint",
            "--robot",
            "puma560",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--torques",
        ],
        1,
    ),
    case(
        "dynamics",
        "traj torque limits of the wrong size",
        &[
            "traj",
            "joint",
            "--robot",
            "space6r",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--torques",
            "--torque-limits",
            "1,2",
        ],
        1,
    ),
    case(
        "dynamics",
        "traj negative torque limit",
        &[
            "traj",
            "joint",
            "--robot",
            "space6r",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--fit-torque-limits",
            "--torque-limits",
            "100,100,100,10,10,-1",
        ],
        1,
    ),
    case(
        "dynamics",
        "gravity of two values",
        &[
            "dynamics",
            "--robot",
            "space6r",
            "--q",
            "0,0,0,0,0,0",
            "--gravity",
            "0,-9.81",
        ],
        1,
    ),
    case(
        "dynamics",
        "forward dynamics on a singular mass matrix (a point mass on its joint's axis)",
        &[
            "dynamics",
            "--urdf",
            "point-mass-on-axis.urdf",
            "--q",
            "0,0",
            "--tau",
            "1,1",
        ],
        1,
    ),
    // Mimic joints and `armkit info`.
    case(
        "urdf",
        "mimic joint whose leader is missing",
        &["fk", "--urdf", "mimic-leader-missing.urdf", "--q", "0"],
        1,
    ),
    case(
        "urdf",
        "mimic joints forming a cycle",
        &[
            "fk",
            "--urdf",
            "mimic-cycle.urdf",
            "--base",
            "a",
            "--tip",
            "c",
            "--q",
            "0",
        ],
        1,
    ),
    case(
        "urdf",
        "mimic joint with a non-finite multiplier",
        &["info", "--urdf", "mimic-infinite-multiplier.urdf"],
        1,
    ),
    case(
        "urdf",
        "mimic joint whose limits leave its leader no range",
        &["info", "--urdf", "mimic-no-range.urdf"],
        1,
    ),
    case(
        "urdf",
        "q of the chain's length (mimic joints are not in q)",
        &["fk", "--urdf", "mimic-ok.urdf", "--q", "0,0"],
        1,
    ),
    case(
        "urdf",
        "mimic joint pushed past its limits through its leader",
        &["fk", "--urdf", "mimic-ok.urdf", "--q", "0.8"],
        1,
    ),
    case(
        "info",
        "--tip without --urdf",
        &["info", "--robot", "ur5", "--tip", "x"],
        1,
    ),
    case("info", "unknown robot", &["info", "--robot", "nobody"], 1),
    case(
        "singularity",
        "miss sweep not a number",
        &["singularity", "--miss-sweep", "0,x"],
        1,
    ),
    case(
        "singularity",
        "miss sweep NaN",
        &["singularity", "--miss-sweep", "0,nan"],
        1,
    ),
    case(
        "ik",
        "time budget too long for a duration",
        &[
            "ik",
            "--robot",
            "ur5",
            "--pose",
            "0.4,0.1,0.4,0,0,0",
            "--budget-ms",
            "1e300",
        ],
        1,
    ),
    case(
        "ik",
        "sweep too long to list",
        &[
            "ik",
            "--robot",
            "panda",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--sweep",
            "100000000",
        ],
        1,
    ),
    case(
        "ik",
        "held joint with a numeric solver (it would be ignored)",
        &[
            "ik",
            "--robot",
            "panda",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "lm",
            "--fixed-joint",
            "3",
        ],
        1,
    ),
    case(
        "redundancy",
        "every joint locked",
        &["redundancy", "--robot", "panda", "--lock", "1,2,3,4,5,6,7"],
        1,
    ),
    case(
        "beam",
        "more samples than a sweep takes",
        &[
            "beam",
            "error-along-beam",
            "--samples",
            "100000000000",
            "--out",
            "beam-out",
        ],
        1,
    ),
    case(
        "mpc",
        "sample time beyond a minute",
        &[
            "mpc",
            "--robot",
            "ur5",
            "--target",
            "0.4,0.1,0.5,0,0,0",
            "--dt",
            "1e300",
        ],
        1,
    ),
    case(
        "singularity",
        "ten billion control periods",
        &["singularity", "--duration", "1e8", "--dt", "0.01"],
        1,
    ),
    case(
        "singularity",
        "knot stride beyond a run",
        &["singularity", "--k", "1e300"],
        1,
    ),
    case(
        "scenario",
        "[singularity] control period of a picosecond",
        &[
            "run",
            "scenario-singularity-tiny-dt.toml",
            "--out",
            "run-out",
        ],
        1,
    ),
    case(
        "redundancy",
        "control period of a picosecond",
        &["redundancy", "--robot", "gantry9", "--dt", "1e-12"],
        1,
    ),
    case(
        "traj",
        "duration too short for the torque fit",
        &[
            "traj",
            "joint",
            "--robot",
            "space6r",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "1e-300",
            "--fit-torque-limits",
        ],
        1,
    ),
    case(
        "traj",
        "duration too long for the polynomial",
        &[
            "traj",
            "joint",
            "--robot",
            "space6r",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "1e300",
            "--torques",
        ],
        1,
    ),
    case(
        "traj",
        "torque fit below gravity (reason on stderr)",
        &[
            "traj",
            "joint",
            "--robot",
            "space6r",
            "--from",
            "0,0,0,0,0,0",
            "--to",
            "1,1,1,1,1,1",
            "--duration",
            "2",
            "--fit-torque-limits",
            "--torque-limits",
            "1e-3,1e-3,1e-3,1e-3,1e-3,1e-3",
        ],
        3,
    ),
    case(
        "traj",
        "torque fit that falls short of the limits (reason on stderr)",
        &[
            "traj",
            "line",
            "--robot",
            "panda",
            "--from",
            "0,-0.3,0,-2.2,0,2,0.8",
            "--to-pose",
            "0.484,0.3,0.413,3.14159,-0.1,0",
            "--fit-torque-limits",
            "--dynamics",
            "panda-urdf",
            "--speed-up",
            "20",
        ],
        3,
    ),
    case(
        "scenario",
        "[redundancy] NaN payload",
        &[
            "run",
            "scenario-redundancy-payload-nan.toml",
            "--out",
            "run-out",
        ],
        1,
    ),
    case(
        "scenario",
        "[mpc] a boolean for a value before another key",
        &[
            "run",
            "scenario-mpc-boolean-horizon.toml",
            "--out",
            "run-out",
        ],
        1,
    ),
    case(
        "scenario",
        "[redundancy] a number for an on/off switch",
        &["run", "scenario-switch-number.toml", "--out", "run-out"],
        1,
    ),
];

fn repository_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A scratch folder holding the fixture files.
fn fixtures() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armkit-bad-inputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in FILES {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

/// Markdown cell: pipes escaped, code in backticks.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

fn code(text: &str) -> String {
    // A double backtick fence copes with backticks inside.
    format!("`` {} ``", cell(text))
}

/// Shell-quoted argument for the table.
fn quoted(arg: &str) -> String {
    if arg.is_empty() || arg.contains([' ', '*', '"', '\'', '<', '>', '(', ')']) {
        format!("'{arg}'")
    } else {
        arg.to_string()
    }
}

/// Runs every case and returns the document, with the problems found.
fn build_document() -> (String, Vec<String>) {
    let dir = fixtures();
    let mut problems = Vec::new();
    let mut rows = Vec::new();
    for (i, c) in CASES.iter().enumerate() {
        let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
            .args(c.args)
            .current_dir(&dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        let command = format!(
            "armkit {}",
            c.args
                .iter()
                .map(|a| quoted(a))
                .collect::<Vec<_>>()
                .join(" ")
        );
        let label = format!("case {} ({}: {}): `{command}`", i + 1, c.area, c.what);
        let exit = output.status.code();
        if exit != Some(c.exit) {
            problems.push(format!(
                "{label}: exit {exit:?}, expected {}; stderr:\n{stderr}",
                c.exit
            ));
        }
        if stderr.contains("panicked") || stderr.contains("RUST_BACKTRACE") {
            problems.push(format!("{label}: panicked:\n{stderr}"));
        }
        let first = stderr.lines().next().unwrap_or("").trim().to_string();
        let message = match c.exit {
            // Not an error: the best effort is printed on stdout, and the
            // reason, when there is one, on stderr.
            3 if !first.is_empty() => format!("(exit 3, stderr) {first}"),
            3 => {
                let stdout = String::from_utf8_lossy(&output.stdout);
                let status = stdout
                    .lines()
                    .find(|l| l.contains("status") || l.contains("converged"))
                    .unwrap_or("")
                    .trim()
                    .to_string();
                format!("(exit 3, stdout) {status}")
            }
            _ => {
                if !first.starts_with("error: ") {
                    problems.push(format!(
                        "{label}: stderr does not start with `error: `:\n{stderr}"
                    ));
                }
                // armkit's own errors are one line; clap adds usage lines.
                if c.exit == 1 && stderr.trim().lines().count() != 1 {
                    problems.push(format!("{label}: more than one line on stderr:\n{stderr}"));
                }
                first
                    .trim_start_matches("error: ")
                    .replace(&dir.display().to_string(), "<dir>")
            }
        };
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} |",
            i + 1,
            c.area,
            cell(c.what),
            code(&command),
            exit.map_or("signal".to_string(), |e| e.to_string()),
            code(&message)
        ));
    }
    let _ = std::fs::remove_dir_all(&dir);
    let mut doc = String::from(
        "# Bad inputs and the errors they get\n\n\
         Generated by `crates/armkit-cli/tests/it/bad_inputs.rs`, which runs every case\n\
         below through the `armkit` binary and fails when this file differs from\n\
         what the binary prints (regenerate after a deliberate change with\n\
         `ARMKIT_BLESS=1 cargo test -p armkit-cli --release --test it -- bad_inputs::`).\n\n\
         Every case ends with a clear error: exit code 1 and one line\n\
         `error: ...` on stderr naming the file, line and column, the field or\n\
         the option; or exit code 2 for a command line clap rejects (its message\n\
         is followed by the usage). None panics. Exit 3 is not an error: the\n\
         run ended without meeting its goal (IK of an unreachable target, a\n\
         torque fit that cannot meet the limits) and printed its best effort;\n\
         the table shows its reason on stderr, or else its status on stdout.\n\
         Counts, periods and durations have documented ranges checked before\n\
         any work, so a request of 10^10 elements is refused at once (a test\n\
         times it). The commands run in a folder holding the files listed\n\
         under [Files](#files).\n\n\
         The library's own entry points are checked with NaN and infinite values\n\
         by `crates/armkit/tests/it/invariants_nonfinite.rs`, and its input formats\n\
         are fuzzed (`fuzz/README.md`).\n\n\
         | # | Area | Bad input | Command | Exit | Message (first line of stderr) |\n\
         |---|---|---|---|---|---|\n",
    );
    for row in rows {
        doc.push_str(&row);
        doc.push('\n');
    }
    doc.push_str("\n## Files\n");
    for (name, text) in FILES {
        doc.push_str(&format!("\n`{name}`:\n\n```\n{text}"));
        if !text.ends_with('\n') {
            doc.push('\n');
        }
        doc.push_str("```\n");
    }
    (doc, problems)
}

/// Lines of `expected` missing from `actual` and the reverse, in order.
fn line_diff(expected: &str, actual: &str) -> String {
    let e: Vec<&str> = expected.lines().collect();
    let a: Vec<&str> = actual.lines().collect();
    let mut out = String::new();
    for line in e.iter().filter(|l| !a.contains(l)) {
        out.push_str(&format!("- {line}\n"));
    }
    for line in a.iter().filter(|l| !e.contains(l)) {
        out.push_str(&format!("+ {line}\n"));
    }
    out
}

#[test]
fn every_bad_input_gets_a_clear_error_and_the_table_is_current() {
    let (document, problems) = build_document();
    let path = repository_root().join("docs/bad-inputs.md");
    if std::env::var("ARMKIT_BLESS").is_ok_and(|v| v == "1") {
        std::fs::write(&path, &document).unwrap();
    }
    assert!(
        problems.is_empty(),
        "{} of {} bad inputs misbehaved:\n\n{}",
        problems.len(),
        CASES.len(),
        problems.join("\n\n")
    );
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == document,
        "docs/bad-inputs.md is stale; regenerate it with\n  \
         ARMKIT_BLESS=1 cargo test -p armkit-cli --release --test it -- bad_inputs::\n\
         (- committed, + now):\n{}",
        line_diff(&committed, &document)
    );
}

/// A request of 10^10 elements (samples, control periods, sweep values) is
/// refused before any work: exit 1 in well under the time one element of
/// real work would take for all of them, and without the memory.
#[test]
fn ten_billion_element_requests_are_refused_quickly() {
    // No fixture is read and nothing is written: any folder does.
    let dir = std::env::temp_dir();
    let requests: &[&[&str]] = &[
        &["singularity", "--duration", "1e8", "--dt", "0.01"],
        &[
            "beam",
            "error-along-beam",
            "--samples",
            "10000000000",
            "--out",
            "beam-out",
        ],
        &[
            "ik",
            "--robot",
            "panda",
            "--pose",
            "0.4,0.1,0.5,pi,0,0",
            "--solver",
            "analytic",
            "--sweep",
            "10000000000",
        ],
        &["redundancy", "--robot", "gantry9", "--dt", "4e-10"],
    ];
    for args in requests {
        let start = std::time::Instant::now();
        let output = Command::new(env!("CARGO_BIN_EXE_armkit"))
            .args(*args)
            .current_dir(&dir)
            .output()
            .unwrap();
        let elapsed = start.elapsed();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
        assert!(
            elapsed < std::time::Duration::from_secs(2),
            "{args:?} took {elapsed:?}"
        );
    }
}
