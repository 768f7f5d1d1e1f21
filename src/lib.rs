//! `rocking`: opening and impact models for columns of rigid blocks (Ther, "Analysis and Design
//! of Rocking Mechanisms"), with a C ABI so that finite-element codes can delegate to it the
//! choice of which joints open, and which way, when a joint lifts or slams shut.
//!
//! See `ARCHITECTURE.md` for the map of modules and where each thesis equation lives.

// `unsafe` lives in the C ABI only (`src/ffi/`): raw pointers from C are checked and copied there,
// and everything else works on slices.
#![deny(unsafe_code)]
// Index loops mirror the thesis's matrix notation (M[a][b], sums over blocks j >= k).
#![allow(clippy::needless_range_loop)]

pub mod chain;
pub mod contact;
pub mod design;
pub mod driver;
pub mod error;
#[allow(unsafe_code)]
pub mod ffi;
pub mod ground;
pub mod model;
pub mod samples;
#[cfg(feature = "serde")]
pub mod scene;
pub mod spectra;
#[cfg(test)]
pub(crate) mod test_support;
pub mod validate;

pub use error::{ErrorKind, RockingError};
pub use model::cone::{ModelOptions, ModelReport, Solver};
pub use model::configuration::Status;
pub use model::constrained::{impact_model_constrained, opening_model_constrained};
pub use model::impact::impact_model;
pub use model::opening::{check_configuration, opening_model};
