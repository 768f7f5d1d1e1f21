//! One module per command of `rocking`.

pub mod design;
pub mod oas;
pub mod oc;
pub mod simulate;
pub mod simulate_drums;
pub mod sweep;
pub mod t1;
pub mod thesis;
pub mod tp;
