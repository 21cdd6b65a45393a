//! The simulated manipulator of a run: a fixed-base arm or an attitude-held
//! free-floating system, behind one interface (pose, Jacobian, stepping,
//! position-level IK).
//!
//! Both systems are *holonomic*: the end-effector pose is a function `F(q)`
//! of the joint positions alone. On a fixed base this is forward kinematics.
//! With the base attitude held and zero linear momentum the system's centre
//! of mass stays where it started, so the base position is fixed by `q`
//! (seed 004, eqs 10-16), and `F(q)` is the pose with the base placed so that
//! the centre of mass is back at its start; `J* = dF/dq` (eq 17; `J*` does not
//! depend on the base position, only on its attitude, which is held).

use super::Manipulator;
use crate::error::Result;
use crate::ik::{damped_least_squares_step, pose_error, IkMethod, IkOptions, IkReport, IkSolver};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Matrix6xX, Pose, Vector3};
use crate::model::Model;
use crate::space::{
    center_of_mass, generalized_jacobian, step, BaseMode, FreeFloatingModel, FreeFloatingState,
    SpaceData,
};

/// One position-level IK solve of a knot of a singular region.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct KnotSolve {
    pub q: Vec<f64>,
    pub converged: bool,
    pub iterations: usize,
    pub position_error: f64,
    pub orientation_error: f64,
}

impl KnotSolve {
    /// No solve yet, at `q`: unconverged, infinite errors (any iterate is
    /// better).
    fn not_started(q: &[f64]) -> KnotSolve {
        KnotSolve {
            q: q.to_vec(),
            converged: false,
            iterations: 0,
            position_error: f64::INFINITY,
            orientation_error: f64::INFINITY,
        }
    }
}

/// Iterations of the reachability check's solves.
const REACH_ITERATIONS: usize = 200;
/// Position (m) and orientation (rad) tolerance of the reachability check
/// (that of [`IkOptions::default`]).
const REACH_TOLERANCE: f64 = 1e-6;

/// The update rule of an IK on the held system's constrained map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Iteration {
    /// Every step `J*^+ e` taken.
    Newton,
    /// Damped steps, taken only when they lower the error.
    LevenbergMarquardt,
}

fn knot_from_report(report: IkReport) -> KnotSolve {
    KnotSolve {
        converged: report.converged(),
        q: report.q,
        iterations: report.iterations,
        position_error: report.position_error,
        orientation_error: report.orientation_error,
    }
}

// One plant per run, built once: the variants' sizes do not matter, and
// boxing them would add an indirection on every step.
#[allow(clippy::large_enum_variant)]
enum System<'m> {
    Fixed {
        arm: &'m Model,
        data: Data,
        /// Newton-Raphson (seed 004, Fig 2), warm-started, no restarts.
        newton: IkSolver,
        /// The default solver (Levenberg-Marquardt, seeded restarts), for
        /// the reachability check.
        robust: IkSolver,
    },
    AttitudeHeld {
        model: &'m FreeFloatingModel,
        data: SpaceData,
        /// Simulated state: base pose (inertial frame) and joints.
        state: FreeFloatingState,
        /// The system's centre of mass, fixed by zero linear momentum (m).
        com: Vector3<f64>,
    },
}

/// A manipulator being driven along a path: its state, and workspaces sized once.
pub(crate) struct Plant<'m> {
    system: System<'m>,
    /// Joint positions of a fixed-base arm (the held system keeps its own in `state`).
    q: Vec<f64>,
    /// Pose `F(q)` and Jacobian at the last [`Plant::evaluate`] (inertial frame).
    pose: Pose,
    jacobian: Matrix6xX<f64>,
    /// Newton step workspace.
    step: Vec<f64>,
    /// Copy of the state's joint positions for [`Plant::evaluate_state`].
    scratch: Vec<f64>,
    ik_tolerance: f64,
    ik_max_iterations: usize,
}

