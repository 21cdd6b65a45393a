//! The velocity-level pseudo-inverses the numeric methods are built from,
//! usable on their own: damped least squares and Chiaverini's
//! singularity-robust inverse, as one step or as a matrix, and the
//! singularity separation with a damped reciprocal (one step).

use super::damping::{ChiaveriniFilter, DampedReciprocal};
use super::kernel::Kernel;
use crate::error::{check_finite, Error, Result};
use crate::math::{DMatrix, Matrix3, Matrix6xX, Vector3, Vector6};

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

/// The singularity-separation step with a damped reciprocal (seed 004's
/// reference [9], the comparator of its conclusion 1), for a 6-joint arm
/// whose last three axes meet (a spherical wrist): writes `dq` into `step`
/// and returns the smallest singular value of the wrist block.
///
/// The twist is moved to the wrist centre `c` (`v_c = v + w x (c - p_e)`),
/// where the Jacobian is block triangular, `[A B; C D]` with `A` the arm's
/// three columns' linear part, `B` the wrist's (zero on a fixed base: the
/// wrist axes pass through `c`), `C`, `D` the angular parts. The wrist is
/// solved first on the Schur complement `S = D - C A^-1 B` (`= D` when
/// `B = 0`, [9]'s separation), `dq_w = S^+ (w - C A^-1 v_c)`, with the SVD
/// `S = U diag(sigma) V'` and only the smallest singular value's reciprocal
/// damped ([`DampedReciprocal`]); then the arm, `dq_a = A^-1 (v_c - B dq_w)`.
/// The wrist centre is the point that the wrist columns move least (the
/// least-squares solution of `z_i x (c - p_e) = -J_v,i`, i = 4, 5, 6): the
/// axes' meeting point on a spherical wrist, read from the Jacobian alone.
/// On an attitude-held base (`J*`) the wrist columns' linear part at `c` is
/// the base's recoil, `B != 0`, which the Schur complement takes exactly.
///
/// `jacobian`: 6 x 6, rows `[vx, vy, vz, wx, wy, wz]` (world frame, at the
/// end effector); `twist`: `[v; w]` in the same rows; `step`: 6 entries,
/// rad/s (or rad per unit of the twist). Allocates nothing.
///
/// Errors: sizes (not 6 columns), non-finite input, bad damping parameters;
/// `Error::Numerical` when the wrist axes are all parallel (no centre) or
/// the arm block `A` is singular (an elbow or shoulder singularity, which
/// the method does not treat).
pub fn separated_damped_reciprocal_step(
    jacobian: &Matrix6xX<f64>,
    twist: &Vector6<f64>,
    damping: &DampedReciprocal,
    step: &mut [f64],
) -> Result<f64> {
    check_step_arguments(jacobian, twist, step.len())?;
    damping.validate()?;
    if jacobian.ncols() != 6 {
        return Err(Error::DimensionMismatch {
            what: "jacobian columns (singularity separation needs a 6-joint arm)",
            expected: 6,
            got: jacobian.ncols(),
        });
    }
    let numerical = |reason: &str| Error::Numerical {
        context: "singularity separation step".into(),
        reason: reason.into(),
    };
    let linear = |i: usize| jacobian.fixed_view::<3, 1>(0, i).into_owned();
    let angular = |i: usize| jacobian.fixed_view::<3, 1>(3, i).into_owned();
    // Wrist centre offset r = c - p_e: sum_i (|z_i|^2 I - z_i z_i') r =
    // sum_i z_i x J_v,i (normal equations of skew(z_i) r = -J_v,i).
    let mut normal = Matrix3::zeros();
    let mut rhs = Vector3::zeros();
    for i in 3..6 {
        let z = angular(i);
        normal += Matrix3::identity() * z.norm_squared() - z * z.transpose();
        rhs += z.cross(&linear(i));
    }
    let r = normal
        .try_inverse()
        .ok_or_else(|| numerical("the wrist axes are parallel: no wrist centre"))?
        * rhs;
    // Linear velocity of the wrist centre: v + w x r, column by column.
    let shifted = |i: usize| linear(i) + angular(i).cross(&r);
    let a = Matrix3::from_columns(&[shifted(0), shifted(1), shifted(2)]);
    let b = Matrix3::from_columns(&[shifted(3), shifted(4), shifted(5)]);
    let c = Matrix3::from_columns(&[angular(0), angular(1), angular(2)]);
    let d = Matrix3::from_columns(&[angular(3), angular(4), angular(5)]);
    let v = Vector3::new(twist[0], twist[1], twist[2]);
    let w = Vector3::new(twist[3], twist[4], twist[5]);
    let v_c = v + w.cross(&r);
    let a_inverse = a
        .try_inverse()
        .ok_or_else(|| numerical("the arm block is singular (elbow or shoulder singularity)"))?;
    let schur = d - c * a_inverse * b;
    let wrist_twist = w - c * (a_inverse * v_c);
    let svd = schur.svd(true, true);
    let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
        return Err(numerical("the SVD of the wrist block did not converge"));
    };
    let sigma = svd.singular_values;
    let smallest = sigma.imin();
    let sigma_min = sigma[smallest];
    let lambda = damping.damping(sigma_min);
    let mut dq_w = Vector3::zeros();
    for i in 0..3 {
        let reciprocal = if i == smallest {
            DampedReciprocal::reciprocal(sigma[i], lambda)
        } else {
            DampedReciprocal::reciprocal(sigma[i], 0.0)
        };
        let projection = u.column(i).dot(&wrist_twist);
        dq_w += v_t.row(i).transpose() * (reciprocal * projection);
    }
    let dq_a = a_inverse * (v_c - b * dq_w);
    step[..3].copy_from_slice(dq_a.as_slice());
    step[3..].copy_from_slice(dq_w.as_slice());
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
