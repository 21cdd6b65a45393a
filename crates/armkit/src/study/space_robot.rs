//! Seed 004's space robot as a study: space6r on its satellite moving a
//! smooth joint motion, once with the base free-floating and once with its
//! attitude held, checked for what momentum conservation implies.

use super::{Check, Finding, FindingStatus, Series, StudyReport};
use crate::error::{check_finite_vector, check_positive, Result};
use crate::ik::pose_error;
use crate::math::{rotation_log, Pose, Vector6};
use crate::robots::space6r_free_floating;
use crate::space::{
    center_of_mass, generalized_jacobian, momentum, step, step_integrated, BaseMode,
    FreeFloatingModel, FreeFloatingState, SinusoidalJointMotion, SpaceData,
};
use crate::tracking::TrackingOptions;

/// Seed 004's free-floating space robot (space6r on a 400 kg satellite):
/// the same seeded smooth joint motion simulated with the base
/// [`BaseMode::FreeFloating`] and [`BaseMode::AttitudeHeld`].
///
/// Checks, for each mode: the system's centre of mass stays put (zero
/// linear momentum is holonomic); the linear momentum of the simulated
/// motion (central differences of base pose and joints) stays zero, and the
/// angular momentum too when free-floating (holding the attitude takes an
/// external torque, so it is not checked there; the attitude is); the
/// generalized Jacobian `J*` predicts the end-effector twist of the
/// simulation (a step of 1e-6 s, differenced) to 1e-4 relative; the base
/// moves. Those hold by construction (the simulator re-places the base from
/// the centre of mass): they are invariants. The results: the same motion
/// with the base integrated from the momentum equations' twist
/// ([`step_integrated`], never re-placed), its centre of mass and momenta
/// computed apart; the attitude-held run is seed 004's finding (eqs 10-16,
/// eq 15). Series: base translation and rotation (roll, pitch, yaw) against
/// time for both modes, and the joint positions (for an animation).
///
/// ```
/// use armkit::study::SpaceRobotStudy;
/// let study = SpaceRobotStudy { duration: 2.0, ..SpaceRobotStudy::default() };
/// let report = study.run().unwrap();
/// assert!(report.all_passed(), "{:?}", report.checks);
/// let drift = report.check("free-floating: centre-of-mass drift").unwrap();
/// assert!(drift.value < 1e-9); // m
/// let moved = report.check("free-floating: the base translates").unwrap();
/// assert!(moved.value > 1e-4); // m: the base moves, the centre of mass does not
/// let base = report.series("base_translation_free_floating").unwrap();
/// assert_eq!(base.x.len(), 201); // 2 s at 0.01 s: the figure's data
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(default, deny_unknown_fields))]
pub struct SpaceRobotStudy {
    /// Start joint positions, rad (6). Default `[0.3, 0.8, -0.6, 0.4, 0.9, -0.3]`.
    pub start: Vec<f64>,
    /// Simulated time, s (> 0). Default 20 s (seed 004's motion time).
    pub duration: f64,
    /// Simulation step, s (> 0). Default 0.01 s.
    pub dt: f64,
    /// Seed of the joint motion ([`SinusoidalJointMotion::random`]). Default 1.
    pub seed: u64,
    /// Amplitude of each joint's excursion, rad (> 0). Default 0.5.
    pub amplitude: f64,
    /// Highest angular frequency of the motion, rad/s (> 0). Default 0.5.
    pub max_frequency: f64,
}

impl Default for SpaceRobotStudy {
    fn default() -> Self {
        SpaceRobotStudy {
            start: SPACE6R_START.to_vec(),
            duration: 20.0,
            dt: 0.01,
            seed: 1,
            amplitude: 0.5,
            max_frequency: 0.5,
        }
    }
}

/// A well-conditioned start configuration of space6r, rad.
pub const SPACE6R_START: [f64; 6] = [0.3, 0.8, -0.6, 0.4, 0.9, -0.3];

/// Centre-of-mass drift allowed, m (round-off: the base is placed from it).
const COM_DRIFT: f64 = 1e-9;
/// Momentum of the simulated motion allowed, kg m/s and kg m^2/s
/// (central differences over 2 dt: O(dt^2) errors on momenta of order 1-10;
/// measured about 2e-5 at dt = 0.01 s).
const MOMENTUM: f64 = 1e-4;
/// Centre-of-mass drift allowed when the base is integrated from the
/// momentum equations (not re-placed), m: the fourth-order steps' error
/// over the run (measured about 1e-12 m at dt = 0.01 s), far below the
/// base's travel (cm).
const INTEGRATED_COM_DRIFT: f64 = 1e-8;
/// Relative error allowed between `J* q_dot` and the differenced twist.
const JACOBIAN_RELATIVE: f64 = 1e-4;
/// Step of the differenced twist, s.
const TWIST_STEP: f64 = 1e-6;

