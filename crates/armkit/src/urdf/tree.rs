//! The link-joint graph of a URDF: checks that it is a tree, and selects the
//! serial chain from a base link to a tip link.

use std::collections::HashMap;

use super::ChainSelection;

/// Where each `<link>` and `<joint>` element starts, for messages.
#[derive(Clone, Debug, Default)]
pub(super) struct SourceLines {
    links: Vec<usize>,
    joints: Vec<usize>,
}

impl SourceLines {
    /// Lines of the `<link>` and `<joint>` children of the root, in document
    /// order, which is the order `urdf-rs` keeps. If the counts differ from
    /// the parsed robot's (they should not), no line is reported.
    pub(super) fn new(document: &super::xml::Document, robot: &urdf_rs::Robot) -> Self {
        let lines_of = |tag: &str| -> Vec<usize> {
            document
                .children
                .iter()
                .filter(|e| e.name == tag)
                .map(|e| e.line)
                .collect()
        };
        let links = lines_of("link");
        let joints = lines_of("joint");
        if links.len() == robot.links.len() && joints.len() == robot.joints.len() {
            SourceLines { links, joints }
        } else {
            SourceLines::default()
        }
    }

    fn suffix(line: Option<&usize>) -> String {
        line.map_or(String::new(), |l| format!(" (line {l})"))
    }
}

/// The URDF's links and joints as a graph, checked to be a forest: every
/// joint's parent and child exist, no link is the child of two joints, and
/// following parents from any link ends at a root.
pub(super) struct Tree<'r> {
    robot: &'r urdf_rs::Robot,
    lines: SourceLines,
    link_index: HashMap<&'r str, usize>,
    /// Per link: the joint whose child it is (`None` for a root).
    parent_joint: Vec<Option<usize>>,
    /// Per link: the joints whose parent it is, in document order.
    child_joints: Vec<Vec<usize>>,
    /// Per joint: (parent link, child link).
    joint_links: Vec<(usize, usize)>,
}

/// The serial chain between two links.
#[derive(Clone, Debug)]
pub(super) struct Chain {
    /// Base link index.
    pub base: usize,
    /// Tip link index.
    pub tip: usize,
    /// Joints from the base to the tip (fixed and moving).
    pub joints: Vec<usize>,
}

impl<'r> Tree<'r> {
    /// Builds and checks the graph; the error message names the element.
    pub(super) fn new(robot: &'r urdf_rs::Robot, lines: SourceLines) -> Result<Self, String> {
        let mut tree = Tree {
            robot,
            lines,
            link_index: HashMap::new(),
            parent_joint: vec![None; robot.links.len()],
            child_joints: vec![Vec::new(); robot.links.len()],
            joint_links: Vec::with_capacity(robot.joints.len()),
        };
        if robot.links.is_empty() {
            return Err("the robot has no <link> element".into());
        }
        for (index, link) in robot.links.iter().enumerate() {
            if let Some(&first) = tree.link_index.get(link.name.as_str()) {
                return Err(format!(
                    "{} is defined twice (first as {})",
                    tree.link(index),
                    tree.link(first)
                ));
            }
            tree.link_index.insert(link.name.as_str(), index);
        }
        let mut joint_names: HashMap<&str, usize> = HashMap::new();
        for (index, joint) in robot.joints.iter().enumerate() {
            if let Some(&first) = joint_names.get(joint.name.as_str()) {
                return Err(format!(
                    "{} is defined twice (first as {})",
                    tree.joint(index),
                    tree.joint(first)
                ));
            }
            joint_names.insert(joint.name.as_str(), index);
            let endpoint = |role: &str, name: &str| {
                tree.link_index.get(name).copied().ok_or_else(|| {
                    format!(
                        "{}: its {role} link `{name}` does not exist (no <link name=\"{name}\">)",
                        tree.joint(index)
                    )
                })
            };
            let parent = endpoint("parent", &joint.parent.link)?;
            let child = endpoint("child", &joint.child.link)?;
            if let Some(other) = tree.parent_joint[child] {
                return Err(format!(
                    "kinematic loop: {} is the child of two joints, {} and {} (a URDF must be a tree)",
                    tree.link(child),
                    tree.joint(other),
                    tree.joint(index)
                ));
            }
            tree.parent_joint[child] = Some(index);
            tree.child_joints[parent].push(index);
            tree.joint_links.push((parent, child));
        }
        tree.check_no_cycle()?;
        Ok(tree)
    }

    /// `link `name` (line L)`.
    pub(super) fn link(&self, index: usize) -> String {
        format!(
            "link `{}`{}",
            self.robot.links[index].name,
            SourceLines::suffix(self.lines.links.get(index))
        )
    }

    /// `joint `name` (line L)`.
    pub(super) fn joint(&self, index: usize) -> String {
        format!(
            "joint `{}`{}",
            self.robot.joints[index].name,
            SourceLines::suffix(self.lines.joints.get(index))
        )
    }

