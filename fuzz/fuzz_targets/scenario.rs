//! Scenario files (`armkit run FILE.toml`): parse and validate, never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::cli_checks::scenario(data);
});
