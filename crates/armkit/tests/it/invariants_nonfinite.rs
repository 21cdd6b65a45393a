//! NaN, +inf and -inf at every public entry point that takes numbers: each
//! must return an `Err` whose message names the argument, never panic, and
//! never hand back NaN.
//!
//! Every case runs under `catch_unwind`, so one run lists every entry point
//! that misbehaves (a panic, an `Ok`, or an error that does not name the
//! argument) instead of stopping at the first. The few entry points that
//! return a plain number (no `Result`) are checked to give a non-finite
//! answer for a non-finite input, never a finite one that looks valid
//! (`plain_number_functions_propagate_non_finite_input`).

use std::fmt::Debug;
use std::panic::{catch_unwind, AssertUnwindSafe};

use armkit::beam::{
    rectangular_second_moment, square_second_moment, weight, CarriageDeflection, PointLoad,
    SimplySupportedBeam, TwoCarriageBeam,
};
use armkit::ik::closed_form::ClosedFormSolver;
use armkit::ik::{
    damped_least_squares_step, damped_pseudo_inverse, IkOptions, IkSolver, LmDamping,
};
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::math::{Matrix3, Matrix6xX, Pose, Vector3, Vector6};
use armkit::mpc::scenario::{simulate, SimulationOptions};
use armkit::mpc::{MpcOptions, MpcPlanner, TaskWeights, VelocityWeights};
use armkit::redundancy::{
    best_partition, Damping, JointWeights, Partition, PartitionedSolver, SolverOptions,
    WeightedLeastNorm,
};
use armkit::redundancy::{energy_measure, gravity_torques, joint_torques, Load, TorqueFloor};
use armkit::redundancy::{joint_limit_cost, joint_limit_gradient};
use armkit::redundancy::{Distribution, DistributionOptions, ResolvedRateTracker};
use armkit::robots::space6r_free_floating;
use armkit::space::{
    center_of_mass, end_effector_pose, generalized_jacobian, momentum, step, track_pose_path,
    BaseMode, FreeFloatingModel, FreeFloatingState, SinusoidalJointMotion, SpaceData,
};
use armkit::tracking::{Feedback, LeastSquares, TrackingOptions};
use armkit::trajectory::clamped_cubic_spline;
use armkit::trajectory::TimeFn;
use armkit::trajectory::{check_limits, scale_to_limits, TimeScaling, TrajectoryLimits};
use armkit::trajectory::{cubic, minimum_time, quintic, rest_to_rest, trapezoidal, ProfileShape};
use armkit::trajectory::{
    interpolate_via_points, plan_continuous_path, BoundaryRates, ContinuousPathOptions,
    SegmentScheme,
};
use armkit::trajectory::{ArcOrientation, ArcPath, CartesianTrajectory, LinePath, TimeLaw};
use armkit::trajectory::{IkTask, NumericPathIk};
use armkit::trajectory::{JointState, Trajectory};
use armkit::Model;

/// The non-finite values every case is tried with.
const BAD: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// Runs cases and collects what went wrong.
#[derive(Default)]
struct Cases {
    run: usize,
    failures: Vec<String>,
}

impl Cases {
    /// `f` must return an `Err` whose message contains `names` (the
    /// argument); a panic or an `Ok` is a failure.
    fn rejects<T: Debug>(
        &mut self,
        case: &str,
        names: &str,
        f: impl FnOnce() -> armkit::Result<T>,
    ) {
        self.run += 1;
        match catch_unwind(AssertUnwindSafe(f)) {
            Err(_) => self.failures.push(format!("{case}: panicked")),
            Ok(Ok(value)) => {
                let shown = format!("{value:?}");
                let shown: String = shown.chars().take(160).collect();
                self.failures
                    .push(format!("{case}: accepted, returned {shown}"));
            }
            Ok(Err(error)) => {
                let message = error.to_string();
                if !message.contains(names) {
                    self.failures.push(format!(
                        "{case}: the error does not name `{names}`: {message}"
                    ));
                }
            }
        }
    }

    /// Every value of [`BAD`] in turn.
    fn rejects_each<T: Debug>(
        &mut self,
        case: &str,
        names: &str,
        mut f: impl FnMut(f64) -> armkit::Result<T>,
    ) {
        for bad in BAD {
            self.rejects(&format!("{case} [{bad}]"), names, || f(bad));
        }
    }

    fn finish(self, group: &str) {
        println!(
            "{group}: {} non-finite cases, {} failures",
            self.run,
            self.failures.len()
        );
        assert!(
            self.failures.is_empty(),
            "{group}: {} of {} cases misbehaved:\n  {}",
            self.failures.len(),
            self.run,
            self.failures.join("\n  ")
        );
    }
}

/// `values` with entry `index` replaced by `bad`.
fn with(values: &[f64], index: usize, bad: f64) -> Vec<f64> {
    let mut v = values.to_vec();
    v[index] = bad;
    v
}

/// A pose with translation entry `index` (0..3) or rotation entry
/// `index - 3` (3..12, row-major) replaced by `bad`.
fn bad_pose(pose: &Pose, index: usize, bad: f64) -> Pose {
    let mut p = *pose;
    if index < 3 {
        p.translation[index] = bad;
    } else {
        p.rotation[((index - 3) / 3, (index - 3) % 3)] = bad;
    }
    p
}

fn robot(name: &str) -> Model {
    armkit::robots::by_name(name).unwrap()
}

fn fk(model: &Model, q: &[f64]) -> Pose {
    *forward_kinematics(model, &mut Data::new(model), q).unwrap()
}

fn jacobian_at(model: &Model, q: &[f64]) -> Matrix6xX<f64> {
    jacobian(model, &mut Data::new(model), q, JacobianFrame::World)
        .unwrap()
        .clone()
}

