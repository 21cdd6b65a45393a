//! Joint couplings: chain joints whose position depends on another joint's.
//!
//! One concept covers both couplings armkit knows:
//!
//! * [`CouplingLaw::Mimic`], a URDF `<mimic>` joint: `q_m = multiplier *
//!   q_leader + offset`. The mimic joint leaves the configuration: the
//!   model's `q` holds the independent joints only ([`super::Model::dof`]).
//! * [`CouplingLaw::Additive`], seed 000's flexible beam: `d3' = d3 + w(d2)`
//!   (eq 4 corrected), a nonlinear curve `f` of the source added to a target
//!   joint that stays independent. The model owns only the curve's interface
//!   ([`CouplingCurve`]); [`crate::beam`] implements it.
//!
//! Both are resolved once, at build time, into one map from the
//! configuration `q` (length `dof`) to the positions of the chain's joints
//! (length [`super::Model::chain_joints`]): forward kinematics expands `q`
//! through it, and the Jacobian folds the chain's columns back,
//! `J = J0 M` with `M = d q_chain / d q` (seed 000, eqs 8-10 for the beam),
//! in one code path ([`crate::kinematics`]).
//!
//! ```
//! use armkit::model::{JointSpec, MimicJoint, ModelBuilder};
//! use armkit::kinematics::{forward_kinematics, Data};
//! // Two revolute joints; the second follows the first at half its angle.
//! let model = ModelBuilder::new("finger")
//!     .joint(JointSpec::revolute("proximal", -1.0, 1.0))
//!     .joint(JointSpec::revolute("distal", -0.4, 0.4))
//!     .mimic(MimicJoint::new("distal", "proximal", 0.5, 0.0))
//!     .build()
//!     .unwrap();
//! assert_eq!(model.dof(), 1); // only `proximal` is in the configuration
//! assert_eq!(model.chain_joints().len(), 2);
//! // distal's limits (+-0.4) bound proximal to +-0.8 (the tighter bound wins).
//! assert_eq!(model.joints()[0].limits.upper, 0.8);
//! let mut data = Data::new(&model);
//! forward_kinematics(&model, &mut data, &[0.6]).unwrap();
//! assert_eq!(data.effective_positions(), &[0.6, 0.3]);
//! ```

use std::fmt::Debug;
use std::sync::Arc;

use crate::error::{Error, Result};
use crate::math::{F64x4, Lane, Matrix6xX, LANES};

/// A scalar curve `f(x)` with its slope, the law of an additive coupling
/// (e.g. a beam's deflection under a carriage, [`crate::beam`]).
///
/// Units are the joints': `x` is the source joint's position, `f(x)` a
/// displacement of the target joint (m for a prismatic target).
pub trait CouplingCurve: Debug + Send + Sync {
    /// `(f(x), df/dx)` at `x`. Called in forward kinematics: must not
    /// allocate, and should return NaN (not panic) for a NaN `x`.
    fn value_and_slope(&self, x: f64) -> (f64, f64);

    /// One line saying what the curve is, for listings (`armkit info`).
    fn describe(&self) -> String;

    /// The curvature `d^2 f / dx^2` at `x`, if the curve provides it
    /// (default: `None`). The dynamics need it: the target joint's
    /// acceleration gains `f''(x) xd^2` ([`crate::dynamics`] refuses a
    /// model with an additive curve that returns `None`). Must not allocate;
    /// NaN for a NaN `x`.
    fn second_derivative(&self, x: f64) -> Option<f64> {
        let _ = x;
        None
    }

    /// Checks the curve's parameters when it is attached to a model
    /// (default: nothing to check).
    fn validate(&self) -> Result<()> {
        Ok(())
    }
}

/// How a coupled (target) joint's position follows its source joint.
#[derive(Clone, Debug)]
pub enum CouplingLaw {
    /// `q_target = multiplier * q_source + offset` (URDF `<mimic>`): the
    /// target is not in the configuration. Offset in the target's units.
    Mimic {
        /// Dimensionless factor (or m/rad across joint kinds).
        multiplier: f64,
        /// Constant term, rad or m.
        offset: f64,
    },
    /// `q_target' = q_target + f(q_source)`: the target stays independent
    /// (seed 000's beam, `d3' = d3 + w(d2)`).
    Additive(Arc<dyn CouplingCurve>),
}

