//! Closed-loop simulation of the planner.
//!
//! [`simulate`] runs the planner against a kinematic plant and records
//! every sample, the limits crossed (velocity and position: both are 0 when
//! no limit is crossed) and whether the run converged. The plant is
//! [`SimulationOptions::plant`]: by default it integrates the commanded
//! joint velocities exactly over each sample (`q(k+1) = q(k) + T u(k)`,
//! what a joint velocity servo does to a velocity held for one sample);
//! [`super::PlantModel::LimitedPrecision`] gives the joints a finite
//! position resolution, deadband or velocity quantisation. Seed 000's
//! examples (sec 5) run on it in `armkit::study` (`Seed000Example`).
//!
//! ```
//! use armkit::kinematics::{forward_kinematics, Data};
//! use armkit::math::{Pose, Vector3};
//! use armkit::mpc::scenario::{simulate, SimulationOptions};
//! use armkit::mpc::{MpcOptions, TaskWeights};
//! let model = armkit::robots::by_name("panda").unwrap();
//! let start = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
//! let pose = *forward_kinematics(&model, &mut Data::new(&model), &start).unwrap();
//! let target = Pose::new(pose.rotation, pose.translation + Vector3::new(0.05, -0.05, 0.05));
//! let options = MpcOptions {
//!     task_weights: TaskWeights::position_only(10.0, 200.0),
//!     ..MpcOptions::default()
//! };
//! let run = simulate(&model, options, &start, &target, &SimulationOptions::default()).unwrap();
//! assert!(run.summary.converged);
//! assert_eq!(run.summary.max_velocity_violation, 0.0);
//! assert_eq!(run.summary.max_position_violation, 0.0);
//! ```

use super::{MpcOptions, MpcPlanner, Plant, PlantModel, StepStatus};
use crate::error::{check_positive, Error, Result};
use crate::math::Pose;
use crate::model::{JointKind, Model};

/// When a run counts as converged, and how long it may take.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationOptions {
    /// Most planner steps to run (> 0). Default 2000.
    pub max_steps: usize,
    /// Position error below which the target counts as reached, m. Default 1e-4.
    pub position_tolerance: f64,
    /// Orientation error below which the target counts as reached, rad
    /// (only when the task weights track orientation). Default 1e-3.
    pub orientation_tolerance: f64,
    /// Every joint speed must be below this, m/s or rad/s. Default 1e-3.
    pub velocity_tolerance: f64,
    /// Steps to keep running after convergence (so that plots show the
    /// robot at rest). Default 0.
    pub hold_steps: usize,
    /// How the joints follow the commanded velocities. Default
    /// [`PlantModel::Exact`]; [`PlantModel::LimitedPrecision`] models
    /// actuators of finite resolution (seed 000, Example 3).
    pub plant: PlantModel,
}

impl Default for SimulationOptions {
    fn default() -> Self {
        SimulationOptions {
            max_steps: 2000,
            position_tolerance: 1e-4,
            orientation_tolerance: 1e-3,
            velocity_tolerance: 1e-3,
            hold_steps: 0,
            plant: PlantModel::Exact,
        }
    }
}

impl SimulationOptions {
    /// Checks `max_steps > 0`, positive finite tolerances and the plant
    /// ([`PlantModel::validate`]).
    pub fn validate(&self) -> Result<()> {
        if self.max_steps == 0 {
            return Err(Error::invalid_argument("max_steps", "must be at least 1"));
        }
        for (name, value) in [
            ("position_tolerance", self.position_tolerance),
            ("orientation_tolerance", self.orientation_tolerance),
            ("velocity_tolerance", self.velocity_tolerance),
        ] {
            check_positive(name, value)?;
        }
        self.plant.validate()
    }
}

/// One recorded sample: the state at time `time` and the input applied from
/// it until the next sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Time, s (`k T`).
    pub time: f64,
    /// Joint positions, m or rad.
    pub q: Vec<f64>,
    /// Joint velocities commanded for `[t, t + T)`, m/s or rad/s.
    pub velocity: Vec<f64>,
    /// End-effector position, m, world frame.
    pub position: [f64; 3],
    /// End-effector roll, pitch, yaw, rad (`R = Rz(yaw) Ry(pitch) Rx(roll)`).
    pub rpy: [f64; 3],
    /// Distance to the target position, m.
    pub position_error: f64,
    /// Rotation angle to the target orientation, rad.
    pub orientation_error: f64,
    /// The planner's status for this step.
    pub status: StepStatus,
    /// QP iterations.
    pub iterations: u32,
}

