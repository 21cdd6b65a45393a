//! Numeric inverse kinematics: FK of every returned solution, joint limits,
//! honest status on unreachable targets, input errors, determinism,
//! redundancy, task masks.

use crate::common;

use armkit::ik::{
    benchmark_targets, IkMethod, IkOptions, IkSelection, IkSolver, IkStatus, Redundancy,
};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::{Pose, Vector3};
use armkit::Model;

const METHODS: [&str; 4] = ["nr", "dls", "lm", "sri"];

fn robots() -> Vec<Model> {
    let mut models: Vec<Model> = [
        "ur5", "puma560", "panda", "gantry9", "stanford", "space6r", "arm4",
    ]
    .iter()
    .map(|n| armkit::robots::by_name(n).unwrap())
    .collect();
    let selection = armkit::urdf::ChainSelection::between("base_link", "tool0");
    models.push(armkit::urdf::load(common::data_path("urdf/iiwa14.urdf"), &selection).unwrap());
    models
}

/// Deterministic options: no wall-clock budget, a bounded number of restarts.
fn options(method: &str, restarts: usize) -> IkOptions {
    IkOptions {
        method: IkMethod::from_short_name(method).unwrap(),
        time_budget: None,
        max_restarts: restarts,
        ..IkOptions::default()
    }
}

