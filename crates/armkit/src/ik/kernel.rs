//! The linear algebra of one numeric IK step: every step solves a 6 x 6
//! symmetric system, whatever the number of joints `n`: with `m` active task
//! components, `J W J' + mu I` (task space, `n >= m`; `dq = J' W^1/2 y`) or
//! `J' W J + mu I` padded with the identity (joint space, `n < m`, e.g. the
//! 4-DOF arm). The two are the same step (`(J'J + mu I)^-1 J' = J' (J J' +
//! mu I)^-1`); the smaller system is factored on the stack (Cholesky, or a
//! symmetric eigendecomposition for the singularity-robust inverse), so one
//! iteration allocates nothing.
//!
//! Why not [`crate::linalg`]'s solve: that kernel (the velocity-level
//! solvers') factors `J A^-1 J'` and calls it singular below one relative
//! threshold, so a tracking run stops with a status before its rates blow
//! up. This one must instead (1) weight the task components and pad the
//! masked ones (a position-only target is not singular), (2) take the
//! joint-space form when there are fewer joints than active components
//! (the 4-DOF arm, where `J J'` is always singular), and (3) solve as long
//! as the Cholesky factor exists (every pivot > 0), with no threshold: LM
//! and DLS bring their own damping, and seed 004's plain baseline
//! (`singularity::Method::Plain`, an undamped step through
//! [`super::damped_least_squares_step`]) must run into the singularity as
//! the paper shows. With `linalg`'s thresholded solve that baseline stops
//! at the singular pose: the demo's check "peak joint rate: plain /
//! avoidance k=1" reads 1.0 with it instead of 393. The two kernels
//! differ on purpose (docs/DEVELOPING.md, "Two 6 x 6 solves").

use crate::math::{Matrix6, Matrix6xX, Vector6};

/// Which 6 x 6 system a step solves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Form {
    /// `J W J' + mu I` (at least as many joints as active task components).
    Task,
    /// `J' W J + mu I`, padded to 6 x 6 with the identity (fewer joints).
    Joint,
}

/// The linear algebra of one step, for one task weighting and joint count.
#[derive(Clone, Copy, Debug)]
pub(super) struct Kernel {
    /// Square roots of the task weights, `W^1/2`.
    pub(super) sqrt_weights: Vector6<f64>,
    /// 1 on the rows of the 6 x 6 system that are structurally empty
    /// (masked task components, or padding beyond n joints), else 0.
    padding: Vector6<f64>,
    pub(super) form: Form,
    /// Number of meaningful singular values: min(active components, joints).
    pub(super) rank: usize,
}

impl Kernel {
    pub(super) fn new(weights: &[f64; 6], dof: usize) -> Kernel {
        let active = weights.iter().filter(|w| **w > 0.0).count();
        let form = if dof >= active {
            Form::Task
        } else {
            Form::Joint
        };
        let mut padding = Vector6::zeros();
        for (i, pad) in padding.iter_mut().enumerate() {
            let empty = match form {
                Form::Task => weights[i] <= 0.0,
                Form::Joint => i >= dof,
            };
            if empty {
                *pad = 1.0;
            }
        }
        Kernel {
            sqrt_weights: Vector6::from_fn(|i, _| weights[i].max(0.0).sqrt()),
            padding,
            form,
            rank: active.min(dof).max(1),
        }
    }

    /// The undamped, unpadded normal matrix: `S J J' S` (task) or `J' S^2 J`
    /// in the top-left n x n block (joint), with `S = W^1/2`.
    // Index loops: the matrix formulas read best with explicit indices.
    #[allow(clippy::needless_range_loop)]
    pub(super) fn normal_matrix(&self, j: &Matrix6xX<f64>) -> Mat6Array {
        let s: [f64; 6] = self.sqrt_weights.into();
        let mut a = [[0.0; 6]; 6];
        match self.form {
            Form::Task => {
                // Lower triangle of sum over columns of col col'.
                for col in columns(j) {
                    for r in 0..6 {
                        for c in 0..=r {
                            a[r][c] += col[r] * col[c];
                        }
                    }
                }
                for r in 0..6 {
                    for c in 0..=r {
                        a[r][c] *= s[r] * s[c];
                    }
                }
            }
            Form::Joint => {
                let weighted: Vec6Array = std::array::from_fn(|k| s[k] * s[k]);
                for (r, col_r) in columns(j).enumerate() {
                    for (c, col_c) in columns(j).take(r + 1).enumerate() {
                        a[r][c] = (0..6).map(|k| weighted[k] * col_r[k] * col_c[k]).sum();
                    }
                }
            }
        }
        for r in 0..6 {
            for c in r + 1..6 {
                a[r][c] = a[c][r];
            }
        }
        a
    }

    /// Right-hand side: `S e` (task) or `J' S^2 e` (joint, padded with zeros).
    pub(super) fn rhs(&self, j: &Matrix6xX<f64>, e: &Vector6<f64>) -> Vector6<f64> {
        let se = e.component_mul(&self.sqrt_weights);
        match self.form {
            Form::Task => se,
            Form::Joint => {
                let sse: Vec6Array = se.component_mul(&self.sqrt_weights).into();
                let mut out = Vector6::zeros();
                for (o, col) in out.iter_mut().zip(columns(j)) {
                    *o = dot6(col, &sse);
                }
                out
            }
        }
    }

