//! Overturning spectra (thesis Chapter 5, SPEC §7) through `rocking::spectra`, with the options
//! and outputs of `rocking oas`, `rocking t1` and `rocking oc` (cli/src/commands/): `oas` and
//! `t1` of a record, `oc` of a pulse shape. The sweeps run on rayon with the GIL released and
//! stop on Ctrl-C between levels (OAS) or pulse durations (OC) (`sweep.rs`): each unit is the
//! library's own call on that one level or duration, so the results are the library's to the
//! bit, whatever the number of threads. `tp` (no simulation) and `suite` (the analysis of OAS
//! already computed, as `rocking suite --merge`) run on the calling thread.

use std::path::PathBuf;
use std::time::Instant;

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyInt};
use rocking::driver::{EventLocator, Integrator};
use rocking::ground::records::{self, PlainFormat, Record as CoreRecord};
use rocking::model::single_block::EquivalentBlock;
use rocking::spectra::report::{OasReport, OcReport, SuiteReport, T1Row, TpRow};
use rocking::spectra::{
    self, column_of_size, linear_levels, log_sizes, Oas, OasLevel, OasOptions, Oc, PulseShape,
    SizeSearch, SpectraError, SweepOptions,
};
use rocking::validate;

use crate::arrays::any_vector;
use crate::errors::{positive, value_error};
use crate::ground::Record;
use crate::json::to_python;
use crate::sweep::Runner;

pub(crate) fn spectra_error(e: SpectraError) -> PyErr {
    value_error(e.to_string())
}

/// The settings of every simulation of a sweep: `rocking oas/t1/oc`'s `SimulationArgs` (a dict
/// from `_spectra.py`).
#[derive(Clone, Copy, FromPyObject)]
#[pyo3(from_item_all)]
pub struct Simulation {
    pub impacts: i64,
    pub dt_factor: f64,
    pub tail: Option<f64>,
    pub hermite: bool,
    pub rk4: bool,
    pub full_runs: bool,
}

impl Simulation {
    /// Writes these settings into `s`, as the CLI does (cli/src/commands/sweep.rs).
    fn apply(&self, s: &mut SweepOptions) -> PyResult<()> {
        let impacts = u32::try_from(self.impacts)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| value_error(format!("impacts = {}: must be >= 1", self.impacts)))?;
        validate::positive("dt_factor", self.dt_factor).map_err(value_error)?;
        s.simulation.physics.model.n_impacts = impacts;
        s.time_step = s.time_step.scaled(self.dt_factor);
        if let Some(tail) = self.tail {
            s.tail = validate::non_negative("tail", tail).map_err(value_error)?;
        }
        if self.hermite || self.rk4 {
            s.simulation.stepping.locator = EventLocator::Hermite;
        }
        if self.rk4 {
            s.simulation.stepping.integrator = Integrator::Rk4;
        }
        s.simulation.stopping.stop_when_safe = !self.full_runs;
        Ok(())
    }
}

/// A count (`int`, ≥ 1) or explicit values (an array-like).
fn count_or_values(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Result<usize, Vec<f64>>> {
    if obj.is_instance_of::<PyInt>() {
        // An int beyond 64 bits: the package's one exception, not Python's OverflowError.
        let n: i64 = obj
            .extract()
            .map_err(|_| value_error(format!("{name} = {obj}: out of range")))?;
        return usize::try_from(n)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| value_error(format!("{name} = {n}: a count must be >= 1")))
            .and_then(|n| crate::sweep::check_count(name, n))
            .map(Ok);
    }
    if obj.is_instance_of::<PyFloat>() {
        // It read as a 0-d array: "has shape (), expected 1-D".
        return Err(PyTypeError::new_err(format!(
            "{name} = {obj}: a count must be an integer (or give the values as a 1-D array)"
        )));
    }
    let values = any_vector(obj, name)?;
    if values.is_empty() {
        // A spectrum of no level, a curve of no duration: nothing computed, silently.
        return Err(value_error(format!(
            "{name}: no value; give a count >= 1 or the values"
        )));
    }
    Ok(Err(values))
}

