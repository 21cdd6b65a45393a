//! Free-floating space manipulators: the generalized Jacobian, a
//! momentum-conserving simulation and resolved-rate tracking (seed 004, sec 1).
//!
//! A spacecraft (the *base*, body 0) carries a serial arm (bodies 1..n). No
//! external force acts, so when the arm moves the base moves too: the
//! end-effector velocity depends on every body's mass. Two base modes
//! ([`BaseMode`]):
//!
//! * [`BaseMode::AttitudeHeld`] (seed 004): the attitude control system
//!   holds the base orientation (`w0 = 0`); the base translates so that the
//!   linear momentum stays zero.
//! * [`BaseMode::FreeFloating`] (Umetani and Yoshida 1989): no actuator on the
//!   base at all; linear and angular momentum both stay zero.
//!
//! In both, the end-effector twist in the inertial frame is
//! `[v_e; w_e] = J* q_dot` with the 6 x n generalized Jacobian `J*`
//! ([`generalized_jacobian`]).
//!
//! # Derivation (seed 004, eqs 1-19; the extraction lost the formulas)
//!
//! The equation numbers are the seed's, placed from its surviving text (what
//! each equation defines and what it is substituted into); the formulas are
//! derived here.
//!
//! Notation, all vectors in the inertial frame: `p0`, `R0` the base frame's
//! origin and orientation; `r_i` the centre of mass of body i (`r_0` the
//! base's), `m_i` its mass, `I_i` its inertia about `r_i` in inertial axes;
//! `p_j`, `k_j` the origin and unit axis of joint j; `p_e` the end-effector
//! origin; `M = sum m_i` (eq 9) and `r_g = sum m_i r_i / M` (eq 10);
//! `[a]x` the cross-product matrix (eqs 1-2).
//!
//! * Velocities (eqs 3-5). With `v0`, `w0` the base frame's linear and angular
//!   velocity, body i (i >= 1) moves with
//!   `v_i = v0 + w0 x (r_i - p0) + sum_{j <= i} k_j x (r_i - p_j) q_dot_j` and
//!   `w_i = w0 + sum_{j <= i} k_j q_dot_j` (a prismatic joint contributes
//!   `k_j q_dot_j` to `v_i` and nothing to `w_i`), and the end effector with
//!   `[v_e; w_e] = J_b [v0; w0] + J_m q_dot` (eq 6), where `J_m` is the
//!   fixed-base geometric Jacobian (in inertial axes) and
//!   `J_b = [E, -[p_e - p0]x; 0, E]`.
//! * Linear momentum (eqs 7-14). Summing `m_i v_i`:
//!   `P = M v0 + M w0 x (r_g - p0) + M J_g q_dot`, where
//!   `J_g = d r_g / d q` with the base held still: column j is
//!   `k_j x (sum_{i >= j} m_i (r_i - p_j)) / M` (revolute) or
//!   `k_j (sum_{i >= j} m_i) / M` (prismatic). This is the seed's `J_Tw / M`.
//! * Attitude held (eqs 15-17). With `w0 = 0` and `P = 0`:
//!   `v0 = -J_g q_dot` (eq 16) and
//!   `J* = [J_v - J_g; J_w]` (eq 17): the end effector moves relative to a
//!   centre of mass that stays put. This mode has no use for the inertias.
//!   Holding the attitude takes a torque on the base (thrusters, or reaction
//!   wheels whose momentum we do not model): the angular momentum of base and
//!   arm is not conserved in this mode.
//! * Fully free (Umetani-Yoshida). The angular momentum about `r_g` is
//!   `L = H_w w0 + H_wq q_dot` (the `v0` term vanishes because
//!   `sum m_i (r_i - r_g) = 0`), with the system's inertia about its centre of
//!   mass `H_w = sum_i (I_i - m_i [d_i]x [d_i]x)`, `d_i = r_i - r_g`, and
//!   column j of `H_wq` equal to `S_j k_j + s_j x (k_j x (r_g - p_j))`
//!   (revolute) or `s_j x k_j` (prismatic), where
//!   `S_j = sum_{i >= j} (I_i - m_i [d_i]x [d_i]x)` and
//!   `s_j = sum_{i >= j} m_i d_i`. `L = 0` gives `w0 = -H_w^-1 H_wq q_dot`,
//!   `P = 0` gives `v0 = (r_g - p0) x w0 - J_g q_dot`, and
//!   `J* = [J_v - J_g - [p_e - r_g]x B_w; J_w + B_w]` with
//!   `B_w = -H_w^-1 H_wq`.
//!
//! Both are computed in O(n) from suffix sums, after one forward kinematics;
//! [`SpaceData::base_jacobian`] gives the base twist per joint rate. The seed's
//! eqs 18-19 (the virtual-manipulator form) express the same `J*`; we do not
//! need them.
//!
//! # Simulation
//!
//! [`step`] advances `(base pose, q)` over `dt` with joint rates held constant.
//! Zero linear momentum is holonomic (the system's centre of mass is fixed), so
//! the base position is not integrated: it is solved from the centre-of-mass
//! condition after each step, which keeps the centre of mass fixed to
//! round-off whatever the step. In the free mode the base attitude follows
//! the non-holonomic `L = 0`: its body-frame angular velocity depends only on
//! `q`, and is integrated with the fourth-order Magnus (Gauss-Legendre) scheme
//! on SO(3) through the exponential map.
//!
//! # Relation to the rigid-body dynamics ([`crate::dynamics`])
//!
//! [`momentum`] is computed with the dynamics module's spatial algebra
//! (each body's spatial velocity and inertia, `sum I_i V_i`). The time
//! stepping does not use [`crate::dynamics::simulate::Simulator`], for three
//! reasons that are properties of the two problems, not of the code:
//!
//! * [`step`] is *kinematic*, as seed 004 is: the joint rates are the input
//!   and the base follows from the momentum conditions, so there is no
//!   torque and no joint acceleration to integrate. The simulator integrates
//!   `ddq = ABA(q, v, tau)` from joint torques.
//! * The simulator's chain has a fixed base (its [`Model`]'s base pose is a
//!   constant, its state `(q, v)` a vector in R^n). A torque-driven
//!   free-floating system needs a six-degree-of-freedom floating root joint
//!   in the articulated-body recursion (Featherstone, ch. 9, floating bases:
//!   the base's articulated inertia solved as a 6 x 6 system) and a state on
//!   SE(3) x R^n with a Lie-group integrator; in the attitude-held mode also
//!   the attitude controller's torque on the base. None of this exists in
//!   `dynamics`.
//! * Here zero linear momentum is imposed exactly (the base position is
//!   solved from the fixed centre of mass), which the demo's seed004-space
//!   checks rely on (centre-of-mass drift at round-off); integrating forces
//!   would only keep it to the integrator's accuracy.
//!
//! # Velocity-level use
//!
//! Because the base moves, inverse kinematics and path tracking on this system
//! run at velocity level with `J*`: [`track_pose_path`] is a resolved-rate
//! tracker of a Cartesian pose path `t -> Pose` (seed 004, eqs 20-28); the
//! singularity-avoidance work builds on [`generalized_jacobian`], [`step`]
//! and [`end_effector_pose`].
//!
//! ```
//! use armkit::robots::space6r_free_floating;
//! use armkit::space::{
//!     center_of_mass, end_effector_pose, generalized_jacobian, step, BaseMode, FreeFloatingState,
//!     SpaceData,
//! };
//! use armkit::math::{Matrix3, Pose};
//! let model = space6r_free_floating().unwrap();
//! let mut data = SpaceData::new(&model);
//! let mut state = FreeFloatingState::new(Pose::identity(), vec![0.1, 0.5, -0.4, 0.2, 0.6, 0.0]);
//! let mode = BaseMode::FreeFloating;
//! let j_star = generalized_jacobian(&model, &mut data, &state.base, &state.q, mode).unwrap();
//! assert_eq!(j_star.shape(), (6, 6));
//! let com = center_of_mass(&model, &mut data, &state.base, &state.q).unwrap();
//! for _ in 0..100 {
//!     step(&model, &mut data, &mut state, &[0.1, -0.2, 0.1, 0.3, 0.0, 0.2], 0.01, mode).unwrap();
//! }
//! // The base has moved and turned, the system's centre of mass has not.
//! assert!(state.base.translation.norm() > 1e-4);
//! assert!((state.base.rotation - Matrix3::identity()).amax() > 1e-5);
//! let com_after = center_of_mass(&model, &mut data, &state.base, &state.q).unwrap();
//! assert!((com_after - com).norm() < 1e-12);
//! let _tip = end_effector_pose(&model, &mut data, &state.base, &state.q).unwrap();
//! ```