#[test]
fn kinematics_and_ik_reject_non_finite_numbers() {
    let mut cases = Cases::default();
    let ur5 = robot("ur5");
    let q = [0.1, -0.8, 1.0, -0.5, 0.7, 0.2];
    let target = fk(&ur5, &[0.3, -1.0, 1.2, -0.4, 0.5, 0.1]);
    let mut data = Data::new(&ur5);
    cases.rejects_each("forward_kinematics q[2]", "joint_positions", |b| {
        forward_kinematics(&ur5, &mut data, &with(&q, 2, b)).copied()
    });
    cases.rejects_each("jacobian q[5]", "joint_positions", |b| {
        jacobian(&ur5, &mut data, &with(&q, 5, b), JacobianFrame::World).cloned()
    });
    cases.rejects_each("Model::check_limits q[0]", "joint_positions", |b| {
        ur5.check_limits(&with(&q, 0, b))
    });
    for (field, names) in [(0, "position_tolerance"), (1, "orientation_tolerance")] {
        cases.rejects_each(&format!("IkSolver::new {names}"), names, |b| {
            let mut options = IkOptions::default();
            if field == 0 {
                options.position_tolerance = b;
            } else {
                options.orientation_tolerance = b;
            }
            IkSolver::new(&ur5, options).map(|_| ())
        });
    }
    cases.rejects_each("IkSolver::new task_weights[3]", "task_weights", |b| {
        let mut options = IkOptions::default();
        options.task_weights[3] = b;
        IkSolver::new(&ur5, options).map(|_| ())
    });
    cases.rejects_each("IkSolver::new LM damping floor", "floor", |b| {
        let options =
            IkOptions::default().with_method(armkit::ik::IkMethod::LevenbergMarquardt(LmDamping {
                floor: b,
            }));
        IkSolver::new(&ur5, options).map(|_| ())
    });
    let mut solver = IkSolver::new(&ur5, IkOptions::default()).unwrap();
    for index in [0, 2, 3, 7, 11] {
        cases.rejects_each(
            &format!("IkSolver::solve target entry {index}"),
            "target",
            |b| solver.solve(&bad_pose(&target, index, b), &q),
        );
    }
    cases.rejects_each("IkSolver::solve start[4]", "joint_positions", |b| {
        solver.solve(&target, &with(&q, 4, b))
    });
    let puma = robot("puma560");
    let closed = ClosedFormSolver::new(&puma).unwrap();
    let puma_target = fk(&puma, &[0.2, 0.3, -0.4, 0.5, 0.6, 0.7]);
    cases.rejects_each("ClosedFormSolver::solve target entry 1", "target", |b| {
        closed.solve(&bad_pose(&puma_target, 1, b), &[0.0; 6])
    });
    cases.rejects_each("ClosedFormSolver::solve target entry 5", "target", |b| {
        closed.solve(&bad_pose(&puma_target, 5, b), &[0.0; 6])
    });
    cases.rejects_each("ClosedFormSolver::solve current[1]", "current", |b| {
        closed.solve(&puma_target, &with(&[0.0; 6], 1, b))
    });
    let j = jacobian_at(&ur5, &q);
    let twist = Vector6::new(0.1, 0.0, -0.1, 0.0, 0.2, 0.0);
    let mut out = [0.0; 6];
    cases.rejects_each("damped_least_squares_step jacobian", "jacobian", |b| {
        let mut bad = j.clone();
        bad[(2, 3)] = b;
        damped_least_squares_step(&bad, &twist, 0.01, &mut out)
    });
    cases.rejects_each("damped_least_squares_step twist", "twist", |b| {
        let mut bad = twist;
        bad[4] = b;
        damped_least_squares_step(&j, &bad, 0.01, &mut out)
    });
    cases.rejects_each("damped_least_squares_step damping", "damping", |b| {
        damped_least_squares_step(&j, &twist, b, &mut out)
    });
    cases.rejects_each("damped_pseudo_inverse damping", "damping", |b| {
        damped_pseudo_inverse(&j, b)
    });
    cases.finish("kinematics and IK");
}

