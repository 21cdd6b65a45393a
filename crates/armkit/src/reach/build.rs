//! The local build on threads, and the partition into chunks.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

use super::{build_chunk, Builder, Chunk, MapLayout, MapSpec, ReachMap};
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
/// least one), chunks of [`LOCAL_CHUNK_WORK`], merged as they finish;
/// `progress(chunks_done, chunks_total)` is called from the calling thread.
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
    let total = work.len();
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let (send, receive) = mpsc::channel();
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1).min(total.max(1)) {
            let send = send.clone();
            let (next, stop, work, layout) = (&next, &stop, &work, &layout);
            scope.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= work.len() || stop.load(Ordering::Relaxed) {
                    break;
                }
                let result = build_chunk(model, layout, &work[i]);
                if result.is_err() {
                    stop.store(true, Ordering::Relaxed);
                }
                if send.send(result).is_err() {
                    break;
                }
            });
        }
        drop(send);
        let mut done = 0;
        progress(0, total);
        let results = receive.iter().inspect(|_| {
            done += 1;
            progress(done, total);
        });
        let map = ReachMap::from_results(layout.clone(), results);
        stop.store(true, Ordering::Relaxed);
        map
    })
}
