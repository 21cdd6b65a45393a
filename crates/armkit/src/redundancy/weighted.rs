//! The weighted least-norm solution `q_dot = A^-1 J' (J A^-1 J')^-1 V` and its
//! damped form, with workspaces sized once.

use super::{check_jacobian, Damping, JointWeights, SolverOptions};
use crate::error::{check_finite, check_finite_vector, Error, Result};
use crate::linalg::{factor_gram, weighted_gram, Solve};
use crate::math::{DMatrix, DVector, Matrix6xX, Vector6};

/// Weighted least-norm redundancy resolution for a fixed number of joints.
///
/// Given the 6 x n world-frame Jacobian `J` (rows `[vx, vy, vz, wx, wy, wz]`),
/// positive weights `A = diag(a_i)` and an end-effector twist `V` (m/s, rad/s),
/// [`WeightedLeastNorm::solve`] returns the joint velocities (rad/s or m/s)
/// that meet `J q_dot = V` with the least cost `q_dot' A q_dot` (seed 001,
/// eq 18; with `a_i = tau_i^2` the energy measure of eq 9):
///
/// `q_dot = A^-1 J' (J A^-1 J')^-1 V`.
///
/// With all weights 1 this is the Moore-Penrose pseudo-inverse (minimum
/// norm); a locked joint (`A^-1` entry 0) gets exactly zero velocity. The
/// 6 x 6 matrix `J A^-1 J'` is formed column by column and factored by a
/// fixed-size Cholesky decomposition on the stack: a solve allocates nothing
/// and costs O(36 n).
///
/// ```
/// use armkit::math::{Matrix6xX, Vector6};
/// use armkit::redundancy::{Damping, JointWeights, SolverOptions, WeightedLeastNorm};
/// let j = Matrix6xX::from_fn(7, |r, c| if r == c { 1.0 } else if (r, c) == (0, 6) { 0.5 } else { 0.0 });
/// let twist = Vector6::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
/// let mut solver = WeightedLeastNorm::new(7, SolverOptions::default()).unwrap();
/// let q_dot = solver.solve(&j, &JointWeights::uniform(7), &twist).unwrap().solved().unwrap().to_vec();
/// // Joints 0 and 6 share the x motion: 1 = q0 + 0.5 q6, least norm.
/// assert!((q_dot[0] + 0.5 * q_dot[6] - 1.0).abs() < 1e-12);
/// assert!((q_dot[6] - 0.5 * q_dot[0]).abs() < 1e-12); // (q0, q6) parallel to (1, 0.5)
/// ```
#[derive(Clone, Debug)]
pub struct WeightedLeastNorm {
    dof: usize,
    options: SolverOptions,
    /// The solution, rad/s or m/s.
    velocities: DVector<f64>,
    /// `(J A^-1 J' + lambda^2 I)^-1 J_i` for each column, for the projector.
    solved_columns: Matrix6xX<f64>,
    /// The null-space projector `N = I - A^-1 J' (J A^-1 J')^-1 J` (n x n).
    projector: DMatrix<f64>,
    /// Damping `lambda` used by the last solve (0 when exact).
    damping: f64,
}

