//! Seed 001's four-way distribution as a study: one straight-line motion of
//! a redundant robot distributed by minimum norm, energy-optimal weights,
//! seed 000's priorities and with joints locked as the paper's baseline
//! (so that six remain), compared by seed 001's energy measure under the
//! static torques of the load and under the full inverse dynamics of the
//! motion; the paper's claims as [`Finding`]s.

use super::StudyReport;
use crate::dynamics::check_dynamics_model;
use crate::error::{brief, check_finite_vector, Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::math::{Pose, Rotation3, Vector3};
use crate::model::Model;
use crate::redundancy::{
    compare_distributions, ComparisonCase, ComparisonResult, Damping, Distribution,
    DistributionOptions, Formulation, JointWeights, Load, SecondaryObjective, TorqueFloor,
};
use crate::seeds::{SEED000_PRIORITY_WEIGHTS, SEED001_GANTRY_MOVE, SEED001_GANTRY_START};
use crate::tracking::{TrackingOptions, TrackingStatus};
use crate::trajectory::{CartesianTrajectory, TimeLaw};

mod instant;
mod measures;
mod sweep;

use instant::instant_comparison;
pub use instant::{InstantComparison, InstantRival};
use measures::{torque_energies, zero_weight_lock};
pub use measures::{TorqueEnergies, ZeroWeightLock};
pub use sweep::{DurationPoint, DurationSweep, DURATION_FACTORS, MODERATE_SPEED_MARGIN};

/// The null-space objective of a [`DistributionStudy`], by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum SecondaryKind {
    /// None.
    #[default]
    None,
    /// Joint-limit avoidance (Liegeois).
    JointLimits,
    /// Manipulability ascent.
    Manipulability,
}

/// The solver of a [`DistributionStudy`], by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum FormulationKind {
    /// The weighted least norm.
    #[default]
    LeastNorm,
    /// Seed 001's partitioned form, best-conditioned partition every step.
    Partitioned,
}

/// Seed 001's comparison (with seed 000's priorities) on a redundant robot:
/// a straight line (quintic timing) from `start`, moved by `displacement`
/// and turned by `rotation`, distributed four ways
/// ([`ComparisonCase::four_way`]), each run measured by eq 9 for the
/// payload. Unset fields take the robot's defaults
/// ([`DistributionStudy::resolve`]): on gantry9 the seed's start, motion,
/// priorities and the paper's baseline, three joints (the gantry's axes)
/// locked so that six remain, with the rail and beam alone locked as a
/// labelled extra (`locked-variant`).
///
/// ```
/// use armkit::study::{DistributionStudy, FindingStatus};
/// // Seed 001: the energy-optimal distribution has the lowest F on gantry9.
/// let report = DistributionStudy::default().run().unwrap();
/// assert!(report.all_passed());
/// // Which run spends the least F is the paper's claim: a finding. Under the
/// // load's (static) torques the energy-optimal run wins.
/// assert!(report.findings.iter().any(|f| f.claim.starts_with("seed 001, secs 1, 2 and 4")
///     && f.status == FindingStatus::Reproduced));
/// // Locking is the paper's zero weight A_Q in eq 19.
/// assert!(report.findings.iter().any(|f| f.claim.contains("A_Q = 0")
///     && f.status == FindingStatus::Reproduced));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(default, deny_unknown_fields))]
pub struct DistributionStudy {
    /// Start joint positions (rad or m). Default: the robot's
    /// ([`SEED001_GANTRY_START`] on gantry9, mid-range otherwise).
    pub start: Option<Vec<f64>>,
    /// End-effector displacement, world frame, m. Default
    /// [`SEED001_GANTRY_MOVE`] on gantry9, `[0.1, 0.1, -0.1]` otherwise.
    pub displacement: Option<[f64; 3]>,
    /// End-effector rotation over the motion (world-frame rotation vector, rad).
    pub rotation: [f64; 3],
    /// Duration, s. Default 4.
    pub duration: f64,
    /// Durations of the sweep (s): the energy-optimal run and the paper's
    /// baseline repeated at each, F under static and dynamic torques, the
    /// crossover and the moderate speed ([`DurationSweep`]). Default:
    /// `duration` times [`DURATION_FACTORS`] (2 to 16 s on gantry9);
    /// `Some(vec![])` for none. Needs mass properties (dynamic torques).
    pub durations: Option<Vec<f64>>,
    /// Payload weight at the end effector, N (finite). Default 50.
    pub payload: f64,
    /// Count the links' own weight when the robot has mass properties. Default true.
    pub link_weights: bool,
    /// Priority weights (large = low priority). Default: seed 000's for 9
    /// joints, 10 for prismatic and 1 for rotational joints otherwise.
    pub priorities: Option<Vec<f64>>,
    /// Joints to lock, 0-based. Default: the paper's baseline (seed 001,
    /// sec 1: joints locked "so that six remain"), the first `n - 6` joints:
    /// 0, 1, 2 (the gantry's rail, beam and vertical axes) on gantry9.
    pub locked: Option<Vec<usize>>,
    /// A labelled extra run (`locked-variant`, not the paper's baseline)
    /// with these joints locked, 0-based. Default: 0 and 1 (rail and beam,
    /// seven joints remain) on gantry9, none otherwise; `Some(vec![])` for none.
    pub variant_locked: Option<Vec<usize>>,
    /// Zero-torque floor of the energy weights, fraction of the largest torque. Default 0.05.
    pub torque_floor: f64,
    /// Control period, s. Default 0.01.
    pub dt: f64,
    /// Position feedback gain, 1/s. Default 10.
    pub gain: f64,
    /// Constant damping of the weighted least norm. Default none.
    pub damping: Option<f64>,
    /// Null-space objective. Default none.
    pub secondary: SecondaryKind,
    /// Its gain. Default 1.
    pub secondary_gain: f64,
    /// Solver. Default the weighted least norm.
    pub formulation: FormulationKind,
}

