//! Redundancy resolution at the velocity level: how a robot with more than
//! six joints shares one end-effector twist among its joints.
//!
//! Every method here returns joint velocities `q_dot` (rad/s or m/s, one per
//! joint) with `J q_dot = V`, where `J` is the 6 x n geometric Jacobian in the
//! world frame (rows `[vx, vy, vz, wx, wy, wz]`, see
//! [`crate::kinematics::jacobian`]) and `V` the end-effector twist (m/s, rad/s),
//! and minimises a weighted norm `q_dot' A q_dot` (seed 001, eq 18) with
//! positive per-joint weights `A = diag(a_i)` ([`JointWeights`]):
//!
//! * [`WeightedLeastNorm`]: `q_dot = A^-1 J' (J A^-1 J')^-1 V`, and a damped
//!   form for a nearly singular `J` ([`Damping`]). Workspaces are sized once;
//!   a solve allocates nothing.
//! * [`PartitionedSolver`]: seed 001 as printed: six "generalized" joints and
//!   `k = n - 6` extra joints (eqs 5-8), the extra joints' velocities in closed
//!   form (eq 19, corrected; eq 17 for energy weights), the generalized ones
//!   from eq 8. [`best_partition`] picks the best-conditioned split. It gives
//!   the same velocities as the weighted least norm (tested to 1e-9).
//! * Energy weights from joint torques ([`joint_torques`], [`energy_measure`]): `a_i = tau_i^2`, so the
//!   cost is seed 001's energy measure `F = sum (q_dot_i tau_i)^2` (eq 9), with
//!   `tau = J' w + gravity` for a load ([`Load`]) and a documented floor for
//!   zero torques ([`TorqueFloor`]); with the full inverse dynamics of a
//!   moving arm instead of the static torques ([`TorqueModel`],
//!   [`EnergyTorques`], [`energy_along_motion`]).
//! * Minimum norm (all weights 1: the pseudo-inverse), joint priorities (seed
//!   000: a large weight is a low priority) and locked joints (an infinite
//!   weight: the joint does not move; seed 001's zero `A_Q` in eq 19), all
//!   through [`JointWeights`].
//! * Secondary objectives in the null space, in the same weighted metric
//!   ([`SecondaryTask`], [`SecondaryObjective`]): Liegeois' gradient projection for joint-limit avoidance
//!   and for manipulability.
//! * A resolved-rate tracker ([`ResolvedRateTracker`]): this module's rate
//!   law in the one tracking loop ([`crate::tracking`]), following a timed
//!   Cartesian path with position feedback, scaling joint velocities to
//!   their limits and never crossing a joint position limit.
//!
//! ```
//! use armkit::kinematics::{jacobian, Data, JacobianFrame};
//! use armkit::math::Vector6;
//! use armkit::redundancy::{JointWeights, SolverOptions, WeightedLeastNorm};
//!
//! let model = armkit::robots::by_name("gantry9").unwrap();
//! let mut data = Data::new(&model);
//! let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
//! let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap().clone();
//! // Seed 000's priorities: rail 100, beam joints 10, arm joints 1.
//! let weights = JointWeights::new(&[100.0, 10.0, 10.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]).unwrap();
//! let mut solver = WeightedLeastNorm::new(9, SolverOptions::default()).unwrap();
//! let twist = Vector6::new(0.1, 0.0, -0.05, 0.0, 0.0, 0.0); // m/s, rad/s
//! let q_dot = solver.solve(&j, &weights, &twist).unwrap().solved().unwrap();
//! let achieved = &j * armkit::math::DVector::from_column_slice(q_dot);
//! assert!((achieved - twist).norm() < 1e-10);
//! ```

mod energy;
mod energy_weights;
mod nullspace;
mod partition;
mod tracking;
mod weighted;

pub use energy::{
    energy_measure, gravity_torques, joint_torques, Load, TorqueFloor, STANDARD_GRAVITY,
};
pub use energy_weights::{energy_along_motion, EnergyTorques, MotionEnergy, TorqueModel};
pub use nullspace::{
    joint_limit_cost, joint_limit_gradient, weighted_direction, SecondaryObjective, SecondaryTask,
};
pub use partition::{best_partition, Partition, PartitionChoice, PartitionedSolver};
pub use tracking::{
    compare_distributions, ComparisonCase, ComparisonResult, Distribution, DistributionOptions,
    Formulation, MotionSummary, ResolvedRateTracker,
};
pub use weighted::WeightedLeastNorm;

use crate::error::{check_finite, check_finite_vector, Error, Result};
use crate::math::Matrix6xX;

pub use crate::seeds::SEED000_PRIORITY_WEIGHTS;

