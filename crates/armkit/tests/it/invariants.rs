//! Randomized invariants with fixed seeds, checked with the test's own code
//! (not the library's reports):
//!
//! * IK (the four numeric methods and the closed forms) never returns a
//!   configuration outside the joint limits, and never claims convergence
//!   when the recomputed error exceeds the tolerance;
//! * a trajectory scaled by `trajectory::scale_to_limits` never
//!   exceeds its velocity or acceleration limits, sampled densely;
//! * the MPC planner, stepped in a loop with the plant `q += T u`, never
//!   commands a velocity over its limit nor moves a joint out of its limits;
//! * the Jacobian agrees with central finite differences of FK, and FK of DH
//!   models agrees with the test's own product of DH matrices.
//!
//! Each test runs at scale 1 in the normal suite (a few seconds in release);
//! the `long_*` tests (`#[ignore]`d) run the same checks at scale 100
//! (`ARMKIT_SCALE=N` overrides the factor):
//!
//!     cargo test -p armkit --release --test it -- --ignored --nocapture invariants::

use crate::common;

use std::time::Instant;

use armkit::ik::closed_form::{ClosedFormSolver, Fit};
use armkit::ik::{ChiaveriniFilter, IkMethod, IkOptions, IkSolver, LmDamping, NakamuraDamping};
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Matrix3, Matrix4, Pose, Vector3};
use armkit::model::{DhConvention, DhLink, JointKind, JointLimits};
use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights};
use armkit::trajectory::clamped_cubic_spline;
use armkit::trajectory::{check_limits, scale_to_limits, TimeScaling, TrajectoryLimits};
use armkit::trajectory::{interpolate_via_points, BoundaryRates, SegmentScheme, ViaVelocity};
use armkit::trajectory::{rest_to_rest, ProfileShape};
use armkit::trajectory::{JointState, Trajectory};
use armkit::Model;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Scale of the long suite (`ARMKIT_SCALE` overrides).
fn long_scale() -> usize {
    std::env::var("ARMKIT_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100)
}

/// What one invariant family ran: cases and the failures found.
struct Tally {
    name: &'static str,
    cases: usize,
    failures: Vec<String>,
    started: Instant,
}

impl Tally {
    fn new(name: &'static str) -> Self {
        Tally {
            name,
            cases: 0,
            failures: Vec::new(),
            started: Instant::now(),
        }
    }

    fn check(&mut self, ok: bool, describe: impl FnOnce() -> String) {
        if !ok {
            self.failures.push(describe());
        }
    }

    /// Prints the figures (the long suite's report) and fails on any failure.
    fn finish(self) {
        println!(
            "{}: {} cases, {} failures, {:.2} s",
            self.name,
            self.cases,
            self.failures.len(),
            self.started.elapsed().as_secs_f64()
        );
        let shown: Vec<&String> = self.failures.iter().take(20).collect();
        assert!(
            self.failures.is_empty(),
            "{}: {} of {} cases failed; the first:\n  {}",
            self.name,
            self.failures.len(),
            self.cases,
            shown
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("\n  ")
        );
    }
}

fn robot(name: &str) -> Model {
    armkit::robots::by_name(name).unwrap()
}

fn fk(model: &Model, data: &mut Data, q: &[f64]) -> Pose {
    *forward_kinematics(model, data, q).unwrap()
}

/// First joint outside its limits (exact comparison), if any.
fn outside_limits(model: &Model, q: &[f64]) -> Option<String> {
    model
        .joints()
        .iter()
        .zip(q)
        .enumerate()
        .find(|(_, (joint, v))| !(**v >= joint.limits.lower && **v <= joint.limits.upper))
        .map(|(j, (joint, v))| {
            format!(
                "joint {j} = {v} outside [{}, {}]",
                joint.limits.lower, joint.limits.upper
            )
        })
}

/// Angle of `R_a R_b'` (rad), computed here from the trace.
fn rotation_angle_between(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    let r = a * b.transpose();
    // The skew part gives sin, the trace cos: atan2 is accurate at any angle.
    let sin = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    )
    .norm()
        * 0.5;
    let cos = (r.trace() - 1.0) * 0.5;
    sin.atan2(cos)
}

