//! Work items on local threads, their results handed to the calling
//! thread as they finish (the local build's chunks, the refinement's).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

use crate::error::Result;

/// Runs `run` on every item of `work` on `threads` threads (at least one),
/// items taken in order as threads free up; `collect` consumes the results
/// in the order they finish on the calling thread, which also calls
/// `progress(items_done, items_total)`. The first error stops the other
/// threads from taking new items.
pub(crate) fn on_threads<W: Sync, R: Send, T>(
    work: &[W],
    threads: usize,
    run: &(dyn Fn(&W) -> Result<R> + Sync),
    progress: &mut dyn FnMut(usize, usize),
    collect: impl FnOnce(&mut dyn Iterator<Item = Result<R>>) -> Result<T>,
) -> Result<T> {
    let total = work.len();
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let (send, receive) = mpsc::channel();
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1).min(total.max(1)) {
            let send = send.clone();
            let (next, stop) = (&next, &stop);
            scope.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= work.len() || stop.load(Ordering::Relaxed) {
                    break;
                }
                let result = run(&work[i]);
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
        let mut results = receive.iter().inspect(|_| {
            done += 1;
            progress(done, total);
        });
        let collected = collect(&mut results);
        stop.store(true, Ordering::Relaxed);
        collected
    })
}
