//! Householder QR with column pivoting of a small dense `k × c` matrix (row-major), the null-space
//! basis of the constrained faces: `Kᵀ Π = Q R`, `Q = H_0 H_1 … H_{ρ−1}`. Its first `ρ` columns
//! span the range of `Kᵀ`, the other `k − ρ` the null space of `K`. `Q` is never formed: the
//! reflectors are applied to vectors and to symmetric matrices.

/// A rank-revealing QR factorisation `Kᵀ Π = Q R` of the `k × c` matrix `Kᵀ`.
#[derive(Debug, Default)]
pub(crate) struct PivotedQr {
    /// Rows of `Kᵀ` (the size of the face).
    pub k: usize,
    /// Columns of `Kᵀ` (constraint rows).
    pub c: usize,
    /// Numerical rank `ρ`.
    pub rank: usize,
    /// `R` (row-major `c × c`, upper triangular in its first `ρ` rows; only those are used).
    pub r: Vec<f64>,
    /// Column permutation: column `j` of `Kᵀ Π` is column `perm[j]` of `Kᵀ`.
    pub perm: Vec<usize>,
    /// Householder vectors, `v_s` of length `k − s` stored at `vecs[s * k ..]` (unit first entry
    /// implicit in `beta`): `H_s = I − beta_s v_s v_sᵀ` acting on entries `s..k`.
    vecs: Vec<f64>,
    beta: Vec<f64>,
    work: Vec<f64>,
    full: Vec<f64>,
}

impl Clone for PivotedQr {
    fn clone(&self) -> Self {
        let mut qr = PivotedQr::default();
        qr.clone_from(self);
        qr
    }

    /// The factors copied into the memory of `self`; the scratch of [`PivotedQr::congruence`]
    /// is not copied (it is overwritten before it is read).
    fn clone_from(&mut self, source: &Self) {
        self.k = source.k;
        self.c = source.c;
        self.rank = source.rank;
        self.r.clone_from(&source.r);
        self.perm.clone_from(&source.perm);
        self.vecs.clone_from(&source.vecs);
        self.beta.clone_from(&source.beta);
    }
}

impl PivotedQr {
    /// Factors the row-major `k × c` matrix `kt` (it is overwritten). A column whose remaining
    /// norm is below `rank_tolerance` times the largest initial column norm ends the
    /// factorisation: the rank is the number of reflectors applied.
    pub fn factor(&mut self, kt: &mut [f64], k: usize, c: usize, rank_tolerance: f64) {
        debug_assert_eq!(kt.len(), k * c);
        if c == 3 {
            // A loop's closure (three rows): the same operations with the columns in registers.
            self.factor_fixed::<3>(kt, k, rank_tolerance);
        } else {
            self.factor_any(kt, k, c, rank_tolerance);
        }
    }

    /// Empties the factorisation for `k` rows and `c` columns.
    fn reset(&mut self, k: usize, c: usize) {
        self.k = k;
        self.c = c;
        self.rank = 0;
        self.perm.clear();
        self.perm.extend(0..c);
        self.vecs.clear();
        self.vecs.resize(k * c.min(k), 0.0);
        self.beta.clear();
        self.r.clear();
        self.r.resize(c * c, 0.0);
    }

    /// Step `s` of the factorisation after its pivot `best` (remaining squared norm
    /// `best_norm`): the pivot column swapped into place, its reflector stored (`vecs`, `beta`)
    /// and column `s` reduced to `−sign(x_s) ‖x‖ e_s`. Returns `β`.
    #[inline(always)]
    fn pivot_and_reduce(&mut self, kt: &mut [f64], s: usize, best: usize, best_norm: f64) -> f64 {
        let (k, c) = (self.k, self.c);
        if best != s {
            for i in 0..k {
                kt.swap(i * c + s, i * c + best);
            }
            self.perm.swap(s, best);
        }
        // Reflector that maps column s (rows s..k) onto −sign(x_s) ‖x‖ e_s.
        let norm = best_norm.sqrt();
        let x0 = kt[s * c + s];
        let alpha = if x0 >= 0.0 { -norm } else { norm };
        let v = &mut self.vecs[s * k..s * k + (k - s)];
        v[0] = x0 - alpha;
        for i in s + 1..k {
            v[i - s] = kt[i * c + s];
        }
        let vnorm2: f64 = v.iter().map(|x| x * x).sum();
        let beta = if vnorm2 > 0.0 { 2.0 / vnorm2 } else { 0.0 };
        self.beta.push(beta);
        kt[s * c + s] = alpha;
        for i in s + 1..k {
            kt[i * c + s] = 0.0;
        }
        beta
    }

