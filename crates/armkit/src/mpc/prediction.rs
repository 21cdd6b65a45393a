//! Prediction over the horizon (seed 000, eqs 13-14 and 21) and the condensed
//! QP cost (eq 20).
//!
//! The incremental model of eq 14 is
//!
//! ```text
//! x(k+1) = A x(k) + B u(k),   y(k) = C x(k),   u(k) = u(k-1) + du(k),
//! x(0) = x_s,  u(-1) = v_old,  du(k) = 0 for k >= M,
//! ```
//!
//! and its outputs over the prediction horizon `N` are (eq 21)
//!
//! ```text
//! Y = S x_s + G1 U_old + G2 L dU,
//! S  = [CA; CA^2; ...; CA^N]                       (N p x nx)
//! G1 = block lower triangular, G1[i][j] = C A^(i-j) B for j <= i (N p x N nu)
//! L  = block lower triangular ones, N x M blocks of I (N nu x M nu)
//! U_old = [v_old; ...; v_old] (N blocks)
//! ```
//!
//! Errata: the printed eq 21 writes `S Xs` with `Xs` the stacked state (it is
//! `S x_s`), and prints `G2` as `G1` shifted down one block row with a zero
//! first row: that would mean `du(k)` does not reach `y(k+1)`, contradicting
//! eq 14 (`u(k) = u(k-1) + du(k)` drives `x(k+1)`). Derived from eq 14,
//! `G2 = G1`; [`PredictionMatrices`] builds it so and the tests check it
//! against direct simulation of eq 14.
//!
//! With the planner's model (eq 13: `A = I`, `B = T J(q)`), block `(i, l)` of
//! `G2 L` is `c(i, l) C B` with `c(i, l) = max(i - l, 0)` (`i = 1..N`,
//! `l = 0..M-1`): the number of samples for which increment `l` has acted by
//! step `i`. [`Condensation`] uses this to build the QP's Hessian and gradient
//! from two `nu x nu` products instead of the `N p x M nu` matrix.
//!
//! ```
//! use armkit::math::{DMatrix, DVector};
//! use armkit::mpc::prediction::{simulate_incremental_model, PredictionMatrices};
//! let a = DMatrix::identity(2, 2);
//! let b = DMatrix::from_row_slice(2, 1, &[0.1, 0.2]);
//! let c = DMatrix::identity(2, 2);
//! let p = PredictionMatrices::new(&a, &b, &c, 4, 2).unwrap();
//! let x0 = DVector::from_vec(vec![1.0, -1.0]);
//! let v_old = DVector::from_vec(vec![0.5]);
//! let du = DVector::from_vec(vec![0.3, -0.1]);
//! let y = p.predict(&x0, &v_old, &du);
//! let direct = simulate_incremental_model(&a, &b, &c, &x0, &v_old, &du, 4);
//! assert!((y - direct).amax() < 1e-14);
//! ```

use crate::error::{Error, Result};
use crate::math::{DMatrix, DVector};

/// `c(i, l) = max(i - l, 0)`: how many samples increment `du(l)` has been
/// applied for when step `i` (1-based) is reached, `A = I`.
#[inline]
pub fn increment_coefficient(step: usize, increment: usize) -> f64 {
    step.saturating_sub(increment) as f64
}

/// The explicit matrices of eq 21 for a linear model `(A, B, C)`.
///
/// Dimensions: `nx` states, `nu` inputs, `p` outputs; `N` = horizon,
/// `M` = control horizon. Used as the reference the planner's structured
/// computation is tested against, and for models with `A != I`.
#[derive(Clone, Debug, PartialEq)]
pub struct PredictionMatrices {
    /// `S` (`N p x nx`).
    pub s: DMatrix<f64>,
    /// `G1` (`N p x N nu`).
    pub g1: DMatrix<f64>,
    /// `G2` (`N p x N nu`), equal to `G1` (see the module's errata).
    pub g2: DMatrix<f64>,
    /// `L` (`N nu x M nu`): maps the increments to the input changes
    /// `u(k+j) - v_old`.
    pub l: DMatrix<f64>,
    /// Prediction horizon `N`.
    pub horizon: usize,
    /// Control horizon `M`.
    pub control_horizon: usize,
}

