//! The whole link-joint tree of a URDF, for a reader choosing a chain (a
//! robot with a gripper, a mobile manipulator, a humanoid has several leaves).

use std::path::Path;

use super::tree::{SourceLines, Tree};
use super::{read_robot, type_name};
use crate::error::{Error, Result};

/// One joint of a URDF tree, as [`Outline`] lists it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OutlineJoint {
    /// The joint's name.
    pub name: String,
    /// `revolute`, `continuous`, `prismatic`, `fixed`, `floating`, `planar`.
    pub kind: &'static str,
    /// Parent link name.
    pub parent: String,
    /// Child link name.
    pub child: String,
    /// Joints between the root and this joint (0 for a joint on a root link).
    pub depth: usize,
}

/// The tree of a URDF: its roots, every joint depth-first from the roots
/// (children in document order), and its leaf links (links with no child),
/// the tips a chain can end at.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Outline {
    /// The `<robot name>`.
    pub robot: String,
    /// Number of `<link>` elements.
    pub links: usize,
    /// Root links (one for a single tree).
    pub roots: Vec<String>,
    /// Every joint, depth-first from the roots.
    pub joints: Vec<OutlineJoint>,
    /// Leaf links, depth-first from the roots.
    pub leaves: Vec<String>,
}

/// The tree of the URDF file at `path`. Errors: the file cannot be read, or
/// any error of [`outline_str`].
pub fn outline(path: impl AsRef<Path>) -> Result<Outline> {
    let path = path.as_ref();
    let (text, source_name) = crate::error::read_source(path)?;
    outline_str(&text, &source_name)
}

/// The tree of URDF text; `source_name` names it in errors. Errors: what
/// [`super::parse_str`] reports about the file and the graph (malformed XML,
/// a missing link, a loop), never about a chain.
///
/// ```
/// let text = r#"<robot name="y">
///   <link name="base"/><link name="left"/><link name="right"/>
///   <joint name="a" type="revolute"><parent link="base"/><child link="left"/>
///     <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
///   <joint name="b" type="fixed"><parent link="base"/><child link="right"/></joint>
/// </robot>"#;
/// let tree = armkit::urdf::outline_str(text, "y.urdf").unwrap();
/// assert_eq!(tree.roots, ["base"]);
/// assert_eq!(tree.leaves, ["left", "right"]);
/// assert_eq!(tree.joints[1].kind, "fixed");
/// ```
pub fn outline_str(text: &str, source_name: &str) -> Result<Outline> {
    let (robot, document) = read_robot(text, source_name)?;
    let tree =
        Tree::new(&robot, SourceLines::new(&document, &robot)).map_err(|reason| Error::Parse {
            source_name: source_name.to_string(),
            reason,
        })?;
    let roots = tree.roots();
    let mut joints = Vec::new();
    let mut leaves = Vec::new();
    for &root in &roots {
        leaves.extend(
            tree.leaves_below(root)
                .into_iter()
                .map(|l| tree.link_name(l).to_string()),
        );
        // Depth-first, children in document order.
        let mut pending: Vec<(usize, usize)> = tree
            .child_joints(root)
            .iter()
            .rev()
            .map(|&j| (j, 0))
            .collect();
        while let Some((j, depth)) = pending.pop() {
            let joint = &robot.joints[j];
            joints.push(OutlineJoint {
                name: joint.name.clone(),
                kind: type_name(&joint.joint_type),
                parent: joint.parent.link.clone(),
                child: joint.child.link.clone(),
                depth,
            });
            let child = tree.child_link(j);
            pending.extend(
                tree.child_joints(child)
                    .iter()
                    .rev()
                    .map(|&k| (k, depth + 1)),
            );
        }
    }
    Ok(Outline {
        robot: robot.name.clone(),
        links: robot.links.len(),
        roots: roots
            .iter()
            .map(|&l| tree.link_name(l).to_string())
            .collect(),
        joints,
        leaves,
    })
}
