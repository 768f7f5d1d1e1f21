//! The C ABI: thin exports over the Rust functions of the same meaning
//! ([`crate::impact_model`], [`crate::opening_model`], [`crate::check_configuration`],
//! [`crate::model::interface_system::column_system`], [`crate::model::column::reduce`]).
//!
//! Every fallible export has one shape (see `boundary.rs`): check the sizes, check the output
//! pointers, copy the inputs, call the core, write the outputs — all inside
//! `status_call`, the panic boundary. Conventions (see `docs/c-api.md` and the header):
//! return 0 on success, a negative code for a bad call, a positive code when the call is valid but
//! cannot be solved as asked; on any non-zero return no output is written;
//! `rocking_last_error_message()` gives the detail of the last failure on the calling thread. No
//! panic crosses the boundary; all functions are reentrant.
//!
//! The header `include/rocking.h` is generated from this folder alone (`build.rs`): every `pub
//! const`, `#[repr(C)]` type and export here appears in it, and nothing from the rest of the
//! crate. The status codes come from the table in `src/error.rs`.

mod boundary;
mod chains;
mod types;

use std::ffi::c_char;

pub use crate::error::codes::*;
use crate::error::ErrorKind;
use crate::model::configuration::{self, Status};
use crate::model::interface_system::{self, BlockArrays};
use boundary::{input, optional_input, status_call, Output};
pub use chains::{
    rocking_arch_system, rocking_colonnade_system, rocking_impact_model_constrained,
    rocking_opening_model_constrained, RockingArch, ROCKING_MAX_CONSTRAINTS,
};
pub use types::{RockingOptions, RockingReport};

/// ABI version of this header; bumped on any incompatible change of a signature or struct.
pub const ROCKING_ABI_VERSION: u32 = 1;

/// Largest `n_interfaces` the models accept.
pub const ROCKING_MAX_INTERFACES: usize = 4096;

/// `RockingOptions::solver`: enumeration for at most 2 closed interfaces, projection above.
pub const ROCKING_SOLVER_AUTO: u32 = 0;
/// `RockingOptions::solver`: the thesis's exhaustive search (refused above 12 closed interfaces).
pub const ROCKING_SOLVER_ENUMERATE: u32 = 1;
/// `RockingOptions::solver`: relaxed bound-constrained least squares with branching (SPEC §4).
pub const ROCKING_SOLVER_PROJECTION: u32 = 2;

/// Sizes `(2n, 4n²)` after checking `n`.
fn sizes(n: usize) -> Result<(usize, usize), crate::RockingError> {
    configuration::check_size(n)?;
    Ok((2 * n, 4 * n * n))
}

fn encode(st: &[Status]) -> Vec<i8> {
    st.iter().map(|s| s.as_i8()).collect()
}

/// Impact model (thesis 3.2.3, Appendix A/B): interface `closing_interface` closes; chooses the
/// configuration after the impact and the post-impact velocities.
///
/// - `mass`: the 2n×2n interface mass matrix (symmetric, so row- or column-major), DOF order
///   `[phĭ_0 … phĭ_{n-1}, phî_0 … phî_{n-1}]` (rotation about the right corner, <= 0; about the
///   left corner, >= 0).
/// - `status`: n values, −1 open about the right corner, 0 closed, +1 open about the left corner;
///   read and written.
/// - `velocity`: 2n DOF rates before the impact (zero on DOFs that are not open), overwritten
///   with the rates after.
/// - `closing_interface`: an open interface whose DOF is moving towards zero.
/// - `options`: may be NULL (`{1, ROCKING_SOLVER_AUTO, 1e-12}`). `report`: may be NULL.
///
/// Returns 0, a negative code for a bad call, or a positive code if it cannot be solved.
/// On a non-zero return nothing is written.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
pub unsafe extern "C" fn rocking_impact_model(
    n_interfaces: usize,
    mass: *const f64,
    status: *mut i8,
    velocity: *mut f64,
    closing_interface: usize,
    options: *const RockingOptions,
    report: *mut RockingReport,
) -> i32 {
    status_call(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let opts = RockingOptions::read(options)?;
        let status = Output::required(status, n_interfaces, "status")?;
        let velocity = Output::required(velocity, m, "velocity")?;
        let report = Output::optional(report, 1, "report")?;
        let mass = input(mass, mm, "mass")?;
        let mut st = configuration::decode_statuses(&status.read())?;
        let mut v = velocity.read();
        let rep = crate::impact_model(&mass, &mut st, &mut v, closing_interface, &opts)?;
        status.write(&encode(&st));
        velocity.write(&v);
        report.write(&[rep.into()]);
        Ok(())
    })
}

