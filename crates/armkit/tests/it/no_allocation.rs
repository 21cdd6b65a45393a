//! Hot paths allocate nothing after set-up, counted by a global allocator
//! that counts the allocations of the calling thread (the test harness's
//! own threads allocate at times too):
//!
//! * Forward kinematics and the Jacobian allocate nothing once `Data` exists: zero allocations across many calls; nor do the batched kernels once `BatchData` exists.
//! * One IK solve allocates exactly once (the report's joint vector) after `IkSolver::new`, whatever the number of iterations and restarts: the iterations themselves allocate nothing.
//! * One MPC step (re-linearise, update the QP in place, solve) allocates nothing once the planner is built: a counting global allocator sees zero allocations over many steps of the planner, of the active-set solver, of OSQP, and of the goal posture between its IK searches; Clarabel makes one small allocation per solve inside its timers (measured and pinned).
//! * A redundancy solve allocates nothing once its workspace exists: a counting global allocator sees zero allocations across many solves (weighted least norm, damped, toward a preferred velocity, projector, seed 001's partitioned form and eq 17, torques, energy weights, null-space directions).
//! * The free-floating hot paths allocate nothing once `SpaceData` exists: a counting global allocator sees zero allocations across many calls of `generalized_jacobian`, `step`, `center_of_mass`, `end_effector_pose` and `momentum`, in both base modes.
//! * Sampling a trajectory allocates nothing: a counting global allocator sees zero allocations across many `sample_into` calls (joint space) and `CartesianTrajectory::sample` calls (built-in paths), counted per thread.
//! * The dynamics algorithms allocate nothing once `DynamicsData` exists: RNEA, CRBA, M^-1, g, C v, ABA, energies, a simulation step (both integrators, with friction) and the seed 001 torques, on coupled models too (gantry9-flex, a mimic-joint chain).
//! * A singularity-tracking control period allocates nothing: a run's allocations (its recorded series) do not depend on its number of periods, for plain, avoidance, DLS and SRI.
//! * The linear-algebra kernels (Gram factor, damped least-squares rates, manipulability) and a period of the tracking loop (fixed base, least squares, a recorder that stores nothing) allocate nothing.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use armkit::ik::{benchmark_targets, IkMethod, IkOptions, IkSolver, Redundancy};
use armkit::kinematics::{
    forward_kinematics, forward_kinematics_batch, jacobian, jacobian_batch, BatchData, Data,
    JacobianFrame,
};
use armkit::math::{Pose, Vector3, Vector6};
use armkit::mpc::qp::{QpOutcome, QpProblem, QpSolver, QpSolverKind, QpStatus};
use armkit::mpc::{MpcOptions, MpcPlanner};
use armkit::redundancy::SecondaryTask;
use armkit::redundancy::{
    best_partition, joint_torques, Damping, JointWeights, Load, PartitionedSolver,
    SecondaryObjective, SolverOptions, TorqueFloor, WeightedLeastNorm,
};
use armkit::robots::space6r_free_floating;
use armkit::space::{
    center_of_mass, end_effector_pose, generalized_jacobian, momentum, step, BaseMode,
    FreeFloatingState, SpaceData,
};
use armkit::study::Seed000Example;
use armkit::trajectory::clamped_cubic_spline;
use armkit::trajectory::JointState;
use armkit::trajectory::{self, ProfileShape};
use armkit::trajectory::{ArcOrientation, ArcPath, CartesianTrajectory, LinePath, TimeLaw};

struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Allocations made so far by the calling thread.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn fk_and_jacobian_do_not_allocate() {
    for name in ["ur5", "panda", "gantry9", "gantry9-flex", "stanford"] {
        let model = armkit::robots::by_name(name).unwrap();
        let mut data = Data::new(&model);
        let q = model.neutral_configuration();
        let before = allocations();
        for _ in 0..100 {
            forward_kinematics(&model, &mut data, &q).unwrap();
            jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
            jacobian(&model, &mut data, &q, JacobianFrame::EndEffector).unwrap();
        }
        let after = allocations();
        assert_eq!(after - before, 0, "{name}: {} allocations", after - before);
    }
}