impl CouplingLaw {
    /// The law's contribution to the target and its derivative with respect
    /// to the source position: `(m x + offset, m)` for a mimic (the whole
    /// target position), `(f(x), f'(x))` for an additive curve (added to the
    /// target's own position).
    pub fn offset_and_slope(&self, source_position: f64) -> (f64, f64) {
        match self {
            CouplingLaw::Mimic { multiplier, offset } => {
                (multiplier * source_position + offset, *multiplier)
            }
            CouplingLaw::Additive(curve) => curve.value_and_slope(source_position),
        }
    }

    /// One line for listings: `q = 0.5 q_leader + 0` or the curve's description.
    pub fn describe(&self) -> String {
        match self {
            CouplingLaw::Mimic { multiplier, offset } => {
                format!("mimic: multiplier {multiplier}, offset {offset}")
            }
            CouplingLaw::Additive(curve) => format!("adds {}", curve.describe()),
        }
    }
}

/// A coupling on a built model: chain joint `target` follows configuration
/// entry `source` through `law`.
///
/// `source` indexes the configuration `q` (and [`super::Model::joints`]);
/// `target` indexes the chain ([`super::Model::chain_joints`],
/// [`crate::kinematics::Data::joint_frames`]). For a model without mimic
/// joints the two numberings coincide (gantry9-flex: source 1 = `d2`,
/// target 2 = `d3`).
#[derive(Clone, Debug)]
pub struct JointCoupling {
    /// Index in the configuration of the joint whose position drives the coupling.
    pub source: usize,
    /// Index in the chain of the joint that is driven.
    pub target: usize,
    /// The law.
    pub law: CouplingLaw,
}

/// A URDF-style mimic declaration for [`super::ModelBuilder::mimic`]:
/// joint `joint` follows joint `leader`, `q = multiplier * q_leader + offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct MimicJoint {
    /// The mimic (follower) joint's name.
    pub joint: String,
    /// The name of the joint it follows (on the chain, another mimic joint,
    /// or a joint added with [`super::ModelBuilder::off_chain_joint`]).
    pub leader: String,
    /// Factor (URDF default 1).
    pub multiplier: f64,
    /// Offset, rad or m (URDF default 0).
    pub offset: f64,
}

impl MimicJoint {
    /// `joint` follows `leader`: `q = multiplier * q_leader + offset`.
    pub fn new(
        joint: impl Into<String>,
        leader: impl Into<String>,
        multiplier: f64,
        offset: f64,
    ) -> Self {
        MimicJoint {
            joint: joint.into(),
            leader: leader.into(),
            multiplier,
            offset,
        }
    }
}

/// Where one chain joint's position comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Drive {
    /// `q_chain = q[index]`.
    Independent(usize),
    /// `q_chain = multiplier * q[leader] + offset`.
    Mimic {
        leader: usize,
        multiplier: f64,
        offset: f64,
    },
}

/// An additive curve on a built model: (configuration source, chain
/// target, curve).
pub(crate) type AdditiveCurve = (usize, usize, Arc<dyn CouplingCurve>);

/// The configuration-to-chain map, resolved at build time into one of
/// three shapes, matched once per call: a model without couplings pays
/// for nothing (forward kinematics copies `q`, the Jacobian is the chain's).
#[derive(Clone, Debug)]
pub(crate) enum JointMap {
    /// The chain's joints are the configuration's, in order, and nothing
    /// is added: the chain's positions are `q`.
    Identity {
        /// Number of joints (chain = configuration).
        joints: usize,
    },
    /// The chain's joints are the configuration's, in order, plus additive
    /// curves (gantry9-flex): `d3' = d3 + w(d2)`; the Jacobian's columns
    /// are folded in place (seed 000, eq 10).
    Additive {
        /// Number of joints (chain = configuration).
        joints: usize,
        /// At least one curve.
        additive: Vec<AdditiveCurve>,
    },
    /// Mimic joints: each chain joint is driven by a configuration entry
    /// (itself or a leader), then the additive curves (possibly none).
    Mimic {
        /// One per chain joint.
        drives: Vec<Drive>,
        additive: Vec<AdditiveCurve>,
    },
}

impl JointMap {
    pub(crate) fn new(drives: Vec<Drive>) -> Self {
        let identity = drives
            .iter()
            .enumerate()
            .all(|(j, d)| *d == Drive::Independent(j));
        if identity {
            JointMap::Identity {
                joints: drives.len(),
            }
        } else {
            JointMap::Mimic {
                drives,
                additive: Vec::new(),
            }
        }
    }