/// A random pose near `pose`: translation moved up to `reach` m, rotated
/// up to `turn` rad.
fn perturbed(pose: &Pose, rng: &mut ChaCha8Rng, reach: f64, turn: f64) -> Pose {
    let dp = Vector3::new(
        rng.gen_range(-reach..=reach),
        rng.gen_range(-reach..=reach),
        rng.gen_range(-reach..=reach),
    );
    let axis = Vector3::new(
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(-1.0..=1.0),
        rng.gen_range(-1.0..=1.0),
    );
    let rotation = armkit::math::Rotation3::new(axis * turn).into_inner();
    Pose::new(rotation * pose.rotation, pose.translation + dp)
}

// ---------------------------------------------------------------- IK

const IK_ROBOTS: [&str; 6] = ["ur5", "panda", "puma560", "stanford", "arm4", "gantry9"];

fn ik_methods() -> [IkMethod; 4] {
    [
        IkMethod::NewtonRaphson,
        IkMethod::DampedLeastSquares(NakamuraDamping::default()),
        IkMethod::LevenbergMarquardt(LmDamping::default()),
        IkMethod::SingularityRobust(ChiaveriniFilter::default()),
    ]
}

/// Numeric IK on reachable targets (FK of a random configuration) and on
/// targets pushed off the reachable set: the returned `q` is always within
/// the limits, and a converged report's errors, recomputed here from FK,
/// are within the tolerances.
fn ik_invariants(scale: usize) {
    let mut tally = Tally::new("IK: limits respected, no false success");
    let mut rng = common::rng(0x1c);
    for name in IK_ROBOTS {
        let model = robot(name);
        let mut data = Data::new(&model);
        let position_only = model.dof() < 6;
        for (m, method) in ik_methods().into_iter().enumerate() {
            let tolerance = [1e-6, 1e-9, 1e-4][m % 3];
            let mut options = IkOptions {
                position_tolerance: tolerance,
                orientation_tolerance: tolerance,
                seed: rng.r#gen(),
                ..IkOptions::default()
            }
            .with_method(method);
            if position_only {
                options.task_weights = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
            }
            let mut solver = IkSolver::new(&model, options).unwrap();
            for k in 0..16 * scale {
                let goal = common::random_configuration(&model, &mut rng);
                let mut target = fk(&model, &mut data, &goal);
                if k % 4 == 3 {
                    // Often unreachable: pushed up to 0.5 m and 1 rad away.
                    target = perturbed(&target, &mut rng, 0.5, 1.0);
                }
                let start = common::random_configuration(&model, &mut rng);
                let report = solver.solve(&target, &start).unwrap();
                tally.cases += 1;
                let case = || format!("{name} {} case {k}", method.short_name());
                if let Some(why) = outside_limits(&model, &report.q) {
                    tally.check(false, || format!("{}: returned q with {why}", case()));
                    continue;
                }
                if report.converged() {
                    let reached = fk(&model, &mut data, &report.q);
                    let position = (target.translation - reached.translation).norm();
                    let orientation = rotation_angle_between(&target.rotation, &reached.rotation);
                    // Slack for recomputing the same numbers in another order.
                    let slack = 1e-12;
                    tally.check(position <= tolerance + slack, || {
                        format!(
                            "{}: converged with position error {position:e} > {tolerance:e}",
                            case()
                        )
                    });
                    tally.check(position_only || orientation <= tolerance + slack, || {
                        format!(
                            "{}: converged with orientation error {orientation:e} > {tolerance:e}",
                            case()
                        )
                    });
                }
            }
        }
    }
    tally.finish();
}

