//! Seed 001 as printed: six generalized joints, `k = n - 6` extra joints, and
//! the extra joints' velocities in closed form.
//!
//! Split the Jacobian's columns into the six generalized joints `q` and the
//! `k` extra joints `phi_p` (seed 001, eq 5): `V = G'0 q_dot + G'0p phi_dot`.
//! With `G'0` nonsingular, `G0 = G'0^-1` and `G0p = G'0^-1 G'0p` (eq 7),
//! `q_dot = G0 V - G0p phi_dot` (eqs 6, 8). Minimising
//! `F = q_dot' A_Q q_dot + phi_dot' A_p phi_dot` (eq 18) over `phi_dot`:
//! `dF/dphi_dot = -2 G0p' A_Q (G0 V - G0p phi_dot) + 2 A_p phi_dot = 0` (eqs 10-15), so
//!
//! `phi_dot = (A_p + G0p' A_Q G0p)^-1 G0p' A_Q G0 V` (eq 19).
//!
//! Erratum: eq 19 as printed drops the `G0` in front of `V`; eq 17 (the energy
//! weights `A = T^2`) prints it.
//!
//! Locking: seed 001's last sentence says the usual "locking of joints" is
//! the weights set to zero. In the paper's own parametrisation that holds:
//! with `A_Q = 0` (and `A_p > 0`) eq 19's right-hand side vanishes, so
//! `phi_dot = 0` and the `k` extra joints stay still while the six
//! generalized joints do the motion, `q_dot = G0 V` (eq 8)
//! ([`PartitionedSolver::solve_with_paper_weights`]). In the weighted least
//! norm over all joints ([`super::JointWeights`]) the same lock is an
//! infinite weight on the locked joints; both give the same velocities.

use super::{check_jacobian, JointWeights};
use crate::error::{check_finite, check_finite_vector, Error, Result};
use crate::linalg::{cholesky_solve_in_place, Solve};
use crate::math::{DMatrix, DVector, Matrix6, Matrix6xX, Vector6};

/// A split of a robot's joints into six generalized joints (seed 001's `q`)
/// and the `k = n - 6` extra joints (`phi_p`). Indices are 0-based joint
/// numbers, each list in increasing order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Partition {
    generalized: [usize; 6],
    extra: Vec<usize>,
}

impl Partition {
    /// The partition of `dof` joints (>= 6) whose generalized joints are
    /// `generalized` (six distinct indices below `dof`, any order); every
    /// other joint is extra.
    pub fn new(dof: usize, generalized: [usize; 6]) -> Result<Self> {
        if dof < 6 {
            return Err(Error::invalid_argument(
                "dof",
                format!("a partition needs at least 6 joints, got {dof}"),
            ));
        }
        let mut sorted = generalized;
        sorted.sort_unstable();
        if let Some(&bad) = sorted.iter().find(|&&j| j >= dof) {
            return Err(Error::invalid_argument(
                "generalized",
                format!("joint index {bad} is out of range for {dof} joints (0-based)"),
            ));
        }
        if sorted.windows(2).any(|pair| pair[0] == pair[1]) {
            return Err(Error::invalid_argument(
                "generalized",
                format!("the six generalized joints must be distinct, got {generalized:?}"),
            ));
        }
        let extra = (0..dof).filter(|j| !sorted.contains(j)).collect();
        Ok(Partition {
            generalized: sorted,
            extra,
        })
    }

    /// The six generalized joints (seed 001's `q`), increasing.
    pub fn generalized(&self) -> &[usize; 6] {
        &self.generalized
    }

    /// The `k = n - 6` extra joints (seed 001's `phi_p`), increasing.
    pub fn extra(&self) -> &[usize] {
        &self.extra
    }

    /// Number of joints, `6 + k`.
    pub fn dof(&self) -> usize {
        6 + self.extra.len()
    }

    /// The 6 x 6 block `G'0` of `jacobian`: the generalized joints' columns.
    fn block(&self, jacobian: &Matrix6xX<f64>) -> Matrix6<f64> {
        let mut block = Matrix6::zeros();
        for (c, &joint) in self.generalized.iter().enumerate() {
            block.set_column(c, &jacobian.column(joint));
        }
        block
    }
}

/// The best-conditioned partition and its block's 2-norm condition number.
#[derive(Clone, Debug, PartialEq)]
pub struct PartitionChoice {
    /// The partition.
    pub partition: Partition,
    /// `sigma_max / sigma_min` of the generalized joints' 6 x 6 block `G'0`.
    pub condition_number: f64,
}

