//! A singular region of seed 004's avoidance (sec 2.3.2, steps 2-4): the
//! IK knots of every `k`-th planned pose until the motion is regular again,
//! each exact where the arm can reach it within `eps_dq` per period and
//! least-squares otherwise, the region's knots then planned jointly where
//! some were least-squares ([`super::region_plan`]), and the C2 fit through
//! them.

use super::avoidance::PathTracker;
use super::detection::{detect, Trigger};
use super::method::SingularRegion;
use super::plant::{KnotSolve, Plant};
use super::region_plan::{plan_jointly, KnotProblem, RegionPlan};
use crate::error::Result;
use crate::ik::{damped_least_squares_step, pose_error};
use crate::math::{DMatrix, Pose};
use crate::trajectory::clamped_cubic_spline;

impl PathTracker<'_> {
    /// Plans the singular region entered at sample `entry` (seed 004, sec
    /// 2.3.2, steps 2-4): the knots, their IK, and the C2 fit.
    pub(super) fn plan_region(
        &self,
        plant: &mut Plant<'_>,
        entry: usize,
        k: usize,
        trigger: Trigger,
        entry_rates: &[f64],
    ) -> Result<(crate::trajectory::Trajectory, usize, SingularRegion)> {
        let h = self.h;
        let mut times = vec![entry as f64 * h];
        let mut knots = vec![plant.q().to_vec()];
        let mut region = SingularRegion {
            start_time: entry as f64 * h,
            end_time: entry as f64 * h,
            trigger,
            knot_times: Vec::new(),
            ik_solves: 0,
            ik_iterations: 0,
            ik_failures: 0,
            bounded_knots: 0,
            max_knot_error: (0.0, 0.0),
            plan: if self.options.region_plan == RegionPlan::Exact {
                RegionPlan::Exact
            } else {
                RegionPlan::Greedy
            },
            greedy_max_error: 0.0,
            cone_programs: 0,
        };
        let mut index = entry;
        loop {
            index = (index + k).min(self.steps);
            let t = index as f64 * h;
            let target = self.trajectory.pose_at(t);
            // Warm start: the last knot moved on by the secant of the last
            // two (first-order continuation), so that the start is on the
            // branch being followed even where J is nearly singular.
            let last = knots.len() - 1;
            let (t_last, q_last) = (times[last], knots[last].clone());
            let slope: Vec<f64> = if last == 0 {
                entry_rates.to_vec()
            } else {
                let dt = t_last - times[last - 1];
                q_last
                    .iter()
                    .zip(&knots[last - 1])
                    .map(|(a, b)| (a - b) / dt)
                    .collect()
            };
            let start: Vec<f64> = q_last
                .iter()
                .zip(&slope)
                .map(|(q, v)| q + v * (t - t_last))
                .collect();
            let mut solve = plant.solve_ik(&target, &start)?;
            self.remove_self_motion(plant, &target, &start, &mut solve)?;
            region.ik_solves += 1;
            region.ik_iterations += solve.iterations;
            if !solve.converged {
                region.ik_failures += 1;
            }
            // A solution that would move some joint faster than eps_dq per
            // control period since the last knot is beyond what the arm can
            // do (the wrist flip a path passing near the singular pose asks
            // for), and a solve that did not converge is no solution: the
            // knot is then the least-squares one, the nearest pose within
            // eps_dq per period of the last knot.
            let radius = self.options.detection.joint_step_threshold * (t - t_last) / h;
            let jump = solve
                .q
                .iter()
                .zip(&q_last)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            // As printed (RegionPlan::Exact) the Newton solution is the knot
            // however far it jumps; a solve that did not converge keeps its
            // best iterate (counted in ik_failures).
            let as_printed = self.options.region_plan == RegionPlan::Exact;
            let exact = solve.converged && (as_printed || jump <= radius);
            if !exact && !as_printed {
                let bounded = plant.bounded_solve(&target, &q_last, radius, &start)?;
                region.bounded_knots += 1;
                region.ik_iterations += bounded.iterations;
                solve = bounded;
            }
            region.max_knot_error.0 = region.max_knot_error.0.max(solve.position_error);
            region.max_knot_error.1 = region.max_knot_error.1.max(solve.orientation_error);
            region.greedy_max_error = region
                .greedy_max_error
                .max(solve.position_error.hypot(solve.orientation_error));
            let end = index == self.steps;
            // The region ends at an exact knot where the motion is regular
            // again: |det J| at or above the threshold and the plain rates
            // of the planned twist within eps_dq per period (the detection's
            // two tests, passed), or at the path's end.
            let regular = exact && !end && self.regular_at(plant, &solve.q, t)?;
            times.push(t);
            knots.push(solve.q);
            if regular || end {
                break;
            }
        }
        if region.bounded_knots > 0 && self.options.region_plan == RegionPlan::Joint {
            self.plan_jointly(plant, &times, &mut knots, index == self.steps, &mut region)?;
        }
        // End rates: the plain inverse of the planned twist at the exit knot
        // (regular there), or rest at the end of the path.
        let n = plant.dof();
        let mut end_rates = vec![0.0; n];
        if index < self.steps {
            self.planned_rates(plant, index as f64 * h, &mut end_rates)?;
        }
        let fit = clamped_cubic_spline(&times, &knots, entry_rates, &end_rates)?;
        region.end_time = index as f64 * h;
        region.knot_times = times;
        Ok((fit, index, region))
    }

    /// Replaces the greedy knots of a region by the joint plan
    /// ([`RegionPlan::Joint`], module [`super::region_plan`]) when it lowers
    /// their largest error, and records it in `region`.
    fn plan_jointly(
        &self,
        plant: &mut Plant<'_>,
        times: &[f64],
        knots: &mut [Vec<f64>],
        free_last: bool,
        region: &mut SingularRegion,
    ) -> Result<()> {
        let targets: Vec<Pose> = times.iter().map(|t| self.trajectory.pose_at(*t)).collect();
        let limits = self.manipulator().arm().position_limits();
        let problem = KnotProblem {
            targets: &targets,
            times,
            rate_bound: self.options.detection.joint_step_threshold / self.h,
            limits: &limits,
            free_last,
        };
        let mut planned = knots.to_vec();
        let outcome = plan_jointly(plant, &problem, knots, &mut planned)?;
        region.cone_programs = outcome.programs;
        if outcome.max_error < outcome.greedy_max_error {
            region.plan = RegionPlan::Joint;
            region.max_knot_error = (0.0, 0.0);
            for (knot, target) in planned.iter().zip(&targets).skip(1) {
                plant.evaluate(knot)?;
                let e = pose_error(target, plant.pose());
                let error = &mut region.max_knot_error;
                error.0 = error.0.max(e.fixed_rows::<3>(0).norm());
                error.1 = error.1.max(e.fixed_rows::<3>(3).norm());
            }
            knots.clone_from_slice(&planned);
        }
        Ok(())
    }

    /// The plain rates of the planned twist at time `t` (s) at the plant's
    /// last evaluation.
    fn planned_rates(&self, plant: &Plant<'_>, t: f64, rates: &mut [f64]) -> Result<()> {
        let planned = self.trajectory.sample(t)?.twist;
        damped_least_squares_step(plant.jacobian(), &planned, 0.0, rates)
    }

    /// True when the detection's tests pass at joint positions `q` on the
    /// path at time `t` (s): `|det J|` at or above the threshold and the
    /// plain rates of the planned twist within `eps_dq` per period.
    fn regular_at(&self, plant: &mut Plant<'_>, q: &[f64], t: f64) -> Result<bool> {
        plant.evaluate(q)?;
        let mut steps = vec![0.0; q.len()];
        if self.planned_rates(plant, t, &mut steps).is_err() {
            return Ok(false);
        }
        steps.iter_mut().for_each(|s| *s *= self.h);
        let detection = detect(plant.jacobian(), &steps, &self.options.detection)?;
        Ok(!detection.is_singular())
    }

    /// At (or next to) a singular pose the IK solutions form a continuum
    /// (for a wrist singularity, `q4 + d`, `q6 -+ d` for any `d`), and Newton's
    /// iterate drifts along it by whatever its first step overshot: the fit
    /// would turn that drift into a spike of joint rate. This keeps, of the
    /// solution and the solution moved back along the Jacobian's
    /// least-singular right direction `v` to the warm start
    /// (`q - v v'(q - start)`), the latter whenever it is also within the IK
    /// tolerance, i.e. whenever the drift did not matter to the pose.
    fn remove_self_motion(
        &self,
        plant: &mut Plant<'_>,
        target: &Pose,
        start: &[f64],
        solve: &mut KnotSolve,
    ) -> Result<()> {
        plant.evaluate(&solve.q)?;
        let j = plant.jacobian();
        let dense = DMatrix::from_column_slice(6, j.ncols(), j.as_slice());
        let svd = dense.svd(false, true);
        let Some(v_t) = svd.v_t else {
            return Ok(());
        };
        let Some(smallest) = svd
            .singular_values
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .map(|(i, _)| i)
        else {
            return Ok(());
        };
        let v = v_t.row(smallest);
        let drift: f64 = solve
            .q
            .iter()
            .zip(start)
            .zip(v.iter())
            .map(|((q, s), vi)| (q - s) * vi)
            .sum();
        let candidate: Vec<f64> = solve
            .q
            .iter()
            .zip(v.iter())
            .map(|(q, vi)| q - drift * vi)
            .collect();
        plant.evaluate(&candidate)?;
        let error = pose_error(target, plant.pose());
        let (position, orientation) = (
            error.fixed_rows::<3>(0).norm(),
            error.fixed_rows::<3>(3).norm(),
        );
        if position <= self.options.ik_tolerance && orientation <= self.options.ik_tolerance {
            solve.q = candidate;
            solve.position_error = position;
            solve.orientation_error = orientation;
            solve.converged = true;
        }
        Ok(())
    }
}
