//! The cone problem of SPEC §4 with linear equality constraints (SPEC §9): over the generators
//! `D` (free, bounded, grouped corners) minimise `f(y) = ½ yᵀAy − bᵀy`, `A = DᵀMD`, subject to
//! `(G D) y = r` — the closure of a loop (`G v = 0` for an impact, `G a = −Ġ v` for an opening).
//!
//! A face (a set `S` of generators allowed to be non-zero) is an equality-constrained quadratic
//! problem, solved in the null space of the face's constraint columns `K = (GD)_S`: `Kᵀ Π = Q R`
//! (Householder, column pivoting), `y = Q [u; z]` with `R11ᵀ u = Πᵀ r` and
//! `(QᵀA_SS Q)_22 z = (Qᵀ b)_2 − (QᵀA_SS Q)_21 u`. `M` of a loop is singular on the full DOF set
//! (the cut joint moves no mass): only this reduced matrix must be positive definite, and a
//! Cholesky failure there is the not-positive-definite error. The multipliers `μ` of `Kᵀμ = b −
//! A y` are the generalised closure forces; they give the gradients that the projection solver
//! uses to decide what opens.
//!
//! Scaling: generators with mass are Jacobi-scaled as in [`ConeProblem`] (unit diagonal);
//! massless ones (the cut joint's DOFs, whose rows of `M` are zero) get the scale of the heaviest
//! generator instead of a division by zero, so their rates are judged like the others'. The
//! constraint rows are normalised to unit length and reduced to a linearly independent set.

use crate::error::{ErrorKind, RockingError};
use crate::model::cholesky;
use crate::model::cone::{ConeProblem, Generator};
use crate::model::constrained::householder::PivotedQr;
pub(crate) use crate::model::constrained::work::ConstrainedWork;
use crate::model::constrained::work::{groups_into, singles_into};

/// A diagonal entry of `DᵀMD` below this fraction of the largest is a massless generator.
const MASSLESS: f64 = 1e-12;
/// Relative column norm under which a face's constraint columns are linearly dependent.
const RANK_TOLERANCE: f64 = 1e-10;
/// Relative residual under which a right-hand side lies in the range of a face's constraints.
const CONSISTENCY: f64 = 1e-9;

/// A cone problem with equality constraints, in scaled variables `y = scale ⊙ ŷ`.
pub(crate) struct ConstrainedProblem {
    /// The unconstrained part: generators, groups, `Â`, `b̂`, scales, thresholds.
    pub cone: ConeProblem,
    /// Number of (independent, normalised) constraint rows.
    pub nc: usize,
    /// `Ĉ = G D S`, row-major `nc × p`, unit rows.
    pub c: Vec<f64>,
    /// Right-hand side of the normalised rows.
    pub r: Vec<f64>,
    /// A feasible point on the free generators alone (minimum norm, zero elsewhere): the
    /// configuration as it is satisfies its closure. Scaled, length `p`.
    pub start: Vec<f64>,
    /// The factors of every generator's constraint columns with every row (`reduce_rows`'s,
    /// when it kept all the rows): the definiteness check and the first branch's rows factor
    /// the same matrix (the same bits) and take them from here.
    pub(super) all_qr: Option<PivotedQr>,
}

/// Buffers of the face solves.
#[derive(Default)]
pub(crate) struct FaceWork {
    qr: PivotedQr,
    kt: Vec<f64>,
    h: Vec<f64>,
    factor: Vec<f64>,
    rhs: Vec<f64>,
    /// Scratch of the solves: `Qᵀ b̂_S`, the reduced right-hand side, the gradient, the rows'
    /// multipliers, the unit vector of [`FaceWork::null_weight`].
    g: Vec<f64>,
    z: Vec<f64>,
    grad: Vec<f64>,
    mu_rows: Vec<f64>,
    unit: Vec<f64>,
    /// Face solution `ŷ_S`, in the order of the set.
    pub y: Vec<f64>,
    /// Multipliers of the rows used (length `nc`, zero for rows not used).
    pub mu: Vec<f64>,
}

impl FaceWork {
    /// Length of the projection of `e_idx` on the null space of the last face's constraint
    /// columns: zero when generator `idx` of the face cannot move without breaking the
    /// constraints (its column is independent of the others'), so that its exact step is zero.
    pub fn null_weight(&mut self, idx: usize) -> f64 {
        let k = self.y.len();
        let mut e = std::mem::take(&mut self.unit);
        e.clear();
        e.resize(k, 0.0);
        e[idx] = 1.0;
        self.qr.apply_qt(&mut e);
        let w = e[self.qr.rank..].iter().map(|x| x * x).sum::<f64>().sqrt();
        self.unit = e;
        w
    }
}

