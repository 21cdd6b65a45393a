//! Analytic inverse kinematics by subproblem decomposition and by
//! algebraic elimination: every solution of a 6-joint arm (in closed form
//! where its class has one), and of a 7-DOF arm at a given redundancy
//! parameter.
//!
//! The arm's joint axes are read as lines in the zero configuration
//! ([`structure`]); which consecutive axes intersect or are parallel decides
//! the class ([`ArmClass`]); each class is solved by a short sequence of the
//! geometric [`subproblems`] (Paden-Kahan 1-3 and a fourth, as in Elias and
//! Wen's IK-Geo; derived here, not ported):
//!
//! * spherical wrist (three axes meeting, at either end) with the other
//!   three having a parallel or an intersecting pair, or a prismatic third
//!   joint (PUMA, Stanford, KUKA/ABB-type arms with a shoulder offset, the
//!   Panda or iiwa with one joint fixed): up to 8 solutions;
//! * axes 2-3-4 parallel with 5-6 intersecting (Universal Robots): up to 8;
//! * axes 2-3-4 (or 3-4-5) parallel, the other three general (a UR-type
//!   arm with an offset wrist): up to 8, by [`subproblem6`] (a quartic);
//! * 7-DOF spherical shoulder, elbow, spherical wrist (iiwa, LWR4) at an
//!   elbow angle ([`Parameter::ElbowAngle`]); any other 7-DOF arm with one
//!   joint held ([`Parameter::FixedJoint`]) if what is left has a class;
//! * a spherical wrist behind three general axes: subproblem 5 in closed
//!   form (a quartic), up to 8;
//! * every other 6R arm of rotation joints (one intersecting or parallel
//!   pair of consecutive axes anywhere, or none: a general 6R arm) by
//!   algebraic elimination (`elimination`: Raghavan and Roth's equations,
//!   the 16 roots of a trigonometric polynomial of degree 8; tens of
//!   microseconds, up to 16 solutions);
//! * elimination cuts the loop where no special pair stops it: from the
//!   tip, from the base, or between joints 1 and 6 (special pairs at both
//!   ends, axes 1-2-3 parallel outside the UR family); an arm it cannot
//!   take at all (e.g. a parallel pair on one line) has no analytic
//!   solver, and the numeric solvers take it.
//!
//! Each solution is checked by forward kinematics (the product of
//! exponentials of the model's joint lines, compared with the model's own
//! at set-up, or the model's where they differ: see
//! [`Verification::ForwardKinematics`]) and marked
//! [`Fit::Exact`] (within [`EXACT_TOLERANCE`] = 1e-10 m and rad) or
//! [`Fit::Approximate`] (the least-squares answer of the subproblems, e.g. a
//! pose out of reach, with its errors). Joint angles are then wrapped into
//! the limits: a joint whose range spans more than 2 pi gives every
//! representative inside it ([`Representatives::Every`]); solutions with a
//! joint outside its limits are dropped ([`RangeFilter::WithinLimits`]);
//! the rest are sorted by joint-space distance to the caller's
//! configuration. After [`AnalyticSolver::new`], a solve allocates nothing
//! (unless the representatives outgrow the buffer sized at set-up for every
//! joint's range, which only happens for [`Parameter::FixedJoint`] changes).
//! A double root may be missed by elimination (>= 99.9 % of random poses
//! recover the generating configuration); a solution of elimination is
//! exact only if forward kinematics confirms it to 1e-10.
//!
//! ```
//! use armkit::ik::analytic::{AnalyticOptions, AnalyticSolver};
//! use armkit::ik::closed_form::Fit;
//! use armkit::kinematics::{forward_kinematics, Data};
//! let model = armkit::robots::by_name("ur5").unwrap();
//! let mut data = Data::new(&model);
//! let q = [0.3, -1.2, 1.4, -0.5, 1.2, 0.4];
//! let target = *forward_kinematics(&model, &mut data, &q).unwrap();
//! let mut solver = AnalyticSolver::new(&model, AnalyticOptions::default()).unwrap();
//! assert_eq!(solver.class().as_str(), "three_parallel_2_3_4_intersecting_5_6");
//! let solutions = solver.solve(&target, &q).unwrap();
//! assert!(solutions.len() >= 8);
//! assert!(solutions.iter().all(|s| s.fit == Fit::Exact));
//! // Nearest first: the configuration the target came from.
//! assert!(solutions[0].q().iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
//! ```

