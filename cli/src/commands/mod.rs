//! One module per command of `rocking`.

pub mod arch;
pub mod arch_suite;
pub mod design;
pub mod oas;
pub mod oc;
pub mod overlay;
pub mod simulate;
pub mod simulate_drums;
pub mod simulate_loop;
pub mod suite;
pub mod suite_charts;
pub mod sweep;
pub mod t1;
pub mod thesis;
pub mod tp;