#[test]
fn redundancy_rejects_non_finite_numbers() {
    let mut cases = Cases::default();
    let gantry = robot("gantry9");
    let q = gantry.neutral_configuration();
    let j = jacobian_at(&gantry, &q);
    let twist = Vector6::new(0.1, 0.05, -0.02, 0.0, 0.1, 0.0);
    let weights = JointWeights::uniform(9);
    let ones = [1.0; 9];
    cases.rejects_each("JointWeights::new values[4]", "weights", |b| {
        JointWeights::new(&with(&ones, 4, b))
    });
    cases.rejects_each("JointWeights::from_priority_levels ratio", "ratio", |b| {
        JointWeights::from_priority_levels(&[1, 1, 1, 0, 0, 0, 0, 0, 0], b)
    });
    cases.rejects_each("JointWeights::set", "weight", |b| {
        JointWeights::uniform(9).set(2, b)
    });
    cases.rejects_each("JointWeights::cost q_dot[1]", "joint_velocities", |b| {
        weights.cost(&with(&ones, 1, b))
    });
    cases.rejects_each("WeightedLeastNorm::new constant damping", "damping", |b| {
        WeightedLeastNorm::new(
            9,
            SolverOptions {
                damping: Damping::Constant(b),
                ..SolverOptions::default()
            },
        )
        .map(|_| ())
    });
    cases.rejects_each(
        "WeightedLeastNorm::new singular_threshold",
        "singular_threshold",
        |b| {
            WeightedLeastNorm::new(
                9,
                SolverOptions {
                    singular_threshold: b,
                    ..SolverOptions::default()
                },
            )
            .map(|_| ())
        },
    );
    let mut wln = WeightedLeastNorm::new(9, SolverOptions::default()).unwrap();
    cases.rejects_each("WeightedLeastNorm::solve jacobian", "jacobian", |b| {
        let mut bad = j.clone();
        bad[(1, 7)] = b;
        wln.solve(&bad, &weights, &twist)
            .map(|o| o.map(<[f64]>::to_vec))
    });
    cases.rejects_each("WeightedLeastNorm::solve twist", "twist", |b| {
        let mut bad = twist;
        bad[0] = b;
        wln.solve(&j, &weights, &bad)
            .map(|o| o.map(<[f64]>::to_vec))
    });
    cases.rejects_each(
        "WeightedLeastNorm::solve_toward preferred",
        "preferred",
        |b| {
            wln.solve_toward(&j, &weights, &twist, &with(&ones, 8, b))
                .map(|o| o.map(<[f64]>::to_vec))
        },
    );
    cases.rejects_each(
        "WeightedLeastNorm::null_space_projector jacobian",
        "jacobian",
        |b| {
            let mut bad = j.clone();
            bad[(5, 0)] = b;
            wln.null_space_projector(&bad, &weights)
                .map(|o| o.map(Clone::clone))
        },
    );
    cases.rejects_each(
        "PartitionedSolver::new max_condition_number",
        "condition",
        |b| PartitionedSolver::new(9, b).map(|_| ()),
    );
    let partition = Partition::new(9, [3, 4, 5, 6, 7, 8]).unwrap();
    let mut partitioned = PartitionedSolver::new(9, 1e10).unwrap();
    cases.rejects_each("PartitionedSolver::solve twist", "twist", |b| {
        let mut bad = twist;
        bad[3] = b;
        partitioned
            .solve(&j, &weights, &bad, &partition)
            .map(<[f64]>::to_vec)
    });
    cases.rejects_each("PartitionedSolver::solve jacobian", "jacobian", |b| {
        let mut bad = j.clone();
        bad[(0, 0)] = b;
        partitioned
            .solve(&bad, &weights, &twist, &partition)
            .map(<[f64]>::to_vec)
    });
    cases.rejects_each(
        "PartitionedSolver::solve_energy_optimal torques",
        "torques",
        |b| {
            partitioned
                .solve_energy_optimal(&j, &with(&ones, 0, b), &twist, &partition)
                .map(<[f64]>::to_vec)
        },
    );
    cases.rejects_each("best_partition jacobian", "jacobian", |b| {
        let mut bad = j.clone();
        bad[(3, 4)] = b;
        best_partition(&bad, None, 1e10)
    });
    cases.rejects_each("best_partition max_condition_number", "condition", |b| {
        best_partition(&j, None, b)
    });
    cases.rejects_each("energy_measure q_dot", "joint_velocities", |b| {
        energy_measure(&with(&ones, 3, b), &ones)
    });
    cases.rejects_each("energy_measure torques", "torques", |b| {
        energy_measure(&ones, &with(&ones, 3, b))
    });
    let mut data = Data::new(&gantry);
    let mut torques = [0.0; 9];
    let load = Load::payload(10.0).with_seed001_gravity();
    cases.rejects_each("joint_torques q", "joint_positions", |b| {
        joint_torques(&gantry, &mut data, &with(&q, 6, b), &load, &mut torques)
    });
    cases.rejects_each("joint_torques Load::payload", "load.wrench", |b| {
        joint_torques(&gantry, &mut data, &q, &Load::payload(b), &mut torques)
    });
    cases.rejects_each("joint_torques Load::wrench", "wrench", |b| {
        let mut w = Vector6::zeros();
        w[2] = b;
        joint_torques(&gantry, &mut data, &q, &Load::wrench(w), &mut torques)
    });
    cases.rejects_each("gravity_torques gravity", "gravity", |b| {
        gravity_torques(
            &gantry,
            &mut data,
            &q,
            &Vector3::new(0.0, 0.0, b),
            &mut torques,
        )
    });
    cases.rejects_each("TorqueFloor::Relative", "floor", |b| {
        JointWeights::from_torques(&ones, TorqueFloor::Relative(b))
    });
    cases.rejects_each("EnergyWeights::from_torques torques", "torques", |b| {
        JointWeights::from_torques(&with(&ones, 2, b), TorqueFloor::default())
    });
    cases.rejects_each("joint_limit_cost q", "joint_positions", |b| {
        joint_limit_cost(&gantry, &with(&q, 1, b))
    });
    cases.rejects_each("joint_limit_gradient q", "joint_positions", |b| {
        let mut g = [0.0; 9];
        joint_limit_gradient(&gantry, &with(&q, 1, b), &mut g)
    });
    let start = fk(&gantry, &q);
    let mut goal = start;
    goal.translation.x += 0.1;
    cases.rejects_each("CartesianTrajectory::line goal", "goal", |b| {
        CartesianTrajectory::line(start, bad_pose(&goal, 1, b), TimeLaw::Quintic, 1.0)
    });
    cases.rejects_each("CartesianTrajectory::line duration", "duration", |b| {
        CartesianTrajectory::line(start, goal, TimeLaw::Quintic, b)
    });
    for (name, set) in [("dt", 0usize), ("feedback_gain", 1)] {
        cases.rejects_each(&format!("ResolvedRateTracker::new {name}"), name, |b| {
            let mut options = DistributionOptions::default();
            if set == 0 {
                options.tracking.dt = b;
            } else {
                options.tracking.feedback = Feedback::Proportional { gain: b };
            }
            ResolvedRateTracker::new(&gantry, Distribution::Weights(weights.clone()), options)
                .map(|_| ())
        });
    }
    let mut tracker = ResolvedRateTracker::new(
        &gantry,
        Distribution::Weights(weights.clone()),
        DistributionOptions::default(),
    )
    .unwrap();
    let line = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, 0.05).unwrap();
    cases.rejects_each("ResolvedRateTracker::run q0", "joint_positions", |b| {
        tracker
            .run(&gantry, &with(&q, 0, b), &line)
            .map(|r| r.status)
    });
    cases.finish("redundancy");
}