#[test]
fn batched_fk_and_jacobians_do_not_allocate() {
    let mimicbot = armkit::urdf::load(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../tests/data/urdf/mimicbot.urdf"
        ),
        &armkit::urdf::ChainSelection::between("base", "fingertip"),
    )
    .unwrap();
    let mut models: Vec<_> = ["ur5", "panda", "gantry9-flex"]
        .iter()
        .map(|name| armkit::robots::by_name(name).unwrap())
        .collect();
    models.push(mimicbot);
    for model in models {
        let n = 10;
        let q: Vec<f64> = (0..n).flat_map(|_| model.neutral_configuration()).collect();
        let mut batch = BatchData::new(&model);
        let mut poses = vec![0.0; n * 16];
        let mut jacobians = vec![0.0; n * 6 * model.dof()];
        let before = allocations();
        for _ in 0..20 {
            forward_kinematics_batch(&model, &mut batch, &q, &mut poses).unwrap();
            for frame in [JacobianFrame::World, JacobianFrame::EndEffector] {
                jacobian_batch(&model, &mut batch, &q, frame, &mut jacobians).unwrap();
            }
        }
        let after = allocations();
        assert_eq!(
            after - before,
            0,
            "{}: {} allocations",
            model.name(),
            after - before
        );
    }
}

#[test]
fn fk_jacobian_and_force_folding_with_mimic_joints_do_not_allocate() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/urdf/mimicbot.urdf"
    );
    let model = armkit::urdf::load(
        path,
        &armkit::urdf::ChainSelection::between("base", "fingertip"),
    )
    .unwrap();
    assert!(model.has_mimic_joints());
    let mut data = Data::new(&model);
    let q = model.neutral_configuration();
    let mut chain = vec![0.0; model.chain_joints().len()];
    let mut forces = vec![0.0; model.dof()];
    let before = allocations();
    for _ in 0..100 {
        forward_kinematics(&model, &mut data, &q).unwrap();
        jacobian(&model, &mut data, &q, JacobianFrame::World).unwrap();
        jacobian(&model, &mut data, &q, JacobianFrame::EndEffector).unwrap();
        model.chain_positions(&q, &mut chain).unwrap();
        model.fold_chain_forces(&q, &chain, &mut forces).unwrap();
    }
    let after = allocations();
    assert_eq!(
        after - before,
        0,
        "mimicbot: {} allocations",
        after - before
    );
}

#[test]
fn an_ik_solve_allocates_only_its_report() {
    for name in ["ur5", "panda", "gantry9", "arm4"] {
        let model = armkit::robots::by_name(name).unwrap();
        let targets = benchmark_targets(&model, 20, 1).unwrap();
        for method in ["nr", "dls", "lm", "sri"] {
            let options = IkOptions {
                method: IkMethod::from_short_name(method).unwrap(),
                time_budget: None,
                max_restarts: 5,
                redundancy: Redundancy::PullToStart {
                    gain: 0.5,
                    iterations: 5,
                },
                ..IkOptions::default()
            };
            let mut solver = IkSolver::new(&model, options).unwrap();
            let start = model.neutral_configuration();
            let mut iterations = 0;
            for (_, target) in &targets {
                let before = allocations();
                let report = solver.solve(target, &start).unwrap();
                let after = allocations();
                iterations += report.iterations;
                assert_eq!(
                    after - before,
                    1,
                    "{name} {method}: {} allocations",
                    after - before
                );
            }
            assert!(
                iterations > 20 * 3,
                "{name} {method}: too few iterations to mean anything"
            );
        }
    }
}

/// Allocations counted over 60 closed-loop steps of Example 1 with control
/// horizon `m` (after 3 warm-up steps), with the backend `build` makes.
fn allocations_per_60_steps(
    m: usize,
    build: impl FnOnce(&QpProblem) -> armkit::Result<Box<dyn QpSolver>>,
) -> usize {
    let example = Seed000Example::LargeMove;
    let model = Seed000Example::model().unwrap();
    let options = MpcOptions {
        control_horizon: m,
        ..example.options()
    };
    let t = options.sample_time;
    let mut planner = MpcPlanner::with_solver(&model, options, build).unwrap();
    planner.set_target(&example.target()).unwrap();
    let mut q = example.start();
    let mut velocity = vec![0.0; q.len()];
    for _ in 0..3 {
        velocity.copy_from_slice(&planner.step(&q).unwrap().velocity);
        q.iter_mut().zip(&velocity).for_each(|(q, v)| *q += t * v);
    }
    let before = allocations();
    for _ in 0..60 {
        velocity.copy_from_slice(&planner.step(&q).unwrap().velocity);
        q.iter_mut().zip(&velocity).for_each(|(q, v)| *q += t * v);
    }
    allocations() - before
}

/// A backend that answers "solved, no change": isolates the planner's own work.
struct HoldSolver;

