//! Overturning spectra (thesis Chapter 5; SPEC §7): overturning curves (OC) of pulses, the
//! overturning acceleration spectrum (OAS) of a record, its transformed form (Eq. 19), the
//! replacement impulse duration `t_1` (Eq. 20), the improved fits `t_1'`, `β` (Eq. 28–30) and a
//! check that the simplified spectra (Eq. 21, 29, 30) are conservative against the computed one.
//!
//! Every point is one time history of the reference driver ([`crate::driver::overturns`]):
//! a column of rigid blocks, at rest and closed, under the scaled motion; *unsafe* means the
//! driver reports overturning (static tipping of the part above some interface, SPEC §5; with
//! `continue_until_fallen`, a block rotated by `π/2`).
//!
//! Axes. A column is described by its *equivalent block* ([`EquivalentBlock::of_column`]): the
//! uniform block of the bottom block's width `B` and the total height `H`, `tan δ = B/H`,
//! `R = ½√(B² + H²)`, `p = √(g/(αR))`, `α = 4/3`, `a_p,min = g tan δ` (Eq. 3, 13). For a single
//! uniform block these are exact; for a stack of equal-width blocks they are the axes of thesis
//! Fig. 40/43 (the column "has the same aspect ratio" as the monolith).
//!
//! [`EquivalentBlock::of_column`]: crate::model::single_block::EquivalentBlock::of_column
//!
//! Time step ([`TimeStep`]): `dt = min(record_fraction · Δt_record, pulse_fraction · t_p,
//! block_fraction / p)`; convergence in `dt` is shown in `docs/t1-accuracy.md` and tested.
//!
//! Sweeps are parallel over levels (OAS) or pulse durations (OC) with the `parallel` feature;
//! every point is computed independently of the others and results are collected in order, so
//! they are bitwise identical whatever the number of threads.
//!
//! Files: `time_step.rs` the rule for `dt`; `sweep.rs` the options every sweep shares and the
//! columns of a size grid; `overturning_curve.rs` the OC of pulses; `oas.rs` the OAS of a record;
//! `transformed.rs` its transformed form, `f_min`, `t_1`, the inclined fit and the conservative
//! checks; `replacement_sine.rs` the replacement sine duration `t_p` of a record (Eq. 25);
//! `statistics.rs` the fractile and the correlation of a record suite; `suite.rs` the
//! characteristic OAS of a suite, its design `t_1` and the check of the simplified spectra against
//! every record; `hull.rs` the convex hull of a transformed OAS (Fig. 48–49); `band.rs` `t_1` with
//! its band over equivalent perturbations (half the step, grids shifted by half a cell, the other
//! event locator); `arch.rs`, `arch_oc.rs` the OAS and OC of arches, `arch_design.rs` the suite
//! procedure on arch OAS and the candidate arch design rules.

mod arch;
mod arch_design;
mod arch_oc;
#[cfg(feature = "serde")]
pub mod arch_report;
mod band;
mod hull;
mod oas;
mod overturning_curve;
mod point;
mod replacement_sine;
#[cfg(feature = "serde")]
pub mod report;
pub mod statistics;
mod step_convergence;
pub mod suite;
mod sweep;
mod time_step;
mod transformed;

pub use arch::{
    arch_oas, arch_onset, arch_record_run, ArchCollapse, ArchFailure, ArchOas, ArchOasOptions,
    ArchOnset, ArchRun, ArchRunCounts, ArchShape, ArchSweepOptions, ArchT1Check,
};
pub use arch_design::{
    arch_suite, candidate_rules, characteristic_arch_oas, fit_factor, same_arch, score_t1,
    ArchCharacteristic, ArchRecord, ArchRule, NamedRule, RuleScore,
};
pub use arch_oc::{arch_oc_row, arch_overturning_curve, arch_pulse_run, ArchOc};
pub use band::{t1_band, t1_band_around, t1_band_with, Perturbation, T1Band};
pub use hull::TransformedHull;
pub use oas::{
    linear_levels, log_sizes, oas, record_overturns, Oas, OasLevel, OasOptions, OasPoint,
    SizeSearch,
};
pub use overturning_curve::{overturning_curve, pulse_overturns, Oc, PulseShape};
pub use point::{point_run, PointRun};
pub use replacement_sine::{replacement_sine, ReplacementSine, SINE_FULLNESS};
pub use step_convergence::{
    check_step_convergence, t1_agree, t1_of, t1_of_with, t1_step_converged, t1_step_converged_with,
    StepConvergence, T1Method, T1Result, STEP_HALVINGS, STEP_TOLERANCE,
};
pub use sweep::{column_of_size, Progress, SweepOptions};
pub use time_step::TimeStep;
pub use transformed::{ConservativeCheck, InclinedFit, OasSummary};

use crate::driver::DriverError;
use crate::ground::excitation::ExcitationError;
use crate::ground::records::RecordError;
use crate::model::column::ColumnError;
use crate::validate::InvalidValue;

/// Why a sweep could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpectraError {
    /// A number of the options is out of its range.
    #[error("{0}")]
    Invalid(#[from] InvalidValue),
    /// An option is invalid otherwise (an empty or unsorted grid, a record without motion).
    #[error("{field}: {reason}")]
    InvalidOption {
        /// Field name.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// A column could not be built.
    #[error("column: {0}")]
    Column(#[from] ColumnError),
    /// A pulse could not be built.
    #[error("pulse: {0}")]
    Excitation(#[from] ExcitationError),
    /// The record is invalid.
    #[error("record: {0}")]
    Record(#[from] RecordError),
    /// A time history failed.
    #[error("simulation: {0}")]
    Driver(#[from] DriverError),
    /// A time history of a closed chain (an arch) failed.
    #[error("arch simulation: {0}")]
    Loop(String),
}

fn invalid(field: &'static str, reason: impl Into<String>) -> SpectraError {
    SpectraError::InvalidOption {
        field,
        reason: reason.into(),
    }
}

/// `n_blocks >= 1`.
fn at_least_one_block(n_blocks: usize) -> Result<(), InvalidValue> {
    if n_blocks == 0 {
        return Err(InvalidValue::new(
            "n_blocks",
            n_blocks,
            "must be at least 1 (a column needs a block)",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod tests_arch;
