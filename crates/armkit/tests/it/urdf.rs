//! The URDF loader: forward kinematics and Jacobians against Pinocchio's
//! reference files, a made-up chain with skew axes against finite differences
//! and a direct composition of the URDF transforms, mass properties, and
//! every error case on its message.

use crate::common::*;
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Matrix3, Pose, Rotation3, Vector3};
use armkit::model::JointKind;
use armkit::urdf::{load, parse_str, ChainSelection};
use armkit::Model;

const POSE_TOLERANCE: f64 = 1e-12;
const JACOBIAN_TOLERANCE: f64 = 1e-9;

fn urdf_path(name: &str) -> String {
    data_path(&format!("urdf/{name}"))
}

fn reference_json(file: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(data_path(file)).unwrap()).unwrap()
}

/// Loads `urdf` between `base` and `tip` and checks joint names, limits,
/// poses and Jacobians against the Pinocchio reference `file`.
fn check_against_pinocchio(urdf: &str, base: &str, tip: &str, file: &str) {
    let model = load(urdf_path(urdf), &ChainSelection::between(base, tip)).unwrap();
    let reference = reference_json(file);
    assert_eq!(reference["base_frame"], base);
    assert_eq!(reference["tip_frame"], tip);
    let names: Vec<String> = serde_json::from_value(reference["joint_names"].clone()).unwrap();
    let model_names: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(model_names, names, "{urdf}: joint names");
    let lower: Vec<f64> =
        serde_json::from_value(reference["joint_limits"]["lower"].clone()).unwrap();
    let upper: Vec<f64> =
        serde_json::from_value(reference["joint_limits"]["upper"].clone()).unwrap();
    assert_eq!(model.position_limits(), (lower, upper), "{urdf}: limits");

    let samples = reference_samples(file);
    assert_eq!(samples.len(), 200);
    let mut data = Data::new(&model);
    let (mut worst_pose, mut worst_jacobian) = (0.0f64, 0.0f64);
    for sample in &samples {
        let pose = *forward_kinematics(&model, &mut data, &sample.q).unwrap();
        worst_pose = worst_pose.max(pose_error(&pose, &sample.pose));
        let j = jacobian(&model, &mut data, &sample.q, JacobianFrame::World).unwrap();
        worst_jacobian = worst_jacobian.max(jacobian_error(j, &sample.jacobian));
    }
    assert!(
        worst_pose < POSE_TOLERANCE,
        "{urdf}: pose error {worst_pose:e}"
    );
    assert!(
        worst_jacobian < JACOBIAN_TOLERANCE,
        "{urdf}: Jacobian error {worst_jacobian:e}"
    );
}

#[test]
fn panda_matches_pinocchio() {
    check_against_pinocchio(
        "panda.urdf",
        "panda_link0",
        "panda_link8",
        "reference_panda.json",
    );
}

#[test]
fn ur5_matches_pinocchio() {
    check_against_pinocchio("ur5.urdf", "base_link", "tool0", "reference_ur5.json");
}

#[test]
fn iiwa14_matches_pinocchio() {
    check_against_pinocchio("iiwa14.urdf", "base_link", "tool0", "reference_iiwa14.json");
}

#[test]
fn velocity_limits_and_kinds_are_read() {
    let panda = load(
        urdf_path("panda.urdf"),
        &ChainSelection::between("panda_link0", "panda_link8"),
    )
    .unwrap();
    let velocities = panda.velocity_limits().unwrap();
    assert_eq!(velocities, [2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61]);
    assert!(panda.joints().iter().all(|j| j.kind == JointKind::Revolute));
    assert_eq!(panda.name(), "panda");

    let skewbot = load(urdf_path("skewbot.urdf"), &skewbot_chain()).unwrap();
    let kinds: Vec<JointKind> = skewbot.joints().iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Revolute,
            JointKind::Prismatic,
            JointKind::Continuous,
            JointKind::Revolute
        ]
    );
    let continuous = &skewbot.joints()[2].limits;
    assert!(continuous.lower == f64::NEG_INFINITY && continuous.upper == f64::INFINITY);
    assert_eq!(continuous.velocity, Some(3.0));
    assert_eq!(skewbot.joints()[1].limits.lower, -0.2);
    assert_eq!(skewbot.joints()[1].limits.upper, 0.4);
}

