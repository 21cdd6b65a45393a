//! The robot model: an immutable description of a serial chain.
//!
//! As in Pinocchio, the [`Model`] holds what never changes (geometry, limits,
//! mass properties) and a [`crate::kinematics::Data`] workspace holds what the
//! algorithms compute. A model is built once, from
//! * Denavit-Hartenberg parameters ([`Model::from_dh`], standard or modified),
//! * a [`ModelBuilder`] of revolute, continuous, prismatic and fixed joints with
//!   any axis (what the URDF loader uses),
//! * a built-in robot ([`crate::robots`]) or a description file
//!   ([`crate::description`]).
//!
//! Internally every joint is reduced to "a fixed placement, then a rotation
//! about / translation along the local z axis": fixed joints, DH link
//! transforms, joint offsets and non-z axes are folded into the placements at
//! build time, so that forward kinematics is one tight loop whatever the source.
//!
//! ```
//! use armkit::model::{DhConvention, DhLink, JointKind, Model};
//! use std::f64::consts::FRAC_PI_2;
//! // A planar 2R arm, standard DH, 0.5 m and 0.3 m links.
//! let links = [
//!     DhLink::revolute(0.0, 0.5, 0.0).with_limits(-FRAC_PI_2, FRAC_PI_2),
//!     DhLink::revolute(0.0, 0.3, 0.0).with_limits(-2.5, 2.5),
//! ];
//! let model = Model::from_dh("planar2r", DhConvention::Standard, &links).unwrap();
//! assert_eq!(model.dof(), 2);
//! assert_eq!(model.joints()[1].kind, JointKind::Revolute);
//! ```

mod builder;
mod coupling;
mod dh;
mod mimic;
mod placement;

pub use builder::{JointSpec, ModelBuilder};
pub(crate) use coupling::JointMap;
pub use coupling::{CouplingCurve, CouplingLaw, JointCoupling, MimicJoint};
pub use dh::{DhConvention, DhLink};
pub(crate) use placement::PlacementForm;

use crate::error::{check_finite_vector, Error, Result};
use crate::math::{Matrix3, Pose, Vector3};

/// How a joint moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// Rotation about the joint axis, within position limits (rad).
    Revolute,
    /// Rotation about the joint axis without position limits: angles wrap.
    Continuous,
    /// Translation along the joint axis, within position limits (m).
    Prismatic,
}

impl JointKind {
    /// True for revolute and continuous joints (their position is an angle).
    #[inline]
    pub fn is_rotational(self) -> bool {
        !matches!(self, JointKind::Prismatic)
    }
}

/// Position, velocity, acceleration and torque limits of one joint.
///
/// Units: rad, rad/s, rad/s^2, N m for rotational joints; m, m/s, m/s^2, N
/// for prismatic ones. Position limits may be infinite (continuous joints, or
/// joints the source gives no limits for); velocity, acceleration and effort
/// (torque or force) limits are symmetric bounds on the magnitude, `None`
/// when unknown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lower position limit.
    pub lower: f64,
    /// Upper position limit.
    pub upper: f64,
    /// Maximum speed magnitude, if known.
    pub velocity: Option<f64>,
    /// Maximum acceleration magnitude, if known.
    pub acceleration: Option<f64>,
    /// Maximum torque (N m) or force (N) magnitude the joint's motor can
    /// deliver, if known (URDF `<limit effort>`, DH files' `tlim`).
    pub effort: Option<f64>,
}

impl JointLimits {
    /// No limits at all.
    pub const UNLIMITED: JointLimits = JointLimits {
        lower: f64::NEG_INFINITY,
        upper: f64::INFINITY,
        velocity: None,
        acceleration: None,
        effort: None,
    };

    /// Position limits only.
    pub fn position(lower: f64, upper: f64) -> Self {
        JointLimits {
            lower,
            upper,
            ..Self::UNLIMITED
        }
    }

    /// True when `value` lies in `[lower, upper]`.
    pub fn contains(&self, value: f64) -> bool {
        value >= self.lower && value <= self.upper
    }

