//! The column helpers of the C ABI called from Rust: `rocking_column_mass_matrix` reproduces
//! thesis Eq. 10 and checks its input; `rocking_reduce` reproduces Appendix C.

use super::tests::last_error;
use super::*;
use crate::samples;

/// `rocking_column_mass_matrix` of two blocks of width `w`, heights 0.3 m and masses 15 kg at
/// the DOF angles `phi` (NULL: straight), no ground acceleration, into `out` (and `load`).
fn column_mass_matrix(
    w: &[f64; 2],
    phi: Option<&[f64; 4]>,
    out: &mut [f64; 16],
    load: Option<&mut [f64; 4]>,
) -> i32 {
    column_mass_matrix_called(2, w, 9.81, phi, out, load)
}

/// [`column_mass_matrix`] with the block count `n` the caller passes (the arrays still hold
/// two blocks: a count the function refuses is refused before they are read) and `gravity`.
fn column_mass_matrix_called(
    n: usize,
    w: &[f64; 2],
    gravity: f64,
    phi: Option<&[f64; 4]>,
    out: &mut [f64; 16],
    load: Option<&mut [f64; 4]>,
) -> i32 {
    let h = [0.3, 0.3];
    let m = [15.0, 15.0];
    unsafe {
        rocking_column_mass_matrix(
            n,
            w.as_ptr(),
            h.as_ptr(),
            m.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            phi.map_or(std::ptr::null(), |p| p.as_ptr()),
            0.0,
            gravity,
            out.as_mut_ptr(),
            load.map_or(std::ptr::null_mut(), |l| l.as_mut_ptr()),
        )
    }
}

#[test]
fn column_mass_matrix_entry_point_matches_eq10_and_checks_input() {
    let w = [0.1, 0.1];
    let mut out = [0.0; 16];
    let mut load = [0.0; 4];
    assert_eq!(column_mass_matrix(&w, None, &mut out, Some(&mut load)), 0);
    assert!((out[2] - samples::THESIS_EQ10_MASS[0][2]).abs() < 1e-12);
    let before = out;
    let code = column_mass_matrix(&[0.1, -0.1], None, &mut out, None);
    assert_eq!(code, ROCKING_ERR_INVALID_GEOMETRY);
    assert!(last_error().contains("block 1"), "{}", last_error());
    let phi = [0.1, 0.0, 0.0, 0.0]; // phĭ must be <= 0
    let code = column_mass_matrix(&w, Some(&phi), &mut out, None);
    assert_eq!(code, ROCKING_ERR_INVALID_ANGLES);
    // The message names the entries of the argument, as the caller indexes them.
    assert!(last_error().contains("phi[0] = 0.1"), "{}", last_error());
    assert_eq!(out, before);
    // Finite blocks whose derived inertia overflows: the overflow code, naming the inputs (not
    // an invalid geometry "inertia = inf" the caller never gave).
    let code = column_mass_matrix(&[1e200, 1e200], None, &mut out, None);
    assert_eq!(code, ROCKING_ERR_OVERFLOW, "{}", last_error());
    assert!(
        last_error().contains("block 0: the inertia") && last_error().contains("width = 1e200"),
        "{}",
        last_error()
    );
    assert_eq!(out, before);
}

#[test]
fn reduce_entry_point_reproduces_appendix_c() {
    // Thesis Eq. C9–C13 with the exact three-point masses of a 1 × 4 m, 1 kg block.
    let end = (17.0 / 12.0) / 8.0;
    let masses = [end, 1.0 - 2.0 * end, end, end, 1.0 - 2.0 * end, end];
    let nn = 12;
    let mut nodal = vec![0.0; nn * nn];
    for i in 0..6 {
        nodal[i * nn + i] = masses[i];
        nodal[(6 + i) * nn + 6 + i] = masses[i];
    }
    // B of Eq. C11, column-major (column 0 then column 1).
    let b = [
        0.0, -2.0, -4.0, -4.0, -6.0, -8.0, -0.5, -0.5, -0.5, -0.5, -0.5, -0.5, //
        0.0, 0.0, 0.0, 0.0, -2.0, -4.0, 0.0, 0.0, 0.0, -0.5, -0.5, -0.5,
    ];
    let p: Vec<f64> = (0..12)
        .map(|i| {
            if i < 6 {
                masses[i]
            } else {
                -9.81 * masses[i - 6]
            }
        })
        .collect();
    let mut rm = [0.0; 4];
    let mut rl = [0.0; 2];
    // `rocking_reduce` of the 12 nodal DOFs onto 2 interface DOFs, into `rm` and `rl`.
    let reduce = |nodal: &[f64], rm: &mut [f64; 4], rl: &mut [f64; 2]| unsafe {
        rocking_reduce(
            12,
            2,
            nodal.as_ptr(),
            b.as_ptr(),
            p.as_ptr(),
            rm.as_mut_ptr(),
            rl.as_mut_ptr(),
        )
    };
    let code = reduce(&nodal, &mut rm, &mut rl);
    assert_eq!(code, 0, "{}", last_error());
    let r3 = |x: f64| (x * 1000.0).round() / 1000.0;
    assert_eq!([r3(rm[0]), r3(rm[1]), r3(rm[3])], [43.333, 13.667, 5.667]);
    assert_eq!([r3(rl[0]), r3(rl[1])], [1.810, 2.905]);
    // Not symmetric: refused, naming the argument (`nodal_mass`, not the models' `mass`),
    // outputs untouched.
    nodal[1] = 0.5;
    let code = reduce(&nodal, &mut rm, &mut rl);
    assert_eq!(code, ROCKING_ERR_NOT_SYMMETRIC);
    assert!(
        last_error().contains("nodal_mass[0][1] = 0.5"),
        "{}",
        last_error()
    );
    assert_eq!(r3(rm[0]), 43.333);
    nodal[1] = f64::NAN;
    let code = reduce(&nodal, &mut rm, &mut rl);
    assert_eq!(code, ROCKING_ERR_NOT_FINITE);
    assert!(
        last_error().contains("nodal_mass[1] = NaN"),
        "{}",
        last_error()
    );
    assert_eq!(r3(rm[0]), 43.333);
}

/// Gravity is the magnitude, positive (the header, docs/c-api.md): an FE code's `g_y = −9.81`
/// (or a forgotten 0) would turn the load upside down (or off) without a word, so it is refused,
/// naming the argument, and nothing is written.
#[test]
fn column_mass_matrix_refuses_gravity_that_is_not_positive() {
    for gravity in [-9.81, 0.0, -0.0] {
        let mut out = [7.0; 16];
        let mut load = [7.0; 4];
        let code =
            column_mass_matrix_called(2, &[0.1; 2], gravity, None, &mut out, Some(&mut load));
        assert_eq!(code, ROCKING_ERR_INVALID_GEOMETRY, "gravity = {gravity}");
        assert!(last_error().contains("gravity"), "{}", last_error());
        assert_eq!((out, load), ([7.0; 16], [7.0; 4]));
    }
}

/// A bad `n_blocks` is refused with a message naming `n_blocks`, the argument of this function
/// (not the models' `n_interfaces`).
#[test]
fn column_mass_matrix_names_n_blocks() {
    let mut out = [7.0; 16];
    for (n, want) in [(0, "n_blocks is 0"), (4097, "n_blocks = 4097 exceeds")] {
        let code = column_mass_matrix_called(n, &[0.1; 2], 9.81, None, &mut out, None);
        assert_eq!(code, ROCKING_ERR_INVALID_SIZE);
        assert!(last_error().contains(want), "{}", last_error());
        assert_eq!(out, [7.0; 16]);
    }
}