#[test]
fn a_tip_alone_chains_from_the_root_and_a_base_alone_to_the_only_leaf() {
    // Tip only: the base is the root above it (`world`, one fixed joint above
    // `base_link`): the same as from base_link, the fixed joint being the identity.
    let ur5 = load(
        urdf_path("ur5.urdf"),
        &ChainSelection::default().with_tip("tool0"),
    )
    .unwrap();
    assert_eq!(ur5.dof(), 6);
    // Base only: below panda_link7 the tree still forks (hand, fingers).
    let err = load(
        urdf_path("panda.urdf"),
        &ChainSelection::default().with_base("panda_link7"),
    )
    .unwrap_err();
    assert!(err.to_string().contains("3 leaf links"), "{err}");
    // Tip only, on a branch: from the root panda_link0 down to the left
    // finger, 7 revolute joints and the finger's prismatic joint.
    let to_finger = load(
        urdf_path("panda.urdf"),
        &ChainSelection::default().with_tip("panda_leftfinger"),
    )
    .unwrap();
    assert_eq!(to_finger.dof(), 8);
    assert_eq!(to_finger.joints()[7].kind, JointKind::Prismatic);
}

#[test]
fn load_and_parse_str_agree() {
    let path = urdf_path("iiwa14.urdf");
    let text = std::fs::read_to_string(&path).unwrap();
    let selection = ChainSelection::between("base_link", "tool0");
    let a = load(&path, &selection).unwrap();
    let b = parse_str(&text, "iiwa14", &selection).unwrap();
    assert_eq!(a.joint_placements(), b.joint_placements());
    assert_eq!(a.end_effector_placement(), b.end_effector_placement());
    assert_eq!(a.joints(), b.joints());
}

// ---------------------------------------------------------------------------
// skewbot.urdf: skew prismatic and revolute axes, rotated origins, a
// continuous joint, fixed joints before, between and after, and branches.

fn skewbot_chain() -> ChainSelection {
    ChainSelection::between("world", "tool")
}

/// The URDF, read by urdf-rs directly, for an independent composition.
fn skewbot_urdf() -> urdf_rs::Robot {
    urdf_rs::read_file(urdf_path("skewbot.urdf")).unwrap()
}

fn origin_pose(origin: &urdf_rs::Pose) -> Pose {
    let (xyz, rpy) = (origin.xyz.0, origin.rpy.0);
    let rotation = Pose::rot_z(rpy[2]) * Pose::rot_y(rpy[1]) * Pose::rot_x(rpy[0]);
    Pose::new(rotation.rotation, Vector3::from(xyz))
}

/// Transform of a joint's child link in its parent link: origin, then the
/// motion about/along the (normalized) axis by `value`; no folding.
fn joint_transform(joint: &urdf_rs::Joint, value: f64) -> Pose {
    let axis = Vector3::from(joint.axis.xyz.0).normalize();
    let motion = match joint.joint_type {
        urdf_rs::JointType::Revolute | urdf_rs::JointType::Continuous => Pose::from_rotation(
            Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), value).into_inner(),
        ),
        urdf_rs::JointType::Prismatic => Pose::from_translation(axis * value),
        _ => Pose::identity(),
    };
    origin_pose(&joint.origin) * motion
}

