//! Integrating the forward dynamics in time, with optional joint friction.
//!
//! ```
//! use armkit::dynamics::simulate::{Integrator, SimulationOptions, Simulator};
//! let model = armkit::robots::by_name("space6r").unwrap();
//! let options = SimulationOptions { time_step: 1e-3, integrator: Integrator::RungeKutta4, ..Default::default() };
//! let mut sim = Simulator::new(&model, options).unwrap();
//! let (mut q, mut v) = (vec![0.0; 6], vec![0.0; 6]);
//! // Let the arm fall under gravity for 10 ms, motors off.
//! for _ in 0..10 {
//!     sim.step(&model, &mut q, &mut v, &[0.0; 6]).unwrap();
//! }
//! assert!(v.iter().any(|x| x.abs() > 1e-3));
//! ```

use std::fmt;

use super::{aba, DynamicsData};
use crate::error::{check_finite_vector, check_positive, Error, Result};
use crate::model::Model;

/// The time-stepping scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// `v += h ddq(q, v)`, then `q += h v` (symplectic Euler, first order,
    /// one ABA per step; energy oscillates but does not drift secularly).
    SemiImplicitEuler,
    /// Classical fourth-order Runge-Kutta on `(q, v)` (four ABAs per step).
    RungeKutta4,
}

impl Integrator {
    /// Short name: `semi-implicit-euler` or `rk4`.
    pub fn as_str(self) -> &'static str {
        match self {
            Integrator::SemiImplicitEuler => "semi-implicit-euler",
            Integrator::RungeKutta4 => "rk4",
        }
    }
}

impl fmt::Display for Integrator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Joint friction torques `tau_f = -(b v + c sign(v))` per joint: viscous
/// coefficients `b` (N m s/rad, N s/m for prismatic joints) and Coulomb
/// levels `c` (N m or N), both >= 0, one per joint.
#[derive(Clone, Debug, PartialEq)]
pub struct JointFriction {
    /// Viscous coefficients `b`, one per joint.
    pub viscous: Vec<f64>,
    /// Coulomb friction levels `c`, one per joint.
    pub coulomb: Vec<f64>,
}

impl JointFriction {
    /// Checks sizes (`dof` each) and that every value is finite and >= 0.
    pub fn validate(&self, dof: usize) -> Result<()> {
        for (what, values) in [
            ("friction.viscous", &self.viscous),
            ("friction.coulomb", &self.coulomb),
        ] {
            check_finite_vector(what, values, dof)?;
            if let Some(index) = values.iter().position(|&x| x < 0.0) {
                return Err(Error::invalid_argument(
                    what,
                    format!("must be >= 0, got {} at joint {index}", values[index]),
                ));
            }
        }
        Ok(())
    }

    /// Adds the friction torques at velocities `v` to `tau`.
    fn add_to(&self, v: &[f64], tau: &mut [f64]) {
        for (((t, &qd), &b), &c) in tau.iter_mut().zip(v).zip(&self.viscous).zip(&self.coulomb) {
            let sign = if qd > 0.0 {
                1.0
            } else if qd < 0.0 {
                -1.0
            } else {
                0.0
            };
            *t -= b * qd + c * sign;
        }
    }
}

/// Options of a [`Simulator`].
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationOptions {
    /// Time step `h`, s (> 0). Default 1 ms.
    pub time_step: f64,
    /// The scheme. Default [`Integrator::RungeKutta4`].
    pub integrator: Integrator,
    /// Joint friction, or `None` (default) for none.
    pub friction: Option<JointFriction>,
}

impl Default for SimulationOptions {
    fn default() -> Self {
        SimulationOptions {
            time_step: 1e-3,
            integrator: Integrator::RungeKutta4,
            friction: None,
        }
    }
}

impl SimulationOptions {
    /// Checks the time step and the friction's sizes and signs for a robot
    /// with `dof` joints.
    pub fn validate(&self, dof: usize) -> Result<()> {
        check_positive("time_step", self.time_step)?;
        if let Some(friction) = &self.friction {
            friction.validate(dof)?;
        }
        Ok(())
    }
}

/// Integrates `M(q) ddq + C(q, v) v + g(q) = tau + tau_friction(v)` in time,
/// one step at a time. Joint limits are not enforced (a joint may pass its
/// limit; check with [`Model::check_limits`]). The gravity is the
/// workspace's ([`Simulator::data_mut`], default `(0, 0, -9.81)` m/s^2).
#[derive(Clone, Debug)]
pub struct Simulator {
    options: SimulationOptions,
    data: DynamicsData,
    tau: Vec<f64>,
    q_stage: Vec<f64>,
    v_stage: Vec<f64>,
    /// RK4 slopes: `dq` and `dv` of the four stages.
    dq: [Vec<f64>; 4],
    dv: [Vec<f64>; 4],
}

