//! Seed 001's claims at one instant, tested along one path at identical
//! configurations: eq 17 gives the least F (eq 9) of every distribution for
//! the same joint positions and the same twist, and unit weights in eq 19
//! give the minimum-norm (pseudo-inverse) rates.
//!
//! A whole run cannot test the first claim: each distribution's run visits
//! its own configurations, so its torques differ and F over the motion
//! compares different instants. Here every distribution solves the same
//! `(q, V)`: the configurations and realised twists `V = J q_dot` of the
//! energy-optimal run.

use crate::error::Result;
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{DMatrix, DVector, Matrix6xX, Vector6};
use crate::model::Model;
use crate::redundancy::{
    best_partition, energy_measure, joint_torques, ComparisonResult, JointWeights, Load,
    PartitionedSolver, SolverOptions, WeightedLeastNorm,
};
use crate::study::{Finding, FindingStatus};

/// Largest condition number of the 6 x 6 block `G'0` accepted for the
/// partitioned form (eqs 5-8); the best partition of gantry9 stays far below.
const MAX_BLOCK_CONDITION: f64 = 1e10;

/// Relative margin below which two values of F count as equal (rounding
/// of a 9-joint solve is about 1e-14 relative).
const EQUAL_F: f64 = 1e-9;

/// One comparison distribution's instantaneous F against eq 17's, over
/// the samples of [`InstantComparison`].
#[derive(Clone, Debug, PartialEq)]
pub struct InstantRival {
    /// The distribution (`minimum-norm`, `priorities`, `locked`).
    pub name: String,
    /// Samples where its F is below eq 17's by more than 1e-9 relative.
    pub lower_samples: usize,
    /// Smallest `F_rival / F_eq17` over the samples (>= 1 when eq 17 is minimal).
    pub min_ratio: f64,
    /// Median `F_rival / F_eq17`.
    pub median_ratio: f64,
}

/// Seed 001's instantaneous claims along one path ([`instant_comparison`]).
#[derive(Clone, Debug, PartialEq)]
pub struct InstantComparison {
    /// Samples compared (every sample of the energy-optimal run with a
    /// nonzero twist).
    pub samples: usize,
    /// Samples left out because eq 17's matrix is singular there (zero
    /// torques; see [`PartitionedSolver::solve_energy_optimal`]).
    pub singular_samples: usize,
    /// Eq 17 (the paper's closed form, the load's static torques squared as
    /// weights, no floor) against each other distribution at the same `(q, V)`.
    pub rivals: Vec<InstantRival>,
    /// Largest `|q_dot_eq19(A = 1) - J^+ V| / |J^+ V|` (max norms), the
    /// pseudo-inverse by singular value decomposition.
    pub unit_weight_difference: f64,
    /// The same distance for eq 17's rates, for scale: how far a
    /// distribution other than the minimum norm lies from `J^+ V`.
    pub energy_rates_difference: f64,
}

