//! `rocking.RockingError`: the one exception of the package, a `ValueError` that carries the C
//! ABI's status code (the `ErrorKind` table of `src/error.rs`) and the detail that names the bad
//! argument.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rocking::ErrorKind;

pyo3::create_exception!(
    rocking,
    RockingError,
    PyValueError,
    "A call the library refused or could not solve.\n\n\
     Attributes: ``code`` (int or None) is the C ABI's status code (``rocking.ERROR_CODES``): \
     negative for a bad call, positive when the call is valid but cannot be solved as asked; \
     None for inputs outside the models (records, pulses). ``name`` is the code's C name \
     (``ROCKING_ERR_NOT_SYMMETRIC``, ...) or None; ``message`` is the code's static text \
     (``rocking_error_message``) and ``detail`` what exactly was wrong, naming the argument \
     (``rocking_last_error_message``)."
);

/// A `RockingError` with its attributes set.
fn raise(py: Python<'_>, kind: Option<ErrorKind>, detail: &str) -> PyErr {
    let text = match kind {
        Some(k) => format!("{}: {detail}", k.message()),
        None => detail.to_string(),
    };
    let err = RockingError::new_err(text);
    let value = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail short of memory exhaustion;
    // the exception is raised either way.
    let _ = value.setattr("code", kind.map(ErrorKind::code));
    let _ = value.setattr("name", kind.map(ErrorKind::c_name));
    let _ = value.setattr("message", kind.map(ErrorKind::message));
    let _ = value.setattr("detail", detail);
    err
}

/// The library's model error as a `RockingError` with its code.
pub fn model_error(e: rocking::RockingError) -> PyErr {
    Python::attach(|py| raise(py, Some(e.kind), &e.detail))
}

/// A `RockingError` of the given kind (checks made in the binding, e.g. array shapes).
pub fn error(kind: ErrorKind, detail: impl AsRef<str>) -> PyErr {
    Python::attach(|py| raise(py, Some(kind), detail.as_ref()))
}

/// A `RockingError` without a C code: bad records, pulses and other inputs outside the models.
pub fn value_error(detail: impl std::fmt::Display) -> PyErr {
    Python::attach(|py| raise(py, None, &detail.to_string()))
}

/// Checks that `path` can be opened for reading, as the `OSError` Python users expect
/// (`FileNotFoundError`, `IsADirectoryError`, …) with its `errno`, `strerror` and `filename`:
/// `[Errno 2] No such file or directory: 'FF-44.AT2'`. The bare conversion of the I/O error
/// said "No such file or directory (os error 2)" without the file, which among the records of
/// a suite left the user to guess which one.
pub fn readable(path: &std::path::Path) -> PyResult<()> {
    let file = path.display().to_string();
    let opened = std::fs::File::open(path).and_then(|f| {
        // Opening a folder succeeds on Linux; reading it is what fails (EISDIR).
        if f.metadata()?.is_dir() {
            Err(std::io::Error::from_raw_os_error(21))
        } else {
            Ok(())
        }
    });
    opened.map_err(|e| match e.raw_os_error() {
        Some(code) => {
            let text = e.to_string();
            let strerror = text
                .strip_suffix(&format!(" (os error {code})"))
                .unwrap_or(&text)
                .to_string();
            // OSError(errno, strerror, filename) is built as the subclass of that errno.
            pyo3::exceptions::PyOSError::new_err((code, strerror, file))
        }
        None => pyo3::exceptions::PyOSError::new_err(format!("{file}: {e}")),
    })
}

/// `Result<T, rocking::RockingError>` → `PyResult<T>`.
pub trait IntoPy<T> {
    /// Converts the library's error.
    fn py(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for Result<T, rocking::RockingError> {
    fn py(self) -> PyResult<T> {
        self.map_err(model_error)
    }
}

/// `{C name: code}` of every status code of the C ABI, success included.
#[pyfunction]
pub fn error_codes() -> Vec<(&'static str, i32)> {
    std::iter::once((rocking::error::SUCCESS.0, 0))
        .chain(ErrorKind::ALL.iter().map(|k| (k.c_name(), k.code())))
        .collect()
}

/// A positive finite number, named (`rocking::validate::positive`'s rule).
pub fn positive(name: &str, v: f64) -> PyResult<f64> {
    rocking::validate::positive(name, v).map_err(value_error)
}

/// A grid of `n` points from `lo` to `hi` runs upwards (a reversed range ran on a reversed grid),
/// both named, as the CLI's `sweep::ascending`.
pub fn ascending(lo_name: &str, lo: f64, hi_name: &str, hi: f64, n: usize) -> PyResult<()> {
    if n > 1 && lo >= hi {
        return Err(value_error(format!(
            "{lo_name} = {lo}: must be below {hi_name} ({hi})"
        )));
    }
    Ok(())
}

/// Levels linear from 1 to `level_max`: it is above 1, as the CLI's `sweep::levels_from_one`.
pub fn levels_from_one(level_max: f64, n: usize) -> PyResult<()> {
    if n > 1 && level_max <= 1.0 {
        return Err(value_error(format!(
            "level_max = {level_max}: must be above 1 (the levels run linearly from 1)"
        )));
    }
    Ok(())
}