/// Closed-form IK (PUMA 560 and space6r by Pieper, seed 002's arm4): every
/// solution is within the limits, and an `Exact` one reproduces the target
/// (recomputed here) to the documented tolerance.
fn closed_form_invariants(scale: usize) {
    let mut tally = Tally::new("closed-form IK: limits respected, exact means exact");
    let mut rng = common::rng(0xcf);
    for name in ["puma560", "space6r", "arm4"] {
        let model = robot(name);
        let solver = ClosedFormSolver::new(&model).unwrap();
        let mut data = Data::new(&model);
        for k in 0..100 * scale {
            let goal = common::random_configuration(&model, &mut rng);
            let mut target = fk(&model, &mut data, &goal);
            if k % 4 == 3 {
                target = perturbed(&target, &mut rng, 0.3, 0.5);
            }
            let current = common::random_configuration(&model, &mut rng);
            let solutions = solver.solve(&target, &current).unwrap();
            tally.cases += 1;
            if k % 4 != 3 {
                tally.check(!solutions.is_empty(), || {
                    format!("{name} case {k}: no solution for a reachable target")
                });
            }
            for s in &solutions {
                if let Some(why) = outside_limits(&model, &s.q) {
                    tally.check(false, || format!("{name} case {k}: solution with {why}"));
                }
                if s.fit == Fit::Exact {
                    let reached = fk(&model, &mut data, &s.q);
                    let position = (target.translation - reached.translation).norm();
                    let orientation = rotation_angle_between(&target.rotation, &reached.rotation);
                    // arm4 has 4 joints: its exact fit is of the pose it can reach.
                    let tolerance = 1e-9;
                    tally.check(position <= tolerance, || {
                        format!("{name} case {k}: exact solution misses by {position:e} m")
                    });
                    tally.check(name == "arm4" || orientation <= tolerance, || {
                        format!("{name} case {k}: exact solution misses by {orientation:e} rad")
                    });
                }
            }
        }
    }
    tally.finish();
}

// ---------------------------------------------------------------- trajectories

/// A random trajectory of `dof` joints: one of the rest-to-rest profiles, a
/// clamped cubic spline or seed 002's via-point schemes through random knots.
fn random_trajectory(rng: &mut ChaCha8Rng, dof: usize) -> Trajectory {
    let point = |rng: &mut ChaCha8Rng| -> Vec<f64> {
        (0..dof).map(|_| rng.gen_range(-2.0..=2.0)).collect()
    };
    let kind = rng.gen_range(0..6);
    let duration = rng.gen_range(0.2..=5.0);
    if kind < 3 {
        let shape = [
            ProfileShape::Cubic,
            ProfileShape::Quintic,
            ProfileShape::Trapezoidal,
        ][kind];
        let acceleration_time =
            (shape == ProfileShape::Trapezoidal).then(|| rng.gen_range(0.05..=0.5) * duration);
        return rest_to_rest(shape, &point(rng), &point(rng), duration, acceleration_time).unwrap();
    }
    let knots = rng.gen_range(2..=6);
    let mut times = vec![0.0];
    for _ in 1..knots {
        let last = *times.last().unwrap();
        times.push(last + rng.gen_range(0.1..=1.5));
    }
    let points: Vec<Vec<f64>> = (0..knots).map(|_| point(rng)).collect();
    match kind {
        3 => {
            let v0 = point(rng);
            let v1 = point(rng);
            clamped_cubic_spline(&times, &points, &v0, &v1).unwrap()
        }
        4 => interpolate_via_points(
            SegmentScheme::QuarticCubicQuartic(ViaVelocity::BackwardDifference),
            &times,
            &points,
            &BoundaryRates::Rest,
        )
        .unwrap(),
        _ => interpolate_via_points(
            SegmentScheme::CubicQuinticLast,
            &times,
            &points,
            &BoundaryRates::Rest,
        )
        .unwrap(),
    }
}

/// Largest |velocity| / limit and |acceleration| / limit over a dense
/// sampling computed here: 401 points per segment, both ends included (the
/// acceleration of a C1 trajectory jumps at a knot: each side counts).
fn sampled_peak_ratios(traj: &Trajectory, limits: &TrajectoryLimits) -> (f64, f64) {
    let mut state = JointState::zeros(traj.dof());
    let (mut v, mut a) = (0.0f64, 0.0f64);
    for segment in 0..traj.segment_count() {
        for i in 0..=400 {
            let phi = f64::from(i) / 400.0;
            traj.sample_segment_into(segment, phi, &mut state).unwrap();
            for j in 0..traj.dof() {
                v = v.max(state.velocity[j].abs() / limits.velocity[j]);
                a = a.max(state.acceleration[j].abs() / limits.acceleration[j]);
            }
        }
    }
    (v, a)
}