    /// Number of chain joints.
    pub(crate) fn chain_len(&self) -> usize {
        match self {
            JointMap::Identity { joints } | JointMap::Additive { joints, .. } => *joints,
            JointMap::Mimic { drives, .. } => drives.len(),
        }
    }

    /// Where chain joint `j` (< [`JointMap::chain_len`]) gets its position.
    pub(crate) fn drive(&self, j: usize) -> Drive {
        match self {
            JointMap::Identity { .. } | JointMap::Additive { .. } => Drive::Independent(j),
            JointMap::Mimic { drives, .. } => drives[j],
        }
    }

    /// The additive curves (empty for most models).
    pub(crate) fn additive(&self) -> &[AdditiveCurve] {
        match self {
            JointMap::Identity { .. } => &[],
            JointMap::Additive { additive, .. } | JointMap::Mimic { additive, .. } => additive,
        }
    }

    /// True when the chain's joints are the configuration's, in order
    /// (no mimic joint): the Jacobian is then computed in place.
    pub(crate) fn is_identity(&self) -> bool {
        !matches!(self, JointMap::Mimic { .. })
    }

    /// This map with its additive curves replaced by `additive`.
    pub(crate) fn with_additive(&self, additive: Vec<AdditiveCurve>) -> JointMap {
        match self {
            JointMap::Identity { joints } | JointMap::Additive { joints, .. } => {
                if additive.is_empty() {
                    JointMap::Identity { joints: *joints }
                } else {
                    JointMap::Additive {
                        joints: *joints,
                        additive,
                    }
                }
            }
            JointMap::Mimic { drives, .. } => JointMap::Mimic {
                drives: drives.clone(),
                additive,
            },
        }
    }

    /// Chain joint positions from the configuration `q` (sizes checked by
    /// the caller): drives first, then the additive curves. Allocates nothing.
    #[inline]
    pub(crate) fn expand(&self, q: &[f64], chain: &mut [f64]) {
        match self {
            JointMap::Identity { .. } => chain.copy_from_slice(q),
            JointMap::Additive { additive, .. } => {
                chain.copy_from_slice(q);
                add_curves(additive, q, chain);
            }
            JointMap::Mimic { drives, additive } => {
                for (value, drive) in chain.iter_mut().zip(drives) {
                    *value = match *drive {
                        Drive::Independent(i) => q[i],
                        Drive::Mimic {
                            leader,
                            multiplier,
                            offset,
                        } => multiplier * q[leader] + offset,
                    };
                }
                add_curves(additive, q, chain);
            }
        }
    }

    /// `J = J0 M`: folds the chain Jacobian into `out` (6 x dof). For
    /// [`JointMap::Identity`] there is nothing to do (`out` already holds
    /// `J0`, `chain` is unused); for [`JointMap::Additive`] only the additive
    /// columns change, in place (seed 000 eq 10, `column(source) += slope *
    /// column(target)`); for [`JointMap::Mimic`], `chain` holds `J0`
    /// (6 x chain joints).
    #[inline]
    pub(crate) fn fold_jacobian(
        &self,
        q: &[f64],
        chain: &Matrix6xX<f64>,
        out: &mut Matrix6xX<f64>,
    ) {
        match self {
            JointMap::Identity { .. } => {}
            JointMap::Additive { additive, .. } => {
                for (source, target, curve) in additive {
                    let (_, slope) = curve.value_and_slope(q[*source]);
                    let column = out.column(*target).into_owned();
                    out.column_mut(*source).axpy(slope, &column, 1.0);
                }
            }
            JointMap::Mimic { drives, additive } => {
                out.fill(0.0);
                for (j, drive) in drives.iter().enumerate() {
                    let (index, factor) = match *drive {
                        Drive::Independent(i) => (i, 1.0),
                        Drive::Mimic {
                            leader, multiplier, ..
                        } => (leader, multiplier),
                    };
                    out.column_mut(index).axpy(factor, &chain.column(j), 1.0);
                }
                for (source, target, curve) in additive {
                    let (_, slope) = curve.value_and_slope(q[*source]);
                    out.column_mut(*source)
                        .axpy(slope, &chain.column(*target), 1.0);
                }
            }
        }
    }