impl QpSolver for HoldSolver {
    fn name(&self) -> &'static str {
        "hold"
    }
    fn solve(&mut self, _: &[f64], _: &[f64], _: &[f64], _: &[f64], x: &mut [f64]) -> QpOutcome {
        x.iter_mut().for_each(|v| *v = 0.0);
        QpOutcome {
            status: QpStatus::Solved,
            iterations: 0,
        }
    }
}

#[test]
fn the_planner_step_itself_does_not_allocate() {
    // Re-linearisation, Hessian, gradient, bounds, limit check, report.
    for m in [1, 5] {
        let count = allocations_per_60_steps(m, |_| Ok(Box::new(HoldSolver)));
        assert_eq!(count, 0, "M={m}: {count} allocations in 60 steps");
    }
}

#[cfg(feature = "osqp")]
#[test]
fn an_mpc_step_on_osqp_does_not_allocate() {
    for m in [1, 5] {
        let count = allocations_per_60_steps(m, |p| QpSolverKind::Osqp.build(p));
        assert_eq!(count, 0, "osqp M={m}: {count} allocations in 60 steps");
    }
}

#[test]
fn an_mpc_step_on_the_active_set_solver_does_not_allocate() {
    for m in [1, 5] {
        let count = allocations_per_60_steps(m, |p| QpSolverKind::ActiveSet.build(p));
        assert_eq!(
            count, 0,
            "active-set M={m}: {count} allocations in 60 steps"
        );
    }
}

#[test]
fn an_mpc_step_with_the_goal_posture_does_not_allocate_after_its_search() {
    // The goal posture's IK search runs at the first step after
    // `set_target` (and after a stall): it allocates; the steps that
    // follow do not.
    let example = Seed000Example::LargeMove;
    let model = Seed000Example::model().unwrap();
    for m in [1, 5] {
        let options = MpcOptions {
            control_horizon: m,
            reach: armkit::mpc::ReachAid::default(),
            ..example.options()
        };
        let t = options.sample_time;
        let mut planner = MpcPlanner::new(&model, options).unwrap();
        planner.set_target(&example.target()).unwrap();
        let mut q = example.start();
        let mut velocity = vec![0.0; q.len()];
        for _ in 0..3 {
            velocity.copy_from_slice(&planner.step(&q).unwrap().velocity);
            q.iter_mut().zip(&velocity).for_each(|(q, v)| *q += t * v);
        }
        assert!(planner.goal_posture().is_some());
        let before = allocations();
        for _ in 0..40 {
            velocity.copy_from_slice(&planner.step(&q).unwrap().velocity);
            q.iter_mut().zip(&velocity).for_each(|(q, v)| *q += t * v);
        }
        let count = allocations() - before;
        assert_eq!(
            count, 0,
            "goal posture M={m}: {count} allocations in 40 steps"
        );
    }
}

#[test]
fn clarabel_allocates_once_per_solve_in_its_timers() {
    // Clarabel 0.11's `solve` resets its timer tree (`info.reset` clears
    // the "solve" timer's children) and rebuilds it: one heap allocation
    // (about 400 bytes) per solve, freed at the next. Nothing else in the
    // step allocates (see the test above); this pins the count so that a
    // change shows.
    for m in [1, 5] {
        let count = allocations_per_60_steps(m, |p| QpSolverKind::Clarabel.build(p));
        assert!(
            count <= 60,
            "clarabel M={m}: {count} allocations in 60 steps"
        );
    }
}

#[test]
fn redundancy_solves_do_not_allocate() {
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let twist = Vector6::new(0.1, 0.05, -0.05, 0.0, 0.1, 0.0);
    let load = Load::payload(50.0).with_seed001_gravity();
    let mut weights = JointWeights::uniform(9);
    let mut torques = [0.0; 9];
    let preferred = [0.01; 9];
    let mut z = [0.0; 9];
    let mut exact = WeightedLeastNorm::new(9, SolverOptions::default()).unwrap();
    let mut damped = WeightedLeastNorm::new(
        9,
        SolverOptions {
            damping: Damping::Adaptive {
                threshold: 0.1,
                max: 0.05,
            },
            ..SolverOptions::default()
        },
    )
    .unwrap();
    let partition = best_partition(&j, None, 1e10).unwrap().partition;
    let mut partitioned = PartitionedSolver::new(9, 1e10).unwrap();
    let mut limits =
        SecondaryTask::new(&model, SecondaryObjective::JointLimits { gain: 1.0 }).unwrap();
    let mut dexterity = SecondaryTask::new(
        &model,
        SecondaryObjective::Manipulability {
            gain: 1.0,
            step: 1e-6,
        },
    )
    .unwrap();
    let before = allocations();
    for _ in 0..100 {
        joint_torques(&model, &mut data, &q, &load, &mut torques).unwrap();
        weights
            .set_from_torques(&torques, TorqueFloor::default())
            .unwrap();
        assert!(!exact.solve(&j, &weights, &twist).unwrap().is_singular());
        assert!(!exact
            .solve_toward(&j, &weights, &twist, &preferred)
            .unwrap()
            .is_singular());
        assert!(!exact
            .null_space_projector(&j, &weights)
            .unwrap()
            .is_singular());
        assert!(!damped.solve(&j, &weights, &twist).unwrap().is_singular());
        partitioned.solve(&j, &weights, &twist, &partition).unwrap();
        partitioned
            .solve_energy_optimal(&j, &torques, &twist, &partition)
            .unwrap();
        limits
            .preferred_velocity(&model, &q, &weights, &mut z)
            .unwrap();
        dexterity
            .preferred_velocity(&model, &q, &weights, &mut z)
            .unwrap();
    }
    let after = allocations();
    assert_eq!(after - before, 0, "{} allocations", after - before);
}

