//! CSV cells and SVG plots of the space commands.

use armkit::math::Pose;

use crate::common::{CliError, CliResult};
use crate::plot::Figure;

/// `x,y,z,roll,pitch,yaw` CSV cells of a pose.
pub(super) fn pose_cells(pose: &Pose) -> String {
    let (roll, pitch, yaw) = pose.rpy();
    let p = pose.translation;
    format!("{},{},{},{roll},{pitch},{yaw}", p.x, p.y, p.z)
}

pub(super) fn pose_header(prefix: &str) -> String {
    ["x", "y", "z", "roll", "pitch", "yaw"]
        .map(|c| format!("{prefix}_{c}"))
        .join(",")
}

pub(super) fn joint_header(prefix: &str, dof: usize) -> String {
    (1..=dof)
        .map(|j| format!("{prefix}{j}"))
        .collect::<Vec<_>>()
        .join(",")
}

pub(super) fn number_cells(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// Writes each figure as `DIR/NAME.svg` (800 x 450 px).
pub(super) fn write_plots(dir: &std::path::Path, figures: &[(&str, Figure)]) -> CliResult {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError(format!("{}: cannot create: {e}", dir.display())))?;
    for (name, figure) in figures {
        let path = dir.join(format!("{name}.svg"));
        let svg = figure
            .to_svg(800, 450)
            .map_err(|e| CliError(format!("{}: plot: {e}", path.display())))?;
        crate::report::write_text(&path, &svg)?;
    }
    Ok(())
}
