//! `armkit.Robot`'s evaluation over arrays of configurations: an (N, dof)
//! array in, a new (N, ...) array out, rows spread over threads with the
//! GIL released, row by row or through the library's batched kernels.

use armkit::kinematics::{BatchData, Data};
use armkit::Model;
use numpy::{PyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::arrays::{new_array, shape_error, RowMajor};
use crate::errors::row_error;
use crate::parallel::{
    for_each_chunk, for_each_row, thread_count, KernelRows, RowError, RowsMut, KERNEL_BLOCK_ROWS,
};
use crate::robot::Robot;

/// Rows per thread below which a batched FK or Jacobian stays on fewer
/// threads (a thread costs about as much to start as a few hundred FKs).
const KINEMATICS_ROWS_PER_THREAD: usize = 2048;

impl Robot {
    /// Evaluates `per_row(data, q_row, out_row)` over the rows of a (N, dof)
    /// array, writing `width` values per row into a new array of shape
    /// `(N, *item_shape)`, with the GIL released.
    pub(crate) fn batched<'py>(
        &self,
        array: &Bound<'py, PyArrayDyn<f64>>,
        item_shape: &[usize],
        threads: Option<i64>,
        per_row: impl Fn(&Model, &mut Data, &[f64], &mut [f64]) -> armkit::Result<()> + Sync,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (model, dof) = (&self.model, self.model.dof());
        self.batch_output(array, item_shape, threads, |q, threads, out| {
            let body = |data: &mut Data, row, local, out: &mut RowsMut<f64>| {
                per_row(model, data, &q[row * dof..(row + 1) * dof], out.row(local))
            };
            let (rows, per_thread) = (q.len() / dof, KINEMATICS_ROWS_PER_THREAD);
            for_each_row(rows, threads, per_thread, out, || Data::new(model), body)
        })
    }

    /// As [`Robot::batched`], through a batched kernel of the library
    /// (`block(model, workspace, q_rows, out_rows)`, many rows per call) in
    /// blocks of [`KERNEL_BLOCK_ROWS`]; a block that fails runs again row
    /// by row with `per_row` (the same results), whose error names the
    /// failing row as the row-by-row path does.
    pub(crate) fn batched_blocks<'py>(
        &self,
        array: &Bound<'py, PyArrayDyn<f64>>,
        item_shape: &[usize],
        threads: Option<i64>,
        block: impl Fn(&Model, &mut BatchData, &[f64], &mut [f64]) -> armkit::Result<()> + Sync,
        per_row: impl Fn(&Model, &mut Data, &[f64], &mut [f64]) -> armkit::Result<()> + Sync,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (model, dof) = (&self.model, self.model.dof());
        self.batch_output(array, item_shape, threads, |q, threads, out| {
            let chunk = |batch: &mut BatchData, start, len, out: &mut RowsMut<f64>| {
                let rows = KernelRows { q, dof, start, len };
                let block =
                    |batch: &mut BatchData, q: &[f64], out: &mut [f64]| block(model, batch, q, out);
                let row =
                    |q: &[f64], out: &mut [f64]| per_row(model, &mut Data::new(model), q, out);
                rows.by_blocks(out, KERNEL_BLOCK_ROWS, batch, block, row)
            };
            let (rows, min) = (q.len() / dof, KINEMATICS_ROWS_PER_THREAD);
            for_each_chunk(rows, threads, min, out, || BatchData::new(model), chunk)
        })
    }

    /// A new array of shape `(N, *item_shape)` for the (N, dof) array
    /// `array`, filled by `fill(q, threads, rows)` (`q` row-major) with the
    /// GIL released; a failing row raises naming it.
    fn batch_output<'py>(
        &self,
        array: &Bound<'py, PyArrayDyn<f64>>,
        item_shape: &[usize],
        threads: Option<i64>,
        fill: impl FnOnce(&[f64], usize, RowsMut<f64>) -> Result<(), RowError> + Send,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (py, shape, dof) = (array.py(), array.shape(), self.model.dof());
        if shape[1] != dof {
            return Err(shape_error("q", &format!("(N, {dof})"), shape));
        }
        let (threads, input) = (thread_count(threads)?, RowMajor::new(array)?);
        let (q, width) = (input.as_slice(), item_shape.iter().product());
        let mut dims = vec![shape[0]];
        dims.extend_from_slice(item_shape);
        let out = new_array(py, numpy::ndarray::IxDyn(&dims), |out| {
            py.detach(|| fill(q, threads, RowsMut::new(out, width)))
                .map_err(|e| row_error("q", e.row, &e.error))
        })?;
        Ok(out.into_any())
    }
}
