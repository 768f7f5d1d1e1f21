//! The two models and the reaction test: `impact_model`, `opening_model`,
//! `check_configuration`. Inputs are copied, outputs are new arrays, the caller's arrays are
//! never written (the library's functions work in place on the copies).

use pyo3::exceptions::{PyOverflowError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::model::configuration::{self, Status};
use rocking::{ErrorKind, ModelOptions, ModelReport, Solver};

use crate::arrays::{matrix, new_statuses, new_vector, statuses, vector};
use crate::errors::{error, IntoPy};

/// What a model call did (thesis 3.2.2, 3.2.3; the C ABI's `RockingReport`).
#[pyclass(frozen, module = "rocking", get_all)]
#[derive(Clone)]
pub struct Report {
    /// The solver that ran: ``"enumerate"`` or ``"projection"``.
    pub solver: &'static str,
    /// Whether the configuration changed (something opened; always True for an impact).
    pub changed: bool,
    /// Another admissible configuration had the same criterion to a relative 1e-9: the choice
    /// was made by the fixed search order (deterministic).
    pub tie: bool,
    /// Consecutive impacts actually applied (0 for an opening).
    pub impacts_applied: u32,
    /// Configurations (enumeration) or relaxed sub-problems (projection) solved.
    pub configurations_examined: u64,
    /// Admissible configurations found (enumeration) or feasible leaves (projection).
    pub admissible: u64,
    /// Impact: kinetic energy before, ½ v⁻ᵀMv⁻. Opening: 0.
    pub kinetic_before: f64,
    /// Impact: kinetic energy after, ½ v⁺ᵀMv⁺. Opening: ½ aᵀMa of the chosen configuration.
    pub kinetic_after: f64,
    /// The same measure for the best other admissible configuration (NaN if none).
    pub runner_up: f64,
    /// Estimate of the condition number of the chosen configuration's (scaled) system.
    pub condition_estimate: f64,
}

fn solver_name(s: Solver) -> &'static str {
    match s {
        Solver::Auto => "auto",
        Solver::Enumerate => "enumerate",
        Solver::Projection => "projection",
    }
}

impl From<ModelReport> for Report {
    fn from(r: ModelReport) -> Report {
        Report {
            solver: solver_name(r.solver),
            changed: r.changed,
            tie: r.tie,
            impacts_applied: r.impacts_applied,
            configurations_examined: r.configurations_examined,
            admissible: r.admissible,
            kinetic_before: r.kinetic_before,
            kinetic_after: r.kinetic_after,
            runner_up: r.runner_up,
            condition_estimate: r.condition_estimate,
        }
    }
}

#[pymethods]
impl Report {
    /// Relative margin of the choice over the runner-up, ``(kinetic_after − runner_up) /
    /// kinetic_after`` (NaN without a runner-up; 0 for a tie).
    #[getter]
    fn runner_up_gap(&self) -> f64 {
        (self.kinetic_after - self.runner_up) / self.kinetic_after
    }

    /// Impact: the fraction of kinetic energy lost, ``1 − kinetic_after / kinetic_before``
    /// (NaN for an opening).
    #[getter]
    fn energy_loss(&self) -> f64 {
        if self.kinetic_before > 0.0 {
            1.0 - self.kinetic_after / self.kinetic_before
        } else {
            f64::NAN
        }
    }

    /// The report as a dict, with the keys of ``report`` in the CLI's events.jsonl
    /// (``runner_up`` None when there is none).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("admissible", self.admissible)?;
        d.set_item("changed", self.changed)?;
        d.set_item("condition_estimate", self.condition_estimate)?;
        d.set_item("configurations_examined", self.configurations_examined)?;
        d.set_item("impacts_applied", self.impacts_applied)?;
        d.set_item("kinetic_after", self.kinetic_after)?;
        d.set_item("kinetic_before", self.kinetic_before)?;
        d.set_item(
            "runner_up",
            (!self.runner_up.is_nan()).then_some(self.runner_up),
        )?;
        d.set_item("solver", self.solver)?;
        d.set_item("tie", self.tie)?;
        Ok(d)
    }

    /// Pickling (multiprocessing, ``copy.deepcopy``): rebuilt from its fields.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        (&'static str, bool, bool, u32, u64, u64, f64, f64, f64, f64),
    )> {
        let maker = py.import("rocking._rocking")?.getattr("_report")?;
        Ok((
            maker,
            (
                self.solver,
                self.changed,
                self.tie,
                self.impacts_applied,
                self.configurations_examined,
                self.admissible,
                self.kinetic_before,
                self.kinetic_after,
                self.runner_up,
                self.condition_estimate,
            ),
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "Report(solver={:?}, changed={}, tie={}, impacts_applied={}, \
             configurations_examined={}, admissible={}, kinetic_before={:?}, kinetic_after={:?}, \
             runner_up={}, condition_estimate={:?})",
            self.solver,
            py_bool(self.changed),
            py_bool(self.tie),
            self.impacts_applied,
            self.configurations_examined,
            self.admissible,
            self.kinetic_before,
            self.kinetic_after,
            py_float(self.runner_up),
            self.condition_estimate
        )
    }
}

