//! DH description files, TOML and JSON: the first byte picks the format, the
//! rest is the text. A model that builds evaluates without a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::armkit_checks::description(data);
});
