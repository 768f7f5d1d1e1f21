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
pub fn factor(a: &mut [f64], m: usize) -> bool {
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

/// Solves `L Lᵀ x = b` in place with the factor of [`factor`].
pub fn solve(l: &[f64], m: usize, x: &mut [f64]) {
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

    #[test]
    fn rejects_indefinite() {
        let mut a = [1.0, 2.0, 2.0, 1.0];
        assert!(!factor(&mut a, 2));
        let mut nan = [f64::NAN];
        assert!(!factor(&mut nan, 1));
    }
}
