//! Checks of the library's input formats (URDF, DH description files) on
//! arbitrary bytes. Each returns normally when armkit behaved (an `Err` is
//! fine); it panics, which the fuzzer reports as a crash, when armkit
//! panicked or built a model that evaluates to non-finite numbers.

use armkit::description::Format;
use armkit::kinematics::{forward_kinematics, jacobian, Data, JacobianFrame};
use armkit::urdf::ChainSelection;
use armkit::Model;

/// A URDF document: `urdf::parse_str` with the default chain selection.
pub fn urdf(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // `urdf::load` reads UTF-8 text: other bytes never reach the parser.
    };
    if let Ok(model) = armkit::urdf::parse_str(text, "<fuzz>", &ChainSelection::default()) {
        evaluate(&model);
    }
}

/// A DH description file, read both as TOML and as JSON.
pub fn description(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    for format in [Format::Toml, Format::Json] {
        if let Ok(model) = armkit::description::parse_str(text, format, "<fuzz>") {
            evaluate(&model);
        }
    }
}

/// A model that loaded is usable: FK and the Jacobian at the neutral
/// configuration and at each finite limit either succeed with finite numbers
/// or return an error; they never panic and never return NaN.
pub fn evaluate(model: &Model) {
    let mut data = Data::new(model);
    let (lower, upper) = model.position_limits();
    let neutral = model.neutral_configuration();
    let at_limit = |limits: &[f64]| -> Vec<f64> {
        limits
            .iter()
            .zip(&neutral)
            .map(|(l, n)| if l.is_finite() { *l } else { *n })
            .collect()
    };
    for q in [neutral.clone(), at_limit(&lower), at_limit(&upper)] {
        if let Ok(pose) = forward_kinematics(model, &mut data, &q) {
            let rows = pose.to_rows();
            assert!(
                rows.iter().flatten().all(|v| v.is_finite()),
                "FK of a loaded model at q = {q:?} is not finite: {rows:?}"
            );
        }
        if let Ok(j) = jacobian(model, &mut data, &q, JacobianFrame::World) {
            assert!(
                j.iter().all(|v| v.is_finite()),
                "the Jacobian of a loaded model at q = {q:?} is not finite: {j}"
            );
        }
    }
}
