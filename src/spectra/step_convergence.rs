//! `t_1` converged in the time step (issue 14, item 2): the OAS again at half the step, and again,
//! until two successive steps give `t_1` within a tolerance. It is how `rocking t1` (and the
//! Python package's `t1`) compute `t_1` by default ([`T1Method`]).
//!
//! The step rule ([`super::TimeStep::default`]) gives `t_1` within 10 % of the half step's on 95
//! of the 100 FEMA P695 records; on the other five, `t_1` moves by 12–21 % when the step halves
//! and settles only at a quarter or an eighth of it, and on one (FF-9 DLT262) it never settles,
//! its governing point chaotic (`docs/t1-accuracy.md`). A finer step rule for every record would
//! multiply the cost of every OAS by the finest factor any record needs; this procedure pays for
//! the finer steps only where the record needs them (about 3× one OAS where the half step
//! agrees). It stops at the first pair of successive steps whose `t_1` agree (`max / min − 1 ≤
//! tolerance`, or both without overturning) and returns the finer spectrum of that pair; after
//! `max_halvings` halvings without agreement it returns the finest spectrum, marked not
//! converged. `rocking oas` and `rocking suite` use the step rule alone (one OAS per record).

use super::{oas, Oas, OasOptions, Progress, SpectraError};

/// The `t_1` of each step tried and whether the last two agree.
#[derive(Clone, Debug, PartialEq)]
pub struct StepConvergence {
    /// `(factor, t_1)` for each step tried, the given options' first (factor 1, relative to
    /// them), each the half of the one before (`None`: nothing overturned on the grid).
    pub steps: Vec<(f64, Option<f64>)>,
    /// Whether the last two steps agree within the tolerance.
    pub converged: bool,
    /// Simulations of all steps.
    pub simulations: usize,
}

impl StepConvergence {
    /// The factor of the step whose spectrum is returned (the last tried).
    pub fn factor(&self) -> f64 {
        self.steps.last().map_or(1.0, |s| s.0)
    }
}

/// Whether two `t_1` agree within `tolerance` (`max / min − 1`); two spectra without
/// overturning agree, one with and one without do not.
pub fn t1_agree(a: Option<f64>, b: Option<f64>, tolerance: f64) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => x.max(y) <= x.min(y) * (1.0 + tolerance),
        _ => false,
    }
}

/// The OAS of `record` at the step of `options`, then at half of it, and so on, until two
/// successive `t_1` agree within `tolerance` or after `max_halvings` halvings; the finest
/// spectrum computed and the history of the steps.
pub fn t1_step_converged(
    record: &crate::ground::records::Record,
    options: &OasOptions,
    tolerance: f64,
    max_halvings: usize,
    progress: Option<Progress<'_>>,
) -> Result<(Oas, StepConvergence), SpectraError> {
    check_step_convergence(tolerance, max_halvings)?;
    t1_step_converged_with(options, tolerance, max_halvings, |o| {
        oas(record, o, progress)
    })
}

/// The checks of [`t1_step_converged`]'s `tolerance` (finite, ≥ 0) and `max_halvings` (≥ 1).
pub fn check_step_convergence(tolerance: f64, max_halvings: usize) -> Result<(), SpectraError> {
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(SpectraError::InvalidOption {
            field: "step_tolerance",
            reason: format!("{tolerance} (must be finite and >= 0)"),
        });
    }
    if max_halvings == 0 {
        return Err(SpectraError::InvalidOption {
            field: "step_halvings",
            reason: "0 (must be at least 1)".to_string(),
        });
    }
    Ok(())
}

/// [`t1_step_converged`] with each spectrum computed by `spectrum` (the OAS of the record under
/// the options given, as [`oas`] computes it): for a caller that runs the OAS its own way (the
/// Python package, on its interruptible runner), with the same spectra and the same history.
/// The caller checks `tolerance` and `max_halvings` first ([`check_step_convergence`]; with
/// `max_halvings` 0 this computes the one spectrum, not converged).
pub fn t1_step_converged_with<E>(
    options: &OasOptions,
    tolerance: f64,
    max_halvings: usize,
    mut spectrum: impl FnMut(&OasOptions) -> Result<Oas, E>,
) -> Result<(Oas, StepConvergence), E> {
    let mut o = options.clone();
    let mut factor = 1.0;
    let mut current = spectrum(&o)?;
    let mut steps = vec![(factor, current.t1())];
    let mut simulations = current.simulations();
    let mut converged = false;
    for _ in 0..max_halvings {
        factor *= 0.5;
        o.sweep.time_step = o.sweep.time_step.scaled(0.5);
        let finer = spectrum(&o)?;
        simulations += finer.simulations();
        let previous = current.t1();
        current = finer;
        steps.push((factor, current.t1()));
        if t1_agree(previous, current.t1(), tolerance) {
            converged = true;
            break;
        }
    }
    Ok((
        current,
        StepConvergence {
            steps,
            converged,
            simulations,
        },
    ))
}

