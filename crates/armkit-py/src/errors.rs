//! armkit's errors as Python exceptions: bad input is a `ValueError` (a file
//! that does not exist a `FileNotFoundError`) carrying the library's own
//! message; a solver that did not converge is a status, never an exception.

use pyo3::exceptions::{PyFileNotFoundError, PyValueError};
use pyo3::PyErr;
use std::path::Path;

/// Converts a library result into a Python one (`ValueError` with the message).
pub trait OrRaise<T> {
    /// `Err(e)` becomes `ValueError(str(e))`.
    fn or_raise(self) -> Result<T, PyErr>;
}

impl<T> OrRaise<T> for armkit::Result<T> {
    fn or_raise(self) -> Result<T, PyErr> {
        self.map_err(value_error)
    }
}

/// `ValueError` with the library's message.
pub fn value_error(error: armkit::Error) -> PyErr {
    PyValueError::new_err(error.to_string())
}

/// The error of a batched call at element `row` of argument `what`:
/// `ValueError("q[3]: joint_positions[1] is not finite (NaN)")`.
pub fn row_error(what: &str, row: usize, error: &armkit::Error) -> PyErr {
    PyValueError::new_err(format!("{what}[{row}]: {error}"))
}

/// A loader's error: `FileNotFoundError` when `path` does not exist,
/// `ValueError` otherwise, both with the library's message.
pub fn load_error(path: &Path, error: armkit::Error) -> PyErr {
    if path.exists() {
        value_error(error)
    } else {
        PyFileNotFoundError::new_err(error.to_string())
    }
}