/// `scale_to_limits` (both modes) meets every velocity and acceleration
/// limit; `Tight` meets the tightest one exactly (no needless slowness).
fn trajectory_invariants(scale: usize) {
    let mut tally = Tally::new("trajectories: scaled to limits, never over them");
    let mut rng = common::rng(0x7a);
    for k in 0..150 * scale {
        let dof = rng.gen_range(1..=7);
        let traj = random_trajectory(&mut rng, dof);
        let velocity: Vec<f64> = (0..dof).map(|_| rng.gen_range(0.05..=5.0)).collect();
        let acceleration: Vec<f64> = (0..dof).map(|_| rng.gen_range(0.05..=20.0)).collect();
        let limits = TrajectoryLimits::new(velocity, acceleration).unwrap();
        for mode in [TimeScaling::SlowDownOnly, TimeScaling::Tight] {
            tally.cases += 1;
            let scaled = scale_to_limits(&traj, &limits, mode).unwrap();
            let (v, a) = sampled_peak_ratios(&scaled.trajectory, &limits);
            // Relative slack for the rounding of the scaled coefficients.
            let slack = 1e-9;
            tally.check(v <= 1.0 + slack && a <= 1.0 + slack, || {
                format!("case {k} {mode:?} (dof {dof}): velocity at {v} and acceleration at {a} of the limit")
            });
            let violations = check_limits(&scaled.trajectory, &limits).unwrap();
            tally.check(violations.is_empty(), || {
                format!("case {k} {mode:?}: check_limits reports {violations:?}")
            });
            if mode == TimeScaling::Tight {
                // Dense sampling can miss the exact peak slightly, never by much.
                tally.check(v.max(a) >= 0.99, || {
                    format!("case {k} Tight: peaks only {v} and {a} of the limits")
                });
            }
        }
    }
    tally.finish();
}

// ---------------------------------------------------------------- MPC

/// The MPC planner stepped with the plant `q += T u` from random starts
/// within the limits towards random targets, with random horizons, sample
/// times, weights and velocity limits: every commanded velocity is within
/// its limit and every joint stays within its position limits (exact).
fn mpc_invariants(scale: usize) {
    let mut tally = Tally::new("MPC: velocity and position limits never crossed");
    let mut rng = common::rng(0x3c);
    let robots = [
        armkit::robots::gantry9_flex().unwrap(),
        robot("panda"),
        robot("ur5"),
    ];
    for k in 0..6 * scale {
        let model = &robots[k % robots.len()];
        let dof = model.dof();
        let mut data = Data::new(model);
        let goal = common::random_configuration(model, &mut rng);
        let target = fk(model, &mut data, &goal);
        let horizon = rng.gen_range(1..=12);
        let velocity_limits: Vec<f64> = (0..dof).map(|_| rng.gen_range(0.1..=2.0)).collect();
        let options = MpcOptions {
            horizon,
            control_horizon: rng.gen_range(1..=horizon.min(3)),
            sample_time: rng.gen_range(0.005..=0.05),
            task_weights: if rng.r#gen() {
                TaskWeights::full_pose(10.0, 200.0)
            } else {
                TaskWeights::position_only(rng.gen_range(1.0..=100.0), 200.0)
            },
            increment_weights: Some((0..dof).map(|_| rng.gen_range(0.1..=100.0)).collect()),
            joint_limits: Some(
                model
                    .joints()
                    .iter()
                    .zip(&velocity_limits)
                    .map(|(joint, &v)| armkit::model::JointLimits {
                        velocity: Some(v),
                        ..joint.limits
                    })
                    .collect(),
            ),
            ..MpcOptions::default()
        };
        let t = options.sample_time;
        let mut planner = MpcPlanner::new(model, options).unwrap();
        planner.set_target(&target).unwrap();
        let mut q = common::random_configuration(model, &mut rng);
        tally.cases += 1;
        for step in 0..150 {
            let report = planner.step(&q).unwrap();
            for j in 0..dof {
                let u = report.velocity[j];
                tally.check(u.abs() <= velocity_limits[j], || {
                    format!(
                        "{} case {k} step {step}: joint {j} velocity {u} over {}",
                        model.name(),
                        velocity_limits[j]
                    )
                });
                q[j] += t * u;
            }
            if let Some(why) = outside_limits(model, &q) {
                tally.check(false, || {
                    format!("{} case {k} step {step}: {why}", model.name())
                });
                break;
            }
        }
    }
    tally.finish();
}

