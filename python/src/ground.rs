//! Ground motions: records (PEER `.AT2` or plain text) and the pulses of thesis Fig. 6 and 8.
//! Both evaluate `a_g(t)` on a float or on an array of times.

use std::path::PathBuf;

use numpy::ndarray::{ArrayD, IxDyn};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyInt, PyTuple};
use rocking::ground::excitation::Pulse as CorePulse;
use rocking::ground::records::{self, PlainFormat, Record as CoreRecord};
use rocking::model::column::GRAVITY;
use rocking::validate;

use crate::arrays::{any_vector, floats, new_vector};
use crate::errors::value_error;

/// `f` on a float, or elementwise on an array-like of times (a new array of the same shape). A
/// NaN time gives NaN (the motions compare the time with their start and end, which a NaN fails:
/// it gave 0).
fn evaluate<'py>(t: &Bound<'py, PyAny>, f: impl Fn(f64) -> f64) -> PyResult<Bound<'py, PyAny>> {
    let py = t.py();
    let f = |x: f64| if x.is_nan() { f64::NAN } else { f(x) };
    if t.is_instance_of::<PyFloat>() || t.is_instance_of::<PyInt>() {
        let x: f64 = t.extract()?;
        return Ok(PyFloat::new(py, f(x)).into_any());
    }
    let times = floats(t, "t")?;
    let values: Vec<f64> = times.values.iter().map(|&x| f(x)).collect();
    let array = ArrayD::from_shape_vec(IxDyn(&times.shape), values).expect("same shape");
    Ok(array.into_pyarray(py).into_any())
}

/// A uniformly sampled ground-acceleration record (m/s², +x = the ground accelerates to the
/// right). Sample ``i`` is the acceleration at ``t = i·dt``; in between, linear interpolation;
/// zero before 0 and after the last sample.
#[pyclass(frozen, module = "rocking")]
#[derive(Clone)]
pub struct Record {
    pub inner: CoreRecord,
}

#[pymethods]
impl Record {
    /// A record from its samples (m/s²) and time step (s).
    #[new]
    #[pyo3(signature = (samples, dt, name = "record"))]
    fn new(samples: &Bound<'_, PyAny>, dt: f64, name: &str) -> PyResult<Record> {
        let samples = any_vector(samples, "samples")?;
        if samples.is_empty() {
            // As read_record refuses an empty file: no ground motion at all ran as a record.
            return Err(value_error(
                "samples: no sample, a record needs at least one",
            ));
        }
        let inner = CoreRecord::new(name, dt, samples).map_err(value_error)?;
        Ok(Record { inner })
    }

    /// Name (the file stem for a record read from a file).
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// Time step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt
    }

    /// The samples (m/s²), a new array.
    #[getter]
    fn samples<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        new_vector(py, self.inner.samples.clone()).into_any()
    }

    /// The sample times ``i·dt`` (s), a new array.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let dt = self.inner.dt;
        let t = (0..self.inner.samples.len())
            .map(|i| i as f64 * dt)
            .collect();
        new_vector(py, t).into_any()
    }

    /// Peak ground acceleration ``max |a|`` (m/s²).
    #[getter]
    fn pga(&self) -> f64 {
        self.inner.pga()
    }

    /// Time of the last sample (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    /// Ground acceleration (m/s²) at ``t`` (a float or an array of times).
    fn acceleration<'py>(&self, t: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        evaluate(t, |x| self.inner.acceleration(x))
    }

    /// The record with every sample multiplied by ``factor``.
    fn scaled(&self, factor: f64) -> PyResult<Record> {
        let inner = self.inner.scaled(factor);
        inner.validate().map_err(value_error)?;
        Ok(Record { inner })
    }

    /// The record scaled to a peak ground acceleration ``pga`` (m/s²), frequency content
    /// unchanged (as the overturning spectra scale records, SPEC §7).
    fn scaled_to_pga(&self, pga: f64) -> PyResult<Record> {
        let inner = self.inner.scaled_to_pga(pga).map_err(value_error)?;
        Ok(Record { inner })
    }

    fn __len__(&self) -> usize {
        self.inner.samples.len()
    }

    /// Pickling (multiprocessing, ``copy.deepcopy``): rebuilt from its samples, step and name.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyAny>, (Bound<'py, PyAny>, f64, String)) {
        (
            py.get_type::<Record>().into_any(),
            (self.samples(py), self.inner.dt, self.inner.name.clone()),
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "Record(name={:?}, dt={}, samples={}, pga={:.4} m/s² ({:.3} g))",
            self.inner.name,
            self.inner.dt,
            self.inner.samples.len(),
            self.inner.pga(),
            self.inner.pga() / GRAVITY
        )
    }
}

