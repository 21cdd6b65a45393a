//! Seed 002's continuous path as a study: a straight line planned by the
//! paper's method (IK at the knots, one polynomial per segment, Fig 6's
//! adaptive segmentation), the paper's variants beside it (the other
//! orientation law, the midpoint-only test, the cubic-quintic scheme, the
//! error against the number of segments) and, optionally, the joint torques
//! along the planned motion against the motors' limits.

use std::time::Instant;

use super::StudyReport;
use crate::error::{check_finite_vector, Error, Result};
use crate::kinematics::{forward_kinematics, Data};
use crate::math::{rotation_angle, Pose};
use crate::model::Model;
use crate::trajectory::{check_limits, TrajectoryLimits};
use crate::trajectory::{
    measure_path_error, plan_continuous_path, rate_amplification, BoundaryRates,
    ContinuousPathOptions, ContinuousPathReport, PathIk, PathTolerance, SegmentScheme,
    Segmentation, ViaVelocity,
};
use crate::trajectory::{path_ik_for, IkTask, NumericPathIk};
use crate::trajectory::{
    scale_to_torque_limits, torque_profile, TorqueCheckOptions, TorqueScaling,
};
use crate::trajectory::{CartesianTrajectory, LinePath, OrientationLaw, TimeLaw};

mod outcome;
mod scope;
mod seed002;

pub use outcome::{ContinuousPathOutcome, PlannedPath, SchemeRun, SweepRow, TorqueOutcome};
pub use scope::{violation_text, PathScope};

/// The start of the arm4 line (rad): joints 3-4 at 0.3 and 0.4 rad, the
/// tool at x = -0.15 m on the line y = -0.30 m (joints 1-2 by Newton).
pub const ARM4_LINE_START: [f64; 4] = [0.33824988933280115, -1.9358832167391893, 0.3, 0.4];
/// The end of the arm4 line (rad): the tool at x = +0.15 m, same y.
pub const ARM4_LINE_END: [f64; 4] = [1.2655451073344133, -1.935883216739189, 0.3, 0.4];

/// The timing law along the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum LawKind {
    /// Quintic from rest to rest.
    Quintic,
    /// Trapezoidal speed (acceleration time: `acceleration_time`).
    #[default]
    Trapezoidal,
    /// Constant speed.
    Linear,
}

/// How the orientation moves along the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum OrientationKind {
    /// Seed 002, eqs 20-22: the orientation angles linear in time.
    #[default]
    RpyLinear,
    /// Slerp between the end orientations, in step with the position.
    Slerp,
}

impl OrientationKind {
    /// The trajectory's law.
    pub fn law(self) -> OrientationLaw {
        match self {
            OrientationKind::RpyLinear => OrientationLaw::RpyLinearInTime,
            OrientationKind::Slerp => OrientationLaw::FollowPath,
        }
    }

    /// The other one (the labelled comparison).
    pub fn other(self) -> Self {
        match self {
            OrientationKind::RpyLinear => OrientationKind::Slerp,
            OrientationKind::Slerp => OrientationKind::RpyLinear,
        }
    }

    /// `paper's law (angles linear in time, eqs 20-22)` or `slerp`.
    pub fn as_str(self) -> &'static str {
        match self {
            OrientationKind::RpyLinear => "paper's law (angles linear in time, eqs 20-22)",
            OrientationKind::Slerp => "slerp",
        }
    }
}

/// What the tolerance and the IK cover.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum TaskKind {
    /// Position only for robots with fewer than 6 joints (arm4), else the pose.
    #[default]
    Auto,
    /// Position and orientation.
    Pose,
    /// Position only.
    Position,
}

/// Seed 002's polynomial schemes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum SchemeKind {
    /// Quartic first and last, cubic middles, via velocities by eq 23 (C1).
    #[default]
    QuarticCubic,
    /// As `QuarticCubic` with central-difference via velocities (not in the seed).
    QuarticCubicCentral,
    /// Cubic segments and a quintic last one (C2; unstable with many segments).
    CubicQuintic,
}

