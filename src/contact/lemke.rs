//! Lemke's complementary pivoting algorithm for the linear complementarity problem
//! `w = M z + q ≥ 0, z ≥ 0, zᵀ w = 0` (Cottle, Pang & Stone, The Linear Complementarity Problem,
//! 1992, §4.4), with the covering vector of ones and the lexicographic ratio test, so that it does
//! not cycle on degenerate problems. The contact problems give it copositive-plus matrices (the
//! LCP of 2D Coulomb friction, Stewart & Trinkle 1996), on which it ends with a solution after a
//! finite number of pivots; here it is the fallback of the active set method and is capped at
//! `50 m` pivots. In floating point the lexicographic comparisons treat ratios within `1e-9` as
//! ties, and when the row of the artificial variable ties for the minimum it leaves (the usual
//! practical rule): without both, the exact ties of degenerate contact problems (symmetric joints
//! at rest) are broken by round-off and the path can end on a ray.

/// Relative tolerance under which two ratios tie.
const TIE: f64 = 1e-9;

/// Workspace of the algorithm (the tableau is reused between calls).
#[derive(Clone, Debug, Default)]
pub struct Lemke {
    tableau: Vec<f64>,
    basis: Vec<usize>,
    z: Vec<f64>,
}

impl Lemke {
    /// Solves the LCP with the row-major `m × m` matrix `mat` and vector `q`; `None` on ray
    /// termination or when the pivot cap is reached.
    pub fn solve(&mut self, mat: &[f64], q: &[f64], m: usize) -> Option<&[f64]> {
        self.z.clear();
        self.z.resize(m, 0.0);
        if q.iter().all(|&x| x >= 0.0) {
            return Some(&self.z);
        }
        // Columns: w (0..m), z (m..2m), z0 (2m), rhs (2m+1).
        let cols = 2 * m + 2;
        let z0 = 2 * m;
        let rhs = 2 * m + 1;
        self.tableau.clear();
        self.tableau.resize(m * cols, 0.0);
        let t = &mut self.tableau;
        for i in 0..m {
            t[i * cols + i] = 1.0;
            for j in 0..m {
                t[i * cols + m + j] = -mat[i * m + j];
            }
            t[i * cols + z0] = -1.0;
            t[i * cols + rhs] = q[i];
        }
        self.basis.clear();
        self.basis.extend(0..m);
        // z0 enters; the row of the most negative q leaves (ties: lexicographic on the rows of
        // B⁻¹ = I).
        let mut r = 0;
        for i in 1..m {
            if q[i] < q[r] || (q[i] == q[r] && i > r) {
                r = i;
            }
        }
        Self::pivot(t, cols, m, r, z0);
        let mut leaving = self.basis[r];
        self.basis[r] = z0;
        for _ in 0..50 * m.max(1) {
            if leaving == z0 {
                break;
            }
            let entering = if leaving < m {
                leaving + m
            } else {
                leaving - m
            };
            // The largest magnitude (a comparison: f64::max's NaN handling is not needed, the
            // running maximum is never NaN and a NaN entry is skipped as by f64::max).
            let mut amax = 0.0_f64;
            for i in 0..m {
                let a = t[i * cols + entering].abs();
                if a > amax {
                    amax = a;
                }
            }
            let eps = 1e-12 * amax;
            let mut best: Option<usize> = None;
            for i in 0..m {
                if t[i * cols + entering] <= eps {
                    continue;
                }
                best = Some(match best {
                    None => i,
                    Some(b) => {
                        if Self::lex_less(t, cols, m, i, b, entering) {
                            i
                        } else {
                            b
                        }
                    }
                });
            }
            // When the row of z0 ties for the minimum ratio, let z0 leave: the algorithm ends.
            if let Some(b) = best {
                if let Some(r0) = self.basis.iter().position(|&v| v == z0) {
                    let a0 = t[r0 * cols + entering];
                    if r0 != b && a0 > eps {
                        let (x, y) = (
                            t[r0 * cols + rhs] / a0,
                            t[b * cols + rhs] / t[b * cols + entering],
                        );
                        if (x - y).abs() <= TIE * x.abs().max(y.abs()) {
                            best = Some(r0);
                        }
                    }
                }
            }
            let r = best?;
            Self::pivot(t, cols, m, r, entering);
            leaving = self.basis[r];
            self.basis[r] = entering;
        }
        if leaving != z0 {
            return None;
        }
        for (i, &b) in self.basis.iter().enumerate() {
            if (m..2 * m).contains(&b) {
                self.z[b - m] = t[i * cols + rhs].max(0.0);
            }
        }
        Some(&self.z)
    }

