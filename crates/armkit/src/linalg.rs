//! Linear-algebra kernels of the velocity-level solvers: the 6 x 6 Gram
//! matrix of a Jacobian, its (damped) Cholesky solve, Yoshikawa's
//! manipulability, and the in-place Cholesky solve of a small system.
//!
//! Every kernel here allocates nothing and returns a typed outcome: a
//! numerically singular matrix is [`Solve::Singular`] with the smallest
//! singular value, never an `Err` (an `Err` from armkit always means the
//! caller's input was wrong). Each kernel has one documented singularity
//! threshold:
//!
//! | kernel | singular when | threshold |
//! |---|---|---|
//! | [`factor_gram`] | `min L_ii^2 < t max G_ii` | caller's `t`; [`WEIGHTED_GRAM_THRESHOLD`] (1e-12) for the weighted least norm, [`GRAM_THRESHOLD`] (1e-14) for the generalized Jacobian |
//! | [`cholesky_solve_in_place`] | a pivot `<= t max M_ii` | [`GRAM_THRESHOLD`] (1e-14) |
//!
//! Frames and units are the caller's: a Jacobian is 6 x n with rows
//! `[vx, vy, vz, wx, wy, wz]` (world or inertial frame), a twist `[v; w]`
//! (m/s, rad/s), joint rates rad/s or m/s.
//!
//! ```
//! use armkit::linalg::{damped_least_squares_rates, manipulability, Solve, GRAM_THRESHOLD};
//! use armkit::math::{Matrix6xX, Vector6};
//! let j = Matrix6xX::from_fn(6, |r, c| if r == c { 2.0 } else { 0.0 });
//! assert!((manipulability(&j) - 64.0).abs() < 1e-12);
//! let twist = Vector6::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
//! let mut rates = [0.0; 6];
//! let outcome = damped_least_squares_rates(&j, &twist, 0.0, GRAM_THRESHOLD, &mut rates);
//! assert_eq!(outcome, Solve::Solved(()));
//! assert!((rates[0] - 0.5).abs() < 1e-15);
//! // A rank-deficient Jacobian is an outcome, not an error.
//! let flat = Matrix6xX::<f64>::zeros(6);
//! assert!(damped_least_squares_rates(&flat, &twist, 0.0, GRAM_THRESHOLD, &mut rates).is_singular());
//! ```

use std::fmt;

use nalgebra::{Cholesky, U6};

use crate::math::{DMatrix, DVector, Matrix6, Matrix6xX, Vector6};

/// Singularity threshold of the weighted least-norm Gram matrix
/// `J A^-1 J'` (see [`factor_gram`]): about the reciprocal of the largest
/// acceptable condition number. Dimensionless.
pub const WEIGHTED_GRAM_THRESHOLD: f64 = 1e-12;

/// Singularity threshold of the generalized Jacobian's Gram matrix
/// `J* J*' + lambda^2 I` and of seed 001's eq 19 system (see
/// [`factor_gram`], [`cholesky_solve_in_place`]). Dimensionless.
pub const GRAM_THRESHOLD: f64 = 1e-14;

/// The outcome of a kernel that inverts a matrix: solved (with its value),
/// or numerically singular.
#[derive(Clone, Copy, Debug, PartialEq)]
#[must_use]
pub enum Solve<T> {
    /// The matrix was regular; the value computed.
    Solved(T),
    /// The matrix was numerically singular (below the kernel's threshold).
    Singular {
        /// Smallest singular value of the matrix whose Gram matrix was
        /// factored (e.g. of `J A^-1/2`), in its units; 0 for a rank-deficient one.
        smallest_singular_value: f64,
    },
}

impl<T> Solve<T> {
    /// The value, if solved.
    pub fn solved(self) -> Option<T> {
        match self {
            Solve::Solved(value) => Some(value),
            Solve::Singular { .. } => None,
        }
    }

    /// True when singular.
    pub fn is_singular(&self) -> bool {
        matches!(self, Solve::Singular { .. })
    }

    /// The value mapped by `f`, the singular outcome kept.
    pub fn map<U>(self, f: impl FnOnce(T) -> U) -> Solve<U> {
        match self {
            Solve::Solved(value) => Solve::Solved(f(value)),
            Solve::Singular {
                smallest_singular_value,
            } => Solve::Singular {
                smallest_singular_value,
            },
        }
    }

