//! The C ABI of closed chains (SPEC §9, issue 15): the two models with linear equality
//! constraints on the interface DOFs and a set of closing joints
//! ([`crate::impact_model_constrained`], [`crate::opening_model_constrained`]), and the systems
//! (`M`, `q`, `G`, `Ġ v`) of a voussoir arch and of a capped colonnade
//! ([`crate::chain::system`]). Same shape as every export: sizes, outputs, inputs, the core, the
//! outputs written on success only.

use super::boundary::{input, optional_input, status_call, Output};
use super::{encode, sizes, RockingOptions, RockingReport};
use crate::chain::arch::VoussoirArch;
use crate::chain::system::{self, LoopSystem};
use crate::chain::Chain;
use crate::error::{ErrorKind, RockingError};
use crate::model::configuration;

/// Largest `n_constraints` the constrained models accept, `3 × ROCKING_MAX_INTERFACES` (a loop
/// has 3).
pub const ROCKING_MAX_CONSTRAINTS: usize = 12288;

/// A voussoir arch (SPEC §9): circular centre line of radius `radius`, thickness `thickness`
/// (radial joints), angle of embrace `embrace_angle` (rad; π is the semicircular arch),
/// `voussoirs` voussoirs of equal angle on rigid abutments, uniform `density` (kg/m³) and
/// out-of-plane `depth` (m). Joint 0 is the left springing, joint `voussoirs` the right one;
/// `phĭ_k` turns about the intrados corner, `phî_k` about the extrados corner.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockingArch {
    pub radius: f64,
    pub thickness: f64,
    pub embrace_angle: f64,
    pub voussoirs: usize,
    pub density: f64,
    pub depth: f64,
}

/// Checks `n_constraints` and returns the length of the constraint array, `n_c × 2n`.
fn constraint_len(n_constraints: usize, m: usize) -> Result<usize, RockingError> {
    if n_constraints > ROCKING_MAX_CONSTRAINTS {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!(
                "n_constraints = {n_constraints} exceeds the supported maximum \
                 {ROCKING_MAX_CONSTRAINTS}"
            ),
        ));
    }
    Ok(n_constraints * m)
}

/// The constraint rows: required unless `n_constraints` is 0 (then NULL is allowed).
///
/// # Safety
/// As [`input`].
unsafe fn constraint_rows(constraints: *const f64, len: usize) -> Result<Vec<f64>, RockingError> {
    if len == 0 {
        Ok(Vec::new())
    } else {
        input(constraints, len, "constraints")
    }
}

/// Impact model of a closed chain (SPEC §9): every interface flagged in `closing` closes at this
/// instant (a four-hinge loop closes its four hinges together); each may stay closed or rotate on
/// about its opposite corner, every other closed interface may stay closed or open either way,
/// open interfaces keep their DOF; the velocities after satisfy `G v⁺ = 0`.
///
/// - `mass`: 2n×2n (symmetric; for a loop only positive semi-definite: the cut joint's rows are
///   zero), DOF order as `rocking_impact_model`;
/// - `constraints`: `G`, row-major `n_constraints × 2n` (NULL allowed when `n_constraints` is 0);
/// - `status`, `velocity`: as `rocking_impact_model` (read and written);
/// - `closing`: n flags, 1 for every open interface that closes now (its DOF at rest or moving
///   towards zero), else 0.
///
/// `n_constraints = 0` with one flag gives exactly the answers of `rocking_impact_model`. The
/// mass matrix must be positive definite on the null space of the constraints restricted to the
/// DOFs of every configuration examined, else `ROCKING_ERR_NOT_POSITIVE_DEFINITE`. Returns 0, a
/// negative code for a bad call, or a positive code if it cannot be solved; on a non-zero return
/// nothing is written.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rocking_impact_model_constrained(
    n_interfaces: usize,
    mass: *const f64,
    n_constraints: usize,
    constraints: *const f64,
    status: *mut i8,
    velocity: *mut f64,
    closing: *const u8,
    options: *const RockingOptions,
    report: *mut RockingReport,
) -> i32 {
    status_call(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let nc = constraint_len(n_constraints, m)?;
        let opts = RockingOptions::read(options)?;
        let status = Output::required(status, n_interfaces, "status")?;
        let velocity = Output::required(velocity, m, "velocity")?;
        let report = Output::optional(report, 1, "report")?;
        let mass = input(mass, mm, "mass")?;
        let g = constraint_rows(constraints, nc)?;
        let flags = input(closing, n_interfaces, "closing")?;
        let closing = flags
            .iter()
            .enumerate()
            .map(|(k, &f)| match f {
                0 => Ok(false),
                1 => Ok(true),
                v => Err(RockingError::new(
                    ErrorKind::InvalidClosingInterface,
                    format!("closing[{k}] = {v}, expected 0 or 1"),
                )),
            })
            .collect::<Result<Vec<bool>, _>>()?;
        let mut st = configuration::decode_statuses(&status.read())?;
        let mut v = velocity.read();
        let rep = crate::impact_model_constrained(&mass, &g, &mut st, &mut v, &closing, &opts)?;
        status.write(&encode(&st));
        velocity.write(&v);
        report.write(&[rep.into()]);
        Ok(())
    })
}

