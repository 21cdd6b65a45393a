//! Rigid-body dynamics of a serial chain: inverse dynamics
//! (RNEA), the joint-space inertia matrix (CRBA) and its inverse, gravity and
//! Coriolis torques, forward dynamics (ABA, O(n)), kinetic and potential
//! energy, and a simulation step.
//!
//! The algorithms are Featherstone's (*Rigid Body Dynamics Algorithms*,
//! 2008: RNEA table 5.1, CRBA table 6.2, ABA table 7.1). The model folds
//! every joint into "a fixed placement, then motion about local z", so in a
//! joint's own frame its motion subspace is the constant `S = (e_z, 0)`
//! (rotational) or `(0, e_z)` (prismatic), and each link's
//! [`crate::model::LinkInertia`], given in that frame, is a constant spatial
//! inertia (computed once, in [`DynamicsData::new`]).
//!
//! * The RNEA and the CRBA run in these **body frames**: one transform per
//!   joint, `X_i` = the joint's placement turned by `Rz(q_i)` (or shifted by
//!   `Tz(q_i)`), carries velocities and accelerations outwards and forces
//!   and composite inertias inwards (on the 3 x 3 blocks, see
//!   [`spatial`]); the products with `S` pick one component. No world pose
//!   is formed. The CRBA's `M[i][j]` (`i < j`) is the `S_i` component of
//!   `Ic_j S_j` carried inwards from frame `j` to frame `i`, in one pass from
//!   the tip: each level carries the composite inertia and every column
//!   beyond it through its one transform, and the base row is read in frame
//!   1 against `S_0` seen from there, so no frame-0 composite is formed.
//! * The ABA runs in the **world frame** (world poses from the same joint
//!   transforms), where the articulated inertias of parent and child add
//!   without a 6 x 6 transform: `S = (z, p x z)` or `(0, z)` there (`z` the
//!   joint axis, `p` its origin).
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
//! such link. A massless link (zero mass and inertia, as a URDF link without
//! `<inertial>` between two joints) is fine: inverse dynamics, the mass
//! matrix, gravity and Coriolis torques are defined whatever the masses.
//!
//! **Forward dynamics** ([`aba`], and [`mass_matrix_inverse`]) needs `M(q)`
//! positive definite, which it is not when some joint moves bodies without
//! inertia about its axis (a point mass on the axis, a massless tip).
//! Whether `M` is singular is decided the same way at every configuration:
//! a pivot of its factorization at or below [`MASS_MATRIX_THRESHOLD`] times
//! `M`'s largest diagonal entry is an [`Error::Numerical`] naming the joint,
//! never accelerations. Rounding alone leaves a pivot of an exactly
//! singular `M` some 1e-16 of that scale, of either sign.
//!
//! **Coupled models** (mimic joints, and `gantry9-flex`'s beam
//! deflection `d3' = d3 + w(d2)`, seed 000 eq 4) work in the independent
//! joints. The algorithms run on the chain's joints at the chain
//! configuration `q_c = c(q)` ([`Model::chain_positions`]) with
//! `qd_c = M qd` and `qdd_c = M qdd + Md qd`, `M = d q_c / d q` (seed 000,
//! eqs 8-10): `Md qd` is zero for a mimic joint and `f''(q_s) qd_s^2` on the
//! target of an additive curve `f` (its
//! [`crate::model::CouplingCurve::second_derivative`]). Torques fold back as
//! `tau = M' tau_c` (the principle of virtual work), the mass matrix as
//! `M' H_c M`, gravity and Coriolis torques as `M' g_c` and
//! `M' (C_c qd_c + H_c Md qd)`. Forward dynamics of a coupled model solves
//! `(M' H_c M) qdd = tau - M'(C + g)` by a Cholesky factorization, O(n^3):
//! the O(n) articulated-body algorithm holds for unconstrained chains only.
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
pub mod simulate;
pub mod spatial;
mod subspace;

pub use algorithms::{
    aba, coriolis_torques, gravity_torques, mass_matrix, mass_matrix_inverse, nonlinear_effects,
    rnea,
};
pub use energy::{kinetic_energy, potential_energy};

use crate::error::{check_finite, Error, Result};
use crate::math::{sin_cos_slice, DMatrix, Pose, Vector3, Vector6};
use crate::model::{CouplingLaw, LinkInertia, Model};
use spatial::{Force, Motion, SpatialInertia};
pub(crate) use subspace::JointAxis;

/// Standard gravity in the world frame, m/s^2: `(0, 0, -9.81)`, as
/// Pinocchio and the Robotics Toolbox use.
pub const DEFAULT_GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