    /// `solved` or `singular`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Solve::Solved(_) => "solved",
            Solve::Singular { .. } => "singular",
        }
    }
}

impl<T> fmt::Display for Solve<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Solve::Solved(_) => f.write_str("solved"),
            Solve::Singular {
                smallest_singular_value,
            } => write!(
                f,
                "singular (smallest singular value {smallest_singular_value:.3e})"
            ),
        }
    }
}

/// `J J' = sum_i J_i J_i'` (6 x 6, symmetric) from the columns of a 6 x n
/// Jacobian. Allocates nothing.
pub fn gram(jacobian: &Matrix6xX<f64>) -> Matrix6<f64> {
    let mut gram = Matrix6::zeros();
    for column in jacobian.column_iter() {
        gram.ger(1.0, &column, &column, 1.0);
    }
    gram
}

/// `J A^-1 J' = sum_i (1 / a_i) J_i J_i'` (6 x 6, symmetric) from the
/// columns `J_i` and the inverse weights `1 / a_i` (0 for a locked joint,
/// which drops out). Only the lower triangle is accumulated (21 of 36
/// products per column), then mirrored. Allocates nothing.
pub fn weighted_gram(jacobian: &Matrix6xX<f64>, inverse_weights: &[f64]) -> Matrix6<f64> {
    let mut lower = [[0.0_f64; 6]; 6];
    for (column, &inv) in jacobian.column_iter().zip(inverse_weights) {
        if inv != 0.0 {
            for r in 0..6 {
                let scaled = inv * column[r];
                for (c, entry) in lower[r].iter_mut().enumerate().take(r + 1) {
                    *entry += scaled * column[c];
                }
            }
        }
    }
    Matrix6::from_fn(|r, c| if c <= r { lower[r][c] } else { lower[c][r] })
}

/// Cholesky factor of a symmetric positive semi-definite 6 x 6 Gram matrix
/// `G` (e.g. `J A^-1 J' + lambda^2 I`), or [`Solve::Singular`] when the
/// smallest pivot squared is below `threshold` times the largest diagonal
/// entry (`min L_ii^2 < t max G_ii`, about `1 / cond(G) < t`), or when `G`
/// is not positive definite. The singular outcome carries the square root of
/// `G`'s smallest eigenvalue (the smallest singular value of `J A^-1/2`),
/// computed only then. Allocates nothing.
pub fn factor_gram(gram: &Matrix6<f64>, threshold: f64) -> Solve<Cholesky<f64, U6>> {
    let singular = || Solve::Singular {
        smallest_singular_value: smallest_singular_value_of_gram(gram),
    };
    let largest_diagonal = gram.diagonal().max();
    if largest_diagonal.is_nan() || largest_diagonal <= 0.0 {
        return singular();
    }
    let Some(cholesky) = Matrix6::cholesky(*gram) else {
        return singular();
    };
    let smallest_pivot = cholesky.l_dirty().diagonal().min();
    if smallest_pivot * smallest_pivot < threshold * largest_diagonal {
        return singular();
    }
    Solve::Solved(cholesky)
}

/// `sqrt(max(0, lambda_min(G)))` of a symmetric 6 x 6 `G`; 0 if not finite.
fn smallest_singular_value_of_gram(gram: &Matrix6<f64>) -> f64 {
    if !gram.iter().all(|v| v.is_finite()) {
        return 0.0;
    }
    gram.symmetric_eigenvalues().min().max(0.0).sqrt()
}

/// Damped least-squares joint rates `rates = J' (J J' + lambda^2 I)^-1 twist`
/// of a 6 x n Jacobian (the pseudo-inverse for `damping` 0 and n >= 6),
/// written into `rates` (n entries, unchanged when singular). Singular as
/// [`factor_gram`] with `threshold`. Allocates nothing.
pub fn damped_least_squares_rates(
    jacobian: &Matrix6xX<f64>,
    twist: &Vector6<f64>,
    damping: f64,
    threshold: f64,
    rates: &mut [f64],
) -> Solve<()> {
    let mut gram = gram(jacobian);
    let lambda_squared = damping * damping;
    for i in 0..6 {
        gram[(i, i)] += lambda_squared;
    }
    factor_gram(&gram, threshold).map(|cholesky| {
        let y = cholesky.solve(twist);
        for (rate, column) in rates.iter_mut().zip(jacobian.column_iter()) {
            *rate = column.dot(&y);
        }
    })
}