/// Opening model of a closed chain (SPEC §9): `a = argmin ½ aᵀMa − aᵀq` over `G a = r` and the
/// cone of the opening model (Gauss's principle of least constraint). A closed loop has no
/// reaction test: the model itself answers — from rest it returns `a ≠ 0` exactly when some
/// admissible mechanism has positive power of the loads (limit analysis). With interfaces already
/// open, "nothing new opens" is a candidate: then `report->changed` is 0 and `acceleration` holds
/// the current mechanism's accelerations.
///
/// - `mass`, `load`: 2n×2n and 2n, as `rocking_opening_model` (`mass` may be singular on the
///   cut joint of a loop);
/// - `constraints`: `G`, row-major `n_constraints × 2n` (NULL allowed when `n_constraints` is 0);
/// - `constraint_rhs`: `r` (n_constraints values, `−Ġ v` for a moving loop), or NULL for zeros;
/// - `status`: n values, read and written; `acceleration`: 2n, written.
///
/// `n_constraints = 0` gives exactly the answers of `rocking_opening_model`.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rocking_opening_model_constrained(
    n_interfaces: usize,
    mass: *const f64,
    load: *const f64,
    n_constraints: usize,
    constraints: *const f64,
    constraint_rhs: *const f64,
    status: *mut i8,
    acceleration: *mut f64,
    options: *const RockingOptions,
    report: *mut RockingReport,
) -> i32 {
    status_call(|| {
        let (m, mm) = sizes(n_interfaces)?;
        let nc = constraint_len(n_constraints, m)?;
        let opts = RockingOptions::read(options)?;
        let status = Output::required(status, n_interfaces, "status")?;
        let acceleration = Output::required(acceleration, m, "acceleration")?;
        let report = Output::optional(report, 1, "report")?;
        let mass = input(mass, mm, "mass")?;
        let load = input(load, m, "load")?;
        let g = constraint_rows(constraints, nc)?;
        let rhs = optional_input(constraint_rhs, n_constraints, "constraint_rhs")?;
        let mut st = configuration::decode_statuses(&status.read())?;
        let mut a = vec![0.0; m];
        let rep = crate::opening_model_constrained(
            &mass,
            &load,
            &g,
            rhs.as_deref(),
            &mut st,
            &mut a,
            &opts,
        )?;
        status.write(&encode(&st));
        acceleration.write(&a);
        report.write(&[rep.into()]);
        Ok(())
    })
}

/// The outputs of the two system helpers, checked at the start and written at the end.
struct SystemOutputs {
    mass: Output<f64>,
    load: Output<f64>,
    constraints: Output<f64>,
    constraint_rate: Output<f64>,
}

impl SystemOutputs {
    fn new(
        n: usize,
        mass: *mut f64,
        load: *mut f64,
        constraints: *mut f64,
        constraint_rate: *mut f64,
    ) -> Result<SystemOutputs, RockingError> {
        let (m, mm) = sizes(n)?;
        Ok(SystemOutputs {
            mass: Output::required(mass, mm, "mass")?,
            load: Output::optional(load, m, "load")?,
            constraints: Output::optional(constraints, 3 * m, "constraints")?,
            constraint_rate: Output::optional(constraint_rate, 3, "constraint_rate")?,
        })
    }

    /// Computes the system of `chain` and writes it.
    ///
    /// # Safety
    /// As [`Output::write`]; `phi` and `rates` NULL or 2n values.
    unsafe fn fill(
        self,
        chain: &Chain,
        phi: *const f64,
        rates: *const f64,
        ground_acceleration: f64,
        gravity: f64,
    ) -> Result<(), RockingError> {
        let m = chain.n_dofs();
        let phi = optional_input(phi, m, "phi")?;
        let rates = optional_input(rates, m, "rates")?;
        let s: LoopSystem = system::loop_system(
            chain,
            phi.as_deref(),
            rates.as_deref(),
            ground_acceleration,
            gravity,
        )?;
        self.mass.write(&s.mass);
        self.load.write(&s.load);
        self.constraints.write(&s.constraints);
        self.constraint_rate.write(&s.constraint_rate);
        Ok(())
    }
}

