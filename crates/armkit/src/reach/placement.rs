//! Inverse reachability for base placement: the base positions on a floor
//! plane from which every task pose is reachable by a map, scored by the
//! capability index (Zacharias et al., IROS 2007: a base from which the
//! task sits in cells of high capability leaves the most orientations
//! free around it).

use super::ReachMap;
use crate::error::{Error, Result};
use crate::math::{Pose, Vector3};

/// The candidate base placements: a grid over `x` and `y` on the plane
/// `z`, times `yaws` headings about the vertical.
///
/// A placement `(x, y, z, yaw)` puts the robot's base frame (the frame the
/// map was built in) at `Trans(x, y, z) RotZ(yaw)` in the world frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorGrid {
    /// World-frame x range `[lower, upper]` of the base positions, m.
    pub x: [f64; 2],
    /// World-frame y range `[lower, upper]` of the base positions, m.
    pub y: [f64; 2],
    /// Grid step along x and y, m (> 0); the ranges' ends are included
    /// when they fall on the grid.
    pub step: f64,
    /// World-frame height of the base frame's origin, m.
    pub z: f64,
    /// Headings sampled uniformly in `[0, 2 pi)` (at least 1; 1 is yaw 0).
    pub yaws: usize,
}

/// One base placement from which every task pose is reachable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasePlacement {
    /// World-frame x of the base frame's origin, m.
    pub x: f64,
    /// World-frame y of the base frame's origin, m.
    pub y: f64,
    /// World-frame z of the base frame's origin (the grid's plane), m.
    pub z: f64,
    /// Heading of the base frame about the world z axis, rad.
    pub yaw: f64,
    /// Mean capability index of the cells holding the task positions
    /// (seen from this base), in (0, 1].
    pub score: f64,
}

/// Most candidate placements one call examines: keeps a call's time
/// bounded (about a second of queries).
const MAX_PLACEMENTS: usize = 10_000_000;

fn grid_axis(name: &str, range: [f64; 2], step: f64) -> Result<usize> {
    if !(range[0].is_finite() && range[1].is_finite()) || range[1] < range[0] {
        return Err(Error::invalid_argument(
            name,
            format!(
                "the range [{}, {}] must be finite with lower <= upper (metres)",
                range[0], range[1]
            ),
        ));
    }
    // Positions lower + i step up to upper (a hair of rounding allowed).
    Ok(((range[1] - range[0]) / step + 1e-9).floor() as usize + 1)
}

/// The base placements on `floor` from which `map` reaches every pose of
/// `task` (world frame), best score first (ties in grid order: x slowest,
/// then y, then yaw).
///
/// A task pose `T` seen from a base at `B` is `B^-1 T` in the map's frame;
/// it is reachable when [`ReachMap::query`] says so. Allocates the result
/// and one pose per task pose.
///
/// Errors: an empty task, a task pose that is not a finite rigid transform,
/// a floor grid with a non-finite or reversed range, a step that is not
/// finite and > 0, zero yaws, more than ten million placements; and, when
/// no placement reaches every pose, an error saying how many were tried and
/// the most task poses any one of them reached.
pub fn base_placements(
    map: &ReachMap,
    task: &[Pose],
    floor: &FloorGrid,
) -> Result<Vec<BasePlacement>> {
    if task.is_empty() {
        return Err(Error::invalid_argument(
            "task",
            "needs at least one pose to place the base for",
        ));
    }
    for (i, pose) in task.iter().enumerate() {
        pose.check_rigid()
            .map_err(|why| Error::invalid_argument("task", format!("pose {i} {why}")))?;
    }
    crate::error::check_positive("step", floor.step)?;
    if !floor.z.is_finite() {
        return Err(Error::invalid_argument("z", "must be finite (metres)"));
    }
    if floor.yaws == 0 {
        return Err(Error::invalid_argument(
            "yaws",
            "must be at least 1 (1 samples yaw 0)",
        ));
    }
    let nx = grid_axis("x", floor.x, floor.step)?;
    let ny = grid_axis("y", floor.y, floor.step)?;
    let total = (nx as f64) * (ny as f64) * (floor.yaws as f64);
    if total > MAX_PLACEMENTS as f64 {
        return Err(Error::invalid_argument(
            "step",
            format!(
                "{nx} x {ny} positions x {} yaws = {total:e} placements exceed the limit of {MAX_PLACEMENTS}: choose a coarser step, a smaller range or fewer yaws",
                floor.yaws
            ),
        ));
    }
    let mut local = task.to_vec();
    let mut found = Vec::new();
    let mut most = 0usize;
    for ix in 0..nx {
        let x = floor.x[0] + ix as f64 * floor.step;
        for iy in 0..ny {
            let y = floor.y[0] + iy as f64 * floor.step;
            for k in 0..floor.yaws {
                let yaw = std::f64::consts::TAU * k as f64 / floor.yaws as f64;
                let mut base = Pose::rot_z(yaw);
                base.translation = Vector3::new(x, y, floor.z);
                let inverse = base.inverse();
                let mut reached = 0usize;
                let mut score = 0.0;
                for (seen, pose) in local.iter_mut().zip(task) {
                    *seen = &inverse * pose;
                    if !map.query(seen) {
                        break;
                    }
                    reached += 1;
                    let p = seen.translation;
                    score += map.capability_at([p.x, p.y, p.z]);
                }
                most = most.max(reached);
                if reached == task.len() {
                    found.push(BasePlacement {
                        x,
                        y,
                        z: floor.z,
                        yaw,
                        score: score / task.len() as f64,
                    });
                }
            }
        }
    }
    if found.is_empty() {
        return Err(Error::invalid_argument(
            "task",
            format!(
                "no base placement reaches all {} task poses: of the {nx} x {ny} positions x {} yaws tried (x in [{}, {}], y in [{}, {}], z = {} m), the best reached {most} of them",
                task.len(),
                floor.yaws,
                floor.x[0],
                floor.x[1],
                floor.y[0],
                floor.y[1],
                floor.z
            ),
        ));
    }
    // Stable: equal scores keep the grid order.
    found.sort_by(|a, b| b.score.total_cmp(&a.score));
    Ok(found)
}
