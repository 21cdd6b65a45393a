//! Building a [`Model`] from joints with any axis, checked.

use super::coupling::{JointMap, MimicJoint};
use super::{
    DhConvention, DhLink, Joint, JointKind, JointLimits, LinkInertia, Model, PlacementForm,
};
use crate::error::{Error, Result};
use crate::math::{rotation_z_to, Pose, Vector3};

/// One moving joint as a URDF describes it.
///
/// The joint frame sits at `origin` in the parent link's frame; the joint
/// rotates about (or slides along) `axis`, a unit vector in the joint frame;
/// the child link's frame is the joint frame after the motion. Limits are in
/// rad (m for prismatic joints); `inertia` is in the child link's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpec {
    /// Joint name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// Joint frame in the parent link frame.
    pub origin: Pose,
    /// Motion axis in the joint frame (normalized at build time; must be non-zero).
    pub axis: Vector3<f64>,
    /// Limits; continuous joints must leave the position limits infinite.
    pub limits: JointLimits,
    /// Mass properties of the child link, in the child link frame.
    pub inertia: Option<LinkInertia>,
}

impl JointSpec {
    fn new(name: impl Into<String>, kind: JointKind, limits: JointLimits) -> Self {
        JointSpec {
            name: name.into(),
            kind,
            origin: Pose::identity(),
            axis: Vector3::z(),
            limits,
            inertia: None,
        }
    }

    /// A revolute joint about z with the given position limits (rad).
    pub fn revolute(name: impl Into<String>, lower: f64, upper: f64) -> Self {
        Self::new(
            name,
            JointKind::Revolute,
            JointLimits::position(lower, upper),
        )
    }

    /// A continuous (unlimited, wrapping) revolute joint about z.
    pub fn continuous(name: impl Into<String>) -> Self {
        Self::new(name, JointKind::Continuous, JointLimits::UNLIMITED)
    }

    /// A prismatic joint along z with the given position limits (m).
    pub fn prismatic(name: impl Into<String>, lower: f64, upper: f64) -> Self {
        Self::new(
            name,
            JointKind::Prismatic,
            JointLimits::position(lower, upper),
        )
    }

    /// Sets the joint frame's placement in the parent link frame.
    pub fn with_origin(mut self, origin: Pose) -> Self {
        self.origin = origin;
        self
    }

    /// Sets the motion axis (in the joint frame).
    pub fn with_axis(mut self, axis: Vector3<f64>) -> Self {
        self.axis = axis;
        self
    }

    /// Sets the velocity limit magnitude (rad/s or m/s).
    pub fn with_velocity_limit(mut self, velocity: f64) -> Self {
        self.limits.velocity = Some(velocity);
        self
    }

    /// Sets the acceleration limit magnitude (rad/s^2 or m/s^2).
    pub fn with_acceleration_limit(mut self, acceleration: f64) -> Self {
        self.limits.acceleration = Some(acceleration);
        self
    }

    /// Sets the effort (torque or force) limit magnitude (N m or N).
    pub fn with_effort_limit(mut self, effort: f64) -> Self {
        self.limits.effort = Some(effort);
        self
    }

    /// Sets the child link's mass properties (child link frame).
    pub fn with_inertia(mut self, inertia: LinkInertia) -> Self {
        self.inertia = Some(inertia);
        self
    }
}

#[derive(Clone, Debug)]
enum Element {
    Joint(Box<JointSpec>),
    Fixed(Pose),
}

/// Assembles a [`Model`] from moving joints and fixed transforms, base to tip.
///
/// ```
/// use armkit::math::{Pose, Vector3};
/// use armkit::model::{JointSpec, ModelBuilder};
/// let model = ModelBuilder::new("slider-crank")
///     .joint(JointSpec::prismatic("slide", 0.0, 0.5).with_axis(Vector3::new(1.0, 1.0, 0.0)))
///     .fixed(Pose::trans_z(0.1))
///     .joint(JointSpec::continuous("spin"))
///     .build()
///     .unwrap();
/// assert_eq!(model.dof(), 2);
/// ```
#[derive(Clone, Debug)]
pub struct ModelBuilder {
    name: String,
    base: Pose,
    tool: Pose,
    elements: Vec<Element>,
    off_chain: Vec<JointSpec>,
    mimics: Vec<MimicJoint>,
    dh: Option<(DhConvention, Vec<DhLink>)>,
}

