//! The merged map and its queries.

use super::{ChunkResult, MapLayout};
use crate::error::{Error, Result};
use crate::math::Pose;

/// A reachability map: per (cell, orientation) bin reachable or not and its
/// IK solution count, per cell the capability index and best
/// manipulability (see the module docs for frames and units).
#[derive(Clone, Debug, PartialEq)]
pub struct ReachMap {
    layout: MapLayout,
    reachable: Vec<u8>,
    solutions: Vec<u8>,
    capability: Vec<f64>,
    manipulability: Vec<f64>,
    calls: u64,
}

impl ReachMap {
    /// Merges chunk results (in any order) into a map; bins no chunk covers
    /// stay unreachable. Errors: a chunk whose arrays do not fit the layout.
    pub fn from_chunks(
        layout: MapLayout,
        chunks: impl IntoIterator<Item = ChunkResult>,
    ) -> Result<ReachMap> {
        let _ = chunks;
        let _ = &layout;
        Err(Error::invalid_argument("chunks", "not merged yet"))
    }

    /// The map's layout.
    pub fn layout(&self) -> &MapLayout {
        &self.layout
    }

    /// Per bin (`cell * orientations + k`): 1 reachable, 0 not.
    pub fn reachable(&self) -> &[u8] {
        &self.reachable
    }

    /// Per bin: distinct IK solutions within the limits (0 for maps built by sampling).
    pub fn solutions(&self) -> &[u8] {
        &self.solutions
    }

    /// Per cell: the capability index, the reachable fraction of its orientations, in [0, 1].
    pub fn capability(&self) -> &[f64] {
        &self.capability
    }

    /// Per cell: the best manipulability over its reachable bins (0 where none).
    pub fn manipulability(&self) -> &[f64] {
        &self.manipulability
    }

    /// IK solves (or samples) the build took.
    pub fn calls(&self) -> u64 {
        self.calls
    }

    /// True when `pose` (world frame, m) falls in a reachable bin.
    pub fn query(&self, pose: &Pose) -> bool {
        let p = pose.translation;
        match self.layout.cell_of([p.x, p.y, p.z]) {
            Some(cell) => {
                let k = self.layout.orientation_of(&pose.rotation);
                self.reachable[cell * self.layout.orientation_count() + k] != 0
            }
            None => false,
        }
    }

    /// The capability index of the cell containing `position` (world frame,
    /// m); 0 outside the box.
    pub fn capability_at(&self, position: [f64; 3]) -> f64 {
        self.layout
            .cell_of(position)
            .map_or(0.0, |cell| self.capability[cell])
    }

    /// The reachable cell (capability > 0) whose centre is nearest
    /// `position` (world frame, m); `None` when no cell is reachable.
    pub fn nearest_reachable_cell(&self, position: [f64; 3]) -> Option<usize> {
        let _ = position;
        None
    }
}