mod chain;
mod class;
mod elimination;
mod finish;
mod geometry;
mod options;
mod parallel;
mod parallel_offset;
mod polish;
mod ranges;
#[cfg(test)]
mod root_isolation_tests;
mod route;
mod srs;
#[cfg(test)]
mod test_random;
mod three_axes;
mod wrist;

pub use class::{ArmClass, ChainEnd, PairKind, Positioning};
pub use finish::{AnalyticSolution, Representatives, Verification};
pub use geometry::{structure, subproblem6, subproblems};
pub use options::{AnalyticOptions, Parameter};
pub use route::{route_class, solver_for, sweep_values, AnalyticRoute, JointNumbering, Redundancy};

use self::chain::{Candidates, Chain};
use self::class::{detect, Detected};
use self::elimination::{Cut, Elimination};
use self::finish::Finisher;
use self::parallel::ThreeParallel;
use self::parallel_offset::ThreeParallelOffset;
use self::srs::SrsChain;
use self::structure::ArmStructure;
use self::wrist::SphericalWrist;
pub use super::closed_form::{Fit, RangeFilter, EXACT_TOLERANCE};
use super::numeric::check_target;
use crate::error::{check_finite_vector, Error, Result};
use crate::math::Pose;
use crate::model::Model;

/// What the solver does per solve, fixed at set-up. Variants differ in
/// size (the prepared geometry); a plan is built once per solver and read
/// in place on every solve, so it is kept inline rather than boxed.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
enum Plan {
    Wrist {
        solver: SphericalWrist,
        end: ChainEnd,
    },
    ThreeParallel {
        solver: ThreeParallel,
        end: ChainEnd,
    },
    ThreeParallelOffset {
        solver: ThreeParallelOffset,
        end: ChainEnd,
    },
    ShoulderElbowWrist(SrsChain),
    Elimination {
        solver: Elimination,
        end: ChainEnd,
    },
}

/// An analytic IK solver for one model (see the module docs).
#[derive(Clone, Debug)]
pub struct AnalyticSolver {
    model: Model,
    structure: ArmStructure,
    class: ArmClass,
    plan: Plan,
    parameter: Option<Parameter>,
    options: AnalyticOptions,
    candidates: Candidates,
    finisher: Finisher,
}

impl AnalyticSolver {
    /// A solver for a 6-joint model of a known class. Errors: another number
    /// of joints (7-DOF arms need [`AnalyticSolver::with_parameter`]), a
    /// coupling, or a class without analytic solution (the message names the class).
    pub fn new(model: &Model, options: AnalyticOptions) -> Result<AnalyticSolver> {
        if model.dof() == 7 {
            return Err(Error::invalid_argument(
                "model",
                format!(
                    "`{}` has 7 joints: give the redundancy parameter (an elbow angle or a fixed joint)",
                    model.name()
                ),
            ));
        }
        Self::build(model, options, None)
    }

    /// A solver for a 7-DOF model at a redundancy parameter.
    pub fn with_parameter(
        model: &Model,
        options: AnalyticOptions,
        parameter: Parameter,
    ) -> Result<AnalyticSolver> {
        if model.dof() != 7 {
            return Err(Error::invalid_argument(
                "parameter",
                format!(
                    "a redundancy parameter is for 7-joint arms; `{}` has {}",
                    model.name(),
                    model.dof()
                ),
            ));
        }
        Self::build(model, options, Some(parameter))
    }

    fn build(
        model: &Model,
        options: AnalyticOptions,
        parameter: Option<Parameter>,
    ) -> Result<AnalyticSolver> {
        let structure = ArmStructure::of_model(model)?;
        if let Some(Parameter::FixedJoint { .. }) = parameter {
            // The value is checked here: an end joint's plan is built at 0.
            plan(model, &structure, parameter)?;
        }
        let reference = reference(&structure, parameter);
        let (class, plan) = plan(model, &structure, reference)?;
        Ok(AnalyticSolver {
            model: model.clone(),
            finisher: Finisher::new(model, options),
            structure,
            class,
            plan,
            parameter,
            options,
            candidates: Candidates::new(),
        })
    }

    /// The options.
    pub fn options(&self) -> &AnalyticOptions {
        &self.options
    }

    /// The model solved for.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The detected class.
    pub fn class(&self) -> ArmClass {
        self.class
    }

