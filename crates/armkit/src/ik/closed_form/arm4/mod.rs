//! Seed 002's 4-DOF arm: two parallel vertical axes (theta1, theta2), a roll
//! about link 2 (theta3), a pitch (theta4), a tool along x4.
//!
//! The structure (standard DH, row j = link j): `alpha1 = 0` (axes 1 and 2
//! parallel), `alpha2 = +-90 deg` (axis 3 horizontal, along link 2),
//! `a3 = 0` and `alpha3 = +-90 deg` (axes 3 and 4 meet at the wrist point,
//! the origin of DH frame 3). Any `d1, a1 > 0, d2, a2, d3` (the link-2
//! length), `d4, a4, alpha4` (the tool), base and tool transforms and joint
//! offsets are allowed; `robots::arm4` is the seed's arm.
//!
//! With `T = base A1 A2 A3 A4 tool` and `G = Tz(d4) Tx(a4) Rx(alpha4) tool`,
//! the chain target `Tc = base^-1 T G^-1 = A1 A2 A3 Rz(theta4)` has its
//! origin at the wrist point `W`, whatever theta4 (seed 002 solves for the
//! wrist pose, eqs 8-18):
//! * `W` lies at the constant height `d1 + d2`, and horizontally
//!   `W = Rz(theta1) [(a1, 0) + Rz(theta2) (a2, -sin(alpha2) d3)]` (eqs 8-9):
//!   theta2 by the law of cosines (eqs 10-11, two branches), theta1 by atan2;
//!   theta12 = theta1 + theta2 is what the orientation sees (eqs 13-16).
//! * `Rx(-alpha2) Rz(-theta12) Rc = Rz(theta3) Rx(alpha3) Rz(theta4)`:
//!   theta3 from its third column, theta4 from its third row (eqs 17-18).
//!
//! The reachable set is 4-dimensional: a pose is reachable only if its
//! wrist point is at height `d1 + d2` and its axis 4 is perpendicular to link 2.
//! For any other pose, [`Arm4Solver::solve`] returns the configurations that
//! put the tool origin exactly on the target position and turn the tool as
//! close as the arm allows to the target orientation (each local minimum
//! over the one-parameter family of such configurations, found by a scan
//! of theta4 and golden-section refinement), flagged [`Fit::Approximate`]
//! with the residual orientation error. Position first because the seed's
//! continuous-path planning (sec 3) checks its segments against a position
//! tolerance: an exact tool position at every knot lets the adaptive
//! segmentation converge. A target position the tool cannot reach gives no
//! solution (an empty list).
//!
//! [`Fit::Approximate`]: super::Fit::Approximate

mod paper;

use super::{
    angle_is, check_arguments, dh_angle, finish, joint_value, quarter_turn_sign, representation,
    rot_x_quarter, solve_cos_sin, standard_dh_table, ClosedFormSolution, Fit, RangeFilter,
};
use crate::error::{Error, Result};
use crate::ik::pose_error::orientation_error;
use crate::kinematics::{forward_kinematics, Data};
use crate::math::roots::golden_section;
use crate::math::Pose;
use crate::model::{DhLink, Model};

/// Samples of theta4 in the scan for approximate solutions.
const SCAN_SAMPLES: usize = 361;
/// Golden-section iterations refining each local minimum (shrinks the
/// bracket by 0.618^60 ~ 3e-13).
const GOLDEN_ITERATIONS: usize = 60;

/// Every solution of seed 002's 4-DOF arm for a target pose, nearest
/// `current` first (the one to use is the first).
///
/// `model`: an arm of the seed-002 structure (`robots::arm4`);
/// `target`: end-effector pose, world frame; `current`: the current joint
/// positions (rad), for the nearest ordering and each angle's 2 pi multiple.
/// Exact solutions (every branch within the joint limits) when the pose is
/// reachable; otherwise [`Fit::Approximate`] ones with the tool position
/// exact and the orientation best fitted (see the module documentation);
/// an empty list when the tool cannot reach the target position. Builds an
/// [`Arm4Solver`] each call; keep one to solve many poses.
pub fn arm4_solutions(
    model: &Model,
    target: &Pose,
    current: &[f64],
) -> Result<Vec<ClosedFormSolution>> {
    Arm4Solver::new(model)?.solve(target, current)
}

/// Closed-form IK of seed 002's 4-DOF arm (see the module documentation).
#[derive(Clone, Debug)]
pub struct Arm4Solver {
    model: Model,
    links: Vec<DhLink>,
    base_inverse: Pose,
    /// `G = Tz(d4) Tx(a4) Rx(alpha4) tool` and its inverse.
    tool_chain: Pose,
    tool_chain_inverse: Pose,
    /// sin(alpha2), sin(alpha3) (each +-1).
    sign2: f64,
    sign3: f64,
}

/// One branch of the approximate family: which root of each two-root equation.
#[derive(Clone, Copy, Debug)]
struct Branch {
    theta3_root: usize,
    theta12_root: usize,
}

