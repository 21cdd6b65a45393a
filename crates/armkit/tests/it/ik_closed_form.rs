//! Closed-form IK: Pieper's 8 solutions for puma560 and space6r, seed 002's
//! 4-DOF arm (exact and approximate), each solution checked by FK.

use crate::common;

use armkit::ik::closed_form::{
    arm4_solutions, Arm4Solver, ClosedFormSolver, Fit, RangeFilter, SphericalWristSolver,
    EXACT_TOLERANCE,
};
use armkit::ik::{benchmark_targets, pose_error};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Pose;
use armkit::Model;

fn fk_errors(model: &Model, q: &[f64], target: &Pose) -> (f64, f64) {
    let mut data = Data::new(model);
    let e = pose_error(target, forward_kinematics(model, &mut data, q).unwrap());
    (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm())
}

fn same_angles(a: &[f64], b: &[f64], tolerance: f64) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| armkit::math::wrap_angle(x - y).abs() < tolerance)
}

#[test]
fn spherical_wrist_arms_have_eight_solutions_at_generic_poses() {
    for name in ["puma560", "space6r"] {
        let model = armkit::robots::by_name(name).unwrap();
        let solver = SphericalWristSolver::new(&model).unwrap();
        let targets = benchmark_targets(&model, 300, 1).unwrap();
        let mut all_eight_in_range = 0;
        for (q, target) in &targets {
            let all = solver
                .solve_with(target, q, RangeFilter::IgnoreLimits)
                .unwrap();
            assert_eq!(all.len(), 8, "{name} at {q:?}");
            for s in &all {
                assert_eq!(s.fit, Fit::Exact);
                let (dp, dr) = fk_errors(&model, &s.q, target);
                assert!(dp <= 1e-10 && dr <= 1e-10, "{name}: {dp:e} m {dr:e} rad");
            }
            // The configuration the target came from is among them, first.
            assert!(
                same_angles(&all[0].q, q, 1e-8),
                "{name}: {:?} vs {q:?}",
                all[0].q
            );
            // The 8 are distinct configurations.
            for i in 0..8 {
                for j in i + 1..8 {
                    assert!(!same_angles(&all[i].q, &all[j].q, 1e-6));
                }
            }
            // Within the limits: exactly those of the 8 inside the limits.
            let within = solver.solve(target, q).unwrap();
            let inside = all
                .iter()
                .filter(|s| model.check_limits(&s.q).is_ok())
                .count();
            assert!(within.len() >= inside, "{name}");
            for s in &within {
                model.check_limits(&s.q).unwrap();
            }
            if within.len() == 8 {
                all_eight_in_range += 1;
            }
        }
        // space6r's +-180 deg joints take every solution; the PUMA's
        // narrower ranges still leave all 8 for many poses.
        if name == "space6r" {
            assert_eq!(all_eight_in_range, 300);
        } else {
            assert!(
                all_eight_in_range >= 30,
                "{name}: all 8 in range only {all_eight_in_range} times"
            );
        }
    }
}

#[test]
fn puma_solutions_are_sorted_nearest_the_current_configuration() {
    let model = armkit::robots::by_name("puma560").unwrap();
    let solver = ClosedFormSolver::new(&model).unwrap();
    let mut rng = common::rng(3);
    let targets = benchmark_targets(&model, 100, 2).unwrap();
    for (_, target) in &targets {
        let current = common::random_configuration(&model, &mut rng);
        let solutions = solver.solve(target, &current).unwrap();
        let distance = |q: &[f64]| {
            q.iter()
                .zip(&current)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
        };
        for pair in solutions.windows(2) {
            assert!(distance(&pair[0].q) <= distance(&pair[1].q));
        }
        for s in &solutions {
            model.check_limits(&s.q).unwrap();
            assert!(s.position_error <= EXACT_TOLERANCE && s.orientation_error <= EXACT_TOLERANCE);
        }
    }
}

