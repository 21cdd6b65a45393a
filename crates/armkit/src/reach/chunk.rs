//! One deterministic piece of a map: a range of position cells (inverse
//! kinematics builder) or of sample indices (forward-sampling builder).

use std::ops::Range;

use super::MapLayout;
use crate::error::{Error, Result};
use crate::model::Model;

/// A piece of a map's work. The inverse-kinematics builder reads `cells`,
/// the forward-sampling builder reads `samples`; the other range is empty.
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
pub struct Chunk {
    /// Position cells (indices into the layout's cells), IK builder.
    pub cells: Range<usize>,
    /// Sample indices, forward-sampling builder.
    pub samples: Range<u64>,
}

/// What one chunk found, as plain arrays (serializable, to cross to and
/// from other processes).
///
/// IK builder: for the chunk's cells, `reachable` and `solutions` per
/// (cell, orientation) in the layout's order (`(cell - cells.start) *
/// orientations + k`), `manipulability` per cell (0 where nothing is
/// reachable). Forward-sampling builder: `hits` holds the distinct bins the
/// samples landed in (`cell * orientations + k`, ascending) and
/// `hit_manipulability` the best manipulability of a sample in each.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
pub struct ChunkResult {
    /// The chunk's position cells (IK builder; empty for sampling).
    pub cells: Range<usize>,
    /// The chunk's sample indices (sampling builder; empty for IK).
    pub samples: Range<u64>,
    /// 1 where the bin's centre pose is reachable within the limits, else 0.
    pub reachable: Vec<u8>,
    /// Distinct IK solutions within the limits per bin (saturating at 255).
    pub solutions: Vec<u8>,
    /// Best manipulability per cell over its reachable bins' solutions.
    pub manipulability: Vec<f64>,
    /// Sampling builder: the distinct bins hit, ascending.
    pub hits: Vec<u64>,
    /// Sampling builder: the best manipulability of a sample in each hit bin.
    pub hit_manipulability: Vec<f64>,
    /// IK solves (or forward-kinematics samples) the chunk took.
    pub calls: u64,
}

/// Computes `chunk` of the map laid out by `layout` for `model`:
/// deterministic (the same chunk gives the same result on any machine and
/// thread).
///
/// Errors: a chunk outside the layout's cells, a model whose joint count
/// differs from the one the layout was made for.
pub fn build_chunk(model: &Model, layout: &MapLayout, chunk: &Chunk) -> Result<ChunkResult> {
    let _ = (model, layout, chunk);
    Err(Error::invalid_argument("chunk", "not built yet"))
}