impl SchemeKind {
    /// The library's scheme.
    pub fn scheme(self) -> SegmentScheme {
        match self {
            SchemeKind::QuarticCubic => {
                SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference)
            }
            SchemeKind::QuarticCubicCentral => {
                SegmentScheme::QuarticCubicQuartic(ViaVelocity::CentralDifference)
            }
            SchemeKind::CubicQuintic => SegmentScheme::CubicQuinticLast,
        }
    }
}

/// Which IK solves the knots.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum IkKind {
    /// Closed form where the robot has one (arm4, PUMA-type), else numeric.
    #[default]
    Auto,
    /// Numeric (Levenberg-Marquardt from the previous knot).
    Numeric,
}

/// Joint rates at both ends of the planned motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "kebab-case"))]
pub enum BoundaryKind {
    /// At rest at both ends: right for a rest-to-rest timing law.
    #[default]
    Rest,
    /// From the knots by finite differences (seed 002, eqs 23-24): right
    /// when the path moves at its ends (a linear law, or eqs 20-22's
    /// constant orientation rates).
    FiniteDifference,
}

impl BoundaryKind {
    /// The planner's boundary rates.
    pub fn rates(self) -> BoundaryRates {
        match self {
            BoundaryKind::Rest => BoundaryRates::Rest,
            BoundaryKind::FiniteDifference => BoundaryRates::FiniteDifference,
        }
    }
}

/// Where the line ends.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(rename_all = "snake_case"))]
pub enum PathGoal {
    /// At the end-effector pose of these joint positions (rad or m).
    Configuration(Vec<f64>),
    /// At this pose: x, y, z (m), roll, pitch, yaw (rad), world frame.
    Pose([f64; 6]),
}

/// The torque check of the planned motion: its joint torques (inverse
/// dynamics) against the motors' limits, and the slow-down that meets them.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(default, deny_unknown_fields))]
pub struct TorqueStudy {
    /// Torque limits (N m or N, > 0), one per joint. Default: the model's
    /// effort limits.
    pub limits: Option<Vec<f64>>,
    /// Samples over the motion (>= 2). Default 401.
    pub samples: usize,
    /// The planned motion is played `speed_up` times faster (> 0) before
    /// the check, then slowed down uniformly until every torque is within
    /// its limit: with `speed_up > 1` the study asks how fast the path can
    /// run. Default 1 (the motion as planned).
    pub speed_up: f64,
}

impl Default for TorqueStudy {
    fn default() -> Self {
        TorqueStudy {
            limits: None,
            samples: TorqueCheckOptions::default().samples,
            speed_up: 1.0,
        }
    }
}

