//! NumPy in and out: any float array-like becomes a float64 array (no copy
//! when it already is one, whatever its memory order or strides), and
//! results are new C-ordered float64 arrays.

use armkit::math::{Matrix4, Matrix6xX, Pose};
use armkit::Error;
use numpy::ndarray::Dimension;
use numpy::{PyArray, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyMemoryError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyFloat, PyInt, PyList, PyTuple};

use crate::errors::OrRaise;

static ASARRAY: PyOnceLock<Py<PyAny>> = PyOnceLock::new();

/// `obj` as a float64 array: itself when it is one (any order, any strides),
/// otherwise `numpy.asarray(obj, dtype=float64)`. `what` names the argument
/// in the error.
pub fn float_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if let Ok(array) = obj.cast::<PyArrayDyn<f64>>() {
        return Ok(array.clone());
    }
    let py = obj.py();
    let asarray = ASARRAY.import(py, "numpy", "asarray")?;
    // NumPy casts complex to float with only a ComplexWarning (dropping the
    // imaginary part) and bool to 0/1, also a bool beside floats in a list:
    // silent wrong answers.
    if holds_bool(obj, 0) {
        return Err(bool_error(what));
    }
    let native = asarray.call1((obj,)).map_err(|e| {
        PyValueError::new_err(format!(
            "{what}: expected an array of numbers: {}",
            e.value(py)
        ))
    })?;
    let kind: String = native.getattr("dtype")?.getattr("kind")?.extract()?;
    match kind.as_str() {
        "c" => {
            return Err(PyTypeError::new_err(format!(
                "{what}: expected real numbers, got a complex array"
            )));
        }
        "b" => return Err(bool_error(what)),
        _ => {}
    }
    // On failure, convert `obj` itself again for NumPy's message about the
    // user's value ('abc', not np.str_('abc')).
    let converted = asarray
        .call1((native, "float64"))
        .or_else(|_| asarray.call1((obj, "float64")))
        .map_err(|e| {
            PyValueError::new_err(format!(
                "{what}: expected an array of numbers: {}",
                e.value(py)
            ))
        })?;
    converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| PyValueError::new_err(format!("{what}: expected an array of numbers")))
}

/// The TypeError for a bool where numbers are expected.
fn bool_error(what: &str) -> PyErr {
    PyTypeError::new_err(format!("{what}: expected numbers, got a bool array"))
}

/// Deepest list nesting [`holds_bool`] looks into: NumPy's own limit on
/// dimensions, beyond which the conversion fails anyway.
const MAX_NESTING: usize = 64;

/// True when `obj` is a bool or a list or tuple holding one, at any depth up
/// to [`MAX_NESTING`].
fn holds_bool(obj: &Bound<'_, PyAny>, depth: usize) -> bool {
    if obj.is_instance_of::<PyBool>() {
        return true;
    }
    if depth >= MAX_NESTING {
        return false;
    }
    if let Ok(list) = obj.cast::<PyList>() {
        list.iter().any(|item| holds_bool(&item, depth + 1))
    } else if let Ok(tuple) = obj.cast::<PyTuple>() {
        tuple.iter().any(|item| holds_bool(&item, depth + 1))
    } else {
        false
    }
}

/// Reads a flat list or tuple of numbers into `out` without going through
/// NumPy (the common `robot.fk([...])` call); false, with `out` unspecified,
/// when `obj` is anything else (an array, nested lists, a non-number):
/// read it with [`float_array`] then.
pub fn read_flat_sequence(obj: &Bound<'_, PyAny>, out: &mut Vec<f64>) -> bool {
    out.clear();
    let read = |item: Bound<'_, PyAny>, out: &mut Vec<f64>| {
        // Floats and ints only: anything else (a string, a nested list)
        // takes the NumPy path, which reports it.
        // (bool is an int subclass; it takes the NumPy path, which refuses it.)
        if item.is_instance_of::<PyFloat>()
            || (item.is_instance_of::<PyInt>() && !item.is_instance_of::<PyBool>())
        {
            if let Ok(value) = item.extract::<f64>() {
                out.push(value);
                return true;
            }
        }
        false
    };
    if let Ok(list) = obj.cast::<PyList>() {
        list.iter().all(|item| read(item, out))
    } else if let Ok(tuple) = obj.cast::<PyTuple>() {
        tuple.iter().all(|item| read(item, out))
    } else {
        false
    }
}

