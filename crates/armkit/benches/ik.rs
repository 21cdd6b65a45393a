//! Criterion benchmarks of the ik module: one full solve (Levenberg-Marquardt
//! from mid-range, cycling through 64 of the benchmark's random reachable
//! targets), one iteration (a solve capped at 1 iteration: the initial
//! FK + Jacobian, one step, the trial FK + Jacobian), the step's linear
//! algebra alone, the closed-form solvers, the analytic solvers (every
//! solution, FK-checked, wrapped into the limits and sorted) and the
//! automatic route.
//!
//! Run: `cargo bench -p armkit --bench ik` (`-- analytic` for the analytic ones).

use std::hint::black_box;

use armkit::ik::analytic::{
    AnalyticOptions, AnalyticSolver, Parameter, Representatives, Verification,
};
use armkit::ik::closed_form::{arm4_solutions, SphericalWristSolver};
use armkit::ik::AutoSolver;
use armkit::ik::{
    benchmark_targets, damped_least_squares_step, singularity_robust_step, ChiaveriniFilter,
    IkOptions, IkSolver,
};
use armkit::kinematics::{jacobian, Data, JacobianFrame};
use armkit::math::Vector6;
use armkit::Model;
use criterion::{criterion_group, criterion_main, Criterion};

fn bench_numeric(c: &mut Criterion, name: &str) {
    let model = armkit::robots::by_name(name).unwrap();
    let targets = benchmark_targets(&model, 64, 42).unwrap();
    let start = model.neutral_configuration();
    let mut solver = IkSolver::new(&model, IkOptions::default()).unwrap();
    let mut k = 0;
    c.bench_function(&format!("ik/solve/lm/{name}"), |b| {
        b.iter(|| {
            k = (k + 1) % targets.len();
            black_box(solver.solve(&targets[k].1, &start).unwrap());
        })
    });
    let one = IkOptions {
        max_iterations: 1,
        max_restarts: 0,
        ..IkOptions::default()
    };
    let mut single = IkSolver::new(&model, one).unwrap();
    c.bench_function(&format!("ik/one_iteration/lm/{name}"), |b| {
        b.iter(|| {
            k = (k + 1) % targets.len();
            black_box(single.solve(&targets[k].1, &start).unwrap());
        })
    });
    let mut data = Data::new(&model);
    let j = jacobian(&model, &mut data, &targets[0].0, JacobianFrame::World)
        .unwrap()
        .clone();
    let e = Vector6::new(0.01, -0.02, 0.005, 0.03, 0.0, -0.01);
    let mut step = vec![0.0; model.dof()];
    c.bench_function(&format!("ik/dls_step/{name}"), |b| {
        b.iter(|| damped_least_squares_step(black_box(&j), &e, 1e-3, &mut step).unwrap())
    });
    let filter = ChiaveriniFilter::default();
    c.bench_function(&format!("ik/sri_step/{name}"), |b| {
        b.iter(|| singularity_robust_step(black_box(&j), &e, &filter, &mut step).unwrap())
    });
}

fn bench_closed_form(c: &mut Criterion) {
    let model = armkit::robots::by_name("puma560").unwrap();
    let targets = benchmark_targets(&model, 64, 42).unwrap();
    let solver = SphericalWristSolver::new(&model).unwrap();
    let start = model.neutral_configuration();
    let mut k = 0;
    c.bench_function("ik/closed_form/puma560", |b| {
        b.iter(|| {
            k = (k + 1) % targets.len();
            black_box(solver.solve(&targets[k].1, &start).unwrap());
        })
    });
    let arm4 = armkit::robots::by_name("arm4").unwrap();
    let targets = benchmark_targets(&arm4, 64, 42).unwrap();
    let start = arm4.neutral_configuration();
    c.bench_function("ik/closed_form/arm4_exact", |b| {
        b.iter(|| {
            k = (k + 1) % targets.len();
            black_box(arm4_solutions(&arm4, &targets[k].1, &start).unwrap());
        })
    });
}

