//! The thesis's design method for rocking piers (thesis Chapter 5, Eq. 19–31; SPEC §7).
//!
//! An earthquake is represented by two numbers: its peak ground acceleration `a_p` and its
//! *replacement impulse duration* `t_1`. The transformed overturning acceleration spectrum
//! (`f = p a_p / a_p,min`, Eq. 19) is bounded on the left by the vertical line
//! `f_min = i_cr / t_1` (Eq. 20), which gives the *simplified OAS* (Eq. 21) and the design check
//! (Eq. 31): a block is safe if `a_p ≤ a_p,min i_cr / (t_1 p)` or `a_p ≤ a_p,min`, with
//! `i_cr ≈ 1` in Eq. 31 and in the pier example (Eq. 23).
//!
//! The pier is an [`EquivalentBlock`]: its full width `B`, height `H` and its mass distribution
//! ([`MassDistribution`], thesis 5.3.3): the centre of mass sits at height `h_c` on the axis,
//! `tan δ = (B/2) / h_c`, `R = √((B/2)² + h_c²)` is the distance from a bottom corner to the
//! centre of mass, and `θ = α m R²` the moment of inertia about the corner (Eq. 22). For a
//! uniform block `h_c = H/2`, so `tan δ = B/H` and `R = ½√(B² + H²)` as in Eq. 3 and Fig. 7.
//!
//! Files: `check.rs` the check of Eq. 31 / 21; `simplified_oas.rs` the simplified and improved
//! spectra (Eq. 20, 21, 28–30); `pier_width.rs` the required width (Eq. 23, 24).

mod check;
mod pier_width;
mod simplified_oas;

pub use check::{design_check, Branch, DesignCheck, ImpulseFactor};
pub use pier_width::{pier_width, PierWidth};
pub use simplified_oas::{
    f_min, improved_oas_eq29, improved_oas_eq29_as_printed, improved_oas_eq30, inclined_line,
    simplified_oas,
};

pub use crate::model::single_block::{EquivalentBlock, MassDistribution};

use crate::validate::InvalidValue;

/// Why a design computation was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DesignError {
    /// An argument (`height`, `pga`, `t1`, `g`, `width`, `alpha`, …) is not a finite number
    /// greater than zero.
    #[error("{0}")]
    Invalid(#[from] InvalidValue),
    /// The width equation has no root that the bracketing search could find (this cannot happen
    /// for valid finite inputs, the left-hand side being increasing in the width; it guards
    /// against overflow for extreme inputs).
    #[error("no solution for `{name}`: {detail}")]
    NoSolution {
        /// Name of the unknown (`width`).
        name: &'static str,
        /// What went wrong.
        detail: String,
    },
}

#[cfg(test)]
mod tests;