/// Seed 002's continuous path (sec 3) on a straight line, with the paper's
/// variants and an optional torque check.
///
/// The main run plans the line with the given options; beside it (each
/// labelled): the other orientation law (pose tasks), the same plan with the
/// paper's midpoint-only test (`checks_per_segment = 1`, Fig 6), the
/// cubic-quintic scheme on fixed segment counts, and the error against the
/// number of segments. [`ContinuousPathStudy::run`] runs it on the built-in
/// robot `robot`; [`ContinuousPathStudy::outcome`] on any model.
///
/// ```
/// use armkit::study::ContinuousPathStudy;
/// // Seed 002's 4-DOF arm on a 0.3 m line with a 0.1 mm tolerance.
/// let study = ContinuousPathStudy { segment_sweep: vec![4, 16], ..Default::default() };
/// let report = study.run().unwrap();
/// assert!(report.all_passed());
/// let sweep = report.series("error_vs_segments").unwrap();
/// assert_eq!(sweep.x, vec![4.0, 16.0]);
/// // Fig 6's midpoint-only test leaves an error well above the tolerance.
/// assert!(report.findings.iter().any(|f| f.claim.contains("midpoint")));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "io", serde(default, deny_unknown_fields))]
pub struct ContinuousPathStudy {
    /// Built-in robot of [`ContinuousPathStudy::run`]. Default `arm4`.
    pub robot: String,
    /// Start joint positions (the line starts at their end-effector pose).
    /// Default [`ARM4_LINE_START`].
    pub start: Vec<f64>,
    /// Where the line ends. Default: the pose of [`ARM4_LINE_END`].
    pub goal: PathGoal,
    /// Duration, s. Default 2.
    pub duration: f64,
    /// Timing law. Default trapezoidal.
    pub law: LawKind,
    /// Acceleration time of the trapezoidal law, s (the other laws ignore
    /// it). Default: 0.5 s (`None`: a quarter of the duration).
    pub acceleration_time: Option<f64>,
    /// Orientation law. Default the paper's (eqs 20-22).
    pub orientation: OrientationKind,
    /// Joint rates at the ends. Default rest.
    pub boundary: BoundaryKind,
    /// What the tolerance and the IK cover. Default auto.
    pub task: TaskKind,
    /// Position tolerance, m. Default 1e-4.
    pub tolerance: f64,
    /// Orientation tolerance, rad (pose tasks). Default 1e-3.
    pub orientation_tolerance: f64,
    /// Polynomial scheme. Default quartic-cubic (eq 23).
    pub scheme: SchemeKind,
    /// Check points per segment (1: the paper's midpoint). Default 3.
    pub checks_per_segment: usize,
    /// Fixed segment count instead of the adaptive segmentation.
    pub segments: Option<usize>,
    /// Largest segment count of the adaptive segmentation. Default 4096.
    pub max_segments: usize,
    /// Which IK. Default auto.
    pub ik: IkKind,
    /// Segment counts of the error-against-segments sweep (fixed
    /// segmentation, the main run's scheme). Default 2, 4, ..., 64; empty:
    /// no sweep.
    pub segment_sweep: Vec<usize>,
    /// Segment counts at which the cubic-quintic scheme is shown. Default
    /// 4, 8, 16; empty: not shown.
    pub cubic_quintic_segments: Vec<usize>,
    /// The torque check. Default none.
    pub torques: Option<TorqueStudy>,
    /// The paper's variants and claims, or armkit's promises only. Default
    /// auto: the paper on seed 002's 4-DOF arm, armkit's on other robots.
    pub scope: PathScope,
}

impl Default for ContinuousPathStudy {
    fn default() -> Self {
        ContinuousPathStudy {
            robot: "arm4".into(),
            start: ARM4_LINE_START.to_vec(),
            goal: PathGoal::Configuration(ARM4_LINE_END.to_vec()),
            duration: 2.0,
            law: LawKind::Trapezoidal,
            acceleration_time: Some(0.5),
            orientation: OrientationKind::RpyLinear,
            boundary: BoundaryKind::Rest,
            task: TaskKind::Auto,
            tolerance: 1e-4,
            orientation_tolerance: 1e-3,
            scheme: SchemeKind::QuarticCubic,
            checks_per_segment: 3,
            segments: None,
            max_segments: 4096,
            ik: IkKind::Auto,
            segment_sweep: vec![2, 4, 8, 16, 32, 64],
            cubic_quintic_segments: vec![4, 8, 16],
            torques: None,
            scope: PathScope::Auto,
        }
    }
}

/// Points per segment at which the path error is measured independently
/// of the check points.
pub const MEASURE_POINTS: usize = 100;

impl ContinuousPathStudy {
    /// The task on `model` (auto: position for fewer than 6 joints).
    pub fn resolved_task(&self, model: &Model) -> IkTask {
        match self.task {
            TaskKind::Pose => IkTask::Pose,
            TaskKind::Position => IkTask::Position,
            TaskKind::Auto if model.dof() < 6 => IkTask::Position,
            TaskKind::Auto => IkTask::Pose,
        }
    }