    /// How this solver solves its class: the class's
    /// [`description`](ArmClass::description), or the elimination's for an
    /// arm solved by elimination.
    pub fn method(&self) -> &'static str {
        match self.plan {
            Plan::Elimination { .. } => elimination::METHOD,
            _ => self.class.description(),
        }
    }

    /// The model's lines at zero configuration.
    pub fn structure(&self) -> &ArmStructure {
        &self.structure
    }

    /// The redundancy parameter (7-DOF arms).
    pub fn parameter(&self) -> Option<Parameter> {
        self.parameter
    }

    /// Changes the redundancy parameter's value (the elbow angle in rad, or
    /// the fixed joint's value). An elbow angle, or the first or last joint
    /// held, changes nothing else (the target is moved instead); another
    /// fixed joint rebuilds the plan (allocates) and fails if the rest loses
    /// its class.
    pub fn set_parameter_value(&mut self, value: f64) -> Result<()> {
        if !value.is_finite() {
            return Err(Error::invalid_argument(
                "parameter",
                format!("must be finite, got {value}"),
            ));
        }
        let parameter = match self.parameter {
            Some(Parameter::ElbowAngle(_)) => Parameter::ElbowAngle(value),
            Some(Parameter::FixedJoint { joint, .. }) => {
                let parameter = Parameter::FixedJoint { joint, value };
                if !held_at_end(&self.structure, joint) {
                    let (class, plan) = plan(&self.model, &self.structure, Some(parameter))?;
                    self.class = class;
                    self.plan = plan;
                }
                parameter
            }
            None => {
                return Err(Error::invalid_argument(
                    "parameter",
                    "this solver has no redundancy parameter (not a 7-joint arm)",
                ))
            }
        };
        self.parameter = Some(parameter);
        Ok(())
    }

    /// The elbow angle (rad) of configuration `q` of a
    /// spherical-shoulder-elbow-wrist arm (the value to give
    /// [`Parameter::ElbowAngle`] to find `q` among the solutions).
    pub fn elbow_angle(&self, q: &[f64]) -> Result<f64> {
        check_finite_vector("q", q, self.model.dof())?;
        match &self.plan {
            Plan::ShoulderElbowWrist(srs) => {
                let (elbow, wrist) = srs.elbow_and_wrist(q);
                Ok(srs.elbow_angle(&elbow, &wrist))
            }
            _ => Err(Error::invalid_argument(
                "model",
                "the elbow angle is defined for spherical-shoulder-elbow-wrist arms only",
            )),
        }
    }

    /// Every solution for `target` (world frame), per the options, nearest
    /// `current` (rad or m, one per joint) first. Errors: a non-finite target
    /// or a rotation that is not proper, `current` of the wrong size or not
    /// finite. An unreachable pose is not an error: its solutions are
    /// least-squares ([`Fit::Approximate`]).
    pub fn solve(&mut self, target: &Pose, current: &[f64]) -> Result<&[AnalyticSolution]> {
        check_target(target)?;
        check_finite_vector("current", current, self.model.dof())?;
        self.candidates.clear();
        let goal = &self.held_target(target);
        let out = &mut self.candidates;
        // The end the plan's chain is solved from (None: the 7-DOF elbow
        // plan, whose candidates are in model order with every joint).
        let end = match &self.plan {
            Plan::Wrist { solver, end } => {
                solver.solve(&goal_of(goal, *end), out);
                Some(*end)
            }
            Plan::ThreeParallel { solver, end } => {
                solver.solve(&goal_of(goal, *end), out);
                Some(*end)
            }
            Plan::ThreeParallelOffset { solver, end } => {
                solver.solve(&goal_of(goal, *end), out);
                Some(*end)
            }
            Plan::ShoulderElbowWrist(srs) => {
                let psi = match self.parameter {
                    Some(Parameter::ElbowAngle(psi)) => psi,
                    _ => 0.0,
                };
                srs.solve(goal, psi, out);
                None
            }
            Plan::Elimination { solver, end } => {
                solver.solve(&goal_of(goal, *end), out);
                Some(*end)
            }
        };
        let reverse = end == Some(ChainEnd::Base);
        let fixed = match (end, self.parameter) {
            (Some(_), Some(Parameter::FixedJoint { joint, value })) => Some((joint, value)),
            _ => None,
        };
        self.finisher.finish(
            &self.model,
            self.candidates.as_slice(),
            reverse,
            fixed,
            target,
            current,
        )
    }

    /// The pose the plan solves for: `target` itself, or for the first or
    /// last joint held at `v` (plan built at 0), `target` moved so that the
    /// other joints' solution is unchanged: `M(v)^-1 T` for the first,
    /// `T home^-1 M(v)^-1 home` for the last (`M` the joint's rigid motion at
    /// zero configuration).
    fn held_target(&self, target: &Pose) -> Pose {
        match self.parameter {
            Some(Parameter::FixedJoint { joint, value }) if held_at_end(&self.structure, joint) => {
                let motion = self.structure.motion(joint, value).inverse();
                if joint == 0 {
                    motion * *target
                } else {
                    let home = &self.structure.home;
                    *target * (home.inverse() * motion * *home)
                }
            }
            _ => *target,
        }
    }

    /// Solutions at each of `values` of the redundancy parameter (rad or m),
    /// together, nearest `current` first (a sweep of the elbow angle or of
    /// the fixed joint). Allocates the result.
    pub fn sweep(
        &mut self,
        target: &Pose,
        current: &[f64],
        values: &[f64],
    ) -> Result<Vec<AnalyticSolution>> {
        let mut all = Vec::new();
        for &value in values {
            self.set_parameter_value(value)?;
            all.extend_from_slice(self.solve(target, current)?);
        }
        finish::sort_nearest(&mut all, current);
        Ok(all)
    }
}