mod dynamics;
mod simulate;
mod tracking;

pub use dynamics::{center_of_mass, end_effector_pose, generalized_jacobian, momentum, Momentum};
pub use simulate::{step, step_integrated, SinusoidalJointMotion};
pub use tracking::{track_pose_path, FloatingBase};

use nalgebra::Matrix3xX;

use crate::error::{Error, Result};
use crate::kinematics::Data;
use crate::math::{Matrix3, Matrix6xX, Pose, Vector3};
use crate::model::{LinkInertia, Model};

/// What the base of a free-floating system does while the arm moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BaseMode {
    /// The base attitude is held by the spacecraft's attitude control
    /// (`w0 = 0`, seed 004 eq 15); zero linear momentum moves the base.
    AttitudeHeld,
    /// Nothing acts on the base: linear and angular momentum both stay zero
    /// (Umetani and Yoshida's generalized Jacobian).
    FreeFloating,
}

/// The spacecraft body carrying the arm.
///
/// Frame: the *base frame*, whose pose in the inertial frame is the state's
/// base pose ([`FreeFloatingState::base`]).
#[derive(Clone, Debug, PartialEq)]
pub struct BaseBody {
    /// Name used in error messages.
    pub name: String,
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Centre of mass in the base frame, m.
    pub com: Vector3<f64>,
    /// Inertia tensor about the centre of mass, in base-frame axes, kg m^2
    /// (symmetric positive definite).
    pub inertia: Matrix3<f64>,
    /// Placement of the arm's mount in the base frame: the frame in which the
    /// arm [`Model`] gives its own base transform (its "world" frame).
    pub mount: Pose,
}