/// A `Report` from its fields, in the order of its `__reduce__` (unpickling).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn _report(
    solver: &str,
    changed: bool,
    tie: bool,
    impacts_applied: u32,
    configurations_examined: u64,
    admissible: u64,
    kinetic_before: f64,
    kinetic_after: f64,
    runner_up: f64,
    condition_estimate: f64,
) -> PyResult<Report> {
    let solver = match solver {
        "auto" => "auto",
        "enumerate" => "enumerate",
        "projection" => "projection",
        other => {
            return Err(error(
                ErrorKind::InvalidOptions,
                format!("solver = {other:?}, expected \"auto\", \"enumerate\" or \"projection\""),
            ))
        }
    };
    Ok(Report {
        solver,
        changed,
        tie,
        impacts_applied,
        configurations_examined,
        admissible,
        kinetic_before,
        kinetic_after,
        runner_up,
        condition_estimate,
    })
}

fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

fn py_float(x: f64) -> String {
    if x.is_nan() {
        "nan".to_string()
    } else {
        format!("{x:?}")
    }
}

/// The options of a call, checked (`InvalidOptions` names the argument).
/// An integer argument without a default (numpy's too): `None` for one beyond 64 bits (for the
/// caller's range error: the model's, not Python's `OverflowError`); not an integer, a
/// TypeError naming it.
fn integer(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Option<i64>> {
    match obj.extract::<i64>() {
        Ok(v) => Ok(Some(v)),
        Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => Ok(None),
        Err(e) => Err(PyTypeError::new_err(format!(
            "{name}: expected an integer ({e})"
        ))),
    }
}

fn options(n_impacts: i64, solver: &str, tolerance: f64) -> PyResult<ModelOptions> {
    let solver = match solver {
        "auto" => Solver::Auto,
        "enumerate" => Solver::Enumerate,
        "projection" => Solver::Projection,
        other => {
            return Err(error(
                ErrorKind::InvalidOptions,
                format!("solver = {other:?}, expected \"auto\", \"enumerate\" or \"projection\""),
            ))
        }
    };
    let n_impacts = u32::try_from(n_impacts).map_err(|_| {
        error(
            ErrorKind::InvalidOptions,
            format!("n_impacts = {n_impacts}, expected 1..=10000"),
        )
    })?;
    let o = ModelOptions {
        n_impacts,
        solver,
        tolerance,
        ..ModelOptions::default()
    };
    o.validate().py()?;
    Ok(o)
}

fn decode(raw: &[i8]) -> PyResult<Vec<Status>> {
    configuration::decode_statuses(raw).py()
}

fn encode(st: &[Status]) -> Vec<i8> {
    st.iter().map(|s| s.as_i8()).collect()
}

/// Impact model (thesis 3.2.3, Eq. 7–8, Appendix A and B; SPEC §2): interface
/// ``closing_interface`` closes; returns the configuration after the impact and the DOF rates
/// after it.
///
/// ``mass`` is the ``2n × 2n`` interface mass matrix (thesis Eq. 10 for the two-block example;
/// :func:`column_mass_matrix` or :func:`reduce` give it), DOF order ``[phĭ_0 … phĭ_{n-1}, phî_0
/// … phî_{n-1}]``; ``status`` the ``n`` interface statuses before (−1 open about the right
/// corner, 0 closed, +1 open about the left corner); ``velocity`` the ``2n`` DOF rates before
/// (zero on DOFs that are not open); ``closing_interface`` an open interface whose DOF moves
/// towards zero. ``n_impacts``: consecutive impacts over equally spaced bumps (1 = Housner,
/// 2 = one bump in the middle, the thesis's recommended model). ``solver``: ``"auto"``,
/// ``"enumerate"`` (the thesis's exhaustive search) or ``"projection"`` (SPEC §4).
///
/// Returns ``(status, velocity, report)``: new int8 and float64 arrays and a :class:`Report`.
/// The arguments are never modified. Raises :class:`RockingError` naming the bad argument.
#[pyfunction]
#[pyo3(signature = (mass, status, velocity, closing_interface, n_impacts = 1, solver = "auto", tolerance = 1e-12))]
#[allow(clippy::too_many_arguments)]
pub fn impact_model<'py>(
    py: Python<'py>,
    mass: &Bound<'py, PyAny>,
    status: &Bound<'py, PyAny>,
    velocity: &Bound<'py, PyAny>,
    closing_interface: &Bound<'py, PyAny>,
    n_impacts: i64,
    solver: &str,
    tolerance: f64,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Report)> {
    let opts = options(n_impacts, solver, tolerance)?;
    let raw = statuses(status, "status")?;
    let n = raw.len();
    configuration::check_size(n).py()?;
    let mass = matrix(mass, "mass", 2 * n, 2 * n)?;
    let mut v = vector(velocity, "velocity", 2 * n)?;
    let mut st = decode(&raw)?;
    // An integer (numpy's too) out of range, even beyond 64 bits, is the model's error; what is
    // not an integer is a TypeError.
    let out_of_range = || {
        error(
            ErrorKind::InvalidClosingInterface,
            format!("closing_interface = {closing_interface}, expected 0..{n}"),
        )
    };
    let closing = integer(closing_interface, "closing_interface")?
        .and_then(|c| usize::try_from(c).ok())
        .ok_or_else(out_of_range)?;
    let report = rocking::impact_model(&mass, &mut st, &mut v, closing, &opts).py()?;
    Ok((
        new_statuses(py, encode(&st)).into_any(),
        new_vector(py, v).into_any(),
        report.into(),
    ))
}

