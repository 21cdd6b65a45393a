//! Loading a serial chain from a URDF file.
//!
//! A URDF describes a tree of links joined by joints. [`load`] (a file) and
//! [`parse_str`] (text) pick the serial chain from a base link to a tip link
//! ([`ChainSelection`]) and turn it into a [`Model`] through
//! [`ModelBuilder`]: the model's world frame is the base link's frame, its
//! end-effector frame is the tip link's frame, and it runs on the same FK and
//! Jacobian code as a DH robot (fixed joints and non-z axes are folded into
//! the joint placements once, at load time).
//!
//! What is read, per element on the chain:
//! * `revolute` joints: rotation about `<axis>` (any direction, normalized),
//!   position limits `<limit lower upper>` (rad, required, as in urdfdom);
//! * `continuous` joints: [`JointKind::Continuous`], no position limits;
//! * `prismatic` joints: translation along `<axis>`, limits in m;
//! * `fixed` joints: folded into the next joint's placement (or the
//!   end-effector placement after the last moving joint);
//! * `<limit velocity>` (rad/s or m/s), `effort` (N m or N) and, from URDF
//!   1.2, `acceleration`: a value of 0 or infinity means "not given";
//! * `<origin xyz rpy>` with `R = Rz(yaw) Ry(pitch) Rx(roll)` (and
//!   `quat_xyzw` from URDF 1.1, which `urdf-rs` converts);
//! * `<inertial>`: each moving joint gets the [`LinkInertia`] of the rigid body
//!   it moves, given in its child link's frame: the child link plus every link
//!   attached below it up to the next moving joint of the chain, including
//!   links off the chain, with joints off the chain locked at zero (as
//!   Pinocchio's `buildReducedModel` does) and bodies behind a floating joint
//!   left out. An inertial origin may be rotated: the tensor is turned into
//!   the link frame (`I = R I' R'`), then moved to the common centre of mass
//!   (parallel-axis theorem). A link without `<inertial>`, or with zero
//!   mass and a zero tensor, contributes nothing; a link with zero mass and a
//!   non-zero tensor contributes its tensor (as in Pinocchio). A body with
//!   neither mass nor inertia is massless (a zero [`LinkInertia`], as in
//!   Pinocchio), unless no body of the chain has any: such a chain describes
//!   kinematics only, and its mass properties are unknown (`None`).
//!
//! * `<mimic joint multiplier offset>`: the joint follows its leader,
//!   `q = multiplier * q_leader + offset` (defaults 1 and 0), and leaves the
//!   configuration ([`crate::model::CouplingLaw::Mimic`]). The leader may be
//!   off the chain (the other finger of a parallel gripper): it then joins
//!   the configuration with its own kind and limits. A mimic of a mimic
//!   resolves to the first independent leader.
//!
//! Only `<link>` (its `<inertial>`) and `<joint>` (`origin`, `parent`,
//! `child`, `axis`, `limit`, `mimic`) are read. Everything else (visuals,
//! collisions, materials and textures, `<dynamics>`, `<calibration>`,
//! `<safety_controller>`, transmissions, Gazebo and sensor tags, vendor
//! extensions) is skipped before parsing, so that however it is written it
//! never blocks a load. `<limit effort>` becomes
//! [`crate::model::JointLimits::effort`] (torque or force limit).
//!
//! Errors are [`Error::Parse`] naming the file and the element (with its
//! line): malformed XML (line and column, the element left open), a joint
//! whose parent or child link does not exist, a kinematic loop (a link that is
//! the child of two joints, or a cycle), a floating, planar or spherical joint
//! on the chain, a base or tip link that does not exist, a tip that is not
//! below the base, several leaves when no tip is given (the error lists
//! them), a revolute or prismatic joint without `<limit>` (the URDF
//! specification requires it), a zero axis, non-finite numbers, negative
//! masses, a mimic joint whose leader does not exist or is fixed, mimic
//! joints that form a cycle, a non-finite multiplier or offset. Joints and
//! links off the chain are checked only as far as the tree structure and the
//! mimic joints need.
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::urdf::{parse_str, ChainSelection};
//!
//! let text = r#"
//! <robot name="slider">
//!   <link name="base"/>
//!   <link name="carriage">
//!     <inertial>
//!       <origin xyz="0 0 0.05" rpy="0 0 0.3"/>
//!       <mass value="2.0"/>
//!       <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/>
//!     </inertial>
//!   </link>
//!   <link name="arm"/>
//!   <link name="tool"/>
//!   <joint name="slide" type="prismatic">
//!     <parent link="base"/> <child link="carriage"/>
//!     <axis xyz="1 1 0"/>
//!     <limit lower="0" upper="0.5" velocity="0.3" effort="100"/>
//!   </joint>
//!   <joint name="spin" type="continuous">
//!     <parent link="carriage"/> <child link="arm"/>
//!     <origin xyz="0 0 0.1" rpy="0 1.5707963267948966 0"/>
//!     <axis xyz="0 0 1"/>
//!   </joint>
//!   <joint name="flange" type="fixed">
//!     <parent link="arm"/> <child link="tool"/>
//!     <origin xyz="0 0 0.2"/>
//!   </joint>
//! </robot>"#;
//! // Default selection: from the only root (`base`) to the only leaf (`tool`).
//! let model = parse_str(text, "<example>", &ChainSelection::default()).unwrap();
//! assert_eq!(model.dof(), 2);
//! assert_eq!(model.joints()[1].name, "spin");
//! assert_eq!(model.joints()[0].limits.velocity, Some(0.3));
//! assert!((model.joints()[0].inertia.unwrap().mass - 2.0).abs() < 1e-15);
//!
//! let mut data = Data::new(&model);
//! // Slide 0.2 m along (1, 1, 0)/sqrt(2); the tool points along +x after the
//! // pitch of pi/2, 0.2 m out from the spin axis.
//! let pose = forward_kinematics(&model, &mut data, &[0.2, 0.0]).unwrap();
//! let s = 0.2 / 2f64.sqrt();
//! assert!((pose.translation - armkit::math::Vector3::new(s + 0.2, s, 0.1)).norm() < 1e-12);
//! ```

