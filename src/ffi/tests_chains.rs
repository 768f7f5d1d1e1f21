//! The C ABI of closed chains called from Rust: the same answers as the Rust functions, the
//! column's entry points reproduced bit for bit without constraints, and every error class with
//! its code, nothing written and a message that names the argument.

use crate::chain::arch::VoussoirArch;
use crate::ffi::*;
use crate::model::column::GRAVITY;
use crate::model::configuration::Status;
use crate::samples;
use std::ffi::CStr;

fn last_error() -> String {
    unsafe { CStr::from_ptr(rocking_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

const ARCH: RockingArch = RockingArch {
    radius: 5.0,
    thickness: 0.75,
    embrace_angle: std::f64::consts::PI,
    voussoirs: 20,
    density: 2000.0,
    depth: 1.0,
};

/// `M`, `q` (under `a_g`), `G`, `Ġ v` of [`ARCH`] through the C ABI.
fn arch_system(
    phi: Option<&[f64]>,
    rates: Option<&[f64]>,
    ag: f64,
) -> (i32, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = ARCH.voussoirs + 1;
    let m = 2 * n;
    let (mut mass, mut load, mut g, mut gdot) = (
        vec![0.0; m * m],
        vec![0.0; m],
        vec![0.0; 3 * m],
        vec![0.0; 3],
    );
    let ptr = |v: Option<&[f64]>| v.map_or(std::ptr::null(), <[f64]>::as_ptr);
    let code = unsafe {
        rocking_arch_system(
            &ARCH,
            n,
            ptr(phi),
            ptr(rates),
            ag,
            GRAVITY,
            mass.as_mut_ptr(),
            load.as_mut_ptr(),
            g.as_mut_ptr(),
            gdot.as_mut_ptr(),
        )
    };
    (code, mass, load, g, gdot)
}

/// `rocking_arch_system` of `arch` (NULL allowed) with `nj` joints under `gravity` into `mass`
/// (and `load`), no ground acceleration and no `G`: the calls of the error tests, whose
/// answers are the code and what stays in the caller's arrays.
fn arch_system_errors(
    arch: *const RockingArch,
    nj: usize,
    phi: Option<&[f64]>,
    rates: Option<&[f64]>,
    gravity: f64,
    mass: &mut [f64],
    load: Option<&mut [f64]>,
) -> i32 {
    let ptr = |v: Option<&[f64]>| v.map_or(std::ptr::null(), <[f64]>::as_ptr);
    unsafe {
        rocking_arch_system(
            arch,
            nj,
            ptr(phi),
            ptr(rates),
            0.0,
            gravity,
            mass.as_mut_ptr(),
            load.map_or(std::ptr::null_mut(), <[f64]>::as_mut_ptr),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        )
    }
}

#[allow(clippy::too_many_arguments)]
fn opening(
    n: usize,
    mass: &[f64],
    load: &[f64],
    nc: usize,
    g: *const f64,
    rhs: *const f64,
    status: &mut [i8],
    acc: &mut [f64],
) -> (i32, RockingReport) {
    let mut report = std::mem::MaybeUninit::<RockingReport>::zeroed();
    let code = unsafe {
        rocking_opening_model_constrained(
            n,
            mass.as_ptr(),
            load.as_ptr(),
            nc,
            g,
            rhs,
            status.as_mut_ptr(),
            acc.as_mut_ptr(),
            std::ptr::null(),
            report.as_mut_ptr(),
        )
    };
    (code, unsafe { report.assume_init() })
}

/// The arch's system through the C ABI is the chain's; the opening model at rest under 1.2 λ_c
/// opens four hinges, and its answer is the Rust function's to the bit; the four hinges swinging
/// back through the impact model close together, energy does not rise, and the rates after
/// satisfy the closure.
#[test]
fn arch_through_the_c_abi() {
    let n = ARCH.voussoirs + 1;
    let m = 2 * n;
    let (code, mass, _, g, gdot) = arch_system(None, None, 0.0);
    assert_eq!(code, ROCKING_OK, "{}", last_error());
    let chain = VoussoirArch::semicircular(5.0, 0.75, 20).chain().unwrap();
    let pose = chain.pose(&vec![0.0; m]);
    assert_eq!(mass, chain.mass_matrix(&pose));
    assert_eq!(g, chain.closure_matrix(&pose));
    assert_eq!(gdot, vec![0.0; 3]);
    // t/R = 0.15, 20 voussoirs: λ_c ≈ 0.15 (tests/arch_statics.rs); 1.2 λ_c opens.
    let (_, _, load, _, _) = arch_system(None, None, -0.18 * GRAVITY);
    let mut status = vec![0i8; n];
    let mut acc = vec![0.0; m];
    let (code, report) = opening(
        n,
        &mass,
        &load,
        3,
        g.as_ptr(),
        std::ptr::null(),
        &mut status,
        &mut acc,
    );
    assert_eq!(code, ROCKING_OK, "{}", last_error());
    assert_eq!(report.changed, 1);
    let hinges: Vec<usize> = (0..n).filter(|&k| status[k] != 0).collect();
    assert_eq!(hinges.len(), 4, "{status:?}");
    let mut st = vec![Status::Closed; n];
    let mut a = vec![0.0; m];
    crate::opening_model_constrained(
        &mass,
        &load,
        &g,
        None,
        &mut st,
        &mut a,
        &crate::ModelOptions::default(),
    )
    .unwrap();
    assert_eq!(super::super::encode(&st), status);
    assert_eq!(
        a.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        acc.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );
    // NULL constraint_rhs is zeros: the same answer, bit for bit, as three explicit zeros.
    let (mut status_z, mut acc_z) = (vec![0i8; n], vec![0.0; m]);
    let zeros = [0.0; 3];
    let (code, _) = opening(
        n,
        &mass,
        &load,
        3,
        g.as_ptr(),
        zeros.as_ptr(),
        &mut status_z,
        &mut acc_z,
    );
    assert_eq!(code, ROCKING_OK, "{}", last_error());
    assert_eq!(status_z, status);
    assert_eq!(
        acc_z.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        acc.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );
    // The mechanism's rates (its accelerations are a velocity of the mechanism: G a = 0 from
    // rest) reversed: all four hinges move back towards zero and close at once.
    let mut velocity: Vec<f64> = acc.iter().map(|x| -x).collect();
    let closing: Vec<u8> = status.iter().map(|&s| u8::from(s != 0)).collect();
    let before = status.clone();
    let mut report = std::mem::MaybeUninit::<RockingReport>::zeroed();
    let code = unsafe {
        rocking_impact_model_constrained(
            n,
            mass.as_ptr(),
            3,
            g.as_ptr(),
            status.as_mut_ptr(),
            velocity.as_mut_ptr(),
            closing.as_ptr(),
            std::ptr::null(),
            report.as_mut_ptr(),
        )
    };
    assert_eq!(code, ROCKING_OK, "{}", last_error());
    let report = unsafe { report.assume_init() };
    assert!(report.kinetic_after <= report.kinetic_before * (1.0 + 1e-12));
    for k in 0..n {
        if before[k] != 0 {
            assert_ne!(status[k], before[k], "joint {k} keeps its corner");
        }
    }
    for row in 0..3 {
        let gv: f64 = (0..m).map(|d| g[row * m + d] * velocity[d]).sum();
        assert!(gv.abs() < 1e-9, "closure after the impact: {gv}");
    }
}

/// Without constraints and with one closing flag the constrained entry points are the column's,
/// bit for bit (thesis Eq. 11 and Fig. 19).
#[test]
fn without_constraints_they_are_the_column_entry_points() {
    let case = samples::two_block_impact();
    for n_impacts in [1, 2] {
        let opts = RockingOptions {
            n_impacts,
            solver: ROCKING_SOLVER_AUTO,
            tolerance: 1e-12,
        };
        let status0: Vec<i8> = case.statuses.iter().map(|s| s.as_i8()).collect();
        let (mut s1, mut v1) = (status0.clone(), case.velocity.clone());
        let (mut s2, mut v2) = (status0.clone(), case.velocity.clone());
        let mut flags = [0u8; 2];
        flags[case.closing] = 1;
        let (mut r1, mut r2) = (
            std::mem::MaybeUninit::<RockingReport>::zeroed(),
            std::mem::MaybeUninit::<RockingReport>::zeroed(),
        );
        let (c1, c2) = unsafe {
            (
                rocking_impact_model(
                    2,
                    case.mass.as_ptr(),
                    s1.as_mut_ptr(),
                    v1.as_mut_ptr(),
                    case.closing,
                    &opts,
                    r1.as_mut_ptr(),
                ),
                rocking_impact_model_constrained(
                    2,
                    case.mass.as_ptr(),
                    0,
                    std::ptr::null(),
                    s2.as_mut_ptr(),
                    v2.as_mut_ptr(),
                    flags.as_ptr(),
                    &opts,
                    r2.as_mut_ptr(),
                ),
            )
        };
        assert_eq!((c1, c2), (0, 0));
        assert_eq!(s1, s2);
        assert_eq!(
            v1.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            v2.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        let (r1, r2) = unsafe { (r1.assume_init(), r2.assume_init()) };
        assert_eq!(format!("{r1:?}"), format!("{r2:?}"));
    }
    let push = samples::two_block_top_push();
    let (mut s1, mut a1) = ([0i8; 2], [0.0; 4]);
    let (mut s2, mut a2) = ([0i8; 2], [0.0; 4]);
    let c1 = unsafe {
        rocking_opening_model(
            2,
            push.mass.as_ptr(),
            push.load.as_ptr(),
            s1.as_mut_ptr(),
            a1.as_mut_ptr(),
            std::ptr::null(),
            std::ptr::null_mut(),
        )
    };
    let (c2, _) = opening(
        2,
        &push.mass,
        &push.load,
        0,
        std::ptr::null(),
        std::ptr::null(),
        &mut s2,
        &mut a2,
    );
    assert_eq!((c1, c2), (0, 0));
    assert_eq!(s1, s2);
    assert_eq!(a1.map(f64::to_bits), a2.map(f64::to_bits));
}

/// Every error class: its code, the caller's arrays untouched, a message naming the argument.
#[test]
fn constrained_error_classes() {
    let n = ARCH.voussoirs + 1;
    let m = 2 * n;
    let (_, mass, load, g, _) = arch_system(None, None, -0.18 * GRAVITY);
    let status0 = vec![0i8; n];
    let run = |nc: usize, gp: *const f64, rhs: *const f64, status: &[i8], mass: &[f64]| {
        let mut st = status.to_vec();
        let mut acc = vec![7.0; m];
        let (code, _) = opening(n, mass, &load, nc, gp, rhs, &mut st, &mut acc);
        if code != 0 {
            assert_eq!(st, status);
            assert!(acc.iter().all(|&a| a == 7.0));
        }
        (code, last_error())
    };
    let (code, msg) = run(3, std::ptr::null(), std::ptr::null(), &status0, &mass);
    assert_eq!(
        (code, msg.as_str()),
        (
            ROCKING_ERR_NULL_POINTER,
            "a required pointer argument is NULL: constraints is NULL"
        )
    );
    let (code, msg) = run(
        ROCKING_MAX_CONSTRAINTS + 1,
        g.as_ptr(),
        std::ptr::null(),
        &status0,
        &mass,
    );
    assert_eq!(code, ROCKING_ERR_INVALID_SIZE);
    assert!(msg.contains("n_constraints"), "{msg}");
    // A loop's M without its G is singular: not positive definite.
    let (code, _) = run(0, std::ptr::null(), std::ptr::null(), &status0, &mass);
    assert_eq!(code, ROCKING_ERR_NOT_POSITIVE_DEFINITE);
    let mut bad_g = g.clone();
    bad_g[5] = f64::NAN;
    let (code, msg) = run(3, bad_g.as_ptr(), std::ptr::null(), &status0, &mass);
    assert_eq!(code, ROCKING_ERR_NOT_FINITE);
    assert!(msg.contains("constraints[5]"), "{msg}");
    let rhs = [0.0, f64::INFINITY, 0.0];
    let (code, msg) = run(3, g.as_ptr(), rhs.as_ptr(), &status0, &mass);
    assert_eq!(code, ROCKING_ERR_NOT_FINITE);
    assert!(msg.contains("constraint_rhs[1]"), "{msg}");
    let mut bad_status = status0.clone();
    bad_status[4] = 3;
    let (code, _) = run(3, g.as_ptr(), std::ptr::null(), &bad_status, &mass);
    assert_eq!(code, ROCKING_ERR_INVALID_STATUS);
    // A closure no configuration satisfies (a zero row of G with r = 1): the code's text speaks of
    // the constraints, not of a closing interface this call does not have.
    let mut g4 = g.clone();
    g4.extend(vec![0.0; m]);
    let rhs = [0.0, 0.0, 0.0, 1.0];
    let (code, msg) = run(4, g4.as_ptr(), rhs.as_ptr(), &status0, &mass);
    assert_eq!(code, ROCKING_ERR_INCONSISTENT_STATE);
    assert!(msg.contains("constraint row 3"), "{msg}");
    let text = unsafe { CStr::from_ptr(rocking_error_message(code)) }.to_string_lossy();
    assert!(text.contains("constraints"), "{text}");

    // Impact: flags other than 0/1, no flag, a closed joint flagged.
    let mut status = vec![0i8; n];
    status[3] = -1;
    status[9] = 1;
    status[15] = -1;
    status[20] = 1;
    let velocity = vec![0.0; m];
    let impact = |flags: &[u8], status: &[i8]| {
        let mut st = status.to_vec();
        let mut v = velocity.clone();
        let code = unsafe {
            rocking_impact_model_constrained(
                n,
                mass.as_ptr(),
                3,
                g.as_ptr(),
                st.as_mut_ptr(),
                v.as_mut_ptr(),
                flags.as_ptr(),
                std::ptr::null(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(st, status);
        assert_eq!(v, velocity);
        (code, last_error())
    };
    let mut flags = vec![0u8; n];
    flags[3] = 2;
    let (code, msg) = impact(&flags, &status);
    assert_eq!(code, ROCKING_ERR_INVALID_CLOSING_INTERFACE);
    assert!(msg.contains("closing[3] = 2"), "{msg}");
    let (code, _) = impact(&vec![0u8; n], &status);
    assert_eq!(code, ROCKING_ERR_INVALID_CLOSING_INTERFACE);
    let mut flags = vec![0u8; n];
    flags[4] = 1;
    let (code, msg) = impact(&flags, &status);
    assert_eq!(code, ROCKING_ERR_INVALID_CLOSING_INTERFACE);
    assert!(msg.contains("interface 4"), "{msg}");
    let code = unsafe {
        rocking_impact_model_constrained(
            n,
            mass.as_ptr(),
            3,
            g.as_ptr(),
            status.clone().as_mut_ptr(),
            velocity.clone().as_mut_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            std::ptr::null_mut(),
        )
    };
    assert_eq!(code, ROCKING_ERR_NULL_POINTER);
    assert!(last_error().contains("closing is NULL"));
}

/// The helpers check their arguments and write nothing on error.
#[test]
fn system_helper_errors() {
    let n = ARCH.voussoirs + 1;
    let m = 2 * n;
    let mut mass = vec![3.0; m * m];
    let call = |arch: &RockingArch, nj: usize, phi: Option<&[f64]>, mass: &mut [f64]| {
        arch_system_errors(arch, nj, phi, None, GRAVITY, mass, None)
    };
    assert_eq!(
        call(&ARCH, n - 1, None, &mut mass),
        ROCKING_ERR_INVALID_SIZE
    );
    assert!(last_error().contains("20 voussoirs has 21 joints"));
    let thick = RockingArch {
        thickness: 10.0,
        ..ARCH
    };
    assert_eq!(
        call(&thick, n, None, &mut mass),
        ROCKING_ERR_INVALID_GEOMETRY
    );
    assert!(last_error().contains("arch.thickness"));
    // The code's text is about geometry in general: an arch has no column.
    assert!(!last_error().contains("column"), "{}", last_error());
    let mut phi = vec![0.0; m];
    phi[2] = 0.1;
    assert_eq!(
        call(&ARCH, n, Some(&phi), &mut mass),
        ROCKING_ERR_INVALID_ANGLES
    );
    assert!(last_error().contains("phi[2] = 0.1"), "{}", last_error());
    assert!(mass.iter().all(|&x| x == 3.0));
    // A closed joint turning the inadmissible way: the message names the entry of `rates`.
    let mut rates = vec![0.0; m];
    rates[3] = 1.0;
    let code = arch_system_errors(&ARCH, n, None, Some(&rates), GRAVITY, &mut mass, None);
    assert_eq!(code, ROCKING_ERR_VELOCITY_ON_CLOSED_DOF);
    assert!(last_error().contains("rates[3] = 1"), "{}", last_error());
    assert!(mass.iter().all(|&x| x == 3.0));
    let code = arch_system_errors(std::ptr::null(), n, None, None, GRAVITY, &mut mass, None);
    assert_eq!(code, ROCKING_ERR_NULL_POINTER);
    assert!(last_error().contains("arch is NULL"));
    // Colonnade: the joint count, the blocks, the beam.
    let col = [0.6, 3.6, 1500.0];
    let beam = [3.6, 0.5, 2400.0];
    let mut out = vec![3.0; 64];
    let colonnade = |n_left: usize, nj: usize, left: &[f64], beam: &[f64], out: &mut [f64]| unsafe {
        rocking_colonnade_system(
            n_left,
            left.as_ptr(),
            1,
            col.as_ptr(),
            beam.as_ptr(),
            3.0,
            nj,
            std::ptr::null(),
            std::ptr::null(),
            0.0,
            GRAVITY,
            out.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        )
    };
    assert_eq!(colonnade(1, 4, &col, &beam, &mut out), ROCKING_OK);
    let frame = crate::chain::colonnade::CappedColonnade::frame(0.6, 3.6, 1500.0, 3.0, 0.5, 2400.0)
        .chain()
        .unwrap();
    assert_eq!(out, frame.mass_matrix(&frame.pose(&[0.0; 8])));
    let mut out = vec![3.0; 64];
    assert_eq!(
        colonnade(1, 5, &col, &beam, &mut out),
        ROCKING_ERR_INVALID_SIZE
    );
    assert_eq!(
        colonnade(usize::MAX, 4, &col, &beam, &mut out),
        ROCKING_ERR_INVALID_SIZE
    );
    assert_eq!(
        colonnade(0, 3, &col, &beam, &mut out),
        ROCKING_ERR_INVALID_SIZE
    );
    let short = [0.6, 2.0, 1500.0];
    assert_eq!(
        colonnade(1, 4, &short, &beam, &mut out),
        ROCKING_ERR_INVALID_GEOMETRY
    );
    assert!(last_error().contains("colonnade.right"), "{}", last_error());
    let nan_beam = [3.6, f64::NAN, 2400.0];
    assert_eq!(
        colonnade(1, 4, &col, &nan_beam, &mut out),
        ROCKING_ERR_NOT_FINITE
    );
    assert!(last_error().contains("beam[1]"));
    assert!(out.iter().all(|&x| x == 3.0));
}

/// Gravity is the magnitude, positive: the arch and colonnade helpers refuse −9.81 and 0 (an
/// upside-down or missing load otherwise), naming the argument, and write nothing.
#[test]
fn system_helpers_refuse_gravity_that_is_not_positive() {
    let n = ARCH.voussoirs + 1;
    let (col, beam) = ([0.6, 3.6, 1500.0], [3.6, 0.5, 2400.0]);
    for gravity in [-GRAVITY, 0.0] {
        let mut mass = vec![3.0; 4 * n * n];
        let mut load = vec![3.0; 2 * n];
        let code = arch_system_errors(&ARCH, n, None, None, gravity, &mut mass, Some(&mut load));
        assert_eq!(
            code, ROCKING_ERR_INVALID_GEOMETRY,
            "arch, gravity = {gravity}"
        );
        assert!(last_error().contains("gravity"), "{}", last_error());
        assert!(mass.iter().chain(&load).all(|&x| x == 3.0));
        let mut out = vec![3.0; 64];
        let code = unsafe {
            rocking_colonnade_system(
                1,
                col.as_ptr(),
                1,
                col.as_ptr(),
                beam.as_ptr(),
                3.0,
                4,
                std::ptr::null(),
                std::ptr::null(),
                0.0,
                gravity,
                out.as_mut_ptr(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(
            code, ROCKING_ERR_INVALID_GEOMETRY,
            "colonnade, gravity = {gravity}"
        );
        assert!(last_error().contains("gravity"), "{}", last_error());
        assert!(out.iter().all(|&x| x == 3.0));
    }
}