/// The partition whose 6 x 6 block `G'0` (seed 001, eq 5) has the smallest
/// 2-norm condition number, over every choice of six unlocked joints
/// (locked joints in `weights`, if given, are always extra).
///
/// Cost: `C(m, 6)` singular value decompositions of a 6 x 6 matrix, `m` the
/// number of unlocked joints (84 for the 9-DOF gantry, 7 for a 7-DOF arm).
///
/// Errors: a Jacobian with fewer than 6 columns or non-finite entries;
/// fewer than 6 unlocked joints; and, when even the best block's condition
/// number exceeds `max_condition_number` (> 1), [`Error::Numerical`]: no
/// 6 x 6 block is nonsingular, i.e. the unlocked joints' Jacobian has rank < 6.
pub fn best_partition(
    jacobian: &Matrix6xX<f64>,
    weights: Option<&JointWeights>,
    max_condition_number: f64,
) -> Result<PartitionChoice> {
    let dof = jacobian.ncols();
    check_jacobian(jacobian, dof)?;
    check_max_condition(max_condition_number)?;
    if let Some(w) = weights {
        w.check_size("weights", dof)?;
    }
    let candidates: Vec<usize> = (0..dof)
        .filter(|&j| weights.is_none_or(|w| !w.is_locked(j)))
        .collect();
    if candidates.len() < 6 {
        return Err(Error::invalid_argument(
            "weights",
            format!(
                "only {} of {dof} joints are unlocked; a 6-D twist needs at least 6",
                candidates.len()
            ),
        ));
    }
    let mut best: Option<([usize; 6], f64)> = None;
    let mut picks = [0, 1, 2, 3, 4, 5];
    loop {
        let generalized = picks.map(|i| candidates[i]);
        let mut block = Matrix6::zeros();
        for (c, &joint) in generalized.iter().enumerate() {
            block.set_column(c, &jacobian.column(joint));
        }
        let condition = condition_number(&block);
        if best.is_none_or(|(_, c)| condition < c) {
            best = Some((generalized, condition));
        }
        if !next_combination(&mut picks, candidates.len()) {
            break;
        }
    }
    let (generalized, condition) = best.ok_or_else(|| Error::Numerical {
        context: "seed 001 partition".into(),
        reason: "no partition was evaluated".into(),
    })?;
    if condition.is_nan() || condition > max_condition_number {
        return Err(Error::Numerical {
            context: "seed 001 partition".into(),
            reason: format!(
                "no nonsingular 6 x 6 block of the Jacobian: the best, joints {generalized:?}, \
                 has condition number {condition:.3e} > {max_condition_number:.1e}; the \
                 unlocked joints' Jacobian has rank < 6 at this configuration"
            ),
        });
    }
    Ok(PartitionChoice {
        partition: Partition::new(dof, generalized)?,
        condition_number: condition,
    })
}

