//! The local build on threads, and the partition into chunks.

use super::parallel::on_threads;
use super::refine::refine_work;
use super::{build_chunk, refine, Boundary, Builder, Chunk, MapLayout, MapSpec, ReachMap};
use crate::error::Result;
use crate::model::Model;

/// IK solves (or samples) per chunk of the local build: tens of
/// milliseconds each, so the progress moves and the threads balance.
pub const LOCAL_CHUNK_WORK: usize = 20_000;

/// Splits the map into chunks of about `target_work` IK solves (whole cells
/// of `spec`'s orientations) or samples each, in order, covering every cell
/// (or sample) once.
pub fn chunks(layout: &MapLayout, spec: &MapSpec, target_work: usize) -> Vec<Chunk> {
    let target = target_work.max(1);
    match spec.builder {
        Builder::InverseKinematics => {
            let per = (target / layout.orientation_count().max(1)).max(1);
            let n = layout.cell_count();
            (0..n)
                .step_by(per)
                .map(|start| Chunk {
                    cells: start..(start + per).min(n),
                    samples: 0..0,
                })
                .collect()
        }
        Builder::ForwardSampling { samples, .. } => {
            let per = target as u64;
            (0..samples.div_ceil(per))
                .map(|i| Chunk {
                    cells: 0..0,
                    samples: i * per..((i + 1) * per).min(samples),
                })
                .collect()
        }
    }
}

/// Builds the whole map of `spec` for `model` on `threads` threads (at
/// least one), chunks of [`LOCAL_CHUNK_WORK`], merged as they finish, then
/// (spec's [`Boundary::Bisection`]) refined by [`refine`] on the same
/// threads; `progress(chunks_done, chunks_total)` is called from the
/// calling thread, the total counting the build's chunks (first) and the
/// refinement's.
/// The result does not depend on `threads` (each chunk is deterministic
/// and the merge order-independent).
///
/// Errors: an invalid spec or layout (see [`MapLayout::new`]), a model the
/// solvers refuse; the first chunk's error stops the build.
pub fn build(
    model: &Model,
    spec: &MapSpec,
    threads: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<ReachMap> {
    let layout = MapLayout::new(model, spec)?;
    let work = chunks(&layout, spec, LOCAL_CHUNK_WORK);
    let first = work.len();
    let total = first
        + match spec.boundary {
            Boundary::Cells => 0,
            Boundary::Bisection { .. } => refine_work(&layout).len(),
        };
    let run = |chunk: &Chunk| build_chunk(model, &layout, chunk);
    let map = on_threads(
        &work,
        threads,
        &run,
        &mut |done, _| progress(done, total),
        |results| ReachMap::from_results(layout.clone(), results),
    )?;
    refine(model, map, threads, &mut |done, _| {
        progress(first + done, total)
    })
}