/// `ValueError` for an array of the wrong shape.
pub fn shape_error(what: &str, expected: &str, got: &[usize]) -> PyErr {
    PyValueError::new_err(format!(
        "{what}: expected an array of shape {expected}, got shape {}",
        format_shape(got)
    ))
}

/// `(2, 3)` for `[2, 3]`, `(6,)` for `[6]`.
pub fn format_shape(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// Copies the values of `array` in row-major (C) order into `out`, whatever
/// its memory layout. Runs with the GIL held, so no Python code can change
/// the array meanwhile.
pub fn copy_values(array: &Bound<'_, PyArrayDyn<f64>>, out: &mut Vec<f64>) {
    out.clear();
    // SAFETY: the GIL is held for the whole copy and no mutable Rust view of
    // this array exists (this crate never makes one of an input).
    let view = unsafe { array.as_array() };
    match view.as_slice() {
        Some(slice) => out.extend_from_slice(slice),
        None => out.extend(view.iter().copied()),
    }
}

/// The values of a float64 array in row-major order, readable without the
/// GIL: the array's own memory when it is C-contiguous (borrowed read-only
/// through NumPy's borrow checker), otherwise a copy.
pub enum RowMajor<'py> {
    /// The array's own memory.
    Borrowed(PyReadonlyArrayDyn<'py, f64>),
    /// A C-ordered copy.
    Copied(Vec<f64>),
}

impl<'py> RowMajor<'py> {
    /// Reads `array` (see the type).
    pub fn new(array: &Bound<'py, PyArrayDyn<f64>>) -> PyResult<Self> {
        if array.is_c_contiguous() {
            if let Ok(readonly) = array.try_readonly() {
                return Ok(RowMajor::Borrowed(readonly));
            }
        }
        let mut values = Vec::new();
        reserve_values(&mut values, array.len(), "the input's copy")?;
        copy_values(array, &mut values);
        Ok(RowMajor::Copied(values))
    }

    /// The values, row-major.
    pub fn as_slice(&self) -> &[f64] {
        match self {
            RowMajor::Borrowed(readonly) => readonly.as_slice().unwrap_or(&[]),
            RowMajor::Copied(values) => values,
        }
    }
}

/// Most float64 values one result or input copy may hold: 2^31 (16 GiB), so
/// that a request beyond it is a MemoryError before any work, not an abort
/// of the interpreter when the allocation fails.
pub const MAX_RESULT_ELEMENTS: usize = 1 << 31;

/// The MemoryError for `what` of `elements` float64 values, with the size it
/// would need.
fn too_large(what: &str, elements: usize) -> PyErr {
    PyMemoryError::new_err(format!(
        "{what} would hold {elements} values ({:.3e} bytes), more than the {MAX_RESULT_ELEMENTS} allowed",
        elements as f64 * 8.0
    ))
}

/// Reserves room for `elements` values in `values`, fallibly: a MemoryError
/// naming `what` above [`MAX_RESULT_ELEMENTS`] or when the allocation fails.
pub fn reserve_values(values: &mut Vec<f64>, elements: usize, what: &str) -> PyResult<()> {
    if elements > MAX_RESULT_ELEMENTS {
        return Err(too_large(what, elements));
    }
    values
        .try_reserve_exact(elements)
        .map_err(|_| too_large(what, elements))
}

/// A new C-ordered float64 array of shape `dims`, filled by `fill` with its
/// values in row-major order (`fill` may release the GIL: it gets a plain slice).
pub fn new_array<'py, D: Dimension>(
    py: Python<'py>,
    dims: D,
    fill: impl FnOnce(&mut [f64]) -> PyResult<()>,
) -> PyResult<Bound<'py, PyArray<f64, D>>> {
    let elements = dims.size_checked().filter(|&n| n <= MAX_RESULT_ELEMENTS);
    if elements.is_none() {
        return Err(too_large(
            "the result",
            dims.slice()
                .iter()
                .fold(1, |n: usize, &d| n.saturating_mul(d)),
        ));
    }
    let array = PyArray::<f64, D>::zeros(py, dims, false);
    {
        // SAFETY: the array is new (no other view of it exists) and C-contiguous.
        let values = unsafe { array.as_slice_mut() }
            .map_err(|e| PyValueError::new_err(format!("allocating the result: {e}")))?;
        fill(values)?;
    }
    Ok(array)
}