/// A `Record`, or the path of a record file read as the CLI reads it (`.AT2` in g, plain text in
/// m/s²). Returns the record and the file (None for a `Record`).
pub(crate) fn record_of(obj: &Bound<'_, PyAny>) -> PyResult<(CoreRecord, Option<String>)> {
    if let Ok(r) = obj.cast::<Record>() {
        return Ok((r.get().inner.clone(), None));
    }
    let path: PathBuf = obj.extract().map_err(|_| {
        value_error("record: expected a rocking.Record or the path of a record file")
    })?;
    crate::errors::readable(&path)?;
    let record = records::read_record(&path, &PlainFormat::default()).map_err(value_error)?;
    Ok((record, Some(path.display().to_string())))
}

/// The grid of an OAS (`rocking oas`'s `OasGridArgs`; a dict from `_spectra.py`).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct Grid<'py> {
    pub slenderness: f64,
    pub levels: Bound<'py, PyAny>,
    pub level_max: f64,
    pub sizes: Bound<'py, PyAny>,
    pub size_min: f64,
    pub size_max: f64,
    pub blocks: i64,
    pub bisection: bool,
}

impl Grid<'_> {
    fn options(&self, simulation: &Simulation) -> PyResult<OasOptions> {
        let levels = match count_or_values(&self.levels, "levels")? {
            Ok(n) => {
                let level_max = positive("level_max", self.level_max)?;
                crate::errors::levels_from_one(level_max, n)?;
                linear_levels(1.0, level_max, n)
            }
            Err(v) => v,
        };
        let sizes = match count_or_values(&self.sizes, "sizes")? {
            Ok(n) => {
                let hi = positive("size_max", self.size_max)?;
                let lo = positive("size_min", self.size_min)?;
                crate::errors::ascending("size_min", lo, "size_max", hi, n)?;
                log_sizes(hi, lo, n)
            }
            Err(v) => v,
        };
        let n_blocks = usize::try_from(self.blocks)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| value_error(format!("blocks = {}: must be >= 1", self.blocks)))?;
        let mut o = OasOptions {
            slenderness: self.slenderness,
            levels,
            sizes,
            n_blocks,
            search: if self.bisection {
                SizeSearch::Bisection
            } else {
                SizeSearch::Scan
            },
            ..OasOptions::default()
        };
        simulation.apply(&mut o.sweep)?;
        Ok(o)
    }
}

/// The OAS of `record`, one level per unit of work (the library's `oas` on that level).
fn compute_oas(
    py: Python<'_>,
    record: &CoreRecord,
    o: &OasOptions,
    runner: &Runner,
) -> PyResult<Oas> {
    // Every check of the options and the record, before any thread starts.
    let no_levels = OasOptions {
        levels: Vec::new(),
        ..o.clone()
    };
    let mut whole = spectra::oas(record, &no_levels, None).map_err(spectra_error)?;
    let levels = runner.map(py, o.levels.len(), |k| {
        let one = OasOptions {
            levels: vec![o.levels[k]],
            ..o.clone()
        };
        spectra::oas(record, &one, None).map(|r| r.levels[0])
    })?;
    whole.levels = levels
        .into_iter()
        .collect::<Result<Vec<OasLevel>, _>>()
        .map_err(spectra_error)?;
    Ok(whole)
}

/// The OAS of a record: `(oas --json as a dict, i_cr)`; `i_cr` (Eq. 18) of the slenderness for
/// the simplified spectra of the plots. `band`, `converge_step`, `converge_halvings`: `oas
/// --band --converge-step TOL --converge-halvings N` (by default one OAS at the step rule).
#[pyfunction]
#[pyo3(signature = (
    record, grid, simulation, threads, progress, band = false, converge_step = None,
    converge_halvings = spectra::STEP_HALVINGS as i64
))]
#[allow(clippy::too_many_arguments)]
pub fn _oas<'py>(
    py: Python<'py>,
    record: &Bound<'py, PyAny>,
    grid: Grid<'py>,
    simulation: Simulation,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    band: bool,
    converge_step: Option<f64>,
    converge_halvings: i64,
) -> PyResult<(Bound<'py, PyAny>, f64)> {
    let (record, _) = record_of(record)?;
    let o = grid.options(&simulation)?;
    let method = t1_method(band, converge_step, converge_halvings)?;
    let runner = Runner { threads, progress };
    let t0 = Instant::now();
    let result = spectra::t1_of_with(&o, method, |x| compute_oas(py, &record, x, &runner))?;
    let seconds = t0.elapsed().as_secs_f64();
    let report = OasReport::of_t1(&result, seconds, simulation.dt_factor);
    Ok((to_python(py, &report)?, result.oas.i_cr()))
}