impl ModelBuilder {
    /// An empty chain named `name`, identity base and tool.
    pub fn new(name: impl Into<String>) -> Self {
        ModelBuilder {
            name: name.into(),
            base: Pose::identity(),
            tool: Pose::identity(),
            elements: Vec::new(),
            off_chain: Vec::new(),
            mimics: Vec::new(),
            dh: None,
        }
    }

    /// Sets the base transform (robot base frame in the world frame).
    pub fn base(mut self, base: Pose) -> Self {
        self.base = base;
        self
    }

    /// Sets the tool transform (end-effector frame in the last link frame).
    pub fn tool(mut self, tool: Pose) -> Self {
        self.tool = tool;
        self
    }

    /// Appends a moving joint.
    pub fn joint(mut self, joint: JointSpec) -> Self {
        self.elements.push(Element::Joint(Box::new(joint)));
        self
    }

    /// Appends a fixed transform (a fixed joint).
    pub fn fixed(mut self, placement: Pose) -> Self {
        self.elements.push(Element::Fixed(placement));
        self
    }

    /// Declares joint `mimic.joint` a mimic joint: its position follows
    /// `mimic.leader`'s, `q = multiplier * q_leader + offset`, and it leaves
    /// the configuration (see [`crate::model::CouplingLaw::Mimic`]). The
    /// leader may be on the chain, another mimic joint (resolved to the
    /// first independent leader) or an [`off_chain_joint`](Self::off_chain_joint).
    pub fn mimic(mut self, mimic: MimicJoint) -> Self {
        self.mimics.push(mimic);
        self
    }

    /// Adds a joint that is not on the chain but that a mimic joint of the
    /// chain follows (e.g. the other finger of a parallel gripper): it
    /// becomes an entry of the configuration, with its kind and limits. Its
    /// origin, axis and inertia are not used.
    pub fn off_chain_joint(mut self, joint: JointSpec) -> Self {
        self.off_chain.push(joint);
        self
    }

    pub(super) fn dh_source(mut self, convention: DhConvention, links: Vec<DhLink>) -> Self {
        self.dh = Some((convention, links));
        self
    }