    /// [`PivotedQr::factor`] for any number of columns.
    fn factor_any(&mut self, kt: &mut [f64], k: usize, c: usize, rank_tolerance: f64) {
        self.reset(k, c);
        let col_norm2 =
            |kt: &[f64], j: usize, from: usize| (from..k).map(|i| kt[i * c + j].powi(2)).sum();
        let largest = (0..c).fold(0.0_f64, |a, j| a.max(col_norm2(kt, j, 0)));
        let floor = rank_tolerance * rank_tolerance * largest;
        for s in 0..c.min(k) {
            // Pivot: the column with the largest remaining norm.
            let (mut best, mut best_norm) = (s, -1.0);
            for j in s..c {
                let nrm = col_norm2(kt, j, s);
                if nrm > best_norm {
                    best = j;
                    best_norm = nrm;
                }
            }
            if best_norm.is_nan() || best_norm <= floor || best_norm == 0.0 {
                break;
            }
            let beta = self.pivot_and_reduce(kt, s, best, best_norm);
            let v = &self.vecs[s * k..s * k + (k - s)];
            for j in s + 1..c {
                let dot: f64 = (s..k).map(|i| v[i - s] * kt[i * c + j]).sum();
                let f = beta * dot;
                for i in s..k {
                    kt[i * c + j] -= f * v[i - s];
                }
            }
            self.rank = s + 1;
        }
        for i in 0..self.rank {
            for j in i..c {
                self.r[i * c + j] = kt[i * c + j];
            }
        }
    }

    /// [`PivotedQr::factor`] for `C` columns: the same operations, the sums over rows of all the
    /// columns in one sweep (each column's sum in the order of the rows from −0.0, as `sum()`;
    /// the sums of columns not needed are computed and never read).
    fn factor_fixed<const C: usize>(&mut self, kt: &mut [f64], k: usize, rank_tolerance: f64) {
        let c = C;
        self.reset(k, c);
        let col_norms2 = |kt: &[f64], from: usize| -> [f64; C] {
            let mut acc = [-0.0_f64; C];
            for row in kt[from * C..k * C].chunks_exact(C) {
                for j in 0..C {
                    acc[j] += row[j].powi(2);
                }
            }
            acc
        };
        let largest = col_norms2(kt, 0).iter().fold(0.0_f64, |a, &n| a.max(n));
        let floor = rank_tolerance * rank_tolerance * largest;
        for s in 0..c.min(k) {
            // Pivot: the column with the largest remaining norm.
            let norms = col_norms2(kt, s);
            let (mut best, mut best_norm) = (s, -1.0);
            for (j, &nrm) in norms.iter().enumerate().skip(s) {
                if nrm > best_norm {
                    best = j;
                    best_norm = nrm;
                }
            }
            if best_norm.is_nan() || best_norm <= floor || best_norm == 0.0 {
                break;
            }
            let beta = self.pivot_and_reduce(kt, s, best, best_norm);
            let v = &self.vecs[s * k..s * k + (k - s)];
            // The columns after s: `f_j = β (v · kt_j)`, then `kt_j −= f_j v`.
            let mut f = [-0.0_f64; C];
            for (row, &vi) in kt[s * C..k * C].chunks_exact(C).zip(v.iter()) {
                for j in 0..C {
                    f[j] += vi * row[j];
                }
            }
            for fj in &mut f {
                *fj *= beta;
            }
            for (row, &vi) in kt[s * C..k * C].chunks_exact_mut(C).zip(v.iter()) {
                for j in s + 1..C {
                    row[j] -= f[j] * vi;
                }
            }
            self.rank = s + 1;
        }
        for i in 0..self.rank {
            for j in i..c {
                self.r[i * c + j] = kt[i * c + j];
            }
        }
    }