/// `M`, `q`, `G` and `Ġ v` of a voussoir arch (SPEC §9) at the joint angles `phi` and rates
/// `rates`, for the two constrained models: an FE code or a test gets the loop's system without
/// assembling it.
///
/// - `arch`: the geometry; `n_interfaces` must be `arch->voussoirs + 1` (the joints: it states
///   the sizes of the arrays);
/// - `phi`: 2n DOF angles (at most one non-zero per joint, admissible sign), or NULL for the
///   arch at rest; `rates`: 2n DOF rates (on the open DOFs; a closed joint may have one DOF moving
///   the admissible way), or NULL for zero;
/// - `ground_acceleration` (m/s², +x right) and `gravity` (m/s², positive);
/// - `mass`: 4n² (symmetric; the last joint's rows and columns are zero: the chain is cut
///   there); `load`: 2n, or NULL; `constraints`: `G`, 3 × 2n row-major, or NULL;
///   `constraint_rate`: `Ġ v` (3; the accelerations obey `G a = −Ġ v`), or NULL.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rocking_arch_system(
    arch: *const RockingArch,
    n_interfaces: usize,
    phi: *const f64,
    rates: *const f64,
    ground_acceleration: f64,
    gravity: f64,
    mass: *mut f64,
    load: *mut f64,
    constraints: *mut f64,
    constraint_rate: *mut f64,
) -> i32 {
    status_call(|| {
        configuration::check_size(n_interfaces)?;
        let out = SystemOutputs::new(n_interfaces, mass, load, constraints, constraint_rate)?;
        let a = input(arch, 1, "arch")?[0];
        let chain = system::arch_chain(
            &VoussoirArch {
                radius: a.radius,
                thickness: a.thickness,
                embrace_angle: a.embrace_angle,
                voussoirs: a.voussoirs,
                density: a.density,
                depth: a.depth,
            },
            n_interfaces,
        )?;
        out.fill(&chain, phi, rates, ground_acceleration, gravity)
    })
}

/// Rows `(width, height, mass)` of a column.
///
/// # Safety
/// As [`input`].
unsafe fn block_rows(ptr: *const f64, n: usize, name: &str) -> Result<Vec<[f64; 3]>, RockingError> {
    if n == 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("n_{name} is 0: a column needs at least one block"),
        ));
    }
    let flat = input(ptr, 3 * n, name)?;
    configuration::check_finite(name, &flat)?;
    Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
}

/// `M`, `q`, `G` and `Ġ v` of a capped colonnade (SPEC §9: ground → left column → beam → right
/// column → ground; Makris & Vassiliou's frame with one block per column) at the joint angles
/// `phi` and rates `rates`.
///
/// - `left`, `right`: `n_left` and `n_right` rows `(width, height, mass)` of each column's
///   blocks, bottom to top (uniform rectangles bearing on their full width); the columns stand at
///   `x = 0` and `x = span` and must be equally tall; `beam`: `(length, depth, mass)`, centred
///   between them, covering both column tops;
/// - `n_interfaces` must be `n_left + n_right + 2` (it states the sizes of the arrays). Joint
///   order: the left column bottom to top (`k = 0 … n_left − 1`), the left top under the beam
///   (`n_left`), the beam on the right top (`n_left + 1`), the right column top to bottom; on
///   the right column the joint normals point down, so `phĭ_k` turns about the corner on the
///   left in world coordinates;
/// - `phi`, `rates`, `ground_acceleration`, `gravity` and the outputs as `rocking_arch_system`.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the documented sizes.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rocking_colonnade_system(
    n_left: usize,
    left: *const f64,
    n_right: usize,
    right: *const f64,
    beam: *const f64,
    span: f64,
    n_interfaces: usize,
    phi: *const f64,
    rates: *const f64,
    ground_acceleration: f64,
    gravity: f64,
    mass: *mut f64,
    load: *mut f64,
    constraints: *mut f64,
    constraint_rate: *mut f64,
) -> i32 {
    status_call(|| {
        configuration::check_size(n_interfaces)?;
        if n_left.checked_add(n_right).and_then(|s| s.checked_add(2)) != Some(n_interfaces) {
            return Err(RockingError::new(
                ErrorKind::InvalidSize,
                format!(
                    "n_interfaces = {n_interfaces}, but a colonnade of n_left = {n_left} and \
                     n_right = {n_right} blocks has n_left + n_right + 2 joints"
                ),
            ));
        }
        let out = SystemOutputs::new(n_interfaces, mass, load, constraints, constraint_rate)?;
        let left = block_rows(left, n_left, "left")?;
        let right = block_rows(right, n_right, "right")?;
        let beam = input(beam, 3, "beam")?;
        configuration::check_finite("beam", &beam)?;
        let chain = system::colonnade_chain(
            &left,
            &right,
            [beam[0], beam[1], beam[2]],
            span,
            n_interfaces,
        )?;
        out.fill(&chain, phi, rates, ground_acceleration, gravity)
    })
}

#[cfg(test)]
#[path = "tests_chains.rs"]
mod tests;