/// Position and orientation error of FK(q) from the target, computed
/// independently of the solver.
fn fk_errors(model: &Model, q: &[f64], target: &Pose) -> (f64, f64) {
    let mut data = Data::new(model);
    let pose = forward_kinematics(model, &mut data, q).unwrap();
    let dp = (pose.translation - target.translation).norm();
    let relative = target.rotation * pose.rotation.transpose();
    let angle = ((relative.trace() - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
    // acos loses digits near 0: use the skew part there.
    let skew = Vector3::new(
        relative[(2, 1)] - relative[(1, 2)],
        relative[(0, 2)] - relative[(2, 0)],
        relative[(1, 0)] - relative[(0, 1)],
    ) * 0.5;
    let angle = if angle < 1e-3 {
        skew.norm().asin()
    } else {
        angle
    };
    (dp, angle)
}

#[test]
fn every_solver_reaches_random_targets_on_every_robot() {
    let targets_per_robot = 25;
    for model in robots() {
        let targets = benchmark_targets(&model, targets_per_robot, 7).unwrap();
        let start = model.neutral_configuration();
        for method in METHODS {
            let restarts = if method == "lm" { 200 } else { 30 };
            let mut solver = IkSolver::new(&model, options(method, restarts)).unwrap();
            let mut converged = 0;
            for (_, target) in &targets {
                let report = solver.solve(target, &start).unwrap();
                model.check_limits(&report.q).unwrap();
                let (dp, dr) = fk_errors(&model, &report.q, target);
                // The report's errors are the true ones at the returned q.
                assert!(
                    (dp - report.position_error).abs() < 1e-12,
                    "{}",
                    model.name()
                );
                assert!(
                    (dr - report.orientation_error).abs() < 1e-9,
                    "{}",
                    model.name()
                );
                if report.status == IkStatus::Converged {
                    converged += 1;
                    assert!(
                        dp <= 1e-6 && dr <= 1e-6,
                        "{} {method}: converged with {dp:e} m, {dr:e} rad",
                        model.name()
                    );
                } else {
                    assert!(
                        dp > 1e-6 || dr > 1e-6,
                        "{} {method}: not converged at a solution",
                        model.name()
                    );
                }
            }
            // Levenberg-Marquardt solves them all; the others are velocity-level
            // baselines (damping slows them near singular targets) but still
            // solve nearly all of these.
            let required = if method == "lm" {
                targets_per_robot
            } else {
                targets_per_robot * 8 / 10
            };
            assert!(
                converged >= required,
                "{} {method}: {converged}/{targets_per_robot} converged",
                model.name()
            );
        }
    }
}

#[test]
fn no_returned_solution_ever_violates_a_joint_limit() {
    // Reachable targets, targets pushed beyond reach and random starts,
    // thousands of solves with a small budget so that many end unconverged.
    let mut rng = common::rng(11);
    let mut solves = 0;
    for model in robots() {
        let targets = benchmark_targets(&model, 160, 3).unwrap();
        let mut solver = IkSolver::new(&model, options("lm", 3)).unwrap();
        for (k, (_, target)) in targets.iter().enumerate() {
            let start = common::random_configuration(&model, &mut rng);
            let mut goal = *target;
            if k % 3 == 0 {
                goal.translation *= 3.0; // mostly beyond reach
            }
            let report = solver.solve(&goal, &start).unwrap();
            assert!(
                model.check_limits(&report.q).is_ok(),
                "{}: {:?} outside the limits",
                model.name(),
                report.q
            );
            solves += 1;
        }
        for method in ["nr", "dls", "sri"] {
            let mut solver = IkSolver::new(&model, options(method, 2)).unwrap();
            for (_, target) in targets.iter().take(30) {
                let report = solver
                    .solve(target, &model.neutral_configuration())
                    .unwrap();
                model.check_limits(&report.q).unwrap();
                solves += 1;
            }
        }
    }
    assert!(solves >= 2000);
}

#[test]
fn unreachable_targets_come_back_not_converged_with_the_best_iterate() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let start = model.neutral_configuration();
    // 3 m away, beyond the sum of the UR5's link lengths (about 1 m): not
    // attempted at all.
    let far = Pose::from_xyz_rpy([3.0, 0.0, 0.3], [0.0, 0.0, 0.0]);
    // 0.99 m from the base axis along x: within the sum of the link lengths
    // (1.009 m) but beyond what the bent arm reaches: every restart fails.
    let target = Pose::from_xyz_rpy([0.99, 0.0, 0.0895], [0.0, 0.0, 0.0]);
    for method in METHODS {
        let mut solver = IkSolver::new(&model, options(method, 20)).unwrap();
        let report = solver.solve(&far, &start).unwrap();
        assert_eq!(report.status, IkStatus::NotConverged, "{method}");
        assert_eq!((report.iterations, report.restarts), (0, 0), "{method}");
        assert_eq!(report.q, start);
        let report = solver.solve(&target, &start).unwrap();
        assert_eq!(report.status, IkStatus::NotConverged, "{method}");
        model.check_limits(&report.q).unwrap();
        let (dp, dr) = fk_errors(&model, &report.q, &target);
        assert!((dp - report.position_error).abs() < 1e-12);
        // The best iterate has the lowest objective E = (|dp|^2 + |dr|^2) / 2
        // seen: no worse than the start, and for Levenberg-Marquardt
        // (which only takes steps that lower E) stretched toward the target.
        let (dp0, dr0) = fk_errors(&model, &start, &target);
        assert!(dp * dp + dr * dr <= dp0 * dp0 + dr0 * dr0, "{method}");
        if method == "lm" {
            assert!(dp < 0.25, "{method}: best iterate {dp} m away");
        }
        assert_eq!(
            report.restarts, 20,
            "{method}: the whole restart budget is used"
        );
    }
    // An orientation-only miss: a reachable position with a rotation that
    // the 4-DOF arm cannot take.
    let arm4 = armkit::robots::by_name("arm4").unwrap();
    let mut data = Data::new(&arm4);
    let reachable = *forward_kinematics(&arm4, &mut data, &[0.3, -0.9, 0.5, 0.4]).unwrap();
    let tilted = Pose::new(
        Pose::rot_x(0.3).rotation * reachable.rotation,
        reachable.translation,
    );
    let mut solver = IkSolver::new(&arm4, options("lm", 10)).unwrap();
    let report = solver
        .solve(&tilted, &arm4.neutral_configuration())
        .unwrap();
    assert_eq!(report.status, IkStatus::NotConverged);
    assert!(report.orientation_error > 1e-6);
}

#[test]
fn nan_and_infinite_targets_and_bad_starts_are_errors() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let mut solver = IkSolver::new(&model, IkOptions::default()).unwrap();
    let start = model.neutral_configuration();
    let mut target = Pose::from_xyz_rpy([0.3, 0.2, 0.4], [0.0, 0.0, 0.0]);
    target.translation.x = f64::NAN;
    let e = solver.solve(&target, &start).unwrap_err().to_string();
    assert!(
        e.contains("invalid argument `target`") && e.contains("non-finite"),
        "{e}"
    );
    let mut target = Pose::from_xyz_rpy([0.3, 0.2, 0.4], [0.0, 0.0, 0.0]);
    target.rotation[(1, 1)] = f64::INFINITY;
    assert!(solver
        .solve(&target, &start)
        .unwrap_err()
        .to_string()
        .contains("target"));
    let mut skewed = Pose::from_xyz_rpy([0.3, 0.2, 0.4], [0.0, 0.0, 0.0]);
    skewed.rotation[(0, 1)] = 0.5;
    let e = solver.solve(&skewed, &start).unwrap_err().to_string();
    assert!(e.contains("not a proper rotation"), "{e}");
    let good = Pose::from_xyz_rpy([0.3, 0.2, 0.4], [0.0, 0.0, 0.0]);
    let e = solver.solve(&good, &[0.0; 5]).unwrap_err().to_string();
    assert_eq!(e, "joint_positions: expected 6 values, got 5");
    let e = solver
        .solve(&good, &[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0])
        .unwrap_err()
        .to_string();
    assert_eq!(e, "joint_positions[2] is not finite (NaN)");
}

