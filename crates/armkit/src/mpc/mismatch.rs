//! Planner models that differ from the plant (seed 000, eq 14 and sec 4.5:
//! the incremental model and the feedback correction are what should leave
//! no static error when the model is wrong): a link-length error here; a
//! rigid-beam planner on the bending gantry is `robots::gantry9` against
//! `robots::gantry9_flex`. The closed loop on a different plant is
//! [`super::scenario::simulate_on_plant`].

use crate::error::{Error, Result};
use crate::math::Pose;
use crate::model::{CouplingLaw, Model};

/// `model` with every link length of its DH table scaled by `1 +
/// fraction`: each link's `a` and constant `d` (for a prismatic link the
/// origin of its joint variable), and the tool's offset; angles, limits, the base and the couplings (the beam's
/// deflection) unchanged. The model is named `<name>+5.0%links` (for 0.05).
///
/// Errors (field `link_length_error`): `fraction` not finite or `<= -1`; a
/// model not built from a DH table (a URDF robot: its lengths are not a
/// table's).
///
/// ```
/// use armkit::kinematics::{forward_kinematics, Data};
/// use armkit::model::{DhConvention, DhLink};
/// use armkit::Model;
/// let links = [DhLink::revolute(0.1, 0.5, 0.0), DhLink::revolute(0.0, 0.4, 0.0)];
/// let model = Model::from_dh("two-link", DhConvention::Standard, &links).unwrap();
/// let longer = armkit::mpc::with_link_length_error(&model, 0.05).unwrap();
/// assert_eq!(longer.name(), "two-link+5.0%links");
/// let q = [0.3, -0.7];
/// let p = forward_kinematics(&model, &mut Data::new(&model), &q).unwrap().translation;
/// let p5 = forward_kinematics(&longer, &mut Data::new(&longer), &q).unwrap().translation;
/// assert!((p5 - p * 1.05).norm() < 1e-12); // identity base and tool: every length scales
/// ```
pub fn with_link_length_error(model: &Model, fraction: f64) -> Result<Model> {
    if !(fraction.is_finite() && fraction > -1.0) {
        return Err(Error::invalid_argument(
            "link_length_error",
            format!("must be finite and > -1, got {fraction}"),
        ));
    }
    let (convention, links) = model.dh_table().ok_or_else(|| {
        Error::invalid_argument(
            "link_length_error",
            format!(
                "{} has no DH table to scale (a URDF robot's lengths are not a table's)",
                model.name()
            ),
        )
    })?;
    let scale = 1.0 + fraction;
    let scaled: Vec<_> = links
        .iter()
        .map(|link| {
            let mut link = *link;
            link.a *= scale;
            link.d *= scale;
            link
        })
        .collect();
    let tool = model.tool();
    let tool = Pose::new(tool.rotation, tool.translation * scale);
    let rebuilt = Model::from_dh_with_transforms(
        &format!("{}{:+.1}%links", model.name(), 100.0 * fraction),
        convention,
        &scaled,
        *model.base(),
        tool,
    )?;
    let additive: Vec<_> = model
        .couplings()
        .iter()
        .filter(|c| !matches!(c.law, CouplingLaw::Mimic { .. }))
        .cloned()
        .collect();
    if additive.is_empty() {
        Ok(rebuilt)
    } else {
        rebuilt.with_additive_couplings(additive)
    }
}