/// Reads a ground-acceleration record: PEER ``.AT2`` (by extension, any case; in g, converted
/// to m/s²) or plain text (one column of accelerations with ``dt``, or two columns ``t a``;
/// ``units``: ``"m/s2"`` (default), ``"g"`` or ``"cm/s2"``). The record is named after the file.
/// An ``.AT2`` file is in g with its own step: ``dt`` or other ``units`` for one are refused.
#[pyfunction]
#[pyo3(signature = (path, dt = None, units = None))]
pub fn read_record(
    py: Python<'_>,
    path: PathBuf,
    dt: Option<f64>,
    units: Option<&str>,
) -> PyResult<Record> {
    if records::is_at2(&path) {
        // They were ignored: a record in m/s² under an .AT2 name read 9.81 times too strong.
        if let Some(dt) = dt {
            return Err(value_error(format!(
                "dt = {dt}: a PEER .AT2 record gives its own step (DT in its header); dt is for \
                 plain-text records of one column"
            )));
        }
        if let Some(u) = units.filter(|u| *u != "g") {
            return Err(value_error(format!(
                "units = {u:?}: a PEER .AT2 record is in g (units \"g\" or none); other units \
                 are for plain-text records"
            )));
        }
    }
    let units = units.unwrap_or("m/s2");
    let scale = records::units_scale(units).ok_or_else(|| {
        value_error(format!(
            "units = {units:?}, expected \"m/s2\", \"g\" or \"cm/s2\""
        ))
    })?;
    // A missing or unreadable file is the OSError Python users expect (FileNotFoundError, …).
    crate::errors::readable(&path)?;
    let format = PlainFormat { dt, scale };
    let inner = py
        .detach(|| records::read_record(&path, &format))
        .map_err(value_error)?;
    Ok(Record { inner })
}

/// A pulse-type ground acceleration (thesis Fig. 6 and 8): build with :func:`half_sine`,
/// :func:`full_sine`, :func:`half_sines`, :func:`rectangular`, :func:`triangular`,
/// :func:`ricker` or :func:`mavroeidis_papageorgiou`.
#[pyclass(frozen, module = "rocking")]
#[derive(Clone)]
pub struct Pulse {
    pub inner: CorePulse,
}

#[pymethods]
impl Pulse {
    /// Short name of the kind (``"half sines"``, ``"rectangular"``, …).
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind()
    }

    /// The signed amplitude (m/s²); the peak ``|a|`` is its absolute value.
    #[getter]
    fn amplitude(&self) -> f64 {
        self.inner.amplitude()
    }

    /// Time after which the pulse is zero (s).
    #[getter]
    fn end_time(&self) -> f64 {
        self.inner.end_time()
    }

    /// Ground acceleration (m/s²) at ``t`` (a float or an array of times).
    fn acceleration<'py>(&self, t: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        evaluate(t, |x| self.inner.acceleration(x))
    }

    /// The same pulse with its amplitude multiplied by ``factor``.
    fn scaled(&self, factor: f64) -> PyResult<Pulse> {
        let inner = self.inner.scaled(factor);
        inner.validate().map_err(value_error)?;
        Ok(Pulse { inner })
    }

    /// The pulse as the ``excitation`` of a scene (the CLI's schema).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        match self.inner {
            CorePulse::HalfSines {
                amplitude,
                half_period,
                lobes,
            } => {
                match lobes {
                    1 => d.set_item("type", "half_sine")?,
                    _ => {
                        d.set_item("type", "half_sines")?;
                        d.set_item("count", lobes)?;
                    }
                }
                d.set_item("amplitude", amplitude)?;
                d.set_item("duration", half_period)?;
            }
            CorePulse::Rectangular {
                amplitude,
                duration,
            }
            | CorePulse::Triangular {
                amplitude,
                duration,
            } => {
                let kind = match self.inner {
                    CorePulse::Rectangular { .. } => "rectangular",
                    _ => "triangular",
                };
                d.set_item("type", kind)?;
                d.set_item("amplitude", amplitude)?;
                d.set_item("duration", duration)?;
            }
            CorePulse::Ricker {
                amplitude,
                frequency,
            } => {
                d.set_item("type", "ricker")?;
                d.set_item("amplitude", amplitude)?;
                d.set_item("frequency", frequency)?;
            }
            CorePulse::MavroeidisPapageorgiou {
                amplitude,
                frequency,
                gamma,
                nu,
            } => {
                d.set_item("type", "mavroeidis_papageorgiou")?;
                d.set_item("amplitude", amplitude)?;
                d.set_item("frequency", frequency)?;
                d.set_item("gamma", gamma)?;
                d.set_item("nu", nu)?;
            }
        }
        Ok(d)
    }

    /// Pickling (multiprocessing, ``copy.deepcopy``): rebuilt by the function that makes it.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let (maker, args) = match self.inner {
            CorePulse::HalfSines {
                amplitude,
                half_period,
                lobes,
            } => (
                "half_sines",
                (amplitude, half_period, lobes).into_pyobject(py)?,
            ),
            CorePulse::Rectangular {
                amplitude,
                duration,
            } => ("rectangular", (amplitude, duration).into_pyobject(py)?),
            CorePulse::Triangular {
                amplitude,
                duration,
            } => ("triangular", (amplitude, duration).into_pyobject(py)?),
            CorePulse::Ricker {
                amplitude,
                frequency,
            } => ("ricker", (amplitude, frequency).into_pyobject(py)?),
            CorePulse::MavroeidisPapageorgiou {
                amplitude,
                frequency,
                gamma,
                nu,
            } => (
                "mavroeidis_papageorgiou",
                (amplitude, frequency, gamma, nu).into_pyobject(py)?,
            ),
        };
        let module = py.import("rocking._rocking")?;
        Ok((module.getattr(maker)?, args))
    }

    fn __repr__(&self) -> String {
        format!("Pulse({})", self.inner.describe())
    }
}