    /// True when both position limits are finite.
    pub fn is_bounded(&self) -> bool {
        self.lower.is_finite() && self.upper.is_finite()
    }

    /// The middle of the position range, or 0 when a bound is infinite.
    pub fn midpoint(&self) -> f64 {
        if self.is_bounded() {
            0.5 * (self.lower + self.upper)
        } else {
            0.0_f64.clamp(self.lower, self.upper)
        }
    }
}

/// Mass properties of the link a joint moves.
///
/// Expressed in the joint's frame as [`crate::kinematics::Data::joint_frames`]
/// reports it (origin on the joint axis, z along the axis, after the joint's
/// motion): `com` in metres, `inertia` in kg m^2 about the centre of mass,
/// in that frame's axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkInertia {
    /// Mass, kg (>= 0; a body of zero mass may still have rotational
    /// inertia, as a URDF link with a zero `<mass>` and an `<inertia>` has).
    pub mass: f64,
    /// Centre of mass, m, in the joint frame.
    pub com: Vector3<f64>,
    /// Inertia tensor about the centre of mass, kg m^2, symmetric positive
    /// semi-definite, in the joint frame's axes.
    pub inertia: Matrix3<f64>,
}

impl LinkInertia {
    /// A point mass (zero rotational inertia) at `com`.
    pub fn point_mass(mass: f64, com: Vector3<f64>) -> Self {
        LinkInertia {
            mass,
            com,
            inertia: Matrix3::zeros(),
        }
    }

    /// One body from several: total mass, mass-weighted centre of mass, and the
    /// tensors moved to that centre (parallel-axis theorem,
    /// `I += m (|d|^2 E - d d')` with `d` the part's offset from the centre).
    /// Parts of zero mass add their tensor alone (the same about any point); a
    /// body of zero total mass has its centre of mass at the origin, as in
    /// Pinocchio. `None` for no parts.
    pub fn combine(parts: &[LinkInertia]) -> Option<LinkInertia> {
        if parts.is_empty() {
            return None;
        }
        let mass: f64 = parts.iter().map(|p| p.mass).sum();
        let first_moment = parts
            .iter()
            .fold(Vector3::zeros(), |sum, p| sum + p.com * p.mass);
        let com = if mass > 0.0 {
            first_moment / mass
        } else {
            Vector3::zeros()
        };
        let inertia = parts.iter().fold(Matrix3::zeros(), |sum, p| {
            let d = p.com - com;
            sum + p.inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * p.mass
        });
        Some(LinkInertia { mass, com, inertia })
    }

    /// The same body seen from a frame in which this body's frame sits at
    /// `placement`: `com' = T com`, `I' = R I R'`.
    pub fn transformed(&self, placement: &Pose) -> Self {
        LinkInertia {
            mass: self.mass,
            com: placement.transform_point(&self.com),
            inertia: placement.rotation * self.inertia * placement.rotation.transpose(),
        }
    }

    /// Checks mass >= 0, finite centre of mass, symmetric positive
    /// semi-definite inertia. The error string names the field.
    pub fn validate(&self) -> std::result::Result<(), (&'static str, String)> {
        if !(self.mass.is_finite() && self.mass >= 0.0) {
            return Err((
                "mass",
                format!("must be finite and >= 0, got {}", self.mass),
            ));
        }
        if !self.com.iter().all(|v| v.is_finite()) {
            return Err((
                "com",
                format!("must be finite, got {:?}", self.com.as_slice()),
            ));
        }
        if !self.inertia.iter().all(|v| v.is_finite()) {
            return Err(("inertia", "must be finite".into()));
        }
        let asymmetry = (self.inertia - self.inertia.transpose()).amax();
        if asymmetry > 1e-9 * self.inertia.amax().max(1.0) {
            return Err((
                "inertia",
                format!("must be symmetric (asymmetry {asymmetry:e})"),
            ));
        }
        let min_eigenvalue = self.inertia.symmetric_eigenvalues().min();
        if min_eigenvalue < -1e-12 * self.inertia.amax().max(1.0) {
            return Err((
                "inertia",
                format!("must be positive semi-definite (smallest eigenvalue {min_eigenvalue:e})"),
            ));
        }
        Ok(())
    }
}