    /// The tolerance for `task`.
    pub fn path_tolerance(&self, task: IkTask) -> PathTolerance {
        match task {
            IkTask::Position => PathTolerance::Position(self.tolerance),
            IkTask::Pose => PathTolerance::Pose {
                position: self.tolerance,
                orientation: self.orientation_tolerance,
            },
        }
    }

    /// The line's end poses on `model` (world frame).
    pub fn end_poses(&self, model: &Model) -> Result<(Pose, Pose)> {
        model.check_joint_positions(&self.start)?;
        let mut data = Data::new(model);
        let start = *forward_kinematics(model, &mut data, &self.start)?;
        let goal = match &self.goal {
            PathGoal::Configuration(q) => {
                model.check_joint_positions(q)?;
                *forward_kinematics(model, &mut data, q)?
            }
            PathGoal::Pose(p) => {
                check_finite_vector("goal", p, 6)?;
                Pose::from_xyz_rpy([p[0], p[1], p[2]], [p[3], p[4], p[5]])
            }
        };
        Ok((start, goal))
    }

    /// The timed line on `model` with orientation law `orientation`.
    pub fn path(&self, model: &Model, orientation: OrientationKind) -> Result<CartesianTrajectory> {
        let law = match self.law {
            LawKind::Trapezoidal => TimeLaw::Trapezoidal {
                acceleration_time: self.acceleration_time.unwrap_or(0.25 * self.duration),
            },
            LawKind::Quintic => TimeLaw::Quintic,
            LawKind::Linear => TimeLaw::Linear,
        };
        let (start, goal) = self.end_poses(model)?;
        Ok(
            CartesianTrajectory::new(LinePath::new(start, goal)?, law.timing(self.duration)?)?
                .with_orientation_law(orientation.law()),
        )
    }

    /// The planner's options for `task` (the main run's).
    pub fn options(&self, task: IkTask) -> ContinuousPathOptions {
        ContinuousPathOptions {
            scheme: self.scheme.scheme(),
            segmentation: match self.segments {
                Some(n) => Segmentation::Fixed(n),
                None => Segmentation::Adaptive {
                    initial: 4.min(self.max_segments),
                    max: self.max_segments,
                },
            },
            tolerance: self.path_tolerance(task),
            checks_per_segment: self.checks_per_segment,
            boundary: self.boundary.rates(),
        }
    }

    /// The IK the study uses on `model`, and its description.
    pub fn path_ik(&self, model: &Model, task: IkTask) -> Result<(Box<dyn PathIk>, &'static str)> {
        match self.ik {
            IkKind::Auto => path_ik_for(model, task),
            IkKind::Numeric => Ok((
                Box::new(NumericPathIk::for_path(model, task)?),
                "numeric (Levenberg-Marquardt from the previous knot)",
            )),
        }
    }

    /// Plans the main run only (what `armkit traj line` does).
    pub fn plan(&self, model: &Model) -> Result<(PlannedPath, &'static str)> {
        let task = self.resolved_task(model);
        let (mut ik, method) = self.path_ik(model, task)?;
        let planned = self.plan_with(
            model,
            &mut *ik,
            self.orientation,
            &self.options(task),
            self.orientation.as_str(),
        )?;
        Ok((planned, method))
    }

    fn plan_with(
        &self,
        model: &Model,
        ik: &mut dyn PathIk,
        orientation: OrientationKind,
        options: &ContinuousPathOptions,
        label: &str,
    ) -> Result<PlannedPath> {
        let path = self.path(model, orientation)?;
        let clock = Instant::now();
        let report = plan_continuous_path(model, &path, ik, &self.start, options)?;
        let planning = clock.elapsed();
        let interior = measure_path_error(model, &report.trajectory, &path, MEASURE_POINTS)?;
        Ok(PlannedPath {
            label: label.to_string(),
            path,
            report,
            interior,
            planning,
        })
    }

    fn validate_lists(&self) -> Result<()> {
        for (what, list) in [
            ("segment_sweep", &self.segment_sweep),
            ("cubic_quintic_segments", &self.cubic_quintic_segments),
        ] {
            if list.contains(&0) {
                return Err(Error::invalid_argument(what, "segment counts must be >= 1"));
            }
        }
        Ok(())
    }

