//! Dense symmetric positive definite factorisation on slices, without allocation, for the many
//! small systems `M_FF x = b` of the models (thesis Eq. 7 and Eq. 6 on a configuration).

/// Dot product with four independent accumulators, so that the compiler can keep several
/// multiply-adds in flight (a plain `sum()` is one serial dependency chain).
#[inline]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0_f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        acc[0] += x[0] * y[0];
        acc[1] += x[1] * y[1];
        acc[2] += x[2] * y[2];
        acc[3] += x[3] * y[3];
    }
    let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for (x, y) in ra.iter().zip(rb) {
        s += x * y;
    }
    s
}

/// In-place lower Cholesky factor of the row-major `m × m` matrix `a` (only the lower triangle is
/// read and written). Returns `false` when a pivot is not positive (not positive definite).
///
/// `m ≤ 3` (every step of a column of up to three blocks) is written out: the same operations in
/// the same order as the loop, bit for bit (`dot` of an empty slice is `+0`, of one pair
/// `0 + x y`; `a − (+0)` is `a`, and `0 + x y` is kept as it is, since it turns `−0` into `+0`).
#[inline]
pub fn factor(a: &mut [f64], m: usize) -> bool {
    match m {
        1 => {
            let d = a[0];
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            a[0] = d.sqrt();
            true
        }
        2 => {
            let a = &mut a[..4];
            let d = a[0];
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            let l00 = d.sqrt();
            a[0] = l00;
            let l10 = a[2] / l00;
            a[2] = l10;
            let d = a[3] - (0.0 + l10 * l10);
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            a[3] = d.sqrt();
            true
        }
        3 => {
            let a = &mut a[..9];
            let d = a[0];
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            let l00 = d.sqrt();
            a[0] = l00;
            let l10 = a[3] / l00;
            a[3] = l10;
            let l20 = a[6] / l00;
            a[6] = l20;
            let d = a[4] - (0.0 + l10 * l10);
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            let l11 = d.sqrt();
            a[4] = l11;
            let l21 = (a[7] - (0.0 + l20 * l10)) / l11;
            a[7] = l21;
            let d = a[8] - ((0.0 + l20 * l20) + l21 * l21);
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            a[8] = d.sqrt();
            true
        }
        _ => factor_loop(a, m),
    }
}

/// [`factor`] for any `m`.
fn factor_loop(a: &mut [f64], m: usize) -> bool {
    for j in 0..m {
        let row_j = &a[j * m..j * m + j];
        let d = a[j * m + j] - dot(row_j, row_j);
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * m + j] = d;
        for i in j + 1..m {
            let (upper, lower) = a.split_at_mut(i * m);
            let s = lower[j] - dot(&lower[..j], &upper[j * m..j * m + j]);
            lower[j] = s / d;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place with the factor of [`factor`]; `m ≤ 3` written out, bit for bit
/// as the loop (see [`factor`]).
#[inline]
pub fn solve(l: &[f64], m: usize, x: &mut [f64]) {
    match m {
        1 => {
            let l00 = l[0];
            x[0] = x[0] / l00 / l00;
        }
        2 => {
            let (l, x) = (&l[..4], &mut x[..2]);
            let x0 = x[0] / l[0];
            let x1 = (x[1] - (0.0 + l[2] * x0)) / l[3];
            let x1 = x1 / l[3];
            x[1] = x1;
            x[0] = (x0 - l[2] * x1) / l[0];
        }
        3 => {
            let (l, x) = (&l[..9], &mut x[..3]);
            let x0 = x[0] / l[0];
            let x1 = (x[1] - (0.0 + l[3] * x0)) / l[4];
            let x2 = (x[2] - ((0.0 + l[6] * x0) + l[7] * x1)) / l[8];
            let x2 = x2 / l[8];
            let x1 = (x1 - l[7] * x2) / l[4];
            x[2] = x2;
            x[1] = x1;
            x[0] = ((x0 - l[3] * x1) - l[6] * x2) / l[0];
        }
        _ => solve_loop(l, m, x),
    }
}

/// [`solve`] for any `m`.
fn solve_loop(l: &[f64], m: usize, x: &mut [f64]) {
    for i in 0..m {
        let s = x[i] - dot(&l[i * m..i * m + i], &x[..i]);
        x[i] = s / l[i * m + i];
    }
    for i in (0..m).rev() {
        let mut s = x[i];
        for k in i + 1..m {
            s -= l[k * m + i] * x[k];
        }
        x[i] = s / l[i * m + i];
    }
}

/// Estimate of the 2-norm condition number from the factor: `(max Lᵢᵢ / min Lᵢᵢ)²`, a lower
/// bound of the true condition number that is cheap and good enough to flag near-singular
/// sub-matrices (a tiny block on a huge one).
pub fn condition_estimate(l: &[f64], m: usize) -> f64 {
    if m == 0 {
        return 1.0;
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for i in 0..m {
        let d = l[i * m + i];
        lo = lo.min(d);
        hi = hi.max(d);
    }
    (hi / lo).powi(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_spd_system() {
        let a = [4.0, 2.0, 0.6, 2.0, 5.0, 1.0, 0.6, 1.0, 3.0];
        let mut l = a;
        assert!(factor(&mut l, 3));
        let mut x = [1.0, -2.0, 0.5];
        let b = x;
        solve(&l, 3, &mut x);
        for i in 0..3 {
            let r: f64 = (0..3).map(|k| a[i * 3 + k] * x[k]).sum();
            assert!((r - b[i]).abs() < 1e-12);
        }
    }

    /// The written-out `m ≤ 3` are the loops bit for bit, on random SPD, indefinite and signed-zero
    /// inputs.
    #[test]
    fn small_sizes_are_the_loops_bit_for_bit() {
        let mut uniform = crate::test_support::uniform(0x9e37_79b9_7f4a_7c15_u64);
        let mut next = move || uniform() - 0.5;
        for case in 0..30_000 {
            let m = 1 + case % 3;
            let mut b = vec![0.0; m * m];
            for v in b.iter_mut() {
                *v = match case % 7 {
                    0 => 0.0,
                    1 => -0.0,
                    _ => next(),
                };
            }
            let mut a = vec![0.0; m * m];
            for i in 0..m {
                for j in 0..m {
                    let s: f64 = (0..m).map(|k| b[i * m + k] * b[j * m + k]).sum();
                    a[i * m + j] = if case % 5 == 0 { next() } else { s };
                }
                if case % 5 != 0 {
                    a[i * m + i] += 1e-3 * (case % 4) as f64;
                }
            }
            let (mut fast, mut slow) = (a.clone(), a.clone());
            let ok = factor(&mut fast, m);
            assert_eq!(ok, factor_loop(&mut slow, m));
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&fast), bits(&slow), "factor, m = {m}");
            if ok {
                let rhs: Vec<f64> = (0..m)
                    .map(|i| if case % 11 == i { -0.0 } else { next() })
                    .collect();
                let (mut xf, mut xs) = (rhs.clone(), rhs);
                solve(&fast, m, &mut xf);
                solve_loop(&slow, m, &mut xs);
                assert_eq!(bits(&xf), bits(&xs), "solve, m = {m}");
            }
        }
    }

    #[test]
    fn rejects_indefinite() {
        let mut a = [1.0, 2.0, 2.0, 1.0];
        assert!(!factor(&mut a, 2));
        let mut nan = [f64::NAN];
        assert!(!factor(&mut nan, 1));
    }
}