impl Default for DistributionStudy {
    fn default() -> Self {
        DistributionStudy {
            start: None,
            displacement: None,
            rotation: [0.0; 3],
            duration: 4.0,
            durations: None,
            payload: 50.0,
            link_weights: true,
            priorities: None,
            locked: None,
            variant_locked: None,
            torque_floor: 0.05,
            dt: 0.01,
            gain: 10.0,
            damping: None,
            secondary: SecondaryKind::None,
            secondary_gain: 1.0,
            formulation: FormulationKind::LeastNorm,
        }
    }
}

/// A [`DistributionStudy`] with every default filled in for one robot.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedDistribution {
    /// Start joint positions.
    pub start: Vec<f64>,
    /// Displacement, m.
    pub displacement: [f64; 3],
    /// Priority weights.
    pub priorities: JointWeights,
    /// Locked joints, 0-based (the paper's baseline by default).
    pub locked: Vec<usize>,
    /// The labelled extra's locked joints, 0-based (empty: no extra run).
    pub variant_locked: Vec<usize>,
    /// Whether the links' weight counts.
    pub gravity: bool,
    /// The load of eq 9.
    pub load: Load,
    /// The tracker options.
    pub options: DistributionOptions,
}

/// What [`DistributionStudy::compare`] ran.
#[derive(Clone, Debug)]
pub struct DistributionOutcome {
    /// The resolved settings.
    pub settings: ResolvedDistribution,
    /// The runs, in the order minimum-norm, energy-optimal, priorities,
    /// locked (the paper's baseline), then `locked-variant` (the labelled
    /// extra) when there is one.
    pub results: Vec<ComparisonResult>,
    /// F under static and dynamic torques, one per run in the same order;
    /// empty when the model has no mass properties (no dynamics).
    pub torque_energies: Vec<TorqueEnergies>,
    /// Seed 001's zero-weight lock along the locked run, when exactly
    /// `n - 6` joints are locked and that run completed.
    pub zero_weight_lock: Option<ZeroWeightLock>,
    /// Seed 001's instantaneous claims (eqs 17 and 19) at the energy-optimal
    /// run's configurations, when that run completed.
    pub instant: Option<InstantComparison>,
    /// The duration sweep, with dynamics and at least one duration.
    pub sweep: Option<DurationSweep>,
}

/// Name of the labelled extra run.
pub const VARIANT_NAME: &str = "locked-variant";

