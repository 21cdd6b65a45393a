//! Seed 004 singularity tracking timings on space6r (fixed base, and the
//! attitude-held system for the full runs): one velocity-level tracking
//! period (Jacobian, pose error, plain inverse, detection, joint update;
//! composed from the public pieces `PathTracker::run` uses), one
//! Newton-Raphson knot solve inside the singular region (warm-started from
//! the previous knot, as the avoidance does), a full 20 s run (2000
//! periods) per method, and the avoidance on lines missing the singular pose
//! by 3 and 10 mm with the region planned jointly and greedily.
//!
//! Run: `cargo bench -p armkit --bench singularity -- --warm-up-time 1 --measurement-time 3`.

use armkit::ik::{
    damped_least_squares_step, pose_error, IkMethod, IkOptions, IkSolver, NakamuraDamping,
};
use armkit::math::Pose;
use armkit::robots::space6r_free_floating;
use armkit::singularity::{
    detect, seed004_path, AvoidanceOptions, Baselines, DetectionOptions, Manipulator, Method,
    PathTracker, RegionPlan,
};
use armkit::{jacobian, Data, JacobianFrame};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn singularity(c: &mut Criterion) {
    let arm = armkit::robots::space6r().unwrap();
    let manipulator = Manipulator::FixedBase(&arm);
    let line = seed004_path(&manipulator).unwrap();
    let options = AvoidanceOptions::default();
    let tracker = PathTracker::new(manipulator, line.task(20.0, 4.0), options).unwrap();
    let (_, h) = tracker.steps();

    // One tracking period at 8 s (regular, before the region).
    let avoid = tracker.run(&Method::Avoidance { k: 1 }).unwrap();
    let at = |i: usize| -> Vec<f64> { avoid.joint_positions.iter().map(|s| s[i]).collect() };
    let q8 = at(800);
    let target = tracker.trajectory().pose_at(8.0 + h);
    let mut data = Data::new(&arm);
    let mut rates = [0.0; 6];
    let mut step = [0.0; 6];
    let detection = DetectionOptions::default();
    c.bench_function(
        "tracking_period/space6r/fixed (J, error, J^-1, detect, update)",
        |b| {
            b.iter(|| {
                let mut q = [0.0; 6];
                q.copy_from_slice(black_box(&q8));
                jacobian(&arm, &mut data, &q, JacobianFrame::World).unwrap();
                let error = pose_error(black_box(&target), data.end_effector_pose());
                let j = data.jacobian();
                damped_least_squares_step(j, &(error / h), 0.0, &mut rates).unwrap();
                for (s, r) in step.iter_mut().zip(&rates) {
                    *s = r * h;
                }
                let found = detect(j, &step, &detection).unwrap();
                for (qi, r) in q.iter_mut().zip(&rates) {
                    *qi += r * h;
                }
                black_box((found, q))
            })
        },
    );

    // One knot: the planned pose at 10.0 s (the singular pose) from the
    // knot at 9.95 s moved on by the last secant, as the avoidance with
    // k = 5 warm-starts it.
    let knot_options = IkOptions {
        method: IkMethod::NewtonRaphson,
        position_tolerance: options.ik_tolerance,
        orientation_tolerance: options.ik_tolerance,
        max_iterations: options.ik_max_iterations,
        max_restarts: 0,
        time_budget: None,
        ..IkOptions::default()
    };
    let mut solver = IkSolver::new(&arm, knot_options).unwrap();
    let (q_prev, q_last) = (at(990), at(995));
    let warm: Vec<f64> = q_last
        .iter()
        .zip(&q_prev)
        .map(|(a, b)| a + (a - b))
        .collect();
    let singular_pose: Pose = tracker.trajectory().pose_at(10.0);
    let report = solver.solve(&singular_pose, &warm).unwrap();
    assert!(report.converged());
    c.bench_function("knot_ik/space6r/newton_raphson at the singular pose", |b| {
        b.iter(|| {
            solver
                .solve(black_box(&singular_pose), black_box(&warm))
                .unwrap()
        })
    });

    let baselines = Baselines::for_detection(&options.detection);
    let methods = [
        Method::Plain,
        Method::Avoidance { k: 1 },
        Method::Avoidance { k: 5 },
        Method::Avoidance { k: 10 },
        Method::DampedLeastSquares(baselines.nakamura),
        Method::SingularityRobust(baselines.chiaverini),
    ];
    let mut group = c.benchmark_group("run_20s/space6r/fixed");
    group.sample_size(20);
    for method in &methods {
        group.bench_function(method.label(), |b| {
            b.iter(|| tracker.run(black_box(method)).unwrap())
        });
    }
    group.finish();

    let system = space6r_free_floating().unwrap();
    let at_through = Manipulator::AttitudeHeld {
        system: &system,
        base: Pose::identity(),
    };
    let held_line = seed004_path(&at_through).unwrap();
    let held = PathTracker::new(
        Manipulator::AttitudeHeld {
            system: &system,
            base: held_line.base,
        },
        held_line.task(20.0, 4.0),
        options,
    )
    .unwrap();
    let mut group = c.benchmark_group("run_20s/space6r/attitude_held");
    group.sample_size(10);
    for method in [
        Method::Plain,
        Method::Avoidance { k: 5 },
        Method::DampedLeastSquares(NakamuraDamping {
            threshold: options.detection.determinant_threshold,
            max_damping: 0.05,
        }),
    ] {
        group.bench_function(method.label(), |b| {
            b.iter(|| held.run(black_box(&method)).unwrap())
        });
    }
    group.finish();

    // Lines 3 and 10 mm off the singular pose: the avoidance's least-squares
    // knots (the wrist cannot flip within eps_dq per period), the region
    // planned jointly (the cone programs) and greedily.
    let fixed = manipulator;
    for (miss, name) in [(0.003, "fixed_miss_3mm"), (0.01, "fixed_miss_10mm")] {
        let near = armkit::singularity::line_through(
            &fixed,
            &armkit::singularity::SEED004_THROUGH,
            &armkit::singularity::SEED004_DIRECTION,
            miss,
        )
        .unwrap();
        let mut group = c.benchmark_group(format!("run_20s/space6r/{name}"));
        group.sample_size(10);
        let avoidance = Method::Avoidance { k: 1 };
        for plan in [RegionPlan::Joint, RegionPlan::Greedy] {
            let plan_options = AvoidanceOptions {
                region_plan: plan,
                ..options
            };
            let near_miss = PathTracker::new(fixed, near.task(20.0, 4.0), plan_options).unwrap();
            group.bench_function(format!("{} ({plan} plan)", avoidance.label()), |b| {
                b.iter(|| near_miss.run(black_box(&avoidance)).unwrap())
            });
        }
        group.finish();
    }

    // The whole seed 004 study of the demo (threshold calibration, the
    // comparison, the fitted variant and the nine-line miss sweep).
    let mut group = c.benchmark_group("study");
    group.sample_size(10);
    group.bench_function("avoidance_default", |b| {
        b.iter(|| armkit::study::AvoidanceStudy::default().run().unwrap())
    });
    group.finish();
}

criterion_group!(benches, singularity);
criterion_main!(benches);