impl WeightedLeastNorm {
    /// A solver for `dof` joints (>= 1). Errors: `dof` = 0, invalid options.
    pub fn new(dof: usize, options: SolverOptions) -> Result<Self> {
        options.validate()?;
        if dof == 0 {
            return Err(Error::invalid_argument("dof", "must be at least 1"));
        }
        Ok(WeightedLeastNorm {
            dof,
            options,
            velocities: DVector::zeros(dof),
            solved_columns: Matrix6xX::zeros(dof),
            projector: DMatrix::zeros(dof, dof),
            damping: 0.0,
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The options.
    pub fn options(&self) -> &SolverOptions {
        &self.options
    }

    /// Damping `lambda` used by the last solve (0 for an exact solve).
    pub fn last_damping(&self) -> f64 {
        self.damping
    }

    /// Joint velocities (rad/s or m/s) meeting `J q_dot = V` with the least
    /// weighted cost: `q_dot = A^-1 J' (J A^-1 J')^-1 V` (damped if the
    /// options say so), or [`Solve::Singular`] when `J A^-1 J'` is
    /// numerically singular (the unlocked joints' Jacobian has rank < 6; see
    /// [`SolverOptions::singular_threshold`]). Allocates nothing.
    ///
    /// Errors (bad input only): sizes (`jacobian` 6 x dof, `weights` for dof
    /// joints), NaN or infinite entries.
    pub fn solve(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &JointWeights,
        twist: &Vector6<f64>,
    ) -> Result<Solve<&[f64]>> {
        self.solve_internal(jacobian, weights, twist, None)
    }

    /// The solution closest to `preferred` (rad/s or m/s) in the weighted
    /// metric: `q_dot = z + A^-1 J' (J A^-1 J')^-1 (V - J z)` with
    /// `z = preferred`, i.e. the least-norm solution plus the projection
    /// `N z` of `z` onto the null space of `J` (Liegeois' gradient projection
    /// when `z` is a scaled gradient, see the `nullspace` module). Allocates nothing.
    ///
    /// Errors: as [`WeightedLeastNorm::solve`], and `preferred` of the wrong
    /// size or not finite.
    pub fn solve_toward(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &JointWeights,
        twist: &Vector6<f64>,
        preferred: &[f64],
    ) -> Result<Solve<&[f64]>> {
        check_finite_vector("preferred", preferred, self.dof)?;
        self.solve_internal(jacobian, weights, twist, Some(preferred))
    }

    /// The weighted null-space projector `N = I - A^-1 J' (J A^-1 J')^-1 J`
    /// (n x n, damped if the options say so): `J N = 0` when undamped, and
    /// `N z` is the motion nearest `z` (in the metric `A`) that does not move
    /// the end effector. Allocates nothing. Errors and the singular outcome:
    /// as [`WeightedLeastNorm::solve`].
    pub fn null_space_projector(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &JointWeights,
    ) -> Result<Solve<&DMatrix<f64>>> {
        self.check_inputs(jacobian, weights)?;
        let cholesky = match self.factor(jacobian, weights) {
            Solve::Solved(cholesky) => cholesky,
            Solve::Singular {
                smallest_singular_value,
            } => {
                return Ok(Solve::Singular {
                    smallest_singular_value,
                })
            }
        };
        for (c, column) in jacobian.column_iter().enumerate() {
            let solved = cholesky.solve(&column.into_owned());
            self.solved_columns.set_column(c, &solved);
        }
        for (r, &row_factor) in weights.inverse().iter().enumerate() {
            let jr = jacobian.column(r);
            for c in 0..self.dof {
                let identity = if r == c { 1.0 } else { 0.0 };
                self.projector[(r, c)] =
                    identity - row_factor * jr.dot(&self.solved_columns.column(c));
            }
        }
        Ok(Solve::Solved(&self.projector))
    }

    fn check_inputs(&self, jacobian: &Matrix6xX<f64>, weights: &JointWeights) -> Result<()> {
        check_jacobian(jacobian, self.dof)?;
        weights.check_size("weights", self.dof)
    }

    /// `q_dot = z + A^-1 J' (J A^-1 J')^-1 (V - J z)`, `z = preferred` or 0.
    fn solve_internal(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &JointWeights,
        twist: &Vector6<f64>,
        preferred: Option<&[f64]>,
    ) -> Result<Solve<&[f64]>> {
        self.check_inputs(jacobian, weights)?;
        check_finite("twist", twist.as_slice())?;
        let cholesky = match self.factor(jacobian, weights) {
            Solve::Solved(cholesky) => cholesky,
            Solve::Singular {
                smallest_singular_value,
            } => {
                return Ok(Solve::Singular {
                    smallest_singular_value,
                })
            }
        };
        let residual = match preferred {
            Some(z) => {
                self.velocities.copy_from_slice(z);
                twist - jacobian * &self.velocities
            }
            None => {
                self.velocities.fill(0.0);
                *twist
            }
        };
        let multipliers = cholesky.solve(&residual);
        for ((velocity, column), &inv) in self
            .velocities
            .iter_mut()
            .zip(jacobian.column_iter())
            .zip(weights.inverse())
        {
            *velocity += inv * column.dot(&multipliers);
        }
        Ok(Solve::Solved(self.velocities.as_slice()))
    }

    /// Cholesky factor of `J A^-1 J' + lambda^2 I` ([`factor_gram`] with the
    /// options' threshold), setting `self.damping`.
    fn factor(
        &mut self,
        jacobian: &Matrix6xX<f64>,
        weights: &JointWeights,
    ) -> Solve<nalgebra::Cholesky<f64, nalgebra::U6>> {
        let mut gram = weighted_gram(jacobian, weights.inverse());
        self.damping = match self.options.damping {
            Damping::None => 0.0,
            Damping::Constant(lambda) => lambda,
            Damping::Adaptive { threshold, max } => {
                // Smallest singular value of J A^-1/2 = sqrt of the smallest
                // eigenvalue of J A^-1 J' (symmetric, fixed size: no allocation).
                let smallest = gram.symmetric_eigenvalues().min().max(0.0).sqrt();
                if smallest < threshold {
                    let ratio = smallest / threshold;
                    max * (1.0 - ratio * ratio).sqrt()
                } else {
                    0.0
                }
            }
        };
        let lambda_squared = self.damping * self.damping;
        for i in 0..6 {
            gram[(i, i)] += lambda_squared;
        }
        factor_gram(&gram, self.options.singular_threshold)
    }
}
