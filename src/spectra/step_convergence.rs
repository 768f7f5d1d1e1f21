//! `t_1` converged in the time step (issue 14, item 2): the OAS again at half the step, and again,
//! until two successive steps give `t_1` within a tolerance.
//!
//! The default step rule ([`super::TimeStep::default`]) gives `t_1` within 10 % of the half step's
//! on 95 of the 100 FEMA P695 records; on the other five, `t_1` moves by 12–21 % when the step
//! halves and settles only at a quarter or an eighth of it (`docs/t1-accuracy.md`). A finer
//! default for every record would multiply the cost of every OAS; this procedure pays for the
//! finer steps only where the record needs them. It stops at the first pair of successive
//! steps whose `t_1` agree (`max / min − 1 ≤ tolerance`, or both without overturning) and returns
//! the finer spectrum of that pair; after `max_halvings` halvings without agreement it returns
//! the finest spectrum, marked not converged.

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