impl DistributionStudy {
    /// The settings for `model` (more than 6 joints): given values checked,
    /// unset ones from the robot (seed 001's gantry9 defaults when `model` is
    /// gantry9). Errors name the field.
    pub fn resolve(&self, model: &Model) -> Result<ResolvedDistribution> {
        let dof = model.dof();
        if dof <= 6 {
            return Err(Error::invalid_argument(
                "model",
                format!(
                    "{}: {dof} joints; redundancy needs more than 6",
                    model.name()
                ),
            ));
        }
        let gantry = dof == 9 && model.name().starts_with("gantry9");
        let start = match &self.start {
            Some(q) => {
                model.check_limits(q)?;
                q.clone()
            }
            None if gantry => SEED001_GANTRY_START.to_vec(),
            None => model.neutral_configuration(),
        };
        let displacement = match self.displacement {
            Some(d) => {
                check_finite_vector("displacement", &d, 3)?;
                d
            }
            None if gantry => SEED001_GANTRY_MOVE,
            None => [0.1, 0.1, -0.1],
        };
        let priorities = match &self.priorities {
            Some(w) => {
                check_finite_vector("priorities", w, dof)?;
                JointWeights::new(w)?
            }
            None if dof == 9 => JointWeights::new(&SEED000_PRIORITY_WEIGHTS)?,
            None => JointWeights::new(
                &model
                    .joints()
                    .iter()
                    .map(|j| if j.kind.is_rotational() { 1.0 } else { 10.0 })
                    .collect::<Vec<_>>(),
            )?,
        };
        // Seed 001, sec 1: the usual practice locks joints "so that six
        // remain" (使剩下关节数目仍保持6个).
        let locked = match &self.locked {
            Some(joints) => joints.clone(),
            None => (0..dof - 6).collect(),
        };
        let variant_locked = match &self.variant_locked {
            Some(joints) => joints.clone(),
            None if gantry => vec![0, 1],
            None => Vec::new(),
        };
        let gravity = self.link_weights && model.has_inertias();
        if !self.payload.is_finite() {
            return Err(Error::invalid_argument(
                "payload",
                format!("must be a finite weight in N, got {}", brief(self.payload)),
            ));
        }
        let mut load = Load::payload(self.payload);
        if gravity {
            load = load.with_seed001_gravity();
        }
        let options = DistributionOptions {
            tracking: TrackingOptions::proportional(self.dt, self.gain),
            damping: self.damping.map_or(Damping::None, Damping::Constant),
            secondary: match self.secondary {
                SecondaryKind::None => SecondaryObjective::None,
                SecondaryKind::JointLimits => SecondaryObjective::JointLimits {
                    gain: self.secondary_gain,
                },
                SecondaryKind::Manipulability => SecondaryObjective::Manipulability {
                    gain: self.secondary_gain,
                    step: 1e-6,
                },
            },
            formulation: match self.formulation {
                FormulationKind::LeastNorm => Formulation::WeightedLeastNorm,
                FormulationKind::Partitioned => Formulation::Partitioned(None),
            },
        };
        Ok(ResolvedDistribution {
            start,
            displacement,
            priorities,
            locked,
            variant_locked,
            gravity,
            load,
            options,
        })
    }

    /// Runs the four distributions on `model`, the instantaneous
    /// comparison along the energy-optimal run and the duration sweep.
    pub fn compare(&self, model: &Model) -> Result<DistributionOutcome> {
        let settings = self.resolve(model)?;
        check_finite_vector("rotation", &self.rotation, 3)?;
        let durations = match &self.durations {
            Some(list) => {
                check_finite_vector("durations", list, list.len())?;
                if let Some(bad) = list.iter().find(|&&d| d <= 0.0) {
                    return Err(Error::invalid_argument(
                        "durations",
                        format!("every duration must be > 0 s, got {bad}"),
                    ));
                }
                let mut sorted = list.clone();
                sorted.sort_by(f64::total_cmp);
                sorted.dedup();
                sorted
            }
            None => DURATION_FACTORS.iter().map(|f| f * self.duration).collect(),
        };
        let mut cases = ComparisonCase::four_way(
            model.dof(),
            settings.load,
            TorqueFloor::Relative(self.torque_floor),
            settings.priorities.clone(),
            &settings.locked,
        )?;
        let sweep_cases: Vec<ComparisonCase> = cases
            .iter()
            .filter(|c| c.name == "energy-optimal" || c.name == "locked")
            .cloned()
            .collect();
        if !settings.variant_locked.is_empty() {
            cases.push(ComparisonCase {
                name: VARIANT_NAME.into(),
                distribution: Distribution::Weights(
                    JointWeights::uniform(model.dof()).with_locked(&settings.variant_locked)?,
                ),
            });
        }
        let results = self.run_cases(model, &settings, self.duration, &cases)?;
        let dynamics = check_dynamics_model(model).is_ok();
        let torque_energies = if dynamics {
            results
                .iter()
                .map(|r| torque_energies(model, r, &settings.load))
                .collect::<Result<Vec<_>>>()?
        } else {
            Vec::new()
        };
        let completed = |name: &str| {
            results
                .iter()
                .find(|r| r.name == name && r.report.status == TrackingStatus::Completed)
        };
        let zero_weight_lock = match completed("locked") {
            Some(run) if settings.locked.len() + 6 == model.dof() => {
                Some(zero_weight_lock(model, run, &settings.locked)?)
            }
            _ => None,
        };
        let instant = match completed("energy-optimal") {
            Some(run) => Some(instant_comparison(
                model,
                run,
                &settings.load,
                &settings.priorities,
                &settings.locked,
            )?),
            None => None,
        };
        let sweep = if dynamics && !durations.is_empty() && sweep_cases.len() == 2 {
            Some(self.sweep(model, &settings, &durations, &sweep_cases)?)
        } else {
            None
        };
        Ok(DistributionOutcome {
            settings,
            results,
            torque_energies,
            zero_weight_lock,
            instant,
            sweep,
        })
    }