/// World pose of `link` by walking up the URDF tree: moving joints named in
/// `chain_names` take the matching value of `q`, every other joint is at 0.
fn naive_link_pose(robot: &urdf_rs::Robot, link: &str, chain_names: &[&str], q: &[f64]) -> Pose {
    let mut pose = Pose::identity();
    let mut current = link.to_string();
    while let Some(joint) = robot.joints.iter().find(|j| j.child.link == current) {
        let value = chain_names
            .iter()
            .position(|n| *n == joint.name)
            .map_or(0.0, |k| q[k]);
        pose = joint_transform(joint, value) * pose;
        current = joint.parent.link.clone();
    }
    pose
}

fn chain_names(model: &Model) -> Vec<&str> {
    model.joints().iter().map(|j| j.name.as_str()).collect()
}

#[test]
fn skewbot_fk_matches_a_direct_composition_of_the_urdf_transforms() {
    let model = load(urdf_path("skewbot.urdf"), &skewbot_chain()).unwrap();
    let robot = skewbot_urdf();
    let names = chain_names(&model);
    let mut data = Data::new(&model);
    let mut rng = rng(31);
    let mut worst = 0.0f64;
    for trial in 0..200 {
        let mut q = random_configuration(&model, &mut rng);
        if trial % 2 == 1 {
            q[2] += 7.0; // the continuous joint beyond [-pi, pi]
        }
        let pose = *forward_kinematics(&model, &mut data, &q).unwrap();
        let expected = naive_link_pose(&robot, "tool", &names, &q);
        worst = worst.max(pose_error(&pose, &expected.to_rows()));
    }
    assert!(worst < POSE_TOLERANCE, "pose error {worst:e}");
}

#[test]
fn skewbot_jacobian_matches_finite_differences() {
    let model = load(urdf_path("skewbot.urdf"), &skewbot_chain()).unwrap();
    let mut data = Data::new(&model);
    let mut rng = rng(32);
    let mut worst = 0.0f64;
    for trial in 0..100 {
        let mut q = random_configuration(&model, &mut rng);
        if trial % 2 == 1 {
            q[2] -= 9.0;
        }
        let analytic = jacobian(&model, &mut data, &q, JacobianFrame::World)
            .unwrap()
            .clone();
        let numeric = finite_difference_jacobian(&model, &q, 1e-6);
        worst = worst.max((analytic - numeric).amax());
    }
    // Central differences with h = 1e-6: truncation ~h^2, rounding ~1e-16/h.
    assert!(worst < 1e-8, "Jacobian vs finite differences: {worst:e}");
}

/// Mass, centre of mass and inertia about the world origin, in world axes,
/// of parts given as (mass, world com, world-axes inertia about the com).
fn about_world_origin(
    parts: &[(f64, Vector3<f64>, Matrix3<f64>)],
) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let mass: f64 = parts.iter().map(|p| p.0).sum();
    let first_moment = parts.iter().fold(Vector3::zeros(), |s, p| s + p.1 * p.0);
    let inertia = parts.iter().fold(Matrix3::zeros(), |s, (m, c, i)| {
        s + i + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * *m
    });
    (mass, first_moment / mass, inertia)
}