impl PredictionMatrices {
    /// Builds `S, G1, G2, L` for `x+ = A x + B u`, `y = C x`. Errors: sizes
    /// that do not match, `N = 0`, `M = 0` or `M > N`.
    pub fn new(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        horizon: usize,
        control_horizon: usize,
    ) -> Result<Self> {
        check_horizons(horizon, control_horizon)?;
        let nx = a.nrows();
        if a.ncols() != nx {
            return Err(Error::DimensionMismatch {
                what: "a (columns)",
                expected: nx,
                got: a.ncols(),
            });
        }
        if b.nrows() != nx {
            return Err(Error::DimensionMismatch {
                what: "b (rows)",
                expected: nx,
                got: b.nrows(),
            });
        }
        if c.ncols() != nx {
            return Err(Error::DimensionMismatch {
                what: "c (columns)",
                expected: nx,
                got: c.ncols(),
            });
        }
        let (p, nu) = (c.nrows(), b.ncols());
        let n = horizon;
        // C A^k for k = 0..N.
        let mut ca_powers = Vec::with_capacity(n + 1);
        ca_powers.push(c.clone());
        for k in 1..=n {
            let next = &ca_powers[k - 1] * a;
            ca_powers.push(next);
        }
        let mut s = DMatrix::zeros(n * p, nx);
        let mut g1 = DMatrix::zeros(n * p, n * nu);
        for i in 0..n {
            s.view_mut((i * p, 0), (p, nx)).copy_from(&ca_powers[i + 1]);
            for j in 0..=i {
                let block = &ca_powers[i - j] * b;
                g1.view_mut((i * p, j * nu), (p, nu)).copy_from(&block);
            }
        }
        let mut l = DMatrix::zeros(n * nu, control_horizon * nu);
        for j in 0..n {
            for m in 0..control_horizon.min(j + 1) {
                l.view_mut((j * nu, m * nu), (nu, nu)).fill_diagonal(1.0);
            }
        }
        Ok(PredictionMatrices {
            s,
            g2: g1.clone(),
            g1,
            l,
            horizon,
            control_horizon,
        })
    }

    /// `Y = S x_s + G1 U_old + G2 L dU` (eq 21): the `N p` predicted outputs
    /// for state `x_s` (`nx`), previous input `v_old` (`nu`) and increments
    /// `dU` (`M nu`, control step major).
    pub fn predict(
        &self,
        state: &DVector<f64>,
        previous_input: &DVector<f64>,
        increments: &DVector<f64>,
    ) -> DVector<f64> {
        let nu = previous_input.len();
        let u_old = DVector::from_fn(self.horizon * nu, |r, _| previous_input[r % nu]);
        &self.s * state + &self.g1 * u_old + &self.g2 * (&self.l * increments)
    }

    /// `G2 L` (`N p x M nu`): the outputs' sensitivity to the increments.
    pub fn increment_gain(&self) -> DMatrix<f64> {
        &self.g2 * &self.l
    }
}

/// Direct simulation of eq 14 for `N` steps: `u(k) = u(k-1) + du(k)` with
/// `du(k) = 0` for `k >= M`, `x(k+1) = A x(k) + B u(k)`, stacking
/// `y(k+1) = C x(k+1)` for `k = 0..N-1`. The reference for
/// [`PredictionMatrices::predict`].
pub fn simulate_incremental_model(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    state: &DVector<f64>,
    previous_input: &DVector<f64>,
    increments: &DVector<f64>,
    horizon: usize,
) -> DVector<f64> {
    let (p, nu) = (c.nrows(), b.ncols());
    let control_horizon = increments.len() / nu.max(1);
    let mut x = state.clone();
    let mut u = previous_input.clone();
    let mut y = DVector::zeros(horizon * p);
    for k in 0..horizon {
        if k < control_horizon {
            u += increments.rows(k * nu, nu);
        }
        x = a * &x + b * &u;
        y.rows_mut(k * p, p).copy_from(&(c * &x));
    }
    y
}