/// Opening model (thesis 3.2.2): when the eccentricity test fires, chooses which closed
/// interfaces open and which way, and returns the DOF accelerations of that configuration.
/// If the current configuration holds (all contact reactions admissible) it is kept and
/// `report->changed` is 0.
///
/// - `mass`: 2n×2n interface mass matrix (as for the impact model); `load`: 2n generalised loads;
/// - `status`: n values (−1, 0, +1), read and written;
/// - `acceleration`: 2n, written (zero on DOFs outside the chosen configuration).
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
pub unsafe extern "C" fn rocking_opening_model(
    n_interfaces: usize,
    mass: *const f64,
    load: *const f64,
    status: *mut i8,
    acceleration: *mut f64,
    options: *const RockingOptions,
    report: *mut RockingReport,
) -> i32 {
    status_call(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let opts = RockingOptions::read(options)?;
        let status = Output::required(status, n_interfaces, "status")?;
        let acceleration = Output::required(acceleration, m, "acceleration")?;
        let report = Output::optional(report, 1, "report")?;
        let mass = input(mass, mm, "mass")?;
        let load = input(load, m, "load")?;
        let mut st = configuration::decode_statuses(&status.read())?;
        let mut a = vec![0.0; m];
        let rep = crate::opening_model(&mass, &load, &mut st, &mut a, &opts)?;
        status.write(&encode(&st));
        acceleration.write(&a);
        report.write(&[rep.into()]);
        Ok(())
    })
}

/// The eccentricity test as reaction signs: does the configuration `status` hold under `load`?
/// Writes `*holds` (1 holds, 0 something must open), and optionally the generalised contact
/// reactions `reactions` (2n, λ = M a − q, zero on open DOFs; admissible λ <= 0 on phĭ_k and
/// λ >= 0 on phî_k of a closed interface) and `must_open` (n flags). `reactions` and `must_open`
/// may be NULL. `tolerance` as in the options (<= 0 means 1e-12).
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
pub unsafe extern "C" fn rocking_check_configuration(
    n_interfaces: usize,
    mass: *const f64,
    load: *const f64,
    status: *const i8,
    tolerance: f64,
    holds: *mut u8,
    reactions: *mut f64,
    must_open: *mut u8,
) -> i32 {
    status_call(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let holds = Output::required(holds, 1, "holds")?;
        let reactions = Output::optional(reactions, m, "reactions")?;
        let must_open = Output::optional(must_open, n_interfaces, "must_open")?;
        let tol = if tolerance.is_nan() || tolerance <= 0.0 {
            1e-12
        } else {
            tolerance
        };
        crate::ModelOptions {
            tolerance: tol,
            ..crate::ModelOptions::default()
        }
        .validate()?;
        let mass = input(mass, mm, "mass")?;
        let load = input(load, m, "load")?;
        let st = configuration::decode_statuses(&input(status, n_interfaces, "status")?)?;
        let check = crate::check_configuration(&mass, &load, &st, tol)?;
        let mut flags = vec![0u8; n_interfaces];
        for &k in &check.must_open {
            flags[k] = 1;
        }
        holds.write(&[u8::from(check.holds())]);
        reactions.write(&check.reactions);
        must_open.write(&flags);
        Ok(())
    })
}

