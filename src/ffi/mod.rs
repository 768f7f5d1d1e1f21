//! The C ABI: a thin layer of null checks, size checks, `catch_unwind` and conversions over the
//! Rust functions of the same meaning ([`crate::impact_model`], [`crate::opening_model`], …).
//!
//! Conventions (see `include/rocking.h`): return 0 on success, a negative code for a bad call, a
//! positive code when the call is valid but cannot be solved as asked. On any non-zero return
//! no output array is written. Inputs are copied before any output is written, so inputs and
//! outputs may even overlap. `rocking_last_error_message()` gives the detail of the last failure
//! on the calling thread. No panic crosses the boundary; all functions are reentrant.

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ModelOptions, ModelReport, Solver};
use crate::model::configuration::{self, Status};

/// ABI version of this header; bumped on any incompatible change of a signature or struct.
pub const ROCKING_ABI_VERSION: u32 = 1;

/// Largest `n_interfaces` the models accept.
pub const ROCKING_MAX_INTERFACES: usize = 4096;

/// Success.
pub const ROCKING_OK: i32 = 0;
/// A required pointer argument is NULL.
pub const ROCKING_ERR_NULL_POINTER: i32 = -1;
/// `n` is zero, above the supported maximum (4096 interfaces), or a size overflows.
pub const ROCKING_ERR_INVALID_SIZE: i32 = -2;
/// An input value is NaN or infinite.
pub const ROCKING_ERR_NOT_FINITE: i32 = -3;
/// The mass matrix is not symmetric (entry-wise relative 1e-9).
pub const ROCKING_ERR_NOT_SYMMETRIC: i32 = -4;
/// A status value is outside −1..1.
pub const ROCKING_ERR_INVALID_STATUS: i32 = -5;
/// The closing interface is out of range or not open.
pub const ROCKING_ERR_INVALID_CLOSING_INTERFACE: i32 = -6;
/// A velocity is non-zero on a DOF that is not open.
pub const ROCKING_ERR_VELOCITY_ON_CLOSED_DOF: i32 = -7;
/// Invalid options (n_impacts = 0, solver not 0..2, tolerance not in (0, 0.01]).
pub const ROCKING_ERR_INVALID_OPTIONS: i32 = -8;
/// The closing interface is moving away from closure.
pub const ROCKING_ERR_INCONSISTENT_STATE: i32 = -9;
/// Invalid column geometry (non-positive or non-finite size, mass, inertia or contact width).
pub const ROCKING_ERR_INVALID_GEOMETRY: i32 = -10;
/// A DOF angle has the inadmissible sign, or both DOFs of an interface are non-zero.
pub const ROCKING_ERR_INVALID_ANGLES: i32 = -11;
/// The mass matrix (or a sub-matrix the model needs) is not positive definite.
pub const ROCKING_ERR_NOT_POSITIVE_DEFINITE: i32 = 1;
/// Enumeration refused: more closed interfaces than its limit (12).
pub const ROCKING_ERR_ENUMERATION_TOO_LARGE: i32 = 2;
/// The projection solver did not converge.
pub const ROCKING_ERR_SOLVER_DID_NOT_CONVERGE: i32 = 3;
/// The inputs are finite but so large that the result overflows.
pub const ROCKING_ERR_OVERFLOW: i32 = 4;
/// Internal error: a panic was caught at the boundary (a bug; please report it).
pub const ROCKING_ERR_INTERNAL: i32 = 99;

/// Options of both models. Passing NULL means `{1, 0, 1e-12}`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockingOptions {
    /// Consecutive impacts per closing: 1 = Housner, 2 = one bump in the middle (the thesis's
    /// recommended model), … Must be >= 1. Ignored by the opening model.
    pub n_impacts: u32,
    /// 0 auto (enumeration for at most 2 closed interfaces, projection above), 1 enumerate (the
    /// thesis's exhaustive search, refused above 12 closed interfaces), 2 projection.
    pub solver: u32,
    /// Relative tolerance of the admissibility tests, in (0, 0.01]; 1e-12 is a good default.
    pub tolerance: f64,
}

/// What a model call did. Written only on success.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockingReport {
    /// Solver that ran: 1 enumerate, 2 projection.
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

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(text: &str) {
    let c = CString::new(text.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = c);
}

/// Runs `body` behind the panic boundary, records the error detail and returns the code.
fn guarded(body: impl FnOnce() -> Result<(), RockingError>) -> i32 {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            set_last_error("");
            ROCKING_OK
        }
        Ok(Err(e)) => {
            set_last_error(&e.to_string());
            e.code()
        }
        Err(_) => {
            set_last_error(ErrorKind::Internal.message());
            ROCKING_ERR_INTERNAL
        }
    }
}

