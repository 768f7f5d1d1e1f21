//! Dense symmetric positive definite factorisation on slices, without allocation, for the many
//! small systems `M_FF x = b` of the models (thesis Eq. 7 and Eq. 6 on a configuration).

/// In-place lower Cholesky factor of the row-major `m × m` matrix `a` (only the lower triangle is
/// read and written). Returns `false` when a pivot is not positive (not positive definite).
pub fn factor(a: &mut [f64], m: usize) -> bool {
    for j in 0..m {
        let mut d = a[j * m + j];
        for k in 0..j {
            d -= a[j * m + k] * a[j * m + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * m + j] = d;
        for i in j + 1..m {
            let mut s = a[i * m + j];
            for k in 0..j {
                s -= a[i * m + k] * a[j * m + k];
            }
            a[i * m + j] = s / d;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place with the factor of [`factor`].
pub fn solve(l: &[f64], m: usize, x: &mut [f64]) {
    for i in 0..m {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i * m + k] * x[k];
        }
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