impl BaseBody {
    /// Checks mass (finite, > 0), centre of mass (finite), inertia (finite,
    /// symmetric, positive definite) and mount (finite, proper rotation). The
    /// error names the body and the field.
    pub fn validate(&self) -> Result<()> {
        let invalid = |field: &str, reason: String| Error::InvalidModelStructure {
            model: self.name.clone(),
            reason: format!("base body, field `{field}`: {reason}"),
        };
        if !(self.mass.is_finite() && self.mass > 0.0) {
            return Err(invalid(
                "mass",
                format!("must be finite and > 0 kg, got {}", self.mass),
            ));
        }
        if !self.com.iter().all(|v| v.is_finite()) {
            return Err(invalid(
                "com",
                format!("must be finite, got {:?}", self.com.as_slice()),
            ));
        }
        if !self.inertia.iter().all(|v| v.is_finite()) {
            return Err(invalid("inertia", "must be finite".into()));
        }
        let scale = self.inertia.amax();
        let asymmetry = (self.inertia - self.inertia.transpose()).amax();
        if asymmetry > 1e-9 * scale.max(1.0) {
            return Err(invalid(
                "inertia",
                format!("must be symmetric (largest asymmetry {asymmetry:e} kg m^2)"),
            ));
        }
        let smallest = self.inertia.symmetric_eigenvalues().min();
        if !(smallest > 1e-12 * scale && scale > 0.0) {
            return Err(invalid(
                "inertia",
                format!(
                    "must be positive definite (smallest eigenvalue {smallest:e} kg m^2): a rigid body has three positive principal moments"
                ),
            ));
        }
        check_pose(&self.mount).map_err(|reason| invalid("mount", reason))
    }
}