#[test]
fn skewbot_inertias_are_the_bodies_each_joint_moves() {
    let model = load(urdf_path("skewbot.urdf"), &skewbot_chain()).unwrap();
    let robot = skewbot_urdf();
    let names = chain_names(&model);
    // Links moved by each joint: up to the next moving joint, with the
    // camera (fixed off the chain) and the sensor (revolute off the chain,
    // locked at 0); `base` is not moved by any joint; massless links count nothing.
    let bodies: [&[&str]; 4] = [
        &["link1"],
        &["link2", "camera", "link2b"],
        &["link3", "sensor"],
        &["link4", "flange", "tool"],
    ];
    let q = [0.4, 0.1, -2.0, 0.7];
    let mut data = Data::new(&model);
    forward_kinematics(&model, &mut data, &q).unwrap();
    for (k, links) in bodies.iter().enumerate() {
        let parts: Vec<_> = links
            .iter()
            .map(|name| robot.links.iter().find(|l| l.name == *name).unwrap())
            .filter(|link| link.inertial.mass.value > 0.0)
            .map(|link| {
                let frame = naive_link_pose(&robot, &link.name, &names, &q)
                    * origin_pose(&link.inertial.origin);
                let i = &link.inertial.inertia;
                let local = Matrix3::new(
                    i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz,
                );
                (
                    link.inertial.mass.value,
                    frame.translation,
                    frame.rotation * local * frame.rotation.transpose(),
                )
            })
            .collect();
        let expected = about_world_origin(&parts);

        let body = model.joints()[k].inertia.expect("every body has mass");
        let frame = data.joint_frames()[k];
        let com = frame.transform_point(&body.com);
        let inertia = frame.rotation * body.inertia * frame.rotation.transpose();
        let got = about_world_origin(&[(body.mass, com, inertia)]);
        assert!((got.0 - expected.0).abs() < 1e-12, "joint {k}: mass");
        assert!((got.1 - expected.1).norm() < 1e-12, "joint {k}: com");
        assert!(
            (got.2 - expected.2).amax() < 1e-12,
            "joint {k}: inertia {} vs {}",
            got.2,
            expected.2
        );
    }
    assert!(model.has_inertias());
}

#[test]
fn iiwa14_without_inertials_has_no_inertias_and_ur5_has_them() {
    let iiwa = load(
        urdf_path("iiwa14.urdf"),
        &ChainSelection::between("base_link", "tool0"),
    )
    .unwrap();
    assert!(iiwa.joints().iter().all(|j| j.inertia.is_none()));
    let ur5 = load(
        urdf_path("ur5.urdf"),
        &ChainSelection::between("base_link", "tool0"),
    )
    .unwrap();
    assert!(ur5.has_inertias());
    // shoulder_link: 3.7 kg, com at its origin.
    let shoulder = ur5.joints()[0].inertia.unwrap();
    assert_eq!(shoulder.mass, 3.7);
    assert!(shoulder.com.norm() < 1e-15);
}

// ---------------------------------------------------------------------------
// Errors, each on its message.

fn parse_error(text: &str, selection: &ChainSelection) -> String {
    parse_str(text, "test.urdf", selection)
        .unwrap_err()
        .to_string()
}

fn assert_error(text: &str, selection: &ChainSelection, expected: &[&str]) {
    let message = parse_error(text, selection);
    for part in expected {
        assert!(
            message.contains(part),
            "expected `{part}` in the message:\n{message}"
        );
    }
}

/// A two-link robot whose joint is `joint` (its XML, parent `a`, child `b`).
fn two_links(joint: &str) -> String {
    format!("<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"b\"/>\n{joint}\n</robot>\n")
}

#[test]
fn several_leaves_without_a_tip_are_listed() {
    let text = std::fs::read_to_string(urdf_path("panda.urdf")).unwrap();
    assert_eq!(
        parse_error(&text, &ChainSelection::default()),
        "test.urdf: the tree below the base link `panda_link0` has 3 leaf links \
         (`panda_hand_tcp`, `panda_leftfinger`, `panda_rightfinger`): choose the tip link"
    );
    let text = std::fs::read_to_string(urdf_path("skewbot.urdf")).unwrap();
    assert_error(
        &text,
        &ChainSelection::default(),
        &[
            "below the base link `world`",
            "`camera`",
            "`sensor`",
            "`tool`",
        ],
    );
}

#[test]
fn floating_planar_and_spherical_joints_on_the_chain_are_errors() {
    for kind in ["floating", "planar", "spherical"] {
        let text = two_links(&format!(
            "<joint name=\"free\" type=\"{kind}\"><parent link=\"a\"/><child link=\"b\"/></joint>"
        ));
        assert_eq!(
            parse_error(&text, &ChainSelection::default()),
            format!(
                "test.urdf: joint `free` (line 4) is {kind}: only revolute, continuous, \
                 prismatic and fixed joints can be on the chain from `a` to `b`"
            )
        );
    }
}

