//! The damping policies of the numeric methods: Nakamura's adaptive damping
//! (damped least squares), Chiaverini's filter (singularity-robust inverse)
//! and Sugihara's Levenberg-Marquardt damping.

use super::kernel::Kernel;
use crate::error::{check_positive, Error, Result};
use crate::math::Matrix6xX;

/// Nakamura and Hanafusa's adaptive damping for damped least squares:
/// `lambda = lambda_0 (1 - w / w_0)` while the manipulability
/// `w = sqrt(det(J J'))` is below the threshold `w_0`, zero above it; the
/// step is `dq = J' (J J' + lambda^2 I)^-1 e`.
///
/// Units: `w` in the product of the Jacobian's row units (for a 6-row
/// Jacobian of a 6R arm, m^3); `lambda` in those of a singular value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NakamuraDamping {
    /// Manipulability below which damping starts, `w_0` (> 0). Default 1e-3.
    pub threshold: f64,
    /// Damping at zero manipulability, `lambda_0` (> 0). Default 0.05.
    pub max_damping: f64,
}

impl Default for NakamuraDamping {
    fn default() -> Self {
        NakamuraDamping {
            threshold: 1e-3,
            max_damping: 0.05,
        }
    }
}

impl NakamuraDamping {
    /// Checks both parameters are finite and > 0.
    pub fn validate(&self) -> Result<()> {
        check_positive("NakamuraDamping.threshold", self.threshold)?;
        check_positive("NakamuraDamping.max_damping", self.max_damping)
    }

    /// The damping `lambda` for a manipulability `w` (>= 0).
    pub fn damping(&self, manipulability: f64) -> f64 {
        if manipulability < self.threshold {
            self.max_damping * (1.0 - manipulability.max(0.0) / self.threshold)
        } else {
            0.0
        }
    }

    /// The damping at a Jacobian (6 x n, any n >= 1): its manipulability
    /// `sqrt(det(J J'))` (`sqrt(det(J' J))` when n < 6) computed on the
    /// stack, then [`NakamuraDamping::damping`].
    pub fn damping_at(&self, jacobian: &Matrix6xX<f64>) -> f64 {
        let kernel = Kernel::new(&[1.0; 6], jacobian.ncols());
        self.damping(kernel.manipulability(&kernel.normal_matrix(jacobian)))
    }
}

/// Chiaverini's singularity-robust inverse with numerical filtering:
/// `J# = J' (J J' + beta^2 I + lambda^2 u_m u_m')^-1`, where `u_m` is the
/// output singular vector of the smallest singular value `sigma_m`, damped
/// by `lambda^2 = lambda_max^2 (1 - (sigma_m / epsilon)^2)` only when
/// `sigma_m < epsilon`; `beta` is a small filter on every direction.
///
/// Singular values are in the Jacobian's units (m/rad for the position
/// rows of a revolute arm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChiaveriniFilter {
    /// Width of the singular region, `epsilon` (> 0). Default 0.05.
    pub threshold: f64,
    /// Damping at `sigma_m = 0`, `lambda_max` (> 0). Default 0.05.
    pub max_damping: f64,
    /// Numerical filter `beta` (>= 0), applied to all directions. Default 1e-4.
    pub filter: f64,
}

impl Default for ChiaveriniFilter {
    fn default() -> Self {
        ChiaveriniFilter {
            threshold: 0.05,
            max_damping: 0.05,
            filter: 1e-4,
        }
    }
}

impl ChiaveriniFilter {
    /// Checks the parameters (threshold, max_damping > 0; filter >= 0; all finite).
    pub fn validate(&self) -> Result<()> {
        check_positive("ChiaveriniFilter.threshold", self.threshold)?;
        check_positive("ChiaveriniFilter.max_damping", self.max_damping)?;
        if !(self.filter.is_finite() && self.filter >= 0.0) {
            return Err(Error::invalid_argument(
                "ChiaveriniFilter.filter",
                format!("must be finite and >= 0, got {}", self.filter),
            ));
        }
        Ok(())
    }