/// Everything known about one moving joint besides its placement.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Name (from the source file, or `q1`, `q2`, ... for DH tables).
    pub name: String,
    /// How the joint moves.
    pub kind: JointKind,
    /// Position, velocity and acceleration limits.
    pub limits: JointLimits,
    /// Mass properties of the link this joint moves, if known.
    pub inertia: Option<LinkInertia>,
}

/// An immutable serial-chain robot model.
///
/// Frames: the world frame is the one in which [`Model::base`] places the
/// robot; poses and Jacobians are reported in it unless stated otherwise.
/// Joint positions `q` (the configuration) hold the independent joints
/// ([`Model::joints`], [`Model::dof`] of them), rad or m; mimic joints of the
/// chain follow them ([`Model::chain_joints`], the `coupling` module).
#[derive(Clone, Debug)]
pub struct Model {
    name: String,
    /// The configuration's joints (independent), limits tightened by mimics.
    joints: Vec<Joint>,
    /// Every moving joint of the chain, base to tip, with its own limits.
    chain_joints: Vec<Joint>,
    /// `chain_joints[j].kind`, packed for the kinematics' loops.
    chain_kinds: Vec<JointKind>,
    /// Placement of chain joint j's frame (before its motion) in the frame of
    /// chain joint j-1 after its motion; for j = 0, in the world frame (base folded in).
    placements: Vec<Pose>,
    /// Each chain joint's link frame in its motion frame (see
    /// [`Model::link_frame_offsets`]).
    link_offsets: Vec<Pose>,
    /// The form of each placement (`placement` module), for the kinematics' loops.
    placement_forms: Vec<PlacementForm>,
    /// The form of `tail`.
    tail_form: PlacementForm,
    /// Placement of the end-effector (tool) frame in the last joint's frame.
    tail: Pose,
    base: Pose,
    tool: Pose,
    /// Configuration -> chain positions (mimic joints and additive curves).
    map: JointMap,
    /// Mimic couplings (one per mimic joint), then additive ones.
    couplings: Vec<JointCoupling>,
    dh: Option<(DhConvention, Vec<DhLink>)>,
}

impl Model {
    /// Model name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Number of independent joints (degrees of freedom): the length of a
    /// configuration `q`. Mimic joints are not counted.
    #[inline]
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// The independent joints, one per entry of `q`, base to tip (a leader
    /// off the chain at the place of its first follower). A leader's limits
    /// are tightened by its mimic joints' (the tighter bound wins), so that
    /// `q` within these limits keeps every mimic joint within its own.
    /// Equal to [`Model::chain_joints`] when the chain has no mimic joint.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Every moving joint of the chain, base to tip, mimic joints included,
    /// with their own limits and the mass properties of the links they move
    /// (the joints [`crate::kinematics::Data::joint_frames`] reports).
    #[inline]
    pub fn chain_joints(&self) -> &[Joint] {
        &self.chain_joints
    }

    /// Placement of each chain joint's frame, before its motion, in the previous
    /// joint's frame after its motion (the first in the world frame). Every
    /// joint moves about or along the local z axis of its frame. One per
    /// [`Model::chain_joints`].
    #[inline]
    pub fn joint_placements(&self) -> &[Pose] {
        &self.placements
    }

    /// The frame of the link each chain joint moves, as the model's source
    /// defines it, in that joint's motion frame
    /// ([`crate::kinematics::Data::joint_frames`], z along the axis): for a
    /// URDF, the child link's frame (the joint frame of the file, axis as
    /// written; Pinocchio's `oMi`); for a DH table, DH frame j (standard: at
    /// the link's distal end; modified: on joint j's axis); for joints built
    /// with [`ModelBuilder`], the joint's frame before its axis was turned
    /// onto z. One per [`Model::chain_joints`];
    /// [`crate::kinematics::link_frames`] gives them in the world frame.
    #[inline]
    pub fn link_frame_offsets(&self) -> &[Pose] {
        &self.link_offsets
    }