#[test]
fn wrist_singular_pose_keeps_the_current_wrist_angle() {
    // q5 = 0: axes 4 and 6 align; theta4 stays at its current value.
    let model = armkit::robots::by_name("puma560").unwrap();
    let q = [0.2, 0.5, -1.0, 0.7, 0.0, -0.3];
    let mut data = Data::new(&model);
    let target = *forward_kinematics(&model, &mut data, &q).unwrap();
    let solutions = SphericalWristSolver::new(&model)
        .unwrap()
        .solve(&target, &q)
        .unwrap();
    assert!(!solutions.is_empty());
    assert!(
        same_angles(&solutions[0].q, &q, 1e-8),
        "{:?}",
        solutions[0].q
    );
    for s in &solutions {
        let (dp, dr) = fk_errors(&model, &s.q, &target);
        assert!(dp <= 1e-10 && dr <= 1e-10);
    }
}

#[test]
fn unreachable_pose_has_no_solution() {
    let model = armkit::robots::by_name("puma560").unwrap();
    let target = Pose::from_xyz_rpy([2.0, 0.5, 0.3], [0.0, 0.0, 0.0]);
    let solutions = ClosedFormSolver::new(&model)
        .unwrap()
        .solve(&target, &[0.0; 6])
        .unwrap();
    assert!(solutions.is_empty());
}

#[test]
fn models_that_do_not_fit_get_a_clear_error() {
    let ur5 = armkit::robots::by_name("ur5").unwrap();
    let e = ClosedFormSolver::new(&ur5).unwrap_err().to_string();
    assert!(e.contains("`ur5` has no closed-form solver"), "{e}");
    assert!(e.contains("alpha3 is not +-90 deg"), "{e}");
    let panda = armkit::robots::by_name("panda").unwrap();
    let e = SphericalWristSolver::new(&panda).unwrap_err().to_string();
    assert!(e.contains("not standard DH"), "{e}");
    let gantry = armkit::robots::by_name("gantry9").unwrap();
    let e = Arm4Solver::new(&gantry).unwrap_err().to_string();
    assert!(e.contains("not standard DH"), "{e}");
    let puma = armkit::robots::by_name("puma560").unwrap();
    let e = Arm4Solver::new(&puma).unwrap_err().to_string();
    assert!(e.contains("6 joints, not 4"), "{e}");
    let stanford = armkit::robots::by_name("stanford").unwrap();
    let e = SphericalWristSolver::new(&stanford)
        .unwrap_err()
        .to_string();
    assert!(e.contains("prismatic"), "{e}");
    let puma = armkit::robots::by_name("puma560").unwrap();
    let solver = SphericalWristSolver::new(&puma).unwrap();
    let mut bad = Pose::identity();
    bad.translation.y = f64::NAN;
    assert!(solver
        .solve(&bad, &[0.0; 6])
        .unwrap_err()
        .to_string()
        .contains("target"));
    assert_eq!(
        solver
            .solve(&Pose::identity(), &[0.0; 5])
            .unwrap_err()
            .to_string(),
        "current: expected 6 values, got 5"
    );
}

#[test]
fn arm4_reachable_poses_are_solved_exactly() {
    // Seed 002's branches (theta2 = +-acos, eq 11) both give a wrist point
    // on target, but the orientation (eqs 17-18) fixes theta12: for a pose
    // of the 4-D reachable set only one branch reproduces it (the other is
    // one of the paper's extraneous roots), so a generic pose has exactly
    // one solution, and it is the configuration the pose came from.
    let model = armkit::robots::by_name("arm4").unwrap();
    let solver = Arm4Solver::new(&model).unwrap();
    let targets = benchmark_targets(&model, 300, 9).unwrap();
    for (q, target) in &targets {
        let all = solver
            .solve_with(target, q, RangeFilter::IgnoreLimits)
            .unwrap();
        assert_eq!(all.len(), 1, "{q:?}: {all:?}");
        for s in &all {
            assert_eq!(s.fit, Fit::Exact);
            let (dp, dr) = fk_errors(&model, &s.q, target);
            assert!(dp <= 1e-10 && dr <= 1e-10);
        }
        let within = arm4_solutions(&model, target, q).unwrap();
        assert_eq!(within.len(), 1);
        assert!(
            same_angles(&within[0].q, q, 1e-8),
            "{:?} vs {q:?}",
            within[0].q
        );
        model.check_limits(&within[0].q).unwrap();
    }
}