/// Totals of a closed-loop run.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSummary {
    /// The target was reached and the robot stopped (see [`SimulationOptions`]).
    pub converged: bool,
    /// Planner steps run until convergence (or `max_steps`), hold steps excluded.
    pub steps: usize,
    /// Position error at the last sample, m.
    pub final_position_error: f64,
    /// Orientation error at the last sample, rad.
    pub final_orientation_error: f64,
    /// Largest amount by which a commanded joint speed exceeded its limit
    /// (m/s or rad/s) over the run; 0 when no limit is crossed.
    pub max_velocity_violation: f64,
    /// Largest amount by which a joint position (at any sample, the start
    /// included) was outside its limits (m or rad); 0 when no limit is
    /// crossed. Between samples joints move linearly, so no limit is crossed
    /// there either when this is 0.
    pub max_position_violation: f64,
    /// Steps whose status was not [`StepStatus::Solved`].
    pub non_solved_steps: usize,
    /// Largest one-sample prediction error of the position, m.
    pub max_prediction_error: f64,
    /// Total QP iterations.
    pub total_iterations: u64,
}

/// A recorded closed-loop run.
#[derive(Clone, Debug, PartialEq)]
pub struct MpcRun {
    /// Sample time, s.
    pub sample_time: f64,
    /// Joint names, in order.
    pub joint_names: Vec<String>,
    /// Joint kinds, in order.
    pub joint_kinds: Vec<JointKind>,
    /// The target pose.
    pub target: Pose,
    /// Whether the task weights track orientation (else only position).
    pub tracks_orientation: bool,
    /// The plant the run was simulated on.
    pub plant: PlantModel,
    /// Every sample, the last one with zero input (the final state).
    pub samples: Vec<Sample>,
    /// Totals.
    pub summary: RunSummary,
}

impl MpcRun {
    /// Indices of the prismatic joints.
    pub fn prismatic_joints(&self) -> Vec<usize> {
        (0..self.joint_kinds.len())
            .filter(|&j| self.joint_kinds[j] == JointKind::Prismatic)
            .collect()
    }

    /// Indices of the rotational joints.
    pub fn rotary_joints(&self) -> Vec<usize> {
        (0..self.joint_kinds.len())
            .filter(|&j| self.joint_kinds[j].is_rotational())
            .collect()
    }

    /// Largest |velocity| of joint `j` over the run.
    pub fn peak_speed(&self, j: usize) -> f64 {
        self.samples
            .iter()
            .map(|s| s.velocity.get(j).map_or(0.0, |v| v.abs()))
            .fold(0.0, f64::max)
    }

    /// The first sample at which the hand is within `tolerance` m of the
    /// target (`None`: never).
    pub fn first_within(&self, tolerance: f64) -> Option<usize> {
        self.samples
            .iter()
            .position(|s| s.position_error <= tolerance)
    }

    /// How often joint `j`'s commanded velocity changes sign from sample
    /// `from` on, counting only commands with `|v| > floor` (m/s or rad/s;
    /// a command at or below it is a stop, not a direction). A joint that
    /// oscillates changes direction every half period; one that settles or
    /// drifts one way does not.
    pub fn direction_changes(&self, j: usize, from: usize, floor: f64) -> usize {
        let mut last_sign = 0.0;
        let mut changes = 0;
        for s in self.samples.iter().skip(from) {
            let v = s.velocity.get(j).copied().unwrap_or(0.0);
            if v.abs() <= floor {
                continue;
            }
            let sign = v.signum();
            if last_sign != 0.0 && sign != last_sign {
                changes += 1;
            }
            last_sign = sign;
        }
        changes
    }

    /// Largest position error from sample `from` on, m (0 when `from` is
    /// past the end).
    pub fn max_position_error_from(&self, from: usize) -> f64 {
        self.samples
            .iter()
            .skip(from)
            .map(|s| s.position_error)
            .fold(0.0, f64::max)
    }

    /// Largest distance of joint `j` from its start over the run, m or rad.
    pub fn excursion(&self, j: usize) -> f64 {
        let start = self.samples.first().and_then(|s| s.q.get(j)).copied();
        start.map_or(0.0, |q0| {
            self.samples
                .iter()
                .filter_map(|s| s.q.get(j))
                .map(|q| (q - q0).abs())
                .fold(0.0, f64::max)
        })
    }

    /// Path length travelled by joint `j`: the sum of |q(k+1) - q(k)|.
    pub fn travel(&self, j: usize) -> f64 {
        self.samples
            .windows(2)
            .map(|w| (w[1].q[j] - w[0].q[j]).abs())
            .sum()
    }

