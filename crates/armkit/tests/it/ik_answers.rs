//! The answers an engineer expects of the analytic and automatic IK: exact
//! solutions before least-squares ones, and a 7-DOF arm's answer near the
//! start when the start is near a solution.

use armkit::ik::analytic::{AnalyticOptions, AnalyticSolver, Fit, Representatives};
use armkit::ik::{AutoSolver, IkOptions, IkStatus};
use armkit::kinematics::{forward_kinematics, Data};
use rand::Rng;

use crate::common;

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// On UR5 poses near the edge of the workspace some branches have only a
/// least-squares answer: every list with an exact solution starts with the
/// nearest exact one, and the case where a least-squares answer is nearer
/// the start than every exact one occurs (so the order is tested).
#[test]
fn exact_solutions_come_first() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let options = AnalyticOptions {
        representatives: Representatives::Nearest,
        ..AnalyticOptions::default()
    };
    let mut solver = AnalyticSolver::new(&model, options).unwrap();
    let mut data = Data::new(&model);
    let mut rng = common::rng(3030);
    let (mut mixed, mut approximate_nearer) = (0, 0);
    for _ in 0..2000 {
        let q = common::random_configuration(&model, &mut rng);
        let start = common::random_configuration(&model, &mut rng);
        let target = *forward_kinematics(&model, &mut data, &q).unwrap();
        let solutions = solver.solve(&target, &start).unwrap();
        let exact: Vec<_> = solutions.iter().filter(|s| s.fit == Fit::Exact).collect();
        assert!(!exact.is_empty(), "q = {q:?}: the generating configuration");
        let n = exact.len();
        // Exact first, each group nearest first.
        assert!(solutions[..n].iter().all(|s| s.fit == Fit::Exact));
        for group in [&solutions[..n], &solutions[n..]] {
            for pair in group.windows(2) {
                assert!(distance(pair[0].q(), &start) <= distance(pair[1].q(), &start) + 1e-12);
            }
        }
        if n < solutions.len() {
            mixed += 1;
            let nearest_miss = distance(solutions[n].q(), &start);
            approximate_nearer += usize::from(nearest_miss < distance(solutions[0].q(), &start));
        }
    }
    assert!(
        mixed > 20 && approximate_nearer > 5,
        "{mixed} {approximate_nearer}"
    );
}

/// The Panda's automatic answer honours the start: over 200 poses, each
/// from a start within 0.2 rad (joint-space distance) of a configuration
/// reaching it, at most 1 % of the answers land more than 0.5 rad from the
/// start.
#[test]
fn panda_auto_lands_near_a_near_start() {
    let model = armkit::robots::by_name("panda").unwrap();
    let options = IkOptions {
        time_budget: None,
        ..IkOptions::default()
    };
    let mut auto = AutoSolver::new(&model, options).unwrap();
    let mut data = Data::new(&model);
    let mut rng = common::rng(3031);
    let (mut far, mut worst) = (0, 0.0f64);
    for _ in 0..200 {
        let q = common::random_configuration(&model, &mut rng);
        let target = *forward_kinematics(&model, &mut data, &q).unwrap();
        // A random direction, a radius up to 0.2 rad, clamped into the
        // limits (which only brings the start nearer q).
        let direction: Vec<f64> = (0..7).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let radius = rng.gen_range(0.0..0.2) / distance(&direction, &[0.0; 7]);
        let start: Vec<f64> = q
            .iter()
            .zip(&direction)
            .zip(model.joints())
            .map(|((v, d), j)| (v + radius * d).clamp(j.limits.lower, j.limits.upper))
            .collect();
        assert!(distance(&start, &q) <= 0.2 + 1e-12);
        let solved = auto.solve(&target, &start).unwrap();
        assert_eq!(solved.report.status, IkStatus::Converged);
        let d = distance(&solved.report.q, &start);
        worst = worst.max(d);
        far += usize::from(d > 0.5);
    }
    assert!(
        far <= 2,
        "{far} of 200 answers more than 0.5 rad from the start (worst {worst:.3})"
    );
}