/// Eq 17 and the other distributions at the configurations and realised
/// twists of `path_run` (the energy-optimal run), for `load`'s static
/// torques (the paper's). `priorities` and `locked` are the study's.
pub(super) fn instant_comparison(
    model: &Model,
    path_run: &ComparisonResult,
    load: &Load,
    priorities: &JointWeights,
    locked: &[usize],
) -> Result<InstantComparison> {
    let dof = model.dof();
    let rivals: Vec<(&str, JointWeights)> = vec![
        ("minimum-norm", JointWeights::uniform(dof)),
        ("priorities", priorities.clone()),
        ("locked", JointWeights::uniform(dof).with_locked(locked)?),
    ];
    let mut least_norm = WeightedLeastNorm::new(dof, SolverOptions::default())?;
    let mut partitioned = PartitionedSolver::new(dof, MAX_BLOCK_CONDITION)?;
    let mut data = Data::new(model);
    let mut torques = vec![0.0; dof];
    let mut ratios: Vec<Vec<f64>> = vec![Vec::new(); rivals.len()];
    let (mut unit_weight_difference, mut energy_rates_difference) = (0.0_f64, 0.0_f64);
    let ones = vec![1.0; dof];
    let (mut samples, mut singular_samples) = (0, 0);
    for sample in &path_run.report.samples {
        joint_torques(model, &mut data, &sample.q, load, &mut torques)?;
        let j: Matrix6xX<f64> =
            jacobian(model, &mut data, &sample.q, JacobianFrame::World)?.clone();
        let realised = &j * DVector::from_column_slice(&sample.joint_rates);
        let twist = Vector6::from_column_slice(realised.as_slice());
        if twist.amax() < 1e-9 {
            continue; // at rest: every distribution gives q_dot = 0
        }
        let partition = best_partition(&j, None, MAX_BLOCK_CONDITION)?.partition;
        // Seed 001, eq 17, as derived (eq 19 with A = T^2; the G0 of the
        // erratum restored).
        // Eq 17 has no answer where zero-torque joints alone can move
        // without moving the end effector (its k x k matrix is singular):
        // such samples are counted, not compared.
        let optimal = match partitioned.solve_energy_optimal(&j, &torques, &twist, &partition) {
            Ok(rates) => rates.to_vec(),
            Err(_) => {
                singular_samples += 1;
                continue;
            }
        };
        samples += 1;
        let f_optimal = energy_measure(&optimal, &torques)?;
        for ((_, weights), ratio) in rivals.iter().zip(ratios.iter_mut()) {
            let rates = least_norm
                .solve(&j, weights, &twist)?
                .solved()
                .map(<[f64]>::to_vec);
            if let Some(rates) = rates {
                ratio.push(energy_measure(&rates, &torques)? / f_optimal);
            }
        }
        // Eq 19 with unit weights against the pseudo-inverse J^+ V (SVD).
        let unit = partitioned
            .solve_with_paper_weights(&j, &ones, &twist, &partition)?
            .to_vec();
        let pinv = pseudo_inverse_rates(&j, &twist);
        let scale = pinv.amax().max(f64::MIN_POSITIVE);
        let distance = |rates: &[f64]| {
            rates
                .iter()
                .zip(pinv.iter())
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
                / scale
        };
        unit_weight_difference = unit_weight_difference.max(distance(&unit));
        energy_rates_difference = energy_rates_difference.max(distance(&optimal));
    }
    let rivals = rivals
        .iter()
        .zip(ratios)
        .map(|((name, _), mut ratio)| {
            ratio.sort_by(f64::total_cmp);
            InstantRival {
                name: (*name).into(),
                lower_samples: ratio.iter().filter(|&&r| r < 1.0 - EQUAL_F).count(),
                min_ratio: ratio.first().copied().unwrap_or(f64::NAN),
                median_ratio: ratio.get(ratio.len() / 2).copied().unwrap_or(f64::NAN),
            }
        })
        .collect();
    Ok(InstantComparison {
        samples,
        singular_samples,
        rivals,
        unit_weight_difference,
        energy_rates_difference,
    })
}

/// `J^+ V` by singular value decomposition (independent of the weighted
/// least norm and of the partitioned form).
fn pseudo_inverse_rates(j: &Matrix6xX<f64>, twist: &Vector6<f64>) -> DVector<f64> {
    let dense = DMatrix::from_column_slice(6, j.ncols(), j.as_slice());
    match dense.pseudo_inverse(1e-12) {
        Ok(pinv) => pinv * DVector::from_column_slice(twist.as_slice()),
        Err(_) => DVector::from_element(j.ncols(), f64::NAN),
    }
}

impl InstantComparison {
    /// The two findings: eq 17 minimal at each instant (against the other
    /// distributions at identical configurations and twists), and unit
    /// weights giving the minimum-norm rates.
    pub fn findings(&self) -> Vec<Finding> {
        let minimal = self.samples > 0
            && self
                .rivals
                .iter()
                .all(|r| r.lower_samples == 0 && r.min_ratio.is_finite());
        let listed = self
            .rivals
            .iter()
            .map(|r| {
                format!(
                    "{}: F/F_eq17 >= {:.4} (median {:.3}), lower at {} samples",
                    r.name, r.min_ratio, r.median_ratio, r.lower_samples
                )
            })
            .collect::<Vec<_>>()
            .join("; ");
        let unit_holds = self.unit_weight_difference <= 1e-9;
        vec![
            Finding::new(
                "seed 001, sec 2, eq 17: the energy-optimal rates give the least F (eq 9) at each \
                 instant, for the same configuration and the same end-effector twist",
                format!(
                    "at the {} configurations and realised twists of the energy-optimal run, \
                     the load's static torques, eq 17 (no torque floor, best-conditioned \
                     partition) against each distribution solved at the same (q, V): {listed}; \
                     eq 17 singular (zero torques) at {} samples, left out",
                    self.samples, self.singular_samples
                ),
                FindingStatus::from_holds(minimal),
            ),
            Finding::new(
                "seed 001, secs 2-3, eq 19: with all weights 1 the distribution is the \
                 minimum-norm solution (the pseudo-inverse's rates)",
                format!(
                    "eq 19 with A_Q = A_p = 1 against J^+ V (singular value decomposition) at \
                     the same {} (q, V): largest difference {:.1e} of the largest rate; eq 17's \
                     energy weights, for scale, lie {:.2} from J^+ V",
                    self.samples, self.unit_weight_difference, self.energy_rates_difference
                ),
                FindingStatus::from_holds(unit_holds && self.energy_rates_difference > 1e-3),
            ),
        ]
    }
}
