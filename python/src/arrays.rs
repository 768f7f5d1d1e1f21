//! Array-likes in, checked copies out: every input is converted once at the boundary (lists,
//! tuples, integer arrays, read-only or strided arrays: `numpy.asarray(x, dtype=float64)` unless
//! it already is a float64 array), its shape is checked against what the call needs, and the
//! values are copied into a `Vec` — the caller's memory is only ever read.

use numpy::ndarray::Array2;
use numpy::{
    Element, IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyAny;
use rocking::ErrorKind;

use crate::errors::error;

static ASARRAY: PyOnceLock<Py<PyAny>> = PyOnceLock::new();

/// A float64 array of any shape, copied row-major, with its shape.
pub struct Floats {
    pub values: Vec<f64>,
    pub shape: Vec<usize>,
}

/// The values of an array in row-major (logical) order and its shape: one copy, no borrow of the
/// caller's array beyond this call.
fn copy_out<T: Element + Copy>(array: &Bound<'_, PyArrayDyn<T>>) -> (Vec<T>, Vec<usize>) {
    let shape = array.shape().to_vec();
    let values = if array.is_c_contiguous() {
        array.to_vec().expect("C-contiguous")
    } else {
        array.to_owned_array().iter().copied().collect()
    };
    (values, shape)
}

/// Converts `obj` to float64 (a TypeError naming `name` if numpy cannot) and copies it.
pub fn floats(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Floats> {
    let py = obj.py();
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        let (values, shape) = copy_out(a);
        return Ok(Floats { values, shape });
    }
    if obj.is_none() {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected an array-like of numbers, got None"
        )));
    }
    // What numpy makes of it as it is: numbers (bool, int, float; objects, which float64 takes
    // one by one) are converted. numpy would also convert strings ("1"), dates and durations
    // (their counts of days, seconds) and, with a warning dropping the imaginary parts, complex
    // values: refused.
    let asarray = ASARRAY.import(py, "numpy", "asarray")?;
    let unreadable = |e: PyErr| {
        PyTypeError::new_err(format!(
            "{name}: cannot be read as an array of float64 ({e})"
        ))
    };
    let raw = asarray.call1((obj,)).map_err(unreadable)?;
    let kind: String = raw.getattr("dtype")?.getattr("kind")?.extract()?;
    match kind.as_str() {
        "b" | "i" | "u" | "f" | "O" => {}
        "c" => {
            return Err(PyTypeError::new_err(format!(
                "{name}: complex values, expected real numbers"
            )))
        }
        _ => {
            let dtype = raw.getattr("dtype")?.str()?;
            return Err(PyTypeError::new_err(format!(
                "{name}: values of dtype {dtype} (strings, dates or durations) are not numbers"
            )));
        }
    }
    let converted = asarray.call1((raw, "float64")).map_err(unreadable)?;
    let array = converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| PyTypeError::new_err(format!("{name}: not an array of float64")))?;
    let (values, shape) = copy_out(&array);
    Ok(Floats { values, shape })
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A vector of exactly `len` values (shape `(len,)`).
pub fn vector(obj: &Bound<'_, PyAny>, name: &str, len: usize) -> PyResult<Vec<f64>> {
    let f = floats(obj, name)?;
    if f.shape != [len] {
        return Err(error(
            ErrorKind::InvalidSize,
            format!(
                "{name} has shape {}, expected ({len},)",
                shape_text(&f.shape)
            ),
        ));
    }
    Ok(f.values)
}

/// A vector of any length (1-D).
pub fn any_vector(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let f = floats(obj, name)?;
    if f.shape.len() != 1 {
        return Err(error(
            ErrorKind::InvalidSize,
            format!("{name} has shape {}, expected 1-D", shape_text(&f.shape)),
        ));
    }
    Ok(f.values)
}

/// A `rows × cols` matrix, row-major (also accepted flat, `rows·cols` values, row-major).
pub fn matrix(obj: &Bound<'_, PyAny>, name: &str, rows: usize, cols: usize) -> PyResult<Vec<f64>> {
    let f = floats(obj, name)?;
    if f.shape != [rows, cols] && f.shape != [rows * cols] {
        return Err(error(
            ErrorKind::InvalidSize,
            format!(
                "{name} has shape {}, expected ({rows}, {cols})",
                shape_text(&f.shape)
            ),
        ));
    }
    Ok(f.values)
}

/// A 2-D matrix of any shape: (values row-major, rows, cols).
pub fn any_matrix(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<(Vec<f64>, usize, usize)> {
    let f = floats(obj, name)?;
    match f.shape[..] {
        [r, c] => Ok((f.values, r, c)),
        _ => Err(error(
            ErrorKind::InvalidSize,
            format!("{name} has shape {}, expected 2-D", shape_text(&f.shape)),
        )),
    }
}

/// Interface statuses: a 1-D array-like of −1, 0, +1 (any numeric dtype; 0.5 or 3 are an
/// `InvalidStatus` error naming the entry).
pub fn statuses(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<i8>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<i8>>() {
        let (values, shape) = copy_out(a);
        if shape.len() == 1 {
            if let Some(k) = values.iter().position(|v| !(-1..=1).contains(v)) {
                return Err(error(
                    ErrorKind::InvalidStatus,
                    format!("{name}[{k}] = {}, expected -1, 0 or 1", values[k]),
                ));
            }
            return Ok(values);
        }
    }
    let values = any_vector(obj, name)?;
    values
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            if v == -1.0 || v == 0.0 || v == 1.0 {
                Ok(v as i8)
            } else {
                Err(error(
                    ErrorKind::InvalidStatus,
                    format!("{name}[{k}] = {v}, expected -1, 0 or 1"),
                ))
            }
        })
        .collect()
}

/// A new 1-D float64 array (numpy's own memory).
pub fn new_vector(py: Python<'_>, v: Vec<f64>) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_slice(py, &v)
}

/// A new int8 status array (numpy's own memory).
pub fn new_statuses(py: Python<'_>, v: Vec<i8>) -> Bound<'_, PyArray1<i8>> {
    PyArray1::from_slice(py, &v)
}

/// A new `rows × cols` float64 array from row-major values.
pub fn new_matrix(
    py: Python<'_>,
    v: Vec<f64>,
    rows: usize,
    cols: usize,
) -> Bound<'_, PyArray2<f64>> {
    Array2::from_shape_vec((rows, cols), v)
        .expect("rows × cols values")
        .into_pyarray(py)
}