#[test]
fn options_are_validated_with_the_field_named() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let cases: Vec<(IkOptions, &str)> = vec![
        (
            IkOptions {
                position_tolerance: 0.0,
                ..IkOptions::default()
            },
            "position_tolerance",
        ),
        (
            IkOptions {
                orientation_tolerance: f64::NAN,
                ..IkOptions::default()
            },
            "orientation_tolerance",
        ),
        (
            IkOptions {
                max_iterations: 0,
                ..IkOptions::default()
            },
            "max_iterations",
        ),
        (
            IkOptions {
                task_weights: [0.0; 6],
                ..IkOptions::default()
            },
            "task_weights",
        ),
        (
            IkOptions {
                task_weights: [1.0, -1.0, 1.0, 1.0, 1.0, 1.0],
                ..IkOptions::default()
            },
            "task_weights",
        ),
        (
            IkOptions {
                selection: IkSelection::Nearest { solutions: 0 },
                ..IkOptions::default()
            },
            "selection",
        ),
        (
            IkOptions {
                redundancy: Redundancy::PullToStart {
                    gain: 2.0,
                    iterations: 5,
                },
                ..IkOptions::default()
            },
            "redundancy",
        ),
        (
            IkOptions {
                time_budget: Some(std::time::Duration::ZERO),
                ..IkOptions::default()
            },
            "time_budget",
        ),
        (
            IkOptions {
                method: IkMethod::LevenbergMarquardt(armkit::ik::LmDamping { floor: -1.0 }),
                ..IkOptions::default()
            },
            "LmDamping.floor",
        ),
    ];
    for (options, field) in cases {
        let e = IkSolver::new(&model, options).unwrap_err().to_string();
        assert!(e.contains(&format!("`{field}`")), "{field}: {e}");
    }
    assert!(IkMethod::from_short_name("newton")
        .unwrap_err()
        .to_string()
        .contains("nr, dls, lm or sri"));
}