#[test]
fn free_floating_hot_paths_do_not_allocate() {
    let model = space6r_free_floating().unwrap();
    let mut data = SpaceData::new(&model);
    let mut state = FreeFloatingState::new(
        Pose::from_xyz_rpy([0.1, 0.2, 0.3], [0.3, 0.2, 0.1]),
        vec![0.3, 0.6, -0.9, 0.4, 0.7, -0.2],
    );
    let rates = [0.1, -0.2, 0.3, 0.1, 0.2, -0.1];
    let twist = Vector6::new(0.01, 0.0, 0.0, 0.0, 0.01, 0.0);
    for mode in [BaseMode::AttitudeHeld, BaseMode::FreeFloating] {
        let before = allocations();
        for _ in 0..100 {
            generalized_jacobian(&model, &mut data, &state.base, &state.q, mode).unwrap();
            step(&model, &mut data, &mut state, &rates, 0.01, mode).unwrap();
            center_of_mass(&model, &mut data, &state.base, &state.q).unwrap();
            end_effector_pose(&model, &mut data, &state.base, &state.q).unwrap();
            momentum(&model, &mut data, &state.base, &state.q, &twist, &rates).unwrap();
        }
        let after = allocations();
        assert_eq!(
            after - before,
            0,
            "{mode:?}: {} allocations",
            after - before
        );
    }
}

#[test]
fn sampling_does_not_allocate() {
    let q0 = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8];
    let qf = [1.0, 0.4, -0.5, -1.2, 0.7, 1.2, -0.3];
    let times: Vec<f64> = (0..=20).map(|i| i as f64 * 0.25).collect();
    let points: Vec<Vec<f64>> = times
        .iter()
        .map(|t| q0.iter().map(|q| q + t.sin()).collect())
        .collect();
    let joint = [
        trajectory::rest_to_rest(ProfileShape::Quintic, &q0, &qf, 2.0, None).unwrap(),
        trajectory::trapezoidal(&q0, &qf, 20.0, 4.0).unwrap(),
        clamped_cubic_spline(&times, &points, &[0.0; 7], &[0.0; 7]).unwrap(),
    ];
    let start = Pose::from_xyz_rpy([0.4, 0.0, 0.3], [0.1, 0.2, 0.3]);
    let end = Pose::from_xyz_rpy([0.4, 0.3, 0.1], [0.3, -0.2, 1.3]);
    let line = CartesianTrajectory::new(
        LinePath::new(start, end).unwrap(),
        TimeLaw::Quintic.timing(2.0).unwrap(),
    )
    .unwrap();
    let arc = ArcPath::new(
        start,
        Vector3::new(0.2, 0.0, 0.3),
        Vector3::z(),
        1.0,
        ArcOrientation::FollowArc,
    )
    .unwrap();
    let arc = CartesianTrajectory::new(
        arc,
        TimeLaw::Trapezoidal {
            acceleration_time: 0.5,
        }
        .timing(2.0)
        .unwrap(),
    )
    .unwrap();
    let mut out = JointState::zeros(7);
    let before = allocations();
    let mut checksum = 0.0;
    for k in 0..1000 {
        let t = k as f64 * 0.0051;
        for traj in &joint {
            traj.sample_into(t, &mut out).unwrap();
            checksum += out.position[0] + out.velocity[6] + out.acceleration[3];
        }
        for path in [&line, &arc] {
            let state = path.sample(t).unwrap();
            checksum += state.pose.translation.x + state.twist[5] + path.pose_at(t).translation.y;
        }
    }
    let after = allocations();
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "{} allocations", after - before);
}