    /// The CSV of the run: a header row, then one row per sample with time,
    /// joint positions, joint velocities, end-effector position and rpy, the
    /// errors and the step status.
    pub fn to_csv(&self) -> String {
        let mut header = vec!["t_s".to_string()];
        header.extend(self.joint_names.iter().map(|n| format!("q_{n}")));
        header.extend(self.joint_names.iter().map(|n| format!("v_{n}")));
        header.extend(
            ["x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"]
                .iter()
                .map(|s| s.to_string()),
        );
        header.extend(
            [
                "position_error_m",
                "orientation_error_rad",
                "status",
                "qp_iterations",
            ]
            .iter()
            .map(|s| s.to_string()),
        );
        let mut out = header.join(",");
        out.push('\n');
        for s in &self.samples {
            let mut row: Vec<String> = vec![format!("{:.4}", s.time)];
            row.extend(s.q.iter().map(|v| format!("{v:.9}")));
            row.extend(s.velocity.iter().map(|v| format!("{v:.9}")));
            row.extend(s.position.iter().chain(&s.rpy).map(|v| format!("{v:.9}")));
            row.push(format!("{:.3e}", s.position_error));
            row.push(format!("{:.3e}", s.orientation_error));
            row.push(s.status.as_str().to_string());
            row.push(s.iterations.to_string());
            out.push_str(&row.join(","));
            out.push('\n');
        }
        out
    }
}

/// Runs the planner in closed loop from `start` (joint positions) to
/// `target`, the joints following the commanded velocities as
/// [`SimulationOptions::plant`] says (exactly by default), until converged
/// (plus [`SimulationOptions::hold_steps`]) or `max_steps`.
///
/// Errors: bad options, or `start` of the wrong size / not finite. A start
/// outside the limits is allowed: the planner brings the joints back
/// ([`StepStatus::Recovering`]) and the summary reports the violation.
pub fn simulate(
    model: &Model,
    options: MpcOptions,
    start: &[f64],
    target: &Pose,
    simulation: &SimulationOptions,
) -> Result<MpcRun> {
    let planner = MpcPlanner::new(model, options)?;
    simulate_with(planner, start, target, simulation, |_| {})
}

/// As [`simulate`] with a ready planner (owned, or `&mut` to read its
/// statistics afterwards), calling `progress(step)` after each step (for
/// progress bars).
pub fn simulate_with(
    planner: impl std::borrow::BorrowMut<MpcPlanner>,
    start: &[f64],
    target: &Pose,
    simulation: &SimulationOptions,
    progress: impl FnMut(usize),
) -> Result<MpcRun> {
    simulate_on_plant(planner, None, start, target, simulation, progress)
}