mod tree;
mod xml;

use std::path::Path;

use crate::error::{Error, Result};
use crate::math::{Matrix3, Pose, Vector3};
use crate::model::{
    JointKind, JointLimits, JointSpec, LinkInertia, MimicJoint, Model, ModelBuilder,
};

use tree::{SourceLines, Tree};

mod outline;
pub use outline::{outline, outline_str, Outline, OutlineJoint};

/// Which serial chain of the URDF tree to load, by link name.
///
/// `base`: the link whose frame becomes the model's world frame; default:
/// the root of the tree (the root above the tip, when a tip is given).
/// `tip`: the link whose frame becomes the end-effector frame; default: the
/// only leaf link below the base (an error lists the leaves when there are
/// several).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ChainSelection {
    /// Base link name; `None`: the root link.
    pub base: Option<String>,
    /// Tip link name; `None`: the only leaf below the base.
    pub tip: Option<String>,
}

impl ChainSelection {
    /// The chain from link `base` to link `tip`.
    pub fn between(base: impl Into<String>, tip: impl Into<String>) -> Self {
        ChainSelection {
            base: Some(base.into()),
            tip: Some(tip.into()),
        }
    }

    /// Sets the base link.
    pub fn with_base(mut self, base: impl Into<String>) -> Self {
        self.base = Some(base.into());
        self
    }

    /// Sets the tip link.
    pub fn with_tip(mut self, tip: impl Into<String>) -> Self {
        self.tip = Some(tip.into());
        self
    }

    /// Checks that a given link name is not empty or blank.
    pub fn validate(&self) -> Result<()> {
        for (field, value) in [("base", &self.base), ("tip", &self.tip)] {
            if value.as_deref().is_some_and(|name| name.trim().is_empty()) {
                return Err(Error::invalid_argument(
                    field,
                    "the link name is empty (leave it unset for the default)",
                ));
            }
        }
        Ok(())
    }
}