    /// [`JointMap::fold_jacobian`] on four configurations side by side:
    /// `chain` holds the chain's columns `[v; w]` (one per chain joint, lane
    /// l of configuration `rows[l]`), `out` receives one per independent
    /// joint, with the same sums in the same order. Allocates nothing.
    #[inline(always)]
    pub(crate) fn fold_lane_columns(
        &self,
        rows: &[&[f64]; LANES],
        chain: &[[F64x4; 6]],
        out: &mut [[F64x4; 6]],
    ) {
        let add_scaled = |out: &mut [F64x4; 6], column: &[F64x4; 6], factor: F64x4| {
            for (o, &c) in out.iter_mut().zip(column) {
                *o = *o + c * factor;
            }
        };
        match self {
            JointMap::Identity { .. } | JointMap::Additive { .. } => out.copy_from_slice(chain),
            JointMap::Mimic { drives, .. } => {
                out.fill([F64x4::default(); 6]);
                for (column, drive) in chain.iter().zip(drives) {
                    let (index, factor) = match *drive {
                        Drive::Independent(i) => (i, 1.0),
                        Drive::Mimic {
                            leader, multiplier, ..
                        } => (leader, multiplier),
                    };
                    add_scaled(&mut out[index], column, F64x4::splat(factor));
                }
            }
        }
        for (source, target, curve) in self.additive() {
            let slope = F64x4(std::array::from_fn(|l| {
                curve.value_and_slope(rows[l][*source]).1
            }));
            add_scaled(&mut out[*source], &chain[*target], slope);
        }
    }

    /// `tau = M' tau0`: generalized forces on the chain joints (`chain`,
    /// one per chain joint) as forces on the configuration (`out`, one per
    /// independent joint). Allocates nothing.
    pub(crate) fn fold_forces(&self, q: &[f64], chain: &[f64], out: &mut [f64]) {
        match self {
            JointMap::Identity { .. } | JointMap::Additive { .. } => {
                // `0 + value`, as the drives below (a -0.0 becomes 0.0).
                for (o, &value) in out.iter_mut().zip(chain) {
                    *o = 0.0 + value;
                }
            }
            JointMap::Mimic { drives, .. } => {
                out.fill(0.0);
                for (&value, drive) in chain.iter().zip(drives) {
                    match *drive {
                        Drive::Independent(i) => out[i] += value,
                        Drive::Mimic {
                            leader, multiplier, ..
                        } => out[leader] += multiplier * value,
                    }
                }
            }
        }
        for (source, target, curve) in self.additive() {
            let (_, slope) = curve.value_and_slope(q[*source]);
            out[*source] += slope * chain[*target];
        }
    }
}

/// `chain[target] += f(q[source])` for each additive curve.
#[inline]
fn add_curves(additive: &[AdditiveCurve], q: &[f64], chain: &mut [f64]) {
    for (source, target, curve) in additive {
        chain[*target] += curve.value_and_slope(q[*source]).0;
    }
}

/// The error for a bad mimic declaration or coupling, naming the joint.
pub(crate) fn mimic_error(model: &str, joint: &str, reason: impl Into<String>) -> Error {
    Error::InvalidModelStructure {
        model: model.to_string(),
        reason: format!("mimic joint `{joint}`: {}", reason.into()),
    }
}

/// Checks an additive coupling against a model's map and chain; `Ok` gives
/// the triple the map stores.
pub(crate) fn check_additive(
    coupling: &JointCoupling,
    dof: usize,
    map: &JointMap,
    target_is_prismatic: bool,
) -> Result<AdditiveCurve> {
    let bad = |reason: String| Error::invalid_argument("coupling", reason);
    let CouplingLaw::Additive(curve) = &coupling.law else {
        return Err(bad(
            "a mimic coupling is declared with ModelBuilder::mimic (a mimic joint), not added to a built model".into(),
        ));
    };
    curve.validate()?;
    let chain_len = map.chain_len();
    if coupling.source >= dof || coupling.target >= chain_len {
        return Err(bad(format!(
            "source {} must index the model's {dof} independent joints and target {} its {chain_len} chain joints",
            coupling.source, coupling.target
        )));
    }
    match map.drive(coupling.target) {
        Drive::Independent(i) if i == coupling.source => {
            return Err(bad("source and target must be different joints".into()))
        }
        Drive::Independent(_) => {}
        Drive::Mimic { .. } => {
            return Err(bad(format!(
                "target joint {} is a mimic joint (its position follows its leader)",
                coupling.target
            )))
        }
    }
    if !target_is_prismatic {
        return Err(bad(format!(
            "target joint {} must be prismatic",
            coupling.target
        )));
    }
    Ok((coupling.source, coupling.target, Arc::clone(curve)))
}