impl<'m> Plant<'m> {
    /// The manipulator at joint positions `q0` (rad or m).
    pub fn new(
        manipulator: &Manipulator<'m>,
        q0: &[f64],
        ik_tolerance: f64,
        ik_max_iterations: usize,
    ) -> Result<Plant<'m>> {
        let system = match *manipulator {
            Manipulator::FixedBase(arm) => {
                arm.check_joint_positions(q0)?;
                let options = IkOptions {
                    method: IkMethod::NewtonRaphson,
                    position_tolerance: ik_tolerance,
                    orientation_tolerance: ik_tolerance,
                    max_iterations: ik_max_iterations,
                    max_restarts: 0,
                    time_budget: None,
                    ..IkOptions::default()
                };
                System::Fixed {
                    arm,
                    data: Data::new(arm),
                    newton: IkSolver::new(arm, options)?,
                    // No time budget: a loaded machine must not turn a
                    // reachable path into an "out of reach" error (the
                    // restarts are seeded, so the check is deterministic).
                    robust: IkSolver::new(
                        arm,
                        IkOptions {
                            time_budget: None,
                            ..IkOptions::default()
                        },
                    )?,
                }
            }
            Manipulator::AttitudeHeld { system, base } => {
                system.arm().check_joint_positions(q0)?;
                let mut data = SpaceData::new(system);
                let com = center_of_mass(system, &mut data, &base, q0)?;
                System::AttitudeHeld {
                    model: system,
                    data,
                    state: FreeFloatingState::new(base, q0.to_vec()),
                    com,
                }
            }
        };
        let n = q0.len();
        Ok(Plant {
            system,
            q: q0.to_vec(),
            pose: Pose::identity(),
            jacobian: Matrix6xX::zeros(n),
            step: vec![0.0; n],
            scratch: vec![0.0; n],
            ik_tolerance,
            ik_max_iterations,
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.q.len()
    }

    /// The current joint positions.
    pub fn q(&self) -> &[f64] {
        match &self.system {
            System::Fixed { .. } => &self.q,
            System::AttitudeHeld { state, .. } => &state.q,
        }
    }

    /// The current base pose (inertial frame); the arm's world frame for a fixed base.
    pub fn base_pose(&self) -> Pose {
        match &self.system {
            System::Fixed { .. } => Pose::identity(),
            System::AttitudeHeld { state, .. } => state.base,
        }
    }

    /// The base pose (inertial frame) the system has at joint positions `q`:
    /// the held attitude, and the position that puts the centre of mass where
    /// it started. The identity on a fixed base.
    pub fn base_at(&mut self, q: &[f64]) -> Result<Pose> {
        match &mut self.system {
            System::Fixed { .. } => Ok(Pose::identity()),
            System::AttitudeHeld {
                model,
                data,
                state,
                com,
            } => {
                let placed = center_of_mass(model, data, &state.base, q)?;
                let mut base = state.base;
                base.translation += *com - placed;
                Ok(base)
            }
        }
    }

    /// Pose of the last evaluation.
    pub fn pose(&self) -> &Pose {
        &self.pose
    }

    /// Jacobian of the last evaluation (`J` or `J*`, 6 x n, inertial frame).
    pub fn jacobian(&self) -> &Matrix6xX<f64> {
        &self.jacobian
    }

    /// `F(q)` and its Jacobian at arbitrary joint positions `q` (the state is
    /// not changed). Allocates nothing.
    pub fn evaluate(&mut self, q: &[f64]) -> Result<()> {
        match &mut self.system {
            System::Fixed { arm, data, .. } => {
                let j = jacobian(arm, data, q, JacobianFrame::World)?;
                self.jacobian.copy_from(j);
                self.pose = *data.end_effector_pose();
            }
            System::AttitudeHeld {
                model,
                data,
                state,
                com,
            } => {
                // The base attitude is the held one; its position is placed
                // so that the centre of mass is where it started (P = 0).
                let j = generalized_jacobian(model, data, &state.base, q, BaseMode::AttitudeHeld)?;
                self.jacobian.copy_from(j);
                let shift = *com - *data.center_of_mass();
                self.pose = *data.end_effector_pose();
                self.pose.translation += shift;
            }
        }
        Ok(())
    }

    /// Evaluates at the current state.
    pub fn evaluate_state(&mut self) -> Result<()> {
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.copy_from_slice(self.q());
        let result = self.evaluate(&scratch);
        self.scratch = scratch;
        result
    }

    /// Advances the state by `h` seconds at constant joint rates (rad/s or
    /// m/s): `q += h q_dot`; the held system's base moves by
    /// [`crate::space::step`] (centre of mass fixed, attitude held).
    pub fn advance(&mut self, rates: &[f64], h: f64) -> Result<()> {
        match &mut self.system {
            System::Fixed { .. } => {
                for (q, rate) in self.q.iter_mut().zip(rates) {
                    *q += rate * h;
                }
                Ok(())
            }
            System::AttitudeHeld {
                model, data, state, ..
            } => step(model, data, state, rates, h, BaseMode::AttitudeHeld),
        }
    }

    /// Newton-Raphson IK of `target` (inertial frame) from `start` (seed 004,
    /// Fig 2, warm-started; no restarts: continuity with the start is the point).
    ///
    /// Fixed base: [`IkSolver`] with [`IkMethod::NewtonRaphson`]. Attitude
    /// held: Newton on the constrained map, `q += J*^+ e(target, F(q))`, so
    /// that the base's reaction is part of the map being inverted (solving on
    /// the fixed-base kinematics from the current base pose would miss by the
    /// base's motion; see the module documentation of [`super`]).
    pub fn solve_ik(&mut self, target: &Pose, start: &[f64]) -> Result<KnotSolve> {
        match &mut self.system {
            System::Fixed { newton, .. } => Ok(knot_from_report(newton.solve(target, start)?)),
            System::AttitudeHeld { .. } => self.held_solve(target, start, Iteration::Newton),
        }
    }

    /// A robust IK of `target` from `start`, for checking that a path is
    /// within reach: [`IkSolver`]'s default (Levenberg-Marquardt with seeded
    /// restarts) on a fixed base, Levenberg-Marquardt with Sugihara's damping
    /// on the constrained map of the held system.
    pub fn reach(&mut self, target: &Pose, start: &[f64]) -> Result<KnotSolve> {
        match &mut self.system {
            System::Fixed { robust, .. } => Ok(knot_from_report(robust.solve(target, start)?)),
            System::AttitudeHeld { .. } => {
                self.held_solve(target, start, Iteration::LevenbergMarquardt)
            }
        }
    }

    /// The least-squares knot within reach: the joint positions within
    /// `radius` (rad or m, every joint) of `centre` whose pose is nearest
    /// `target` (inertial frame), by Levenberg-Marquardt with Sugihara's
    /// damping on the box (`min |e(target, F(q))|^2` over
    /// `|q_j - centre_j| <= radius`), from `start` clamped into the box.
    ///
    /// Each iteration solves the damped step on the free joints, clamps the
    /// joints that would leave the box at its face and solves again without
    /// them (at most n rounds), and keeps the step only when it lowers the
    /// error. Converged when the pose is within the IK tolerance; otherwise
    /// the best iterate, with its errors (a near miss of a singular pose asks
    /// the wrist to turn faster than the box allows: the knot is then the
    /// nearest pose the arm reaches).
    pub fn bounded_solve(
        &mut self,
        target: &Pose,
        centre: &[f64],
        radius: f64,
        start: &[f64],
    ) -> Result<KnotSolve> {
        let lower: Vec<f64> = centre.iter().map(|c| c - radius).collect();
        let upper: Vec<f64> = centre.iter().map(|c| c + radius).collect();
        self.box_solve(target, &lower, &upper, start)
    }

    /// The joint positions within `lower <= q <= upper` (rad or m, every
    /// joint; a joint with equal bounds is held) whose pose is nearest
    /// `target`, by the box-constrained Levenberg-Marquardt of
    /// [`Plant::bounded_solve`], from `start` clamped into the box.
    pub fn box_solve(
        &mut self,
        target: &Pose,
        lower: &[f64],
        upper: &[f64],
        start: &[f64],
    ) -> Result<KnotSolve> {
        let n = self.dof();
        let mut q: Vec<f64> = start
            .iter()
            .zip(lower.iter().zip(upper))
            .map(|(s, (lo, hi))| s.clamp(*lo, *hi))
            .collect();
        let mut trial = q.clone();
        let mut delta = vec![0.0; n];
        let mut step = vec![0.0; n];
        let mut fixed = vec![false; n];
        let mut free_jacobian = Matrix6xX::zeros(n);
        let tolerance = self.ik_tolerance;
        let mut best = KnotSolve::not_started(&q);
        self.evaluate(&q)?;
        let mut error = pose_error(target, &self.pose);
        let mut best_norm = f64::INFINITY;
        let mut damping_scale = 1.0;
        for used in 0..=self.ik_max_iterations {
            let position = error.fixed_rows::<3>(0).norm();
            let orientation = error.fixed_rows::<3>(3).norm();
            best.iterations = used;
            if error.norm() < best_norm {
                best_norm = error.norm();
                best.q.copy_from_slice(&q);
                best.position_error = position;
                best.orientation_error = orientation;
            }
            if position <= tolerance && orientation <= tolerance {
                best.converged = true;
                break;
            }
            // A box-constrained minimum: no step lowers the error any more.
            if used == self.ik_max_iterations || damping_scale > 1e12 {
                break;
            }
            let objective = 0.5 * error.norm_squared();
            let damping = (damping_scale * (objective + 1e-12)).sqrt();
            fixed.iter_mut().for_each(|f| *f = false);
            delta.iter_mut().for_each(|d| *d = 0.0);
            for _ in 0..n {
                // The damped step of the free joints, with the clamped ones'
                // motion taken out of the error (their columns zeroed, so
                // that their step is zero).
                free_jacobian.copy_from(&self.jacobian);
                let mut rest = error;
                for j in (0..n).filter(|&j| fixed[j]) {
                    rest -= self.jacobian.column(j) * delta[j];
                    free_jacobian.column_mut(j).fill(0.0);
                }
                damped_least_squares_step(&free_jacobian, &rest, damping, &mut step)?;
                let mut clamped = false;
                for j in 0..n {
                    if fixed[j] {
                        continue;
                    }
                    let (lo, hi) = (lower[j] - q[j], upper[j] - q[j]);
                    delta[j] = step[j];
                    if !(lo..=hi).contains(&delta[j]) {
                        delta[j] = delta[j].clamp(lo.min(0.0), hi.max(0.0));
                        fixed[j] = true;
                        clamped = true;
                    }
                }
                if !clamped {
                    break;
                }
            }
            for j in 0..n {
                trial[j] = (q[j] + delta[j]).clamp(lower[j], upper[j]);
            }
            self.evaluate(&trial)?;
            let trial_error = pose_error(target, &self.pose);
            if 0.5 * trial_error.norm_squared() < objective {
                std::mem::swap(&mut q, &mut trial);
                error = trial_error;
                damping_scale = (damping_scale * 0.5).max(1.0);
            } else {
                damping_scale *= 10.0;
                self.evaluate(&q)?;
            }
        }
        Ok(best)
    }

    /// Iterates on the held system's constrained map `F(q)` with `J*`.
    fn held_solve(
        &mut self,
        target: &Pose,
        start: &[f64],
        iteration: Iteration,
    ) -> Result<KnotSolve> {
        let (max_iterations, tolerance) = match iteration {
            Iteration::Newton => (self.ik_max_iterations, self.ik_tolerance),
            Iteration::LevenbergMarquardt => (REACH_ITERATIONS, REACH_TOLERANCE),
        };
        let mut q = start.to_vec();
        let mut trial = start.to_vec();
        let mut best = KnotSolve::not_started(&q);
        let mut step = std::mem::take(&mut self.step);
        let mut damping_scale = 1.0;
        let outcome = (|| -> Result<()> {
            self.evaluate(&q)?;
            let mut error = pose_error(target, &self.pose);
            for used in 0..=max_iterations {
                let position = error.fixed_rows::<3>(0).norm();
                let orientation = error.fixed_rows::<3>(3).norm();
                best.iterations = used;
                if position.max(orientation) < best.position_error.max(best.orientation_error) {
                    best.q.copy_from_slice(&q);
                    best.position_error = position;
                    best.orientation_error = orientation;
                }
                if position <= tolerance && orientation <= tolerance {
                    best.converged = true;
                    return Ok(());
                }
                if used == max_iterations {
                    return Ok(());
                }
                let objective = 0.5 * error.norm_squared();
                let damping = match iteration {
                    // The plain inverse; at an exactly singular J* a damping
                    // lambda = 1e-6 |J*| keeps the step finite (as
                    // IkMethod::NewtonRaphson does with 1e-12 of trace(J J')).
                    Iteration::Newton => 0.0,
                    // Sugihara: lambda^2 = E + w_N, grown on a rejected step.
                    Iteration::LevenbergMarquardt => (damping_scale * (objective + 1e-9)).sqrt(),
                };
                if damped_least_squares_step(&self.jacobian, &error, damping, &mut step).is_err() {
                    let fallback = 1e-6 * self.jacobian.norm();
                    damped_least_squares_step(&self.jacobian, &error, fallback, &mut step)?;
                }
                for ((t, value), delta) in trial.iter_mut().zip(&q).zip(&step) {
                    *t = value + delta;
                }
                self.evaluate(&trial)?;
                let trial_error = pose_error(target, &self.pose);
                let accept = match iteration {
                    Iteration::Newton => true,
                    Iteration::LevenbergMarquardt => 0.5 * trial_error.norm_squared() < objective,
                };
                if accept {
                    std::mem::swap(&mut q, &mut trial);
                    error = trial_error;
                    damping_scale = (damping_scale * 0.5).max(1.0);
                } else {
                    damping_scale *= 10.0;
                    self.evaluate(&q)?;
                }
            }
            Ok(())
        })();
        self.step = step;
        outcome?;
        Ok(best)
    }
}

/// The tracking loop's view: the state is evaluated by
/// [`Plant::evaluate_state`], the pose is `F(q)`.
impl crate::tracking::Plant for Plant<'_> {
    fn dof(&self) -> usize {
        Plant::dof(self)
    }

    fn joint_positions(&self) -> &[f64] {
        self.q()
    }

    fn evaluate(&mut self) -> Result<()> {
        self.evaluate_state()
    }

    fn end_effector(&self) -> &Pose {
        self.pose()
    }

    fn jacobian(&self) -> &Matrix6xX<f64> {
        Plant::jacobian(self)
    }

    fn base(&self) -> Pose {
        self.base_pose()
    }

    fn advance(&mut self, rates: &[f64], dt: f64) -> Result<()> {
        Plant::advance(self, rates, dt)
    }
}