pub(crate) fn check_horizons(horizon: usize, control_horizon: usize) -> Result<()> {
    if horizon == 0 {
        return Err(Error::invalid_argument("horizon", "must be at least 1"));
    }
    if control_horizon == 0 || control_horizon > horizon {
        return Err(Error::invalid_argument(
            "control_horizon",
            format!("must be in 1..={horizon} (the prediction horizon), got {control_horizon}"),
        ));
    }
    Ok(())
}

/// The structured condensation of eq 20 for `A = I` (eq 13), with tracking
/// weights `Q` on steps `1..N-1` and terminal weights `Q_N` on step `N`.
///
/// With `Bt = T J` (`6 x nu`) and `c(i, l)` from [`increment_coefficient`]:
///
/// ```text
/// H[l][m] = K1[l][m] Bt'Q Bt + K2[l][m] Bt'Q_N Bt + delta(l, m) R,
///   K1[l][m] = sum_{i<N} c(i,l) c(i,m),   K2[l][m] = c(N,l) c(N,m)
/// f[l]    = Bt' ( Q (alpha_l a + beta_l g) + c(N,l) Q_N (a + N g) ),
///   a = y(k) - y_d (the current output error),  g = Bt v_old,
///   alpha_l = sum_{i<N} c(i,l),  beta_l = sum_{i<N} i c(i,l)
/// ```
///
/// which is `H = (G2 L)' Q (G2 L) + R`, `f = (G2 L)' Q (S x_s + G1 U_old - Y_d)`
/// for a constant set-point `Y_d`: the QP `min 1/2 dU'H dU + f'dU` has the
/// minimiser of eq 20 (the cost halved).
///
/// An optional velocity term `sum_{j<N} u(k+j)' W u(k+j)` (`W` diagonal,
/// [`super::MpcOptions::velocity_weights`]; not in eq 20) adds, with
/// `u(k+j) = v_old + sum_{l<=min(j,M-1)} du(l)`,
///
/// ```text
/// H[l][m] += (N - max(l, m)) W,    f[l] += (N - l) W v_old.
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Condensation {
    horizon: usize,
    control_horizon: usize,
    k_tracking: Vec<f64>,
    k_terminal: Vec<f64>,
    alpha: Vec<f64>,
    beta: Vec<f64>,
    terminal: Vec<f64>,
}

impl Condensation {
    /// Precomputes the horizon sums for `N`, `M`.
    pub fn new(horizon: usize, control_horizon: usize) -> Result<Self> {
        check_horizons(horizon, control_horizon)?;
        let m = control_horizon;
        let mut k_tracking = vec![0.0; m * m];
        let mut k_terminal = vec![0.0; m * m];
        for l in 0..m {
            for r in 0..m {
                k_tracking[l * m + r] = (1..horizon)
                    .map(|i| increment_coefficient(i, l) * increment_coefficient(i, r))
                    .sum();
                k_terminal[l * m + r] =
                    increment_coefficient(horizon, l) * increment_coefficient(horizon, r);
            }
        }
        let alpha = (0..m)
            .map(|l| (1..horizon).map(|i| increment_coefficient(i, l)).sum())
            .collect();
        let beta = (0..m)
            .map(|l| {
                (1..horizon)
                    .map(|i| i as f64 * increment_coefficient(i, l))
                    .sum()
            })
            .collect();
        let terminal = (0..m).map(|l| increment_coefficient(horizon, l)).collect();
        Ok(Condensation {
            horizon,
            control_horizon,
            k_tracking,
            k_terminal,
            alpha,
            beta,
            terminal,
        })
    }

    /// Prediction horizon `N`.
    pub fn horizon(&self) -> usize {
        self.horizon
    }

    /// Control horizon `M`.
    pub fn control_horizon(&self) -> usize {
        self.control_horizon
    }