    /// Whether row `i` is lexicographically smaller than row `j` in the ratio test of column `e`:
    /// `(rhs, B⁻¹ row) / a`, entries within the relative tolerance [`TIE`] counting as equal (the
    /// exact ties of degenerate problems come out of floating point a few ulps apart).
    fn lex_less(t: &[f64], cols: usize, m: usize, i: usize, j: usize, e: usize) -> bool {
        let (ai, aj) = (t[i * cols + e], t[j * cols + e]);
        let rhs = cols - 1;
        let key = |row: usize, a: f64, c: usize| t[row * cols + c] / a;
        let differs = |x: f64, y: f64| (x - y).abs() > TIE * x.abs().max(y.abs());
        let (ri, rj) = (key(i, ai, rhs), key(j, aj, rhs));
        if differs(ri, rj) {
            return ri < rj;
        }
        for c in 0..m {
            let (x, y) = (key(i, ai, c), key(j, aj, c));
            if differs(x, y) {
                return x < y;
            }
        }
        i < j
    }

    /// Pivots the tableau on row `r`, column `e`: row by row with slices (the same operations
    /// in the same order as indexed loops, which the compiler can run over several entries at
    /// once: they are independent).
    fn pivot(t: &mut [f64], cols: usize, m: usize, r: usize, e: usize) {
        let t = &mut t[..m * cols];
        let p = t[r * cols + e];
        let (before, rest) = t.split_at_mut(r * cols);
        let (row_r, after) = rest.split_at_mut(cols);
        for x in row_r.iter_mut() {
            *x /= p;
        }
        let row_r = &*row_r;
        for row in before
            .chunks_exact_mut(cols)
            .chain(after.chunks_exact_mut(cols))
        {
            let f = row[e];
            if f == 0.0 {
                continue;
            }
            for (x, &y) in row.iter_mut().zip(row_r) {
                *x -= f * y;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(mat: &[f64], q: &[f64], z: &[f64]) {
        let m = q.len();
        for i in 0..m {
            let w: f64 = q[i] + (0..m).map(|j| mat[i * m + j] * z[j]).sum::<f64>();
            assert!(z[i] >= 0.0 && w >= -1e-10, "row {i}: z {} w {w}", z[i]);
            assert!((z[i] * w).abs() < 1e-10, "row {i}: z {} w {w}", z[i]);
        }
    }

    /// Symmetric positive definite and P-matrix problems with a known unique solution.
    #[test]
    fn solves_positive_definite_problems() {
        let mut lemke = Lemke::default();
        // Pseudo-random but deterministic.
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        for m in 1..12 {
            let a: Vec<f64> = (0..m * m).map(|_| rnd()).collect();
            let mut mat = vec![0.0; m * m];
            for i in 0..m {
                for j in 0..m {
                    mat[i * m + j] = (0..m).map(|k| a[k * m + i] * a[k * m + j]).sum::<f64>();
                }
                mat[i * m + i] += 0.1;
            }
            let q: Vec<f64> = (0..m).map(|_| rnd()).collect();
            let z = lemke.solve(&mat, &q, m).unwrap().to_vec();
            check(&mat, &q, &z);
        }
    }

    /// A degenerate problem (several zero entries of q) does not cycle.
    #[test]
    fn degenerate_problem() {
        let mut lemke = Lemke::default();
        let mat = [1.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let q = [-1.0, -1.0, 0.0];
        let z = lemke.solve(&mat, &q, 3).unwrap().to_vec();
        check(&mat, &q, &z);
    }
}
