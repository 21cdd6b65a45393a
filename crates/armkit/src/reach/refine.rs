//! Boundary refinement: where, between two neighbouring cell centres that
//! disagree (one reachable, the other not, for the same orientation), the
//! boundary crosses the grid edge, found by bisection with the build's IK
//! oracle; then per bin the signed distance to the boundary
//! ([`ReachMap::boundary`]) that the point query interpolates.
//!
//! Runs after the merge (the whole map's bits are needed to see which
//! edges disagree), in chunks of cells like the build: [`refine_chunk`] is
//! deterministic and [`apply_refinement`] order-independent, so a distributed
//! refinement gives the local one's map.

use std::ops::Range;

use super::oracle::PoseOracle;
use super::parallel::on_threads;
use super::{Boundary, MapLayout, ReachMap, BOUNDARY_UNITS};
use crate::error::{Error, Result};
use crate::math::{Pose, Vector3};
use crate::model::Model;

/// Bins (cells times orientations) per chunk of the local refinement.
const CHUNK_BINS: usize = 20_000;

/// One located crossing of the boundary: on the grid edge from the centre
/// of `bin`'s cell to its neighbour's along `+axis`, same orientation, at
/// `at` (a fraction of the edge, in (0, 1)) from the bin's cell centre.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
pub struct Crossing {
    /// The bin (`cell * orientations + k`) the edge starts from.
    pub bin: u64,
    /// The edge's axis: 0 x, 1 y, 2 z.
    pub axis: u8,
    /// Where the boundary crosses, fraction of the edge from the bin's centre.
    pub at: f32,
}

/// What [`refine_chunk`] found over a range of cells.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize, serde::Deserialize))]
pub struct Refinement {
    /// The cells whose `+axis` edges were examined.
    pub cells: Range<usize>,
    /// The crossings on the disagreeing edges.
    pub crossings: Vec<Crossing>,
    /// IK solves taken.
    pub calls: u64,
}

/// The bisection steps of `map`'s spec (none for [`Boundary::Cells`]).
fn steps_of(map: &ReachMap) -> Option<u8> {
    match map.layout().spec().boundary {
        Boundary::Cells => None,
        Boundary::Bisection { steps } => Some(steps),
    }
}