    /// Runs everything on `model`; the torque check (if asked for) on
    /// `dynamics` when given (a model of the same arm with mass properties
    /// and effort limits, e.g. a URDF of the robot planned with a DH model:
    /// its joints must be the planning model's, checked at every knot), else
    /// on `model`. Errors: bad options (named), a line out of reach, a
    /// torque check on a model without mass properties.
    pub fn outcome(
        &self,
        model: &Model,
        dynamics: Option<&Model>,
    ) -> Result<ContinuousPathOutcome> {
        self.validate_lists()?;
        let task = self.resolved_task(model);
        let tolerance = self.path_tolerance(task);
        let (mut ik, method) = self.path_ik(model, task)?;
        let options = self.options(task);
        let label = self.orientation.as_str();
        let main = self.plan_with(model, &mut *ik, self.orientation, &options, label)?;
        let scope = self.scope.resolve(model);
        let paper = scope == PathScope::Paper;
        let other_orientation = match task {
            IkTask::Pose if paper => {
                let other = self.orientation.other();
                let label = format!("{} (comparison)", other.as_str());
                Some(self.plan_with(model, &mut *ik, other, &options, &label)?)
            }
            _ => None,
        };
        let midpoint_only = if self.checks_per_segment == 1 || !paper {
            None
        } else {
            let midpoint = ContinuousPathOptions {
                checks_per_segment: 1,
                ..options.clone()
            };
            let label = "the paper's midpoint-only test (Fig 6)";
            Some(self.plan_with(model, &mut *ik, self.orientation, &midpoint, label)?)
        };
        let mut cubic_quintic = Vec::new();
        let (cubic_counts, sweep_counts): (&[usize], &[usize]) = match scope {
            PathScope::Armkit => (&[], &[]),
            _ => (&self.cubic_quintic_segments, &self.segment_sweep),
        };
        for &n in cubic_counts {
            let fixed = ContinuousPathOptions {
                scheme: SegmentScheme::CubicQuinticLast,
                segmentation: Segmentation::Fixed(n),
                ..options.clone()
            };
            let run = self.plan_with(model, &mut *ik, self.orientation, &fixed, "cubic-quintic")?;
            cubic_quintic.push(SchemeRun {
                segments: n,
                status: run.report.status,
                interior: run.interior,
                amplification: rate_amplification(&run.report.trajectory),
            });
        }
        let mut sweep = Vec::new();
        for &n in sweep_counts {
            let fixed = ContinuousPathOptions {
                segmentation: Segmentation::Fixed(n),
                checks_per_segment: 1,
                ..options.clone()
            };
            let run = self.plan_with(model, &mut *ik, self.orientation, &fixed, "sweep")?;
            sweep.push(SweepRow {
                segments: n,
                midpoint: run.report.checked_error,
                interior: run.interior,
            });
        }
        let limit_violations = check_limits(
            &main.report.trajectory,
            &TrajectoryLimits::from_model(model),
        )?;
        let torques = match &self.torques {
            Some(study) => Some(torque_outcome(model, dynamics, &main.report, study)?),
            None => None,
        };
        let mut seed002_findings = if paper {
            seed002::arm4_findings(model)?
        } else {
            Vec::new()
        };
        // The orientation law matters where the orientation is followed.
        if paper && matches!(task, IkTask::Pose) {
            seed002_findings.push(seed002::orientation_law_finding(&main));
        }
        Ok(ContinuousPathOutcome {
            robot: model.name().to_string(),
            scope,
            task,
            tolerance,
            ik_method: method,
            checks_per_segment: self.checks_per_segment,
            main,
            other_orientation,
            midpoint_only,
            cubic_quintic,
            sweep,
            limit_violations,
            torques,
            seed002_findings,
        })
    }

    /// The study on the built-in robot `robot`.
    pub fn run(&self) -> Result<StudyReport> {
        let model = crate::robots::by_name(&self.robot)?;
        Ok(self.outcome(&model, None)?.report())
    }
}

