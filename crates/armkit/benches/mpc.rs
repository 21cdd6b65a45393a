//! One MPC step (re-linearise, update the QP in place, solve) on the
//! flexible-beam gantry9, `N = 10`, `M = 1` and `M = 5`, with each QP
//! backend compiled in: the active-set solver (the default), Clarabel, and
//! OSQP with `--features osqp`.
//!
//! The step is measured at the states of a recorded closed-loop run of seed
//! 000's Example 1 (the planner is reset to each recorded `(q, v_old)` in
//! turn), so the QP has the active constraints of a real motion. Besides
//! criterion's estimates, a percentile pass prints the median and p99 of the
//! whole step and of the backend's solve alone.
//!
//! Run: `cargo bench -p armkit --bench mpc [--features osqp]`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use armkit::mpc::qp::QpSolverKind;
use armkit::mpc::scenario::simulate;
use armkit::mpc::{MpcOptions, MpcPlanner};
use armkit::study::Seed000Example;
use criterion::{criterion_group, criterion_main, Criterion};

/// The recorded states `(q, v_old)` of Example 1 with control horizon `m`.
fn states(m: usize) -> Vec<(Vec<f64>, Vec<f64>)> {
    let example = Seed000Example::LargeMove;
    let model = Seed000Example::model().unwrap();
    let options = MpcOptions {
        control_horizon: m,
        ..example.options()
    };
    let run = simulate(
        &model,
        options,
        &example.start(),
        &example.target(),
        &example.simulation(),
    )
    .unwrap();
    let mut previous = vec![0.0; 9];
    run.samples
        .iter()
        .map(|s| {
            let state = (s.q.clone(), previous.clone());
            previous = s.velocity.clone();
            state
        })
        .collect()
}

fn planner(m: usize, solver: QpSolverKind) -> MpcPlanner {
    let example = Seed000Example::LargeMove;
    let options = MpcOptions {
        control_horizon: m,
        solver,
        ..example.options()
    };
    assert_eq!(options.reach, armkit::mpc::ReachAid::Off);
    let mut planner = MpcPlanner::new(&Seed000Example::model().unwrap(), options).unwrap();
    planner.set_target(&example.target()).unwrap();
    planner
}

fn percentile(sorted: &[Duration], p: f64) -> Duration {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn bench_mpc(c: &mut Criterion) {
    for m in [1, 5] {
        let states = states(m);
        for &solver in QpSolverKind::available() {
            let mut planner = planner(m, solver);
            let name = format!("mpc_step/gantry9-flex/N10_M{m}/{}", solver.name());
            let mut k = 0;
            c.bench_function(&name, |b| {
                b.iter(|| {
                    let (q, v) = &states[k % states.len()];
                    k += 1;
                    planner.reset(v).unwrap();
                    black_box(planner.step(black_box(q)).unwrap().velocity[0]);
                })
            });
            // Percentiles over every state, 20 passes.
            let mut step_times = Vec::new();
            let mut solve_times = Vec::new();
            let mut iterations = 0u64;
            for _ in 0..20 {
                for (q, v) in &states {
                    planner.reset(v).unwrap();
                    let started = Instant::now();
                    let report = planner.step(q).unwrap();
                    step_times.push(started.elapsed());
                    solve_times.push(report.solve_time);
                    iterations += u64::from(report.qp.iterations);
                }
            }
            step_times.sort();
            solve_times.sort();
            println!(
                "{name}: step median {:?} p99 {:?}; {} solve median {:?} p99 {:?}; {:.1} iterations per solve ({} samples, {} fallback solves)",
                percentile(&step_times, 0.5),
                percentile(&step_times, 0.99),
                solver.name(),
                percentile(&solve_times, 0.5),
                percentile(&solve_times, 0.99),
                iterations as f64 / step_times.len() as f64,
                step_times.len(),
                planner.fallback_solves()
            );
        }
    }
}

criterion_group!(benches, bench_mpc);
criterion_main!(benches);
