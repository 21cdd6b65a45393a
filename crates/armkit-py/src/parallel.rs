//! Batched calls on all cores: the rows of a batch are split into one
//! contiguous chunk per thread (`std::thread::scope`), each thread with its
//! own workspace, writing into its own part of the output arrays. The caller
//! runs this with the GIL released; nothing here touches Python.

use std::num::NonZeroUsize;

use pyo3::exceptions::PyValueError;
use pyo3::PyResult;

/// The number of threads a batched call uses: `requested`, or every core
/// the process may use (`std::thread::available_parallelism`) by default.
pub fn thread_count(requested: Option<i64>) -> PyResult<usize> {
    match requested {
        Some(n) if n >= 1 => Ok(usize::try_from(n).unwrap_or(usize::MAX)),
        Some(n) => Err(PyValueError::new_err(format!(
            "invalid argument `threads`: must be >= 1 (or None for every core), got {n}"
        ))),
        None => Ok(std::thread::available_parallelism().map_or(1, NonZeroUsize::get)),
    }
}

/// Output rows that can be split between threads.
pub trait Output: Send + Sized {
    /// The first `rows` rows and the rest.
    fn split_at(self, rows: usize) -> (Self, Self);
}

/// A mutable row-major block of `width` values per row.
pub struct RowsMut<'a, T> {
    data: &'a mut [T],
    width: usize,
}

impl<'a, T> RowsMut<'a, T> {
    /// Rows of `width` values over `data` (`data.len()` a multiple of `width`).
    pub fn new(data: &'a mut [T], width: usize) -> Self {
        RowsMut { data, width }
    }

    /// Row `i` of this block (0-based within the block).
    pub fn row(&mut self, i: usize) -> &mut [T] {
        self.rows(i, 1)
    }

    /// Rows `i..i + count` of this block, one slice.
    pub fn rows(&mut self, i: usize, count: usize) -> &mut [T] {
        &mut self.data[i * self.width..(i + count) * self.width]
    }
}

impl<T: Send> Output for RowsMut<'_, T> {
    fn split_at(self, rows: usize) -> (Self, Self) {
        let (head, tail) = self.data.split_at_mut(rows * self.width);
        (
            RowsMut::new(head, self.width),
            RowsMut::new(tail, self.width),
        )
    }
}

impl<A: Output, B: Output> Output for (A, B) {
    fn split_at(self, rows: usize) -> (Self, Self) {
        let (a_head, a_tail) = self.0.split_at(rows);
        let (b_head, b_tail) = self.1.split_at(rows);
        ((a_head, b_head), (a_tail, b_tail))
    }
}

/// Rows per call of the library's batched FK and Jacobian kernels: a block
/// of configurations and its results (about 1024 x (6 + 16) values, under
/// 200 kB) stay in the core's cache.
pub const KERNEL_BLOCK_ROWS: usize = 1024;

/// Rows `start..start + len` of a row-major batch `q` of `dof` values per
/// row, for a kernel that takes many rows per call.
pub struct KernelRows<'a> {
    /// The whole batch, row-major.
    pub q: &'a [f64],
    /// Values per row of `q`.
    pub dof: usize,
    /// The first row of these.
    pub start: usize,
    /// The number of rows.
    pub len: usize,
}