/// The torque check of the planned trajectory on `dynamics` (or `model`).
fn torque_outcome(
    model: &Model,
    dynamics: Option<&Model>,
    planned: &ContinuousPathReport,
    study: &TorqueStudy,
) -> Result<TorqueOutcome> {
    if !(study.speed_up.is_finite() && study.speed_up > 0.0) {
        return Err(Error::invalid_argument(
            "torques.speed_up",
            format!("must be finite and > 0, got {}", study.speed_up),
        ));
    }
    let (dynamics_model, model_mismatch) = match dynamics {
        Some(d) => (
            d,
            Some(end_effector_offset_drift(
                model,
                d,
                &planned.configurations,
            )?),
        ),
        None => (model, None),
    };
    let options = TorqueCheckOptions {
        samples: study.samples,
        limits: study.limits.clone(),
        ..Default::default()
    };
    let played = planned.trajectory.time_scaled(1.0 / study.speed_up)?;
    let scaling: TorqueScaling = scale_to_torque_limits(dynamics_model, &played, &options)?;
    // The scaling law tau_k = g + (tau - g) / k^2 at the same path points,
    // against the RNEA run on the scaled trajectory; samples on a knot are
    // left out (the C1 scheme's acceleration jumps there, and rounding can
    // put the two samples on either side of it).
    let k2 = scaling.factor * scaling.factor;
    let knots = played.knots();
    let on_knot = |t: f64| {
        let i = knots.partition_point(|&k| k < t);
        let near = |k: Option<&f64>| k.is_some_and(|k| (k - t).abs() <= 1e-9 * played.duration());
        near(knots.get(i)) || (i > 0 && near(knots.get(i - 1)))
    };
    let mut law_error: f64 = 0.0;
    for (((before, after), g), _) in scaling
        .before
        .torques
        .iter()
        .zip(&scaling.after.torques)
        .zip(&scaling.before.gravity)
        .zip(&scaling.before.times)
        .filter(|&(_, &t)| !on_knot(t))
    {
        for j in 0..before.len() {
            let predicted = g[j] + (before[j] - g[j]) / k2;
            law_error = law_error.max((predicted - after[j]).abs() / (1.0 + before[j].abs()));
        }
    }
    // Tightness: 0.1 % faster than the factor found exceeds a limit.
    let faster_status = if scaling.factor > 1.0 {
        let faster = played.time_scaled(scaling.factor * (1.0 - 1e-3))?;
        Some(torque_profile(dynamics_model, &faster, &options)?.status)
    } else {
        None
    };
    Ok(TorqueOutcome {
        dynamics_robot: dynamics_model.name().to_string(),
        speed_up: study.speed_up,
        planned_duration: planned.trajectory.duration(),
        scaling,
        law_error,
        faster_status,
        model_mismatch,
    })
}

/// The largest change, over the knots, of the end-effector offset between
/// two models of one arm (m, plus rad of rotation): zero when their joints
/// are the same and only the tool differs.
fn end_effector_offset_drift(
    model: &Model,
    dynamics: &Model,
    configurations: &[Vec<f64>],
) -> Result<f64> {
    if dynamics.dof() != model.dof() {
        return Err(Error::DimensionMismatch {
            what: "dynamics model joints",
            expected: model.dof(),
            got: dynamics.dof(),
        });
    }
    let (mut a, mut b) = (Data::new(model), Data::new(dynamics));
    let mut first: Option<Pose> = None;
    let mut worst: f64 = 0.0;
    for q in configurations {
        let planned = *forward_kinematics(model, &mut a, q)?;
        let other = *forward_kinematics(dynamics, &mut b, q)?;
        let offset = other.inverse() * planned;
        let reference = *first.get_or_insert(offset);
        let change = reference.inverse() * offset;
        worst = worst.max(change.translation.norm() + rotation_angle(&change.rotation));
    }
    Ok(worst)
}