/// Loads the chain `selection` names from the URDF file at `path`.
///
/// Errors: the file cannot be read, or any error of [`parse_str`] (named
/// with the path).
pub fn load(path: impl AsRef<Path>, selection: &ChainSelection) -> Result<Model> {
    let path = path.as_ref();
    let (text, source_name) = crate::error::read_source(path)?;
    parse_str(&text, &source_name, selection)
}

/// Parses URDF text and builds the chain `selection` names; `source_name`
/// names the text in errors (a path, or e.g. `<string>`).
///
/// The model is named after the `<robot name>` attribute (or `source_name`
/// when it is empty); its joints are the moving joints from base to tip, in
/// that order, under their URDF names. See the [module docs](self) for what
/// is read and which errors are reported.
pub fn parse_str(text: &str, source_name: &str, selection: &ChainSelection) -> Result<Model> {
    selection.validate()?;
    let fail = |reason: String| Error::Parse {
        source_name: source_name.to_string(),
        reason,
    };
    let (robot, document) = read_robot(text, source_name)?;
    let tree = Tree::new(&robot, SourceLines::new(&document, &robot)).map_err(fail)?;
    let chain = tree.select(selection).map_err(fail)?;
    let name = if robot.name.trim().is_empty() {
        source_name
    } else {
        robot.name.as_str()
    };
    let limited = joints_with_limit(&document);
    let builder = chain_builder(name, &robot, &tree, &chain, &limited).map_err(fail)?;
    builder.build().map_err(|e| fail(e.to_string()))
}

/// The URDF text as urdf-rs reads it, with the scanned document (element
/// lines, `<limit>`s) beside it. Errors name `source_name` and the line.
fn read_robot(text: &str, source_name: &str) -> Result<(urdf_rs::Robot, xml::Document)> {
    let fail = |reason: String| Error::Parse {
        source_name: source_name.to_string(),
        reason,
    };
    // Some CAD exporters write a byte-order mark, which XML allows before the root.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let document = xml::scan(text).map_err(fail)?;
    if document.root != "robot" {
        return Err(fail(format!(
            "the root element is <{}>, a URDF's is <robot>",
            document.root
        )));
    }
    // Only what the model reads goes to urdf-rs (same offsets and lines).
    let text = xml::kinematic_text(text, &document);
    let robot = urdf_rs::read_from_string(&text)
        .map_err(|e| fail(locate_urdf_rs_error(&text, &document, &e)))?;
    Ok((robot, document))
}

/// Names of the joints that have a `<limit>` element (urdf-rs fills a
/// missing one with zeros, which a written `<limit lower="0" upper="0"
/// effort="0" velocity="0"/>` cannot be told from).
fn joints_with_limit(document: &xml::Document) -> Vec<&str> {
    document
        .children
        .iter()
        .filter(|e| e.name == "joint" && e.children.iter().any(|(child, _)| child == "limit"))
        .filter_map(|e| e.name_attribute.as_deref())
        .collect()
}

/// `urdf-rs` messages name neither the element nor the line. Parsing each
/// top-level element alone finds the first one `urdf-rs` rejects, and the
/// message then names it; otherwise the message is passed on as it is.
fn locate_urdf_rs_error(
    text: &str,
    document: &xml::Document,
    error: &urdf_rs::UrdfError,
) -> String {
    let clean = |e: &urdf_rs::UrdfError| {
        let message = e.to_string();
        message
            .strip_prefix("custom: ")
            .unwrap_or(&message)
            .to_string()
    };
    let root_start_tag = &text[document.root_start_tag.clone()];
    for element in &document.children {
        if !matches!(element.name.as_str(), "link" | "joint" | "material") {
            continue;
        }
        let alone = format!(
            "{root_start_tag}{}</{}>",
            &text[element.span.clone()],
            document.root
        );
        if let Err(e) = urdf_rs::read_from_string(&alone) {
            let which = match &element.name_attribute {
                Some(name) => format!("{} `{name}`", element.name),
                None => format!("a <{}> without a name", element.name),
            };
            return format!("{which} (line {}): {}", element.line, clean(&e));
        }
    }
    format!("invalid URDF: {}", clean(error))
}