/// Checks that a pose is finite with a proper rotation ([`Pose::check_rigid`]);
/// the error string says what is wrong.
fn check_pose(pose: &Pose) -> std::result::Result<(), String> {
    pose.check_rigid()
}

/// A base body carrying a serial arm whose every link has mass properties.
///
/// Immutable once built, like [`Model`]; pair it with a [`SpaceData`]
/// workspace.
#[derive(Clone, Debug)]
pub struct FreeFloatingModel {
    base: BaseBody,
    arm: Model,
    links: Vec<LinkInertia>,
    total_mass: f64,
}

impl FreeFloatingModel {
    /// Builds the system after checking the base body ([`BaseBody::validate`])
    /// and that every link of `arm` has mass properties (the model builder has
    /// already checked their values). Arms with a joint coupling are refused:
    /// the coupling's effect on the mass distribution is not modelled.
    pub fn new(base: BaseBody, arm: Model) -> Result<Self> {
        base.validate()?;
        if arm.dof() == 0 {
            return Err(Error::InvalidModelStructure {
                model: arm.name().to_string(),
                reason: "a free-floating system needs an arm with at least one joint".into(),
            });
        }
        if arm.coupling().is_some() {
            return Err(Error::InvalidModelStructure {
                model: arm.name().to_string(),
                reason: "joint couplings are not supported on a free-floating base".into(),
            });
        }
        let mut links = Vec::with_capacity(arm.dof());
        for (j, joint) in arm.joints().iter().enumerate() {
            match joint.inertia {
                Some(inertia) => links.push(inertia),
                None => {
                    return Err(Error::InvalidModel {
                        link: j,
                        name: joint.name.clone(),
                        field: "inertia".into(),
                        reason: "no mass properties: a free-floating system needs the mass, \
                                 centre of mass and inertia of every link"
                            .into(),
                    })
                }
            }
        }
        let total_mass = base.mass + links.iter().map(|l| l.mass).sum::<f64>();
        Ok(FreeFloatingModel {
            base,
            arm,
            links,
            total_mass,
        })
    }

    /// The base body.
    pub fn base(&self) -> &BaseBody {
        &self.base
    }

    /// The arm (its world frame is the base body's mount frame).
    pub fn arm(&self) -> &Model {
        &self.arm
    }

    /// Number of arm joints.
    pub fn dof(&self) -> usize {
        self.arm.dof()
    }

    /// Mass properties of each link, in its joint frame (see [`LinkInertia`]).
    pub fn link_inertias(&self) -> &[LinkInertia] {
        &self.links
    }

    /// Mass of the whole system (base and links), kg.
    pub fn total_mass(&self) -> f64 {
        self.total_mass
    }

    /// A copy with the base body replaced (validated as in [`Self::new`]).
    pub fn with_base(&self, base: BaseBody) -> Result<Self> {
        Self::new(base, self.arm.clone())
    }
}

/// The state of a free-floating system: base pose and joint positions.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeFloatingState {
    /// Pose of the base frame in the inertial frame (m).
    pub base: Pose,
    /// Joint positions, rad or m, one per arm joint.
    pub q: Vec<f64>,
}

impl FreeFloatingState {
    /// A state from a base pose (inertial frame) and joint positions.
    pub fn new(base: Pose, q: Vec<f64>) -> Self {
        FreeFloatingState { base, q }
    }
}

