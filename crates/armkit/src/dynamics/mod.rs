//! Rigid-body dynamics of a serial chain (issue 18): inverse dynamics
//! (RNEA), the joint-space inertia matrix (CRBA) and its inverse, gravity and
//! Coriolis torques, forward dynamics (ABA, O(n)), kinetic and potential
//! energy, and a simulation step.
//!
//! The algorithms are Featherstone's (*Rigid Body Dynamics Algorithms*,
//! 2008: RNEA table 5.1, CRBA table 6.2, ABA table 7.1), written with every
//! spatial quantity in the **world frame**, about the world origin. Forward
//! kinematics ([`crate::kinematics::forward_kinematics`]) gives each joint's
//! world frame, in which the model folds every joint into "a fixed placement,
//! then motion about local z": the joint's motion subspace is then
//! `S = (z, p x z)` for a rotational joint and `(0, z)` for a prismatic one
//! (`z` its axis, `p` its origin, world frame), and bodies' inertias add up
//! without any transform. Each link's [`crate::model::LinkInertia`] is given
//! in its joint's frame.
//!
//! Conventions, as in Pinocchio and the Robotics Toolbox:
//! * `q`, `v`, `a` (joint positions, velocities, accelerations) in rad, rad/s,
//!   rad/s^2 (m, m/s, m/s^2 for prismatic joints), torques `tau` in N m (N);
//! * `M(q) a + C(q, v) v + g(q) = tau`, `g(q) = RNEA(q, 0, 0)` the torques
//!   that hold the arm still (the gradient of the potential energy);
//! * gravity is a world-frame acceleration, by default `(0, 0, -9.81)` m/s^2
//!   ([`DEFAULT_GRAVITY`], set with [`DynamicsData::set_gravity`]).
//!
//! A model whose links lack mass properties is refused, naming the first
//! such link. A model with a joint coupling (`gantry9-flex`'s beam
//! deflection `d3' = d3 + w(d2)`) is refused too: the coupling would have to
//! enter through its Jacobian and its second derivative, which these
//! algorithms do not include; use the rigid `gantry9`.
//!
//! All algorithms allocate nothing after [`DynamicsData::new`].
//!
//! ```
//! use armkit::dynamics::{aba, mass_matrix, rnea, DynamicsData};
//! let model = armkit::robots::by_name("space6r").unwrap();
//! let mut data = DynamicsData::new(&model).unwrap();
//! let q = [0.1, -0.4, 0.8, 0.2, 0.5, -0.3];
//! let v = [0.2, 0.1, -0.3, 0.4, 0.0, 0.1];
//! let a = [1.0, -0.5, 0.3, 0.0, 0.2, 0.1];
//! let tau = rnea(&model, &mut data, &q, &v, &a).unwrap().to_vec();
//! // Forward dynamics undoes inverse dynamics.
//! let ddq = aba(&model, &mut data, &q, &v, &tau).unwrap();
//! assert!(ddq.iter().zip(&a).all(|(x, y)| (x - y).abs() < 1e-9));
//! let m = mass_matrix(&model, &mut data, &q).unwrap();
//! assert!((m - m.transpose()).amax() < 1e-12);
//! ```

mod algorithms;
mod energy;
pub mod energy_weights;
pub mod simulate;
pub mod spatial;
pub mod torque_limits;

pub use algorithms::{
    aba, coriolis_torques, gravity_torques, mass_matrix, mass_matrix_inverse, nonlinear_effects,
    rnea,
};
pub use energy::{kinetic_energy, potential_energy};