fn urdf(file: &str, edit: &dyn Fn(String) -> String) -> Model {
    let path = format!(
        "{}/../../tests/data/urdf/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = edit(std::fs::read_to_string(path).unwrap());
    let selection = armkit::urdf::ChainSelection::between("base_link", "tool0");
    armkit::urdf::parse_str(&text, file, &selection).unwrap()
}

/// The iiwa14 URDF without its 0.436 mm shoulder and elbow offsets.
fn ideal_iiwa14() -> Model {
    urdf("iiwa14.urdf", &|t| {
        t.replace("xyz=\"-0.00043624 0 0.36\"", "xyz=\"0 0 0.36\"")
            .replace("xyz=\"0.00043624 0 0.42\"", "xyz=\"0 0 0.42\"")
    })
}

/// Lines (point, axis) at zero configuration of an arm whose axes 5 and 6
/// meet and whose other consecutive axes are skew.
const ONE_PAIR: [([f64; 3], [f64; 3]); 6] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.1, 0.05, 0.4], [0.3, 0.9, 0.3]),
    ([0.5, -0.1, 0.6], [-0.2, 0.8, 0.55]),
    ([0.8, 0.1, 0.55], [0.9, 0.2, -0.4]),
    ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
    ([1.0, 0.0, 0.5], [0.85, -0.2, 0.5]),
];

/// Lines of an arm whose axes 2 and 3 are parallel (both along y) and whose
/// other consecutive axes are skew (the parallel-pair 1-D search class).
const PARALLEL_PAIR: [([f64; 3], [f64; 3]); 6] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.1, 0.05, 0.4], [0.0, 1.0, 0.0]),
    ([0.5, -0.1, 0.6], [0.0, 1.0, 0.0]),
    ([0.8, 0.1, 0.55], [0.9, 0.2, -0.4]),
    ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
    ([1.1, 0.1, 0.45], [0.85, -0.2, 0.5]),
];

/// Lines of an arm whose axes 1 and 2 are parallel (both along z) and whose
/// other consecutive axes are skew (the end parallel-pair 1-D search class;
/// the lines of `end_parallel_pair`'s doc example).
const PARALLEL_PAIR_1_2: [([f64; 3], [f64; 3]); 6] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.3, 0.05, 0.4], [0.0, 0.0, 1.0]),
    ([0.5, -0.1, 0.6], [0.3, 0.9, 0.3]),
    ([0.8, 0.1, 0.55], [0.9, 0.2, -0.4]),
    ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
    ([1.1, 0.1, 0.45], [0.85, -0.2, 0.5]),
];

/// Lines of a 6R arm whose only special pair is axes 3-4 meeting.
const PAIR_3_4: [([f64; 3], [f64; 3]); 6] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.1, 0.05, 0.4], [0.3, 0.9, 0.3]),
    ([0.5, -0.1, 0.6], [-0.2, 0.8, 0.55]),
    ([0.5, -0.1, 0.6], [0.9, 0.2, -0.4]),
    ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
    ([1.1, 0.1, 0.45], [0.85, -0.2, 0.5]),
];

/// Lines of a general 6R arm (no consecutive axes meet or are parallel).
const GENERAL: [([f64; 3], [f64; 3]); 6] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.1, 0.05, 0.4], [0.3, 0.9, 0.3]),
    ([0.5, -0.1, 0.6], [-0.2, 0.8, 0.55]),
    ([0.8, 0.1, 0.55], [0.9, 0.2, -0.4]),
    ([1.0, 0.0, 0.5], [0.1, 0.95, 0.3]),
    ([1.1, 0.1, 0.45], [0.85, -0.2, 0.5]),
];

/// Lines of a spherical-wrist arm with a shoulder offset (KUKA KR-type:
/// vertical axis 1, shoulder 2 offset 0.35 m forward and 0.1 m sideways,
/// skew to axis 1, elbow 3 parallel to 2, wrist 4-5-6 meeting), as in the
/// `ik_analytic` test of that name.
const SHOULDER_OFFSET: [([f64; 3], [f64; 3]); 6] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.35, 0.1, 0.675], [0.0, 1.0, 0.0]),
    ([0.35, 0.1, 1.825], [0.0, 1.0, 0.0]),
    ([0.35, 0.0, 1.86], [1.0, 0.0, 0.0]),
    ([1.55, 0.0, 1.86], [0.0, 1.0, 0.0]),
    ([1.55, 0.0, 1.86], [1.0, 0.0, 0.0]),
];