/// The method of `t1` and `oas` from their arguments: the checks of the tolerance and the
/// halvings with the arguments' names, then the library's (`T1Method::check`).
fn t1_method(
    band: bool,
    converge_step: Option<f64>,
    converge_halvings: i64,
) -> PyResult<spectra::T1Method> {
    let halvings = usize::try_from(converge_halvings)
        .ok()
        .filter(|&n| n >= 1)
        .ok_or_else(|| {
            value_error(format!(
                "converge_halvings = {converge_halvings}: must be >= 1"
            ))
        })?;
    if let Some(tol) = converge_step {
        validate::non_negative("converge_step", tol).map_err(value_error)?;
    }
    let method = spectra::T1Method {
        converge: converge_step.map(|tol| (tol, halvings)),
        band,
    };
    method.check().map_err(spectra_error)?;
    Ok(method)
}

/// `t1 --json`'s row of each record (a `Record` or a path), in order, by the library's
/// `t1_of_with` as `rocking t1` computes it: `converge_step` `Some(TOL)` converged in the step
/// (`--converge-step TOL --converge-halvings N`; the default, `STEP_TOLERANCE` and
/// `STEP_HALVINGS`), None one OAS at the step rule (`--single-step`); `band`: `--band`, at the
/// row's step. Each OAS runs on the runner, one level per unit of work, as `compute_oas`; the
/// library composes them and builds the row (`T1Row::of`), so the rows are the CLI's.
#[pyfunction]
#[pyo3(signature = (
    records, grid, simulation, threads, progress, band = false,
    converge_step = Some(spectra::STEP_TOLERANCE), converge_halvings = spectra::STEP_HALVINGS as i64
))]
#[allow(clippy::too_many_arguments)]
pub fn _t1<'py>(
    py: Python<'py>,
    records: Vec<Bound<'py, PyAny>>,
    grid: Grid<'py>,
    simulation: Simulation,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    band: bool,
    converge_step: Option<f64>,
    converge_halvings: i64,
) -> PyResult<Bound<'py, PyAny>> {
    let o = grid.options(&simulation)?;
    let method = t1_method(band, converge_step, converge_halvings)?;
    let runner = Runner { threads, progress };
    // Every record read before the first spectrum: a missing or malformed file late in the
    // list was refused only after the spectra of the records before it.
    let records = records
        .iter()
        .map(record_of)
        .collect::<PyResult<Vec<_>>>()?;
    let mut rows = Vec::with_capacity(records.len());
    for (record, file) in records {
        let t0 = Instant::now();
        let result = spectra::t1_of_with(&o, method, |x| compute_oas(py, &record, x, &runner))?;
        let t_p = spectra::replacement_sine(&record).map(|s| s.t_p);
        rows.push(T1Row::of(
            &result,
            t0.elapsed().as_secs_f64(),
            file,
            &o,
            simulation.dt_factor,
            t_p,
            None,
        ));
    }
    to_python(py, &rows)
}

/// The pulse shapes of `rocking oc --shape` (hyphens or underscores).
pub(crate) fn shape_of(name: &str) -> PyResult<PulseShape> {
    Ok(match name.replace('_', "-").as_str() {
        "half-sine" => PulseShape::half_sine(),
        "full-sine" => PulseShape::full_sine(),
        "three-half-sines" => PulseShape::three_half_sines(),
        "rectangular" => PulseShape::Rectangular,
        "triangular" => PulseShape::Triangular,
        "ricker" => PulseShape::Ricker,
        _ => {
            return Err(value_error(format!(
                "shape = {name:?}: expected half-sine, full-sine, three-half-sines, \
                 rectangular, triangular or ricker"
            )))
        }
    })
}