fn null(name: &str) -> RockingError {
    RockingError::new(ErrorKind::NullPointer, format!("{name} is NULL"))
}

/// Copies `len` values from a caller's array after checking the pointer.
///
/// # Safety
/// `ptr` must be NULL or point to `len` readable, initialised values.
unsafe fn read_array<T: Copy + Default>(
    ptr: *const T,
    len: usize,
    name: &str,
) -> Result<Vec<T>, RockingError> {
    if ptr.is_null() {
        return Err(null(name));
    }
    if (ptr as usize) % std::mem::align_of::<T>() != 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("{name} is not aligned"),
        ));
    }
    let mut v = vec![T::default(); len];
    std::ptr::copy_nonoverlapping(ptr, v.as_mut_ptr(), len);
    Ok(v)
}

/// Checks an output pointer.
fn check_out<T>(ptr: *mut T, name: &str) -> Result<(), RockingError> {
    if ptr.is_null() {
        return Err(null(name));
    }
    if (ptr as usize) % std::mem::align_of::<T>() != 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("{name} is not aligned"),
        ));
    }
    Ok(())
}

/// Copies a result into a caller's array.
///
/// # Safety
/// `ptr` must point to `values.len()` writable values (checked non-NULL and aligned before).
unsafe fn write_array<T: Copy>(ptr: *mut T, values: &[T]) {
    std::ptr::copy_nonoverlapping(values.as_ptr(), ptr, values.len());
}

/// Sizes `(2n, 4n²)` after checking `n`.
fn sizes(n: usize) -> Result<(usize, usize), RockingError> {
    configuration::check_size(n)?;
    Ok((2 * n, 4 * n * n))
}

fn options(ptr: *const RockingOptions) -> Result<ModelOptions, RockingError> {
    let mut o = ModelOptions::default();
    if ptr.is_null() {
        return Ok(o);
    }
    if (ptr as usize) % std::mem::align_of::<RockingOptions>() != 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            "options is not aligned",
        ));
    }
    // SAFETY: non-NULL and aligned; the caller promises a valid struct.
    let c = unsafe { std::ptr::read(ptr) };
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