    /// Placement of the end-effector frame in the last joint's frame (tool
    /// transform and any trailing fixed transforms folded in).
    #[inline]
    pub fn end_effector_placement(&self) -> &Pose {
        &self.tail
    }

    /// The base transform: the robot's base frame in the world frame.
    pub fn base(&self) -> &Pose {
        &self.base
    }

    /// The tool transform: the end-effector frame in the flange (last link) frame.
    pub fn tool(&self) -> &Pose {
        &self.tool
    }

    /// The first joint coupling (a mimic joint, or e.g. the gantry beam's
    /// deflection), if any; see [`Model::couplings`] for all of them.
    pub fn coupling(&self) -> Option<&JointCoupling> {
        self.couplings.first()
    }

    /// Every coupling: one per mimic joint of the chain (resolved to its
    /// independent leader), then the additive ones (the gantry's beam).
    pub fn couplings(&self) -> &[JointCoupling] {
        &self.couplings
    }

    /// True when some chain joint is a mimic joint (the chain has more
    /// joints than the configuration).
    pub fn has_mimic_joints(&self) -> bool {
        self.couplings
            .iter()
            .any(|c| matches!(c.law, CouplingLaw::Mimic { .. }))
    }

    #[inline]
    pub(crate) fn joint_map(&self) -> &JointMap {
        &self.map
    }

    /// The form of each [`Model::joint_placements`] entry (decided at build).
    #[inline]
    pub(crate) fn placement_forms(&self) -> &[PlacementForm] {
        &self.placement_forms
    }

    /// The form of [`Model::end_effector_placement`].
    #[inline]
    pub(crate) fn end_effector_form(&self) -> &PlacementForm {
        &self.tail_form
    }

    /// The kind of each chain joint ([`Model::chain_joints`]), packed.
    #[inline]
    pub(crate) fn chain_kinds(&self) -> &[JointKind] {
        &self.chain_kinds
    }

    /// The chain joints' positions (one per [`Model::chain_joints`]) for the
    /// configuration `q`: mimic joints from their leaders, additive
    /// couplings added (what forward kinematics evaluates the chain at).
    /// Errors: `q` or `chain_positions` of the wrong size, `q` not finite.
    /// Allocates nothing.
    pub fn chain_positions(&self, q: &[f64], chain_positions: &mut [f64]) -> Result<()> {
        self.check_joint_positions(q)?;
        if chain_positions.len() != self.chain_joints.len() {
            return Err(Error::DimensionMismatch {
                what: "chain_positions",
                expected: self.chain_joints.len(),
                got: chain_positions.len(),
            });
        }
        self.map.expand(q, chain_positions);
        Ok(())
    }

    /// Generalized forces on the chain's joints (`chain_forces`, N m or N,
    /// one per chain joint) as forces on the configuration: `tau = M' tau0`,
    /// `M = d q_chain / d q` at `q` (a mimic joint's torque goes to its
    /// leader times the multiplier; seed 000 eq 10 for the beam). Errors:
    /// wrong sizes, non-finite values. Allocates nothing.
    pub fn fold_chain_forces(
        &self,
        q: &[f64],
        chain_forces: &[f64],
        forces: &mut [f64],
    ) -> Result<()> {
        self.check_joint_positions(q)?;
        check_finite_vector("chain_forces", chain_forces, self.chain_joints.len())?;
        if forces.len() != self.dof() {
            return Err(Error::DimensionMismatch {
                what: "forces",
                expected: self.dof(),
                got: forces.len(),
            });
        }
        self.map.fold_forces(q, chain_forces, forces);
        Ok(())
    }

