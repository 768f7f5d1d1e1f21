//! `rocking`: opening and impact models for columns of rigid blocks (Ther, "Analysis and Design
//! of Rocking Mechanisms"), with a C ABI so that finite-element codes can delegate to it the
//! choice of which joints open, and which way, when a joint lifts or slams shut.
//!
//! See `ARCHITECTURE.md` for the map of modules and where each thesis equation lives.

pub mod column;
pub mod excitation;
pub mod records;