impl SpaceRobotStudy {
    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<()> {
        self.validate_for(6)
    }

    /// Checks every field for an arm of `dof` joints; the error names it.
    fn validate_for(&self, dof: usize) -> Result<()> {
        check_finite_vector("start", &self.start, dof)?;
        check_positive("duration", self.duration)?;
        check_positive("dt", self.dt)?;
        check_positive("amplitude", self.amplitude)?;
        check_positive("max_frequency", self.max_frequency)?;
        // The simulation records every step, as a tracking run does.
        TrackingOptions {
            dt: self.dt,
            ..TrackingOptions::default()
        }
        .periods(self.duration, 6)?;
        Ok(())
    }

    /// Simulates both modes of seed 004's space6r on its satellite and checks them.
    pub fn run(&self) -> Result<StudyReport> {
        self.run_on(&space6r_free_floating()?)
    }

    /// Simulates both modes of any free-floating system (an arm with mass
    /// properties on a [`crate::space::BaseBody`]) and checks them; `start`
    /// then has one value per joint of the arm, within its limits. The checks
    /// are the laws of a free-floating system, not figures of the paper.
    ///
    /// ```
    /// use armkit::robots::space6r_base_body;
    /// use armkit::space::FreeFloatingModel;
    /// use armkit::study::SpaceRobotStudy;
    /// let arm = armkit::robots::by_name("gantry9")?; // 9 joints with mass properties
    /// let start = arm.neutral_configuration();
    /// let system = FreeFloatingModel::new(space6r_base_body(), arm)?;
    /// let study = SpaceRobotStudy {
    ///     start,
    ///     duration: 1.0,
    ///     ..SpaceRobotStudy::default()
    /// };
    /// let report = study.run_on(&system)?;
    /// assert!(report.check("free-floating: centre-of-mass drift").unwrap().value < 1e-9);
    /// # Ok::<(), armkit::Error>(())
    /// ```
    pub fn run_on(&self, model: &FreeFloatingModel) -> Result<StudyReport> {
        self.validate_for(model.dof())?;
        model.arm().check_limits(&self.start)?;
        let mut report = StudyReport::default();
        for (mode, key, label) in [
            (BaseMode::FreeFloating, "free_floating", "free-floating"),
            (BaseMode::AttitudeHeld, "attitude_held", "attitude held"),
        ] {
            let run = self.simulate(model, mode, false)?;
            run.check(mode, label, &mut report);
            let integrated = self.simulate(model, mode, true)?;
            integrated.check_integrated(mode, label, &mut report);
            integrated.findings(mode, label, &mut report);
            run.series(key, label, &mut report);
        }
        report.notes.push(
            "With the attitude held the attitude controller applies a torque to the base: the \
             angular momentum of base and arm is not conserved (not checked); the attitude is."
                .into(),
        );
        Ok(report)
    }