impl KernelRows<'_> {
    /// Runs `block(state, q_rows, out_rows)` on up to `block_rows` rows at a
    /// time, `out` holding this chunk's rows (row `start` first); a block
    /// that fails runs again row by row with `per_row(q_row, out_row)` (the
    /// same results), whose error names the failing row as a row-by-row
    /// batch does.
    pub fn by_blocks<S>(
        &self,
        out: &mut RowsMut<f64>,
        block_rows: usize,
        state: &mut S,
        block: impl Fn(&mut S, &[f64], &mut [f64]) -> armkit::Result<()>,
        per_row: impl Fn(&[f64], &mut [f64]) -> armkit::Result<()>,
    ) -> Result<(), RowError> {
        let (dof, width) = (self.dof, out.width);
        let mut local = 0;
        while local < self.len {
            let n = block_rows.max(1).min(self.len - local);
            let first = self.start + local;
            let q = &self.q[first * dof..(first + n) * dof];
            let out = out.rows(local, n);
            if block(state, q, out).is_err() {
                let rows = q.chunks_exact(dof).zip(out.chunks_exact_mut(width));
                for (k, (q_row, out_row)) in rows.enumerate() {
                    per_row(q_row, out_row).map_err(|error| RowError {
                        row: first + k,
                        error,
                    })?;
                }
            }
            local += n;
        }
        Ok(())
    }
}

/// The first failing row of a batch and its error.
#[derive(Debug)]
pub struct RowError {
    /// 0-based row of the batch.
    pub row: usize,
    /// The library's error for that row.
    pub error: armkit::Error,
}

/// Runs `body(workspace, row, local_row, output_chunk)` for every row in
/// `0..rows`, on up to `threads` threads with at least `min_rows_per_thread`
/// rows each (spawning costs tens of microseconds). Each thread gets its own
/// workspace from `workspace()` and its own contiguous chunk of `output`
/// (`local_row` indexes it). Stops a chunk at its first error and returns
/// the error of the smallest row.
pub fn for_each_row<S, O, W, F>(
    rows: usize,
    threads: usize,
    min_rows_per_thread: usize,
    output: O,
    workspace: W,
    body: F,
) -> Result<(), RowError>
where
    O: Output,
    W: Fn() -> S + Sync,
    F: Fn(&mut S, usize, usize, &mut O) -> armkit::Result<()> + Sync,
{
    for_each_chunk(
        rows,
        threads,
        min_rows_per_thread,
        output,
        workspace,
        |state, start, len, output| {
            for local in 0..len {
                body(state, start + local, local, output).map_err(|error| RowError {
                    row: start + local,
                    error,
                })?;
            }
            Ok(())
        },
    )
}

/// Runs `body(workspace, first_row, rows, output_chunk)` once per thread on
/// its contiguous chunk of `0..rows` (split as [`for_each_row`] splits),
/// for kernels that take many rows per call. `body` returns the error of
/// the chunk's smallest failing row; the smallest over the chunks is
/// returned.
pub fn for_each_chunk<S, O, W, F>(
    rows: usize,
    threads: usize,
    min_rows_per_thread: usize,
    output: O,
    workspace: W,
    body: F,
) -> Result<(), RowError>
where
    O: Output,
    W: Fn() -> S + Sync,
    F: Fn(&mut S, usize, usize, &mut O) -> Result<(), RowError> + Sync,
{
    let threads = threads
        .min(rows.div_ceil(min_rows_per_thread.max(1)))
        .max(1);
    if threads == 1 {
        let mut output = output;
        return body(&mut workspace(), 0, rows, &mut output);
    }
    let chunk = rows.div_ceil(threads);
    std::thread::scope(|scope| {
        let mut handles = Vec::with_capacity(threads);
        let mut rest = output;
        let mut start = 0;
        while start < rows {
            let len = chunk.min(rows - start);
            let (mut head, tail) = rest.split_at(len);
            rest = tail;
            let (workspace, body) = (&workspace, &body);
            handles.push((
                start,
                scope.spawn(move || body(&mut workspace(), start, len, &mut head)),
            ));
            start += len;
        }
        // Chunks are in row order: the first chunk with an error has the
        // smallest failing row.
        let mut first = Ok(());
        for (start, handle) in handles {
            let result = handle.join().unwrap_or_else(|_| {
                Err(RowError {
                    row: start,
                    error: armkit::Error::Numerical {
                        context: "a batched call".into(),
                        reason: "a worker thread panicked".into(),
                    },
                })
            });
            if first.is_ok() {
                first = result;
            }
        }
        first
    })
}
