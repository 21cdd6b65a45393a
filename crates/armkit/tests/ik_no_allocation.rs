//! One IK solve allocates exactly once (the report's joint vector) after
//! `IkSolver::new`, whatever the number of iterations and restarts: the
//! iterations themselves allocate nothing.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use armkit::ik::{benchmark_targets, IkMethod, IkOptions, IkSolver, Redundancy};

struct CountingAllocator;

thread_local! {
    // Per thread: the test harness's own threads allocate at times too.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

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
