//! The column and the two models: geometry and the interface mass matrix (thesis Eq. 4–6,
//! Appendix C), configurations, the common cone problem (SPEC §4) and its two solvers, the
//! impact model (3.2.3) and the opening model (3.2.2), and the single block's closed forms.

pub mod cholesky;
pub mod column;
pub mod cone;
pub mod configuration;
pub mod constrained;
pub mod enumeration;
pub mod impact;
pub mod interface_system;
pub mod opening;
pub mod projection;
pub mod single_block;
pub mod solver;