/// The overturning curve of a pulse shape (`rocking oc`): `oc --json` as a dict.
#[pyfunction]
#[pyo3(signature = (shape, blocks, slenderness, size, ptp, ptp_min, ptp_max, levels, level_max, simulation, threads, progress))]
#[allow(clippy::too_many_arguments)]
pub fn _oc<'py>(
    py: Python<'py>,
    shape: &str,
    blocks: i64,
    slenderness: f64,
    size: f64,
    ptp: Bound<'py, PyAny>,
    ptp_min: f64,
    ptp_max: f64,
    levels: Bound<'py, PyAny>,
    level_max: f64,
    simulation: Simulation,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = shape_of(shape)?;
    let n_blocks = usize::try_from(blocks)
        .ok()
        .filter(|&n| n >= 1)
        .ok_or_else(|| value_error(format!("blocks = {blocks}: must be >= 1")))?;
    let column = column_of_size(size, slenderness, n_blocks).map_err(spectra_error)?;
    let mut sweep = SweepOptions::default();
    simulation.apply(&mut sweep)?;
    let block = EquivalentBlock::of_column(&column);
    let g = sweep.simulation.physics.gravity;
    let (mono_p, mono_a_p_min) = (block.frequency_parameter(g), block.a_p_min(g));
    // As the CLI: p t_p log-spaced ascending, levels linear from 1.
    let ptp: Vec<f64> = match count_or_values(&ptp, "ptp")? {
        Ok(n) => {
            let (lo, hi) = (positive("ptp_min", ptp_min)?, positive("ptp_max", ptp_max)?);
            crate::errors::ascending("ptp_min", lo, "ptp_max", hi, n)?;
            log_sizes(hi, lo, n).into_iter().rev().collect()
        }
        Err(v) => v,
    };
    let t_p: Vec<f64> = ptp.iter().map(|x| x / mono_p).collect();
    let levels = match count_or_values(&levels, "levels")? {
        Ok(n) => {
            let level_max = positive("level_max", level_max)?;
            crate::errors::levels_from_one(level_max, n)?;
            linear_levels(1.0, level_max, n)
        }
        Err(v) => v,
    };
    let a_p: Vec<f64> = levels.iter().map(|l| l * mono_a_p_min).collect();
    // Every check before any thread starts; then one pulse duration per unit of work.
    let mut res = spectra::overturning_curve(&column, shape, &[], &a_p, &sweep, None)
        .map_err(spectra_error)?;
    spectra::overturning_curve(&column, shape, &t_p, &[], &sweep, None).map_err(spectra_error)?;
    let runner = Runner { threads, progress };
    let rows = runner.map(py, t_p.len(), |i| {
        spectra::overturning_curve(&column, shape, &t_p[i..=i], &a_p, &sweep, None)
            .map(|oc: Oc| oc.overturned)
    })?;
    res.t_p = t_p;
    for row in rows {
        res.overturned.extend(row.map_err(spectra_error)?);
    }
    to_python(
        py,
        &OcReport::of(&res, &a_p, n_blocks, mono_p, mono_a_p_min),
    )
}