    /// The joint step from the solution `y` of the 6 x 6 system:
    /// `J' S y` (task) or the first n entries of `y` (joint).
    pub(super) fn map_back(&self, j: &Matrix6xX<f64>, y: &Vector6<f64>, dq: &mut [f64]) {
        match self.form {
            Form::Task => {
                let sy: Vec6Array = y.component_mul(&self.sqrt_weights).into();
                for (d, col) in dq.iter_mut().zip(columns(j)) {
                    *d = dot6(col, &sy);
                }
            }
            Form::Joint => {
                for (d, v) in dq.iter_mut().zip(y.iter()) {
                    *d = *v;
                }
            }
        }
    }

    /// `A0 + mu I + padding`.
    fn damped(&self, a0: &Mat6Array, mu: f64) -> Mat6Array {
        let mut a = *a0;
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += mu + self.padding[i];
        }
        a
    }

    /// Solves `(A0 + mu I + padding) y = rhs` by Cholesky; `None` when the
    /// matrix is not numerically positive definite.
    pub(super) fn solve_damped(
        &self,
        a0: &Mat6Array,
        mu: f64,
        rhs: &Vector6<f64>,
    ) -> Option<Vector6<f64>> {
        let mut a = self.damped(a0, mu);
        if !cholesky6(&mut a) {
            return None;
        }
        let mut y: Vec6Array = (*rhs).into();
        cholesky6_solve(&a, &mut y);
        y.iter().all(|v| v.is_finite()).then(|| Vector6::from(y))
    }

    /// `sqrt(det)` of the active block of the normal matrix (Yoshikawa's
    /// manipulability of the weighted Jacobian), 0 when it is singular.
    pub(super) fn manipulability(&self, a0: &Mat6Array) -> f64 {
        let mut a = self.damped(a0, 0.0);
        if cholesky6(&mut a) {
            // det = prod(L_ii)^2, so sqrt(det) = prod(L_ii).
            (0..6).map(|i| a[i][i]).product()
        } else {
            0.0
        }
    }

    /// Chiaverini's filtered inverse applied to `rhs`: returns `y` and the
    /// smallest meaningful singular value `sigma_m`. `damping(sigma_m)` is
    /// the extra damping `lambda` of the smallest direction, `filter` the
    /// `beta` of every direction (the policy: `super::ChiaveriniFilter`).
    pub(super) fn solve_filtered(
        &self,
        a0: &Mat6Array,
        rhs: &Vector6<f64>,
        damping: impl Fn(f64) -> f64,
        filter: f64,
    ) -> (Vector6<f64>, f64) {
        let eigen = Matrix6::from_fn(|r, c| a0[r][c]).symmetric_eigen();
        let mut order = [0usize, 1, 2, 3, 4, 5];
        order.sort_unstable_by(|a, b| eigen.eigenvalues[*b].total_cmp(&eigen.eigenvalues[*a]));
        let smallest = order[self.rank - 1];
        let sigma_min = eigen.eigenvalues[smallest].max(0.0).sqrt();
        let lambda = damping(sigma_min);
        let beta2 = filter * filter;
        let mut y = Vector6::zeros();
        for i in 0..6 {
            let u = eigen.eigenvectors.column(i);
            let mut denominator = eigen.eigenvalues[i].max(0.0) + beta2;
            if i == smallest {
                denominator += lambda * lambda;
            }
            let projection = u.dot(rhs);
            if denominator > 0.0 && projection != 0.0 {
                y.axpy(projection / denominator, &u, 1.0);
            }
        }
        (y, sigma_min)
    }
}

/// A 6 x 6 matrix as row-major arrays (the fixed-size kernels below).
pub(super) type Mat6Array = [[f64; 6]; 6];
/// A 6-vector as an array.
type Vec6Array = [f64; 6];

/// The columns of a 6 x n Jacobian as fixed-size arrays (its storage is
/// column-major, so each is a contiguous chunk of 6).
fn columns(j: &Matrix6xX<f64>) -> impl Iterator<Item = &Vec6Array> {
    j.as_slice()
        .chunks_exact(6)
        .filter_map(|chunk| <&Vec6Array>::try_from(chunk).ok())
}

pub(super) fn trace(a: &Mat6Array) -> f64 {
    (0..6).map(|i| a[i][i]).sum()
}

#[inline(always)]
fn dot6(a: &Vec6Array, b: &Vec6Array) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]
}

/// In-place Cholesky factorization `A = L L'` of a symmetric 6 x 6 matrix
/// (lower triangle read, L written there); false if A is not numerically
/// positive definite. Fixed size, so the loops unroll: several times faster
/// than the generic factorization for the hot path of one IK iteration.
#[inline]
#[allow(clippy::needless_range_loop)]
fn cholesky6(a: &mut Mat6Array) -> bool {
    for j in 0..6 {
        let mut d = a[j][j];
        for k in 0..j {
            d -= a[j][k] * a[j][k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let l = d.sqrt();
        a[j][j] = l;
        let inverse = 1.0 / l;
        for i in j + 1..6 {
            let mut v = a[i][j];
            for k in 0..j {
                v -= a[i][k] * a[j][k];
            }
            a[i][j] = v * inverse;
        }
    }
    true
}

/// Solves `L L' y = b` in place, `L` from [`cholesky6`].
#[inline]
#[allow(clippy::needless_range_loop)]
fn cholesky6_solve(l: &Mat6Array, b: &mut Vec6Array) {
    for i in 0..6 {
        let mut v = b[i];
        for k in 0..i {
            v -= l[i][k] * b[k];
        }
        b[i] = v / l[i][i];
    }
    for i in (0..6).rev() {
        let mut v = b[i];
        for k in i + 1..6 {
            v -= l[k][i] * b[k];
        }
        b[i] = v / l[i][i];
    }
}
