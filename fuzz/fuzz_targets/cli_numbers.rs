//! The CLI's number lists and poses (`--q`, `--pose`): parse, never panic;
//! what parses is finite, and a pose's rotation is orthonormal.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::cli_checks::cli_numbers(data);
});