/// What a face solve found besides `ŷ_S` and `μ` (left in [`FaceWork`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FaceInfo {
    /// `f(ŷ) = ½ ŷᵀÂŷ − b̂ᵀŷ`.
    pub objective: f64,
    /// Rank of the face's constraint columns.
    pub rank: usize,
    /// Condition estimate of the reduced matrix.
    pub condition: f64,
}

fn not_pd(detail: impl Into<String>) -> RockingError {
    RockingError::new(ErrorKind::NotPositiveDefinite, detail)
}

impl ConstrainedProblem {
    /// Builds the scaled problem from the row-major `m × m` mass matrix, the right-hand side
    /// `rhs` (`b = Dᵀ rhs`), the row-major `nc × m` constraint matrix `g` and its right-hand side
    /// `g_rhs` (length `nc`).
    ///
    /// Fails with [`ErrorKind::NotPositiveDefinite`] when `DᵀMD` has a negative diagonal entry or
    /// is not positive definite on the null space of the constraints, and with
    /// [`ErrorKind::InconsistentState`] when the free generators (the open DOFs, which the model
    /// keeps) cannot satisfy the constraints: the configuration as given does not close.
    ///
    /// Built in the memory of `work`: the storage of the last problem given back by
    /// [`ConstrainedWork::recycle`] and the buffers of the checks (the same problem as in new
    /// memory).
    #[allow(clippy::too_many_arguments)]
    pub fn new_in(
        gens: Vec<Generator>,
        mass: &[f64],
        m: usize,
        rhs: &[f64],
        g: &[f64],
        nc: usize,
        g_rhs: &[f64],
        tolerance: f64,
        work: &mut ConstrainedWork,
    ) -> Result<ConstrainedProblem, RockingError> {
        let p = gens.len();
        let spare = &mut work.spare;
        let mut a = std::mem::take(&mut spare.a);
        a.clear();
        a.resize(p * p, 0.0);
        let mut b = std::mem::take(&mut spare.b);
        b.clear();
        b.resize(p, 0.0);
        let cg = &mut work.kt;
        cg.clear();
        cg.resize(nc * p, 0.0);
        for i in 0..p {
            let ti = gens[i].terms();
            for j in i..p {
                let tj = gens[j].terms();
                let s = if let ([(di, ci)], [(dj, cj)]) = (ti, tj) {
                    // One term each (unit generators): the loop's single `0.0 + c_i c_j M`.
                    0.0 + ci * cj * mass[di * m + dj]
                } else {
                    let mut s = 0.0;
                    for &(di, ci) in ti {
                        for &(dj, cj) in tj {
                            s += ci * cj * mass[di * m + dj];
                        }
                    }
                    s
                };
                a[i * p + j] = s;
                a[j * p + i] = s;
            }
            // A unit generator's sums have one term: `−0.0 + x` is `x` to the bit (a zero
            // keeps its sign), so the term is taken as it is.
            if let [(d, c)] = *ti {
                b[i] = c * rhs[d];
                for row in 0..nc {
                    cg[row * p + i] = c * g[row * m + d];
                }
            } else {
                b[i] = ti.iter().map(|&(d, c)| c * rhs[d]).sum();
                for row in 0..nc {
                    cg[row * p + i] = ti.iter().map(|&(d, c)| c * g[row * m + d]).sum();
                }
            }
        }
        let dmax = (0..p).fold(0.0_f64, |acc, i| acc.max(a[i * p + i]));
        if p > 0 && (dmax.is_nan() || dmax <= 0.0) {
            return Err(not_pd("no DOF of the configuration carries mass"));
        }
        let mut scale = std::mem::take(&mut spare.scale);
        scale.clear();
        scale.resize(p, 0.0);
        for i in 0..p {
            let d = a[i * p + i];
            if d.is_nan() || d < -MASSLESS * dmax {
                return Err(not_pd(format!(
                    "diagonal entry of a configuration's mass matrix is {d}"
                )));
            }
            scale[i] = if d > MASSLESS * dmax {
                1.0 / d.sqrt()
            } else {
                1.0 / dmax.sqrt()
            };
        }
        for i in 0..p {
            let massive = a[i * p + i] > MASSLESS * dmax;
            for j in 0..p {
                a[i * p + j] *= scale[i] * scale[j];
            }
            if massive {
                a[i * p + i] = 1.0;
            }
            b[i] *= scale[i];
            for row in 0..nc {
                cg[row * p + i] *= scale[i];
            }
        }
        // Normalise the rows; a row that touches no generator must have a zero right-hand side.
        let mut rows = std::mem::take(&mut spare.c);
        rows.clear();
        rows.reserve(nc * p);
        let mut rr = std::mem::take(&mut spare.r);
        rr.clear();
        for row in 0..nc {
            let norm = cg[row * p..(row + 1) * p]
                .iter()
                .map(|x| x * x)
                .sum::<f64>()
                .sqrt();
            if norm > 0.0 {
                rows.extend(cg[row * p..(row + 1) * p].iter().map(|x| x / norm));
                rr.push(g_rhs[row] / norm);
            } else if g_rhs[row] != 0.0 {
                return Err(RockingError::new(
                    ErrorKind::InconsistentState,
                    format!(
                        "constraint row {row} is zero on every DOF the model may use but its \
                         right-hand side is {}",
                        g_rhs[row]
                    ),
                ));
            }
        }
        let bmax = b.iter().fold(0.0_f64, |acc, v| acc.max(v.abs()));
        let (mut groups, mut singles) = (
            std::mem::take(&mut spare.groups),
            std::mem::take(&mut spare.singles),
        );
        groups_into(&gens, &mut spare.members, &mut groups);
        singles_into(&gens, &mut singles);
        let cone = ConeProblem {
            groups,
            singles,
            gens,
            a,
            b,
            scale,
            threshold: tolerance * bmax,
            tolerance,
        };
        let mut start = std::mem::take(&mut spare.start);
        start.clear();
        start.resize(p, 0.0);
        let mut problem = ConstrainedProblem {
            cone,
            nc: rr.len(),
            c: rows,
            r: rr,
            start,
            all_qr: None,
        };
        problem.reduce_rows(work)?;
        problem.find_start(work)?;
        // The gradient scale of a problem with a non-zero right-hand side includes Â ŷ₀.
        let mut grad_scale = bmax;
        for i in 0..p {
            let row = &problem.cone.a[i * p..(i + 1) * p];
            let v: f64 = row.iter().zip(&problem.start).map(|(x, y)| x * y).sum();
            grad_scale = grad_scale.max(v.abs());
        }
        problem.cone.threshold = tolerance * grad_scale;
        // Positive definiteness on the null space of all constraint columns: every face's
        // reduced matrix is a principal part of it.
        let (all, rows_all) = (&mut work.all, &mut work.rows);
        all.clear();
        all.extend(0..p);
        rows_all.clear();
        rows_all.extend(0..problem.nc);
        // Only the factor's success is needed here (the face solve's first half, the same
        // operations: the same verdict to the bit).
        problem.factor_face(all, rows_all, &mut work.face)?;
        Ok(problem)
    }