/// Positive per-joint weights `a_i` of the velocity cost `sum a_i q_dot_i^2`
/// (seed 001, eq 18), or a locked joint.
///
/// A weight is in units of (cost) / (joint velocity)^2; only ratios matter.
/// A large weight makes a joint expensive to move, i.e. a low priority (seed
/// 000, sec 4.4). A locked joint has an infinite weight: every solver here
/// gives it exactly zero velocity. This is seed 001's "locking joints" in the
/// weighted least norm over all joints; the paper's last sentence says the
/// weights are *zero*, which is the same lock in its own parametrisation:
/// zero weights `A_Q` on the six generalized joints make eq 19 give the
/// extra joints `phi_dot = 0` ([`PartitionedSolver::solve_with_paper_weights`]).
///
/// ```
/// use armkit::redundancy::JointWeights;
/// let mut w = JointWeights::uniform(7); // minimum norm: the pseudo-inverse
/// w.set(2, 10.0).unwrap();              // joint 2 moves less
/// w.lock(6).unwrap();                   // joint 6 does not move
/// assert!(w.is_locked(6) && w.inverse()[6] == 0.0);
/// assert!(w.set(0, 0.0).is_err());      // weights must be > 0
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct JointWeights {
    /// `a_i`, `f64::INFINITY` for a locked joint.
    values: Vec<f64>,
    /// `1 / a_i`, exactly 0 for a locked joint.
    inverse: Vec<f64>,
}

impl JointWeights {
    /// All weights 1: the minimum-norm (pseudo-inverse) solution.
    pub fn uniform(dof: usize) -> Self {
        JointWeights {
            values: vec![1.0; dof],
            inverse: vec![1.0; dof],
        }
    }

    /// Weights from values, each finite and > 0 (use [`JointWeights::lock`]
    /// for an infinite weight). Error names the first bad entry.
    pub fn new(values: &[f64]) -> Result<Self> {
        let mut weights = Self::uniform(values.len());
        for (joint, &value) in values.iter().enumerate() {
            weights.set(joint, value)?;
        }
        Ok(weights)
    }

    /// Weights from priority levels (seed 000, sec 4.4): level 0 is the
    /// highest priority (weight 1), and each level down multiplies the weight
    /// by `ratio` (> 1): `a_i = ratio^level_i`. Seed 000's gantry is levels
    /// `[2, 1, 1, 0, 0, 0, 0, 0, 0]` with ratio 10, i.e.
    /// [`SEED000_PRIORITY_WEIGHTS`].
    pub fn from_priority_levels(levels: &[u32], ratio: f64) -> Result<Self> {
        if !(ratio.is_finite() && ratio > 1.0) {
            return Err(Error::invalid_argument(
                "ratio",
                format!("must be finite and > 1, got {ratio}"),
            ));
        }
        let values: Vec<f64> = levels
            .iter()
            .map(|&level| ratio.powf(f64::from(level)))
            .collect();
        Self::new(&values)
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.values.len()
    }

    /// The weights `a_i` (`f64::INFINITY` for locked joints).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The inverse weights `1 / a_i` (0 for locked joints): the diagonal of `A^-1`.
    pub fn inverse(&self) -> &[f64] {
        &self.inverse
    }

    /// True when `joint` is locked.
    pub fn is_locked(&self, joint: usize) -> bool {
        self.inverse.get(joint).is_some_and(|&inv| inv == 0.0)
    }

    /// Number of locked joints.
    pub fn locked_count(&self) -> usize {
        self.inverse.iter().filter(|&&inv| inv == 0.0).count()
    }

