//! The two structs of the C ABI and their conversions to and from the core's types.

use super::boundary::optional_input;
use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ModelOptions, ModelReport, Solver};

/// Options of both models. Passing NULL means `{1, ROCKING_SOLVER_AUTO, 1e-12}`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockingOptions {
    /// Consecutive impacts per closing: 1 = Housner, 2 = one bump in the middle (the thesis's
    /// recommended model), … Must be in 1..=10000, also for the opening models, which do not
    /// use it (a zero-initialised struct is refused: start from `{1, ROCKING_SOLVER_AUTO, 1e-12}`).
    pub n_impacts: u32,
    /// `ROCKING_SOLVER_AUTO` (enumeration for at most 2 closed interfaces, projection above),
    /// `ROCKING_SOLVER_ENUMERATE` (the thesis's exhaustive search, refused above 12 closed
    /// interfaces) or `ROCKING_SOLVER_PROJECTION`.
    pub solver: u32,
    /// Relative tolerance of the admissibility tests, in (0, 0.01]; 1e-12 is a good default.
    pub tolerance: f64,
}

/// What a model call did. Written only on success.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockingReport {
    /// Solver that ran: `ROCKING_SOLVER_ENUMERATE` or `ROCKING_SOLVER_PROJECTION`.
    pub solver: u32,
    /// 1 if the configuration changed (something opened; for an impact always 1).
    pub changed: u32,
    /// 1 if another admissible configuration had the same criterion to a relative 1e-9 (the
    /// choice was made deterministically by the search order).
    pub tie: u32,
    /// Consecutive impacts actually applied (an impact chain stops early if the impacting
    /// interface comes to rest on a bump); 0 for an opening.
    pub impacts_applied: u32,
    /// Configurations (enumeration) or relaxed sub-problems (projection) solved.
    pub configurations_examined: u64,
    /// Admissible configurations found (enumeration) or feasible leaves (projection).
    pub admissible: u64,
    /// Impact: kinetic energy before, ½ v⁻ᵀMv⁻. Opening: 0.
    pub kinetic_before: f64,
    /// Impact: kinetic energy after. Opening: ½ aᵀMa of the chosen configuration.
    pub kinetic_after: f64,
    /// The same measure for the best other admissible configuration examined (NaN if none).
    pub runner_up: f64,
    /// Estimate of the condition number of the chosen configuration's (scaled) system.
    pub condition_estimate: f64,
}

impl From<ModelReport> for RockingReport {
    fn from(r: ModelReport) -> RockingReport {
        RockingReport {
            solver: r.solver.code(),
            changed: u32::from(r.changed),
            tie: u32::from(r.tie),
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

impl RockingOptions {
    /// The core's options from a caller's pointer (NULL: the defaults), validated.
    ///
    /// # Safety
    /// `ptr` must be NULL or point to a `RockingOptions`.
    pub(super) unsafe fn read(ptr: *const RockingOptions) -> Result<ModelOptions, RockingError> {
        let mut o = ModelOptions::default();
        let Some(c) = optional_input(ptr, 1, "options")? else {
            return Ok(o);
        };
        let c = c[0];
        o.n_impacts = c.n_impacts;
        o.solver = Solver::from_code(c.solver).ok_or_else(|| {
            RockingError::new(
                ErrorKind::InvalidOptions,
                format!("solver = {}, expected 0, 1 or 2", c.solver),
            )
        })?;
        o.tolerance = c.tolerance;
        o.validate()?;
        Ok(o)
    }
}