/// Locates the boundary on every disagreeing `+axis` edge leaving `cells`
/// (the edge to the last cell of a row has no neighbour beyond it: none),
/// by the spec's bisection steps: each step decides the pose at the
/// midpoint of the interval known to hold the crossing (the edge's
/// orientation, its position on the segment between the centres) with the
/// build's oracle and keeps the half whose ends disagree. Deterministic.
///
/// Errors: `cells` beyond the layout, a model that fails the solvers'
/// set-up (it must be the map's model).
pub fn refine_chunk(model: &Model, map: &ReachMap, cells: Range<usize>) -> Result<Refinement> {
    let layout = map.layout();
    layout.check_cells("cells", &cells)?;
    let mut result = Refinement {
        cells: cells.clone(),
        ..Refinement::default()
    };
    let Some(steps) = steps_of(map) else {
        return Ok(result);
    };
    let (dims, r) = (layout.dims(), layout.resolution());
    let strides = [dims[1] * dims[2], dims[2], 1];
    let orientations = layout.orientation_count();
    let reachable = map.reachable();
    let mut oracle = PoseOracle::new(model, layout.spec().target)?;
    let rotations: Vec<_> = (0..orientations)
        .map(|k| layout.orientation(k).into_inner())
        .collect();
    for cell in cells {
        let ijk = layout.cell_coordinates(cell);
        let centre = Vector3::from(layout.cell_center(cell));
        for axis in 0..3 {
            if ijk[axis] + 1 >= dims[axis] {
                continue;
            }
            let neighbour = cell + strides[axis];
            for (k, rotation) in rotations.iter().enumerate() {
                let (a, b) = (cell * orientations + k, neighbour * orientations + k);
                let inside = reachable[a] != 0;
                if inside == (reachable[b] != 0) {
                    continue;
                }
                let (mut lo, mut hi) = (0.0f64, 1.0f64);
                for _ in 0..steps {
                    let mid = 0.5 * (lo + hi);
                    let mut translation = centre;
                    translation[axis] += mid * r;
                    let pose = Pose {
                        rotation: *rotation,
                        translation,
                    };
                    let found = oracle.decide(&pose)?.solutions > 0;
                    result.calls += 1;
                    if found == inside {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                result.crossings.push(Crossing {
                    bin: a as u64,
                    axis: axis as u8,
                    at: (0.5 * (lo + hi)) as f32,
                });
            }
        }
    }
    Ok(result)
}

/// `map` with the boundary distances of `parts` (any order, any
/// partition): per bin and axis the nearer crossing `d_a` on its two edges
/// (in cells), the distance `1 / sqrt(sum 1 / d_a^2)` to the plane through
/// them, at most one cell, in units of 1 / [`BOUNDARY_UNITS`] (at least
/// one unit), signed positive where the bin is reachable; bins without a
/// crossing keep one cell. The parts' calls are added to the map's.
///
/// Errors: a crossing whose bin or neighbour is beyond the map, an axis
/// beyond 2, a position not in [0, 1].
pub fn apply_refinement(
    map: ReachMap,
    parts: impl IntoIterator<Item = Refinement>,
) -> Result<ReachMap> {
    let layout = map.layout();
    let (dims, orientations) = (layout.dims(), layout.orientation_count());
    let strides = [dims[1] * dims[2], dims[2], 1];
    let bins = map.reachable().len();
    // (bin, axis, distance in cells) for both ends of every edge.
    let mut ends: Vec<(usize, u8, f32)> = Vec::new();
    let mut calls = 0;
    for part in parts {
        calls += part.calls;
        for c in part.crossings {
            let bin = usize::try_from(c.bin).unwrap_or(usize::MAX);
            let other = (c.axis < 3)
                .then(|| bin.checked_add(strides[c.axis as usize] * orientations))
                .flatten()
                .filter(|&o| o < bins && bin < bins);
            let Some(other) = other.filter(|_| (0.0..=1.0).contains(&c.at)) else {
                return Err(Error::invalid_argument(
                    "crossings",
                    format!(
                        "a crossing at bin {} axis {} position {} is not on an edge of the map's {bins} bins",
                        c.bin, c.axis, c.at
                    ),
                ));
            };
            ends.push((bin, c.axis, c.at));
            ends.push((other, c.axis, 1.0 - c.at));
        }
    }
    ends.sort_unstable_by(|x, y| x.0.cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.total_cmp(&y.2)));
    let mut boundary = map.boundary().to_vec();
    let units = f64::from(BOUNDARY_UNITS);
    for group in ends.chunk_by(|x, y| x.0 == y.0) {
        let mut nearest = [f64::INFINITY; 3];
        for &(_, axis, d) in group {
            let n = &mut nearest[axis as usize];
            *n = n.min(f64::from(d));
        }
        let inverse: f64 = nearest.iter().map(|d| 1.0 / (d * d)).sum();
        let distance = (1.0 / inverse.sqrt()).min(1.0);
        let magnitude = (distance * units).round().clamp(1.0, units) as i8;
        let bin = group[0].0;
        boundary[bin] = if map.reachable()[bin] != 0 {
            magnitude
        } else {
            -magnitude
        };
    }
    let mut refined = map.with_boundary(boundary)?;
    refined.add_calls(calls);
    Ok(refined)
}

/// The cell ranges of the local refinement's chunks (about 20 000 bins
/// each), in order, covering every cell once.
pub(crate) fn refine_work(layout: &MapLayout) -> Vec<Range<usize>> {
    let per = (CHUNK_BINS / layout.orientation_count().max(1)).max(1);
    let n = layout.cell_count();
    (0..n)
        .step_by(per)
        .map(|start| start..(start + per).min(n))
        .collect()
}

/// The refined `map` of `model` (its spec's [`Boundary::Bisection`]
/// steps; a map of [`Boundary::Cells`] is returned as it is): every
/// disagreeing edge located by [`refine_chunk`] on `threads` threads,
/// chunks of about 20 000 bins, then [`apply_refinement`]; `progress(chunks_done,
/// chunks_total)` from the calling thread. The result does not depend on
/// `threads`.
///
/// Errors: those of [`refine_chunk`] and [`apply_refinement`].
pub fn refine(
    model: &Model,
    map: ReachMap,
    threads: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<ReachMap> {
    if steps_of(&map).is_none() {
        return Ok(map);
    }
    let work = refine_work(map.layout());
    let run = |cells: &Range<usize>| refine_chunk(model, &map, cells.clone());
    let parts = on_threads(&work, threads, &run, progress, |results| {
        results.collect::<Result<Vec<_>>>()
    })?;
    apply_refinement(map, parts)
}