    /// Validates every element and folds the chain into a [`Model`].
    ///
    /// Errors name the link (its 0-based position among the moving joints)
    /// and the field: non-finite numbers, a lower limit above the upper one,
    /// a zero axis, a non-positive velocity limit, bad mass properties, an
    /// empty chain, or a base or tool that is not a rigid transform.
    pub fn build(self) -> Result<Model> {
        let structure_error = |reason: String| Error::InvalidModelStructure {
            model: self.name.clone(),
            reason,
        };
        check_transform(&self.base).map_err(|r| structure_error(format!("base: {r}")))?;
        check_transform(&self.tool).map_err(|r| structure_error(format!("tool: {r}")))?;

        let mut joints = Vec::new();
        let mut placements = Vec::new();
        let mut link_offsets = Vec::new();
        // Transform accumulated since the last joint's motion frame.
        let mut pending = self.base;
        for element in &self.elements {
            match element {
                Element::Fixed(placement) => {
                    check_transform(placement).map_err(|reason| Error::InvalidModel {
                        link: joints.len(),
                        name: format!("fixed after joint {}", joints.len()),
                        field: "origin".into(),
                        reason,
                    })?;
                    pending = pending * *placement;
                }
                Element::Joint(spec) => {
                    let link = joints.len();
                    validate_joint(spec).map_err(|(field, reason)| Error::InvalidModel {
                        link,
                        name: spec.name.clone(),
                        field: field.into(),
                        reason,
                    })?;
                    // Rotate the joint frame so that its axis becomes local z;
                    // the child link frame is then the motion frame times
                    // align', which the next element picks up through `pending`.
                    let align = Pose::from_rotation(rotation_z_to(&spec.axis.normalize()));
                    placements.push(pending * spec.origin * align);
                    let unalign = align.inverse();
                    link_offsets.push(unalign);
                    pending = unalign;
                    joints.push(Joint {
                        name: spec.name.clone(),
                        kind: spec.kind,
                        limits: spec.limits,
                        inertia: spec.inertia.map(|i| i.transformed(&align.inverse())),
                    });
                }
            }
        }
        if joints.is_empty() {
            return Err(structure_error(
                "the chain has no moving joint (an empty chain)".into(),
            ));
        }
        let mut off_chain = Vec::with_capacity(self.off_chain.len());
        for spec in &self.off_chain {
            validate_joint(spec).map_err(|(field, reason)| Error::InvalidModel {
                link: joints.len() + off_chain.len(),
                name: spec.name.clone(),
                field: field.into(),
                reason,
            })?;
            off_chain.push(Joint {
                name: spec.name.clone(),
                kind: spec.kind,
                limits: spec.limits,
                inertia: None,
            });
        }
        let resolved = super::mimic::resolve(&self.name, &joints, &off_chain, &self.mimics)?;
        Ok(Model {
            name: self.name,
            joints: resolved.joints,
            chain_kinds: joints.iter().map(|j| j.kind).collect(),
            chain_joints: joints,
            placement_forms: placements.iter().map(PlacementForm::of).collect(),
            placements,
            link_offsets,
            tail_form: PlacementForm::of(&(pending * self.tool)),
            tail: pending * self.tool,
            base: self.base,
            tool: self.tool,
            map: JointMap::new(resolved.drives),
            couplings: resolved.couplings,
            dh: self.dh,
        })
    }
}

fn check_transform(pose: &Pose) -> std::result::Result<(), String> {
    Pose::from_matrix4(&pose.to_matrix4()).map(|_| ())
}

fn validate_joint(spec: &JointSpec) -> std::result::Result<(), (&'static str, String)> {
    check_transform(&spec.origin).map_err(|r| ("origin", r))?;
    let axis_norm = spec.axis.norm();
    if !(axis_norm.is_finite() && axis_norm > 1e-12) {
        return Err((
            "axis",
            format!(
                "must be a finite non-zero vector, got {:?}",
                spec.axis.as_slice()
            ),
        ));
    }
    let limits = &spec.limits;
    if limits.lower.is_nan() || limits.upper.is_nan() {
        return Err(("qlim", "position limits must not be NaN".into()));
    }
    if limits.lower > limits.upper {
        return Err((
            "qlim",
            format!(
                "lower limit {} is above upper limit {}",
                limits.lower, limits.upper
            ),
        ));
    }
    if spec.kind == JointKind::Continuous && limits.is_bounded() {
        return Err(("qlim", "a continuous joint has no position limits".into()));
    }
    for (field, value) in [
        ("vlim", limits.velocity),
        ("alim", limits.acceleration),
        ("tlim", limits.effort),
    ] {
        if let Some(v) = value {
            if !(v.is_finite() && v > 0.0) {
                return Err((field, format!("must be finite and > 0, got {v}")));
            }
        }
    }
    if let Some(inertia) = &spec.inertia {
        inertia.validate()?;
    }
    Ok(())
}

impl Model {
    /// A model from a DH table, with identity base and tool transforms.
    ///
    /// Joint names are `q1`, `q2`, ...; errors name the 0-based link index and
    /// the DH field (`theta`, `d`, `a`, `alpha`, `offset`, `qlim`, `vlim`,
    /// `mass`, `com`, `inertia`).
    pub fn from_dh(name: &str, convention: DhConvention, links: &[DhLink]) -> Result<Model> {
        Self::from_dh_with_transforms(name, convention, links, Pose::identity(), Pose::identity())
    }