/// Yoshikawa's manipulability `sqrt(det(J J'))` of a 6 x n Jacobian (units
/// mix those of its rows); 0 at a singularity. Allocates nothing (for other
/// shapes, [`crate::kinematics::manipulability`] works from the singular
/// values).
pub fn manipulability(jacobian: &Matrix6xX<f64>) -> f64 {
    gram(jacobian).determinant().max(0.0).sqrt()
}

/// Solves `M x = b` in place for a symmetric positive definite `M` (its
/// leading `n x n` block), by Cholesky: `M` is overwritten by its factor,
/// `b` by `x`. [`Solve::Singular`] when a pivot is at or below
/// [`GRAM_THRESHOLD`] times the largest diagonal entry; its
/// `smallest_singular_value` is then the square root of the failing pivot
/// (an upper bound on `M`'s smallest singular value's square root, 0 if not
/// positive). Allocates nothing.
pub fn cholesky_solve_in_place(m: &mut DMatrix<f64>, b: &mut DVector<f64>, n: usize) -> Solve<()> {
    if n == 0 {
        return Solve::Solved(());
    }
    let largest = (0..n).map(|i| m[(i, i)]).fold(0.0, f64::max);
    if largest.is_nan() || largest <= 0.0 {
        return Solve::Singular {
            smallest_singular_value: 0.0,
        };
    }
    let tolerance = GRAM_THRESHOLD * largest;
    for j in 0..n {
        let mut diagonal = m[(j, j)];
        for p in 0..j {
            diagonal -= m[(j, p)] * m[(j, p)];
        }
        if diagonal.is_nan() || diagonal <= tolerance {
            return Solve::Singular {
                smallest_singular_value: diagonal.max(0.0).sqrt(),
            };
        }
        let pivot = diagonal.sqrt();
        m[(j, j)] = pivot;
        for i in j + 1..n {
            let mut value = m[(i, j)];
            for p in 0..j {
                value -= m[(i, p)] * m[(j, p)];
            }
            m[(i, j)] = value / pivot;
        }
    }
    // Forward then back substitution with L and L'.
    for i in 0..n {
        let mut value = b[i];
        for p in 0..i {
            value -= m[(i, p)] * b[p];
        }
        b[i] = value / m[(i, i)];
    }
    for i in (0..n).rev() {
        let mut value = b[i];
        for p in i + 1..n {
            value -= m[(p, i)] * b[p];
        }
        b[i] = value / m[(i, i)];
    }
    Solve::Solved(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn in_place_cholesky_solves_and_detects_singularity() {
        let mut m = DMatrix::from_row_slice(3, 3, &[4.0, 2.0, 0.6, 2.0, 5.0, 1.0, 0.6, 1.0, 3.0]);
        let original = m.clone();
        let x = DVector::from_vec(vec![1.0, -2.0, 0.5]);
        let mut b = &original * &x;
        assert_eq!(
            cholesky_solve_in_place(&mut m, &mut b, 3),
            Solve::Solved(())
        );
        assert!((b - x).norm() < 1e-14);
        let mut singular = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        let mut b = DVector::from_vec(vec![1.0, 1.0]);
        assert!(cholesky_solve_in_place(&mut singular, &mut b, 2).is_singular());
    }

    #[test]
    fn gram_factor_reports_the_smallest_singular_value() {
        // J = diag(3, 2, 1, 1, 1, 0): rank 5, smallest singular value 0.
        let mut j = Matrix6xX::zeros(6);
        for (i, s) in [3.0, 2.0, 1.0, 1.0, 1.0, 0.0].iter().enumerate() {
            j[(i, i)] = *s;
        }
        let outcome = factor_gram(&gram(&j), WEIGHTED_GRAM_THRESHOLD);
        assert!(
            matches!(outcome, Solve::Singular { smallest_singular_value } if smallest_singular_value < 1e-12)
        );
        j[(5, 5)] = 0.5;
        assert!(!factor_gram(&gram(&j), WEIGHTED_GRAM_THRESHOLD).is_singular());
        assert!((manipulability(&j) - 3.0).abs() < 1e-12);
        assert_eq!(weighted_gram(&j, &[1.0; 6]), gram(&j));
    }
}