fn sample_trajectory() -> Trajectory {
    cubic(
        &JointState::at_rest(&[0.0, 0.5, -0.2]),
        &JointState::at_rest(&[1.0, -0.5, 0.3]),
        2.0,
    )
    .unwrap()
}

#[test]
fn trajectories_reject_non_finite_numbers() {
    let mut cases = Cases::default();
    let a = [0.0, 0.5, -0.2];
    let b_ = [1.0, -0.5, 0.3];
    let rest_a = JointState::at_rest(&a);
    let rest_b = JointState::at_rest(&b_);
    for (field, names) in [(0, "position"), (1, "velocity"), (2, "acceleration")] {
        let bad_state = |b: f64| {
            let mut s = rest_a.clone();
            match field {
                0 => s.position[1] = b,
                1 => s.velocity[1] = b,
                _ => s.acceleration[1] = b,
            }
            s
        };
        cases.rejects_each(&format!("cubic start {names}"), names, |b| {
            cubic(&bad_state(b), &rest_b, 1.0)
        });
        cases.rejects_each(&format!("quintic end {names}"), names, |b| {
            quintic(&rest_b, &bad_state(b), 1.0)
        });
    }
    cases.rejects_each("cubic duration", "duration", |b| cubic(&rest_a, &rest_b, b));
    cases.rejects_each("quintic duration", "duration", |b| {
        quintic(&rest_a, &rest_b, b)
    });
    cases.rejects_each("trapezoidal q0", "q0", |b| {
        trapezoidal(&with(&a, 0, b), &b_, 2.0, 0.5)
    });
    cases.rejects_each("trapezoidal qf", "qf", |b| {
        trapezoidal(&a, &with(&b_, 2, b), 2.0, 0.5)
    });
    cases.rejects_each("trapezoidal duration", "duration", |b| {
        trapezoidal(&a, &b_, b, 0.5)
    });
    cases.rejects_each("trapezoidal acceleration_time", "acceleration_time", |b| {
        trapezoidal(&a, &b_, 2.0, b)
    });
    for shape in [
        ProfileShape::Cubic,
        ProfileShape::Quintic,
        ProfileShape::Trapezoidal,
    ] {
        cases.rejects_each(
            &format!("rest_to_rest {shape:?} duration"),
            "duration",
            |b| {
                let acceleration_time = (shape == ProfileShape::Trapezoidal).then_some(0.5);
                rest_to_rest(shape, &a, &b_, b, acceleration_time)
            },
        );
        cases.rejects_each(&format!("rest_to_rest {shape:?} q0"), "q0", |b| {
            rest_to_rest(shape, &with(&a, 1, b), &b_, 2.0, None)
        });
        let limits = TrajectoryLimits::new(vec![1.0; 3], vec![2.0; 3]).unwrap();
        cases.rejects_each(&format!("minimum_time {shape:?} qf"), "qf", |b| {
            minimum_time(shape, &a, &with(&b_, 0, b), &limits)
        });
    }
    cases.rejects_each(
        "rest_to_rest Trapezoidal acceleration_time",
        "acceleration_time",
        |b| rest_to_rest(ProfileShape::Trapezoidal, &a, &b_, 2.0, Some(b)),
    );
    // +inf is "no limit" for velocity and acceleration: only NaN and -inf are bad.
    for bad in [f64::NAN, f64::NEG_INFINITY] {
        cases.rejects(
            &format!("TrajectoryLimits::new velocity [{bad}]"),
            "velocity",
            || TrajectoryLimits::new(vec![1.0, bad, 1.0], vec![2.0; 3]),
        );
        cases.rejects(
            &format!("TrajectoryLimits::new acceleration [{bad}]"),
            "acceleration",
            || TrajectoryLimits::new(vec![1.0; 3], vec![2.0, 2.0, bad]),
        );
    }
    cases.rejects_each("Trajectory::stationary position", "position", |b| {
        Trajectory::stationary(&with(&a, 0, b), 0.0, 1.0)
    });
    cases.rejects_each("Trajectory::stationary start_time", "start_time", |b| {
        Trajectory::stationary(&a, b, 1.0)
    });
    cases.rejects_each("Trajectory::stationary duration", "duration", |b| {
        Trajectory::stationary(&a, 0.0, b)
    });
    cases.rejects_each("Trajectory::from_polynomials knots", "knots", |b| {
        Trajectory::from_polynomials(vec![0.0, b], 1, vec![[0.0; 6]])
    });
    cases.rejects_each(
        "Trajectory::from_polynomials coefficients",
        "coefficients",
        |b| Trajectory::from_polynomials(vec![0.0, 1.0], 1, vec![[0.0, 1.0, b, 0.0, 0.0, 0.0]]),
    );
    let traj = sample_trajectory();
    cases.rejects_each("Trajectory::sample t", "t", |b| traj.sample(b));
    cases.rejects_each("Trajectory::sample_into t", "t", |b| {
        let mut out = JointState::zeros(3);
        traj.sample_into(b, &mut out)
    });
    cases.rejects_each("Trajectory::sample_segment_into phi", "phi", |b| {
        let mut out = JointState::zeros(3);
        traj.sample_segment_into(0, b, &mut out)
    });
    cases.rejects_each("Trajectory::time_scaled factor", "factor", |b| {
        traj.time_scaled(b)
    });
    cases.rejects_each("Trajectory::shifted_to start_time", "start_time", |b| {
        traj.shifted_to(b)
    });
    for bad in [f64::NAN, f64::NEG_INFINITY] {
        let mut limits = TrajectoryLimits::new(vec![1.0; 3], vec![2.0; 3]).unwrap();
        limits.velocity[1] = bad;
        cases.rejects(
            &format!("scale_to_limits velocity [{bad}]"),
            "velocity",
            || scale_to_limits(&traj, &limits, TimeScaling::Tight),
        );
        cases.rejects(
            &format!("check_limits velocity [{bad}]"),
            "velocity",
            || check_limits(&traj, &limits),
        );
    }
    let mut limits = TrajectoryLimits::new(vec![1.0; 3], vec![2.0; 3]).unwrap();
    limits.lower[0] = f64::NAN;
    cases.rejects("scale_to_limits lower [NaN]", "lower", || {
        scale_to_limits(&traj, &limits, TimeScaling::SlowDownOnly)
    });
    let times = [0.0, 1.0, 2.0];
    let points = vec![a.to_vec(), b_.to_vec(), a.to_vec()];
    cases.rejects_each("clamped_cubic_spline times", "times", |b| {
        clamped_cubic_spline(&with(&times, 1, b), &points, &[0.0; 3], &[0.0; 3])
    });
    cases.rejects_each("clamped_cubic_spline positions", "positions", |b| {
        let mut p = points.clone();
        p[1][2] = b;
        clamped_cubic_spline(&times, &p, &[0.0; 3], &[0.0; 3])
    });
    cases.rejects_each(
        "clamped_cubic_spline start_velocity",
        "start_velocity",
        |b| clamped_cubic_spline(&times, &points, &with(&[0.0; 3], 0, b), &[0.0; 3]),
    );
    for scheme in [
        SegmentScheme::CubicQuinticLast,
        ContinuousPathOptions::default().scheme,
    ] {
        cases.rejects_each(
            &format!("interpolate_via_points {scheme:?} times"),
            "times",
            |b| interpolate_via_points(scheme, &with(&times, 2, b), &points, &BoundaryRates::Rest),
        );
        cases.rejects_each(
            &format!("interpolate_via_points {scheme:?} positions"),
            "positions",
            |b| {
                let mut p = points.clone();
                p[0][0] = b;
                interpolate_via_points(scheme, &times, &p, &BoundaryRates::Rest)
            },
        );
        cases.rejects_each(
            &format!("interpolate_via_points {scheme:?} given end velocity"),
            "velocity",
            |b| {
                let mut end = JointState::at_rest(&a);
                end.velocity[2] = b;
                let boundary = BoundaryRates::Given {
                    start: JointState::at_rest(&a),
                    end,
                };
                interpolate_via_points(scheme, &times, &points, &boundary)
            },
        );
    }
    cases.finish("joint-space trajectories");
}