/// Mass matrix and load vector of a column of rectangular blocks (SPEC §1) in the current
/// geometry, for an FE code that does not assemble `BᵀMB` itself.
///
/// - `width`, `height`, `block_mass`: n values each (bottom block first);
/// - `inertia`: n moments of inertia about the block centres, or NULL for uniform rectangles;
/// - `contact_width`: n contact widths (of the interface under each block), or NULL for
///   `min(w_{k-1}, w_k)`;
/// - `phi`: 2n DOF angles (at most one non-zero per interface, admissible sign), or NULL for the
///   straight column;
/// - `ground_acceleration` (m/s², +x right) and `gravity` (m/s², positive);
/// - `mass_out`: 4n² (row-major = column-major, symmetric); `load_out`: 2n, or NULL.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rocking_column_mass_matrix(
    n_blocks: usize,
    width: *const f64,
    height: *const f64,
    block_mass: *const f64,
    inertia: *const f64,
    contact_width: *const f64,
    phi: *const f64,
    ground_acceleration: f64,
    gravity: f64,
    mass_out: *mut f64,
    load_out: *mut f64,
) -> i32 {
    status_call(|| {
        configuration::check_size_named("n_blocks", n_blocks)?;
        let (m, mm) = sizes(n_blocks)?;
        let mass_out = Output::required(mass_out, mm, "mass_out")?;
        let load_out = Output::optional(load_out, m, "load_out")?;
        let width = input(width, n_blocks, "width")?;
        let height = input(height, n_blocks, "height")?;
        let block_mass = input(block_mass, n_blocks, "block_mass")?;
        let inertia = optional_input(inertia, n_blocks, "inertia")?;
        let contact_width = optional_input(contact_width, n_blocks, "contact_width")?;
        let phi = optional_input(phi, m, "phi")?;
        let blocks = BlockArrays {
            width: &width,
            height: &height,
            mass: &block_mass,
            inertia: inertia.as_deref(),
            contact_width: contact_width.as_deref(),
        };
        let system =
            interface_system::column_system(&blocks, phi.as_deref(), ground_acceleration, gravity)?;
        mass_out.write(&system.mass);
        load_out.write(&system.load);
        Ok(())
    })
}

/// The FE route of thesis Appendix C: `reduced_mass = BᵀMB` (n_reduced²) and
/// `reduced_load = Bᵀp` (n_reduced) from a nodal mass matrix `nodal_mass` (n_nodal², symmetric),
/// the transformation `transformation` (`B`, n_nodal × n_reduced, COLUMN-MAJOR as in LAPACK and
/// OpenSees: entry (r, c) at `[c * n_nodal + r]`) and nodal loads `nodal_load` (n_nodal).
/// `reduced_load` and `nodal_load` may both be NULL.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
pub unsafe extern "C" fn rocking_reduce(
    n_nodal: usize,
    n_reduced: usize,
    nodal_mass: *const f64,
    transformation: *const f64,
    nodal_load: *const f64,
    reduced_mass: *mut f64,
    reduced_load: *mut f64,
) -> i32 {
    status_call(|| {
        interface_system::check_reduction_sizes(n_nodal, n_reduced)?;
        let reduced_mass = Output::required(reduced_mass, n_reduced * n_reduced, "reduced_mass")?;
        let reduced_load = Output::optional(reduced_load, n_reduced, "reduced_load")?;
        // Each input is checked as soon as it is read (as before the FFI was thinned: the code
        // returned for a call with several faults stays the same).
        let mass = input(nodal_mass, n_nodal * n_nodal, "nodal_mass")?;
        configuration::check_symmetric_named("nodal_mass", &mass, n_nodal)?;
        let b = input(transformation, n_nodal * n_reduced, "transformation")?;
        configuration::check_finite("transformation", &b)?;
        let p = if reduced_load.is_requested() {
            let p = input(nodal_load, n_nodal, "nodal_load")?;
            configuration::check_finite("nodal_load", &p)?;
            p
        } else {
            vec![0.0; n_nodal]
        };
        let mut rm = vec![0.0; n_reduced * n_reduced];
        let mut rl = vec![0.0; n_reduced];
        crate::model::column::reduce(n_nodal, n_reduced, &mass, &b, &p, &mut rm, &mut rl);
        configuration::check_result(&rm, &rl)?;
        reduced_mass.write(&rm);
        reduced_load.write(&rl);
        Ok(())
    })
}

/// Static text of a status code (never NULL; unknown codes get a generic text).
#[no_mangle]
pub extern "C" fn rocking_error_message(code: i32) -> *const c_char {
    let text = match ErrorKind::from_code(code) {
        _ if code == ROCKING_OK => crate::error::SUCCESS_C_MESSAGE,
        Some(kind) => kind.c_message(),
        None => "unknown status code\0",
    };
    text.as_ptr().cast()
}

/// Detail of the last failure on the calling thread ("" after a success). The text stays valid
/// until the next call into the library on the same thread.
#[no_mangle]
pub extern "C" fn rocking_last_error_message() -> *const c_char {
    boundary::last_error()
}

/// Library version, e.g. "0.1.0" (static text).
#[no_mangle]
pub extern "C" fn rocking_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// ABI version; compare with `ROCKING_ABI_VERSION` of the header you compiled against.
#[no_mangle]
pub extern "C" fn rocking_abi_version() -> u32 {
    ROCKING_ABI_VERSION
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_column;
