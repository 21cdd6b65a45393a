//! `armkit ik` on a command line built from the bytes (a robot, then the
//! solvers' and the analytic solver's options with edge values); never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::command_checks::ik_command(data);
});