/// Singularity threshold of the mass matrix in forward dynamics
/// (dimensionless): `M(q)` is numerically singular, and forward dynamics an
/// error, when a pivot of its factorization is at or below this times the
/// largest diagonal entry of `M(q)`. The pivots are the ABA's articulated
/// inertias `D_j = S_j' IA_j S_j` (those of `M = L' D L`, eliminating from
/// the tip; Featherstone, section 6.5), or the squared diagonal of a Cholesky
/// factor `M = L L'` ([`mass_matrix_inverse`], coupled models). A pivot of
/// an exactly singular `M` comes out of rounding at about 1e-16 of the
/// largest diagonal, of either sign; a ratio of 1e-10 still leaves
/// accelerations with about six correct digits (about `1e-16 / ratio`). On
/// 440 root-to-leaf chains of example-robot-data 6.0.0's URDFs (those
/// without mimic joints; Pinocchio's `M` at three configurations each),
/// the smallest pivot ratio of a regular `M`, in either order, is 1.1e-7
/// (iCub's `imu_frame` chain), three orders above the threshold; rounding
/// is six orders below it.
pub const MASS_MATRIX_THRESHOLD: f64 = 1e-10;

/// The error of forward dynamics on a numerically singular mass matrix:
/// `pivot` (see [`MASS_MATRIX_THRESHOLD`]) at `joint`, `largest` `M`'s
/// largest diagonal entry.
fn singular_mass_matrix(
    model: &Model,
    context: &str,
    joint: usize,
    pivot: f64,
    largest: f64,
) -> Error {
    Error::Numerical {
        context: context.into(),
        reason: format!(
            "the mass matrix is singular at joint {joint} (`{}`): its pivot there is {pivot:.3e}, \
             not above {MASS_MATRIX_THRESHOLD:e} times the matrix's largest diagonal entry \
             {largest:.3e} (the bodies this joint moves have no inertia about its axis that \
             the other joints cannot take up, e.g. a point mass on the axis or a massless \
             tip)",
            model.joints()[joint].name
        ),
    }
}

/// Workspace for the dynamics algorithms, sized once for one model.
///
/// Holds the gravity vector, the model's mass properties in each joint's
/// frame (read here, and read again when the workspace is next used with
/// another [`Model`] value of the same size), every per-body buffer, and the
/// results of the last call of each algorithm. Create it once per model and thread with
/// [`DynamicsData::new`], which also checks that the model has mass
/// properties.
#[derive(Clone, Debug)]
pub struct DynamicsData {
    dof: usize,
    gravity: Vector3<f64>,
    /// Buffers of the configuration-to-chain map; `None` without coupling.
    coupled: Option<CoupledBuffers>,
    /// Address of the chain joints of the model the subspaces, inertias and
    /// placements below were read from.
    source: usize,
    /// Each chain joint's motion subspace, in its own frame (set-up).
    joint_axes: Vec<JointAxis>,
    /// Each body's spatial inertia about its joint frame's origin, in that
    /// frame's axes (set-up).
    local_inertias: Vec<SpatialInertia>,
    /// Chain joint positions at the last configuration, and their (sin, cos).
    chain_positions: Vec<f64>,
    sin_cos: Vec<(f64, f64)>,
    /// Each joint's frame, after its motion, in the previous joint's frame
    /// (the first in the world frame): Featherstone's `X_J X_T`. Holds the
    /// model's placements from `read_model` on, and only the moving
    /// part is written per call.
    transforms: Vec<Pose>,
    /// ABA: motion subspace of each chain joint, world frame.
    world_axes: Vec<Motion>,
    /// ABA: each body's spatial inertia, world frame.
    world_inertias: Vec<SpatialInertia>,
    /// Each body's velocity, in its own frame (RNEA, kinetic energy).
    velocities: Vec<Motion>,
    /// ABA: body velocities in the world frame.
    world_velocities: Vec<Motion>,
    /// ABA: velocity-product accelerations `v x S qd`, world frame.
    accelerations: Vec<Motion>,
    /// RNEA: each body's force; CRBA: the columns `Ic_k S_k` being carried
    /// inwards.
    forces: Vec<Force>,
    /// ABA: `U_j = IA_j S_j`.
    u_columns: Vec<Vector6<f64>>,
    /// ABA: `D_j = S_j' U_j`.
    d_values: Vec<f64>,
    /// ABA: `u_j = tau_j - S_j' pA_j`.
    u_values: Vec<f64>,
    zeros: Vec<f64>,
    /// One torque per chain joint (the result itself without coupling).
    tau: Vec<f64>,
    ddq: Vec<f64>,
    mass_matrix: DMatrix<f64>,
    mass_matrix_inverse: DMatrix<f64>,
}