#[test]
fn same_seed_same_answer() {
    for name in ["ur5", "panda"] {
        let model = armkit::robots::by_name(name).unwrap();
        let targets = benchmark_targets(&model, 30, 5).unwrap();
        let start = model.neutral_configuration();
        let mut first = IkSolver::new(&model, options("lm", 100).with_seed(9)).unwrap();
        let mut second = IkSolver::new(&model, options("lm", 100).with_seed(9)).unwrap();
        let mut restarted = 0;
        for (_, target) in &targets {
            let a = first.solve(target, &start).unwrap();
            let b = second.solve(target, &start).unwrap();
            let again = first.solve(target, &start).unwrap();
            assert_eq!(a.q, b.q, "{name}");
            assert_eq!(a.q, again.q, "{name}");
            assert_eq!((a.iterations, a.restarts), (b.iterations, b.restarts));
            restarted += usize::from(a.restarts > 0);
        }
        // The check means something only if some solves used random restarts.
        assert!(restarted > 0, "{name}: no solve needed a restart");
    }
}

#[test]
fn the_first_attempt_starts_from_the_start_and_keeps_continuity() {
    // A target close to the start is solved from the start, without restarts,
    // and the solution is the nearby one.
    let mut rng = common::rng(21);
    for name in ["ur5", "puma560", "panda", "gantry9"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut solver = IkSolver::new(&model, options("lm", 50)).unwrap();
        let mut data = Data::new(&model);
        for _ in 0..20 {
            let start = common::random_configuration(&model, &mut rng);
            let nearby: Vec<f64> = start
                .iter()
                .zip(model.joints())
                .map(|(q, j)| (q + 0.02).clamp(j.limits.lower, j.limits.upper))
                .collect();
            let target = *forward_kinematics(&model, &mut data, &nearby).unwrap();
            let report = solver.solve(&target, &start).unwrap();
            assert!(report.converged(), "{name}");
            assert_eq!(report.restarts, 0, "{name}");
            let distance: f64 = report
                .q
                .iter()
                .zip(&start)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            let moved: f64 = nearby
                .iter()
                .zip(&start)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                distance <= moved * 1.5 + 1e-9,
                "{name}: went {distance} for a {moved} move"
            );
        }
    }
}

#[test]
fn redundant_robots_stay_near_the_start() {
    // With 7 or 9 joints the minimum-norm steps leave the spare freedom
    // where the start put it: for a target near the start, the solution is
    // about as near the start as the configuration the target was made from
    // (within 50 %: each step is minimum-norm, but the first, heavily damped
    // steps bend the path), and with the null-space pull no farther at all.
    let mut rng = common::rng(5);
    for name in ["panda", "gantry9"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut data = Data::new(&model);
        let mut solver = IkSolver::new(&model, options("lm", 0)).unwrap();
        let pull = IkOptions {
            redundancy: Redundancy::PullToStart {
                gain: 0.5,
                iterations: 30,
            },
            ..options("lm", 0)
        };
        let mut pulled = IkSolver::new(&model, pull).unwrap();
        let start = model.neutral_configuration();
        for _ in 0..20 {
            let offset: Vec<f64> = start
                .iter()
                .zip(model.joints())
                .map(|(q, j)| {
                    (q + rand::Rng::gen_range(&mut rng, -0.15..0.15))
                        .clamp(j.limits.lower, j.limits.upper)
                })
                .collect();
            let target = *forward_kinematics(&model, &mut data, &offset).unwrap();
            let made_from = distance(&offset, &start);
            let report = solver.solve(&target, &start).unwrap();
            assert!(report.converged(), "{name}");
            let d = distance(&report.q, &start);
            assert!(d <= 1.5 * made_from, "{name}: {d} vs {made_from}");
            let report = pulled.solve(&target, &start).unwrap();
            assert!(report.converged(), "{name}");
            let d = distance(&report.q, &start);
            assert!(d <= made_from + 1e-6, "{name}: pulled {d} vs {made_from}");
        }
    }
}