    /// The damping `lambda` applied to the smallest singular value `sigma_m`.
    pub fn damping(&self, smallest_singular_value: f64) -> f64 {
        variable_damping(self.threshold, self.max_damping, smallest_singular_value)
    }
}

/// `lambda = lambda_max sqrt(1 - (sigma / epsilon)^2)` for `sigma < epsilon`,
/// else 0: the variable damping of the smallest singular value shared by
/// [`ChiaveriniFilter`] and [`DampedReciprocal`].
fn variable_damping(threshold: f64, max_damping: f64, smallest_singular_value: f64) -> f64 {
    let ratio = smallest_singular_value.max(0.0) / threshold;
    if ratio < 1.0 {
        max_damping * (1.0 - ratio * ratio).sqrt()
    } else {
        0.0
    }
}

/// The damped reciprocal of the singularity-separation method (seed 004's
/// reference [9], Xu Wenfu et al.): in the wrist block's inverse
/// `V diag(1 / sigma_i) U'`, only the smallest singular value's reciprocal
/// becomes `sigma_m / (sigma_m^2 + lambda^2)`, with
/// `lambda = lambda_max sqrt(1 - (sigma_m / epsilon)^2)` while
/// `sigma_m < epsilon` (0 above: the exact inverse). The other directions
/// keep their exact reciprocals, so only the end effector's motion along the
/// lost direction is sacrificed.
///
/// Singular values are those of the wrist block (rad/rad for a revolute
/// wrist: dimensionless).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DampedReciprocal {
    /// Width of the singular region, `epsilon` (> 0). Default 0.05.
    pub threshold: f64,
    /// Damping at `sigma_m = 0`, `lambda_max` (> 0). Default 0.05.
    pub max_damping: f64,
}

impl Default for DampedReciprocal {
    fn default() -> Self {
        DampedReciprocal {
            threshold: 0.05,
            max_damping: 0.05,
        }
    }
}

impl DampedReciprocal {
    /// Checks both parameters are finite and > 0.
    pub fn validate(&self) -> Result<()> {
        check_positive("DampedReciprocal.threshold", self.threshold)?;
        check_positive("DampedReciprocal.max_damping", self.max_damping)
    }

    /// The damping `lambda` of the smallest singular value `sigma_m` (>= 0).
    pub fn damping(&self, smallest_singular_value: f64) -> f64 {
        variable_damping(self.threshold, self.max_damping, smallest_singular_value)
    }

    /// The damped reciprocal `sigma / (sigma^2 + lambda^2)` of a singular
    /// value `sigma` whose damping is `lambda` (0 when both are 0).
    pub fn reciprocal(sigma: f64, lambda: f64) -> f64 {
        let denominator = sigma * sigma + lambda * lambda;
        if denominator > 0.0 {
            sigma / denominator
        } else {
            0.0
        }
    }
}

/// Sugihara's Levenberg-Marquardt damping: `W_N = (E + w_N) I` with
/// `E = e' W_E e / 2` the current weighted squared error. The damping thus
/// fades as the error does (quadratic convergence near a solution) while
/// `w_N` keeps the step bounded near singularities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LmDamping {
    /// The floor `w_N` (> 0), in squared Jacobian units (m^2). Default
    /// 1e-9: small, so that the last iterations converge quadratically even
    /// close to a singularity (with 1e-4, 1 % of UR5 targets near a
    /// singular configuration crept toward 1e-6 too slowly to finish).
    pub floor: f64,
}

impl Default for LmDamping {
    fn default() -> Self {
        LmDamping { floor: 1e-9 }
    }
}

impl LmDamping {
    /// Checks the floor is finite and > 0.
    pub fn validate(&self) -> Result<()> {
        check_positive("LmDamping.floor", self.floor)
    }
}