#[test]
fn cartesian_paths_reject_non_finite_numbers() {
    let mut cases = Cases::default();
    let ur5 = robot("ur5");
    let q = [0.1, -0.8, 1.0, -0.5, 0.7, 0.2];
    let start = fk(&ur5, &q);
    let mut end = start;
    end.translation.z += 0.05;
    for index in [0, 2, 4, 10] {
        cases.rejects_each(
            &format!("cartesian LinePath::new end entry {index}"),
            "end",
            |b| LinePath::new(start, bad_pose(&end, index, b)),
        );
        cases.rejects_each(
            &format!("cartesian LinePath::new start entry {index}"),
            "start",
            |b| LinePath::new(bad_pose(&start, index, b), end),
        );
    }
    let centre = start.translation + Vector3::new(0.05, 0.0, 0.0);
    let axis = Vector3::new(0.0, 0.0, 1.0);
    cases.rejects_each("ArcPath::new centre", "centre", |b| {
        ArcPath::new(
            start,
            centre + Vector3::new(0.0, b, 0.0),
            axis,
            1.0,
            ArcOrientation::Constant,
        )
    });
    cases.rejects_each("ArcPath::new axis", "axis", |b| {
        ArcPath::new(
            start,
            centre,
            Vector3::new(b, 0.0, 1.0),
            1.0,
            ArcOrientation::Constant,
        )
    });
    cases.rejects_each("ArcPath::new angle", "angle", |b| {
        ArcPath::new(start, centre, axis, b, ArcOrientation::FollowArc)
    });
    cases.rejects_each("ArcPath::through via", "via", |b| {
        ArcPath::through(
            start,
            start.translation + Vector3::new(0.05, 0.05, b),
            start.translation + Vector3::new(0.1, 0.0, 0.0),
            ArcOrientation::Constant,
        )
    });
    cases.rejects_each("TimeLaw::Linear.timing duration", "duration", |b| {
        TimeLaw::Linear.timing(b)
    });
    cases.rejects_each(
        "TimeLaw::Trapezoidal acceleration_time",
        "acceleration_time",
        |b| {
            TimeLaw::Trapezoidal {
                acceleration_time: b,
            }
            .timing(1.0)
        },
    );
    let path = CartesianTrajectory::new(
        LinePath::new(start, end).unwrap(),
        TimeLaw::Quintic.timing(0.5).unwrap(),
    )
    .unwrap();
    cases.rejects_each("CartesianTrajectory::sample t", "t", |b| path.sample(b));
    let mut ik = NumericPathIk::for_path(&ur5, IkTask::Pose).unwrap();
    cases.rejects_each("plan_continuous_path start", "joint_positions", |b| {
        plan_continuous_path(
            &ur5,
            &path,
            &mut ik,
            &with(&q, 3, b),
            &ContinuousPathOptions::default(),
        )
        .map(|r| r.status)
    });
    cases.finish("Cartesian paths");
}