impl Arm4Solver {
    /// Reads `model`'s DH table; the error names what does not fit.
    pub fn new(model: &Model) -> Result<Arm4Solver> {
        let links = standard_dh_table(model, 4)?;
        let not_fit = |why: String| Error::invalid_argument("model", why);
        if !angle_is(links[0].alpha, 0.0) {
            return Err(not_fit(
                "alpha1 is not 0 (axes 1 and 2 not parallel)".into(),
            ));
        }
        let sign2 = quarter_turn_sign(links[1].alpha)
            .ok_or_else(|| not_fit("alpha2 is not +-90 deg".into()))?;
        let sign3 = quarter_turn_sign(links[2].alpha)
            .ok_or_else(|| not_fit("alpha3 is not +-90 deg".into()))?;
        if links[2].a.abs() > 1e-12 {
            return Err(not_fit(format!(
                "a3 = {} is not 0 (axes 3 and 4 do not meet)",
                links[2].a
            )));
        }
        if links[0].a.abs() < 1e-9 || links[1].a.hypot(links[2].d) < 1e-9 {
            return Err(not_fit("a1 or link 2 has zero length".into()));
        }
        let l4 = &links[3];
        let tool_chain =
            Pose::trans_z(l4.d) * Pose::trans_x(l4.a) * Pose::rot_x(l4.alpha) * *model.tool();
        Ok(Arm4Solver {
            model: model.clone(),
            base_inverse: model.base().inverse(),
            tool_chain_inverse: tool_chain.inverse(),
            tool_chain,
            links,
            sign2,
            sign3,
        })
    }

    /// Solutions within the joint limits, nearest `current` first: exact
    /// ones if the pose is reachable, else approximate ones (see
    /// [`arm4_solutions`]).
    pub fn solve(&self, target: &Pose, current: &[f64]) -> Result<Vec<ClosedFormSolution>> {
        self.solve_with(target, current, RangeFilter::WithinLimits)
    }

    /// As [`Arm4Solver::solve`], with a choice of range filter.
    pub fn solve_with(
        &self,
        target: &Pose,
        current: &[f64],
        filter: RangeFilter,
    ) -> Result<Vec<ClosedFormSolution>> {
        check_arguments(&self.model, target, current)?;
        let exact: Vec<ClosedFormSolution> = finish(
            &self.model,
            &self.exact_candidates(target),
            target,
            current,
            filter,
        )?
        .into_iter()
        .filter(|s| s.fit == Fit::Exact)
        .collect();
        if !exact.is_empty() {
            return Ok(exact);
        }
        finish(
            &self.model,
            &self.approximate_candidates(target, current, filter)?,
            target,
            current,
            filter,
        )
    }

    /// Seed 002's branches (eqs 8-18) for the wrist point of the target:
    /// exact when the pose is reachable (checked afterwards by FK).
    fn exact_candidates(&self, target: &Pose) -> Vec<Vec<f64>> {
        let l = &self.links;
        let chain = self.base_inverse * *target * self.tool_chain_inverse;
        let w = chain.translation;
        let (a1, v2x, v2y) = (l[0].a, l[1].a, -self.sign2 * l[2].d);
        let k = (w.x * w.x + w.y * w.y - a1 * a1 - v2x * v2x - v2y * v2y) / (2.0 * a1);
        let mut candidates = Vec::with_capacity(2);
        for theta2 in solve_cos_sin(v2x, -v2y, k) {
            let (s2, c2) = theta2.sin_cos();
            let ux = a1 + c2 * v2x - s2 * v2y;
            let uy = s2 * v2x + c2 * v2y;
            let theta1 = w.y.atan2(w.x) - uy.atan2(ux);
            let m = rot_x_quarter(-self.sign2)
                * Pose::rot_z(-(theta1 + theta2)).rotation
                * chain.rotation;
            let s = self.sign3;
            let theta4 = (s * m[(2, 0)]).atan2(s * m[(2, 1)]);
            let theta3 = (s * m[(0, 2)]).atan2(-s * m[(1, 2)]);
            candidates.push(self.joint_values([theta1, theta2, theta3, theta4]));
        }
        candidates
    }