/// A singularity-tracking run allocates by design (it records every
/// sample's series, sized once, and each region's knots and fit), but its
/// control period does not: on a regular path, the allocations of a run do
/// not depend on its number of periods, for every method.
#[test]
fn a_tracking_period_does_not_allocate() {
    use armkit::ik::{ChiaveriniFilter, NakamuraDamping};
    use armkit::singularity::{line_through, AvoidanceOptions, Manipulator, Method, PathTracker};
    use armkit::tracking::TrackingOptions;
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let through = [0.2, 0.9, -0.6, 0.4, 1.1, 0.3];
    let direction = [0.2, -0.1, 0.15, 0.1, 0.1, -0.1];
    let line = line_through(&manipulator, &through, &direction, 0.0).unwrap();
    let counts = |dt: f64, method: &Method| {
        let options = AvoidanceOptions {
            tracking: TrackingOptions {
                dt,
                ..TrackingOptions::default()
            },
            ..AvoidanceOptions::default()
        };
        let tracker = PathTracker::new(manipulator, line.task(5.0, 1.0), options).unwrap();
        let before = allocations();
        let run = tracker.run(method).unwrap();
        let after = allocations();
        assert!(run.regions.is_empty());
        after - before
    };
    for method in [
        Method::Plain,
        Method::Avoidance { k: 5 },
        Method::DampedLeastSquares(NakamuraDamping {
            threshold: 0.1,
            max_damping: 0.05,
        }),
        Method::SingularityRobust(ChiaveriniFilter {
            threshold: 0.5,
            ..ChiaveriniFilter::default()
        }),
    ] {
        let (coarse, fine) = (counts(0.01, &method), counts(0.0025, &method));
        assert_eq!(
            coarse,
            fine,
            "{}: {coarse} vs {fine} allocations",
            method.label()
        );
    }
}

#[test]
fn dynamics_does_not_allocate() {
    use armkit::dynamics::simulate::{Integrator, JointFriction, SimulationOptions, Simulator};
    use armkit::dynamics::{
        aba, coriolis_torques, gravity_torques, kinetic_energy, mass_matrix, mass_matrix_inverse,
        nonlinear_effects, potential_energy, rnea, DynamicsData,
    };
    use armkit::redundancy::{EnergyTorques, TorqueModel};
    // Coupled models too: the flexible gantry and a mimic-joint finger.
    let mut models: Vec<armkit::Model> = ["space6r", "gantry9", "gantry9-flex"]
        .into_iter()
        .map(|name| armkit::robots::by_name(name).unwrap())
        .collect();
    models.push(
        armkit::urdf::load(
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../tests/data/urdf/mimicbot.urdf"
            ),
            &armkit::urdf::ChainSelection::between("base", "fingertip"),
        )
        .unwrap(),
    );
    for model in &models {
        let name = model.name();
        let model = model.clone();
        let n = model.dof();
        let mut data = DynamicsData::new(&model).unwrap();
        let q = model.neutral_configuration();
        let v = vec![0.3; n];
        let a = vec![-0.2; n];
        let mut tau = vec![0.0; n];
        let friction = JointFriction {
            viscous: vec![0.1; n],
            coulomb: vec![0.05; n],
        };
        let mut simulators: Vec<Simulator> =
            [Integrator::SemiImplicitEuler, Integrator::RungeKutta4]
                .into_iter()
                .map(|integrator| {
                    let options = SimulationOptions {
                        integrator,
                        friction: Some(friction.clone()),
                        ..Default::default()
                    };
                    Simulator::new(&model, options).unwrap()
                })
                .collect();
        let (mut qs, mut vs) = (q.clone(), v.clone());
        let mut energy = EnergyTorques::new(&model).unwrap();
        let load = Load::payload(50.0).with_seed001_gravity();
        let before = allocations();
        for _ in 0..50 {
            tau.copy_from_slice(rnea(&model, &mut data, &q, &v, &a).unwrap());
            mass_matrix(&model, &mut data, &q).unwrap();
            mass_matrix_inverse(&model, &mut data, &q).unwrap();
            gravity_torques(&model, &mut data, &q).unwrap();
            coriolis_torques(&model, &mut data, &q, &v).unwrap();
            nonlinear_effects(&model, &mut data, &q, &v).unwrap();
            aba(&model, &mut data, &q, &v, &tau).unwrap();
            kinetic_energy(&model, &mut data, &q, &v).unwrap();
            potential_energy(&model, &mut data, &q).unwrap();
            for sim in simulators.iter_mut() {
                sim.step(&model, &mut qs, &mut vs, &tau).unwrap();
            }
            // (The static load torques refuse mimic joints: statics' limit.)
            let torque_models = if model.has_mimic_joints() {
                &[TorqueModel::Dynamic][..]
            } else {
                &[TorqueModel::Static, TorqueModel::Dynamic][..]
            };
            for &torque_model in torque_models {
                energy
                    .torques(&model, &q, &v, &a, &load, torque_model, &mut tau)
                    .unwrap();
            }
        }
        let after = allocations();
        assert_eq!(after - before, 0, "{name}: {} allocations", after - before);
    }
}