    /// The name of joint `index`.
    pub(super) fn joint_name(&self, index: usize) -> &'r str {
        self.robot.joints[index].name.as_str()
    }

    pub(super) fn link_name(&self, index: usize) -> &'r str {
        self.robot.links[index].name.as_str()
    }

    /// Every link has at most one parent (checked in `new`), so a cycle shows
    /// as a walk up the parents that never reaches a root.
    fn check_no_cycle(&self) -> Result<(), String> {
        #[derive(Clone, Copy, PartialEq)]
        enum Mark {
            Unvisited,
            OnPath,
            Done,
        }
        let mut marks = vec![Mark::Unvisited; self.robot.links.len()];
        for start in 0..self.robot.links.len() {
            let mut path = Vec::new();
            let mut link = start;
            loop {
                match marks[link] {
                    Mark::Done => break,
                    Mark::OnPath => {
                        let from = path.iter().position(|&l| l == link).unwrap_or(0);
                        // `path` goes from child to parent; print parent to child.
                        let names: Vec<&str> = std::iter::once(link)
                            .chain(path[from..].iter().rev().copied())
                            .map(|l| self.link_name(l))
                            .collect();
                        return Err(format!(
                            "kinematic loop: the links {} form a cycle (a URDF must be a tree)",
                            names.join(" -> ")
                        ));
                    }
                    Mark::Unvisited => {
                        marks[link] = Mark::OnPath;
                        path.push(link);
                        match self.parent_joint[link] {
                            Some(joint) => link = self.joint_links[joint].0,
                            None => break,
                        }
                    }
                }
            }
            for l in path {
                marks[l] = Mark::Done;
            }
        }
        Ok(())
    }

    /// The joints whose parent is `link`.
    pub(super) fn child_joints(&self, link: usize) -> &[usize] {
        &self.child_joints[link]
    }

    /// The child link of `joint`.
    pub(super) fn child_link(&self, joint: usize) -> usize {
        self.joint_links[joint].1
    }

    fn find_link(&self, role: &str, name: &str) -> Result<usize, String> {
        self.link_index.get(name).copied().ok_or_else(|| {
            let known: Vec<&str> = self.robot.links.iter().map(|l| l.name.as_str()).collect();
            format!(
                "the {role} link `{name}` does not exist; the links are: {}",
                known.join(", ")
            )
        })
    }

    pub(super) fn roots(&self) -> Vec<usize> {
        (0..self.robot.links.len())
            .filter(|&l| self.parent_joint[l].is_none())
            .collect()
    }

    fn top_ancestor(&self, mut link: usize) -> usize {
        while let Some(joint) = self.parent_joint[link] {
            link = self.joint_links[joint].0;
        }
        link
    }

    /// Links without children in the subtree below `link` (itself if it has none).
    pub(super) fn leaves_below(&self, link: usize) -> Vec<usize> {
        let mut leaves = Vec::new();
        let mut pending = vec![link];
        while let Some(l) = pending.pop() {
            let children = &self.child_joints[l];
            if children.is_empty() {
                leaves.push(l);
            }
            pending.extend(children.iter().rev().map(|&j| self.joint_links[j].1));
        }
        leaves
    }

    fn quoted_names(&self, links: &[usize]) -> String {
        links
            .iter()
            .map(|&l| format!("`{}`", self.link_name(l)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The chain `selection` asks for. Defaults: the base is the root (of the
    /// tree holding the tip, when a tip is given), the tip the only leaf below
    /// the base. The error names the links and lists the choices.
    pub(super) fn select(&self, selection: &ChainSelection) -> Result<Chain, String> {
        let tip = selection
            .tip
            .as_deref()
            .map(|name| self.find_link("tip", name))
            .transpose()?;
        let base = match (selection.base.as_deref(), tip) {
            (Some(name), _) => self.find_link("base", name)?,
            (None, Some(tip)) => self.top_ancestor(tip),
            (None, None) => match self.roots().as_slice() {
                [root] => *root,
                roots => {
                    return Err(format!(
                        "the URDF has {} root links ({}), not one tree: choose the base link",
                        roots.len(),
                        self.quoted_names(roots)
                    ))
                }
            },
        };
        let tip = match tip {
            Some(tip) => tip,
            None => match self.leaves_below(base).as_slice() {
                [leaf] => *leaf,
                leaves => {
                    return Err(format!(
                    "the tree below the base link `{}` has {} leaf links ({}): choose the tip link",
                    self.link_name(base),
                    leaves.len(),
                    self.quoted_names(leaves)
                ))
                }
            },
        };
        if tip == base {
            return Err(format!(
                "the base and the tip are the same link `{}`: the chain has no joint",
                self.link_name(base)
            ));
        }
        let mut joints = Vec::new();
        let mut link = tip;
        while link != base {
            let Some(joint) = self.parent_joint[link] else {
                return Err(format!(
                    "the tip link `{}` is not below the base link `{}` (going up from the tip reaches the root `{}` without passing the base)",
                    self.link_name(tip),
                    self.link_name(base),
                    self.link_name(link)
                ));
            };
            joints.push(joint);
            link = self.joint_links[joint].0;
        }
        joints.reverse();
        Ok(Chain { base, tip, joints })
    }
}