    /// `x ← Qᵀ x` (length `k`).
    pub fn apply_qt(&self, x: &mut [f64]) {
        for s in 0..self.rank {
            self.reflect(s, x);
        }
    }

    /// `x ← Q x` (length `k`).
    pub fn apply_q(&self, x: &mut [f64]) {
        for s in (0..self.rank).rev() {
            self.reflect(s, x);
        }
    }

    fn reflect(&self, s: usize, x: &mut [f64]) {
        let k = self.k;
        let v = &self.vecs[s * k..s * k + (k - s)];
        let dot: f64 = v.iter().zip(&x[s..]).map(|(a, b)| a * b).sum();
        let f = self.beta[s] * dot;
        for (xi, vi) in x[s..].iter_mut().zip(v) {
            *xi -= f * vi;
        }
    }

    /// `A ← Qᵀ A Q` for the symmetric row-major `k × k` matrix `a`, one reflector at a time as
    /// the symmetric rank-two update `H A H = A − v uᵀ − u vᵀ` with `w = A v`,
    /// `u = β w − ½ β² (vᵀw) v`.
    pub fn congruence(&mut self, a: &mut [f64]) {
        let k = self.k;
        let mut w = std::mem::take(&mut self.work);
        // `v` over all `k` entries (zero before `s`).
        let mut vfull = std::mem::take(&mut self.full);
        for s in 0..self.rank {
            let v = &self.vecs[s * k..s * k + (k - s)];
            let beta = self.beta[s];
            row_dots(a, k, s, v, &mut w);
            let gamma: f64 = v.iter().zip(&w[s..]).map(|(x, y)| x * y).sum();
            let half = 0.5 * beta * beta * gamma;
            for i in 0..k {
                w[i] *= beta;
                if i >= s {
                    w[i] -= half * v[i - s];
                }
            }
            vfull.clear();
            vfull.resize(s, 0.0);
            vfull.extend_from_slice(v);
            // Rows and columns before s: only the columns s.. change (A_ij −= u_i v_j).
            for (i, row) in a.chunks_exact_mut(k).enumerate() {
                let ui = w[i];
                let vi = vfull[i];
                if vi == 0.0 {
                    for (x, vj) in row[s..].iter_mut().zip(v) {
                        *x -= ui * vj;
                    }
                } else {
                    // Columns before s have v_j = 0 (the product `ui * 0.0` kept: the same
                    // operations as one loop over every column).
                    for ((x, wj), vj) in row.iter_mut().zip(&w[..k]).zip(&vfull) {
                        *x -= vi * wj + ui * vj;
                    }
                }
            }
        }
        self.work = w;
        self.full = vfull;
    }

    /// Solves `R11ᵀ u = (Πᵀ r)[..ρ]` (forward substitution) and returns the residual of the other
    /// `c − ρ` equations, `max |R12ᵀ u − (Πᵀ r)[ρ..]|`: zero when `r` lies in the range of `K`.
    pub fn solve_range(&self, rhs: &[f64], u: &mut [f64]) -> f64 {
        let (c, rank) = (self.c, self.rank);
        for i in 0..rank {
            let mut s = rhs[self.perm[i]];
            for j in 0..i {
                s -= self.r[j * c + i] * u[j];
            }
            u[i] = s / self.r[i * c + i];
        }
        let mut residual = 0.0_f64;
        for i in rank..c {
            let mut s = rhs[self.perm[i]];
            for j in 0..rank {
                s -= self.r[j * c + i] * u[j];
            }
            residual = residual.max(s.abs());
        }
        residual
    }