/// The simplified OAS (Eq. 21), `max{i_cr / (t_1 p), 1}`, and the improved one with the
/// inclined line (Eq. 30), `max{1/(t_1 p), 1/(t_1'(p − 1/β)), 1}`, at each `p`: the curves of
/// the plots. Returns `(eq21, eq30)`; `eq30` is None without `t1_prime` and `beta`.
#[pyfunction]
#[pyo3(signature = (p, t1, i_cr, t1_prime = None, beta = None))]
pub fn _simplified_oas<'py>(
    py: Python<'py>,
    p: &Bound<'py, PyAny>,
    t1: f64,
    i_cr: f64,
    t1_prime: Option<f64>,
    beta: Option<f64>,
) -> PyResult<(Bound<'py, PyAny>, Option<Bound<'py, PyAny>>)> {
    let p = any_vector(p, "p")?;
    let eq21: Vec<f64> = p
        .iter()
        .map(|&x| rocking::design::simplified_oas(x, t1, i_cr))
        .collect();
    let eq30 = match (t1_prime, beta) {
        (Some(tp), Some(b)) => Some(
            p.iter()
                .map(|&x| rocking::design::improved_oas_eq30(x, t1, tp, b))
                .collect::<Vec<f64>>(),
        ),
        _ => None,
    };
    Ok((
        crate::arrays::new_vector(py, eq21).into_any(),
        eq30.map(|v| crate::arrays::new_vector(py, v).into_any()),
    ))
}

/// `tp --json`'s row of each record (a `Record` or a path), in order: the replacement sine
/// (Eq. 25).
#[pyfunction]
pub fn _tp<'py>(py: Python<'py>, records: Vec<Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyAny>> {
    let mut rows = Vec::with_capacity(records.len());
    for (k, r) in records.iter().enumerate() {
        let (record, file) = record_of(r)?;
        let s = spectra::replacement_sine(&record).ok_or_else(|| {
            value_error(format!(
                "records[{k}]: `{}` is zero everywhere",
                record.name
            ))
        })?;
        rows.push(TpRow::of(&record.name, file, &s));
    }
    to_python(py, &rows)
}

/// Fractiles in (0, 1] (`rocking suite --fractile`).
pub(crate) fn fractiles_of(fractiles: Vec<f64>) -> PyResult<Vec<f64>> {
    if fractiles.is_empty() {
        return Err(value_error("fractiles: needs at least one fractile"));
    }
    for (k, &q) in fractiles.iter().enumerate() {
        if !(q > 0.0 && q <= 1.0) {
            return Err(value_error(format!(
                "fractiles[{k}] = {q}: must be in (0, 1]"
            )));
        }
    }
    Ok(fractiles)
}

/// The suite procedure on OAS already computed, as `rocking suite --merge` on `oas --json`
/// reports: `spectra` the JSON texts of the records' reports. Returns `(suite --json as a dict,
/// i_cr of each record of the report, i_cr of each characteristic OAS)`, in the report's order.
#[pyfunction]
pub fn _suite<'py>(
    py: Python<'py>,
    spectra: Vec<String>,
    name: &str,
    fractiles: Vec<f64>,
) -> PyResult<(Bound<'py, PyAny>, Vec<f64>, Vec<f64>)> {
    let fractiles = fractiles_of(fractiles)?;
    if spectra.is_empty() {
        return Err(value_error("spectra: a suite needs at least one OAS"));
    }
    let mut out: Vec<(Oas, f64)> = Vec::with_capacity(spectra.len());
    for (k, text) in spectra.iter().enumerate() {
        let report: OasReport = serde_json::from_str(text).map_err(|e| {
            value_error(format!(
                "spectra[{k}]: not an OAS (`rocking oas --json`): {e}"
            ))
        })?;
        let seconds = report.summary.seconds;
        let Some(o) = OasReport::merge(vec![report]) else {
            continue;
        };
        if out.iter().any(|(p, _)| p.record == o.record) {
            return Err(value_error(format!(
                "spectra[{k}]: record `{}` is already in the suite",
                o.record
            )));
        }
        out.push((o, seconds));
    }
    let report = py
        .detach(|| SuiteReport::of(name, &out, &fractiles))
        .map_err(spectra_error)?;
    let i_cr = |reports: Vec<&OasReport>| -> Vec<f64> {
        reports
            .into_iter()
            .filter_map(|r| OasReport::merge(vec![r.clone()]))
            .map(|o| o.i_cr())
            .collect()
    };
    let records = i_cr(report.records.iter().collect());
    let characteristic = i_cr(report.characteristic.iter().map(|c| &c.oas).collect());
    Ok((to_python(py, &report)?, records, characteristic))
}