/// Opening model (thesis 3.2.2, Fig. 18–19; SPEC §3): when the eccentricity test fires, which
/// closed interfaces open and which way, and the DOF accelerations of that configuration
/// (``M_FF a_F = q_F``, thesis Eq. 6). If the current configuration holds it is kept
/// (``report.changed`` False).
///
/// ``mass``: ``2n × 2n`` as for :func:`impact_model`; ``load``: the ``2n`` generalised loads
/// ``q`` (``Bᵀp``); ``status``: the ``n`` statuses.
///
/// Returns ``(status, acceleration, report)``, new arrays; the arguments are never modified.
#[pyfunction]
#[pyo3(signature = (mass, load, status, solver = "auto", tolerance = 1e-12))]
pub fn opening_model<'py>(
    py: Python<'py>,
    mass: &Bound<'py, PyAny>,
    load: &Bound<'py, PyAny>,
    status: &Bound<'py, PyAny>,
    solver: &str,
    tolerance: f64,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Report)> {
    let opts = options(1, solver, tolerance)?;
    let raw = statuses(status, "status")?;
    let n = raw.len();
    configuration::check_size(n).py()?;
    let mass = matrix(mass, "mass", 2 * n, 2 * n)?;
    let load = vector(load, "load", 2 * n)?;
    let mut st = decode(&raw)?;
    let mut a = vec![0.0; 2 * n];
    let report = rocking::opening_model(&mass, &load, &mut st, &mut a, &opts).py()?;
    Ok((
        new_statuses(py, encode(&st)).into_any(),
        new_vector(py, a).into_any(),
        report.into(),
    ))
}

/// The eccentricity test as reaction signs (thesis 3.2.2; SPEC §3): does configuration
/// ``status`` hold under ``load``?
///
/// Returns ``(holds, reactions, must_open)``: a bool; the ``2n`` generalised contact reactions
/// ``λ = M a − q`` (zero on open DOFs; admissible ``λ <= 0`` on ``phĭ_k``, ``λ >= 0`` on
/// ``phî_k`` of a closed interface); the closed interfaces that must open (int array).
#[pyfunction]
#[pyo3(signature = (mass, load, status, tolerance = 1e-12))]
pub fn check_configuration<'py>(
    py: Python<'py>,
    mass: &Bound<'py, PyAny>,
    load: &Bound<'py, PyAny>,
    status: &Bound<'py, PyAny>,
    tolerance: f64,
) -> PyResult<(bool, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    options(1, "auto", tolerance)?;
    let raw = statuses(status, "status")?;
    let n = raw.len();
    configuration::check_size(n).py()?;
    let mass = matrix(mass, "mass", 2 * n, 2 * n)?;
    let load = vector(load, "load", 2 * n)?;
    let st = decode(&raw)?;
    let check = rocking::check_configuration(&mass, &load, &st, tolerance).py()?;
    let must_open: Vec<i64> = check.must_open.iter().map(|&k| k as i64).collect();
    Ok((
        check.holds(),
        new_vector(py, check.reactions).into_any(),
        numpy::IntoPyArray::into_pyarray(must_open, py).into_any(),
    ))
}

/// Benchmark hook (`python/benches/overhead.py`): mean seconds per call of the library's impact
/// model alone on these inputs, over `repeats` calls (the inputs converted once, the in-place
/// arrays reset before each call as a C caller would), so that the binding's overhead is the
/// Python call's time minus this, measured in one process.
#[pyfunction]
#[pyo3(signature = (mass, status, velocity, closing_interface, n_impacts = 1, repeats = 100_000))]
pub fn _time_impact_model(
    mass: &Bound<'_, PyAny>,
    status: &Bound<'_, PyAny>,
    velocity: &Bound<'_, PyAny>,
    closing_interface: usize,
    n_impacts: i64,
    repeats: u32,
) -> PyResult<f64> {
    let opts = options(n_impacts, "auto", 1e-12)?;
    let st0 = decode(&statuses(status, "status")?)?;
    let n = st0.len();
    let mass = matrix(mass, "mass", 2 * n, 2 * n)?;
    let v0 = vector(velocity, "velocity", 2 * n)?;
    let (mut st, mut v) = (st0.clone(), v0.clone());
    let start = std::time::Instant::now();
    for _ in 0..repeats.max(1) {
        st.copy_from_slice(&st0);
        v.copy_from_slice(&v0);
        let r = rocking::impact_model(
            std::hint::black_box(&mass),
            &mut st,
            &mut v,
            closing_interface,
            &opts,
        )
        .py()?;
        std::hint::black_box((&st, &v, r));
    }
    Ok(start.elapsed().as_secs_f64() / f64::from(repeats.max(1)))
}
