//! bench-ik's preemption rule and the thread clock it reads.

use std::time::{Duration, Instant};

use armkit_cli::commands::ik::{preempted, thread_cpu_time};

#[test]
fn a_failed_solve_is_preempted_only_when_its_thread_lacked_the_processor() {
    let ms = Duration::from_millis;
    // Budget reached, thread ran 1 of 6 ms: preempted.
    assert!(preempted(ms(6), Some(ms(1)), 5.0));
    // Budget reached with the processor most of the time: a real failure.
    assert!(!preempted(ms(6), Some(ms(5)), 5.0));
    // Failed before the budget: the solver gave up by itself.
    assert!(!preempted(ms(2), Some(ms(0)), 5.0));
    // No thread clock: never called preempted.
    assert!(!preempted(ms(60), None, 5.0));
}

#[test]
fn the_thread_clock_advances_with_work_and_not_with_sleep() {
    let Some(before) = thread_cpu_time() else {
        return; // a platform without a thread clock
    };
    std::thread::sleep(Duration::from_millis(30));
    let slept = thread_cpu_time().unwrap() - before;
    assert!(
        slept < Duration::from_millis(15),
        "{slept:?} of CPU while asleep"
    );
    let mut x = 1.0f64;
    let busy = Instant::now();
    while busy.elapsed() < Duration::from_millis(30) {
        x = std::hint::black_box(x.sin() + 1.0);
    }
    assert!(thread_cpu_time().unwrap() - before > slept, "{x}");
}