#[test]
fn a_floating_joint_off_the_chain_is_ignored() {
    let text = "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"object\">\
        <inertial><mass value=\"9\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\
        <joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>\
        <joint name=\"free\" type=\"floating\"><parent link=\"b\"/><child link=\"object\"/></joint></robot>";
    let model = parse_str(text, "t", &ChainSelection::between("a", "b")).unwrap();
    assert_eq!(model.dof(), 1);
    // The free object is not part of the body `j` moves.
    assert!(model.joints()[0].inertia.is_none());
}

#[test]
fn a_mimic_joint_follows_its_leader_off_the_chain() {
    let text = std::fs::read_to_string(urdf_path("panda.urdf")).unwrap();
    // panda_finger_joint2 mimics panda_finger_joint1, on the other finger:
    // the configuration is the leader's position.
    let right = parse_str(
        &text,
        "t",
        &ChainSelection::between("panda_hand", "panda_rightfinger"),
    )
    .unwrap();
    assert_eq!(right.dof(), 1);
    assert_eq!(right.joints()[0].name, "panda_finger_joint1");
    assert_eq!(right.chain_joints()[0].name, "panda_finger_joint2");
    assert_eq!(right.position_limits(), (vec![0.0], vec![0.04]));
    assert!(right.has_mimic_joints());
    let left = parse_str(
        &text,
        "t",
        &ChainSelection::between("panda_hand", "panda_leftfinger"),
    )
    .unwrap();
    assert_eq!(left.dof(), 1);
    assert!(!left.has_mimic_joints());
    // Both fingers open by the same amount, in opposite directions.
    let mut right_data = Data::new(&right);
    let mut left_data = Data::new(&left);
    for q in [0.0, 0.013, 0.04] {
        let r = *forward_kinematics(&right, &mut right_data, &[q]).unwrap();
        let l = *forward_kinematics(&left, &mut left_data, &[q]).unwrap();
        assert!((r.translation.y + l.translation.y).abs() < 1e-15, "{q}");
        assert!(((r.translation.y - l.translation.y).abs() - 2.0 * q).abs() < 1e-15);
    }
}

#[test]
fn a_link_with_two_parents_is_a_kinematic_loop() {
    let text = "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"b\"/>\n<link name=\"c\"/>\n\
        <joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n\
        <joint name=\"bc\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/></joint>\n\
        <joint name=\"ac\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint>\n</robot>";
    assert_eq!(
        parse_error(text, &ChainSelection::default()),
        "test.urdf: kinematic loop: link `c` (line 4) is the child of two joints, \
         joint `bc` (line 6) and joint `ac` (line 7) (a URDF must be a tree)"
    );
}

#[test]
fn a_cycle_of_joints_is_a_kinematic_loop() {
    let text = "<robot name=\"r\"><link name=\"root\"/><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
        <joint name=\"r\" type=\"fixed\"><parent link=\"root\"/><child link=\"a\"/></joint>\
        <joint name=\"bc\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/></joint>\
        <joint name=\"cb\" type=\"fixed\"><parent link=\"c\"/><child link=\"b\"/></joint></robot>";
    let message = parse_error(text, &ChainSelection::default());
    assert!(
        message == "test.urdf: kinematic loop: the links c -> b -> c form a cycle (a URDF must be a tree)"
            || message == "test.urdf: kinematic loop: the links b -> c -> b form a cycle (a URDF must be a tree)",
        "{message}"
    );
    let own_parent = two_links(
        "<joint name=\"self\" type=\"fixed\"><parent link=\"b\"/><child link=\"b\"/></joint>",
    );
    assert_error(
        &own_parent,
        &ChainSelection::default(),
        &["kinematic loop: the links b -> b"],
    );
}