    /// Sets joint `joint`'s weight (finite, > 0); this unlocks a locked joint.
    pub fn set(&mut self, joint: usize, value: f64) -> Result<()> {
        self.check_joint(joint)?;
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::invalid_argument(
                "weights",
                format!("weight of joint {joint} must be finite and > 0, got {value}"),
            ));
        }
        self.values[joint] = value;
        self.inverse[joint] = 1.0 / value;
        Ok(())
    }

    /// Locks joint `joint`: infinite weight, zero velocity.
    pub fn lock(&mut self, joint: usize) -> Result<()> {
        self.check_joint(joint)?;
        self.values[joint] = f64::INFINITY;
        self.inverse[joint] = 0.0;
        Ok(())
    }

    /// These weights with `joints` locked.
    pub fn with_locked(mut self, joints: &[usize]) -> Result<Self> {
        for &joint in joints {
            self.lock(joint)?;
        }
        Ok(self)
    }

    /// The weighted cost `sum a_i q_dot_i^2` (seed 001, eq 18) of joint
    /// velocities `q_dot`; a locked joint adds 0 when it does not move and
    /// infinity when it does. Error: wrong size or a non-finite entry.
    pub fn cost(&self, q_dot: &[f64]) -> Result<f64> {
        check_finite_vector("joint_velocities", q_dot, self.dof())?;
        Ok(self
            .values
            .iter()
            .zip(q_dot)
            .map(|(&a, &v)| if v == 0.0 { 0.0 } else { a * v * v })
            .sum())
    }

    /// Copies `other` into `self` without allocating (same number of joints).
    pub(crate) fn copy_from(&mut self, other: &JointWeights) -> Result<()> {
        self.check_size("weights", other.dof())?;
        self.values.copy_from_slice(&other.values);
        self.inverse.copy_from_slice(&other.inverse);
        Ok(())
    }

    /// Checks that these weights are for `dof` joints (the error reports
    /// `dof` as expected and the weights' size as given).
    pub(crate) fn check_size(&self, what: &'static str, dof: usize) -> Result<()> {
        if dof != self.dof() {
            return Err(Error::DimensionMismatch {
                what,
                expected: dof,
                got: self.dof(),
            });
        }
        Ok(())
    }

    fn check_joint(&self, joint: usize) -> Result<()> {
        if joint >= self.dof() {
            return Err(Error::invalid_argument(
                "joint",
                format!(
                    "index {joint} is out of range for {} joints (0-based)",
                    self.dof()
                ),
            ));
        }
        Ok(())
    }
}

/// Damping of the weighted least-norm solution near singularities.
///
/// Damped, the solver minimises `|J q_dot - V|^2 + lambda^2 q_dot' A q_dot`,
/// i.e. `q_dot = A^-1 J' (J A^-1 J' + lambda^2 I)^-1 V`: the end-effector
/// twist is no longer met exactly, but joint velocities stay bounded. `lambda`
/// is in the units of `J A^-1/2` (m/s or rad/s per unit of weighted joint velocity).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Damping {
    /// Exact solution; a singular `J A^-1 J'` is an error.
    #[default]
    None,
    /// Constant damping `lambda` (> 0).
    Constant(f64),
    /// Nakamura and Hanafusa's variable damping: with `s` the smallest
    /// singular value of `J A^-1/2`,
    /// `lambda^2 = max^2 (1 - (s / threshold)^2)` when `s < threshold`, else 0.
    /// Exact away from singularities; costs a 6 x 6 symmetric eigen
    /// decomposition per solve.
    Adaptive {
        /// Singular value below which damping starts (> 0).
        threshold: f64,
        /// Damping `lambda` at a singularity (> 0).
        max: f64,
    },
}

impl Damping {
    /// Checks the parameters: finite and > 0.
    pub fn validate(&self) -> Result<()> {
        let positive = crate::error::check_positive;
        match *self {
            Damping::None => Ok(()),
            Damping::Constant(lambda) => positive("damping.lambda", lambda),
            Damping::Adaptive { threshold, max } => {
                positive("damping.threshold", threshold)?;
                positive("damping.max", max)
            }
        }
    }
}

/// Options of the weighted least-norm solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverOptions {
    /// Damping near singularities. Default: [`Damping::None`].
    pub damping: Damping,
    /// A solve is [`crate::linalg::Solve::Singular`] when the smallest
    /// pivot of the Cholesky factor of `J A^-1 J' (+ lambda^2 I)`, squared,
    /// is below this fraction of its largest diagonal entry (about the
    /// reciprocal of its condition number; see [`crate::linalg::factor_gram`]).
    /// Default [`crate::linalg::WEIGHTED_GRAM_THRESHOLD`] (1e-12); in `(0, 1)`.
    pub singular_threshold: f64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            damping: Damping::None,
            singular_threshold: crate::linalg::WEIGHTED_GRAM_THRESHOLD,
        }
    }
}

impl SolverOptions {
    /// Checks the damping and that `singular_threshold` is in `(0, 1)`.
    pub fn validate(&self) -> Result<()> {
        self.damping.validate()?;
        if !(self.singular_threshold > 0.0 && self.singular_threshold < 1.0) {
            return Err(Error::invalid_argument(
                "singular_threshold",
                format!("must be in (0, 1), got {}", self.singular_threshold),
            ));
        }
        Ok(())
    }
}

/// Checks a Jacobian against a joint count: 6 x `dof`, all entries finite.
fn check_jacobian(jacobian: &Matrix6xX<f64>, dof: usize) -> Result<()> {
    if jacobian.ncols() != dof {
        return Err(Error::DimensionMismatch {
            what: "jacobian (columns)",
            expected: dof,
            got: jacobian.ncols(),
        });
    }
    check_finite("jacobian", jacobian.as_slice())
}