use crate::error::{check_finite, Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::math::{DMatrix, Vector3, Vector6};
use crate::model::{LinkInertia, Model};
use spatial::{Force, Motion, SpatialInertia};

/// Standard gravity in the world frame, m/s^2: `(0, 0, -9.81)`, as
/// Pinocchio and the Robotics Toolbox use.
pub const DEFAULT_GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

/// Workspace for the dynamics algorithms, sized once for one model.
///
/// Holds the gravity vector, the kinematics workspace and every per-body
/// buffer, and the results of the last call of each algorithm. Create it
/// once per model and thread with [`DynamicsData::new`], which also checks
/// that the model has mass properties and no coupling.
#[derive(Clone, Debug)]
pub struct DynamicsData {
    dof: usize,
    gravity: Vector3<f64>,
    kinematics: Data,
    /// Motion subspace of each joint, world frame.
    axes: Vec<Motion>,
    /// Each body's spatial inertia, world frame.
    bodies: Vec<SpatialInertia>,
    velocities: Vec<Motion>,
    /// RNEA: body accelerations; ABA: velocity-product accelerations `v x S qd`.
    accelerations: Vec<Motion>,
    forces: Vec<Force>,
    composite: Vec<SpatialInertia>,
    /// ABA: `U_j = IA_j S_j`.
    u_columns: Vec<Vector6<f64>>,
    /// ABA: `D_j = S_j' U_j`.
    d_values: Vec<f64>,
    /// ABA: `u_j = tau_j - S_j' pA_j`.
    u_values: Vec<f64>,
    zeros: Vec<f64>,
    tau: Vec<f64>,
    ddq: Vec<f64>,
    mass_matrix: DMatrix<f64>,
    mass_matrix_inverse: DMatrix<f64>,
}

impl DynamicsData {
    /// A workspace for `model`, with gravity [`DEFAULT_GRAVITY`].
    ///
    /// Errors: a link without mass properties (the first one is named), or a
    /// model with a joint coupling (see the module documentation).
    pub fn new(model: &Model) -> Result<Self> {
        check_dynamics_model(model)?;
        let n = model.dof();
        Ok(DynamicsData {
            dof: n,
            gravity: DEFAULT_GRAVITY,
            kinematics: Data::new(model),
            axes: vec![Motion::ZERO; n],
            bodies: vec![SpatialInertia::ZERO; n],
            velocities: vec![Motion::ZERO; n],
            accelerations: vec![Motion::ZERO; n],
            forces: vec![Force::ZERO; n],
            composite: vec![SpatialInertia::ZERO; n],
            u_columns: vec![Vector6::zeros(); n],
            d_values: vec![0.0; n],
            u_values: vec![0.0; n],
            zeros: vec![0.0; n],
            tau: vec![0.0; n],
            ddq: vec![0.0; n],
            mass_matrix: DMatrix::zeros(n, n),
            mass_matrix_inverse: DMatrix::zeros(n, n),
        })
    }

    /// The gravitational acceleration, world frame, m/s^2.
    pub fn gravity(&self) -> &Vector3<f64> {
        &self.gravity
    }

    /// Sets the gravitational acceleration (world frame, m/s^2; zero for
    /// none). Error: a non-finite component.
    pub fn set_gravity(&mut self, gravity: Vector3<f64>) -> Result<()> {
        check_finite("gravity", gravity.as_slice())?;
        self.gravity = gravity;
        Ok(())
    }

    /// This workspace with gravity `gravity` (see [`DynamicsData::set_gravity`]).
    pub fn with_gravity(mut self, gravity: Vector3<f64>) -> Result<Self> {
        self.set_gravity(gravity)?;
        Ok(self)
    }

    /// The kinematics workspace, holding the forward kinematics of the last
    /// call (joint frames, end-effector pose).
    pub fn kinematics(&self) -> &Data {
        &self.kinematics
    }

    /// Each body's spatial velocity from the last [`rnea`], [`aba`] or
    /// [`kinetic_energy`] call, world frame, about the world origin.
    pub fn body_velocities(&self) -> &[Motion] {
        &self.velocities
    }

    /// The joint torques of the last [`rnea`], [`gravity_torques`],
    /// [`coriolis_torques`] or [`nonlinear_effects`] call (N m or N).
    pub fn torques(&self) -> &[f64] {
        &self.tau
    }

    /// The joint accelerations of the last [`aba`] call.
    pub fn accelerations(&self) -> &[f64] {
        &self.ddq
    }

    /// The mass matrix of the last [`mass_matrix`] call (n x n, kg m^2,
    /// kg for prismatic rows and columns).
    pub fn mass_matrix(&self) -> &DMatrix<f64> {
        &self.mass_matrix
    }

    fn check_model(&self, model: &Model) -> Result<()> {
        if self.dof != model.dof() {
            return Err(Error::DimensionMismatch {
                what: "dynamics data (workspace made for another model)",
                expected: model.dof(),
                got: self.dof,
            });
        }
        if model.coupling().is_some() {
            return Err(coupling_error(model));
        }
        Ok(())
    }

    /// Forward kinematics at `q`, then each joint's motion subspace and each
    /// body's inertia in the world frame.
    fn update_bodies(&mut self, model: &Model, q: &[f64]) -> Result<()> {
        self.check_model(model)?;
        forward_kinematics(model, &mut self.kinematics, q)?;
        let frames = self.kinematics.joint_frames();
        for (link, ((joint, frame), (axis, body))) in model
            .joints()
            .iter()
            .zip(frames)
            .zip(self.axes.iter_mut().zip(self.bodies.iter_mut()))
            .enumerate()
        {
            let z: Vector3<f64> = frame.rotation.column(2).into_owned();
            *axis = if joint.kind.is_rotational() {
                Motion::new(z, frame.translation.cross(&z))
            } else {
                Motion::new(Vector3::zeros(), z)
            };
            let inertia = link_inertia(model, link, joint.inertia.as_ref())?;
            *body = SpatialInertia::from_link(inertia, frame);
        }
        Ok(())
    }
}

fn link_inertia<'m>(
    model: &Model,
    link: usize,
    inertia: Option<&'m LinkInertia>,
) -> Result<&'m LinkInertia> {
    inertia.ok_or_else(|| Error::InvalidModel {
        link,
        name: model.joints()[link].name.clone(),
        field: "mass".into(),
        reason: format!(
            "model `{}` has no mass properties for this link: dynamics needs every link's \
             mass, centre of mass and inertia (DH files: `mass`, `com`, `inertia`; URDF: \
             <inertial>)",
            model.name()
        ),
    })
}

fn coupling_error(model: &Model) -> Error {
    Error::InvalidModelStructure {
        model: model.name().to_string(),
        reason: "the model has a joint coupling (e.g. gantry9-flex's beam deflection): \
                 armkit's dynamics does not include couplings; use the rigid model \
                 (gantry9) instead"
            .into(),
    }
}

/// Checks that `model` can go through the dynamics algorithms: every link
/// has mass properties (the error names the first that has none) and there is
/// no joint coupling.
pub fn check_dynamics_model(model: &Model) -> Result<()> {
    if model.coupling().is_some() {
        return Err(coupling_error(model));
    }
    for (link, joint) in model.joints().iter().enumerate() {
        link_inertia(model, link, joint.inertia.as_ref())?;
    }
    Ok(())
}