/// The checks the CLI makes on a scene's pulse, naming the arguments as the caller wrote them
/// (the library's pulses name `half_period`, which `full_sine` halves).
fn check_pulse(amplitude: f64, field: &str, value: f64) -> PyResult<()> {
    validate::finite("amplitude", amplitude).map_err(value_error)?;
    validate::positive(field, value).map_err(value_error)?;
    Ok(())
}

fn pulse(p: Result<CorePulse, rocking::ground::excitation::ExcitationError>) -> PyResult<Pulse> {
    p.map(|inner| Pulse { inner }).map_err(value_error)
}

/// Half sine ``a sin(π t / duration)`` on ``[0, duration]`` (thesis Fig. 8a; Housner 1963).
#[pyfunction]
pub fn half_sine(amplitude: f64, duration: f64) -> PyResult<Pulse> {
    check_pulse(amplitude, "duration", duration)?;
    pulse(CorePulse::half_sine(amplitude, duration))
}

/// One full period of a sine; ``duration`` is the WHOLE period (each lobe lasts
/// ``duration / 2``, the thesis's ``t_p`` of Fig. 8b), as in the CLI's scenes.
#[pyfunction]
pub fn full_sine(amplitude: f64, duration: f64) -> PyResult<Pulse> {
    check_pulse(amplitude, "duration", duration)?;
    pulse(CorePulse::full_sine(amplitude, 0.5 * duration))
}

/// ``count`` consecutive half sines of alternating sign, each lasting ``duration`` (thesis
/// Fig. 8c: three half sines).
#[pyfunction]
pub fn half_sines(amplitude: f64, duration: f64, count: i64) -> PyResult<Pulse> {
    let lobes = u32::try_from(count)
        .ok()
        .filter(|&c| c >= 1)
        .ok_or_else(|| value_error(format!("count = {count}: must be an integer >= 1")))?;
    check_pulse(amplitude, "duration", duration)?;
    pulse(CorePulse::half_sines(amplitude, duration, lobes))
}

/// Constant ``amplitude`` on ``[0, duration)`` (thesis Fig. 6).
#[pyfunction]
pub fn rectangular(amplitude: f64, duration: f64) -> PyResult<Pulse> {
    pulse(CorePulse::rectangular(amplitude, duration))
}

/// Symmetric triangle peaking at ``duration / 2`` (thesis Fig. 6).
#[pyfunction]
pub fn triangular(amplitude: f64, duration: f64) -> PyResult<Pulse> {
    pulse(CorePulse::triangular(amplitude, duration))
}

/// Ricker wavelet of peak ``amplitude`` and central ``frequency`` (Hz).
#[pyfunction]
pub fn ricker(amplitude: f64, frequency: f64) -> PyResult<Pulse> {
    pulse(CorePulse::ricker(amplitude, frequency))
}

/// Mavroeidis–Papageorgiou (2003) near-fault pulse of peak acceleration ``amplitude``,
/// frequency ``frequency`` (Hz), oscillatory character ``gamma`` (1 < γ ≤ 100) and phase ``nu``.
#[pyfunction]
pub fn mavroeidis_papageorgiou(
    amplitude: f64,
    frequency: f64,
    gamma: f64,
    nu: f64,
) -> PyResult<Pulse> {
    pulse(CorePulse::mavroeidis_papageorgiou(
        amplitude, frequency, gamma, nu,
    ))
}