#[test]
fn the_null_space_pull_brings_redundant_robots_nearer_the_start() {
    // Far targets: the minimum-norm path bends, and the pull then moves the
    // converged solution along its self-motion toward the start.
    for name in ["panda", "gantry9"] {
        let model = armkit::robots::by_name(name).unwrap();
        let targets = benchmark_targets(&model, 30, 6).unwrap();
        let start = model.neutral_configuration();
        let mut minimum_norm = IkSolver::new(&model, options("lm", 100)).unwrap();
        let pull = IkOptions {
            redundancy: Redundancy::PullToStart {
                gain: 0.5,
                iterations: 30,
            },
            ..options("lm", 100)
        };
        let mut pulled = IkSolver::new(&model, pull).unwrap();
        let mut improved = 0;
        for (_, target) in &targets {
            let a = minimum_norm.solve(target, &start).unwrap();
            let b = pulled.solve(target, &start).unwrap();
            assert!(a.converged() && b.converged(), "{name}");
            assert!(
                distance(&b.q, &start) <= distance(&a.q, &start) + 1e-12,
                "{name}"
            );
            improved += usize::from(distance(&b.q, &start) < distance(&a.q, &start) - 1e-3);
        }
        assert!(
            improved >= 10,
            "{name}: the pull helped only {improved} times in 30"
        );
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn nearest_selection_is_never_farther_than_the_first() {
    let model = armkit::robots::by_name("ur5").unwrap();
    let targets = benchmark_targets(&model, 20, 8).unwrap();
    let start = model.neutral_configuration();
    let mut first = IkSolver::new(&model, options("lm", 200)).unwrap();
    let nearest_options = IkOptions {
        selection: IkSelection::Nearest { solutions: 6 },
        ..options("lm", 200)
    };
    let mut nearest = IkSolver::new(&model, nearest_options).unwrap();
    let distance = |q: &[f64]| {
        q.iter()
            .zip(&start)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let mut strictly = 0;
    for (_, target) in &targets {
        let a = first.solve(target, &start).unwrap();
        let b = nearest.solve(target, &start).unwrap();
        assert!(a.converged() && b.converged());
        assert!(distance(&b.q) <= distance(&a.q) + 1e-12);
        strictly += usize::from(distance(&b.q) < distance(&a.q) - 1e-6);
    }
    assert!(strictly > 0, "Nearest never found a nearer solution");
}

#[test]
fn position_only_mask_solves_the_four_dof_arm() {
    // arm4 reaches a 3-D set of positions: a position-only task always
    // converges and reports no orientation error.
    let model = armkit::robots::by_name("arm4").unwrap();
    let targets = benchmark_targets(&model, 50, 4).unwrap();
    let mut rng = common::rng(2);
    let masked = IkOptions {
        task_weights: [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
        ..options("lm", 50)
    };
    let mut solver = IkSolver::new(&model, masked).unwrap();
    for (_, target) in &targets {
        // Any orientation: it is not asked for.
        let goal = Pose::new(
            Pose::rot_y(rand::Rng::gen_range(&mut rng, -1.0..1.0)).rotation,
            target.translation,
        );
        let report = solver.solve(&goal, &model.neutral_configuration()).unwrap();
        assert!(report.converged());
        assert_eq!(report.orientation_error, 0.0);
        let (dp, _) = fk_errors(&model, &report.q, &goal);
        assert!(dp <= 1e-6);
    }
}

#[test]
fn wide_revolute_joints_come_back_nearest_the_start() {
    // UR5 joints span +-2 pi: of q and q +- 2 pi, the one nearest the start.
    let model = armkit::robots::by_name("ur5").unwrap();
    let targets = benchmark_targets(&model, 50, 12).unwrap();
    let start = [4.0, -4.0, 0.5, 3.5, -3.5, 5.0];
    let mut solver = IkSolver::new(&model, options("lm", 200)).unwrap();
    for (_, target) in &targets {
        let report = solver.solve(target, &start).unwrap();
        assert!(report.converged());
        for (j, (q, s)) in report.q.iter().zip(&start).enumerate() {
            let limits = model.joints()[j].limits;
            for k in [-1.0, 1.0] {
                let other = q + k * std::f64::consts::TAU;
                if limits.contains(other) {
                    assert!(
                        (q - s).abs() <= (other - s).abs() + 1e-12,
                        "joint {j}: {q} vs {other}"
                    );
                }
            }
        }
    }
}
