//! Scenario method tables (`[mpc]`, `[redundancy]`, ...) built from the
//! bytes: keys of the method with values from the edges of the checks;
//! parse and validate, never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::cli_checks::scenario_tables(data);
});