/// The linear-algebra kernels allocate nothing, and neither does a period
/// of the tracking loop on a fixed-base plant with the least-squares law:
/// a run's allocations (its samples) grow with its periods, by the same
/// count per period whatever the duration (one sample: joint positions and
/// rates), so the loop itself adds none.
#[test]
fn linalg_kernels_and_the_tracking_loop_do_not_allocate() {
    use armkit::linalg::{damped_least_squares_rates, factor_gram, gram, manipulability};
    use armkit::tracking::{track, FixedBase, LeastSquares, Recorder, SampleState};
    use armkit::trajectory::TimedPath;
    let model = armkit::robots::by_name("gantry9").unwrap();
    let mut data = Data::new(&model);
    let q = [3.0, 2.5, 1.0, 0.3, 0.4, -0.5, 0.2, 0.8, 0.1];
    let j = jacobian(&model, &mut data, &q, JacobianFrame::World)
        .unwrap()
        .clone();
    let twist = Vector6::new(0.1, 0.05, -0.05, 0.0, 0.1, 0.0);
    let mut rates = [0.0; 9];
    let before = allocations();
    for _ in 0..100 {
        assert!(!factor_gram(&gram(&j), 1e-12).is_singular());
        assert!(!damped_least_squares_rates(&j, &twist, 0.01, 1e-14, &mut rates).is_singular());
        assert!(manipulability(&j) > 0.0);
    }
    assert_eq!(allocations() - before, 0);

    /// Counts samples without storing them.
    struct Count(usize);
    impl Recorder for Count {
        fn state(&mut self, _: &SampleState<'_>) -> armkit::Result<()> {
            self.0 += 1;
            Ok(())
        }
        fn rates(&mut self, _: &[f64], _: Option<&armkit::tracking::RateOutcome>) {}
    }
    let start = *forward_kinematics(&model, &mut data, &q).unwrap();
    let goal = Pose::from_translation(Vector3::new(0.1, 0.0, -0.05)) * start;
    let loop_allocations = |duration: f64| {
        let path = CartesianTrajectory::line(start, goal, TimeLaw::Quintic, duration).unwrap();
        let mut data = Data::new(&model);
        let mut plant = FixedBase::new(&model, &mut data, &q).unwrap();
        let mut recorder = Count(0);
        let mut rates = [0.0; 9];
        let options = armkit::tracking::TrackingOptions::default();
        let before = allocations();
        let status = track(
            &mut plant,
            &mut LeastSquares { damping: 0.0 },
            &path as &dyn TimedPath,
            &options,
            &mut recorder,
            &mut rates,
        )
        .unwrap();
        let after = allocations();
        assert!(status.is_completed() && recorder.0 > 10);
        after - before
    };
    assert_eq!(loop_allocations(0.5), 0);
    assert_eq!(loop_allocations(2.0), 0);
}

#[test]
fn the_simulated_plant_does_not_allocate() {
    use armkit::mpc::{ActuatorPrecision, Plant, PlantModel};
    let model = armkit::robots::gantry9_flex().unwrap();
    let kinds: Vec<_> = model.joints().iter().map(|j| j.kind).collect();
    let limited = PlantModel::LimitedPrecision {
        prismatic: ActuatorPrecision {
            position_resolution: 1e-3,
            deadband: 1e-3,
            velocity_resolution: 1e-4,
        },
        rotary: ActuatorPrecision::EXACT,
    };
    for plant_model in [PlantModel::Exact, limited] {
        let mut q = model.neutral_configuration();
        let mut plant = Plant::new(plant_model, &kinds, &q).unwrap();
        let u = vec![0.013; q.len()];
        let before = allocations();
        for _ in 0..100 {
            plant.advance(&mut q, &u, 0.05).unwrap();
        }
        let after = allocations();
        assert_eq!(
            after - before,
            0,
            "{plant_model:?}: {} allocations",
            after - before
        );
    }
}