// ---------------------------------------------------------------- FK and Jacobian

/// A random DH model: 1 to 8 joints (revolute with limits, continuous,
/// prismatic), link lengths up to 1 m, random base and tool.
fn random_dh_model(rng: &mut ChaCha8Rng, convention: DhConvention) -> Model {
    let n = rng.gen_range(1..=8);
    let links: Vec<DhLink> = (0..n)
        .map(|_| {
            let kind = [
                JointKind::Revolute,
                JointKind::Continuous,
                JointKind::Prismatic,
            ][rng.gen_range(0..3)];
            let (lower, upper) = match kind {
                JointKind::Revolute => (rng.gen_range(-3.0..=-0.1), rng.gen_range(0.1..=3.0)),
                JointKind::Prismatic => (rng.gen_range(-0.5..=0.0), rng.gen_range(0.1..=1.0)),
                JointKind::Continuous => (f64::NEG_INFINITY, f64::INFINITY),
            };
            DhLink {
                kind,
                theta: rng.gen_range(-3.0..=3.0),
                d: rng.gen_range(-1.0..=1.0),
                a: rng.gen_range(-1.0..=1.0),
                alpha: rng.gen_range(-3.0..=3.0),
                offset: rng.gen_range(-1.0..=1.0),
                limits: JointLimits {
                    lower,
                    upper,
                    velocity: None,
                    acceleration: None,
                    effort: None,
                },
                inertia: None,
            }
        })
        .collect();
    let random_pose = |rng: &mut ChaCha8Rng| {
        let turn = rng.gen_range(0.0..=3.0);
        perturbed(&Pose::identity(), rng, 1.0, turn)
    };
    let base = random_pose(rng);
    let tool = random_pose(rng);
    Model::from_dh_with_transforms("random", convention, &links, base, tool).unwrap()
}

/// The DH product written out here, independently of the library:
/// standard `Rz(theta) Tz(d) Tx(a) Rx(alpha)`, modified
/// `Rx(alpha) Tx(a) Rz(theta) Tz(d)`.
fn dh_product(model: &Model, q: &[f64]) -> Matrix4<f64> {
    let (convention, links) = model.dh_table().unwrap();
    let rz = |t: f64| {
        let (s, c) = t.sin_cos();
        Matrix4::new(
            c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        )
    };
    let rx = |t: f64| {
        let (s, c) = t.sin_cos();
        Matrix4::new(
            1.0, 0.0, 0.0, 0.0, 0.0, c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0,
        )
    };
    let translate = |x: f64, z: f64| {
        let mut m = Matrix4::identity();
        m[(0, 3)] = x;
        m[(2, 3)] = z;
        m
    };
    let mut t = model.base().to_matrix4();
    for (link, &qj) in links.iter().zip(q) {
        let (theta, d) = if link.kind.is_rotational() {
            (link.theta + qj + link.offset, link.d)
        } else {
            (link.theta, link.d + qj + link.offset)
        };
        t *= match convention {
            DhConvention::Standard => {
                rz(theta) * translate(0.0, d) * translate(link.a, 0.0) * rx(link.alpha)
            }
            DhConvention::Modified => {
                rx(link.alpha) * translate(link.a, 0.0) * rz(theta) * translate(0.0, d)
            }
        };
    }
    t * model.tool().to_matrix4()
}

