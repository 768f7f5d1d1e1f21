//! Library results as Python objects through their JSON: the CLI prints them with serde_json
//! (keys in alphabetical order, floats as the shortest text that reads back to the same `f64`,
//! NaN and infinities as `null`), and `json.loads` of that text gives dicts, lists, floats and
//! None equal to what a Python user reads from the CLI's files.

use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;

use crate::errors::value_error;

static LOADS: PyOnceLock<Py<PyAny>> = PyOnceLock::new();

/// `value` as the Python object of its JSON (the CLI's key order: alphabetical).
pub fn to_python<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_value(value)
        .and_then(|tree| serde_json::to_string(&tree))
        .map_err(|e| value_error(e.to_string()))?;
    LOADS.import(py, "json", "loads")?.call1((text,))
}
