//! The error a rigid-beam model makes along the gantry's beam (`armkit beam error-along-beam`).

use armkit::beam::{CarriageDeflection, GantryBeam, SimplySupportedBeam, TwoCarriageBeam};
use armkit::kinematics::{forward_kinematics, Data};
use armkit::math::Vector3;
use armkit::robots;

use super::LoadArgs;
use crate::common::{parse_joint_positions, CliError, CliResult, LimitPolicy};
use crate::plot::Figure;

/// One sample of the sweep: carriage position and what the rigid model misses.
pub struct ErrorSample {
    pub(super) d2: f64,
    pub(super) deflection: f64,
    pub(super) error: Vector3<f64>,
    pub(super) two_arm_deflection: f64,
}

/// Most carriage positions one sweep takes (each is a kinematics solve and
/// a row of the CSV and the figure).
pub const MAX_SAMPLES: usize = 100_000;

pub(super) fn error_along_beam(
    load: LoadArgs,
    count: usize,
    q_text: Option<&str>,
) -> CliResult<Vec<ErrorSample>> {
    if !(2..=MAX_SAMPLES).contains(&count) {
        return Err(CliError(format!(
            "--samples: expected 2..={MAX_SAMPLES}, got {count}"
        )));
    }
    let beam = SimplySupportedBeam::seed000();
    let carriage = CarriageDeflection::from_mass(beam, load.mass, load.gravity)?;
    let rigid = robots::gantry9_with_beam(&GantryBeam::Rigid)?;
    let flex = robots::gantry9_with_beam(&GantryBeam::Flexible(carriage))?;
    let two_arm = TwoCarriageBeam::new(beam, [carriage.force, carriage.force])?;
    let mut q = match q_text {
        Some(text) => parse_joint_positions(text, &rigid, LimitPolicy::Enforce)?,
        None => rigid.neutral_configuration(),
    };
    let limits = rigid.joints()[1].limits;
    let (mut rigid_data, mut flex_data) = (Data::new(&rigid), Data::new(&flex));
    (0..count)
        .map(|k| {
            let d2 = limits.lower + (limits.upper - limits.lower) * k as f64 / (count - 1) as f64;
            q[1] = d2;
            let truth = forward_kinematics(&flex, &mut flex_data, &q)?.translation;
            let assumed = forward_kinematics(&rigid, &mut rigid_data, &q)?.translation;
            // The second arm of the two-arm gantry mirrored about mid-span.
            let mirror = beam.length() - d2;
            Ok(ErrorSample {
                d2,
                deflection: carriage.deflection_and_slope(d2).0,
                error: truth - assumed,
                two_arm_deflection: two_arm.deflections([d2, mirror])?[0],
            })
        })
        .collect()
}

/// The error-along-beam figure: the end-effector error of a rigid-beam
/// model (mm) against the carriage position d2 (m).
pub fn error_along_beam_figure(samples: &[ErrorSample]) -> Figure {
    let x: Vec<f64> = samples.iter().map(|s| s.d2).collect();
    let millimetres = |f: fn(&ErrorSample) -> f64| samples.iter().map(|s| 1e3 * f(s)).collect();
    Figure::new(
        "End-effector error of a rigid-beam model (gantry9, seed 000 beam)",
        "carriage position d2 (m)",
        "error (mm)",
        x,
    )
    .with_series("|error|, one arm (mm)", millimetres(|s| s.error.norm()))
    .with_series(
        "deflection w(d2) at the carriage (mm)",
        millimetres(|s| s.deflection),
    )
    .with_series(
        "deflection with a second arm at L - d2 (mm)",
        millimetres(|s| s.two_arm_deflection),
    )
}

/// The sweep in metres, every component: what `error-along-beam` writes.
pub(super) fn error_along_beam_csv(samples: &[ErrorSample]) -> String {
    let mut csv = String::from(
        "d2_m,deflection_m,error_x_m,error_y_m,error_z_m,error_norm_m,deflection_two_arm_mirrored_m\n",
    );
    for s in samples {
        csv += &format!(
            "{},{},{},{},{},{},{}\n",
            s.d2,
            s.deflection,
            s.error.x,
            s.error.y,
            s.error.z,
            s.error.norm(),
            s.two_arm_deflection
        );
    }
    csv
}

pub(super) fn worst_sample(samples: &[ErrorSample]) -> CliResult<&ErrorSample> {
    samples
        .iter()
        .max_by(|a, b| a.error.norm().total_cmp(&b.error.norm()))
        .ok_or_else(|| CliError("no samples".into()))
}
