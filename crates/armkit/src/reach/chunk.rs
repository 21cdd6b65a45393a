//! One deterministic piece of a map: a range of position cells (inverse
//! kinematics builder) or of sample indices (forward-sampling builder).

use std::ops::Range;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::oracle::{sample_configuration, PoseOracle};
use super::{Builder, MapLayout};
use crate::error::{Error, Result};
use crate::kinematics::{jacobian, Data, JacobianFrame};
use crate::math::{Pose, Vector3};
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
/// A whole map's arrays as one IK-builder chunk over every cell rebuild the
/// map with [`super::ReachMap::from_chunks`] (loading a saved map).
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
/// thread: every IK solve starts from the model's neutral configuration,
/// numeric restarts are seeded and have no time budget; sample `s` draws
/// from stream `s` of a ChaCha8 generator seeded with the spec's seed).
///
/// Errors: a chunk beyond the layout's cells, or a model that fails the
/// solvers' set-up.
pub fn build_chunk(model: &Model, layout: &MapLayout, chunk: &Chunk) -> Result<ChunkResult> {
    match layout.spec().builder {
        Builder::InverseKinematics => by_inverse_kinematics(model, layout, chunk.cells.clone()),
        Builder::ForwardSampling { samples, seed } => {
            if chunk.samples.end > samples || chunk.samples.start > chunk.samples.end {
                return Err(Error::invalid_argument(
                    "chunk",
                    format!(
                        "samples {:?} are not within the spec's 0..{samples}",
                        chunk.samples
                    ),
                ));
            }
            by_sampling(model, layout, chunk.samples.clone(), seed)
        }
    }
}

fn by_inverse_kinematics(
    model: &Model,
    layout: &MapLayout,
    cells: Range<usize>,
) -> Result<ChunkResult> {
    layout.check_cells("chunk", &cells)?;
    let orientations = layout.orientation_count();
    let bins = cells.len() * orientations;
    let mut result = ChunkResult {
        cells: cells.clone(),
        samples: 0..0,
        reachable: vec![0; bins],
        solutions: vec![0; bins],
        manipulability: vec![0.0; cells.len()],
        ..ChunkResult::default()
    };
    let rotations: Vec<_> = (0..orientations)
        .map(|k| layout.orientation(k).into_inner())
        .collect();
    let mut oracle = PoseOracle::new(model, layout.spec().target)?;
    for (local, cell) in cells.enumerate() {
        let centre = Vector3::from(layout.cell_center(cell));
        // A cell whose centre is beyond the reach bound (by more than the
        // bound's margin) has no reachable orientation: no solve.
        if oracle.beyond_reach(&centre) {
            continue;
        }
        let mut best = 0.0f64;
        for (k, rotation) in rotations.iter().enumerate() {
            let target = Pose {
                rotation: *rotation,
                translation: centre,
            };
            let found = oracle.decide(&target)?;
            result.calls += 1;
            if found.solutions > 0 {
                let bin = local * orientations + k;
                result.reachable[bin] = 1;
                result.solutions[bin] = found.solutions.min(255) as u8;
                best = best.max(found.manipulability);
            }
        }
        result.manipulability[local] = best;
    }
    Ok(result)
}

fn by_sampling(
    model: &Model,
    layout: &MapLayout,
    samples: Range<u64>,
    seed: u64,
) -> Result<ChunkResult> {
    let orientations = layout.orientation_count() as u64;
    let mut data = Data::new(model);
    let mut q = vec![0.0; model.dof()];
    let mut hits: Vec<(u64, f64)> =
        Vec::with_capacity(((samples.end - samples.start) / 4) as usize + 1);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for s in samples.clone() {
        rng.set_stream(s);
        rng.set_word_pos(0);
        sample_configuration(model, &mut rng, &mut q);
        let measure =
            crate::linalg::manipulability(jacobian(model, &mut data, &q, JacobianFrame::World)?);
        let pose = data.end_effector_pose();
        let p = pose.translation;
        if let Some(cell) = layout.cell_of([p.x, p.y, p.z]) {
            let k = layout.orientation_of(&pose.rotation) as u64;
            hits.push((cell as u64 * orientations + k, measure));
        }
    }
    hits.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.total_cmp(&a.1)));
    // Sorted by bin, best manipulability first: the first of each bin wins.
    hits.dedup_by_key(|h| h.0);
    Ok(ChunkResult {
        cells: 0..0,
        samples: samples.clone(),
        hits: hits.iter().map(|h| h.0).collect(),
        hit_manipulability: hits.iter().map(|h| h.1).collect(),
        calls: samples.end - samples.start,
        ..ChunkResult::default()
    })
}