#[test]
fn a_missing_parent_or_child_link_is_named() {
    let text = two_links(
        "<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"ghost\"/></joint>",
    );
    assert_eq!(
        parse_error(&text, &ChainSelection::default()),
        "test.urdf: joint `j` (line 4): its child link `ghost` does not exist (no <link name=\"ghost\">)"
    );
    let text = two_links(
        "<joint name=\"j\" type=\"fixed\"><parent link=\"nobody\"/><child link=\"b\"/></joint>",
    );
    assert_eq!(
        parse_error(&text, &ChainSelection::default()),
        "test.urdf: joint `j` (line 4): its parent link `nobody` does not exist (no <link name=\"nobody\">)"
    );
    // No <parent> element at all: urdf-rs's message, traced to the joint.
    let text = two_links("<joint name=\"j\" type=\"fixed\"><child link=\"b\"/></joint>");
    assert_eq!(
        parse_error(&text, &ChainSelection::default()),
        "test.urdf: joint `j` (line 4): missing field `parent`"
    );
}

#[test]
fn a_base_or_tip_that_does_not_exist_is_named() {
    let text = std::fs::read_to_string(urdf_path("iiwa14.urdf")).unwrap();
    assert_eq!(
        parse_error(&text, &ChainSelection::between("base_link", "flange")),
        "test.urdf: the tip link `flange` does not exist; the links are: base_link, link_1, \
         link_2, link_3, link_4, link_5, link_6, link_7, tool0, base"
    );
    assert_error(
        &text,
        &ChainSelection::default().with_base("world"),
        &["the base link `world` does not exist; the links are: base_link, link_1"],
    );
}

#[test]
fn a_tip_not_below_the_base_is_an_error() {
    let text = std::fs::read_to_string(urdf_path("ur5.urdf")).unwrap();
    assert_eq!(
        parse_error(&text, &ChainSelection::between("tool0", "base_link")),
        "test.urdf: the tip link `base_link` is not below the base link `tool0` \
         (going up from the tip reaches the root `world` without passing the base)"
    );
    // Two branches: `base` hangs from base_link, not from the tool.
    assert_error(
        &text,
        &ChainSelection::between("ee_link", "tool0"),
        &["the tip link `tool0` is not below the base link `ee_link`"],
    );
    assert_error(
        &text,
        &ChainSelection::between("tool0", "tool0"),
        &["the base and the tip are the same link `tool0`"],
    );
    assert_error(
        &text,
        &ChainSelection::between("world", "base"),
        &["the chain from `world` to `base` has no moving joint"],
    );
}

#[test]
fn malformed_xml_is_located() {
    let text = "<robot name=\"r\">\n  <link name=\"a\">\n  <link name=\"b\"/>\n</robot>\n";
    assert_eq!(
        parse_error(text, &ChainSelection::default()),
        "test.urdf: malformed XML at line 4, column 1: `</robot>` closes <link name=\"a\"> opened at line 2"
    );
    assert_eq!(
        parse_error("<robot name=\"r\">\n<link name=\"a\"/>\n", &ChainSelection::default()),
        "test.urdf: malformed XML at line 3, column 1: <robot name=\"r\"> opened at line 1 is never closed"
    );
    assert_eq!(
        parse_error("not a URDF", &ChainSelection::default()),
        "test.urdf: malformed XML at line 1, column 1: text before the root element"
    );
    assert_eq!(
        parse_error("<robot><link name=a/></robot>", &ChainSelection::default()),
        "test.urdf: malformed XML at line 1, column 19: the value of attribute `name` of <link> is not quoted"
    );
    assert_eq!(
        parse_error("<sdf><model/></sdf>", &ChainSelection::default()),
        "test.urdf: the root element is <sdf>, a URDF's is <robot>"
    );
}