#[test]
fn beam_rejects_non_finite_numbers() {
    let mut cases = Cases::default();
    cases.rejects_each("rectangular_second_moment width", "width", |b| {
        rectangular_second_moment(b, 0.2)
    });
    cases.rejects_each("rectangular_second_moment height", "height", |b| {
        rectangular_second_moment(0.2, b)
    });
    cases.rejects_each("square_second_moment side", "side", square_second_moment);
    cases.rejects_each("weight mass", "mass", |b| weight(b, 9.81));
    cases.rejects_each("weight gravity", "gravity", |b| weight(400.0, b));
    // A load's position is "checked when used" (`PointLoad::new` is plain
    // data): the `deflection load position` case below covers it.
    cases.rejects_each("PointLoad::from_mass mass", "mass", |b| {
        PointLoad::from_mass(3.3, b, 9.81)
    });
    cases.rejects_each("SimplySupportedBeam::new length", "length", |b| {
        SimplySupportedBeam::new(b, 200e9, 1e-4)
    });
    cases.rejects_each(
        "SimplySupportedBeam::new youngs_modulus",
        "youngs_modulus",
        |b| SimplySupportedBeam::new(10.0, b, 1e-4),
    );
    cases.rejects_each(
        "SimplySupportedBeam::new second_moment",
        "second_moment",
        |b| SimplySupportedBeam::new(10.0, 200e9, b),
    );
    cases.rejects_each(
        "SimplySupportedBeam::with_rectangular_section width",
        "width",
        |b| SimplySupportedBeam::with_rectangular_section(10.0, 200e9, b, 0.2),
    );
    let beam = SimplySupportedBeam::seed000();
    let load = PointLoad::new(3.3, 4000.0);
    cases.rejects_each("deflection x", "x", |b| beam.deflection(b, &[load]));
    cases.rejects_each("deflection load position", "position", |b| {
        beam.deflection(5.0, &[PointLoad::new(b, 4000.0)])
    });
    cases.rejects_each("deflection load force", "force", |b| {
        beam.deflection(5.0, &[load, PointLoad::new(6.0, b)])
    });
    cases.rejects_each("slope x", "x", |b| beam.slope(b, &[load]));
    cases.rejects_each("deflection_due_to x", "x", |b| {
        beam.deflection_due_to(b, load)
    });
    cases.rejects_each(
        "deflection_derivative_wrt_load_position force",
        "force",
        |b| beam.deflection_derivative_wrt_load_position(2.0, PointLoad::new(3.0, b)),
    );
    cases.rejects_each("deflection_under_load position", "position", |b| {
        beam.deflection_under_load(b, 4000.0)
    });
    cases.rejects_each("deflection_under_load force", "force", |b| {
        beam.deflection_under_load(5.0, b)
    });
    cases.rejects_each("CarriageDeflection::new force", "force", |b| {
        CarriageDeflection::new(beam, b)
    });
    cases.rejects_each("CarriageDeflection::from_mass mass", "mass", |b| {
        CarriageDeflection::from_mass(beam, b, 9.81)
    });
    cases.rejects_each("TwoCarriageBeam::new forces", "force", |b| {
        TwoCarriageBeam::new(beam, [4000.0, b])
    });
    let two = TwoCarriageBeam::seed000();
    cases.rejects_each("TwoCarriageBeam::deflections positions", "position", |b| {
        two.deflections([3.3, b])
    });
    cases.rejects_each(
        "TwoCarriageBeam::deflection_jacobian positions",
        "position",
        |b| two.deflection_jacobian([b, 6.7]),
    );
    cases.finish("beam");
}

fn space_model() -> FreeFloatingModel {
    space6r_free_floating().unwrap()
}