    /// The DH table the model was built from, if it was built from one.
    pub fn dh_table(&self) -> Option<(DhConvention, &[DhLink])> {
        self.dh.as_ref().map(|(c, links)| (*c, links.as_slice()))
    }

    /// A copy of this model with its additive coupling replaced by
    /// `coupling` (or removed with `None`); mimic joints stay. See
    /// [`Model::with_additive_couplings`].
    pub fn with_coupling(&self, coupling: Option<JointCoupling>) -> Result<Model> {
        self.with_additive_couplings(coupling.into_iter().collect())
    }

    /// A copy of this model whose additive couplings
    /// ([`CouplingLaw::Additive`]) are `couplings`; mimic joints stay.
    /// Errors (field `coupling`): a mimic law (declare mimic joints with
    /// [`ModelBuilder::mimic`]), indices out of range, a target that is a
    /// mimic joint, not prismatic, or its own source, a target that is the
    /// source of another coupling, a curve whose parameters are invalid.
    pub fn with_additive_couplings(&self, couplings: Vec<JointCoupling>) -> Result<Model> {
        let mut additive = Vec::with_capacity(couplings.len());
        for coupling in &couplings {
            let prismatic = self
                .chain_joints
                .get(coupling.target)
                .is_some_and(|j| j.kind == JointKind::Prismatic);
            additive.push(coupling::check_additive(
                coupling,
                self.dof(),
                &self.map,
                prismatic,
            )?);
        }
        // The Jacobian folds additive columns in place: a target must not
        // be another coupling's source (its column would already be folded).
        for (_, target, _) in &additive {
            if let crate::model::coupling::Drive::Independent(i) = self.map.drive(*target) {
                if additive.iter().any(|(source, ..)| *source == i) {
                    return Err(Error::invalid_argument(
                        "coupling",
                        format!("joint {target} is the target of one coupling and the source of another"),
                    ));
                }
            }
        }
        let mut model = self.clone();
        model.map = self.map.with_additive(additive);
        model
            .couplings
            .retain(|c| matches!(c.law, CouplingLaw::Mimic { .. }));
        model.couplings.extend(couplings);
        Ok(model)
    }

    /// A copy of this model under a new name.
    pub fn renamed(&self, name: impl Into<String>) -> Model {
        let mut model = self.clone();
        model.name = name.into();
        model
    }

    /// Checks that `q` has one finite value per joint.
    #[inline]
    pub fn check_joint_positions(&self, q: &[f64]) -> Result<()> {
        check_finite_vector("joint_positions", q, self.dof())
    }

    /// Checks size and finiteness, then that every joint position lies within
    /// its limits; the error names the first joint outside.
    pub fn check_limits(&self, q: &[f64]) -> Result<()> {
        self.check_joint_positions(q)?;
        for (j, (joint, &value)) in self.joints.iter().zip(q).enumerate() {
            if !joint.limits.contains(value) {
                return Err(Error::OutOfLimits {
                    joint: j,
                    name: joint.name.clone(),
                    value,
                    lower: joint.limits.lower,
                    upper: joint.limits.upper,
                });
            }
        }
        Ok(())
    }

    /// The mid-range configuration (0 for joints without finite limits).
    pub fn neutral_configuration(&self) -> Vec<f64> {
        self.joints.iter().map(|j| j.limits.midpoint()).collect()
    }

    /// Lower and upper position limits as two vectors.
    pub fn position_limits(&self) -> (Vec<f64>, Vec<f64>) {
        (
            self.joints.iter().map(|j| j.limits.lower).collect(),
            self.joints.iter().map(|j| j.limits.upper).collect(),
        )
    }

    /// Velocity limits, one per joint, or `None` if any joint has none.
    pub fn velocity_limits(&self) -> Option<Vec<f64>> {
        self.joints.iter().map(|j| j.limits.velocity).collect()
    }

    /// True when every link of the chain has mass properties.
    pub fn has_inertias(&self) -> bool {
        self.chain_joints.iter().all(|j| j.inertia.is_some())
    }
}