    /// The joint motion simulated in `mode`: the base re-placed from the
    /// centre of mass every step ([`step`]), or, when `integrate`, moved by
    /// integrating the momentum equations' base twist ([`step_integrated`]).
    fn simulate(&self, model: &FreeFloatingModel, mode: BaseMode, integrate: bool) -> Result<Run> {
        let n = model.dof();
        let motion =
            SinusoidalJointMotion::random(n, self.seed, self.amplitude, self.max_frequency)?;
        let steps = ((self.duration / self.dt) - 1e-9).ceil().max(1.0) as usize;
        let dt = self.duration / steps as f64;
        let mut data = SpaceData::new(model);
        let mut state = FreeFloatingState::new(Pose::identity(), self.start.clone());
        let mut states = Vec::with_capacity(steps + 1);
        let mut applied = Vec::with_capacity(steps);
        states.push(state.clone());
        let mut rates = vec![0.0; n];
        for k in 0..steps {
            // Rates at the middle of the step (zero-order hold).
            motion.rates((k as f64 + 0.5) * dt, &mut rates);
            if integrate {
                step_integrated(model, &mut data, &mut state, &rates, dt, mode)?;
            } else {
                step(model, &mut data, &mut state, &rates, dt, mode)?;
            }
            states.push(state.clone());
            applied.push(rates.clone());
        }
        let com0 = center_of_mass(model, &mut data, &states[0].base, &states[0].q)?;
        let mut run = Run {
            dt,
            states,
            com_drift: 0.0,
            linear: 0.0,
            angular: 0.0,
            jacobian_error: 0.0,
        };
        for k in 0..=steps {
            let s = &run.states[k];
            let com = center_of_mass(model, &mut data, &s.base, &s.q)?;
            run.com_drift = run.com_drift.max((com - com0).norm());
            if k > 0 && k < steps {
                let (before, after) = (&run.states[k - 1], &run.states[k + 1]);
                let q_dot: Vec<f64> = (0..n)
                    .map(|j| (after.q[j] - before.q[j]) / (2.0 * dt))
                    .collect();
                let twist = differenced_twist(&before.base, &after.base, 2.0 * dt);
                let m = momentum(model, &mut data, &s.base, &s.q, &twist, &q_dot)?;
                run.linear = run.linear.max(m.linear.norm());
                run.angular = run.angular.max(m.angular.norm());
            }
            if let Some(rates) = applied.get(k).filter(|_| !integrate) {
                let error = jacobian_error(model, &mut data, s, rates, mode)?;
                run.jacobian_error = run.jacobian_error.max(error);
            }
        }
        Ok(run)
    }
}

/// One simulated mode.
struct Run {
    dt: f64,
    states: Vec<FreeFloatingState>,
    com_drift: f64,
    linear: f64,
    angular: f64,
    jacobian_error: f64,
}

impl Run {
    fn check(&self, mode: BaseMode, label: &str, report: &mut StudyReport) {
        let (travel, turn) = self.base_motion();
        report.checks.push(
            Check::at_most(
                format!("{label}: centre-of-mass drift"),
                self.com_drift,
                COM_DRIFT,
                "m",
            )
            .invariant(),
        );
        report.checks.push(
            Check::at_most(
                format!("{label}: linear momentum of the simulated motion"),
                self.linear,
                MOMENTUM,
                "kg m/s",
            )
            .invariant(),
        );
        if mode == BaseMode::FreeFloating {
            report.checks.push(
                Check::at_most(
                    format!("{label}: angular momentum of the simulated motion"),
                    self.angular,
                    MOMENTUM,
                    "kg m^2/s",
                )
                .invariant(),
            );
            report.checks.push(Check::at_least(
                format!("{label}: the base turns"),
                turn,
                1e-3,
                "rad",
            ));
        } else {
            report.checks.push(Check::at_most(
                format!("{label}: the base keeps its attitude"),
                turn,
                1e-12,
                "rad",
            ));
        }
        report.checks.push(
            Check::at_most(
                format!("{label}: J* against the differenced simulated motion (relative)"),
                self.jacobian_error,
                JACOBIAN_RELATIVE,
                "",
            )
            .invariant(),
        );
        report.checks.push(Check::at_least(
            format!("{label}: the base translates"),
            travel,
            1e-4,
            "m",
        ));
    }

    /// The base's travel (m) and turn (rad) from the first state to the last.
    fn base_motion(&self) -> (f64, f64) {
        let (first, last) = (
            &self.states[0].base,
            &self.states[self.states.len() - 1].base,
        );
        (
            (last.translation - first.translation).norm(),
            rotation_log(&(last.rotation * first.rotation.transpose())).norm(),
        )
    }

    /// The checks of the run whose base was integrated from the momentum
    /// equations: the centre of mass ([`center_of_mass`]) and the momenta
    /// of the differenced motion ([`momentum`], body by body), both computed
    /// apart from the base Jacobian that moved the base. Results, not
    /// invariants: nothing re-places the base.
    fn check_integrated(&self, mode: BaseMode, label: &str, report: &mut StudyReport) {
        let label = format!("{label}, base integrated from eqs 10-16");
        report.checks.push(Check::at_most(
            format!("{label}: centre-of-mass drift"),
            self.com_drift,
            INTEGRATED_COM_DRIFT,
            "m",
        ));
        report.checks.push(Check::at_most(
            format!("{label}: linear momentum of the integrated motion"),
            self.linear,
            MOMENTUM,
            "kg m/s",
        ));
        if mode == BaseMode::FreeFloating {
            report.checks.push(Check::at_most(
                format!("{label}: angular momentum of the integrated motion"),
                self.angular,
                MOMENTUM,
                "kg m^2/s",
            ));
        }
    }