/// A model from lines at zero configuration, revolute joints in [-pi, pi].
fn lines_model(name: &str, lines: &[([f64; 3], [f64; 3]); 6]) -> Model {
    use armkit::math::{Pose, Vector3};
    use armkit::model::{JointSpec, ModelBuilder};
    use std::f64::consts::PI;
    let mut builder = ModelBuilder::new(name);
    let mut previous = Vector3::zeros();
    for (i, (c, h)) in lines.iter().enumerate() {
        let c = Vector3::from(*c);
        builder = builder.joint(
            JointSpec::revolute(format!("q{}", i + 1), -PI, PI)
                .with_origin(Pose::from_translation(c - previous))
                .with_axis(Vector3::from(*h).normalize()),
        );
        previous = c;
    }
    builder
        .fixed(Pose::from_translation(Vector3::new(0.15, 0.0, 0.0)))
        .build()
        .unwrap()
}

fn bench_analytic_solver(
    c: &mut Criterion,
    label: &str,
    model: &Model,
    mut solver: AnalyticSolver,
) {
    let targets = benchmark_targets(model, 64, 42).unwrap();
    let start = model.neutral_configuration();
    let mut k = 0;
    c.bench_function(&format!("ik/analytic/{label}"), |b| {
        b.iter(|| {
            k = (k + 1) % targets.len();
            black_box(solver.solve(&targets[k].1, &start).unwrap().len());
        })
    });
}

fn bench_analytic(c: &mut Criterion) {
    let nearest = AnalyticOptions {
        representatives: Representatives::Nearest,
        ..AnalyticOptions::default()
    };
    let every = AnalyticOptions::default();
    let ur5 = armkit::robots::by_name("ur5").unwrap();
    let ur5_urdf = urdf("ur5.urdf", &|t| t);
    for (label, model) in [
        ("ur5", &ur5),
        ("ur5_urdf", &ur5_urdf),
        ("puma560", &armkit::robots::by_name("puma560").unwrap()),
        ("stanford", &armkit::robots::by_name("stanford").unwrap()),
    ] {
        let solver = AnalyticSolver::new(model, nearest).unwrap();
        bench_analytic_solver(c, &format!("{label}/distinct"), model, solver);
    }
    let solver = AnalyticSolver::new(&ur5, every).unwrap();
    bench_analytic_solver(c, "ur5/every_representative", &ur5, solver);
    // The default options: every representative in the limits, FK-checked.
    let puma = armkit::robots::by_name("puma560").unwrap();
    let solver = AnalyticSolver::new(&puma, every).unwrap();
    bench_analytic_solver(c, "puma560/every_representative", &puma, solver);
    // Fit from the subproblems' own flags, no FK check (IK-Geo's measure).
    let unchecked = AnalyticOptions {
        verification: Verification::Subproblems,
        ..nearest
    };
    for name in ["ur5", "puma560", "stanford"] {
        let model = armkit::robots::by_name(name).unwrap();
        let solver = AnalyticSolver::new(&model, unchecked).unwrap();
        bench_analytic_solver(c, &format!("{name}/distinct_unchecked"), &model, solver);
    }
    // A spherical wrist behind a skew shoulder offset (parallel 2-3).
    let offset = lines_model("shoulder_offset", &SHOULDER_OFFSET);
    for (label, options) in [("distinct", nearest), ("distinct_unchecked", unchecked)] {
        let solver = AnalyticSolver::new(&offset, options).unwrap();
        assert_eq!(solver.class().as_str(), "spherical_wrist_parallel_2_3");
        bench_analytic_solver(c, &format!("shoulder_offset/{label}"), &offset, solver);
    }
    let iiwa = ideal_iiwa14();
    let solver =
        AnalyticSolver::with_parameter(&iiwa, nearest, Parameter::ElbowAngle(0.3)).unwrap();
    bench_analytic_solver(c, "iiwa14_ideal_elbow_angle/distinct", &iiwa, solver);
    let solver =
        AnalyticSolver::with_parameter(&iiwa, unchecked, Parameter::ElbowAngle(0.3)).unwrap();
    bench_analytic_solver(
        c,
        "iiwa14_ideal_elbow_angle/distinct_unchecked",
        &iiwa,
        solver,
    );
    let panda = armkit::robots::by_name("panda").unwrap();
    let held = Parameter::FixedJoint {
        joint: 6,
        value: 0.3,
    };
    let solver = AnalyticSolver::with_parameter(&panda, nearest, held).unwrap();
    bench_analytic_solver(c, "panda_q7_held/distinct", &panda, solver);
    // A spherical wrist behind three general axes (subproblem 5 in closed
    // form): the iiwa14 URDF (0.436 mm offsets) with joint 3 held.
    let iiwa_urdf = urdf("iiwa14.urdf", &|t| t);
    let held = Parameter::FixedJoint {
        joint: 2,
        value: 0.4,
    };
    for (label, options) in [("distinct", nearest), ("distinct_unchecked", unchecked)] {
        let solver = AnalyticSolver::with_parameter(&iiwa_urdf, options, held).unwrap();
        bench_analytic_solver(
            c,
            &format!("iiwa14_urdf_q3_held_general_axes/{label}"),
            &iiwa_urdf,
            solver,
        );
    }
    // The arms without a closed form, by elimination: one pair (axes 5-6
    // or 3-4 meet), parallel axes 2-3 or 1-2, the rest general; a general
    // 6R arm.
    let cases = [
        ("one_pair_5_6", &ONE_PAIR, "one_pair_intersecting_5_6"),
        ("one_pair_3_4", &PAIR_3_4, "one_pair_intersecting_3_4"),
        ("parallel_pair_2_3", &PARALLEL_PAIR, "one_pair_parallel_2_3"),
        (
            "parallel_pair_1_2",
            &PARALLEL_PAIR_1_2,
            "one_pair_parallel_1_2",
        ),
        ("general_6r", &GENERAL, "general_6r"),
    ];
    for (label, lines, class) in cases {
        let model = lines_model(label, lines);
        let solver = AnalyticSolver::new(&model, nearest).unwrap();
        assert_eq!(solver.class().as_str(), class);
        bench_analytic_solver(c, &format!("{label}_elimination/distinct"), &model, solver);
    }
    for name in ["ur5", "panda"] {
        let model = armkit::robots::by_name(name).unwrap();
        let targets = benchmark_targets(&model, 64, 42).unwrap();
        let start = model.neutral_configuration();
        let mut solver = AutoSolver::new(&model, IkOptions::default()).unwrap();
        let mut k = 0;
        c.bench_function(&format!("ik/auto/{name}"), |b| {
            b.iter(|| {
                k = (k + 1) % targets.len();
                black_box(solver.solve(&targets[k].1, &start).unwrap());
            })
        });
    }
}

