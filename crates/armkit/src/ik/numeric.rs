//! The numeric solvers: one iteration engine, four step rules, and the
//! velocity-level pseudo-inverses they are built from.
//!
//! Every step solves a 6 x 6 symmetric system, whatever the number of joints
//! `n`: with `m` active task components, `J W J' + mu I` (task space,
//! `n >= m`; `dq = J' W^1/2 y`) or `J' W J + mu I` padded with the identity
//! (joint space, `n < m`, e.g. the 4-DOF arm). The two are the same step
//! (`(J'J + mu I)^-1 J' = J' (J J' + mu I)^-1`); the smaller system is
//! factored on the stack (Cholesky, or a symmetric eigendecomposition for the
//! singularity-robust inverse), so one iteration allocates nothing.

use std::time::Instant;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::pose_error::{masked_error_norms, pose_error};
use super::protocol::sample_joint;
use super::{IkMethod, IkOptions, IkReport, IkSelection, IkStatus, Redundancy};
use crate::error::{check_finite, check_positive, Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{wrap_angle, DMatrix, Matrix6, Matrix6xX, Pose, Vector6};
use crate::model::{JointKind, Model};

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
        let ratio = smallest_singular_value.max(0.0) / self.threshold;
        if ratio < 1.0 {
            self.max_damping * (1.0 - ratio * ratio).sqrt()
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

/// Which 6 x 6 system a step solves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Form {
    /// `J W J' + mu I` (at least as many joints as active task components).
    Task,
    /// `J' W J + mu I`, padded to 6 x 6 with the identity (fewer joints).
    Joint,
}

/// The linear algebra of one step, for one task weighting and joint count.
#[derive(Clone, Copy, Debug)]
struct Kernel {
    /// Square roots of the task weights, `W^1/2`.
    sqrt_weights: Vector6<f64>,
    /// 1 on the rows of the 6 x 6 system that are structurally empty
    /// (masked task components, or padding beyond n joints), else 0.
    padding: Vector6<f64>,
    form: Form,
    /// Number of meaningful singular values: min(active components, joints).
    rank: usize,
}

impl Kernel {
    fn new(weights: &[f64; 6], dof: usize) -> Kernel {
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
    fn normal_matrix(&self, j: &Matrix6xX<f64>) -> Mat6Array {
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
    fn rhs(&self, j: &Matrix6xX<f64>, e: &Vector6<f64>) -> Vector6<f64> {
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
    fn map_back(&self, j: &Matrix6xX<f64>, y: &Vector6<f64>, dq: &mut [f64]) {
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
    fn solve_damped(&self, a0: &Mat6Array, mu: f64, rhs: &Vector6<f64>) -> Option<Vector6<f64>> {
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
    fn manipulability(&self, a0: &Mat6Array) -> f64 {
        let mut a = self.damped(a0, 0.0);
        if cholesky6(&mut a) {
            // det = prod(L_ii)^2, so sqrt(det) = prod(L_ii).
            (0..6).map(|i| a[i][i]).product()
        } else {
            0.0
        }
    }

    /// Chiaverini's filtered inverse applied to `rhs`: returns `y` and the
    /// smallest meaningful singular value.
    fn solve_filtered(
        &self,
        a0: &Mat6Array,
        rhs: &Vector6<f64>,
        filter: &ChiaveriniFilter,
    ) -> (Vector6<f64>, f64) {
        let eigen = Matrix6::from_fn(|r, c| a0[r][c]).symmetric_eigen();
        let mut order = [0usize, 1, 2, 3, 4, 5];
        order.sort_unstable_by(|a, b| eigen.eigenvalues[*b].total_cmp(&eigen.eigenvalues[*a]));
        let smallest = order[self.rank - 1];
        let sigma_min = eigen.eigenvalues[smallest].max(0.0).sqrt();
        let lambda = filter.damping(sigma_min);
        let beta2 = filter.filter * filter.filter;
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
type Mat6Array = [[f64; 6]; 6];
/// A 6-vector as an array.
type Vec6Array = [f64; 6];

/// The columns of a 6 x n Jacobian as fixed-size arrays (its storage is
/// column-major, so each is a contiguous chunk of 6).
fn columns(j: &Matrix6xX<f64>) -> impl Iterator<Item = &Vec6Array> {
    j.as_slice()
        .chunks_exact(6)
        .filter_map(|chunk| <&Vec6Array>::try_from(chunk).ok())
}

fn trace(a: &Mat6Array) -> f64 {
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
    let (y, sigma_min) = kernel.solve_filtered(&a0, &rhs, filter);
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

/// When an attempt gives up: after `stall` iterations in a row that did not
/// lower the attempt's best objective below `progress` times itself. Near a
/// solution every step divides the error by far more, so a stall means a
/// local minimum, a singular region or a limit: restart.
#[derive(Clone, Copy, Debug)]
struct Patience {
    stall: usize,
    progress: f64,
}

impl Patience {
    /// The attempt from the caller's start is given more patience: its
    /// solution is the one continuous with the start.
    const START: Patience = Patience {
        stall: 5,
        progress: 0.9,
    };
    /// Random restarts give up sooner: another restart is cheaper than a slow one.
    const RESTART: Patience = Patience {
        stall: 4,
        progress: 0.7,
    };
}
/// Growth of Levenberg-Marquardt's damping after a rejected step.
const LM_REJECT_GROWTH: f64 = 10.0;

/// Pose error at one configuration, with its weighted objective.
#[derive(Clone, Copy, Debug)]
struct Evaluation {
    error: Vector6<f64>,
    /// `E = e' W e / 2`.
    objective: f64,
}

/// How one attempt ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AttemptEnd {
    Converged,
    Stalled,
    OutOfTime,
}

/// A numeric inverse-kinematics solver for one model: options and every
/// workspace, sized once by [`IkSolver::new`]; [`IkSolver::solve`] then
/// allocates only its report's joint vector.
///
/// Not `Sync`-shared: use one solver per thread.
#[derive(Clone, Debug)]
pub struct IkSolver {
    model: Model,
    options: IkOptions,
    kernel: Kernel,
    kinds: Vec<JointKind>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    current: Data,
    trial: Data,
    q: Vec<f64>,
    q_trial: Vec<f64>,
    step: Vec<f64>,
    start: Vec<f64>,
    best: Vec<f64>,
    solution: Vec<f64>,
    /// Joints held at a limit in the current step (active set).
    held: Vec<bool>,
    /// The Jacobian with the held joints' columns zeroed.
    held_jacobian: Matrix6xX<f64>,
}

impl IkSolver {
    /// A solver for `model` (cloned) with validated `options`.
    pub fn new(model: &Model, options: IkOptions) -> Result<IkSolver> {
        options.validate()?;
        let n = model.dof();
        if n == 0 {
            return Err(Error::invalid_argument("model", "has no moving joints"));
        }
        let (lower, upper) = model.position_limits();
        Ok(IkSolver {
            model: model.clone(),
            options,
            kernel: Kernel::new(&options.task_weights, n),
            kinds: model.joints().iter().map(|j| j.kind).collect(),
            lower,
            upper,
            current: Data::new(model),
            trial: Data::new(model),
            q: vec![0.0; n],
            q_trial: vec![0.0; n],
            step: vec![0.0; n],
            start: vec![0.0; n],
            best: vec![0.0; n],
            solution: vec![0.0; n],
            held: vec![false; n],
            held_jacobian: Matrix6xX::zeros(n),
        })
    }

    /// The options in use.
    pub fn options(&self) -> &IkOptions {
        &self.options
    }

    /// The model solved for.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Replaces the options (validated); workspaces are kept.
    pub fn set_options(&mut self, options: IkOptions) -> Result<()> {
        options.validate()?;
        self.kernel = Kernel::new(&options.task_weights, self.model.dof());
        self.options = options;
        Ok(())
    }

    /// Solves for joint positions that put the end-effector at `target`
    /// (world frame), starting from `start` (one value per joint, rad or m;
    /// clamped into the limits if outside).
    ///
    /// Errors only for bad input: `start` of the wrong size or not finite, a
    /// `target` with a non-finite entry or a rotation that is not
    /// orthonormal (to 1e-6) with determinant +1. Not reaching the target is
    /// [`IkStatus::NotConverged`] with the best iterate.
    pub fn solve(&mut self, target: &Pose, start: &[f64]) -> Result<IkReport> {
        let began = Instant::now();
        self.model.check_joint_positions(start)?;
        check_target(target)?;
        let deadline = self.options.time_budget.map(|b| began + b);
        let mut rng = ChaCha8Rng::seed_from_u64(self.options.seed);
        for (j, value) in start.iter().enumerate() {
            self.start[j] = self.project(j, *value);
        }
        let wanted = match self.options.selection {
            IkSelection::First => 1,
            IkSelection::Nearest { solutions } => solutions,
        };
        let mut best_objective = f64::INFINITY;
        let mut found = 0usize;
        let mut solution_distance = f64::INFINITY;
        let mut iterations = 0usize;
        let mut restarts = 0usize;
        for attempt in 0..=self.options.max_restarts {
            if attempt == 0 {
                self.q.copy_from_slice(&self.start);
            } else {
                restarts += 1;
                self.random_configuration(&mut rng);
            }
            let patience = if attempt == 0 {
                Patience::START
            } else {
                Patience::RESTART
            };
            let (end, used) = self.attempt(target, deadline, &mut best_objective, patience)?;
            iterations += used;
            if end == AttemptEnd::Converged {
                self.nearest_representation();
                let distance = self.distance_to_start(&self.q);
                if distance < solution_distance {
                    solution_distance = distance;
                    self.solution.copy_from_slice(&self.q);
                }
                found += 1;
                if found >= wanted {
                    break;
                }
            }
            if end == AttemptEnd::OutOfTime || deadline.is_some_and(|d| Instant::now() >= d) {
                break;
            }
        }
        if found > 0 {
            self.q.copy_from_slice(&self.solution);
            if let Redundancy::PullToStart {
                gain,
                iterations: extra,
            } = self.options.redundancy
            {
                iterations += self.pull_to_start(target, gain, extra)?;
            }
        } else {
            self.q.copy_from_slice(&self.best);
        }
        // The report is computed afresh at the returned q: never a success
        // above tolerance, whatever happened before.
        let evaluation = self.evaluate_current(target)?;
        let (position_error, orientation_error) =
            masked_error_norms(&evaluation.error, &self.options.task_weights);
        let status = if self.within_tolerance(&evaluation.error) {
            IkStatus::Converged
        } else {
            IkStatus::NotConverged
        };
        Ok(IkReport {
            status,
            q: self.q.clone(),
            position_error,
            orientation_error,
            iterations,
            restarts,
            elapsed: began.elapsed(),
        })
    }

    /// One attempt from `self.q`: iterates until converged, stalled, out of
    /// iterations or out of time. Keeps `self.best` (the lowest objective
    /// seen over all attempts) up to date. Returns how it ended and the
    /// iterations used.
    fn attempt(
        &mut self,
        target: &Pose,
        deadline: Option<Instant>,
        best_objective: &mut f64,
        patience: Patience,
    ) -> Result<(AttemptEnd, usize)> {
        let mut current = self.evaluate_current(target)?;
        self.record_best(&current, best_objective);
        let mut attempt_best = current.objective;
        let mut stall = 0usize;
        let mut damping_scale = 1.0;
        for iteration in 0..self.options.max_iterations {
            if self.within_tolerance(&current.error) {
                return Ok((AttemptEnd::Converged, iteration));
            }
            if iteration % 4 == 3 && deadline.is_some_and(|d| Instant::now() >= d) {
                return Ok((AttemptEnd::OutOfTime, iteration));
            }
            let stepped = self.compute_step(&current, damping_scale);
            let mut progressed = false;
            if stepped {
                for j in 0..self.q.len() {
                    self.q_trial[j] = self.project(j, self.q[j] + self.step[j]);
                }
                let trial = self.evaluate_trial(target)?;
                let accept = match self.options.method {
                    IkMethod::LevenbergMarquardt(_) => trial.objective < current.objective,
                    _ => trial.objective.is_finite(),
                };
                if accept {
                    std::mem::swap(&mut self.current, &mut self.trial);
                    std::mem::swap(&mut self.q, &mut self.q_trial);
                    current = trial;
                    self.record_best(&current, best_objective);
                    damping_scale = (damping_scale * 0.5).max(1.0);
                } else {
                    damping_scale *= LM_REJECT_GROWTH;
                }
                if current.objective < patience.progress * attempt_best {
                    attempt_best = current.objective;
                    progressed = true;
                }
            } else {
                damping_scale *= LM_REJECT_GROWTH;
            }
            if progressed {
                stall = 0;
            } else {
                stall += 1;
                if stall >= patience.stall && !self.within_tolerance(&current.error) {
                    return Ok((AttemptEnd::Stalled, iteration + 1));
                }
            }
        }
        let end = if self.within_tolerance(&current.error) {
            AttemptEnd::Converged
        } else {
            AttemptEnd::Stalled
        };
        Ok((end, self.options.max_iterations))
    }

    /// The method's step at the current iterate into `self.step`; false if
    /// no finite step could be formed.
    ///
    /// Joint limits are an active set: a joint at a limit whose step would
    /// push it further out is held (its Jacobian column zeroed) and the step
    /// recomputed, so that the other joints make up for it instead of the
    /// whole step being distorted by clamping.
    fn compute_step(&mut self, current: &Evaluation, damping_scale: f64) -> bool {
        let method = self.options.method;
        if !method_step(
            &self.kernel,
            method,
            self.current.jacobian(),
            current,
            damping_scale,
            &mut self.step,
        ) {
            return false;
        }
        let mut any_held = false;
        for (j, held) in self.held.iter_mut().enumerate() {
            let q = self.q[j];
            *held = (q <= self.lower[j] && self.step[j] < 0.0)
                || (q >= self.upper[j] && self.step[j] > 0.0);
            any_held |= *held;
        }
        if !any_held {
            return true;
        }
        self.held_jacobian.copy_from(self.current.jacobian());
        for (j, held) in self.held.iter().enumerate() {
            if *held {
                self.held_jacobian.column_mut(j).fill(0.0);
            }
        }
        let ok = method_step(
            &self.kernel,
            method,
            &self.held_jacobian,
            current,
            damping_scale,
            &mut self.step,
        );
        for (value, held) in self.step.iter_mut().zip(&self.held) {
            if *held {
                *value = 0.0;
            }
        }
        ok
    }

    /// Null-space steps toward the start after convergence (redundant
    /// robots, [`Redundancy::PullToStart`]); `self.q` stays converged.
    /// Returns the iterations used.
    fn pull_to_start(&mut self, target: &Pose, gain: f64, extra: usize) -> Result<usize> {
        if self.kernel.form != Form::Task || self.kernel.rank >= self.model.dof() {
            return Ok(0);
        }
        let mut current = self.evaluate_current(target)?;
        // self.q is converged: it is the fallback answer.
        self.solution.copy_from_slice(&self.q);
        let mut best_distance = self.distance_to_start(&self.q);
        let mut used = extra;
        for iteration in 0..extra {
            let j = self.current.jacobian();
            let kernel = &self.kernel;
            let a0 = kernel.normal_matrix(j);
            let rhs = kernel.rhs(j, &current.error);
            // r = gain (q_start - q); its null-space part is r - J' S (S J J' S)^-1 S J r.
            let mut task_of_r = Vector6::zeros();
            for (c, col) in j.column_iter().enumerate() {
                task_of_r.axpy(gain * (self.start[c] - self.q[c]), &col, 1.0);
            }
            let task_of_r = task_of_r.component_mul(&kernel.sqrt_weights);
            let mu = 1e-12 * trace(&a0).max(f64::MIN_POSITIVE);
            let (Some(y), Some(y_null)) = (
                kernel.solve_damped(&a0, mu, &rhs),
                kernel.solve_damped(&a0, mu, &task_of_r),
            ) else {
                used = iteration;
                break;
            };
            let combined = y - y_null;
            kernel.map_back(j, &combined, &mut self.step);
            let mut moved = 0.0;
            for c in 0..self.q.len() {
                let null_part = gain * (self.start[c] - self.q[c]);
                let value = self.project(c, self.q[c] + self.step[c] + null_part);
                moved += (value - self.q[c]).powi(2);
                self.q_trial[c] = value;
            }
            // Every step is taken (the task part corrects the second-order
            // drift of the previous null-space move); the answer is the
            // converged iterate nearest the start.
            current = self.evaluate_trial(target)?;
            std::mem::swap(&mut self.current, &mut self.trial);
            std::mem::swap(&mut self.q, &mut self.q_trial);
            let distance = self.distance_to_start(&self.q);
            if self.within_tolerance(&current.error) && distance < best_distance {
                best_distance = distance;
                self.solution.copy_from_slice(&self.q);
            }
            if moved.sqrt() < 1e-12 {
                used = iteration + 1;
                break;
            }
        }
        self.q.copy_from_slice(&self.solution);
        Ok(used)
    }

    fn evaluate_current(&mut self, target: &Pose) -> Result<Evaluation> {
        jacobian(
            &self.model,
            &mut self.current,
            &self.q,
            JacobianFrame::World,
        )?;
        Ok(self.evaluation(target, self.current.end_effector_pose()))
    }

    fn evaluate_trial(&mut self, target: &Pose) -> Result<Evaluation> {
        jacobian(
            &self.model,
            &mut self.trial,
            &self.q_trial,
            JacobianFrame::World,
        )?;
        Ok(self.evaluation(target, self.trial.end_effector_pose()))
    }

    fn evaluation(&self, target: &Pose, pose: &Pose) -> Evaluation {
        let error = pose_error(target, pose);
        let weighted = error.component_mul(&self.kernel.sqrt_weights);
        Evaluation {
            error,
            objective: 0.5 * weighted.norm_squared(),
        }
    }

    fn record_best(&mut self, evaluation: &Evaluation, best_objective: &mut f64) {
        if evaluation.objective < *best_objective {
            *best_objective = evaluation.objective;
            self.best.copy_from_slice(&self.q);
        }
    }

    fn within_tolerance(&self, error: &Vector6<f64>) -> bool {
        let (position, orientation) = masked_error_norms(error, &self.options.task_weights);
        position <= self.options.position_tolerance
            && orientation <= self.options.orientation_tolerance
    }

    /// Joint j's value moved into its limits: clamped, or wrapped to
    /// (-pi, pi] for a continuous joint.
    fn project(&self, j: usize, value: f64) -> f64 {
        match self.kinds[j] {
            JointKind::Continuous => wrap_angle(value),
            _ => value.clamp(self.lower[j], self.upper[j]),
        }
    }

    /// A configuration drawn uniformly within the limits into `self.q`
    /// (see [`super::protocol::sample_joint`]).
    fn random_configuration(&mut self, rng: &mut ChaCha8Rng) {
        for (j, joint) in self.model.joints().iter().enumerate() {
            self.q[j] = sample_joint(joint, self.start[j], rng);
        }
    }

    /// For each rotational joint, the 2 pi multiple of `self.q[j]` nearest
    /// the start that lies within the limits (the pose does not change).
    fn nearest_representation(&mut self) {
        use std::f64::consts::TAU;
        for j in 0..self.q.len() {
            if !self.kinds[j].is_rotational() {
                continue;
            }
            let value = self.q[j];
            let turns = ((self.start[j] - value) / TAU).round();
            let mut chosen = value;
            for k in [turns, turns - 1.0, turns + 1.0] {
                let candidate = value + k * TAU;
                let inside = match self.kinds[j] {
                    JointKind::Continuous => true,
                    _ => candidate >= self.lower[j] && candidate <= self.upper[j],
                };
                if inside && (candidate - self.start[j]).abs() < (chosen - self.start[j]).abs() {
                    chosen = candidate;
                }
            }
            self.q[j] = chosen;
        }
    }

    fn distance_to_start(&self, q: &[f64]) -> f64 {
        q.iter()
            .zip(&self.start)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt()
    }
}

/// One step of `method` for the Jacobian `j` at the evaluation `current`
/// into `step`; false if no finite step could be formed.
fn method_step(
    kernel: &Kernel,
    method: IkMethod,
    j: &Matrix6xX<f64>,
    current: &Evaluation,
    damping_scale: f64,
    step: &mut [f64],
) -> bool {
    let a0 = kernel.normal_matrix(j);
    let rhs = kernel.rhs(j, &current.error);
    let y = match method {
        IkMethod::NewtonRaphson => kernel.solve_damped(&a0, 0.0, &rhs).or_else(|| {
            let mu = 1e-12 * trace(&a0).max(f64::MIN_POSITIVE);
            kernel.solve_damped(&a0, mu, &rhs)
        }),
        IkMethod::DampedLeastSquares(nakamura) => {
            let lambda = nakamura.damping(kernel.manipulability(&a0));
            kernel.solve_damped(&a0, lambda * lambda, &rhs)
        }
        IkMethod::LevenbergMarquardt(lm) => {
            let mu = damping_scale * (current.objective + lm.floor);
            kernel.solve_damped(&a0, mu, &rhs)
        }
        IkMethod::SingularityRobust(filter) => Some(kernel.solve_filtered(&a0, &rhs, &filter).0),
    };
    match y {
        Some(y) => {
            kernel.map_back(j, &y, step);
            step.iter().all(|v| v.is_finite())
        }
        None => false,
    }
}

/// Checks an IK target: finite, rotation orthonormal to 1e-6, determinant +1.
pub(crate) fn check_target(target: &Pose) -> Result<()> {
    if !target.is_finite() {
        return Err(Error::invalid_argument(
            "target",
            "has a non-finite entry (NaN or infinity)",
        ));
    }
    let r = &target.rotation;
    let orthonormality = (r.transpose() * r - crate::math::Matrix3::identity()).amax();
    if orthonormality > 1e-6 || r.determinant() < 0.0 {
        return Err(Error::invalid_argument(
            "target",
            format!(
                "rotation is not a proper rotation (|R'R - I| = {orthonormality:.3e}, det = {:.6})",
                r.determinant()
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::forward_kinematics;

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