/// A float64 vector as a new 1-D array.
pub fn vector<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, numpy::PyArray1<f64>> {
    PyArray::from_slice(py, values)
}

/// Rows of equal length as a new (rows, width) array.
pub fn matrix_from_rows<'py>(
    py: Python<'py>,
    rows: &[Vec<f64>],
    width: usize,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    new_array(py, numpy::ndarray::Dim([rows.len(), width]), |out| {
        for (chunk, row) in out.chunks_exact_mut(width.max(1)).zip(rows) {
            chunk.copy_from_slice(&row[..width]);
        }
        Ok(())
    })
}

/// Writes `pose` as a row-major homogeneous 4 x 4 matrix into `out[..16]`.
pub fn write_pose(pose: &Pose, out: &mut [f64]) {
    for r in 0..3 {
        for c in 0..3 {
            out[4 * r + c] = pose.rotation[(r, c)];
        }
        out[4 * r + 3] = pose.translation[r];
    }
    out[12..16].copy_from_slice(&[0.0, 0.0, 0.0, 1.0]);
}

/// Writes a 6 x n Jacobian row-major into `out[..6 n]`.
pub fn write_jacobian(jacobian: &Matrix6xX<f64>, out: &mut [f64]) {
    let n = jacobian.ncols();
    for r in 0..6 {
        for c in 0..n {
            out[r * n + c] = jacobian[(r, c)];
        }
    }
}

/// A pose from 16 row-major values of a homogeneous matrix; the error names
/// `what` and says what is wrong (last row, non-finite, rotation not orthonormal).
pub fn read_pose(values: &[f64], what: &str) -> armkit::Result<Pose> {
    let matrix = Matrix4::from_row_slice(values);
    Pose::from_matrix4(&matrix).map_err(|reason| Error::invalid_argument(what, reason))
}

/// Reads one pose argument: a (4, 4) array-like.
pub fn pose_argument(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Pose> {
    let array = float_array(obj, what)?;
    if array.shape() != [4, 4] {
        return Err(shape_error(what, "(4, 4)", array.shape()));
    }
    let mut values = Vec::with_capacity(16);
    copy_values(&array, &mut values);
    read_pose(&values, what).or_raise()
}

/// Reads a vector of `len` finite values; the error is the library's
/// (`what: expected 6 values, got 5`, `what[2] is not finite (NaN)`).
pub fn vector_argument(
    obj: &Bound<'_, PyAny>,
    what: &'static str,
    len: usize,
) -> PyResult<Vec<f64>> {
    let array = float_array(obj, what)?;
    if array.ndim() != 1 {
        return Err(shape_error(what, &format!("({len},)"), array.shape()));
    }
    let mut values = Vec::with_capacity(len);
    copy_values(&array, &mut values);
    armkit::error::check_finite_vector(what, &values, len).or_raise()?;
    Ok(values)
}
