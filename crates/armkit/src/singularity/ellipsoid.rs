//! Yoshikawa's manipulability ellipsoid of a Jacobian's translational or
//! rotational part.

use crate::error::{check_finite, Result};
use crate::math::{Matrix3, Matrix6xX, Vector3};

/// Which three rows of a `[vx vy vz wx wy wz]` Jacobian.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JacobianPart {
    /// Rows 0..3: the end-effector's linear velocity (m/s per rad/s or m/s).
    Translational,
    /// Rows 3..6: its angular velocity (rad/s per rad/s or m/s).
    Rotational,
}

/// The velocity ellipsoid `{ J_p q_dot : |q_dot| <= 1 }` of a 3 x n part `J_p`
/// of a Jacobian: principal axes and semi-axis lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipsoid {
    /// Principal axes: unit vectors in the Jacobian's frame (the world frame
    /// for [`crate::kinematics::JacobianFrame::World`]), mutually
    /// orthogonal, in the order of `radii`.
    pub axes: [Vector3<f64>; 3],
    /// Semi-axis lengths: the singular values of `J_p` (m/rad for the
    /// translational part of a revolute arm, rad/rad for the rotational),
    /// largest first; zero along a direction the part cannot move in (from
    /// the eigenvalues of `J_p J_p'`: radii below about 1e-8 of the largest
    /// are at rounding level).
    pub radii: [f64; 3],
}

impl Ellipsoid {
    /// The product of the radii: the part's manipulability `sqrt(det(J_p J_p'))`.
    pub fn volume_measure(&self) -> f64 {
        self.radii.iter().product()
    }

    /// Smallest radius over largest (0 at a singularity of the part, 1 when
    /// isotropic); 0 for an all-zero part.
    pub fn isotropy(&self) -> f64 {
        if self.radii[0] > 0.0 {
            self.radii[2] / self.radii[0]
        } else {
            0.0
        }
    }
}

/// The manipulability ellipsoid of `part` of `jacobian` (6 x n, rows
/// `[vx vy vz wx wy wz]`): the eigen-decomposition of the 3 x 3 matrix
/// `J_p J_p'`, whose eigenvalues are the squared singular values of `J_p`.
/// Computed on the stack; allocates nothing.
///
/// Errors: a Jacobian with non-finite entries.
///
/// ```
/// use armkit::singularity::{manipulability_ellipsoid, JacobianPart};
/// use armkit::{jacobian, Data, JacobianFrame};
/// let puma = armkit::robots::puma560()?;
/// let mut data = Data::new(&puma);
/// let j = jacobian(&puma, &mut data, &[0.0, 0.5, -0.4, 0.0, 0.6, 0.0], JacobianFrame::World)?;
/// let e = manipulability_ellipsoid(j, JacobianPart::Translational)?;
/// assert!(e.radii[0] >= e.radii[1] && e.radii[1] >= e.radii[2] && e.radii[2] > 0.0);
/// assert!((e.axes[0].norm() - 1.0).abs() < 1e-12);
/// # Ok::<(), armkit::Error>(())
/// ```
pub fn manipulability_ellipsoid(
    jacobian: &Matrix6xX<f64>,
    part: JacobianPart,
) -> Result<Ellipsoid> {
    check_finite("jacobian", jacobian.as_slice())?;
    let first = match part {
        JacobianPart::Translational => 0,
        JacobianPart::Rotational => 3,
    };
    let rows = jacobian.fixed_rows::<3>(first);
    let mut gram = Matrix3::zeros();
    for column in rows.column_iter() {
        gram += column * column.transpose();
    }
    let eigen = gram.symmetric_eigen();
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
    let axes = order.map(|i| {
        let axis = eigen.eigenvectors.column(i).into_owned();
        let norm = axis.norm();
        if norm > 0.0 {
            axis / norm
        } else {
            axis
        }
    });
    let radii = order.map(|i| eigen.eigenvalues[i].max(0.0).sqrt());
    Ok(Ellipsoid { axes, radii })
}
