//! The seed studies from Python (`armkit.study`): run one by name, get its
//! checks, the series behind its figures (as arrays) and its notes.

use armkit::mpc::qp::QpSolverKind;
use armkit::study::Seed000Example;
use armkit::study::{
    AvoidanceStudy, BeamTableStudy, ContinuousPathStudy, DistributionStudy, MpcExampleStudy,
    SpaceRobotStudy, StudyReport as LibraryReport,
};
use armkit::Error;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict, PyList};

use crate::errors::OrRaise;

/// The studies `run` knows, in the order `study.names()` lists them.
const STUDIES: &[&str] = &[
    "beam-table",
    "mpc-ex1",
    "mpc-ex1-rigid-model",
    "mpc-ex1-link-error",
    "mpc-ex2",
    "mpc-ex2-paper-weights",
    "mpc-ex2-strict",
    "mpc-ex3",
    "mpc-ex3-undamped",
    "distribution",
    "continuous-path",
    "avoidance",
    "space-robot",
];

/// What a study produced.
#[pyclass(frozen, module = "armkit", name = "StudyReport")]
pub struct StudyReport {
    /// The study's name.
    #[pyo3(get)]
    name: String,
    /// Each check as a dict: `name`, `value`, `threshold`, `comparison`
    /// (`"<="` or `">="`), `unit`, `detail`, `passed`, `text` (one line).
    #[pyo3(get)]
    checks: Py<PyList>,
    /// The figures' data by name: dicts with `title`, `x_label`, `y_label`,
    /// `x` (array) and `columns` (label -> array of the same length).
    #[pyo3(get)]
    series: Py<PyDict>,
    /// Notes (deviations from the paper and why).
    #[pyo3(get)]
    notes: Vec<String>,
    /// The paper's claims: each a dict with claim, measured, status
    /// ("reproduced", "reproduced with deviation", "not reproduced", "not
    /// attempted") and same_evidence_as (the row it restates, or None).
    #[pyo3(get)]
    findings: Py<PyList>,
    /// Number of checks that pass.
    #[pyo3(get)]
    passed: usize,
    /// True when every check passes.
    #[pyo3(get)]
    all_passed: bool,
}

#[pymethods]
impl StudyReport {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "StudyReport('{}', {}/{} checks passed)",
            self.name,
            self.passed,
            self.checks.bind(py).len()
        )
    }
}

impl StudyReport {
    fn new(py: Python<'_>, name: &str, report: LibraryReport) -> PyResult<Self> {
        let checks = PyList::empty(py);
        for check in &report.checks {
            let item = PyDict::new(py);
            item.set_item("name", &check.name)?;
            item.set_item("value", check.value)?;
            item.set_item("threshold", check.threshold)?;
            item.set_item("comparison", check.comparison.as_str())?;
            item.set_item("unit", &check.unit)?;
            item.set_item("detail", &check.detail)?;
            item.set_item("passed", check.passed())?;
            item.set_item("text", check.to_string())?;
            checks.append(item)?;
        }
        let findings = PyList::empty(py);
        for finding in &report.findings {
            let item = PyDict::new(py);
            item.set_item("claim", &finding.claim)?;
            item.set_item("measured", &finding.measured)?;
            item.set_item("status", finding.status.as_str())?;
            item.set_item("same_evidence_as", finding.same_evidence_as.as_deref())?;
            findings.append(item)?;
        }
        let series = PyDict::new(py);
        for set in &report.series {
            let item = PyDict::new(py);
            item.set_item("title", &set.title)?;
            item.set_item("x_label", &set.x_label)?;
            item.set_item("y_label", &set.y_label)?;
            item.set_item("x", PyArray1::from_slice(py, &set.x))?;
            let columns = PyDict::new(py);
            for (label, values) in &set.columns {
                columns.set_item(label, PyArray1::from_slice(py, values))?;
            }
            item.set_item("columns", columns)?;
            series.set_item(&set.name, item)?;
        }
        Ok(StudyReport {
            name: name.to_string(),
            checks: checks.unbind(),
            series: series.unbind(),
            passed: report.passed(),
            all_passed: report.all_passed(),
            notes: report.notes,
            findings: findings.unbind(),
        })
    }
}

/// The names of the studies `run` knows.
#[pyfunction]
pub fn names() -> Vec<&'static str> {
    STUDIES.to_vec()
}