#[test]
fn space_robot_rejects_non_finite_numbers() {
    let mut cases = Cases::default();
    let model = space_model();
    let mut data = SpaceData::new(&model);
    let q = [0.1, -0.5, 0.8, 0.2, 0.6, -0.3];
    let base = Pose::identity();
    let base_body = armkit::robots::space6r_base_body();
    cases.rejects_each("FreeFloatingModel::new base mass", "mass", |b| {
        let mut body = base_body.clone();
        body.mass = b;
        FreeFloatingModel::new(body, model.arm().clone()).map(|_| ())
    });
    cases.rejects_each("FreeFloatingModel::new base com", "com", |b| {
        let mut body = base_body.clone();
        body.com.y = b;
        FreeFloatingModel::new(body, model.arm().clone()).map(|_| ())
    });
    cases.rejects_each("FreeFloatingModel::new base inertia", "inertia", |b| {
        let mut body = base_body.clone();
        body.inertia = Matrix3::identity() * b;
        FreeFloatingModel::new(body, model.arm().clone()).map(|_| ())
    });
    cases.rejects_each("FreeFloatingModel::new base mount", "mount", |b| {
        let mut body = base_body.clone();
        body.mount = bad_pose(&body.mount, 1, b);
        FreeFloatingModel::new(body, model.arm().clone()).map(|_| ())
    });
    cases.rejects_each("center_of_mass base", "base", |b| {
        center_of_mass(&model, &mut data, &bad_pose(&base, 4, b), &q)
    });
    cases.rejects_each("center_of_mass q", "joint_positions", |b| {
        center_of_mass(&model, &mut data, &base, &with(&q, 3, b))
    });
    cases.rejects_each("end_effector_pose q", "joint_positions", |b| {
        end_effector_pose(&model, &mut data, &base, &with(&q, 5, b))
    });
    for mode in [BaseMode::AttitudeHeld, BaseMode::FreeFloating] {
        cases.rejects_each(
            &format!("generalized_jacobian {mode:?} q"),
            "joint_positions",
            |b| generalized_jacobian(&model, &mut data, &base, &with(&q, 0, b), mode).cloned(),
        );
        cases.rejects_each(
            &format!("generalized_jacobian {mode:?} base"),
            "base",
            |b| generalized_jacobian(&model, &mut data, &bad_pose(&base, 0, b), &q, mode).cloned(),
        );
    }
    cases.rejects_each("momentum base_twist", "base_twist", |b| {
        let mut twist = Vector6::zeros();
        twist[5] = b;
        momentum(&model, &mut data, &base, &q, &twist, &[0.0; 6])
    });
    cases.rejects_each("momentum q_dot", "joint_rates", |b| {
        momentum(
            &model,
            &mut data,
            &base,
            &q,
            &Vector6::zeros(),
            &with(&[0.0; 6], 2, b),
        )
    });
    let state = FreeFloatingState::new(base, q.to_vec());
    cases.rejects_each("step joint_rates", "joint_rates", |b| {
        let mut s = state.clone();
        step(
            &model,
            &mut data,
            &mut s,
            &with(&[0.1; 6], 1, b),
            0.01,
            BaseMode::AttitudeHeld,
        )
    });
    cases.rejects_each("step dt", "dt", |b| {
        let mut s = state.clone();
        step(
            &model,
            &mut data,
            &mut s,
            &[0.1; 6],
            b,
            BaseMode::FreeFloating,
        )
    });
    cases.rejects_each("step state q", "joint_positions", |b| {
        let mut s = FreeFloatingState::new(base, with(&q, 4, b));
        step(
            &model,
            &mut data,
            &mut s,
            &[0.1; 6],
            0.01,
            BaseMode::AttitudeHeld,
        )
    });
    cases.rejects_each("step state base", "base", |b| {
        let mut s = FreeFloatingState::new(bad_pose(&base, 2, b), q.to_vec());
        step(
            &model,
            &mut data,
            &mut s,
            &[0.1; 6],
            0.01,
            BaseMode::AttitudeHeld,
        )
    });
    cases.rejects_each(
        "SinusoidalJointMotion::random amplitude",
        "amplitude",
        |b| SinusoidalJointMotion::random(6, 1, b, 1.0),
    );
    cases.rejects_each(
        "SinusoidalJointMotion::random max_frequency",
        "max_frequency",
        |b| SinusoidalJointMotion::random(6, 1, 0.1, b),
    );
    let tip = end_effector_pose(&model, &mut data, &base, &q).unwrap();
    let options = TrackingOptions::default();
    let law = LeastSquares { damping: 0.0 };
    cases.rejects_each("track_pose_path path pose", "path", |b| {
        let path = TimeFn::new(0.1, |t| if t > 0.05 { bad_pose(&tip, 0, b) } else { tip })?;
        track_pose_path(
            &model,
            &mut data,
            BaseMode::AttitudeHeld,
            &state,
            &path,
            law,
            &options,
        )
        .map(|r| r.status)
    });
    cases.rejects_each("track_pose_path duration", "duration", |b| {
        let path = TimeFn::new(b, |_| tip)?;
        track_pose_path(
            &model,
            &mut data,
            BaseMode::AttitudeHeld,
            &state,
            &path,
            law,
            &options,
        )
        .map(|r| r.status)
    });
    cases.rejects_each("track_pose_path dt", "dt", |b| {
        let options = TrackingOptions { dt: b, ..options };
        track_pose_path(
            &model,
            &mut data,
            BaseMode::AttitudeHeld,
            &state,
            &TimeFn::new(0.1, |_| tip)?,
            law,
            &options,
        )
        .map(|r| r.status)
    });
    cases.rejects_each("track_pose_path damping", "damping", |b| {
        track_pose_path(
            &model,
            &mut data,
            BaseMode::AttitudeHeld,
            &state,
            &TimeFn::new(0.1, |_| tip)?,
            LeastSquares { damping: b },
            &options,
        )
        .map(|r| r.status)
    });
    cases.rejects_each("track_pose_path initial q", "joint_positions", |b| {
        let initial = FreeFloatingState::new(base, with(&q, 0, b));
        track_pose_path(
            &model,
            &mut data,
            BaseMode::AttitudeHeld,
            &initial,
            &TimeFn::new(0.1, |_| tip)?,
            law,
            &options,
        )
        .map(|r| r.status)
    });
    cases.finish("space robot");
}