#[test]
fn analytic_ik_solves_do_not_allocate() {
    use armkit::ik::analytic::{AnalyticOptions, AnalyticSolver, Parameter};
    let cases = [
        ("ur5", None),
        ("puma560", None),
        ("stanford", None),
        (
            "panda",
            Some(Parameter::FixedJoint {
                joint: 6,
                value: 0.3,
            }),
        ),
    ];
    for (name, parameter) in cases {
        let model = armkit::robots::by_name(name).unwrap();
        let targets = benchmark_targets(&model, 20, 3).unwrap();
        let options = AnalyticOptions::default();
        let mut solver = match parameter {
            Some(p) => AnalyticSolver::with_parameter(&model, options, p).unwrap(),
            None => AnalyticSolver::new(&model, options).unwrap(),
        };
        let start = model.neutral_configuration();
        let mut solutions = 0;
        for (_, target) in &targets {
            let before = allocations();
            solutions += solver.solve(target, &start).unwrap().len();
            let after = allocations();
            assert_eq!(after - before, 0, "{name}: {} allocations", after - before);
        }
        assert!(solutions > 0, "{name}");
    }
    // The three-parallel class without an intersecting pair (subproblem 6).
    use armkit::model::{DhConvention, DhLink};
    let links = [
        (0.31, 0.08, 1.1),
        (0.12, 0.52, 0.0),
        (-0.07, 0.44, 0.0),
        (0.21, 0.06, -0.8),
        (0.17, 0.05, 1.3),
        (0.09, 0.0, 0.4),
    ]
    .map(|(d, a, alpha)| DhLink::revolute(d, a, alpha).with_limits(-3.0, 3.0));
    let model = armkit::Model::from_dh("offset", DhConvention::Standard, &links).unwrap();
    let mut solver = AnalyticSolver::new(&model, AnalyticOptions::default()).unwrap();
    assert_eq!(solver.class().as_str(), "three_parallel_2_3_4");
    let start = model.neutral_configuration();
    let mut solutions = 0;
    for (_, target) in &benchmark_targets(&model, 20, 5).unwrap() {
        let before = allocations();
        solutions += solver.solve(target, &start).unwrap().len();
        assert_eq!(allocations() - before, 0, "three_parallel_2_3_4");
    }
    assert!(solutions > 0);
    // Out of reach: the least-squares path.
    let far = armkit::math::Pose::from_translation(armkit::math::Vector3::new(9.0, 0.0, 0.5));
    let before = allocations();
    assert!(!solver.solve(&far, &start).unwrap().is_empty());
    assert_eq!(
        allocations() - before,
        0,
        "three_parallel_2_3_4 out of reach"
    );
}

#[test]
fn analytic_ik_with_a_changing_held_end_joint_does_not_allocate() {
    use armkit::ik::analytic::{AnalyticOptions, AnalyticSolver, Parameter};
    let model = armkit::robots::by_name("panda").unwrap();
    let targets = benchmark_targets(&model, 20, 4).unwrap();
    let parameter = Parameter::FixedJoint {
        joint: 6,
        value: 0.0,
    };
    let mut solver =
        AnalyticSolver::with_parameter(&model, AnalyticOptions::default(), parameter).unwrap();
    let start = model.neutral_configuration();
    let mut solutions = 0;
    for (i, (_, target)) in targets.iter().enumerate() {
        let before = allocations();
        solver.set_parameter_value(-2.0 + 0.2 * i as f64).unwrap();
        solutions += solver.solve(target, &start).unwrap().len();
        let after = allocations();
        assert_eq!(
            after - before,
            0,
            "panda q7 held: {} allocations",
            after - before
        );
    }
    assert!(solutions > 0);
}

#[test]
fn dynamics_workspace_moving_between_models_does_not_allocate() {
    use armkit::dynamics::{mass_matrix, rnea, DynamicsData};
    // Two model values of the same size: each switch reads the other's mass
    // properties and placements again, in place.
    let first = armkit::robots::by_name("space6r").unwrap();
    let second = first.clone();
    let mut data = DynamicsData::new(&first).unwrap();
    let q = first.neutral_configuration();
    let v = vec![0.3; 6];
    let before = allocations();
    for _ in 0..50 {
        for model in [&first, &second] {
            rnea(model, &mut data, &q, &v, &v).unwrap();
            mass_matrix(model, &mut data, &q).unwrap();
        }
    }
    assert_eq!(
        allocations() - before,
        0,
        "dynamics with a workspace moving between models"
    );
}