    /// A model from a DH table: `T = base A_1 ... A_n tool`.
    pub fn from_dh_with_transforms(
        name: &str,
        convention: DhConvention,
        links: &[DhLink],
        base: Pose,
        tool: Pose,
    ) -> Result<Model> {
        let mut builder = ModelBuilder::new(name)
            .base(base)
            .tool(tool)
            .dh_source(convention, links.to_vec());
        for (j, link) in links.iter().enumerate() {
            let invalid = |(field, reason): (&str, String)| Error::InvalidModel {
                link: j,
                name: format!("q{}", j + 1),
                field: field.into(),
                reason,
            };
            link.check_numbers().map_err(invalid)?;
            let (before, after) = link.split(convention);
            let spec = JointSpec {
                name: format!("q{}", j + 1),
                kind: link.kind,
                origin: before,
                axis: Vector3::z(),
                limits: link.limits,
                // The DH frame is the motion frame followed by `after`.
                inertia: link.inertia.map(|i| i.transformed(&after)),
            };
            builder = builder.joint(spec).fixed(after);
        }
        let mut model = builder.build()?;
        // The axis is z already (no turn): DH frame j is the motion frame
        // followed by `after`.
        for (offset, link) in model.link_offsets.iter_mut().zip(links) {
            *offset = link.split(convention).1;
        }
        Ok(model)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_chain_is_an_error() {
        let err = ModelBuilder::new("nothing").build().unwrap_err();
        assert!(err.to_string().contains("empty chain"), "{err}");
    }

    #[test]
    fn inverted_limits_name_link_and_field() {
        let err = ModelBuilder::new("r")
            .joint(JointSpec::revolute("a", -1.0, 1.0))
            .joint(JointSpec::revolute("b", 1.0, -1.0))
            .build()
            .unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("link 1") && text.contains("`b`") && text.contains("qlim"),
            "{text}"
        );
    }

    #[test]
    fn zero_axis_and_bad_velocity_are_errors() {
        let err = ModelBuilder::new("r")
            .joint(JointSpec::revolute("a", -1.0, 1.0).with_axis(Vector3::zeros()))
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("axis"), "{err}");
        let err = ModelBuilder::new("r")
            .joint(JointSpec::revolute("a", -1.0, 1.0).with_velocity_limit(-2.0))
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("vlim"), "{err}");
    }

    #[test]
    fn non_finite_origin_and_bad_base_are_errors() {
        let err = ModelBuilder::new("r")
            .joint(JointSpec::revolute("a", -1.0, 1.0).with_origin(Pose::trans_x(f64::NAN)))
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("origin"), "{err}");
        let mut base = Pose::identity();
        base.rotation[(0, 0)] = 3.0;
        let err = ModelBuilder::new("r")
            .base(base)
            .joint(JointSpec::revolute("a", -1.0, 1.0))
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("base"), "{err}");
    }

    #[test]
    fn bad_inertia_is_an_error() {
        let inertia = LinkInertia::point_mass(-1.0, Vector3::zeros());
        let err = ModelBuilder::new("r")
            .joint(JointSpec::revolute("a", -1.0, 1.0).with_inertia(inertia))
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("mass"), "{err}");
        let mut inertia = LinkInertia::point_mass(1.0, Vector3::zeros());
        inertia.inertia[(0, 0)] = -1.0;
        let err = ModelBuilder::new("r")
            .joint(JointSpec::revolute("a", -1.0, 1.0).with_inertia(inertia))
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("positive semi-definite"), "{err}");
    }

    #[test]
    fn continuous_joint_with_limits_is_an_error() {
        let mut spec = JointSpec::continuous("c");
        spec.limits = JointLimits::position(-1.0, 1.0);
        let err = ModelBuilder::new("r").joint(spec).build().unwrap_err();
        assert!(err.to_string().contains("continuous"), "{err}");
    }
}
