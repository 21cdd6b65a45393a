//! Description-file errors, each asserted on its message.

use armkit::description::{parse_str, Format};

fn toml_error(text: &str) -> String {
    parse_str(text, Format::Toml, "robot.toml")
        .unwrap_err()
        .to_string()
}

fn one_link(extra: &str) -> String {
    format!("convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0.1\na = 0.2\nalpha = 0.0\n{extra}")
}

#[test]
fn a_valid_file_with_every_optional_field_loads() {
    let text = one_link(
        "theta = 0.1\noffset = 0.2\nqlim = [-1.0, 1.0]\nvlim = 2.0\nalim = 5.0\nmass = 3.0\ncom = [-0.1, 0.0, 0.0]\ninertia = [0.1, 0.2, 0.3, 0.0, 0.0, 0.0]\n",
    );
    let model = parse_str(&text, Format::Toml, "robot.toml").unwrap();
    let joint = &model.joints()[0];
    assert_eq!(joint.limits.velocity, Some(2.0));
    assert_eq!(joint.limits.acceleration, Some(5.0));
    assert_eq!(joint.inertia.unwrap().mass, 3.0);
    assert_eq!(model.name(), "robot");
}

#[test]
fn unknown_field_is_named_with_its_line() {
    let message = toml_error(&one_link("qlimit = [-1.0, 1.0]\n"));
    assert!(message.starts_with("robot.toml: "), "{message}");
    assert!(
        message.contains("unknown field `qlimit`") && message.contains("line 7"),
        "{message}"
    );
}

#[test]
fn missing_field_is_named() {
    let message =
        toml_error("convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = 0.1\nalpha = 0.0\n");
    assert!(message.contains("missing field `a`"), "{message}");
}

#[test]
fn wrong_type_is_named_with_its_line() {
    let message = toml_error(&one_link("qlim = \"wide\"\n"));
    assert!(
        message.contains("line 7") && message.contains("qlim"),
        "{message}"
    );
}

#[test]
fn bad_convention_and_joint_type_are_named() {
    let message = toml_error(
        "convention = \"sideways\"\n[[links]]\ntype = \"R\"\nd = 0.1\na = 0.2\nalpha = 0.0\n",
    );
    assert_eq!(
        message,
        "robot.toml: field `convention`: expected \"standard\" or \"modified\" (also \"modified (Craig)\"), got \"sideways\""
    );
    let message = toml_error("convention = \"modified (Craig)\"\n[[links]]\ntype = \"X\"\nd = 0.1\na = 0.2\nalpha = 0.0\n");
    assert_eq!(
        message,
        "robot.toml: link 0, field `type`: expected \"R\" or \"P\", got \"X\""
    );
}

#[test]
fn inverted_and_nan_limits_name_the_link() {
    let message = toml_error(&one_link("qlim = [1.0, -1.0]\n"));
    assert_eq!(
        message,
        "robot.toml: invalid model: link 0 (`q1`), field `qlim`: lower limit 1 is above upper limit -1"
    );
    let message = toml_error(&one_link("qlim = [nan, 1.0]\n"));
    assert!(
        message.contains("field `qlim`: position limits must not be NaN"),
        "{message}"
    );
}

#[test]
fn non_finite_dh_parameter_is_named() {
    let text =
        "convention = \"standard\"\n[[links]]\ntype = \"R\"\nd = inf\na = 0.2\nalpha = 0.0\n";
    let message = toml_error(text);
    assert_eq!(
        message,
        "robot.toml: invalid model: link 0 (`q1`), field `d`: must be finite, got inf"
    );
}

#[test]
fn bad_mass_properties_are_named() {
    let message = toml_error(&one_link("com = [0.0, 0.0, 0.1]\n"));
    assert_eq!(
        message,
        "robot.toml: link 0, field `mass`: `com` or `inertia` is given without `mass`"
    );
    let message = toml_error(&one_link("mass = -2.0\n"));
    assert!(
        message.ends_with("field `mass`: must be finite and >= 0, got -2"),
        "{message}"
    );
    let message = toml_error(&one_link(
        "mass = 1.0\ninertia = [1.0, 1.0, -1.0, 0.0, 0.0, 0.0]\n",
    ));
    assert!(message.contains("positive semi-definite"), "{message}");
}

#[test]
fn bad_base_or_tool_matrix_is_named() {
    let text = format!(
        "base = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[1,0,0,1]]\n{}",
        one_link("")
    );
    let message = toml_error(&text);
    assert!(
        message.starts_with("robot.toml: field `base`: last row must be"),
        "{message}"
    );
    let text = format!(
        "tool = [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n{}",
        one_link("")
    );
    let message = toml_error(&text);
    assert!(
        message.starts_with("robot.toml: field `tool`: rotation block is not orthonormal"),
        "{message}"
    );
}

#[test]
fn empty_chain_is_an_error() {
    let message = toml_error("convention = \"standard\"\nlinks = []\n");
    assert_eq!(
        message,
        "robot.toml: field `links`: the chain has no links (an empty chain)"
    );
}

#[test]
fn malformed_json_gives_line_and_column() {
    let message = parse_str(
        "{\"convention\": \"standard\",\n \"links\": [}",
        Format::Json,
        "robot.json",
    )
    .unwrap_err()
    .to_string();
    assert!(
        message.starts_with("robot.json: invalid JSON") && message.contains("line 2"),
        "{message}"
    );
}

#[test]
fn a_bad_dh_block_inside_a_reference_file_is_located() {
    let text = r#"{"robot": "x", "dh": {"convention": "standard", "links": [{"type": "R", "d": 0, "a": 0}]}}"#;
    let message = parse_str(text, Format::Json, "ref.json")
        .unwrap_err()
        .to_string();
    assert_eq!(
        message,
        "ref.json: in the `dh` block: missing field `alpha`"
    );
}

#[test]
fn a_reference_file_takes_its_robot_name() {
    let path = format!(
        "{}/../../tests/data/reference_ur5_dh.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let model = armkit::description::load(path).unwrap();
    assert_eq!(model.name(), "ur5_dh");
    // qlim null: revolute joints without limits become continuous joints.
    assert_eq!(model.joints()[0].kind, armkit::model::JointKind::Continuous);
}