    /// The straight line of `duration` s (quintic timing) from the start,
    /// each case tracking it.
    fn run_cases(
        &self,
        model: &Model,
        settings: &ResolvedDistribution,
        duration: f64,
        cases: &[ComparisonCase],
    ) -> Result<Vec<ComparisonResult>> {
        let mut data = Data::new(model);
        let start = *forward_kinematics(model, &mut data, &settings.start)?;
        let turn = Rotation3::from_scaled_axis(Vector3::from(self.rotation));
        let goal = Pose::new(
            turn.into_inner() * start.rotation,
            start.translation + Vector3::from(settings.displacement),
        );
        let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, duration)?;
        compare_distributions(
            model,
            &settings.start,
            &path,
            &settings.load,
            cases,
            &settings.options,
        )
    }

    /// The energy-optimal run and the baseline (`cases`, in that order) at
    /// each of `durations`, F under both torque models.
    fn sweep(
        &self,
        model: &Model,
        settings: &ResolvedDistribution,
        durations: &[f64],
        cases: &[ComparisonCase],
    ) -> Result<DurationSweep> {
        let points = durations
            .iter()
            .map(|&duration| {
                let runs = self.run_cases(model, settings, duration, cases)?;
                let optimal = torque_energies(model, &runs[0], &settings.load)?;
                let baseline = torque_energies(model, &runs[1], &settings.load)?;
                Ok(DurationPoint {
                    duration,
                    optimal_static: optimal.static_energy,
                    baseline_static: baseline.static_energy,
                    optimal_dynamic: optimal.dynamic_energy,
                    baseline_dynamic: baseline.dynamic_energy,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(DurationSweep { points })
    }

    /// The study on gantry9.
    pub fn run(&self) -> Result<StudyReport> {
        let model = crate::robots::by_name("gantry9")?;
        let outcome = self.compare(&model)?;
        Ok(StudyReport {
            checks: outcome.checks()?,
            findings: outcome.findings(),
            series: outcome.sweep.iter().map(DurationSweep::series).collect(),
            notes: vec![DISTRIBUTION_NOTE.into()],
        })
    }
}

/// What the study's numbers rest on.
pub const DISTRIBUTION_NOTE: &str = "A zero torque would make a joint free of cost: the energy \
     weights are floored at 5 % of the largest torque (a_i = max(|tau_i|, 0.05 max|tau|)^2). \
     Seed 001's eq 17 minimises F at each instant, not over the whole motion, with the torques \
     holding the load (the paper: 'at a speed that is not too high'); F under dynamic torques \
     adds the motion's inertia to the same runs. The baseline is the paper's usual practice: \
     joints locked so that six remain (n - 6 of them). A locked joint has an infinite weight in \
     the weighted least norm over all joints; in the paper's partitioned form it is A_Q = 0 in \
     eq 19, which gives the extra joints phi_p_dot = 0: the same lock (a finding measures it). Whole runs visit different configurations, so \
     eq 17's claim at each instant is tested apart: every distribution solved at the \
     energy-optimal run's configurations and twists. The duration sweep repeats the \
     energy-optimal run and the baseline at several durations: the inertia share is how much \
     the motion's inertia changes F, and 'moderate speed' is read as the durations from \
     which on it stays within 5 %.";

impl DistributionOutcome {
    /// The run named `name` (`minimum-norm`, `energy-optimal`, `priorities`,
    /// `locked`, `locked-variant`).
    pub fn result(&self, name: &str) -> Option<&ComparisonResult> {
        self.results.iter().find(|r| r.name == name)
    }

    /// Name of the distribution with the lowest energy measure F.
    pub fn lowest(&self) -> String {
        self.results
            .iter()
            .min_by(|a, b| a.summary.energy.total_cmp(&b.summary.energy))
            .map(|r| r.name.clone())
            .unwrap_or_default()
    }

    /// True when every run completed the path.
    pub fn all_completed(&self) -> bool {
        self.results
            .iter()
            .all(|r| r.report.status == TrackingStatus::Completed)
    }
}