/// A fixed arm of the three-parallel class without an intersecting pair:
/// axes 2-3-4 parallel (alpha 2 = alpha 3 = 0), the others skew (made-up
/// lengths and twists, standard DH).
fn three_parallel_offset_arm() -> Model {
    use armkit::model::{DhConvention, DhLink};
    let table = [
        (0.31, 0.08, 1.1),
        (0.12, 0.52, 0.0),
        (-0.07, 0.44, 0.0),
        (0.21, 0.06, -0.8),
        (0.17, 0.05, 1.3),
        (0.09, 0.0, 0.4),
    ];
    let links = table.map(|(d, a, alpha)| {
        DhLink::revolute(d, a, alpha).with_limits(-std::f64::consts::PI, std::f64::consts::PI)
    });
    Model::from_dh("three-parallel-offset", DhConvention::Standard, &links).unwrap()
}

fn bench_three_parallel_offset(c: &mut Criterion) {
    let model = three_parallel_offset_arm();
    for (label, verification) in [
        ("distinct", Verification::ForwardKinematics),
        ("distinct_unchecked", Verification::Subproblems),
    ] {
        let options = AnalyticOptions {
            representatives: Representatives::Nearest,
            verification,
            ..AnalyticOptions::default()
        };
        let solver = AnalyticSolver::new(&model, options).unwrap();
        assert_eq!(solver.class().as_str(), "three_parallel_2_3_4");
        bench_analytic_solver(c, &format!("three_parallel_offset/{label}"), &model, solver);
    }
}

fn ik(c: &mut Criterion) {
    for name in ["ur5", "panda", "gantry9"] {
        bench_numeric(c, name);
    }
    bench_closed_form(c);
    bench_analytic(c);
    bench_three_parallel_offset(c);
}

criterion_group!(benches, ik);
criterion_main!(benches);
