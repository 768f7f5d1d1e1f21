//! The block LU of the active set method ([`super::active_set`]) with the reduced sizes as
//! constants: each kernel is written once with its loop bounds as const parameters and called
//! through [`by_size`] / [`by_sizes`], which turn the run-time sizes (0–3 unknowns per joint) into
//! those constants. The floating-point operations and their order are exactly those of the loops
//! with run-time bounds (the compiler unrolls the loops, it does not reassociate them): only the
//! loop counting, the bound checks and the calls go.

use super::friction::{dot3, invert3, Reduction, B3};

/// Calls `f::<M>(args)` for the run-time size `m` (0–3).
macro_rules! by_size {
    ($f:ident, $m:expr, ($($arg:expr),* $(,)?)) => {
        match $m {
            0 => $f::<0>($($arg),*),
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            _ => $f::<3>($($arg),*),
        }
    };
}

/// Calls `f::<M, L>(args)` for the run-time sizes `m`, `l` (0–3 each).
macro_rules! by_sizes {
    ($f:ident, $m:expr, $l:expr, ($($arg:expr),* $(,)?)) => {
        match ($m, $l) {
            (0, 0) => $f::<0, 0>($($arg),*),
            (0, 1) => $f::<0, 1>($($arg),*),
            (0, 2) => $f::<0, 2>($($arg),*),
            (0, _) => $f::<0, 3>($($arg),*),
            (1, 0) => $f::<1, 0>($($arg),*),
            (1, 1) => $f::<1, 1>($($arg),*),
            (1, 2) => $f::<1, 2>($($arg),*),
            (1, _) => $f::<1, 3>($($arg),*),
            (2, 0) => $f::<2, 0>($($arg),*),
            (2, 1) => $f::<2, 1>($($arg),*),
            (2, 2) => $f::<2, 2>($($arg),*),
            (2, _) => $f::<2, 3>($($arg),*),
            (_, 0) => $f::<3, 0>($($arg),*),
            (_, 1) => $f::<3, 1>($($arg),*),
            (_, 2) => $f::<3, 2>($($arg),*),
            (_, _) => $f::<3, 3>($($arg),*),
        }
    };
}

pub(super) use {by_size, by_sizes};

/// `S_k X E_l` for `M` rows of joint `k`'s reduction and `L` columns of joint `l`'s.
#[inline(always)]
fn reduced<const M: usize, const L: usize>(rk: &Reduction, x: &B3, rl: &Reduction) -> B3 {
    let mut out = [[0.0; 3]; 3];
    for i in 0..M {
        let row = &x[rk.rows[i]];
        for j in 0..L {
            out[i][j] = dot3(row, &rl.cols[j]);
        }
    }
    out
}

/// `S_k Xᵀ E_l`.
#[inline(always)]
fn reduced_t<const M: usize, const L: usize>(rk: &Reduction, x: &B3, rl: &Reduction) -> B3 {
    let mut out = [[0.0; 3]; 3];
    for i in 0..M {
        let r = rk.rows[i];
        let row = [x[0][r], x[1][r], x[2][r]];
        for j in 0..L {
            out[i][j] = dot3(&row, &rl.cols[j]);
        }
    }
    out
}

/// The coupling of a joint (`M` unknowns, inverse pivot `dinv`) with the next (`N` unknowns)
/// through their off-diagonal block `wo`: `C = D⁻¹ (S_k W_o E_{k+1})`.
#[inline(always)]
pub(super) fn coupling<const M: usize, const N: usize>(
    rk: &Reduction,
    rn: &Reduction,
    wo: &B3,
    dinv: &B3,
) -> B3 {
    let a_up = reduced::<M, N>(rk, wo, rn);
    let mut c = [[0.0; 3]; 3];
    for i in 0..M {
        for j in 0..N {
            let mut acc = 0.0;
            for l in 0..M {
                acc += dinv[i][l] * a_up[l][j];
            }
            c[i][j] = acc;
        }
    }
    c
}

/// The pivot of a joint with `M` unknowns after the previous joint with `P` (zero: none, or no
/// unknowns) is eliminated: `D = S W_d E − A_lo C_prev`, `rhs = −S b − A_lo d_prev`; its inverse
/// and `y = D⁻¹ rhs`, `None` when `D` is singular.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn pivot<const M: usize, const P: usize>(
    rk: &Reduction,
    rp: &Reduction,
    wd: &B3,
    b: &[f64; 3],
    wo_prev: &B3,
    cprev: &B3,
    dprev: &[f64; 3],
) -> Option<(B3, [f64; 3])> {
    let mut d = reduced::<M, M>(rk, wd, rk);
    let mut rhs = [0.0; 3];
    for i in 0..M {
        rhs[i] = -b[rk.rows[i]];
    }
    if P > 0 {
        let a_lo = reduced_t::<M, P>(rk, wo_prev, rp);
        for i in 0..M {
            for j in 0..M {
                let mut acc = 0.0;
                for l in 0..P {
                    acc += a_lo[i][l] * cprev[l][j];
                }
                d[i][j] -= acc;
            }
            let mut acc = 0.0;
            for l in 0..P {
                acc += a_lo[i][l] * dprev[l];
            }
            rhs[i] -= acc;
        }
    }
    let dinv = invert3(&d, M)?;
    let mut y = [0.0; 3];
    for i in 0..M {
        for j in 0..M {
            y[i] += dinv[i][j] * rhs[j];
        }
    }
    Some((dinv, y))
}

/// Back substitution of a joint with `M` unknowns: `z = d − C z_next` (`N` unknowns next).
#[inline(always)]
pub(super) fn back<const M: usize, const N: usize>(
    dp: &[f64; 3],
    cp: &B3,
    zn: &[f64; 3],
) -> [f64; 3] {
    let mut z = *dp;
    for i in 0..M {
        let mut acc = 0.0;
        for j in 0..N {
            acc += cp[i][j] * zn[j];
        }
        z[i] -= acc;
    }
    z
}

/// The impulses `(P_R, P_L, T)` of the `M` reduced unknowns `z`.
#[inline(always)]
pub(super) fn impulses<const M: usize>(red: &Reduction, z: &[f64; 3]) -> [f64; 3] {
    let mut p = [0.0; 3];
    for j in 0..M {
        let zj = z[j];
        for a in 0..3 {
            p[a] += red.cols[j][a] * zj;
        }
    }
    p
}
