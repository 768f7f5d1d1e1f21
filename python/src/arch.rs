//! Spectra of voussoir arches (issue 15, item 5) through `rocking::spectra`, with the options and
//! the JSON of `rocking arch oas`, `rocking arch oc` and `rocking arch suite`
//! (cli/src/commands/arch.rs, arch_suite.rs). The sweeps run as the single-block ones
//! (`spectra.rs`): on rayon with the GIL released, interruptible between levels (OAS) or pulse
//! durations (OC); each unit is the library's own call (`arch_oas` on one level, `arch_oc_row`
//! on one duration) and the units are assembled as the library assembles them, so the results
//! are the CLI's to the bit.

use std::time::Instant;

use pyo3::prelude::*;
use rocking::spectra::arch_report::{ArchOasReport, ArchOcReport, ArchSuiteReport};
use rocking::spectra::{
    self, characteristic_arch_oas, linear_levels, log_sizes, ArchOas, ArchOasOptions, ArchRecord,
    ArchShape, ArchSweepOptions, OasLevel,
};

use crate::errors::{positive, value_error};
use crate::json::to_python;
use crate::spectra::{fractiles_of, record_of, shape_of, spectra_error};
use crate::sweep::Runner;

/// The arch family and the runs' settings (`rocking arch`'s `ArchFamilyArgs`; a dict from
/// `_arch.py`).
#[derive(Clone, Copy, FromPyObject)]
#[pyo3(from_item_all)]
pub struct Family {
    pub thickness_ratio: f64,
    pub embrace: f64,
    pub voussoirs: i64,
    pub dt_factor: f64,
}

/// A count `>= 1`, named.
fn count(name: &str, n: i64) -> PyResult<usize> {
    usize::try_from(n)
        .ok()
        .filter(|&n| n >= 1)
        .ok_or_else(|| value_error(format!("{name} = {n}: must be >= 1")))
        .and_then(|n| crate::sweep::check_count(name, n))
}

impl Family {
    /// The sweep options, as the CLI's `ArchFamilyArgs::options`.
    fn options(&self) -> PyResult<ArchSweepOptions> {
        // Judged as given, in degrees and as t/R (the arch's own checks name `arch.embrace_angle`
        // in radians and `arch.thickness`).
        if !(self.embrace > 0.0 && self.embrace < 360.0) {
            return Err(value_error(format!(
                "embrace = {}: must be greater than 0 and less than 360 degrees (a full ring has \
                 no abutments)",
                self.embrace
            )));
        }
        if !(self.thickness_ratio > 0.0 && self.thickness_ratio < 2.0) {
            return Err(value_error(format!(
                "thickness_ratio = {}: must be greater than 0 and less than 2 (the intrados \
                 radius R − t/2 must be positive)",
                self.thickness_ratio
            )));
        }
        let mut o = ArchSweepOptions {
            shape: ArchShape {
                thickness_ratio: positive("thickness_ratio", self.thickness_ratio)?,
                embrace_angle: positive("embrace", self.embrace)?.to_radians(),
                voussoirs: count("voussoirs", self.voussoirs)?,
            },
            ..ArchSweepOptions::default()
        };
        o.time_step = o.time_step.scaled(positive("dt_factor", self.dt_factor)?);
        Ok(o)
    }
}

/// The arch OAS of a record: `arch oas --json` as a dict.
#[pyfunction]
#[pyo3(signature = (record, family, radius_max, radius_min, radius_n, level_min, level_max, level_n, t1, threads, progress))]
#[allow(clippy::too_many_arguments)]
pub fn _arch_oas<'py>(
    py: Python<'py>,
    record: &Bound<'py, PyAny>,
    family: Family,
    radius_max: f64,
    radius_min: f64,
    radius_n: i64,
    level_min: f64,
    level_max: f64,
    level_n: i64,
    t1: Option<f64>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let sweep = family.options()?;
    let (radius_max, radius_min) = (
        positive("radius_max", radius_max)?,
        positive("radius_min", radius_min)?,
    );
    let radius_n = count("radius_n", radius_n)?;
    if radius_min >= radius_max && radius_n > 1 {
        return Err(value_error(format!(
            "radius_min = {radius_min}: must be below radius_max ({radius_max})"
        )));
    }
    let (level_min, level_max) = (
        positive("level_min", level_min)?,
        positive("level_max", level_max)?,
    );
    let level_n = count("level_n", level_n)?;
    crate::errors::ascending("level_min", level_min, "level_max", level_max, level_n)?;
    let t1 = t1.map(|t| positive("t1", t)).transpose()?;
    let (record, _) = record_of(record)?;
    let o = ArchOasOptions {
        levels: linear_levels(level_min, level_max, level_n),
        sizes: log_sizes(radius_max, radius_min, radius_n),
        sweep,
    };
    let runner = Runner { threads, progress };
    let t0 = Instant::now();
    // Every check and the onset, before any thread starts; then one level per unit, merged in
    // level order as `arch_oas` merges them.
    let mut whole = spectra::arch_oas(
        &record,
        &ArchOasOptions {
            levels: Vec::new(),
            ..o.clone()
        },
        None,
    )
    .map_err(spectra_error)?;
    let levels = runner.map(py, o.levels.len(), |k| {
        let one = ArchOasOptions {
            levels: vec![o.levels[k]],
            ..o.clone()
        };
        spectra::arch_oas(&record, &one, None)
    })?;
    for level in levels {
        let one = level.map_err(spectra_error)?;
        let l: OasLevel = one.levels[0];
        whole.levels.push(l);
        whole.runs.merge(&one.runs);
    }
    let seconds = t0.elapsed().as_secs_f64();
    to_python(py, &ArchOasReport::of(&whole, t1, seconds))
}

