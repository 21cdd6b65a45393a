//! Whether one tool pose is reachable within the joint limits, with how
//! many IK solutions and the best manipulability among them; and the
//! joint-space sampler of the forward-sampling builder.

use rand::RngCore;

use super::bound::ReachBox;
use crate::error::Result;
use crate::ik::analytic::{
    AnalyticOptions, AnalyticSolver, ArmClass, RangeFilter, Representatives, Verification,
};
use crate::ik::{AutoSolver, IkOptions, IkSolver};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Pose, Vector3};
use crate::model::Model;

/// Joint-space distance (max over joints, rad or m) below which two
/// solutions count as one: the analytic branches meet at singular poses.
const SAME_SOLUTION: f64 = 1e-6;

/// Numeric IK restarts per pose of the map builders' oracle where the arm
/// takes the numeric route: seeded, no time budget, so a pose's answer does
/// not depend on the machine.
pub const NUMERIC_RESTARTS: usize = 20;

/// What one pose gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Decision {
    /// Distinct solutions within the limits (0: unreachable).
    pub solutions: usize,
    /// Best Yoshikawa manipulability over them (0 if none).
    pub manipulability: f64,
}

enum Route {
    /// A 6-joint arm of a closed-form class: every solution, counted.
    Analytic(Box<AnalyticSolver>),
    /// Any other arm: the automatic solver (analytic at the redundancy
    /// parameter and its sweep where the class allows, numeric with seeded
    /// restarts otherwise); one solution counted.
    Auto(Box<AutoSolver>),
    /// A position-only map: the numeric solver with the orientation masked
    /// (`task_weights = [1, 1, 1, 0, 0, 0]`), seeded restarts; one solution
    /// counted.
    Position(Box<IkSolver>),
}

/// The per-pose decision of the IK builder, set up once per chunk.
pub(crate) struct PoseOracle {
    model: Model,
    route: Route,
    data: Data,
    start: Vec<f64>,
    reach: ReachBox,
    options: IkOptions,
}

impl PoseOracle {
    /// The oracle of `target` poses (the layout's [`super::MapTarget`]).
    pub(crate) fn new(model: &Model, target: super::MapTarget) -> Result<PoseOracle> {
        let options = IkOptions {
            max_restarts: NUMERIC_RESTARTS,
            time_budget: None,
            ..IkOptions::default()
        };
        let reach = ReachBox::of_model(model)?;
        if target == super::MapTarget::Position {
            let options = IkOptions {
                task_weights: [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
                ..options
            };
            return Ok(PoseOracle {
                model: model.clone(),
                route: Route::Position(Box::new(IkSolver::new(model, options)?)),
                data: Data::new(model),
                start: model.neutral_configuration(),
                reach,
                options,
            });
        }
        let analytic = AnalyticSolver::new(
            model,
            AnalyticOptions {
                representatives: Representatives::Nearest,
                limits: RangeFilter::WithinLimits,
                verification: Verification::ForwardKinematics,
            },
        )
        .ok()
        .filter(|s| {
            matches!(
                s.class(),
                ArmClass::SphericalWrist { .. }
                    | ArmClass::ThreeParallel { .. }
                    | ArmClass::ThreeParallelOffset { .. }
            )
        });
        let route = match analytic {
            Some(solver) => Route::Analytic(Box::new(solver)),
            None => Route::Auto(Box::new(AutoSolver::new(model, options)?)),
        };
        Ok(PoseOracle {
            model: model.clone(),
            route,
            data: Data::new(model),
            start: model.neutral_configuration(),
            reach,
            options,
        })
    }

    /// True when `position` (world frame, m) is beyond the reach bound.
    pub(crate) fn beyond_reach(&self, position: &Vector3<f64>) -> bool {
        self.reach.excludes(position)
    }

    /// Decides `target` (world frame; its rotation unused by a
    /// position-only oracle), from the neutral configuration.
    pub(crate) fn decide(&mut self, target: &Pose) -> Result<Decision> {
        let mut decision = Decision {
            solutions: 0,
            manipulability: 0.0,
        };
        let single = match &mut self.route {
            Route::Analytic(solver) => {
                let (tp, to) = (
                    self.options.position_tolerance,
                    self.options.orientation_tolerance,
                );
                let found = solver.solve(target, &self.start)?;
                // Accepted as IkOptions' tolerances accept a numeric answer
                // (1e-6 m and rad, checked by forward kinematics).
                let mut accepted = found
                    .iter()
                    .filter(|s| s.position_error <= tp && s.orientation_error <= to);
                let mut kept: [Option<&[f64]>; 32] = [None; 32];
                let mut count = 0;
                for s in accepted.by_ref() {
                    let q = s.q();
                    let duplicate = kept[..count.min(32)]
                        .iter()
                        .flatten()
                        .any(|k| k.iter().zip(q).all(|(a, b)| (a - b).abs() <= SAME_SOLUTION));
                    if duplicate {
                        continue;
                    }
                    if count < 32 {
                        kept[count] = Some(q);
                    }
                    count += 1;
                    let j = jacobian(&self.model, &mut self.data, q, JacobianFrame::World)?;
                    decision.manipulability = decision
                        .manipulability
                        .max(crate::linalg::manipulability(j));
                }
                decision.solutions = count;
                None
            }
            Route::Auto(solver) => {
                let answer = solver.solve(target, &self.start)?;
                answer.report.converged().then_some(answer.report.q)
            }
            Route::Position(solver) => {
                let report = solver.solve(target, &self.start)?;
                report.converged().then_some(report.q)
            }
        };
        if let Some(q) = single {
            decision = self.one_solution(&q)?;
        }
        Ok(decision)
    }
}

impl PoseOracle {
    /// One solution `q` and its manipulability.
    fn one_solution(&mut self, q: &[f64]) -> Result<Decision> {
        let j = jacobian(&self.model, &mut self.data, q, JacobianFrame::World)?;
        Ok(Decision {
            solutions: 1,
            manipulability: crate::linalg::manipulability(j),
        })
    }
}

/// A configuration drawn uniformly within `model`'s limits into `q` (rad or
/// m): one `u64` of `rng` per joint (53 bits), so a sample's values depend
/// only on its stream. Rotational joints without finite limits in
/// `[-pi, pi]`, prismatic ones within 1 m of zero.
pub(crate) fn sample_configuration(model: &Model, rng: &mut impl RngCore, q: &mut [f64]) {
    use std::f64::consts::PI;
    for (value, joint) in q.iter_mut().zip(model.joints()) {
        let limits = &joint.limits;
        let (lo, hi) = if limits.is_bounded() {
            (limits.lower, limits.upper)
        } else {
            let half = if joint.kind.is_rotational() { PI } else { 1.0 };
            (
                (-half).clamp(limits.lower, limits.upper),
                half.clamp(limits.lower, limits.upper),
            )
        };
        let unit = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        *value = lo + (hi - lo) * unit;
    }
}