/// What a coupled model's dynamics needs besides the chain's buffers.
#[derive(Clone, Debug)]
struct CoupledBuffers {
    /// `M = d q_c / d q` at the last configuration (chain joints x dof).
    map: DMatrix<f64>,
    /// The additive curves: (configuration source, chain target, `f''(q_s)`
    /// at the last configuration).
    additive: Vec<(usize, usize, f64)>,
    /// Chain velocities `M qd`.
    chain_velocities: Vec<f64>,
    /// Chain accelerations `M qdd + Md qd`.
    chain_accelerations: Vec<f64>,
    /// The chain's mass matrix `H_c` (chain joints x chain joints).
    chain_mass_matrix: DMatrix<f64>,
    /// `H_c M` (chain joints x dof).
    product: DMatrix<f64>,
    /// The folded torques `M' tau_c` (one per independent joint).
    torques: Vec<f64>,
    /// Scratch: a unit chain force, and one row of `M`.
    unit: Vec<f64>,
    row: Vec<f64>,
}

impl DynamicsData {
    /// A workspace for `model`, with gravity [`DEFAULT_GRAVITY`].
    ///
    /// Errors: a link without mass properties (the first one is named), or
    /// an additive coupling curve without a second derivative.
    pub fn new(model: &Model) -> Result<Self> {
        check_dynamics_model(model)?;
        let n = model.dof();
        let chain = model.chain_joints().len();
        let coupled = (!model.couplings().is_empty()).then(|| CoupledBuffers {
            map: DMatrix::zeros(chain, n),
            additive: model
                .couplings()
                .iter()
                .filter(|c| matches!(c.law, CouplingLaw::Additive(_)))
                .map(|c| (c.source, c.target, 0.0))
                .collect(),
            chain_velocities: vec![0.0; chain],
            chain_accelerations: vec![0.0; chain],
            chain_mass_matrix: DMatrix::zeros(chain, chain),
            product: DMatrix::zeros(chain, n),
            torques: vec![0.0; n],
            unit: vec![0.0; chain],
            row: vec![0.0; n],
        });
        let mut data = DynamicsData {
            dof: n,
            gravity: DEFAULT_GRAVITY,
            coupled,
            source: 0,
            joint_axes: vec![JointAxis::Rotation; chain],
            local_inertias: vec![SpatialInertia::ZERO; chain],
            chain_positions: vec![0.0; chain],
            sin_cos: vec![(0.0, 1.0); chain],
            transforms: vec![Pose::identity(); chain],
            world_axes: vec![Motion::ZERO; chain],
            world_inertias: vec![SpatialInertia::ZERO; chain],
            velocities: vec![Motion::ZERO; chain],
            world_velocities: vec![Motion::ZERO; chain],
            accelerations: vec![Motion::ZERO; chain],
            forces: vec![Force::ZERO; chain],
            u_columns: vec![Vector6::zeros(); chain],
            d_values: vec![0.0; chain],
            u_values: vec![0.0; chain],
            zeros: vec![0.0; chain],
            tau: vec![0.0; chain],
            ddq: vec![0.0; n],
            mass_matrix: DMatrix::zeros(n, n),
            mass_matrix_inverse: DMatrix::zeros(n, n),
        };
        data.read_model(model)?;
        Ok(data)
    }

