//! `armkit dynamics` on a command line built from the bytes (a robot,
//! then options with values at the edges of their checks); never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::command_checks::dynamics_command(data);
});