/// The joint (0-based) of a 7-joint `model` to hold so that the other six
/// form a class at any value of it (checked at 0, 0.7 and -1.9), with that
/// class: the last such joint of a closed-form class, else the last of a
/// one-pair class (solved by elimination); `None` if none (or not 7
/// joints).
pub fn joint_to_hold(model: &Model) -> Option<(usize, ArmClass)> {
    if model.dof() != 7 {
        return None;
    }
    let structure = ArmStructure::of_model(model).ok()?;
    let class_at = |joint: usize| -> Option<ArmClass> {
        let mut class = None;
        for value in [0.0, 0.7, -1.9] {
            let c = match detect(&structure.with_fixed_joint(joint, value)) {
                Detected::Unsolvable(_) => return None,
                detected => detected.class(),
            };
            if class.is_some_and(|k| k != c) {
                return None;
            }
            class = Some(c);
        }
        class
    };
    // Closed forms first, then a one-pair class (elimination, tens of
    // microseconds).
    let cost = |c: &ArmClass| match c {
        ArmClass::OnePair { .. } => 1,
        _ => 0,
    };
    let classes: Vec<(usize, ArmClass)> = (0..7)
        .rev()
        .filter_map(|j| class_at(j).map(|c| (j, c)))
        .collect();
    (0..2).find_map(|rank| classes.iter().find(|(_, c)| cost(c) == rank).copied())
}

/// The class of `model` and the lines it was read from (for `--explain`).
pub fn explain(model: &Model, parameter: Option<Parameter>) -> Result<(ArmClass, ArmStructure)> {
    let structure = ArmStructure::of_model(model)?;
    let class = match plan(model, &structure, parameter) {
        Ok((class, _)) => class,
        Err(_) => detect(&reduced(&structure, parameter)).class(),
    };
    Ok((class, structure))
}

/// True when `joint` is the first or last of `structure`: holding it moves
/// the target only, not the other joints' lines.
fn held_at_end(structure: &ArmStructure, joint: usize) -> bool {
    joint == 0 || joint + 1 == structure.dof()
}

/// The parameter the plan is built for: an end joint held at 0 (its value
/// moves the target, see [`AnalyticSolver::held_target`]), else `parameter`.
fn reference(structure: &ArmStructure, parameter: Option<Parameter>) -> Option<Parameter> {
    match parameter {
        Some(Parameter::FixedJoint { joint, .. }) if held_at_end(structure, joint) => {
            Some(Parameter::FixedJoint { joint, value: 0.0 })
        }
        other => other,
    }
}

fn reduced(structure: &ArmStructure, parameter: Option<Parameter>) -> ArmStructure {
    match parameter {
        Some(Parameter::FixedJoint { joint, value }) if joint < structure.dof() => {
            structure.with_fixed_joint(joint, value)
        }
        _ => structure.clone(),
    }
}