/// The tolerance of `rocking t1`'s default convergence in the step (`max / min − 1` of two
/// successive `t_1`): the band `t1_converged_in_dt` asserts on the bundled record.
pub const STEP_TOLERANCE: f64 = 0.1;
/// The most halvings of the step by default (down to a sixteenth of the step rule).
pub const STEP_HALVINGS: usize = 4;

/// How `t_1` is computed (`rocking t1` and the Python package's `t1`): by default converged in
/// the step ([`STEP_TOLERANCE`], [`STEP_HALVINGS`]), without the band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct T1Method {
    /// `Some((tolerance, max_halvings))`: the step halved until `t_1` converges
    /// ([`t1_step_converged`]); `None`: one OAS at the options' step.
    pub converge: Option<(f64, usize)>,
    /// Also the band of `t_1` ([`super::t1_band`]) around the row's spectrum, at its step.
    pub band: bool,
}

impl Default for T1Method {
    fn default() -> T1Method {
        T1Method {
            converge: Some((STEP_TOLERANCE, STEP_HALVINGS)),
            band: false,
        }
    }
}

impl T1Method {
    /// One OAS at the options' step (the procedure before `t_1` converged by default).
    pub const SINGLE_STEP: T1Method = T1Method {
        converge: None,
        band: false,
    };

    /// The checks of the tolerance and the halvings ([`check_step_convergence`]).
    pub fn check(&self) -> Result<(), SpectraError> {
        match self.converge {
            Some((tolerance, halvings)) => check_step_convergence(tolerance, halvings),
            None => Ok(()),
        }
    }

    /// The fewest spectra the method computes (for a progress bar: two steps when converging,
    /// four more with the band).
    pub fn min_spectra(&self) -> usize {
        let steps = if self.converge.is_some() { 2 } else { 1 };
        steps + if self.band { 4 } else { 0 }
    }
}

/// `t_1` of a record as [`T1Method`] computes it.
#[derive(Clone, Debug, PartialEq)]
pub struct T1Result {
    /// The row's spectrum (the finest step's when converging).
    pub oas: Oas,
    /// The steps tried, when converging.
    pub steps: Option<StepConvergence>,
    /// The band around `oas`, at its step.
    pub band: Option<super::T1Band>,
}

impl T1Result {
    /// The factor of the row's step relative to the options' (1 without convergence).
    pub fn factor(&self) -> f64 {
        self.steps.as_ref().map_or(1.0, StepConvergence::factor)
    }
}

/// `t_1` of `record` under `options` by `method` (checked first).
pub fn t1_of(
    record: &crate::ground::records::Record,
    options: &OasOptions,
    method: T1Method,
    progress: Option<Progress<'_>>,
) -> Result<T1Result, SpectraError> {
    method.check()?;
    t1_of_with(options, method, |o| oas(record, o, progress))
}

/// [`t1_of`] with each spectrum computed by `spectrum` (as [`t1_step_converged_with`]); the
/// caller checks the method first ([`T1Method::check`]). With the band, the spectra are the
/// steps', then the band's other members at the row's step.
pub fn t1_of_with<E>(
    options: &OasOptions,
    method: T1Method,
    mut spectrum: impl FnMut(&OasOptions) -> Result<Oas, E>,
) -> Result<T1Result, E> {
    let (oas, steps) = match method.converge {
        Some((tolerance, halvings)) => {
            let (oas, steps) = t1_step_converged_with(options, tolerance, halvings, &mut spectrum)?;
            (oas, Some(steps))
        }
        None => (spectrum(options)?, None),
    };
    let factor = steps.as_ref().map_or(1.0, StepConvergence::factor);
    let (oas, band) = if method.band {
        let (oas, band) = super::band::t1_band_around(oas, &options.at_step(factor), spectrum)?;
        (oas, Some(band))
    } else {
        (oas, None)
    };
    Ok(T1Result { oas, steps, band })
}