fn is_moving(joint_type: &urdf_rs::JointType) -> bool {
    matches!(
        joint_type,
        urdf_rs::JointType::Revolute
            | urdf_rs::JointType::Continuous
            | urdf_rs::JointType::Prismatic
    )
}

/// The builder for the chain: fixed joints as fixed placements, moving
/// joints as [`JointSpec`]s with limits and the mass properties of the body
/// they move.
fn chain_builder(
    name: &str,
    robot: &urdf_rs::Robot,
    tree: &Tree<'_>,
    chain: &tree::Chain,
    limited: &[&str],
) -> std::result::Result<ModelBuilder, String> {
    let mut builder = ModelBuilder::new(name);
    let mut any_moving = false;
    let mut off_chain_leaders = Vec::new();
    let next_moving = |position: usize| {
        chain.joints[position + 1..]
            .iter()
            .copied()
            .find(|&n| is_moving(&robot.joints[n].joint_type))
    };
    // Whether any body of the chain has mass properties (a bad <inertial> is
    // reported by the loop below, in chain order).
    let chain_has_mass = chain.joints.iter().enumerate().any(|(position, &j)| {
        is_moving(&robot.joints[j].joint_type)
            && matches!(
                body_inertia(robot, tree, tree.child_link(j), next_moving(position)),
                Ok(Some(_))
            )
    });
    for (position, &j) in chain.joints.iter().enumerate() {
        let joint = &robot.joints[j];
        let origin = pose_of(&joint.origin)
            .ok_or_else(|| format!("{}: <origin> is not finite", tree.joint(j)))?;
        let kind = match joint.joint_type {
            urdf_rs::JointType::Fixed => {
                builder = builder.fixed(origin);
                continue;
            }
            urdf_rs::JointType::Revolute => JointKind::Revolute,
            urdf_rs::JointType::Continuous => JointKind::Continuous,
            urdf_rs::JointType::Prismatic => JointKind::Prismatic,
            urdf_rs::JointType::Floating
            | urdf_rs::JointType::Planar
            | urdf_rs::JointType::Spherical => {
                return Err(format!(
                    "{} is {}: only revolute, continuous, prismatic and fixed joints can be on the chain from `{}` to `{}`",
                    tree.joint(j),
                    type_name(&joint.joint_type),
                    robot.links[chain.base].name,
                    robot.links[chain.tip].name
                ));
            }
        };
        if joint.mimic.is_some() {
            builder = add_mimic(
                builder,
                robot,
                tree,
                chain,
                j,
                limited,
                &mut off_chain_leaders,
            )?;
        }
        let axis = Vector3::from(joint.axis.xyz.0);
        if !(axis.iter().all(|v| v.is_finite()) && axis.norm() > 1e-12) {
            return Err(format!(
                "{}: <axis xyz> must be a finite non-zero vector, got {:?}",
                tree.joint(j),
                joint.axis.xyz.0
            ));
        }
        let mut spec = JointSpec {
            name: joint.name.clone(),
            kind,
            origin,
            axis,
            limits: joint_limits(tree, j, &joint.limit, kind, limited)?,
            inertia: None,
        };
        let inertia = match body_inertia(robot, tree, tree.child_link(j), next_moving(position))? {
            None if chain_has_mass => Some(LinkInertia::point_mass(0.0, Vector3::zeros())),
            inertia => inertia,
        };
        if let Some(inertia) = inertia {
            spec = spec.with_inertia(inertia);
        }
        builder = builder.joint(spec);
        any_moving = true;
    }
    if !any_moving {
        return Err(format!(
            "the chain from `{}` to `{}` has no moving joint (only fixed joints)",
            robot.links[chain.base].name, robot.links[chain.tip].name
        ));
    }
    Ok(builder)
}