    /// Each chain joint's motion subspace, its link's spatial inertia in its
    /// own frame and its placement, from `model` (sizes checked by the
    /// caller).
    fn read_model(&mut self, model: &Model) -> Result<()> {
        // Unknown until every link is read (an error leaves it unknown).
        self.source = 0;
        for (link, ((joint, axis), inertia)) in model
            .chain_joints()
            .iter()
            .zip(self.joint_axes.iter_mut())
            .zip(self.local_inertias.iter_mut())
            .enumerate()
        {
            *axis = JointAxis::of(joint.kind);
            *inertia = SpatialInertia::of_link(link_inertia(model, link, joint.inertia.as_ref())?);
        }
        // The parts of each joint transform that its motion leaves alone
        // (`JointAxis::move_frame` writes the rest).
        self.transforms.copy_from_slice(model.joint_placements());
        self.source = model.chain_joints().as_ptr() as usize;
        Ok(())
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

    /// Each body's spatial velocity from the last [`rnea`],
    /// [`nonlinear_effects`], [`coriolis_torques`] or [`kinetic_energy`]
    /// call, in the body's own joint frame ([`crate::kinematics::Data::joint_frames`]'s
    /// axes, about its origin; one per chain joint, [`Model::chain_joints`]).
    pub fn body_velocities(&self) -> &[Motion] {
        &self.velocities
    }

    /// The joint torques of the last [`rnea`], [`gravity_torques`],
    /// [`coriolis_torques`] or [`nonlinear_effects`] call (N m or N), one
    /// per independent joint.
    pub fn torques(&self) -> &[f64] {
        match &self.coupled {
            Some(coupled) => &coupled.torques,
            None => &self.tau,
        }
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

    /// Checks that the workspace fits `model`'s sizes, and reads its mass
    /// properties again if it is another model value than last time.
    fn check_model(&mut self, model: &Model) -> Result<()> {
        if self.dof != model.dof() {
            return Err(Error::DimensionMismatch {
                what: "dynamics data (workspace made for another model)",
                expected: model.dof(),
                got: self.dof,
            });
        }
        if self.joint_axes.len() != model.chain_joints().len()
            || self.coupled.is_some() == model.couplings().is_empty()
        {
            return Err(Error::DimensionMismatch {
                what: "dynamics data chain joints (workspace made for another model)",
                expected: model.chain_joints().len(),
                got: self.joint_axes.len(),
            });
        }
        if model.chain_joints().as_ptr() as usize != self.source {
            self.read_model(model)?;
        }
        Ok(())
    }

    /// Each joint's frame at `q` in its predecessor's
    /// ([`DynamicsData::joint_transforms`]), and a coupled model's map.
    #[inline(always)] // into the CRBA's `mass_matrix_avx2_fma` (algorithms.rs)
    fn update_transforms(&mut self, model: &Model, q: &[f64]) -> Result<()> {
        self.check_model(model)?;
        model.check_joint_positions(q)?;
        // Without coupling the chain's positions are `q` itself.
        let positions: &[f64] = match &mut self.coupled {
            None => q,
            Some(coupled) => {
                model.joint_map().expand(q, &mut self.chain_positions);
                coupled.update_map(model, q);
                &self.chain_positions
            }
        };
        // The trigonometry in a loop of its own: the calls are independent,
        // so the processor overlaps them.
        sin_cos_slice(positions, &mut self.sin_cos);
        for ((((transform, placement), axis), &position), &sin_cos) in self
            .transforms
            .iter_mut()
            .zip(model.joint_placements())
            .zip(&self.joint_axes)
            .zip(positions)
            .zip(&self.sin_cos)
        {
            axis.move_frame(transform, placement, position, sin_cos);
        }
        Ok(())
    }

    /// After `update_transforms`: each joint's world frame, motion subspace
    /// and body inertia in the world frame (what the ABA and the potential
    /// energy use).
    fn update_world_bodies(&mut self) {
        let mut frame = Pose::identity();
        for (j, transform) in self.transforms.iter().enumerate() {
            frame = if j == 0 {
                *transform
            } else {
                &frame * transform
            };
            self.world_axes[j] = self.joint_axes[j].in_frame(&frame);
            self.world_inertias[j] = self.local_inertias[j].transformed(&frame);
        }
    }

    /// The RNEA's two passes on the chain (after `update_transforms`) at
    /// joint velocities `v` and accelerations `a` (each `None`: zero) of the
    /// independent joints, `gravity` `None` leaving it out; the torques are
    /// then in [`DynamicsData::torques`]. A coupled model's chain moves at
    /// `M v`, `M a + Md v`, and its torques fold to `M' tau_c`. Error: a
    /// torque that overflowed.
    fn chain_newton_euler(
        &mut self,
        v: Option<&[f64]>,
        a: Option<&[f64]>,
        gravity: Option<&Vector3<f64>>,
    ) -> Result<()> {
        let zeros = std::mem::take(&mut self.zeros);
        let v = v.unwrap_or(&zeros);
        // Checked before `take` so that an uncoupled call moves nothing.
        let coupled = if self.coupled.is_some() {
            self.coupled.take()
        } else {
            None
        };
        match coupled {
            None => {
                algorithms::newton_euler(self, v, a.unwrap_or(&zeros), gravity);
            }
            Some(mut coupled) => {
                coupled.expand(v, a);
                algorithms::newton_euler(
                    self,
                    &coupled.chain_velocities,
                    &coupled.chain_accelerations,
                    gravity,
                );
                coupled.fold_torques(&self.tau);
                self.coupled = Some(coupled);
            }
        }
        self.zeros = zeros;
        check_not_overflowed("inverse dynamics", self.torques())
    }
}

/// Finite inputs can still overflow (lengths or prismatic positions near
/// `f64::MAX`); a non-finite result is an error rather than a result.
fn check_not_overflowed(context: &str, values: &[f64]) -> Result<()> {
    // `0 x` is 0 for a finite x and NaN otherwise: one branch for the slice.
    if values.iter().map(|v| v * 0.0).sum::<f64>() == 0.0 {
        return Ok(());
    }
    Err(Error::Numerical {
        context: context.into(),
        reason: "the result overflowed to a non-finite value (link lengths or joint positions \
                 too large)"
            .into(),
    })
}

impl CoupledBuffers {
    /// `M = d q_c / d q` at `q`, and each additive curve's `f''(q_s)`.
    fn update_map(&mut self, model: &Model, q: &[f64]) {
        // Row j of M is M' e_j: the model's own fold of a unit chain force
        // (one code path with the Jacobian's J = J0 M).
        let map = model.joint_map();
        for j in 0..self.unit.len() {
            self.unit[j] = 1.0;
            map.fold_forces(q, &self.unit, &mut self.row);
            self.unit[j] = 0.0;
            for (i, &value) in self.row.iter().enumerate() {
                self.map[(j, i)] = value;
            }
        }
        let curves = model.couplings().iter().filter_map(|c| match &c.law {
            CouplingLaw::Additive(curve) => Some(curve),
            CouplingLaw::Mimic { .. } => None,
        });
        for ((source, _, curvature), curve) in self.additive.iter_mut().zip(curves) {
            // Checked at set-up (`check_dynamics_model`): the curve has a
            // second derivative.
            *curvature = curve.second_derivative(q[*source]).unwrap_or(f64::NAN);
        }
    }

    /// Chain velocities `M v` and accelerations `M a + Md v` (`a` `None`:
    /// zero), `Md v` the additive curves' `f''(q_s) v_s^2` on their targets.
    fn expand(&mut self, v: &[f64], a: Option<&[f64]>) {
        multiply(&self.map, v, &mut self.chain_velocities);
        match a {
            Some(a) => multiply(&self.map, a, &mut self.chain_accelerations),
            None => self.chain_accelerations.fill(0.0),
        }
        for &(source, target, curvature) in &self.additive {
            self.chain_accelerations[target] += curvature * v[source] * v[source];
        }
    }

    /// `tau = M' tau_c` into `torques`.
    fn fold_torques(&mut self, chain_torques: &[f64]) {
        for (i, value) in self.torques.iter_mut().enumerate() {
            *value = self
                .map
                .column(i)
                .iter()
                .zip(chain_torques)
                .map(|(m, t)| m * t)
                .sum();
        }
    }
}

/// `out = m x` for a matrix `m` (rows = `out.len()`, columns = `x.len()`).
fn multiply(m: &DMatrix<f64>, x: &[f64], out: &mut [f64]) {
    for (i, value) in out.iter_mut().enumerate() {
        *value = m.row(i).iter().zip(x).map(|(a, b)| a * b).sum();
    }
}

fn link_inertia<'m>(
    model: &Model,
    link: usize,
    inertia: Option<&'m LinkInertia>,
) -> Result<&'m LinkInertia> {
    inertia.ok_or_else(|| Error::InvalidModel {
        link,
        name: model.chain_joints()[link].name.clone(),
        field: "mass".into(),
        reason: format!(
            "model `{}` has no mass properties for this link: dynamics needs every link's \
             mass, centre of mass and inertia (DH files: `mass`, `com`, `inertia`; URDF: \
             <inertial>)",
            model.name()
        ),
    })
}

/// Checks that `model` can go through the dynamics algorithms: every chain
/// link has mass properties (the error names the first that has none), and
/// every additive coupling curve gives its second derivative.
pub fn check_dynamics_model(model: &Model) -> Result<()> {
    for coupling in model.couplings() {
        if let CouplingLaw::Additive(curve) = &coupling.law {
            if curve.second_derivative(0.0).is_none() {
                return Err(Error::InvalidModelStructure {
                    model: model.name().to_string(),
                    reason: format!(
                        "the coupling of chain joint {} ({}) has no second derivative \
                         (CouplingCurve::second_derivative): the dynamics need it for the \
                         coupled joint's acceleration",
                        coupling.target,
                        curve.describe()
                    ),
                });
            }
        }
    }
    for (link, joint) in model.chain_joints().iter().enumerate() {
        link_inertia(model, link, joint.inertia.as_ref())?;
    }
    Ok(())
}