fn decode(raw: &[i8]) -> Result<Vec<Status>, RockingError> {
    configuration::decode_statuses(raw)
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
/// - `options`: may be NULL (`{1, 0, 1e-12}`). `report`: may be NULL.
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
    guarded(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let opts = self::options(options)?;
        check_out(status, "status")?;
        check_out(velocity, "velocity")?;
        if !report.is_null() {
            check_out(report, "report")?;
        }
        let mass = read_array(mass, mm, "mass")?;
        let raw_status = read_array(status as *const i8, n_interfaces, "status")?;
        let mut v = read_array(velocity as *const f64, m, "velocity")?;
        let mut st = decode(&raw_status)?;
        let rep = crate::impact_model(&mass, &mut st, &mut v, closing_interface, &opts)?;
        write_array(status, &encode(&st));
        write_array(velocity, &v);
        if !report.is_null() {
            std::ptr::write(report, rep.into());
        }
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
    guarded(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let opts = self::options(options)?;
        check_out(status, "status")?;
        check_out(acceleration, "acceleration")?;
        if !report.is_null() {
            check_out(report, "report")?;
        }
        let mass = read_array(mass, mm, "mass")?;
        let load = read_array(load, m, "load")?;
        let raw_status = read_array(status as *const i8, n_interfaces, "status")?;
        let mut st = decode(&raw_status)?;
        let mut a = vec![0.0; m];
        let rep = crate::opening_model(&mass, &load, &mut st, &mut a, &opts)?;
        write_array(status, &encode(&st));
        write_array(acceleration, &a);
        if !report.is_null() {
            std::ptr::write(report, rep.into());
        }
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
    guarded(|| {
        let (m, mm) = sizes(n_interfaces)?;
        check_out(holds, "holds")?;
        if !reactions.is_null() {
            check_out(reactions, "reactions")?;
        }
        let tol = if tolerance.is_nan() || tolerance <= 0.0 {
            1e-12
        } else {
            tolerance
        };
        ModelOptions {
            tolerance: tol,
            ..ModelOptions::default()
        }
        .validate()?;
        let mass = read_array(mass, mm, "mass")?;
        let load = read_array(load, m, "load")?;
        let st = decode(&read_array(status, n_interfaces, "status")?)?;
        let check = crate::check_configuration(&mass, &load, &st, tol)?;
        std::ptr::write(holds, u8::from(check.holds()));
        if !reactions.is_null() {
            write_array(reactions, &check.reactions);
        }
        if !must_open.is_null() {
            let mut flags = vec![0u8; n_interfaces];
            for &k in &check.must_open {
                flags[k] = 1;
            }
            write_array(must_open, &flags);
        }
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
    guarded(|| {
        let (m, mm) = sizes(n_blocks)?;
        check_out(mass_out, "mass_out")?;
        if !load_out.is_null() {
            check_out(load_out, "load_out")?;
        }
        let w = read_array(width, n_blocks, "width")?;
        let h = read_array(height, n_blocks, "height")?;
        let bm = read_array(block_mass, n_blocks, "block_mass")?;
        let inertia = if inertia.is_null() {
            None
        } else {
            Some(read_array(inertia, n_blocks, "inertia")?)
        };
        let contact = if contact_width.is_null() {
            None
        } else {
            Some(read_array(contact_width, n_blocks, "contact_width")?)
        };
        let phi = if phi.is_null() {
            vec![0.0; m]
        } else {
            read_array(phi, m, "phi")?
        };
        configuration::check_finite("phi", &phi)?;
        for (name, v) in [
            ("ground_acceleration", ground_acceleration),
            ("gravity", gravity),
        ] {
            if !v.is_finite() {
                return Err(RockingError::new(
                    ErrorKind::NotFinite,
                    format!("{name} = {v}"),
                ));
            }
        }
        configuration::statuses_from_angles(&phi)?;
        let blocks = (0..n_blocks)
            .map(|k| crate::model::column::Block {
                width: w[k],
                height: h[k],
                mass: bm[k],
                inertia: inertia.as_ref().map(|i| i[k]),
                contact_width: contact.as_ref().map(|c| c[k]),
            })
            .collect();
        let column = crate::model::column::Column::new(blocks)
            .map_err(|e| RockingError::new(ErrorKind::InvalidGeometry, e.to_string()))?;
        let pose = column.pose(&phi);
        let mass = column.mass_matrix(&pose);
        let load = column.load_vector(&pose, ground_acceleration, gravity);
        debug_assert_eq!(mass.len(), mm);
        configuration::check_result(&mass, &load)?;
        write_array(mass_out, &mass);
        if !load_out.is_null() {
            write_array(load_out, &load);
        }
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
    guarded(|| {
        const MAX_NODAL: usize = 1 << 16;
        if n_nodal == 0 || n_reduced == 0 || n_nodal > MAX_NODAL || n_reduced > MAX_NODAL {
            return Err(RockingError::new(
                ErrorKind::InvalidSize,
                format!(
                    "n_nodal = {n_nodal}, n_reduced = {n_reduced}: each must be in 1..={MAX_NODAL}"
                ),
            ));
        }
        let nn = n_nodal * n_nodal;
        let nb = n_nodal * n_reduced;
        check_out(reduced_mass, "reduced_mass")?;
        let want_load = !reduced_load.is_null();
        if want_load {
            check_out(reduced_load, "reduced_load")?;
        }
        let mass = read_array(nodal_mass, nn, "nodal_mass")?;
        configuration::check_symmetric(&mass, n_nodal)?;
        let b = read_array(transformation, nb, "transformation")?;
        configuration::check_finite("transformation", &b)?;
        let p = if want_load {
            let p = read_array(nodal_load, n_nodal, "nodal_load")?;
            configuration::check_finite("nodal_load", &p)?;
            p
        } else {
            vec![0.0; n_nodal]
        };
        let mut rm = vec![0.0; n_reduced * n_reduced];
        let mut rl = vec![0.0; n_reduced];
        crate::model::column::reduce(n_nodal, n_reduced, &mass, &b, &p, &mut rm, &mut rl);
        configuration::check_result(&rm, &rl)?;
        write_array(reduced_mass, &rm);
        if want_load {
            write_array(reduced_load, &rl);
        }
        Ok(())
    })
}

/// Static text of a status code (never NULL; unknown codes get a generic text).
#[no_mangle]
pub extern "C" fn rocking_error_message(code: i32) -> *const c_char {
    let text = match ErrorKind::from_code(code) {
        _ if code == 0 => "success\0",
        Some(kind) => kind.c_message(),
        None => "unknown status code\0",
    };
    text.as_ptr().cast()
}

/// Detail of the last failure on the calling thread ("" after a success). The text stays valid
/// until the next call into the library on the same thread.
#[no_mangle]
pub extern "C" fn rocking_last_error_message() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
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
