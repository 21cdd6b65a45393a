//! The velocity-level pseudo-inverses the numeric methods are built from,
//! usable on their own: damped least squares and Chiaverini's
//! singularity-robust inverse, as one step or as a matrix.

use super::damping::ChiaveriniFilter;
use super::kernel::Kernel;
use crate::error::{check_finite, Error, Result};
use crate::math::{DMatrix, Matrix6xX, Vector6};

fn check_step_arguments(
    jacobian: &Matrix6xX<f64>,
    twist: &Vector6<f64>,
    step_len: usize,
) -> Result<()> {
    if jacobian.ncols() == 0 {
        return Err(Error::invalid_argument("jacobian", "has no columns"));
    }
    check_finite("jacobian", jacobian.as_slice())?;
    check_finite("twist", twist.as_slice())?;
    if step_len != jacobian.ncols() {
        return Err(Error::DimensionMismatch {
            what: "step",
            expected: jacobian.ncols(),
            got: step_len,
        });
    }
    Ok(())
}

/// Damped least squares (Nakamura; Wampler): writes
/// `dq = J' (J J' + lambda^2 I)^-1 v` into `step` (equivalently
/// `(J' J + lambda^2 I)^-1 J' v`, which is what is solved when J has fewer
/// than 6 columns).
///
/// `jacobian`: 6 x n, rows `[vx, vy, vz, wx, wy, wz]`; `twist`: the task
/// velocity or pose error in the same rows; `damping`: `lambda` (>= 0, in
/// singular-value units; 0 gives the pseudo-inverse); `step`: n entries,
/// rad or m (per unit time if `twist` is a velocity). Allocates nothing.
/// Errors: sizes, non-finite input, negative damping, or `lambda = 0` at a
/// singular Jacobian (`Error::Numerical`).
pub fn damped_least_squares_step(
    jacobian: &Matrix6xX<f64>,
    twist: &Vector6<f64>,
    damping: f64,
    step: &mut [f64],
) -> Result<()> {
    check_step_arguments(jacobian, twist, step.len())?;
    if !(damping.is_finite() && damping >= 0.0) {
        return Err(Error::invalid_argument(
            "damping",
            format!("must be finite and >= 0, got {damping}"),
        ));
    }
    let kernel = Kernel::new(&[1.0; 6], jacobian.ncols());
    let a0 = kernel.normal_matrix(jacobian);
    let rhs = kernel.rhs(jacobian, twist);
    let y = kernel
        .solve_damped(&a0, damping * damping, &rhs)
        .ok_or_else(|| Error::Numerical {
            context: "damped least squares step".into(),
            reason: "J J' + lambda^2 I is singular (use a damping > 0)".into(),
        })?;
    kernel.map_back(jacobian, &y, step);
    Ok(())
}

/// Chiaverini's singularity-robust inverse with numerical filtering (see
/// [`ChiaveriniFilter`]): writes `dq = J# v` into `step` and returns the
/// smallest singular value of J (of its first min(6, n) ones).
///
/// Same arguments and units as [`damped_least_squares_step`]; allocates nothing.
pub fn singularity_robust_step(
    jacobian: &Matrix6xX<f64>,
    twist: &Vector6<f64>,
    filter: &ChiaveriniFilter,
    step: &mut [f64],
) -> Result<f64> {
    check_step_arguments(jacobian, twist, step.len())?;
    filter.validate()?;
    let kernel = Kernel::new(&[1.0; 6], jacobian.ncols());
    let a0 = kernel.normal_matrix(jacobian);
    let rhs = kernel.rhs(jacobian, twist);
    let (y, sigma_min) = kernel.solve_filtered(&a0, &rhs, |s| filter.damping(s), filter.filter);
    kernel.map_back(jacobian, &y, step);
    Ok(sigma_min)
}

/// The damped pseudo-inverse `J' (J J' + lambda^2 I)^-1` as an n x 6 matrix
/// (column k is [`damped_least_squares_step`] of the k-th unit twist).
/// Allocates the result.
pub fn damped_pseudo_inverse(jacobian: &Matrix6xX<f64>, damping: f64) -> Result<DMatrix<f64>> {
    let mut inverse = DMatrix::zeros(jacobian.ncols(), 6);
    let mut column = vec![0.0; jacobian.ncols()];
    for k in 0..6 {
        damped_least_squares_step(jacobian, &Vector6::ith(k, 1.0), damping, &mut column)?;
        inverse.column_mut(k).copy_from_slice(&column);
    }
    Ok(inverse)
}

