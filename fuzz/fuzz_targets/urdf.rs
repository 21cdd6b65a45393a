//! URDF loader: any text either builds a model or is an `Err`; a model that
//! builds evaluates (FK, Jacobian) without a panic and with finite output.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    armkit_fuzz::armkit_checks::urdf(data);
});