    /// Number of generators.
    pub fn p(&self) -> usize {
        self.cone.p()
    }

    /// Keeps a linearly independent subset of the constraint rows; a dependent row's right-hand
    /// side must be the same combination of the others'.
    fn reduce_rows(&mut self, work: &mut ConstrainedWork) -> Result<(), RockingError> {
        let (p, nc) = (self.p(), self.nc);
        if nc == 0 {
            return Ok(());
        }
        let kt = &mut work.kt;
        kt.clear();
        kt.resize(p * nc, 0.0);
        for i in 0..p {
            for row in 0..nc {
                kt[i * nc + row] = self.c[row * p + i];
            }
        }
        // The factors of every row, kept by the problem when they are all independent.
        let mut qr = std::mem::take(&mut work.spare.all_qr);
        qr.factor(kt, p, nc, RANK_TOLERANCE);
        let u = &mut work.u;
        u.clear();
        u.resize(p, 0.0);
        let residual = qr.solve_range(&self.r, u);
        if residual > CONSISTENCY * (1.0 + self.rmax()) {
            work.spare.all_qr = qr;
            return Err(RockingError::new(
                ErrorKind::InconsistentState,
                format!(
                    "the constraint rows are linearly dependent but their right-hand sides are \
                     not (residual {residual:e})"
                ),
            ));
        }
        if qr.rank == nc {
            self.all_qr = Some(qr);
        } else {
            let keep = &qr.perm[..qr.rank];
            let c = &mut work.kt;
            c.clear();
            c.reserve(keep.len() * p);
            for &row in keep {
                c.extend_from_slice(&self.c[row * p..(row + 1) * p]);
            }
            std::mem::swap(&mut self.c, c);
            let r = &mut work.rhs;
            r.clear();
            r.extend(keep.iter().map(|&row| self.r[row]));
            std::mem::swap(&mut self.r, r);
            self.nc = keep.len();
            work.spare.all_qr = qr;
        }
        Ok(())
    }

    fn rmax(&self) -> f64 {
        self.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
    }

