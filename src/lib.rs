//! `rocking`: opening and impact models for columns of rigid blocks (Ther, "Analysis and Design
//! of Rocking Mechanisms"), with a C ABI so that finite-element codes can delegate to it the
//! choice of which joints open, and which way, when a joint lifts or slams shut.
//!
//! See `ARCHITECTURE.md` for the map of modules and where each thesis equation lives.

// Index loops mirror the thesis's matrix notation (M[a][b], sums over blocks j >= k).
#![allow(clippy::needless_range_loop)]

pub mod cholesky;
pub mod column;
pub mod cone;
pub mod configuration;
pub mod design;
pub mod driver;
pub mod enumeration;
pub mod error;
pub mod excitation;
pub mod ffi;
pub mod impact;
pub mod opening;
pub mod projection;
pub mod records;
pub mod samples;
pub mod single_block;
pub mod spectra;

pub use cone::{ModelOptions, ModelReport, Solver};
pub use configuration::Status;
pub use error::{ErrorKind, RockingError};
pub use impact::impact_model;
pub use opening::{check_configuration, opening_model};