#[test]
fn arm4_out_of_range_solutions_are_dropped() {
    // A pose made with the pitch beyond its +120 deg limit: its exact
    // solution is outside the limits, so within the limits only
    // approximate ones remain (tool position exact, e.g. with the roll
    // turned by pi and the pitch at 180 deg - 132 deg).
    let model = armkit::robots::by_name("arm4").unwrap();
    let q = [-0.4, 1.2, 0.3, 2.3];
    assert!(model.check_limits(&q).is_err());
    let mut data = Data::new(&model);
    let target = *forward_kinematics(&model, &mut data, &q).unwrap();
    let solver = Arm4Solver::new(&model).unwrap();
    let all = solver
        .solve_with(&target, &q, RangeFilter::IgnoreLimits)
        .unwrap();
    assert_eq!(all.len(), 1);
    assert!(same_angles(&all[0].q, &q, 1e-8) && all[0].fit == Fit::Exact);
    let within = solver.solve(&target, &[0.0; 4]).unwrap();
    assert!(!within.is_empty());
    for s in &within {
        assert_eq!(s.fit, Fit::Approximate);
        model.check_limits(&s.q).unwrap();
        assert!(s.position_error <= 1e-10 && s.orientation_error > 1e-6);
    }
}

#[test]
fn arm4_unreachable_orientation_keeps_the_position_and_fits_the_orientation() {
    // Tilt reachable poses off the arm's 4-D set: the solutions put the tool
    // on the target position exactly, and the orientation residual is no
    // worse than the tilt (the untilted configuration is in the family).
    let model = armkit::robots::by_name("arm4").unwrap();
    let solver = Arm4Solver::new(&model).unwrap();
    let targets = benchmark_targets(&model, 40, 10).unwrap();
    let mut strictly_better = 0;
    for (k, (q, target)) in targets.iter().enumerate() {
        let tilt = 0.05 + 0.005 * k as f64;
        let tilted = Pose::new(
            Pose::rot_x(tilt).rotation * target.rotation,
            target.translation,
        );
        let solutions = solver.solve(&tilted, q).unwrap();
        assert!(!solutions.is_empty(), "{q:?}");
        let best = solutions
            .iter()
            .map(|s| s.orientation_error)
            .fold(f64::INFINITY, f64::min);
        assert!(best <= tilt + 1e-9, "residual {best} > tilt {tilt}");
        strictly_better += usize::from(best < tilt - 1e-4);
        for s in &solutions {
            assert_eq!(s.fit, Fit::Approximate);
            model.check_limits(&s.q).unwrap();
            let (dp, dr) = fk_errors(&model, &s.q, &tilted);
            assert!(dp <= 1e-10, "tool position off by {dp:e} m");
            assert!((dr - s.orientation_error).abs() < 1e-9);
        }
    }
    // The best fit usually beats the untilted configuration.
    assert!(strictly_better >= 20, "{strictly_better}");
}

#[test]
fn arm4_position_out_of_reach_gives_no_solution() {
    let model = armkit::robots::by_name("arm4").unwrap();
    let far = Pose::from_xyz_rpy([2.0, 0.0, 0.3], [0.0, 0.0, 0.0]);
    assert!(arm4_solutions(&model, &far, &[0.0; 4]).unwrap().is_empty());
}
