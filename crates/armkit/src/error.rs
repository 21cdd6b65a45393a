//! The crate's one error type.
//!
//! Every fallible public function returns [`Result`]. Errors name what was
//! wrong (the link, the field, the value, the file) so that a message alone
//! tells the user what to fix. Non-convergence of an iterative solver is not an
//! error: solvers return a report with a status.

/// Result alias used across armkit.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with enough context to fix it: always bad input (or a
/// numerical failure of a computation on valid input, such as an overflow).
/// A solver's non-convergence or a singular matrix is an outcome (a status
/// in a report), never an `Error`. New variants may be added: match with a
/// wildcard arm.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A robot model is inconsistent: names the link (0-based index of the
    /// moving joint or fixed element in the chain) and the field.
    #[error("invalid model: link {link} (`{name}`), field `{field}`: {reason}")]
    InvalidModel {
        /// 0-based index of the link in the chain.
        link: usize,
        /// Name of the link or joint.
        name: String,
        /// The offending field, e.g. `qlim`, `alpha`, `mass`.
        field: String,
        /// What is wrong with it.
        reason: String,
    },

    /// A model-wide problem that is not tied to one link (an empty chain, a
    /// bad base or tool transform).
    #[error("invalid model `{model}`: {reason}")]
    InvalidModelStructure {
        /// Model name.
        model: String,
        /// What is wrong.
        reason: String,
    },

    /// A vector or matrix argument has the wrong size.
    #[error("{what}: expected {expected} values, got {got}")]
    DimensionMismatch {
        /// The argument, e.g. `joint_positions`.
        what: &'static str,
        /// The size the model requires.
        expected: usize,
        /// The size given.
        got: usize,
    },

    /// An argument holds NaN or an infinity where a finite number is required.
    #[error("{what}[{index}] is not finite ({value})")]
    NonFinite {
        /// The argument, e.g. `joint_positions`.
        what: &'static str,
        /// Index of the first non-finite entry.
        index: usize,
        /// The value found.
        value: f64,
    },

    /// A joint position lies outside its limits.
    #[error("joint {joint} (`{name}`) = {value} is outside its limits [{lower}, {upper}]")]
    OutOfLimits {
        /// 0-based joint index.
        joint: usize,
        /// Joint name.
        name: String,
        /// The position given (rad or m).
        value: f64,
        /// Lower limit.
        lower: f64,
        /// Upper limit.
        upper: f64,
    },

    /// An argument is outside its valid domain (a negative duration, a weight
    /// <= 0, ...).
    #[error("invalid argument `{name}`: {reason}")]
    InvalidArgument {
        /// The argument's name.
        name: String,
        /// What is wrong and what was expected.
        reason: String,
    },

    /// A built-in robot name that does not exist.
    #[error("unknown robot `{name}`; the built-in robots are: {known}")]
    UnknownRobot {
        /// The name asked for.
        name: String,
        /// Comma-separated list of the built-in names.
        known: String,
    },

    /// A robot description, URDF or scenario file could not be read or parsed.
    #[error("{source_name}: {reason}")]
    Parse {
        /// The file path (or `<string>` for in-memory text).
        source_name: String,
        /// What is wrong, with line and column where known.
        reason: String,
    },

    /// A numerical step failed (a singular matrix where one must be inverted,
    /// a QP solver failure), with what was being computed.
    #[error("numerical failure in {context}: {reason}")]
    Numerical {
        /// What was being computed.
        context: String,
        /// Why it failed.
        reason: String,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidArgument`].
    pub fn invalid_argument(name: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidArgument {
            name: name.into(),
            reason: reason.into(),
        }
    }
}

/// Checks that `values` has `expected` entries, all finite.
///
/// `what` names the argument in the error (e.g. `"joint_positions"`).
#[inline]
pub fn check_finite_vector(what: &'static str, values: &[f64], expected: usize) -> Result<()> {
    if values.len() != expected {
        return Err(Error::DimensionMismatch {
            what,
            expected,
            got: values.len(),
        });
    }
    check_finite(what, values)
}

/// Checks that every entry of `values` is finite (not NaN, not infinite).
#[inline]
pub fn check_finite(what: &'static str, values: &[f64]) -> Result<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(Error::NonFinite {
            what,
            index,
            value: values[index],
        }),
    }
}

/// A text file's contents and its name for messages (the path as given);
/// a file that cannot be read is an [`Error::Parse`] naming it.
pub fn read_source(path: &std::path::Path) -> Result<(String, String)> {
    let source_name = path.display().to_string();
    match std::fs::read_to_string(path) {
        Ok(text) => Ok((text, source_name)),
        Err(e) => Err(Error::Parse {
            source_name,
            reason: format!("cannot read the file: {e}"),
        }),
    }
}

/// `value` as a message prints it: plain between 1e-4 and 1e6 (and 0, NaN,
/// infinities), in exponent form outside (`1e300`, not 301 digits).
pub fn brief(value: f64) -> String {
    let size = value.abs();
    if value != 0.0 && size.is_finite() && !(1e-4..1e6).contains(&size) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

/// Checks that `value` is finite and > 0; the error names the argument:
/// ``invalid argument `name`: must be finite and > 0, got -1``.
pub fn check_positive(name: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid_argument(
            name,
            format!("must be finite and > 0, got {value}"),
        ))
    }
}