/// Advances `picks` (increasing indices below `n`) to the next combination
/// in lexicographic order; false after the last one.
fn next_combination(picks: &mut [usize; 6], n: usize) -> bool {
    let k = picks.len();
    let mut i = k;
    while i > 0 {
        i -= 1;
        if picks[i] < n - k + i {
            picks[i] += 1;
            for j in i + 1..k {
                picks[j] = picks[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

/// 2-norm condition number of a 6 x 6 matrix (infinite when singular).
fn condition_number(block: &Matrix6<f64>) -> f64 {
    let values = block.singular_values();
    let (largest, smallest) = (values.max(), values.min());
    if smallest > 0.0 {
        largest / smallest
    } else {
        f64::INFINITY
    }
}

fn check_max_condition(value: f64) -> Result<()> {
    if !(value.is_finite() && value > 1.0) {
        return Err(Error::invalid_argument(
            "max_condition_number",
            format!("must be finite and > 1, got {value}"),
        ));
    }
    Ok(())
}

/// Seed 001's partitioned solver (eqs 5-8, 17, 19), with workspaces sized
/// once for `n` joints.
///
/// Gives the same joint velocities as [`super::WeightedLeastNorm`] for any
/// valid partition (both minimise the same cost over the same solutions); it
/// is the paper's form, kept for fidelity and as an independent check. Only
/// the `k x k` system of eq 19 is solved (an in-place Cholesky on a
/// preallocated buffer), so a solve allocates nothing.
///
/// ```
/// use armkit::kinematics::{jacobian, Data, JacobianFrame};
/// use armkit::math::Vector6;
/// use armkit::redundancy::{best_partition, JointWeights, PartitionedSolver};
/// let model = armkit::robots::by_name("panda").unwrap();
/// let mut data = Data::new(&model);
/// let q = [0.1, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7];
/// let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap().clone();
/// let choice = best_partition(&j, None, 1e10).unwrap();
/// assert_eq!(choice.partition.extra().len(), 1); // k = 7 - 6
/// let mut solver = PartitionedSolver::new(7, 1e10).unwrap();
/// let twist = Vector6::new(0.05, 0.0, 0.0, 0.0, 0.0, 0.1);
/// let w = JointWeights::uniform(7);
/// let q_dot = solver.solve(&j, &w, &twist, &choice.partition).unwrap();
/// assert_eq!(q_dot.len(), 7);
/// ```
#[derive(Clone, Debug)]
pub struct PartitionedSolver {
    dof: usize,
    max_condition_number: f64,
    /// `G0p = G'0^-1 G'0p` (6 x k, eq 7).
    coupling: Matrix6xX<f64>,
    /// `A_p + G0p' A_Q G0p` (k x k, eq 19), factored in place.
    system: DMatrix<f64>,
    /// Right-hand side, then `phi_dot` (k).
    extra_velocities: DVector<f64>,
    /// The solution (n), rad/s or m/s.
    velocities: DVector<f64>,
    /// Condition number estimate of `G'0` from the last solve (1-norm).
    block_condition: f64,
    /// Squared torques for eq 17 (n).
    squared_torques: DVector<f64>,
}

impl PartitionedSolver {
    /// A solver for `dof` (>= 6) joints. A partition's block `G'0` counts as
    /// singular when its 1-norm condition number exceeds
    /// `max_condition_number` (> 1; `1e10` is a sound default).
    pub fn new(dof: usize, max_condition_number: f64) -> Result<Self> {
        check_max_condition(max_condition_number)?;
        if dof < 6 {
            return Err(Error::invalid_argument(
                "dof",
                format!("seed 001's partition needs at least 6 joints, got {dof}"),
            ));
        }
        let k = dof - 6;
        Ok(PartitionedSolver {
            dof,
            max_condition_number,
            coupling: Matrix6xX::zeros(k),
            system: DMatrix::zeros(k, k),
            extra_velocities: DVector::zeros(k),
            velocities: DVector::zeros(dof),
            block_condition: f64::NAN,
            squared_torques: DVector::zeros(dof),
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// 1-norm condition number `|G'0|_1 |G0|_1` of the last solve's block.
    pub fn last_block_condition(&self) -> f64 {
        self.block_condition
    }

    /// Joint velocities (rad/s or m/s) meeting `J q_dot = V` with the least
    /// cost `q_dot' A q_dot` (seed 001, eqs 8 and 19, corrected), for the
    /// world-frame Jacobian `jacobian` (6 x n), weights `weights` and twist
    /// `twist` (m/s, rad/s). Locked joints must be extra joints of
    /// `partition`; they get zero velocity. Allocates nothing.
    ///
    /// Errors: sizes, NaN, a locked generalized joint, a singular block `G'0`
    /// ([`Error::Numerical`], naming the joints: pick another partition, e.g.
    /// with [`best_partition`]).
    pub fn solve(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &JointWeights,
        twist: &Vector6<f64>,
        partition: &Partition,
    ) -> Result<&[f64]> {
        weights.check_size("weights", self.dof)?;
        self.solve_with_weights(jacobian, weights.values(), twist, partition)
    }

    /// Seed 001's energy-optimal distribution, eq 17: the weights are the
    /// squared joint torques `tau_i^2` (N^2 m^2 or N^2) exactly as printed,
    /// with no floor: zero torques are allowed as long as the `k x k` matrix
    /// `T_p^2 + G0p' T_Q^2 G0p` stays nonsingular (it is singular when some
    /// motion of zero-torque joints alone leaves the end effector still: then
    /// eq 9 cannot choose, and the error says so). The weighted form with a
    /// floor ([`super::TorqueFloor`]) converges to this as the floor goes to 0.
    pub fn solve_energy_optimal(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        torques: &[f64],
        twist: &Vector6<f64>,
        partition: &Partition,
    ) -> Result<&[f64]> {
        check_finite_vector("torques", torques, self.dof)?;
        // The weights are read from a separate buffer (sized once), so the
        // solution buffer can be written while they are in use.
        let mut squared = std::mem::take(&mut self.squared_torques);
        for (s, &t) in squared.iter_mut().zip(torques) {
            *s = t * t;
        }
        let result = self
            .solve_with_weights(jacobian, squared.as_slice(), twist, partition)
            .map(|_| ());
        self.squared_torques = squared;
        result?;
        Ok(self.velocities.as_slice())
    }

    /// Seed 001's eqs 8 and 19 with the paper's weights (eq 18, eq 20):
    /// `weights[i] = a_i >= 0` for every joint, finite, where the paper's
    /// `A_Q` are the generalized joints' entries and `A_p` the extra
    /// joints'. Unlike [`JointWeights`], zero is allowed: the paper's last
    /// sentence locks joints with zero weights, and `A_Q = 0`, `A_p > 0`
    /// gives exactly `phi_dot = 0` (the extra joints locked, the six
    /// generalized joints alone realise `V`). Allocates nothing.
    ///
    /// Errors: sizes, NaN, infinite or negative weights, a singular block
    /// `G'0`, and a singular `A_p + G0p' A_Q G0p` (e.g. `A_Q = 0` with a zero
    /// `A_p` entry: the cost cannot choose that joint's rate).
    ///
    /// ```
    /// use armkit::kinematics::{jacobian, Data, JacobianFrame};
    /// use armkit::math::Vector6;
    /// use armkit::redundancy::{Partition, PartitionedSolver};
    /// let model = armkit::robots::by_name("gantry9").unwrap();
    /// let mut data = Data::new(&model);
    /// let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    /// let j = jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap().clone();
    /// // The arm's six joints generalized, the gantry's three axes extra.
    /// let partition = Partition::new(9, [3, 4, 5, 6, 7, 8]).unwrap();
    /// let mut solver = PartitionedSolver::new(9, 1e10).unwrap();
    /// let twist = Vector6::new(0.1, 0.05, -0.05, 0.0, 0.0, 0.1);
    /// // A_Q = 0, A_p = 1: the extra joints are locked.
    /// let weights = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    /// let q_dot = solver.solve_with_paper_weights(&j, &weights, &twist, &partition).unwrap();
    /// assert_eq!(&q_dot[..3], &[0.0, 0.0, 0.0]);
    /// ```
    pub fn solve_with_paper_weights(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &[f64],
        twist: &Vector6<f64>,
        partition: &Partition,
    ) -> Result<&[f64]> {
        check_finite_vector("weights", weights, self.dof)?;
        if let Some((joint, value)) = weights.iter().enumerate().find(|&(_, &w)| w < 0.0) {
            return Err(Error::invalid_argument(
                "weights",
                format!("weight of joint {joint} must be >= 0 (seed 001, eq 18), got {value}"),
            ));
        }
        self.solve_with_weights(jacobian, weights, twist, partition)
    }

    /// Eqs 5-8 and 19 with per-joint weights `values` (`>= 0`, infinite =
    /// locked, which must be extra joints).
    fn solve_with_weights(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        values: &[f64],
        twist: &Vector6<f64>,
        partition: &Partition,
    ) -> Result<&[f64]> {
        check_jacobian(jacobian, self.dof)?;
        check_finite("twist", twist.as_slice())?;
        if partition.dof() != self.dof {
            return Err(Error::DimensionMismatch {
                what: "partition (joints)",
                expected: self.dof,
                got: partition.dof(),
            });
        }
        if let Some(&joint) = partition
            .generalized()
            .iter()
            .find(|&&j| !values[j].is_finite())
        {
            return Err(Error::invalid_argument(
                "partition",
                format!(
                    "joint {joint} is locked but is one of the generalized joints \
                     {:?}; seed 001's form locks extra joints only: choose a partition \
                     with it among the extras (best_partition does)",
                    partition.generalized()
                ),
            ));
        }
        // Eq 7: G0 = G'0^-1 (6 x 6, on the stack).
        let block = partition.block(jacobian);
        let block_singular = |condition: f64| Error::Numerical {
            context: "seed 001 partition".into(),
            reason: format!(
                "the generalized joints' block G'0 (joints {:?}) is singular \
                 (condition number {condition:.3e}): choose another partition",
                partition.generalized()
            ),
        };
        let inverse = block
            .try_inverse()
            .ok_or_else(|| block_singular(f64::INFINITY))?;
        self.block_condition = one_norm(&block) * one_norm(&inverse);
        if self.block_condition.is_nan() || self.block_condition > self.max_condition_number {
            return Err(block_singular(self.block_condition));
        }
        // Eq 7: G0p = G0 G'0p; eq 8's first term G0 V.
        for (c, &joint) in partition.extra().iter().enumerate() {
            let column = inverse * jacobian.column(joint);
            self.coupling.set_column(c, &column);
        }
        let base: Vector6<f64> = inverse * twist;
        // Eq 19 (corrected): (A_p + G0p' A_Q G0p) phi = G0p' A_Q G0 V.
        // A locked extra joint (infinite weight) gets a unit row and column
        // and a zero right-hand side: phi = 0 for it, the rest unaffected.
        let generalized_weights = partition.generalized().map(|j| values[j]);
        let k = partition.extra().len();
        for (r, &row_joint) in partition.extra().iter().enumerate() {
            let row_locked = !values[row_joint].is_finite();
            let gr = self.coupling.column(r);
            let mut rhs = 0.0;
            for m in 0..6 {
                rhs += gr[m] * generalized_weights[m] * base[m];
            }
            self.extra_velocities[r] = if row_locked { 0.0 } else { rhs };
            for (c, &col_joint) in partition.extra().iter().enumerate() {
                let col_locked = !values[col_joint].is_finite();
                self.system[(r, c)] = if row_locked || col_locked {
                    if r == c {
                        1.0
                    } else {
                        0.0
                    }
                } else {
                    let gc = self.coupling.column(c);
                    let mut sum = if r == c { values[row_joint] } else { 0.0 };
                    for m in 0..6 {
                        sum += gr[m] * generalized_weights[m] * gc[m];
                    }
                    sum
                };
            }
        }
        if let Solve::Singular {
            smallest_singular_value,
        } = cholesky_solve_in_place(&mut self.system, &mut self.extra_velocities, k)
        {
            return Err(Error::Numerical {
                context: "seed 001 eq 19".into(),
                reason: format!(
                    "A_p + G0p' A_Q G0p is singular (smallest pivot {:.1e}): some motion \
                     of zero-weight joints leaves the end effector still, so the cost \
                     cannot choose among the solutions (give those joints a weight > 0)",
                    smallest_singular_value * smallest_singular_value
                ),
            });
        }
        // Eq 8: q_dot = G0 V - G0p phi_dot.
        let mut generalized_velocities = base;
        for c in 0..k {
            generalized_velocities -= self.coupling.column(c) * self.extra_velocities[c];
        }
        for (m, &joint) in partition.generalized().iter().enumerate() {
            self.velocities[joint] = generalized_velocities[m];
        }
        for (c, &joint) in partition.extra().iter().enumerate() {
            self.velocities[joint] = self.extra_velocities[c];
        }
        Ok(self.velocities.as_slice())
    }
}

/// 1-norm (largest absolute column sum) of a 6 x 6 matrix.
fn one_norm(m: &Matrix6<f64>) -> f64 {
    m.column_iter()
        .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combinations_enumerate_all_subsets() {
        let mut picks = [0, 1, 2, 3, 4, 5];
        let mut count = 1;
        while next_combination(&mut picks, 9) {
            assert!(picks.windows(2).all(|p| p[0] < p[1]) && picks[5] < 9);
            count += 1;
        }
        assert_eq!(count, 84);
        let mut picks = [0, 1, 2, 3, 4, 5];
        assert!(!next_combination(&mut picks, 6));
    }

    #[test]
    fn partition_rejects_bad_indices() {
        assert!(Partition::new(9, [0, 1, 2, 3, 4, 9])
            .unwrap_err()
            .to_string()
            .contains("out of range"));
        assert!(Partition::new(9, [0, 1, 2, 3, 4, 4])
            .unwrap_err()
            .to_string()
            .contains("distinct"));
        let p = Partition::new(9, [8, 0, 4, 3, 2, 1]).unwrap();
        assert_eq!(p.generalized(), &[0, 1, 2, 3, 4, 8]);
        assert_eq!(p.extra(), &[5, 6, 7]);
    }
}
