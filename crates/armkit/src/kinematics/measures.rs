//! Dexterity measures of a Jacobian: singular values, Yoshikawa's
//! manipulability, condition number.
//!
//! These take any Jacobian (6 x n, or a row subset for a reduced task) and
//! work on its singular values, computed by SVD (they allocate).

use crate::math::DMatrix;
use nalgebra::{Dim, Matrix, RawStorage};

/// Singular values of `jacobian`, largest first; `min(rows, cols)` of them.
pub fn singular_values<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(
    jacobian: &Matrix<f64, R, C, S>,
) -> Vec<f64> {
    let (rows, cols) = jacobian.shape();
    let copy = DMatrix::from_fn(rows, cols, |r, c| jacobian[(r, c)]);
    let mut values: Vec<f64> = copy
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    values.sort_by(|a, b| b.total_cmp(a));
    values
}

/// Yoshikawa's manipulability: the product of the singular values, i.e.
/// `sqrt(det(J J'))` when J has at least as many columns as rows (and
/// `sqrt(det(J' J))` otherwise). Units mix those of the rows; zero at a singularity.
pub fn manipulability<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(
    jacobian: &Matrix<f64, R, C, S>,
) -> f64 {
    singular_values(jacobian).iter().product()
}

/// Smallest singular value (distance to the nearest singular matrix in the
/// 2-norm).
pub fn smallest_singular_value<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(
    jacobian: &Matrix<f64, R, C, S>,
) -> f64 {
    singular_values(jacobian).last().copied().unwrap_or(0.0)
}

/// 2-norm condition number `sigma_max / sigma_min`; infinite at a singularity.
pub fn condition_number<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(
    jacobian: &Matrix<f64, R, C, S>,
) -> f64 {
    let values = singular_values(jacobian);
    match (values.first(), values.last()) {
        (Some(&largest), Some(&smallest)) if smallest > 0.0 => largest / smallest,
        _ => f64::INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Matrix6xX;

    #[test]
    fn diagonal_jacobian_measures() {
        let mut j = Matrix6xX::zeros(6);
        for (i, s) in [3.0, 2.0, 1.0, 0.5, 0.25, 4.0].iter().enumerate() {
            j[(i, i)] = *s;
        }
        assert_eq!(singular_values(&j), vec![4.0, 3.0, 2.0, 1.0, 0.5, 0.25]);
        assert!((manipulability(&j) - 3.0).abs() < 1e-12);
        assert!((condition_number(&j) - 16.0).abs() < 1e-12);
        assert!((smallest_singular_value(&j) - 0.25).abs() < 1e-15);
        j[(4, 4)] = 0.0;
        assert_eq!(condition_number(&j), f64::INFINITY);
        assert_eq!(manipulability(&j), 0.0);
    }

    /// A Jacobian with no rank at all (every singular value zero) is
    /// infinitely ill-conditioned, as one singular value at zero is: the
    /// ratio `0 / 0` is not a condition number.
    #[test]
    fn a_zero_jacobian_has_an_infinite_condition_number() {
        for columns in [1, 3, 6, 7] {
            let j = Matrix6xX::zeros(columns);
            assert_eq!(singular_values(&j), vec![0.0; columns.min(6)]);
            assert_eq!(condition_number(&j), f64::INFINITY, "6 x {columns}");
            assert_eq!(manipulability(&j), 0.0);
            assert_eq!(smallest_singular_value(&j), 0.0);
        }
    }
}