/// Declares chain joint `j`'s `<mimic>`, and follows its leaders off the
/// chain (each becomes an off-chain joint of the model, with its limits,
/// recorded in `added`) until one is on the chain, independent, or already
/// added (possibly a cycle, which the model reports naming the joints).
fn add_mimic(
    mut builder: ModelBuilder,
    robot: &urdf_rs::Robot,
    tree: &Tree<'_>,
    chain: &tree::Chain,
    j: usize,
    limited: &[&str],
    added: &mut Vec<usize>,
) -> std::result::Result<ModelBuilder, String> {
    let mut follower = j;
    while let Some(mimic) = &robot.joints[follower].mimic {
        let leader = robot
            .joints
            .iter()
            .position(|joint| joint.name == mimic.joint)
            .ok_or_else(|| {
                format!(
                    "{}: <mimic joint=\"{}\">: the file has no joint named `{}` (a mimic joint follows an existing joint)",
                    tree.joint(follower),
                    mimic.joint,
                    mimic.joint
                )
            })?;
        let leader_kind = match robot.joints[leader].joint_type {
            urdf_rs::JointType::Revolute => JointKind::Revolute,
            urdf_rs::JointType::Continuous => JointKind::Continuous,
            urdf_rs::JointType::Prismatic => JointKind::Prismatic,
            ref other => {
                return Err(format!(
                    "{} mimics {}, which is {}: a mimic joint must follow a revolute, continuous or prismatic joint",
                    tree.joint(follower),
                    tree.joint(leader),
                    type_name(other)
                ))
            }
        };
        builder = builder.mimic(MimicJoint::new(
            robot.joints[follower].name.clone(),
            mimic.joint.clone(),
            mimic.multiplier.unwrap_or(1.0),
            mimic.offset.unwrap_or(0.0),
        ));
        if chain.joints.contains(&leader) || added.contains(&leader) {
            break;
        }
        added.push(leader);
        let limits = joint_limits(
            tree,
            leader,
            &robot.joints[leader].limit,
            leader_kind,
            limited,
        )?;
        builder = builder.off_chain_joint(JointSpec {
            name: robot.joints[leader].name.clone(),
            kind: leader_kind,
            origin: Pose::identity(),
            axis: Vector3::z(),
            limits,
            inertia: None,
        });
        follower = leader;
    }
    Ok(builder)
}

fn type_name(joint_type: &urdf_rs::JointType) -> &'static str {
    match joint_type {
        urdf_rs::JointType::Revolute => "revolute",
        urdf_rs::JointType::Continuous => "continuous",
        urdf_rs::JointType::Prismatic => "prismatic",
        urdf_rs::JointType::Fixed => "fixed",
        urdf_rs::JointType::Floating => "floating",
        urdf_rs::JointType::Planar => "planar",
        urdf_rs::JointType::Spherical => "spherical",
    }
}

/// A URDF `<origin>` as a pose, or `None` if a number is not finite.
fn pose_of(origin: &urdf_rs::Pose) -> Option<Pose> {
    let pose = Pose::from_xyz_rpy(origin.xyz.0, origin.rpy.0);
    pose.is_finite().then_some(pose)
}

/// A rate limit (velocity, acceleration): 0 or infinity means not given.
fn optional_rate(value: f64) -> Option<f64> {
    (value.is_finite() && value > 0.0).then_some(value)
}

fn joint_limits(
    tree: &Tree<'_>,
    joint: usize,
    limit: &urdf_rs::JointLimit,
    kind: JointKind,
    limited: &[&str],
) -> std::result::Result<JointLimits, String> {
    for (field, value) in [
        ("velocity", limit.velocity),
        ("acceleration", limit.acceleration),
        ("effort", limit.effort),
    ] {
        if value.is_nan() || value < 0.0 {
            return Err(format!(
                "{}: <limit {field}> must be >= 0, got {value}",
                tree.joint(joint)
            ));
        }
    }
    let rates = JointLimits {
        velocity: optional_rate(limit.velocity),
        acceleration: optional_rate(limit.acceleration),
        effort: optional_rate(limit.effort),
        ..JointLimits::UNLIMITED
    };
    if kind == JointKind::Continuous {
        // URDF: a continuous joint has no position limits; any given are ignored.
        return Ok(rates);
    }
    // urdfdom rejects revolute and prismatic joints without <limit>, and so
    // do we (urdf-rs fills a missing one with zeros: the scan says whether
    // the element is there).
    if !limited.contains(&tree.joint_name(joint)) {
        return Err(format!(
            "{} is {} but has no <limit> element: the URDF specification requires <limit> (lower, upper, velocity, effort) on revolute and prismatic joints",
            tree.joint(joint),
            if kind == JointKind::Prismatic {
                "prismatic"
            } else {
                "revolute"
            }
        ));
    }
    if limit.lower.is_nan() || limit.upper.is_nan() {
        return Err(format!(
            "{}: <limit> lower and upper must be numbers, got {} and {}",
            tree.joint(joint),
            limit.lower,
            limit.upper
        ));
    }
    if limit.lower > limit.upper {
        return Err(format!(
            "{}: <limit> lower = {} must not be above upper = {}",
            tree.joint(joint),
            limit.lower,
            limit.upper
        ));
    }
    Ok(JointLimits {
        lower: limit.lower,
        upper: limit.upper,
        ..rates
    })
}