/// Options given as keywords, as the study's options type (the library's
/// field names; unknown names are errors). Every value goes through JSON on
/// its own, so that a value of the wrong type is an error naming its keyword.
fn options<T: serde::de::DeserializeOwned>(
    py: Python<'_>,
    study: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<T> {
    let dumps = py.import("json")?.getattr("dumps")?;
    let mut fields = serde_json::Map::new();
    for (key, value) in options.into_iter().flat_map(|o| o.iter()) {
        let key: String = key.extract()?;
        let invalid = |reason: String| {
            Error::invalid_argument(key.as_str(), format!("study `{study}`: {reason}"))
        };
        // allow_nan=False: json.dumps would write NaN and Infinity, which
        // JSON (and so the option parser) does not have.
        let strict = [("allow_nan", false)].into_py_dict(py)?;
        let text: String = match dumps.call((&value,), Some(&strict)) {
            Ok(text) => text.extract()?,
            Err(e) if e.is_instance_of::<pyo3::exceptions::PyValueError>(py) => {
                let reason = "must be finite: NaN and infinities are refused";
                return Err(invalid(reason.to_string())).or_raise();
            }
            Err(e) => return Err(invalid(format!("not a JSON value: {e}"))).or_raise(),
        };
        let value: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| invalid(e.to_string()))
            .or_raise()?;
        // The keyword alone (the other options at their defaults) names a
        // value of the wrong type before the options meet.
        let alone = serde_json::Value::Object([(key.clone(), value.clone())].into_iter().collect());
        if let Err(e) = serde_json::from_value::<T>(alone) {
            let message = e.to_string();
            if !(message.starts_with("unknown field") || message.starts_with("missing field")) {
                return Err(invalid(e.to_string())).or_raise();
            }
        }
        fields.insert(key, value);
    }
    serde_json::from_value(serde_json::Value::Object(fields))
        .map_err(|e| Error::invalid_argument("options", format!("study `{study}`: {e}")))
        .or_raise()
}

/// Runs the seed study `name` (`study.names()` lists them) with `options`
/// as keywords (the library's option names, e.g. `payload=50.0` for
/// `distribution`, `ks=[1, 5]` for `avoidance`; `solver="clarabel"` for the
/// MPC examples). A failed check is in the report, never an exception.
#[pyfunction]
#[pyo3(signature = (name, **options))]
pub fn run(
    py: Python<'_>,
    name: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<StudyReport> {
    let report = match name {
        "beam-table" => {
            let study: BeamTableStudy = self::options(py, name, options)?;
            py.detach(|| study.run())
        }
        "distribution" => {
            let study: DistributionStudy = self::options(py, name, options)?;
            py.detach(|| study.run())
        }
        "continuous-path" => {
            let study: ContinuousPathStudy = self::options(py, name, options)?;
            py.detach(|| study.run())
        }
        "avoidance" => {
            let study: AvoidanceStudy = self::options(py, name, options)?;
            py.detach(|| study.run())
        }
        "space-robot" => {
            let study: SpaceRobotStudy = self::options(py, name, options)?;
            py.detach(|| study.run())
        }
        other => match other.strip_prefix("mpc-").map(Seed000Example::from_id) {
            Some(Ok(example)) => {
                let mut study = MpcExampleStudy::new(example);
                if let Some(options) = options {
                    for (key, value) in options.iter() {
                        let key: String = key.extract()?;
                        if key != "solver" {
                            return Err(Error::invalid_argument(
                                "options",
                                format!("study `{name}` takes only `solver`, got `{key}`"),
                            ))
                            .or_raise();
                        }
                        let solver: String = value.extract()?;
                        study.solver = Some(
                            QpSolverKind::available()
                                .iter()
                                .copied()
                                .find(|k| k.name() == solver)
                                .ok_or_else(|| {
                                    Error::invalid_argument(
                                        "solver",
                                        format!("unknown QP solver `{solver}`"),
                                    )
                                })
                                .or_raise()?,
                        );
                    }
                }
                py.detach(|| study.run())
            }
            _ => Err(Error::invalid_argument(
                "name",
                format!(
                    "unknown study `{other}`; the studies are: {}",
                    STUDIES.join(", ")
                ),
            )),
        },
    }
    .or_raise()?;
    StudyReport::new(py, name, report)
}