#[test]
fn analytic_ik_by_elimination_does_not_allocate() {
    use armkit::ik::analytic::AnalyticOptions;
    use armkit::math::{Pose, Vector3};
    use armkit::model::{JointSpec, ModelBuilder};
    use std::f64::consts::PI;
    // Axes 5-6 meet (one intersecting pair); moved apart, a general 6R
    // arm; that with axis 3 along axis 2 (a parallel pair); axes 3-4
    // meeting instead (the pair in the middle); axis 2 along axis 1 (a
    // parallel pair at the base): all by elimination.
    let lines = |third: [f64; 3], fourth: [f64; 3], last: [f64; 3], second: [f64; 3]| {
        [
            ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.1, 0.05, 0.4], second),
            ([0.5, -0.1, 0.6], third),
            (fourth, [0.9, 0.2, -0.4]),
            ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
            (last, [0.85, -0.2, 0.5]),
        ]
    };
    let skew = [-0.2, 0.8, 0.55];
    let fourth = [0.8, 0.1, 0.55];
    let second = [0.3, 0.9, 0.3];
    for (name, third, fourth, last, second) in [
        ("one_pair", skew, fourth, [1.0, 0.0, 0.5], second),
        ("general", skew, fourth, [1.1, 0.1, 0.45], second),
        ("parallel_pair", second, fourth, [1.1, 0.1, 0.45], second),
        (
            "parallel_pair_1_2",
            skew,
            fourth,
            [1.1, 0.1, 0.45],
            [0.0, 0.0, 1.0],
        ),
        ("pair_3_4", skew, [0.5, -0.1, 0.6], [1.1, 0.1, 0.45], second),
    ] {
        let mut builder = ModelBuilder::new(name);
        let mut previous = Vector3::zeros();
        for (i, (c, h)) in lines(third, fourth, last, second).iter().enumerate() {
            let c = Vector3::from(*c);
            builder = builder.joint(
                JointSpec::revolute(format!("q{}", i + 1), -PI, PI)
                    .with_origin(Pose::from_translation(c - previous))
                    .with_axis(Vector3::from(*h).normalize()),
            );
            previous = c;
        }
        let model = builder
            .fixed(Pose::from_translation(Vector3::new(0.15, 0.0, 0.0)))
            .build()
            .unwrap();
        solve_without_allocating(name, &model, AnalyticOptions::default());
    }
}

/// Solves 5 targets of `model` with a solver of `options`; asserts none of
/// the solves allocates and that some solution is found.
fn solve_without_allocating(
    name: &str,
    model: &armkit::Model,
    options: armkit::ik::analytic::AnalyticOptions,
) {
    use armkit::ik::analytic::AnalyticSolver;
    let mut solver = AnalyticSolver::new(model, options).unwrap();
    if name == "parallel_pair" {
        assert_eq!(solver.class().as_str(), "one_pair_parallel_2_3");
    }
    if name == "parallel_pair_1_2" {
        assert_eq!(solver.class().as_str(), "one_pair_parallel_1_2");
    }
    if name == "pair_3_4" {
        assert_eq!(solver.class().as_str(), "one_pair_intersecting_3_4");
    }
    let targets = benchmark_targets(model, 5, 3).unwrap();
    let start = model.neutral_configuration();
    let mut solutions = 0;
    for (_, target) in &targets {
        let before = allocations();
        solutions += solver.solve(target, &start).unwrap().len();
        let after = allocations();
        let method = solver.method();
        assert_eq!(
            after - before,
            0,
            "{name} ({method}): {} allocations",
            after - before
        );
    }
    assert!(solutions > 0, "{name}");
}

#[test]
fn auto_ik_allocates_only_the_answer() {
    // One allocation per solve, the report's `q`: the search for the
    // solution nearest the start (over a 7-joint arm's held joint) runs in
    // the solver's own workspace.
    use armkit::ik::{AutoSolver, IkOptions};
    for name in ["ur5", "panda"] {
        let model = armkit::robots::by_name(name).unwrap();
        let targets = benchmark_targets(&model, 40, 5).unwrap();
        let mut solver = AutoSolver::new(&model, IkOptions::default()).unwrap();
        let start = model.neutral_configuration();
        solver.solve(&targets[0].1, &start).unwrap();
        for (_, target) in &targets {
            let before = allocations();
            solver.solve(target, &start).unwrap();
            let after = allocations();
            // A 7-joint arm whose nearest analytic answer lies beyond the
            // window also tries one numeric descent from the start; when
            // that loses, its report's `q` is the second allocation.
            let most = if name == "panda" { 2 } else { 1 };
            let count = after - before;
            assert!(
                (1..=most).contains(&count),
                "{name} auto: {count} allocations"
            );
        }
    }
}