    /// The stored factors of every generator's columns with every row, when `set` is every
    /// generator in order and `rows` every row in order (the matrix they were computed from).
    fn all_factors(&self, set: &[usize], rows: &[usize]) -> Option<&PivotedQr> {
        let identity =
            |v: &[usize], n: usize| v.len() == n && v.iter().enumerate().all(|(i, &x)| i == x);
        self.all_qr
            .as_ref()
            .filter(|_| identity(set, self.p()) && identity(rows, self.nc))
    }

    /// The minimum-norm point of the free generators that satisfies the constraints.
    fn find_start(&mut self, work: &mut ConstrainedWork) -> Result<(), RockingError> {
        let free = &mut work.all;
        free.clear();
        free.extend((0..self.p()).filter(|&i| !self.cone.gens[i].bounded));
        let rows = &mut work.rows;
        rows.clear();
        rows.extend(0..self.nc);
        let u = &mut work.u;
        u.clear();
        u.resize(free.len(), 0.0);
        let residual = self.particular(free, rows, &mut work.qr, u, (&mut work.kt, &mut work.rhs));
        if residual > CONSISTENCY * (1.0 + self.rmax()) {
            return Err(RockingError::new(
                ErrorKind::InconsistentState,
                format!(
                    "the open DOFs cannot satisfy the constraints G x = r (residual {residual:e}): \
                     the configuration as given does not close"
                ),
            ));
        }
        for (&i, &v) in free.iter().zip(u.iter()) {
            self.start[i] = v;
        }
        Ok(())
    }

    /// Minimum-norm solution `u` (length `set.len()`) of `Ĉ_{rows,set} ŷ = r_rows`, and the
    /// residual of the equations the face cannot satisfy.
    /// `kt` and `rhs` are scratch.
    pub fn particular(
        &self,
        set: &[usize],
        rows: &[usize],
        qr: &mut PivotedQr,
        u: &mut [f64],
        (kt, rhs): (&mut Vec<f64>, &mut Vec<f64>),
    ) -> f64 {
        let (k, c, p) = (set.len(), rows.len(), self.p());
        if let Some(all) = self.all_factors(set, rows) {
            qr.clone_from(all);
        } else {
            kt.clear();
            kt.reserve(k * c);
            for &s in set {
                kt.extend(rows.iter().map(|&row| self.c[row * p + s]));
            }
            qr.factor(kt, k, c, RANK_TOLERANCE);
        }
        rhs.clear();
        rhs.extend(rows.iter().map(|&row| self.r[row]));
        u.iter_mut().for_each(|x| *x = 0.0);
        let residual = qr.solve_range(rhs, u);
        qr.apply_q(u);
        residual
    }

    /// The first half of a face solve: the QR factors of the face's constraint columns, the
    /// particular solution `u` in `ws.y[..rank]`, the reduced matrix `QᵀÂ_SS Q` in `ws.h` and
    /// the Cholesky factor of its null-space block in `ws.factor`. `Ok(None)` when the face
    /// cannot satisfy the constraints; the not-positive-definite error when the factor fails.
    fn factor_face(
        &self,
        set: &[usize],
        rows: &[usize],
        ws: &mut FaceWork,
    ) -> Result<Option<usize>, RockingError> {
        let (k, p) = (set.len(), self.p());
        let c = rows.len();
        if let Some(all) = self.all_factors(set, rows) {
            ws.qr.clone_from(all);
        } else {
            ws.kt.clear();
            ws.kt.reserve(k * c);
            for &s in set {
                ws.kt.extend(rows.iter().map(|&row| self.c[row * p + s]));
            }
            ws.qr.factor(&mut ws.kt, k, c, RANK_TOLERANCE);
        }
        let rank = ws.qr.rank;
        ws.rhs.clear();
        ws.rhs.extend(rows.iter().map(|&row| self.r[row]));
        ws.y.clear();
        ws.y.resize(k, 0.0);
        let residual = ws.qr.solve_range(&ws.rhs, &mut ws.y);
        let rscale = rows
            .iter()
            .fold(0.0_f64, |a, &row| a.max(self.r[row].abs()));
        if residual > CONSISTENCY * (1.0 + rscale) {
            return Ok(None);
        }
        // Reduced problem in u = Qᵀ y: H = Qᵀ Â_SS Q.
        ws.h.clear();
        ws.h.reserve(k * k);
        for &r in set {
            ws.h.extend(set.iter().map(|&s| self.cone.a[r * p + s]));
        }
        ws.qr.congruence(&mut ws.h);
        let free = k - rank;
        ws.factor.clear();
        ws.factor.reserve(free * free);
        for i in rank..k {
            ws.factor
                .extend_from_slice(&ws.h[i * k + rank..(i + 1) * k]);
        }
        if free > 0 && !cholesky::factor(&mut ws.factor, free) {
            return Err(not_pd(
                "the mass matrix of a configuration is not positive definite on the null \
                 space of the constraints",
            ));
        }
        Ok(Some(rank))
    }