impl Simulator {
    /// A simulator for `model`. Errors: invalid options, a model without
    /// mass properties or with a coupling.
    pub fn new(model: &Model, options: SimulationOptions) -> Result<Self> {
        options.validate(model.dof())?;
        let n = model.dof();
        Ok(Simulator {
            options,
            data: DynamicsData::new(model)?,
            tau: vec![0.0; n],
            q_stage: vec![0.0; n],
            v_stage: vec![0.0; n],
            dq: std::array::from_fn(|_| vec![0.0; n]),
            dv: std::array::from_fn(|_| vec![0.0; n]),
        })
    }

    /// The options.
    pub fn options(&self) -> &SimulationOptions {
        &self.options
    }

    /// The dynamics workspace (to set the gravity, or read the last results).
    pub fn data_mut(&mut self) -> &mut DynamicsData {
        &mut self.data
    }

    /// Advances `(q, v)` by one time step under joint torques `tau` (N m or
    /// N, held constant over the step), in place. Errors: sizes, NaN, a state
    /// that becomes non-finite. Allocates nothing.
    pub fn step(&mut self, model: &Model, q: &mut [f64], v: &mut [f64], tau: &[f64]) -> Result<()> {
        model.check_joint_positions(q)?;
        check_finite_vector("joint_velocities", v, model.dof())?;
        check_finite_vector("joint_torques", tau, model.dof())?;
        let h = self.options.time_step;
        match self.options.integrator {
            Integrator::SemiImplicitEuler => {
                self.accelerations_at(model, q, v, tau, 0)?;
                for ((qj, vj), &aj) in q.iter_mut().zip(v.iter_mut()).zip(&self.dv[0]) {
                    *vj += h * aj;
                    *qj += h * *vj;
                }
            }
            Integrator::RungeKutta4 => self.runge_kutta_4(model, q, v, tau, h)?,
        }
        check_finite_vector("joint_positions (after the step)", q, model.dof())?;
        check_finite_vector("joint_velocities (after the step)", v, model.dof())
    }

    fn runge_kutta_4(
        &mut self,
        model: &Model,
        q: &mut [f64],
        v: &mut [f64],
        tau: &[f64],
        h: f64,
    ) -> Result<()> {
        // Stage k evaluates at (q, v) + f_k h (slopes of stage k - 1).
        for (stage, fraction) in [0.0, 0.5, 0.5, 1.0].into_iter().enumerate() {
            if stage == 0 {
                self.q_stage.copy_from_slice(q);
                self.v_stage.copy_from_slice(v);
            } else {
                let f = fraction * h;
                let (dq, dv) = (&self.dq[stage - 1], &self.dv[stage - 1]);
                for j in 0..q.len() {
                    self.q_stage[j] = q[j] + f * dq[j];
                    self.v_stage[j] = v[j] + f * dv[j];
                }
            }
            self.dq[stage].copy_from_slice(&self.v_stage);
            let (qs, vs) = (
                std::mem::take(&mut self.q_stage),
                std::mem::take(&mut self.v_stage),
            );
            let result = self.accelerations_at(model, &qs, &vs, tau, stage);
            self.q_stage = qs;
            self.v_stage = vs;
            result?;
        }
        for j in 0..q.len() {
            q[j] += h / 6.0
                * (self.dq[0][j] + 2.0 * self.dq[1][j] + 2.0 * self.dq[2][j] + self.dq[3][j]);
            v[j] += h / 6.0
                * (self.dv[0][j] + 2.0 * self.dv[1][j] + 2.0 * self.dv[2][j] + self.dv[3][j]);
        }
        Ok(())
    }

    /// `ddq(q, v)` with friction, into `dv[stage]`.
    fn accelerations_at(
        &mut self,
        model: &Model,
        q: &[f64],
        v: &[f64],
        tau: &[f64],
        stage: usize,
    ) -> Result<()> {
        self.tau.copy_from_slice(tau);
        if let Some(friction) = &self.options.friction {
            friction.add_to(v, &mut self.tau);
        }
        let ddq = aba(model, &mut self.data, q, v, &self.tau)?;
        self.dv[stage].copy_from_slice(ddq);
        Ok(())
    }
}