/// Chiaverini's singularity-robust inverse `J#` as an n x 6 matrix (column
/// k is [`singularity_robust_step`] of the k-th unit twist). Allocates the result.
pub fn singularity_robust_inverse(
    jacobian: &Matrix6xX<f64>,
    filter: &ChiaveriniFilter,
) -> Result<DMatrix<f64>> {
    let mut inverse = DMatrix::zeros(jacobian.ncols(), 6);
    let mut column = vec![0.0; jacobian.ncols()];
    for k in 0..6 {
        singularity_robust_step(jacobian, &Vector6::ith(k, 1.0), filter, &mut column)?;
        inverse.column_mut(k).copy_from_slice(&column);
    }
    Ok(inverse)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::NakamuraDamping;
    use crate::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};

    fn ur5_jacobian(q: &[f64]) -> Matrix6xX<f64> {
        let model = crate::robots::by_name("ur5").unwrap();
        let mut data = Data::new(&model);
        jacobian(&model, &mut data, q, JacobianFrame::World)
            .unwrap()
            .clone()
    }

    #[test]
    fn zero_damping_is_the_inverse_of_a_square_jacobian() {
        let j = ur5_jacobian(&[0.1, -1.0, 1.2, -0.4, 1.1, 0.3]);
        let v = Vector6::new(0.1, -0.2, 0.05, 0.3, 0.0, -0.1);
        let mut dq = vec![0.0; 6];
        damped_least_squares_step(&j, &v, 0.0, &mut dq).unwrap();
        let back = &j * nalgebra::DVector::from_column_slice(&dq);
        for i in 0..6 {
            assert!((back[i] - v[i]).abs() < 1e-10, "{back:?} vs {v:?}");
        }
    }

    #[test]
    fn damped_inverse_matches_the_svd_formula() {
        let j = ur5_jacobian(&[0.4, -0.7, 0.9, 0.2, -1.3, 0.6]);
        let lambda = 0.07;
        let inverse = damped_pseudo_inverse(&j, lambda).unwrap();
        let dense = DMatrix::from_column_slice(6, 6, j.as_slice());
        let svd = dense.clone().svd(true, true);
        let (u, vt) = (svd.u.unwrap(), svd.v_t.unwrap());
        let mut expected = DMatrix::zeros(6, 6);
        for i in 0..6 {
            let s = svd.singular_values[i];
            expected +=
                vt.row(i).transpose() * u.column(i).transpose() * (s / (s * s + lambda * lambda));
        }
        assert!((inverse - expected).amax() < 1e-10);
    }

    #[test]
    fn singularity_robust_inverse_damps_only_the_smallest_direction() {
        // At the UR5's wrist singularity (q5 = 0) J has a null direction.
        let j = ur5_jacobian(&[0.1, -1.0, 1.2, -0.4, 0.0, 0.3]);
        let filter = ChiaveriniFilter::default();
        let inverse = singularity_robust_inverse(&j, &filter).unwrap();
        assert!(inverse.iter().all(|v| v.is_finite()));
        let dense = DMatrix::from_column_slice(6, 6, j.as_slice());
        let svd = dense.clone().svd(true, true);
        let (u, vt) = (svd.u.unwrap(), svd.v_t.unwrap());
        let mut order: Vec<usize> = (0..6).collect();
        order.sort_by(|a, b| svd.singular_values[*b].total_cmp(&svd.singular_values[*a]));
        let smallest = order[5];
        let sigma_min = svd.singular_values[smallest];
        assert!(sigma_min < 1e-9);
        let lambda = filter.damping(sigma_min);
        assert!((lambda - filter.max_damping).abs() < 1e-6);
        let beta2 = filter.filter * filter.filter;
        let mut expected = DMatrix::zeros(6, 6);
        for i in 0..6 {
            let s = svd.singular_values[i];
            let extra = if i == smallest { lambda * lambda } else { 0.0 };
            expected +=
                vt.row(i).transpose() * u.column(i).transpose() * (s / (s * s + beta2 + extra));
        }
        assert!((inverse - expected).amax() < 1e-8);
        let mut dq = vec![0.0; 6];
        let sigma = singularity_robust_step(&j, &Vector6::x(), &filter, &mut dq).unwrap();
        assert!(sigma < 1e-6);
    }

    #[test]
    fn nakamura_damping_grows_below_the_threshold() {
        let d = NakamuraDamping::default();
        assert_eq!(d.damping(2.0 * d.threshold), 0.0);
        assert!((d.damping(0.0) - d.max_damping).abs() < 1e-15);
        assert!((d.damping(0.5 * d.threshold) - 0.5 * d.max_damping).abs() < 1e-15);
        let singular = ur5_jacobian(&[0.1, -1.0, 1.2, -0.4, 0.0, 0.3]);
        assert!((d.damping_at(&singular) - d.max_damping).abs() < 1e-6);
    }

    #[test]
    fn step_arguments_are_checked() {
        let j = ur5_jacobian(&[0.0; 6]);
        let mut short = vec![0.0; 5];
        let e = damped_least_squares_step(&j, &Vector6::x(), 0.1, &mut short).unwrap_err();
        assert!(
            e.to_string().contains("step: expected 6 values, got 5"),
            "{e}"
        );
        let mut dq = vec![0.0; 6];
        let e = damped_least_squares_step(&j, &Vector6::x(), -1.0, &mut dq).unwrap_err();
        assert!(e.to_string().contains("damping"), "{e}");
        let mut nan = Vector6::x();
        nan[3] = f64::NAN;
        let e =
            singularity_robust_step(&j, &nan, &ChiaveriniFilter::default(), &mut dq).unwrap_err();
        assert!(e.to_string().contains("twist[3] is not finite"), "{e}");
    }

    #[test]
    fn joint_space_form_solves_a_short_jacobian() {
        // arm4 (4 joints): the step is (J'J + mu I)^-1 J' v.
        let model = crate::robots::by_name("arm4").unwrap();
        let mut data = Data::new(&model);
        let q = [0.3, -0.8, 0.4, 0.5];
        let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
            .unwrap()
            .clone();
        let dense = DMatrix::from_column_slice(6, 4, j.as_slice());
        let v = Vector6::new(0.01, -0.02, 0.0, 0.1, 0.0, 0.05);
        let lambda = 0.01;
        let normal = dense.transpose() * &dense + DMatrix::identity(4, 4) * (lambda * lambda);
        let expected = normal
            .lu()
            .solve(&(dense.transpose() * nalgebra::DVector::from_column_slice(v.as_slice())))
            .unwrap();
        let mut dq = vec![0.0; 4];
        damped_least_squares_step(&j, &v, lambda, &mut dq).unwrap();
        for i in 0..4 {
            assert!((dq[i] - expected[i]).abs() < 1e-12);
        }
        let _ = forward_kinematics(&model, &mut data, &q).unwrap();
    }
}