/// Workspace for the free-floating algorithms, sized once for one model.
///
/// Holds the results of the last call, all in the inertial frame.
#[derive(Clone, Debug)]
pub struct SpaceData {
    dof: usize,
    arm: Data,
    joint_origins: Vec<Vector3<f64>>,
    joint_axes: Vec<Vector3<f64>>,
    link_coms: Vec<Vector3<f64>>,
    link_rotations: Vec<Matrix3<f64>>,
    base_pose: Pose,
    base_com: Vector3<f64>,
    com: Vector3<f64>,
    end_effector: Pose,
    jacobian: Matrix6xX<f64>,
    base_jacobian: Matrix6xX<f64>,
    com_jacobian: Matrix3xX<f64>,
    momentum_jacobian: Matrix3xX<f64>,
    system_inertia: Matrix3<f64>,
    q_node: Vec<f64>,
}

impl SpaceData {
    /// A workspace for `model`.
    pub fn new(model: &FreeFloatingModel) -> Self {
        let n = model.dof();
        SpaceData {
            dof: n,
            arm: Data::new(&model.arm),
            joint_origins: vec![Vector3::zeros(); n],
            joint_axes: vec![Vector3::zeros(); n],
            link_coms: vec![Vector3::zeros(); n],
            link_rotations: vec![Matrix3::identity(); n],
            base_pose: Pose::identity(),
            base_com: Vector3::zeros(),
            com: Vector3::zeros(),
            end_effector: Pose::identity(),
            jacobian: Matrix6xX::zeros(n),
            base_jacobian: Matrix6xX::zeros(n),
            com_jacobian: Matrix3xX::zeros(n),
            momentum_jacobian: Matrix3xX::zeros(n),
            system_inertia: Matrix3::zeros(),
            q_node: vec![0.0; n],
        }
    }

    /// The generalized Jacobian `J*` (6 x n, rows `[v; w]` of the end-effector
    /// origin, inertial frame) from the last [`generalized_jacobian`].
    pub fn jacobian(&self) -> &Matrix6xX<f64> {
        &self.jacobian
    }

    /// The base twist per joint rate (6 x n): `[v0; w0] = base_jacobian q_dot`,
    /// `v0` the velocity of the base frame's origin (m/s), `w0` the base angular
    /// velocity (rad/s), inertial frame; from the last [`generalized_jacobian`].
    pub fn base_jacobian(&self) -> &Matrix6xX<f64> {
        &self.base_jacobian
    }

    /// `J_g = d r_g / d q` with the base held still (3 x n, m per rad or m per
    /// m, inertial frame): seed 004's `J_Tw / M`. From the last
    /// [`generalized_jacobian`].
    pub fn com_jacobian(&self) -> &Matrix3xX<f64> {
        &self.com_jacobian
    }

    /// Centre of mass of the whole system (m, inertial frame) at the last
    /// evaluated state.
    pub fn center_of_mass(&self) -> &Vector3<f64> {
        &self.com
    }

    /// End-effector pose (inertial frame) at the last evaluated state.
    pub fn end_effector_pose(&self) -> &Pose {
        &self.end_effector
    }

    /// The arm's kinematics workspace from the last evaluation: its joint
    /// frames ([`Data::joint_frames`]) and end-effector pose are in the mount
    /// frame (the arm model's world frame), not the inertial frame.
    pub fn arm_data(&self) -> &Data {
        &self.arm
    }

    /// Moves every cached position by `shift` (m, inertial frame): the
    /// kinematics of the same configuration with the base translated.
    fn translate(&mut self, shift: &Vector3<f64>) {
        for p in self
            .joint_origins
            .iter_mut()
            .chain(self.link_coms.iter_mut())
        {
            *p += shift;
        }
        self.base_pose.translation += shift;
        self.base_com += shift;
        self.com += shift;
        self.end_effector.translation += shift;
    }

    fn check_model(&self, model: &FreeFloatingModel) -> Result<()> {
        if self.dof != model.dof() {
            return Err(Error::DimensionMismatch {
                what: "data (workspace made for another model)",
                expected: model.dof(),
                got: self.dof,
            });
        }
        Ok(())
    }
}