    /// Seed 004 sec 1 (eqs 10-16, the base attitude held as in eq 15) on the
    /// run whose base was integrated from the momentum equations: the base
    /// translates while the system's centre of mass stays put and the linear
    /// momentum stays zero. The free-floating mode (angular momentum, its
    /// `J*`) is not the paper's: its checks only.
    fn findings(&self, mode: BaseMode, label: &str, report: &mut StudyReport) {
        if mode != BaseMode::AttitudeHeld {
            return;
        }
        let (travel, _) = self.base_motion();
        let holds =
            self.com_drift <= INTEGRATED_COM_DRIFT && self.linear <= MOMENTUM && travel > 1e-4;
        report.findings.push(Finding::new(
            format!(
                "seed 004, sec 1 (eqs 10-16, {label} as in eq 15): without external force the \
                 base translates so that the linear momentum stays zero and the system's centre \
                 of mass stays put"
            ),
            format!(
                "the base integrated from the momentum equations' twist (v0 = -J_g q_dot, \
                 fourth-order steps of {} s, never re-placed) travels {travel:.3e} m while the \
                 centre of mass (computed apart, link by link) drifts {:.2e} m and the linear \
                 momentum of the differenced motion (body by body) stays within {:.2e} kg m/s; \
                 our joint motion (the paper's is not printed)",
                self.dt, self.com_drift, self.linear
            ),
            FindingStatus::from_holds(holds),
        ));
    }

    fn series(&self, key: &str, label: &str, report: &mut StudyReport) {
        let time: Vec<f64> = (0..self.states.len()).map(|k| k as f64 * self.dt).collect();
        let column = |f: &dyn Fn(&FreeFloatingState) -> f64| -> Vec<f64> {
            self.states.iter().map(f).collect()
        };
        let rpy = |s: &FreeFloatingState| s.base.rpy();
        report.series.push(
            Series::new(
                format!("base_translation_{key}"),
                format!("Base translation, {label}"),
                "t (s)",
                "m",
                time.clone(),
            )
            .with("x", column(&|s| s.base.translation.x))
            .with("y", column(&|s| s.base.translation.y))
            .with("z", column(&|s| s.base.translation.z)),
        );
        report.series.push(
            Series::new(
                format!("base_rotation_{key}"),
                format!("Base rotation, {label}"),
                "t (s)",
                "rad",
                time.clone(),
            )
            .with("roll", column(&|s| rpy(s).0))
            .with("pitch", column(&|s| rpy(s).1))
            .with("yaw", column(&|s| rpy(s).2)),
        );
        let mut joints = Series::new(
            format!("joints_{key}"),
            format!("Joint positions, {label}"),
            "t (s)",
            "rad",
            time,
        );
        for j in 0..self.states[0].q.len() {
            joints = joints.with(format!("q{}", j + 1), column(&|s| s.q[j]));
        }
        report.series.push(joints);
    }
}

/// `[v; w]` of a pose moving from `before` to `after` in `interval` s.
fn differenced_twist(before: &Pose, after: &Pose, interval: f64) -> Vector6<f64> {
    let v = (after.translation - before.translation) / interval;
    let w = rotation_log(&(after.rotation * before.rotation.transpose())) / interval;
    Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z)
}

/// `|J* q_dot - (x(h) - x(0)) / h| / |J* q_dot|` at `state` for `rates`,
/// the motion simulated by [`step`] over `h` = 1e-6 s.
fn jacobian_error(
    model: &FreeFloatingModel,
    data: &mut SpaceData,
    state: &FreeFloatingState,
    rates: &[f64],
    mode: BaseMode,
) -> Result<f64> {
    let j = generalized_jacobian(model, data, &state.base, &state.q, mode)?.clone();
    let before = *data.end_effector_pose();
    let mut moved = state.clone();
    step(model, data, &mut moved, rates, TWIST_STEP, mode)?;
    generalized_jacobian(model, data, &moved.base, &moved.q, mode)?;
    let differenced = pose_error(data.end_effector_pose(), &before) / TWIST_STEP;
    let mut predicted = Vector6::zeros();
    for (column, rate) in j.column_iter().zip(rates) {
        predicted += column * *rate;
    }
    let scale = predicted.norm().max(1e-12);
    Ok((predicted - differenced).norm() / scale)
}