/// The `<inertial>` of one link in that link's frame, `None` for neither
/// mass nor inertia.
fn link_inertia(
    robot: &urdf_rs::Robot,
    tree: &Tree<'_>,
    link: usize,
) -> std::result::Result<Option<LinkInertia>, String> {
    let inertial = &robot.links[link].inertial;
    let mass = inertial.mass.value;
    let i = &inertial.inertia;
    if mass == 0.0 && [i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz] == [0.0; 6] {
        return Ok(None);
    }
    let body = LinkInertia {
        mass,
        com: Vector3::zeros(),
        inertia: Matrix3::new(
            i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz,
        ),
    };
    body.validate()
        .map_err(|(field, reason)| format!("{}: <inertial> {field} {reason}", tree.link(link)))?;
    let origin = pose_of(&inertial.origin)
        .ok_or_else(|| format!("{}: <inertial> <origin> is not finite", tree.link(link)))?;
    // The tensor is given in the inertial frame, which may be rotated in the
    // link frame: com = origin, I_link = R I R'.
    Ok(Some(body.transformed(&origin)))
}

/// Mass properties, in the frame of `link`, of the rigid body made of `link`
/// and everything attached below it, except past `stop` (the next moving
/// joint of the chain). Joints off the chain count at their zero position;
/// floating joints detach what is behind them.
fn body_inertia(
    robot: &urdf_rs::Robot,
    tree: &Tree<'_>,
    link: usize,
    stop: Option<usize>,
) -> std::result::Result<Option<LinkInertia>, String> {
    let mut parts = Vec::new();
    let mut pending = vec![(link, Pose::identity())];
    while let Some((l, placement)) = pending.pop() {
        if let Some(part) = link_inertia(robot, tree, l)? {
            parts.push(part.transformed(&placement));
        }
        for &j in tree.child_joints(l) {
            let joint = &robot.joints[j];
            if Some(j) == stop || joint.joint_type == urdf_rs::JointType::Floating {
                continue;
            }
            let origin = pose_of(&joint.origin)
                .ok_or_else(|| format!("{}: <origin> is not finite", tree.joint(j)))?;
            pending.push((tree.child_link(j), placement * origin));
        }
    }
    Ok(LinkInertia::combine(&parts))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combine_matches_the_parallel_axis_theorem() {
        // Two 1 kg point masses 1 m apart on x: com at the middle, inertia
        // 2 * 0.5^2 about y and z.
        let parts = [
            LinkInertia::point_mass(1.0, Vector3::new(0.0, 0.0, 0.0)),
            LinkInertia::point_mass(1.0, Vector3::new(1.0, 0.0, 0.0)),
        ];
        let body = LinkInertia::combine(&parts).unwrap();
        assert_eq!(body.mass, 2.0);
        assert!((body.com - Vector3::new(0.5, 0.0, 0.0)).norm() < 1e-15);
        let expected = Matrix3::from_diagonal(&Vector3::new(0.0, 0.5, 0.5));
        assert!((body.inertia - expected).amax() < 1e-15);
        assert!(LinkInertia::combine(&[]).is_none());
    }
}