/// The overturning curve of an arch under a pulse: `arch oc --json` as a dict.
#[pyfunction]
#[pyo3(signature = (shape, family, radius, ptp_min, ptp_max, ptp_n, level_max, level_n, threads, progress))]
#[allow(clippy::too_many_arguments)]
pub fn _arch_oc<'py>(
    py: Python<'py>,
    shape: &str,
    family: Family,
    radius: f64,
    ptp_min: f64,
    ptp_max: f64,
    ptp_n: i64,
    level_max: f64,
    level_n: i64,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let pulse = shape_of(shape)?;
    let options = family.options()?;
    let radius = positive("radius", radius)?;
    let (ptp_min, ptp_max) = (positive("ptp_min", ptp_min)?, positive("ptp_max", ptp_max)?);
    let ptp_n = count("ptp_n", ptp_n)?;
    let level_max = positive("level_max", level_max)?;
    let level_n = count("level_n", level_n)?;
    crate::errors::ascending("ptp_min", ptp_min, "ptp_max", ptp_max, ptp_n)?;
    crate::errors::levels_from_one(level_max, level_n)?;
    let sim = &options.simulation;
    let onset =
        spectra::arch_onset(&options.shape, sim.gravity, &sim.model).map_err(spectra_error)?;
    let p = onset.p(radius);
    // As the CLI: p t_p log-spaced ascending, levels linear from 1.
    let t_p: Vec<f64> = log_sizes(ptp_max, ptp_min, ptp_n)
        .into_iter()
        .rev()
        .map(|x| x / p)
        .collect();
    let levels = linear_levels(1.0, level_max, level_n);
    let t0 = Instant::now();
    // Every check before any thread starts (no duration: no run); then one duration per unit,
    // assembled in order as `arch_overturning_curve` assembles them.
    let mut oc = spectra::arch_overturning_curve(pulse, radius, &[], &levels, &options, None)
        .map_err(spectra_error)?;
    spectra::arch_overturning_curve(pulse, radius, &t_p, &[], &options, None)
        .map_err(spectra_error)?;
    let runner = Runner { threads, progress };
    let rows = runner.map(py, t_p.len(), |i| {
        spectra::arch_oc_row(pulse, &oc.onset, t_p[i], &levels, radius, &options)
    })?;
    for (i, row) in rows.into_iter().enumerate() {
        oc.push_row(t_p[i], row.map_err(spectra_error)?);
    }
    to_python(py, &ArchOcReport::of(&oc, t0.elapsed().as_secs_f64()))
}

/// The suite procedure on arch OAS already computed (`rocking arch suite --json` as a dict):
/// `spectra` the JSON texts of `arch oas` reports, one record each, one arch and grid.
#[pyfunction]
pub fn _arch_suite<'py>(
    py: Python<'py>,
    spectra: Vec<String>,
    name: &str,
    fractiles: Vec<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let fractiles = fractiles_of(fractiles)?;
    let mut records: Vec<ArchRecord> = Vec::with_capacity(spectra.len());
    for (k, text) in spectra.iter().enumerate() {
        let report: ArchOasReport = serde_json::from_str(text).map_err(|e| {
            value_error(format!(
                "spectra[{k}]: not an arch OAS (`rocking arch oas`): {e}"
            ))
        })?;
        let oas: ArchOas = report
            .to_oas()
            .map_err(|e| value_error(format!("spectra[{k}]: {e}")))?;
        if records.iter().any(|r| r.oas.record == oas.record) {
            return Err(value_error(format!(
                "spectra[{k}]: record `{}` is already in the suite",
                oas.record
            )));
        }
        // One arch and grid: as the CLI, the first record's against each other.
        if let Some(first) = records.first() {
            characteristic_arch_oas(&[first.oas.clone(), oas.clone()], 1.0, "check")
                .map_err(|e| value_error(format!("spectra[{k}]: {e}")))?;
        }
        records.push(ArchRecord {
            t_p: None,
            block_t1: report.check.as_ref().map(|c| c.t1),
            oas,
        });
    }
    let report = py
        .detach(|| ArchSuiteReport::of(name, &records, &fractiles))
        .map_err(spectra_error)?;
    to_python(py, &report)
}