    /// Writes the upper triangle (column-major, see
    /// [`super::qp::upper_index`]) of `H` (`M nu x M nu`) from
    /// `Bt'Q Bt` and `Bt'Q_N Bt` (`nu x nu`, row-major, symmetric), the
    /// increment weights `R` and the velocity weights `W` (`nu` each).
    /// Allocates nothing.
    pub fn fill_hessian(
        &self,
        tracking: &[f64],
        terminal: &[f64],
        increment_weights: &[f64],
        velocity_weights: &[f64],
        hessian_upper: &mut [f64],
    ) {
        let nu = increment_weights.len();
        let m = self.control_horizon;
        for col in 0..m * nu {
            let (cb, cj) = (col / nu, col % nu);
            for row in 0..=col {
                let (rb, rj) = (row / nu, row % nu);
                let k1 = self.k_tracking[rb * m + cb];
                let k2 = self.k_terminal[rb * m + cb];
                let mut value = k1 * tracking[rj * nu + cj] + k2 * terminal[rj * nu + cj];
                if rj == cj {
                    let after = (self.horizon - rb.max(cb)) as f64;
                    value += after * velocity_weights[rj];
                    if row == col {
                        value += increment_weights[rj];
                    }
                }
                hessian_upper[super::qp::upper_index(row, col)] = value;
            }
        }
    }

    /// Writes the gradient `f` (`M nu`) from `Bt` (`6 x nu`, row-major), the
    /// output error `a = y(k) - y_d` (6), `g = Bt v_old` (6), the diagonal
    /// weights `Q`, `Q_N` (6 each), and `W v_old` (`nu`, the velocity
    /// term). Allocates nothing.
    #[allow(clippy::too_many_arguments)]
    pub fn fill_gradient(
        &self,
        bt: &[f64],
        error: &[f64; 6],
        drift: &[f64; 6],
        tracking_weights: &[f64; 6],
        terminal_weights: &[f64; 6],
        weighted_velocity: &[f64],
        gradient: &mut [f64],
    ) {
        let nu = bt.len() / 6;
        let n = self.horizon as f64;
        for l in 0..self.control_horizon {
            let mut weighted = [0.0; 6];
            for r in 0..6 {
                weighted[r] = tracking_weights[r]
                    * (self.alpha[l] * error[r] + self.beta[l] * drift[r])
                    + self.terminal[l] * terminal_weights[r] * (error[r] + n * drift[r]);
            }
            let after = (self.horizon - l) as f64;
            for j in 0..nu {
                gradient[l * nu + j] = (0..6).map(|r| bt[r * nu + j] * weighted[r]).sum::<f64>()
                    + after * weighted_velocity[j];
            }
        }
    }
}

impl Condensation {
    /// Adds to the gradient `f` (`M nu`) the term of a joint-space output
    /// `q(k+i)` (`Bt = T I`, `A = I`) with error `a = q(k) - q_g`
    /// (`posture_error`, `nu`), drift `g = T v_old`, and scalar weights
    /// `tracking` on samples `1..N-1` and `terminal` on sample `N`: the
    /// formula of [`Condensation::fill_gradient`] with `Bt = T I`. The
    /// Hessian's share, `T^2 w I`, is added to the Gram matrices by the
    /// caller. Allocates nothing.
    pub fn add_joint_gradient(
        &self,
        sample_time: f64,
        posture_error: &[f64],
        previous_velocity: &[f64],
        tracking: f64,
        terminal: f64,
        gradient: &mut [f64],
    ) {
        let nu = posture_error.len();
        let n = self.horizon as f64;
        for l in 0..self.control_horizon {
            for j in 0..nu {
                let (a, g) = (posture_error[j], sample_time * previous_velocity[j]);
                let weighted = tracking * (self.alpha[l] * a + self.beta[l] * g)
                    + self.terminal[l] * terminal * (a + n * g);
                gradient[l * nu + j] += sample_time * weighted;
            }
        }
    }
}

/// `Bt' diag(w) Bt` (`nu x nu`, row-major) for `Bt` (`6 x nu`, row-major).
/// Allocates nothing.
pub fn weighted_gram(bt: &[f64], weights: &[f64; 6], out: &mut [f64]) {
    let nu = bt.len() / 6;
    for i in 0..nu {
        for j in i..nu {
            let v: f64 = (0..6)
                .map(|r| weights[r] * bt[r * nu + i] * bt[r * nu + j])
                .sum();
            out[i * nu + j] = v;
            out[j * nu + i] = v;
        }
    }
}