#[test]
fn mpc_rejects_non_finite_numbers() {
    let mut cases = Cases::default();
    let ur5 = robot("ur5");
    let q = [0.1, -0.8, 1.0, -0.5, 0.7, 0.2];
    let target = fk(&ur5, &[0.2, -0.9, 1.1, -0.4, 0.6, 0.3]);
    let options_with = |edit: &dyn Fn(&mut MpcOptions)| {
        let mut options = MpcOptions::default();
        edit(&mut options);
        MpcPlanner::new(&ur5, options).map(|_| ())
    };
    cases.rejects_each("MpcPlanner::new sample_time", "sample_time", |b| {
        options_with(&|o| o.sample_time = b)
    });
    cases.rejects_each("MpcPlanner::new task weights", "weight", |b| {
        options_with(&|o| o.task_weights = TaskWeights::position_only(b, 200.0))
    });
    cases.rejects_each("MpcPlanner::new terminal weight", "weight", |b| {
        options_with(&|o| o.task_weights = TaskWeights::full_pose(10.0, b))
    });
    cases.rejects_each(
        "MpcPlanner::new increment_weights",
        "increment_weights",
        |b| options_with(&|o| o.increment_weights = Some(with(&[1.0; 6], 2, b))),
    );
    let limits_of_ur5: Vec<armkit::model::JointLimits> =
        ur5.joints().iter().map(|j| j.limits).collect();
    cases.rejects_each(
        "MpcPlanner::new joint_limits velocity",
        "joint_limits",
        |b| {
            options_with(&|o| {
                let mut limits = limits_of_ur5.clone();
                limits[5].velocity = Some(b);
                o.joint_limits = Some(limits)
            })
        },
    );
    cases.rejects_each(
        "MpcPlanner::new velocity_weights",
        "velocity_weights",
        |b| options_with(&|o| o.velocity_weights = VelocityWeights::Proportional(b)),
    );
    cases.rejects_each(
        "MpcPlanner::new velocity_weights per joint",
        "velocity_weights",
        |b| {
            options_with(&|o| o.velocity_weights = VelocityWeights::PerJoint(with(&[0.1; 6], 0, b)))
        },
    );
    cases.rejects_each("MpcPlanner::new recovery_speed", "recovery_speed", |b| {
        options_with(&|o| o.recovery_speed = b)
    });
    // Infinite position limits mean "unbounded": only NaN is bad there.
    cases.rejects(
        "MpcPlanner::new joint_limits position [NaN]",
        "joint_limits",
        || {
            options_with(&|o| {
                let mut limits = limits_of_ur5.clone();
                limits[1].lower = f64::NAN;
                o.joint_limits = Some(limits)
            })
        },
    );
    let mut planner = MpcPlanner::new(&ur5, MpcOptions::default()).unwrap();
    planner.set_target(&target).unwrap();
    cases.rejects_each("MpcPlanner::step q", "joint_positions", |b| {
        planner.step(&with(&q, 3, b)).map(|r| r.status)
    });
    for index in [1, 6] {
        cases.rejects_each(
            &format!("MpcPlanner::set_target entry {index}"),
            "target",
            |b| planner.set_target(&bad_pose(&target, index, b)),
        );
    }
    cases.rejects_each("MpcPlanner::reset velocity", "velocity", |b| {
        planner.reset(&with(&[0.0; 6], 0, b))
    });
    cases.rejects_each(
        "MpcPlanner::step_with_measured_pose pose",
        "measured_pose",
        |b| {
            planner
                .step_with_measured_pose(&q, &bad_pose(&target, 9, b))
                .map(|r| r.status)
        },
    );
    // After all those rejected calls the planner still works.
    let report = planner.step(&q).unwrap();
    assert!(report.velocity.iter().all(|v| v.is_finite()));
    let simulation = SimulationOptions {
        max_steps: 5,
        ..SimulationOptions::default()
    };
    cases.rejects_each("simulate start", "joint_positions", |b| {
        simulate(
            &ur5,
            MpcOptions::default(),
            &with(&q, 2, b),
            &target,
            &simulation,
        )
        .map(|r| r.summary.steps)
    });
    cases.rejects_each("simulate target", "target", |b| {
        simulate(
            &ur5,
            MpcOptions::default(),
            &q,
            &bad_pose(&target, 2, b),
            &simulation,
        )
        .map(|r| r.summary.steps)
    });
    for name in [
        "position_tolerance",
        "orientation_tolerance",
        "velocity_tolerance",
    ] {
        cases.rejects_each(&format!("simulate {name}"), name, |b| {
            let mut s = simulation.clone();
            match name {
                "position_tolerance" => s.position_tolerance = b,
                "orientation_tolerance" => s.orientation_tolerance = b,
                _ => s.velocity_tolerance = b,
            }
            simulate(&ur5, MpcOptions::default(), &q, &target, &s).map(|r| r.summary.steps)
        });
    }
    cases.finish("MPC");
}

/// Entry points that return a plain number cannot return an error: they
/// must not turn a non-finite input into a finite, valid-looking answer,
/// except where they document a clamp.
#[test]
fn plain_number_functions_propagate_non_finite_input() {
    let beam = CarriageDeflection::seed000();
    // NaN carriage position: NaN deflection and slope (this recursed forever
    // before the fix in beam.rs); +-inf is clamped to a support: no deflection.
    let (w, slope) = beam.deflection_and_slope(f64::NAN);
    assert!(
        w.is_nan() && slope.is_nan(),
        "deflection_and_slope(NaN) = ({w}, {slope})"
    );
    for bad in [f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(beam.deflection_and_slope(bad), (0.0, 0.0), "{bad}");
    }
    // CartesianTrajectory::pose_at clamps t into the trajectory (documented):
    // -inf and NaN give the start pose (f64::max drops a NaN), +inf the end;
    // the checked variant, `sample`, rejects them (cartesian_paths_* above).
    let ur5 = robot("ur5");
    let start = fk(&ur5, &[0.1, -0.8, 1.0, -0.5, 0.7, 0.2]);
    let mut end = start;
    end.translation.y += 0.1;
    let path = CartesianTrajectory::new(
        LinePath::new(start, end).unwrap(),
        TimeLaw::Linear.timing(1.0).unwrap(),
    )
    .unwrap();
    let gap = |a: &Pose, b: &Pose| (a.to_matrix4() - b.to_matrix4()).abs().max();
    assert!(gap(&path.pose_at(f64::NEG_INFINITY), &start) < 1e-12);
    assert!(gap(&path.pose_at(f64::NAN), &start) < 1e-12);
    assert!(gap(&path.pose_at(f64::INFINITY), &end) < 1e-12);
}