#[test]
fn invalid_urdf_content_is_traced_to_its_element() {
    let text = two_links(
        "<joint name=\"j\" type=\"hinge\"><parent link=\"a\"/><child link=\"b\"/></joint>",
    );
    assert_error(
        &text,
        &ChainSelection::default(),
        &["joint `j` (line 4): unknown variant `hinge`"],
    );
    let text = two_links(
        "<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
         <limit lower=\"-1\" upper=\"1\"/></joint>",
    );
    assert_error(
        &text,
        &ChainSelection::default(),
        &["joint `j` (line 4): missing field `velocity`"],
    );
    let text =
        "<robot name=\"r\">\n<link name=\"a\">\n<inertial><mass/></inertial>\n</link>\n</robot>";
    assert_error(
        text,
        &ChainSelection::default(),
        &["link `a` (line 2): missing field `value`"],
    );
}

#[test]
fn bad_joint_values_are_named() {
    let revolute = |inner: &str| {
        two_links(&format!(
            "<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>{inner}</joint>"
        ))
    };
    let cases = [
        (
            revolute(""),
            "joint `j` (line 4) is revolute but has no <limit> element: the URDF specification requires <limit> (lower, upper, velocity, effort) on revolute and prismatic joints",
        ),
        (
            revolute("<limit lower=\"1\" upper=\"-1\" velocity=\"1\"/>"),
            "joint `j` (line 4): <limit> lower = 1 must not be above upper = -1",
        ),
        (
            revolute("<limit lower=\"nan\" upper=\"1\" velocity=\"1\"/>"),
            "joint `j` (line 4): <limit> lower and upper must be numbers, got NaN and 1",
        ),
        (
            revolute("<limit lower=\"-1\" upper=\"1\" velocity=\"-2\"/>"),
            "joint `j` (line 4): <limit velocity> must be >= 0, got -2",
        ),
        (
            revolute("<axis xyz=\"0 0 0\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\"/>"),
            "joint `j` (line 4): <axis xyz> must be a finite non-zero vector, got [0.0, 0.0, 0.0]",
        ),
        (
            revolute("<origin xyz=\"0 nan 0\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\"/>"),
            "joint `j` (line 4): <origin> is not finite",
        ),
    ];
    for (text, expected) in cases {
        assert_eq!(
            parse_error(&text, &ChainSelection::default()),
            format!("test.urdf: {expected}")
        );
    }
    // A prismatic joint without <limit> is named as such.
    let text = two_links(
        "<joint name=\"p\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/></joint>",
    );
    assert_error(
        &text,
        &ChainSelection::default(),
        &["joint `p` (line 4) is prismatic but has no <limit>"],
    );
}

#[test]
fn bad_inertials_are_named() {
    let with_inertial = |inertial: &str| {
        format!(
            "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"b\"><inertial>{inertial}</inertial></link>\n\
             <joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>\n</robot>"
        )
    };
    let text = with_inertial(
        "<mass value=\"-1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>",
    );
    assert_error(
        &text,
        &ChainSelection::default(),
        &["link `b` (line 3): <inertial> mass must be finite and >= 0, got -1"],
    );
    let text = with_inertial(
        "<mass value=\"1\"/><inertia ixx=\"-1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>",
    );
    assert_error(
        &text,
        &ChainSelection::default(),
        &["link `b` (line 3): <inertial> inertia must be positive semi-definite"],
    );
}

#[test]
fn duplicate_names_and_several_roots_are_errors() {
    let text = "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"a\"/>\n</robot>";
    assert_eq!(
        parse_error(text, &ChainSelection::default()),
        "test.urdf: link `a` (line 3) is defined twice (first as link `a` (line 2))"
    );
    let text = "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
        <joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>";
    assert_eq!(
        parse_error(text, &ChainSelection::default()),
        "test.urdf: the URDF has 2 root links (`a`, `c`), not one tree: choose the base link"
    );
    // With a base, the separate link does not matter.
    assert_eq!(
        parse_str(text, "t", &ChainSelection::default().with_base("a"))
            .unwrap()
            .dof(),
        1
    );
}

