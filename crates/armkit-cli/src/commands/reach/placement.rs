//! `armkit reach --base-placements TASK.json`: inverse reachability, the
//! base placements on a floor grid from which the built map reaches every
//! task pose (`armkit::reach::base_placements`).

use armkit::math::{Pose, UnitQuaternion, Vector3};
use armkit::reach::{base_placements, BasePlacement, FloorGrid, ReachMap};
use nalgebra::Quaternion;

use crate::common::{CliError, CliResult};

/// Placements printed in the text summary (JSON lists them all).
const SHOWN: usize = 10;

/// The task poses of `text` (world frame): a JSON list whose items are
/// 4 x 4 row-major transforms (lists of 4 rows) or 7-number rows
/// `[x, y, z, qw, qx, qy, qz]` (m, a non-zero quaternion, normalized).
pub fn read_task(text: &str, path: &str) -> CliResult<Vec<Pose>> {
    let items: Vec<serde_json::Value> = serde_json::from_str(text).map_err(|e| {
        CliError(format!(
            "{path}: a task is a JSON list of 4 x 4 transforms or [x, y, z, qw, qx, qy, qz] rows: {e}"
        ))
    })?;
    let bad = |i: usize, why: &str| CliError(format!("{path}: task pose {i} {why}"));
    let mut poses = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        if let Ok(rows) = serde_json::from_value::<[[f64; 4]; 4]>(item.clone()) {
            poses.push(Pose::from_rows(&rows).map_err(|why| bad(i, &why))?);
        } else if let Ok(v) = serde_json::from_value::<[f64; 7]>(item.clone()) {
            let q = Quaternion::new(v[3], v[4], v[5], v[6]);
            if !(q.norm() > 1e-12 && q.norm().is_finite()) {
                return Err(bad(i, "has a zero or non-finite quaternion"));
            }
            let rotation = UnitQuaternion::from_quaternion(q).to_rotation_matrix();
            poses.push(Pose::new(
                rotation.into_inner(),
                Vector3::new(v[0], v[1], v[2]),
            ));
        } else {
            return Err(bad(
                i,
                "is neither a 4 x 4 transform nor [x, y, z, qw, qx, qy, qz]",
            ));
        }
    }
    Ok(poses)
}

/// The placements for the task in `path` on `floor`.
pub fn placements(
    map: &ReachMap,
    path: &std::path::Path,
    floor: &FloorGrid,
) -> CliResult<Vec<BasePlacement>> {
    let name = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|e| CliError(format!("cannot read {name}: {e}")))?;
    let task = read_task(&text, &name)?;
    Ok(base_placements(map, &task, floor)?)
}

/// The placements as JSON rows.
pub fn json(found: &[BasePlacement]) -> serde_json::Value {
    serde_json::Value::Array(
        found
            .iter()
            .map(|p| serde_json::json!({"x": p.x, "y": p.y, "z": p.z, "yaw": p.yaw, "score": p.score}))
            .collect(),
    )
}

/// Prints the best placements.
pub fn print(found: &[BasePlacement]) {
    println!(
        "base placements reaching every task pose: {} (best {} shown; x, y, z m, yaw rad, mean capability)",
        found.len(),
        found.len().min(SHOWN)
    );
    for p in found.iter().take(SHOWN) {
        println!(
            "  x {:.3} y {:.3} z {:.3} yaw {:.3} score {:.4}",
            p.x, p.y, p.z, p.yaw, p.score
        );
    }
}