/// As [`simulate_with`], the hand measured on `plant_model` when given: the
/// planner predicts with its own model while the hand really is where
/// `plant_model`'s forward kinematics puts it at the joints' positions
/// (model mismatch: a rigid-beam planner on a bending gantry, a link-length
/// error, [`super::with_link_length_error`]). Every step starts its
/// prediction from that measured pose ([`MpcPlanner::step_with_measured_pose`],
/// the feedback correction of seed 000 sec 4.5); the errors recorded are
/// the plant's. `None`: the planner's model is the plant's ([`simulate_with`]).
///
/// Errors: those of [`simulate_with`], and a plant model with another
/// number of joints.
pub fn simulate_on_plant(
    mut planner: impl std::borrow::BorrowMut<MpcPlanner>,
    plant_model: Option<&Model>,
    start: &[f64],
    target: &Pose,
    simulation: &SimulationOptions,
    mut progress: impl FnMut(usize),
) -> Result<MpcRun> {
    simulation.validate()?;
    let planner = planner.borrow_mut();
    let model = planner.model().clone();
    model.check_joint_positions(start)?;
    if let Some(plant) = plant_model {
        if plant.dof() != model.dof() {
            return Err(Error::DimensionMismatch {
                what: "plant model (joints)",
                expected: model.dof(),
                got: plant.dof(),
            });
        }
    }
    // The hand's true kinematics.
    let kinematics: &Model = plant_model.unwrap_or(&model);
    planner.set_target(target)?;
    let t = planner.options().sample_time;
    let tracks_orientation = planner.options().task_weights.tracks_orientation();
    let vmax = planner.velocity_limits().to_vec();
    let (lower, upper) = {
        let (l, u) = planner.position_limits();
        (l.to_vec(), u.to_vec())
    };
    let mut data = crate::kinematics::Data::new(kinematics);
    let kinds: Vec<JointKind> = model.joints().iter().map(|j| j.kind).collect();
    let mut plant = Plant::new(simulation.plant, &kinds, start)?;
    let mut q = start.to_vec();
    let mut samples = Vec::new();
    let mut summary = RunSummary {
        converged: false,
        steps: 0,
        final_position_error: f64::NAN,
        final_orientation_error: f64::NAN,
        max_velocity_violation: 0.0,
        max_position_violation: position_violation(&q, &lower, &upper),
        non_solved_steps: 0,
        max_prediction_error: 0.0,
        total_iterations: 0,
    };
    let mut hold_left: Option<usize> = None;
    for step in 0..simulation.max_steps + simulation.hold_steps {
        let pose = *crate::kinematics::forward_kinematics(kinematics, &mut data, &q)?;
        let report = match plant_model {
            None => planner.step(&q)?,
            Some(_) => planner.step_with_measured_pose(&q, &pose)?,
        };
        let (roll, pitch, yaw) = pose.rpy();
        samples.push(Sample {
            time: step as f64 * t,
            q: q.clone(),
            velocity: report.velocity.clone(),
            position: [pose.translation.x, pose.translation.y, pose.translation.z],
            rpy: [roll, pitch, yaw],
            position_error: report.position_error,
            orientation_error: report.orientation_error,
            status: report.status,
            iterations: report.qp.iterations,
        });
        summary.total_iterations += u64::from(report.qp.iterations);
        summary.max_prediction_error = summary.max_prediction_error.max(report.prediction_error);
        if report.status != StepStatus::Solved {
            summary.non_solved_steps += 1;
        }
        for (j, &u) in report.velocity.iter().enumerate() {
            summary.max_velocity_violation = summary.max_velocity_violation.max(u.abs() - vmax[j]);
        }
        // The plant: the velocity held for one sample (q += T u when exact).
        plant.advance(&mut q, &report.velocity, t)?;
        summary.max_position_violation = summary
            .max_position_violation
            .max(position_violation(&q, &lower, &upper));
        progress(step);
        match hold_left {
            Some(0) => break,
            Some(n) => hold_left = Some(n - 1),
            None => {
                // Converged: at the target (the measured errors of this
                // step) and, after this step's input, at rest.
                let at_target = report.position_error <= simulation.position_tolerance
                    && (!tracks_orientation
                        || report.orientation_error <= simulation.orientation_tolerance);
                let at_rest = report
                    .velocity
                    .iter()
                    .all(|v| v.abs() <= simulation.velocity_tolerance);
                summary.steps = step + 1;
                if at_target && at_rest {
                    summary.converged = true;
                    if simulation.hold_steps == 0 {
                        break;
                    }
                    hold_left = Some(simulation.hold_steps - 1);
                } else if step + 1 >= simulation.max_steps {
                    break;
                }
            }
        }
    }
    // The final state, at rest.
    let pose = *crate::kinematics::forward_kinematics(kinematics, &mut data, &q)?;
    let (roll, pitch, yaw) = pose.rpy();
    let position_error = (pose.translation - target.translation).norm();
    let orientation_error =
        crate::math::Rotation3::from_matrix_unchecked(target.rotation * pose.rotation.transpose())
            .angle();
    samples.push(Sample {
        time: samples.len() as f64 * t,
        q: q.clone(),
        velocity: vec![0.0; q.len()],
        position: [pose.translation.x, pose.translation.y, pose.translation.z],
        rpy: [roll, pitch, yaw],
        position_error,
        orientation_error,
        status: StepStatus::Solved,
        iterations: 0,
    });
    summary.final_position_error = position_error;
    summary.final_orientation_error = orientation_error;
    summary.max_velocity_violation = summary.max_velocity_violation.max(0.0);
    Ok(MpcRun {
        sample_time: t,
        joint_names: model.joints().iter().map(|j| j.name.clone()).collect(),
        joint_kinds: kinds,
        target: *target,
        tracks_orientation,
        plant: simulation.plant,
        samples,
        summary,
    })
}

/// Largest distance of a joint position outside its limits (0 inside).
pub fn position_violation(q: &[f64], lower: &[f64], upper: &[f64]) -> f64 {
    q.iter()
        .zip(lower.iter().zip(upper))
        .map(|(&v, (&lo, &hi))| (lo - v).max(v - hi).max(0.0))
        .fold(0.0, f64::max)
}