#[test]
fn unreadable_files_and_empty_names_are_errors() {
    let err = load("/nonexistent/robot.urdf", &ChainSelection::default()).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("/nonexistent/robot.urdf: cannot read the file:"),
        "{err}"
    );
    let err = load(
        urdf_path("ur5.urdf"),
        &ChainSelection::default().with_tip(" "),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "invalid argument `tip`: the link name is empty (leave it unset for the default)"
    );
}

#[test]
fn a_byte_order_mark_and_a_missing_axis_are_accepted() {
    // No <axis>: URDF's default is x. A byte-order mark before the XML.
    let text = format!(
        "\u{feff}{}",
        two_links(
            "<joint name=\"j\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/>\
             <limit lower=\"0\" upper=\"1\" velocity=\"0\"/></joint>"
        )
    );
    let model = parse_str(&text, "t", &ChainSelection::default()).unwrap();
    let mut data = Data::new(&model);
    let pose = *forward_kinematics(&model, &mut data, &[0.25]).unwrap();
    assert!((pose.translation - Vector3::new(0.25, 0.0, 0.0)).norm() < 1e-15);
    // velocity="0" means no velocity limit given.
    assert_eq!(model.joints()[0].limits.velocity, None);
}

/// Elements the kinematics and mass properties do not read never
/// block a load, however they are written; what the model reads still
/// fails with the file, line and element.
#[test]
fn elements_the_model_does_not_read_never_block_a_load() {
    let text = "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n\
        <material name=\"skin\"><texture /></material>\n\
        <link name=\"a\">\n\
          <visual><geometry><mesh filename=\"package://nowhere.stl\" scale=\"x y z\"/></geometry>\
            <material name=\"m\"><color rgba=\"not numbers\"/><texture /></material></visual>\n\
          <collision><geometry><box/></geometry></collision>\n\
        </link>\n\
        <link name=\"b\"><inertial><mass value=\"2\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>\
          <visual><origin xyz=\"nan\"/></visual><sensor name=\"cam\" type=\"camera\"/></link>\n\
        <joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
          <limit lower=\"-1\" upper=\"1\" velocity=\"2\" effort=\"3\"/>\
          <calibration rising=\"abc\"/><dynamics damping=\"lots\"/>\
          <safety_controller soft_lower_limit=\"?\" k_velocity=\"\"/></joint>\n\
        <transmission name=\"t\"><type>junk</type><joint/></transmission>\n\
        <gazebo reference=\"b\"><sensor><plugin/></sensor><unknown_tag/></gazebo>\n\
        <vendor_extension anything=\"goes\"><deeply><nested/></deeply></vendor_extension>\n\
        </robot>\n";
    let model = parse_str(text, "lenient.urdf", &ChainSelection::default()).unwrap();
    assert_eq!(model.dof(), 1);
    assert_eq!(model.joints()[0].limits.velocity, Some(2.0));
    assert_eq!(model.joints()[0].inertia.unwrap().mass, 2.0);

    // What the model reads is still checked, with the line.
    let broken = text.replace("<mass value=\"2\"/>", "<mass value=\"heavy\"/>");
    let message = parse_str(&broken, "lenient.urdf", &ChainSelection::default())
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("lenient.urdf: link `b` (line 8):"),
        "{message}"
    );
    let broken = text.replace("velocity=\"2\"", "velocity=\"fast\"");
    let message = parse_str(&broken, "lenient.urdf", &ChainSelection::default())
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("lenient.urdf: joint `j` (line 9):"),
        "{message}"
    );
    // Malformed XML anywhere is still an error (the file is not XML).
    let broken = text.replace("<unknown_tag/>", "<unknown_tag>");
    let message = parse_str(&broken, "lenient.urdf", &ChainSelection::default())
        .unwrap_err()
        .to_string();
    assert!(message.contains("malformed XML at line 11"), "{message}");
}