    /// Solves the face `set` with the constraint rows `rows`: `ŷ_S` into `ws.y`, `μ` into
    /// `ws.mu`. `None` when the face cannot satisfy the constraints.
    pub fn solve_face(
        &self,
        set: &[usize],
        rows: &[usize],
        ws: &mut FaceWork,
    ) -> Result<Option<FaceInfo>, RockingError> {
        let Some(rank) = self.factor_face(set, rows, ws)? else {
            return Ok(None);
        };
        let (k, c, p) = (set.len(), rows.len(), self.p());
        let free = k - rank;
        let mut g = std::mem::take(&mut ws.g);
        g.clear();
        g.extend(set.iter().map(|&s| self.cone.b[s]));
        ws.qr.apply_qt(&mut g);
        let mut z = std::mem::take(&mut ws.z);
        z.clear();
        z.extend(
            (rank..k).map(|i| g[i] - (0..rank).map(|j| ws.h[i * k + j] * ws.y[j]).sum::<f64>()),
        );
        ws.g = g;
        let mut condition = 1.0;
        if free > 0 {
            cholesky::solve(&ws.factor, free, &mut z);
            condition = cholesky::condition_estimate(&ws.factor, free);
        }
        ws.y[rank..].copy_from_slice(&z);
        ws.z = z;
        ws.qr.apply_q(&mut ws.y);
        // Objective and multipliers: Kᵀ μ = b̂_S − Â_SS ŷ.
        let mut grad = std::mem::take(&mut ws.grad);
        grad.clear();
        grad.resize(k, 0.0);
        let mut quad = 0.0;
        let mut lin = 0.0;
        for (i, &r) in set.iter().enumerate() {
            let ay: f64 = set
                .iter()
                .zip(&ws.y)
                .map(|(&s, y)| self.cone.a[r * p + s] * y)
                .sum();
            quad += ws.y[i] * ay;
            lin += self.cone.b[r] * ws.y[i];
            grad[i] = self.cone.b[r] - ay;
        }
        ws.qr.apply_qt(&mut grad);
        let mut mu_rows = std::mem::take(&mut ws.mu_rows);
        mu_rows.clear();
        mu_rows.resize(c, 0.0);
        ws.qr.multipliers(&grad, &mut mu_rows);
        ws.grad = grad;
        ws.mu.clear();
        ws.mu.resize(self.nc, 0.0);
        for (&row, &v) in rows.iter().zip(&mu_rows) {
            ws.mu[row] = v;
        }
        ws.mu_rows = mu_rows;
        Ok(Some(FaceInfo {
            objective: 0.5 * quad - lin,
            rank,
            condition,
        }))
    }

    /// Gradients `b̂_j − (Â ŷ)_j − (Ĉᵀ μ)_j` of every generator `j` at the point `y` (length `p`,
    /// non-zero only on `set`) with the multipliers `mu` (length `nc`), into `out` (length `p`):
    /// `(Â ŷ)_j` summed over `set` in its order from −0.0 and `(Ĉᵀ μ)_j` over the rows in
    /// order, as `sum()` — `Â` is symmetric to the bit (built mirrored, each entry scaled by the
    /// product of its two scales), so row `s` of it holds column `s`, and the sums of all `j`
    /// run along rows.
    /// `cm` is scratch.
    pub fn gradients(
        &self,
        set: &[usize],
        y: &[f64],
        mu: &[f64],
        out: &mut Vec<f64>,
        cm: &mut Vec<f64>,
    ) {
        let p = self.p();
        let mut ay = std::mem::take(out);
        ay.clear();
        ay.resize(p, -0.0);
        for &s in set {
            let ys = y[s];
            for (acc, a) in ay.iter_mut().zip(&self.cone.a[s * p..(s + 1) * p]) {
                *acc += a * ys;
            }
        }
        cm.clear();
        cm.resize(p, -0.0);
        for (r, &m) in mu.iter().enumerate().take(self.nc) {
            for (acc, c) in cm.iter_mut().zip(&self.c[r * p..(r + 1) * p]) {
                *acc += c * m;
            }
        }
        for ((g, &b), &c) in ay.iter_mut().zip(&self.cone.b).zip(cm.iter()) {
            *g = b - *g - c;
        }
        *out = ay;
    }
}