/// Every built-in robot, the URDFs of `tests/data` and random DH models
/// (both conventions) at random configurations: the Jacobian matches
/// central differences of FK, and FK of a DH model matches `dh_product`.
fn kinematics_invariants(scale: usize) {
    let mut tally = Tally::new("FK and Jacobian: agree with finite differences");
    let mut rng = common::rng(0xfd);
    let mut models: Vec<Model> = armkit::robots::names().map(robot).collect();
    for (file, tip) in [
        ("iiwa14.urdf", Some("tool0")),
        ("panda.urdf", Some("panda_hand_tcp")),
        ("ur5.urdf", Some("tool0")),
        ("skewbot.urdf", Some("tool")),
    ] {
        let path = common::data_path(&format!("urdf/{file}"));
        let selection = armkit::urdf::ChainSelection {
            base: None,
            tip: tip.map(str::to_string),
        };
        models.push(armkit::urdf::load(path, &selection).unwrap());
    }
    let fixed_models = models.len();
    for k in 0..20 * scale {
        let convention = if k % 2 == 0 {
            DhConvention::Standard
        } else {
            DhConvention::Modified
        };
        models.push(random_dh_model(&mut rng, convention));
    }
    for (m, model) in models.iter().enumerate() {
        let mut data = Data::new(model);
        let count = if m < fixed_models { 5 * scale } else { 3 };
        for _ in 0..count {
            let q = common::random_configuration(model, &mut rng);
            tally.cases += 1;
            let j = jacobian(model, &mut data, &q, JacobianFrame::World)
                .unwrap()
                .clone();
            let fd = common::finite_difference_jacobian(model, &q, 1e-6);
            let size = j.abs().max().max(1.0);
            let gap = (&j - &fd).abs().max();
            tally.check(gap <= 1e-7 * size, || {
                format!(
                    "{} at {q:?}: |J - J_fd| = {gap:e} (|J| = {size})",
                    model.name()
                )
            });
            if model.dh_table().is_some() && model.coupling().is_none() {
                let pose = fk(model, &mut data, &q).to_matrix4();
                let expected = dh_product(model, &q);
                let gap = (pose - expected).abs().max();
                tally.check(gap <= 1e-12 * expected.abs().max().max(1.0), || {
                    format!(
                        "{} at {q:?}: FK differs from the DH product by {gap:e}",
                        model.name()
                    )
                });
            }
        }
    }
    tally.finish();
}

// ---------------------------------------------------------------- the suites

#[test]
fn ik_never_leaves_the_limits_nor_claims_false_success() {
    ik_invariants(1);
}

#[test]
fn closed_form_ik_respects_limits_and_exactness() {
    closed_form_invariants(1);
}

#[test]
fn trajectories_scaled_to_limits_stay_within_them() {
    trajectory_invariants(1);
}

#[test]
fn mpc_never_crosses_a_limit() {
    mpc_invariants(1);
}

#[test]
fn jacobian_matches_finite_differences_and_fk_the_dh_product() {
    kinematics_invariants(1);
}

#[test]
#[ignore = "long suite: scale 100 (ARMKIT_SCALE), minutes in release"]
fn long_ik_invariants() {
    ik_invariants(long_scale());
}

#[test]
#[ignore = "long suite: scale 100 (ARMKIT_SCALE), minutes in release"]
fn long_closed_form_invariants() {
    closed_form_invariants(long_scale());
}

#[test]
#[ignore = "long suite: scale 100 (ARMKIT_SCALE), minutes in release"]
fn long_trajectory_invariants() {
    trajectory_invariants(long_scale());
}

#[test]
#[ignore = "long suite: scale 100 (ARMKIT_SCALE), minutes in release"]
fn long_mpc_invariants() {
    mpc_invariants(long_scale());
}

#[test]
#[ignore = "long suite: scale 100 (ARMKIT_SCALE), minutes in release"]
fn long_kinematics_invariants() {
    kinematics_invariants(long_scale());
}