    /// The local minima of the orientation error over the configurations
    /// that put the tool origin exactly on the target position.
    fn approximate_candidates(
        &self,
        target: &Pose,
        current: &[f64],
        filter: RangeFilter,
    ) -> Result<Vec<Vec<f64>>> {
        let mut data = Data::new(&self.model);
        let (low, high) = self.theta4_range();
        let step = (high - low) / (SCAN_SAMPLES - 1) as f64;
        let mut candidates = Vec::new();
        let mut costs = vec![f64::INFINITY; SCAN_SAMPLES];
        for theta3_root in 0..2 {
            for theta12_root in 0..2 {
                let branch = Branch {
                    theta3_root,
                    theta12_root,
                };
                let mut cost = |theta4: f64| -> Result<f64> {
                    self.branch_cost(&mut data, target, current, filter, branch, theta4)
                };
                for (i, c) in costs.iter_mut().enumerate() {
                    *c = cost(low + step * i as f64)?;
                }
                for i in 0..SCAN_SAMPLES {
                    let here = costs[i];
                    let left = if i > 0 { costs[i - 1] } else { f64::INFINITY };
                    let right = costs.get(i + 1).copied().unwrap_or(f64::INFINITY);
                    if !here.is_finite() || here > left || here > right || (here == left && i > 0) {
                        continue;
                    }
                    let a = (low + step * (i as f64 - 1.0)).max(low);
                    let b = (low + step * (i as f64 + 1.0)).min(high);
                    let mut best = (low + step * i as f64, here);
                    let refined = golden_section(&mut cost, a, b, GOLDEN_ITERATIONS)?;
                    let refined_cost = cost(refined)?;
                    if refined_cost < best.1 {
                        best = (refined, refined_cost);
                    }
                    if let Some(thetas) = self.branch_angles(target, branch, best.0) {
                        candidates.push(self.joint_values(thetas));
                    }
                }
            }
        }
        Ok(candidates)
    }

    /// Orientation error (rad) of one branch at `theta4`, or infinity where
    /// the branch does not exist or leaves the joint limits.
    fn branch_cost(
        &self,
        data: &mut Data,
        target: &Pose,
        current: &[f64],
        filter: RangeFilter,
        branch: Branch,
        theta4: f64,
    ) -> Result<f64> {
        let Some(thetas) = self.branch_angles(target, branch, theta4) else {
            return Ok(f64::INFINITY);
        };
        let mut q = self.joint_values(thetas);
        for (j, value) in q.iter_mut().enumerate() {
            match representation(&self.model, j, *value, current[j], filter) {
                Some(v) => *value = v,
                None => return Ok(f64::INFINITY),
            }
        }
        let pose = forward_kinematics(&self.model, data, &q)?;
        Ok(orientation_error(&target.rotation, &pose.rotation).norm())
    }

    /// DH angles of one branch of the configurations whose tool origin is
    /// at the target position, for a given theta4 (`None` where the branch
    /// does not exist).
    ///
    /// With `k = Rx(alpha3) Rz(theta4) g` (`g` the tool origin in frame 4
    /// before the tool chain) the tool origin in frame 0 is
    /// `Rz(theta1) (a1, 0, d1) + Rz(theta12) [(a2, -s_a2 d3, d2) + Rx(alpha2) Rz(theta3) k]`:
    /// its height fixes theta3 (two roots), the circle of radius a1 about
    /// axis 1 fixes theta12 (two roots), then theta1 by atan2.
    fn branch_angles(&self, target: &Pose, branch: Branch, theta4: f64) -> Option<[f64; 4]> {
        let l = &self.links;
        let p = (self.base_inverse * *target).translation;
        let g = self.tool_chain.translation;
        let k = rot_x_quarter(self.sign3) * (Pose::rot_z(theta4).rotation * g);
        let height = self.sign2 * (p.z - l[0].d - l[1].d);
        let theta3 = *solve_cos_sin(k.y, k.x, height).get(branch.theta3_root)?;
        let (s3, c3) = theta3.sin_cos();
        // u = Rx(alpha2) Rz(theta3) k, horizontal part.
        let ux = c3 * k.x - s3 * k.y;
        let uy = -self.sign2 * k.z;
        let wx = l[1].a + ux;
        let wy = -self.sign2 * l[2].d + uy;
        let a1 = l[0].a;
        let rhs = 0.5 * (p.x * p.x + p.y * p.y + wx * wx + wy * wy - a1 * a1);
        let theta12 = *solve_cos_sin(p.x * wx + p.y * wy, p.y * wx - p.x * wy, rhs)
            .get(branch.theta12_root)?;
        let (s12, c12) = theta12.sin_cos();
        let rx = p.x - (c12 * wx - s12 * wy);
        let ry = p.y - (s12 * wx + c12 * wy);
        let theta1 = ry.atan2(rx);
        Some([theta1, theta12 - theta1, theta3, theta4])
    }

    /// The DH range of theta4 scanned: its joint limits, or one turn
    /// about its midpoint when they span more than a turn.
    fn theta4_range(&self) -> (f64, f64) {
        use std::f64::consts::PI;
        let limits = &self.model.joints()[3].limits;
        let link = &self.links[3];
        if limits.is_bounded() && limits.upper - limits.lower < 2.0 * PI {
            (dh_angle(link, limits.lower), dh_angle(link, limits.upper))
        } else {
            let middle = dh_angle(link, limits.midpoint());
            (middle - PI, middle + PI)
        }
    }

    fn joint_values(&self, thetas: [f64; 4]) -> Vec<f64> {
        thetas
            .iter()
            .zip(&self.links)
            .map(|(t, link)| joint_value(link, *t))
            .collect()
    }
}