    /// Multipliers `μ` (length `c`) of `Kᵀ μ = g` from `w = Qᵀ g` (first `ρ` entries used):
    /// `R11 ν = w[..ρ]`, `μ = Π ν` with the entries beyond the rank set to zero.
    pub fn multipliers(&self, w: &[f64], mu: &mut [f64]) {
        let (c, rank) = (self.c, self.rank);
        mu.iter_mut().for_each(|m| *m = 0.0);
        // `ν` on the stack for the loops' three rows (and up to eight), else on the heap.
        let mut stack = [0.0; 8];
        let mut heap = Vec::new();
        let nu: &mut [f64] = if rank <= stack.len() {
            &mut stack[..rank]
        } else {
            heap.resize(rank, 0.0);
            &mut heap
        };
        for i in (0..rank).rev() {
            let mut s = w[i];
            for j in i + 1..rank {
                s -= self.r[i * c + j] * nu[j];
            }
            nu[i] = s / self.r[i * c + i];
        }
        for i in 0..rank {
            mu[self.perm[i]] = nu[i];
        }
    }
}

/// `w_i = Σ_j a[i][s + j] v_j` for every row `i` of the row-major `k × k` matrix `a`: each sum
/// in the order of `j` from `-0.0`, as `iter().sum()` (the same bits), four rows at a time
/// (independent chains, `v_j` loaded once).
fn row_dots(a: &[f64], k: usize, s: usize, v: &[f64], w: &mut Vec<f64>) {
    let len = k - s;
    let v = &v[..len];
    w.clear();
    w.resize(k, 0.0);
    let mut i = 0;
    while i + 4 <= k {
        let r0 = &a[i * k + s..][..len];
        let r1 = &a[(i + 1) * k + s..][..len];
        let r2 = &a[(i + 2) * k + s..][..len];
        let r3 = &a[(i + 3) * k + s..][..len];
        let mut acc = [-0.0_f64; 4];
        for j in 0..len {
            let vj = v[j];
            acc[0] += r0[j] * vj;
            acc[1] += r1[j] * vj;
            acc[2] += r2[j] * vj;
            acc[3] += r3[j] * vj;
        }
        w[i..i + 4].copy_from_slice(&acc);
        i += 4;
    }
    for (i, wi) in w.iter_mut().enumerate().skip(i) {
        *wi = a[i * k + s..][..len]
            .iter()
            .zip(v)
            .map(|(x, y)| x * y)
            .sum::<f64>();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matmul_t(kt: &[f64], k: usize, c: usize, y: &[f64]) -> Vec<f64> {
        (0..c)
            .map(|j| (0..k).map(|i| kt[i * c + j] * y[i]).sum())
            .collect()
    }

    /// The three-column factorisation is the general one bit for bit (factors, permutation,
    /// rank, reflectors), on random matrices, with a dependent column, zero rows and signed zeros.
    #[test]
    fn three_columns_are_the_general_factor_bit_for_bit() {
        let mut uniform = crate::test_support::uniform(0x2545_f491_4f6c_dd1d_u64);
        let mut next = move || uniform() - 0.5;
        for case in 0..400 {
            let k = 1 + case % 40;
            let mut kt: Vec<f64> = (0..3 * k).map(|_| next()).collect();
            match case % 5 {
                1 => (0..k).for_each(|i| kt[i * 3 + 2] = 2.0 * kt[i * 3]),
                2 => (0..k / 2).for_each(|i| kt[i * 3..i * 3 + 3].fill(-0.0)),
                3 => kt.iter_mut().step_by(2).for_each(|x| *x = 0.0),
                _ => {}
            }
            let (mut a, mut b) = (kt.clone(), kt);
            let (mut qa, mut qb) = (PivotedQr::default(), PivotedQr::default());
            qa.factor_fixed::<3>(&mut a, k, 1e-10);
            qb.factor_any(&mut b, k, 3, 1e-10);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!((qa.rank, &qa.perm), (qb.rank, &qb.perm), "case {case}");
            assert_eq!(bits(&qa.r), bits(&qb.r), "case {case}");
            assert_eq!(bits(&qa.vecs), bits(&qb.vecs), "case {case}");
            assert_eq!(bits(&qa.beta), bits(&qb.beta), "case {case}");
            assert_eq!(bits(&a), bits(&b), "case {case}");
        }
    }

    #[test]
    fn range_and_null_space() {
        // K (2 × 4): two independent rows.
        let k = 4;
        let c = 2;
        let kt0 = vec![1.0, 0.5, 2.0, -1.0, 0.0, 3.0, -1.0, 0.25];
        let mut kt = kt0.clone();
        let mut qr = PivotedQr::default();
        qr.factor(&mut kt, k, c, 1e-12);
        assert_eq!(qr.rank, 2);
        // Particular solution of K y = r.
        let r = [0.7, -1.3];
        let mut u = vec![0.0; k];
        assert!(qr.solve_range(&r, &mut u) == 0.0);
        let mut y = u.clone();
        qr.apply_q(&mut y);
        let ky = matmul_t(&kt0, k, c, &y);
        for j in 0..c {
            assert!((ky[j] - r[j]).abs() < 1e-12, "{ky:?}");
        }
        // Null space: Q e_j, j >= rank.
        for j in 2..k {
            let mut e = vec![0.0; k];
            e[j] = 1.0;
            qr.apply_q(&mut e);
            let ke = matmul_t(&kt0, k, c, &e);
            assert!(ke.iter().all(|v| v.abs() < 1e-12));
        }
    }

    #[test]
    fn detects_rank_deficiency_and_inconsistency() {
        // Second row = 2 × first.
        let (k, c) = (3, 2);
        let mut kt = vec![1.0, 2.0, -1.0, -2.0, 0.5, 1.0];
        let mut qr = PivotedQr::default();
        qr.factor(&mut kt, k, c, 1e-12);
        assert_eq!(qr.rank, 1);
        let mut u = vec![0.0; k];
        assert!(qr.solve_range(&[1.0, 2.0], &mut u) < 1e-14);
        assert!(qr.solve_range(&[1.0, 1.0], &mut u) > 0.1);
    }

    #[test]
    fn congruence_matches_explicit_q() {
        // One reflector (k = 3) and three (k = 5, rank 3).
        let cases: [(usize, usize, Vec<f64>); 2] = [
            (3, 1, vec![1.0, 2.0, 2.0]),
            (
                5,
                3,
                vec![
                    1.0, 0.0, 2.0, 0.5, 1.0, -1.0, -0.3, 0.2, 0.7, 2.0, 1.5, 0.1, 0.4, -0.6, 1.1,
                ],
            ),
        ];
        for (k, c, kt0) in cases {
            let mut kt = kt0.clone();
            let mut qr = PivotedQr::default();
            qr.factor(&mut kt, k, c, 1e-12);
            assert_eq!(qr.rank, c);
            let a0: Vec<f64> = (0..k * k)
                .map(|x| {
                    let (i, j) = (x / k, x % k);
                    let d = if i == j { 5.0 } else { 0.0 };
                    d + 1.0 / (1.0 + (i + j) as f64)
                })
                .collect();
            let mut a = a0.clone();
            qr.congruence(&mut a);
            let mut q = vec![0.0; k * k];
            for j in 0..k {
                let mut e = vec![0.0; k];
                e[j] = 1.0;
                qr.apply_q(&mut e);
                for i in 0..k {
                    q[i * k + j] = e[i];
                }
            }
            for i in 0..k {
                for j in 0..k {
                    let mut s = 0.0;
                    for p in 0..k {
                        for r in 0..k {
                            s += q[p * k + i] * a0[p * k + r] * q[r * k + j];
                        }
                    }
                    assert!((s - a[i * k + j]).abs() < 1e-12, "k = {k}: ({i}, {j})");
                }
            }
        }
    }
}