fn plan(
    model: &Model,
    structure: &ArmStructure,
    parameter: Option<Parameter>,
) -> Result<(ArmClass, Plan)> {
    if let Some(Parameter::FixedJoint { joint, value }) = parameter {
        if joint >= structure.dof() || !value.is_finite() {
            return Err(Error::invalid_argument(
                "parameter",
                format!(
                    "fixed joint {} = {value}: needs a joint index below {} and a finite value",
                    joint + 1,
                    structure.dof()
                ),
            ));
        }
    }
    if let Some(Parameter::ElbowAngle(psi)) = parameter {
        if !psi.is_finite() {
            return Err(Error::invalid_argument(
                "parameter",
                format!("elbow angle must be finite, got {psi}"),
            ));
        }
    }
    let arm = reduced(structure, parameter);
    let detected = detect(&arm);
    let class = detected.class();
    let unsolvable = |why: &str| {
        Error::invalid_argument(
            "model",
            format!(
                "`{}` has no analytic solver: class {class} ({}){why}",
                model.name(),
                class.description()
            ),
        )
    };
    if eliminable(&detected, parameter) {
        if let Some(plan) = elimination_plan(&arm) {
            return Ok((class, plan));
        }
    }
    match (detected, parameter) {
        (Detected::ShoulderElbowWrist { .. }, Some(Parameter::FixedJoint { .. })) => {
            Err(unsolvable(""))
        }
        (
            Detected::ShoulderElbowWrist {
                shoulder,
                elbow,
                wrist,
            },
            _,
        ) => Ok((
            class,
            Plan::ShoulderElbowWrist(SrsChain::new(&arm, shoulder, elbow, wrist)),
        )),
        (_, Some(Parameter::ElbowAngle(_))) => Err(unsolvable(
            "; an elbow angle needs a spherical-shoulder-elbow-wrist 7-DOF arm",
        )),
        (
            Detected::SphericalWrist {
                end,
                positioning,
                wrist,
                shoulder,
            },
            _,
        ) => {
            let chain = chain_of(&arm, end).ok_or_else(|| unsolvable(""))?;
            Ok((
                class,
                Plan::Wrist {
                    solver: SphericalWrist::new(&chain, positioning, &wrist, &shoulder),
                    end,
                },
            ))
        }
        (Detected::ThreeParallel { end, meet }, _) => {
            let chain = chain_of(&arm, end).ok_or_else(|| unsolvable(""))?;
            let solver = ThreeParallel::new(&chain, &meet);
            Ok((class, Plan::ThreeParallel { solver, end }))
        }
        (Detected::ThreeParallelOffset { end }, _) => {
            let chain = chain_of(&arm, end).ok_or_else(|| unsolvable(""))?;
            let solver = ThreeParallelOffset::new(&chain);
            Ok((class, Plan::ThreeParallelOffset { solver, end }))
        }
        // Elimination was tried (and does not apply to this arm).
        (
            Detected::Pair(_)
            | Detected::Unsolvable(ArmClass::General | ArmClass::OtherPairs | ArmClass::OnePair { .. }),
            _,
        ) => Err(unsolvable(
            "; elimination does not apply to it (its determinant vanishes identically at every cut of the loop); use a numeric solver (CLI: --solver lm)",
        )),
        (Detected::Unsolvable(_), _) => Err(unsolvable("")),
    }
}

/// Whether elimination is tried for `detected`: the 6R classes without a
/// closed form that have a special pair or none (a spherical wrist behind
/// general axes makes `det Sigma` vanish identically); not with an elbow
/// angle.
fn eliminable(detected: &Detected, parameter: Option<Parameter>) -> bool {
    let class_fits = matches!(
        detected,
        Detected::Pair(_)
            | Detected::Unsolvable(
                ArmClass::General | ArmClass::OtherPairs | ArmClass::OnePair { .. }
            )
    );
    class_fits && !matches!(parameter, Some(Parameter::ElbowAngle(_)))
}

/// The elimination of `arm`'s chain from the tip, else from the base (a
/// special pair at joints 1-2 needs the reversed chain), else with the loop
/// cut between joints 1 and 6 (special pairs at both ends), if any applies.
fn elimination_plan(arm: &ArmStructure) -> Option<Plan> {
    let cuts = [
        (ChainEnd::Tip, Cut::Tip),
        (ChainEnd::Base, Cut::Tip),
        (ChainEnd::Tip, Cut::Split),
    ];
    cuts.into_iter().find_map(|(end, cut)| {
        let solver = Elimination::new(&chain_of(arm, end)?, cut)?;
        Some(Plan::Elimination { solver, end })
    })
}

/// The target as the chain is solved: the pose itself, or its inverse for
/// a chain solved from the base.
fn goal_of(target: &Pose, end: ChainEnd) -> Pose {
    match end {
        ChainEnd::Tip => *target,
        ChainEnd::Base => target.inverse(),
    }
}

fn chain_of(arm: &ArmStructure, end: ChainEnd) -> Option<Chain> {
    match end {
        ChainEnd::Tip => Chain::of(arm),
        ChainEnd::Base => Chain::of(&arm.reversed()),
    }
}
