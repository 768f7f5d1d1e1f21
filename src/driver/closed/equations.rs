//! The equations of motion of an open mechanism of a loop (SPEC §9): the open DOFs `F` of the cut
//! chain with the closure kept at acceleration level,
//! `[M_FF G_Fᵀ; G_F 0] [a; μ] = [q_F + f_F; −Ġ v]` (`f`: the exact velocity terms), geometry
//! recomputed at every evaluation; and the classical RK4 step on the open DOFs.

use crate::chain::{Chain, ChainPose};
use crate::model::configuration::Status;

/// The constrained equations of a loop's open DOFs, with scratch for one evaluation.
#[derive(Clone, Debug)]
pub struct LoopEquations<'a> {
    chain: &'a Chain,
    gravity: f64,
    phi: Vec<f64>,
    rates: Vec<f64>,
    kkt: Vec<f64>,
    rhs: Vec<f64>,
    pose: ChainPose,
    scratch: Vec<[f64; 2]>,
    screen: Vec<f64>,
    /// The open DOFs' joints and pivots in the pose (`Chain::dof_pivot`).
    pivots: Vec<(usize, [f64; 2])>,
    /// The last evaluation at the start of a step or of a screen (its open DOFs, `a_g`, `x`,
    /// `v` and accelerations): the next step's first stage, and a located closing's first
    /// stage, evaluate the same arguments again (the function is pure: the same bits).
    memo: Memo,
    /// The RK4 stages' vectors.
    stages: Vec<Vec<f64>>,
}

#[derive(Clone, Debug, Default)]
struct Memo {
    valid: bool,
    open: Vec<usize>,
    ag: u64,
    x: Vec<f64>,
    v: Vec<f64>,
    out: Vec<f64>,
}

fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

impl Memo {
    fn matches(&self, open: &[usize], ag: f64, x: &[f64], v: &[f64]) -> bool {
        self.valid
            && self.open == open
            && self.ag == ag.to_bits()
            && same_bits(&self.x, x)
            && same_bits(&self.v, v)
    }

    fn store(&mut self, open: &[usize], ag: f64, x: &[f64], v: &[f64], out: &[f64]) {
        self.valid = true;
        self.open.clear();
        self.open.extend_from_slice(open);
        self.ag = ag.to_bits();
        self.x.clear();
        self.x.extend_from_slice(x);
        self.v.clear();
        self.v.extend_from_slice(v);
        self.out.clear();
        self.out.extend_from_slice(out);
    }
}

impl<'a> LoopEquations<'a> {
    /// The equations of `chain` under `gravity` (m/s², positive).
    pub fn new(chain: &'a Chain, gravity: f64) -> LoopEquations<'a> {
        let m = chain.n_dofs();
        LoopEquations {
            chain,
            gravity,
            phi: vec![0.0; m],
            rates: vec![0.0; m],
            kkt: Vec::new(),
            rhs: Vec::new(),
            pose: ChainPose::default(),
            scratch: Vec::new(),
            screen: Vec::new(),
            pivots: Vec::new(),
            memo: Memo::default(),
            stages: Vec::new(),
        }
    }

    /// The chain.
    pub fn chain(&self) -> &'a Chain {
        self.chain
    }

    /// Accelerations `out` of the open DOFs `open` (reduced angles `x` and rates `v`, all of
    /// length `open.len()`) under the ground acceleration `ag` (m/s², +x). Returns `false` when
    /// the KKT system is singular (no motion compatible with the closure, or `M` not positive
    /// definite on the null space of `G_F`).
    pub fn accelerations(
        &mut self,
        open: &[usize],
        ag: f64,
        x: &[f64],
        v: &[f64],
        out: &mut [f64],
    ) -> bool {
        self.phi.iter_mut().for_each(|p| *p = 0.0);
        self.rates.iter_mut().for_each(|p| *p = 0.0);
        for (i, &d) in open.iter().enumerate() {
            self.phi[d] = x[i];
            self.rates[d] = v[i];
        }
        // Only the open DOFs' entries are built (the same formulas as the full matrices, so the
        // system is the same to the bit): `M_FF`, `q_F`, `f_F`, `G_F` and `Ġ v`.
        self.chain.pose_into(&self.phi, &mut self.pose);
        let pose = &self.pose;
        // The velocity terms' suffix sums; the entries of the open DOFs from them (a closed
        // DOF's, for the screen, in `current_holds`).
        self.chain
            .velocity_load_sums(pose, &self.phi, &self.rates, &mut self.scratch);
        let gdot = self.chain.closure_rate_of(pose, &self.rates);
        let nf = open.len();
        let k = nf + 3;
        // Every entry but the zero `3 × 3` block is written below (`M_FF` whole, `G_F` and its
        // transpose), so only that block is cleared, not the whole matrix.
        self.kkt.resize(k * k, 0.0);
        for r in nf..k {
            self.kkt[r * k + nf..(r + 1) * k].fill(0.0);
        }
        self.rhs.clear();
        self.rhs.resize(k, 0.0);
        self.pivots.clear();
        self.pivots
            .extend(open.iter().map(|&d| self.chain.dof_pivot(pose, d)));
        let (a, b, piv) = (&mut self.kkt, &mut self.rhs, &self.pivots);
        self.chain.mass_block_into(pose, piv, a, k);
        for (i, &di) in open.iter().enumerate() {
            let p = piv[i].1;
            for (r, g) in [1.0, p[1], -p[0]].into_iter().enumerate() {
                a[i * k + nf + r] = g;
                a[(nf + r) * k + i] = g;
            }
            b[i] = self.chain.load_entry(pose, di, ag, self.gravity)
                + self.chain.velocity_load_entry(pose, &self.scratch, di);
        }
        for r in 0..3 {
            b[nf + r] = -gdot[r];
        }
        if !solve_in_place(a, b) {
            return false;
        }
        out[..nf].copy_from_slice(&b[..nf]);
        true
    }

    /// The screen of the opening model (`LoopOptions::screen`, docs/arch-performance.md): whether the
    /// configuration `statuses` (open DOFs `open`, reduced angles `x` and rates `v`) under the
    /// ground acceleration `ag` is the opening model's own answer. With `a` and `μ` the
    /// mechanism's constrained accelerations and closure multipliers (the KKT system of
    /// [`LoopEquations::accelerations`]), the model's optimality conditions at "nothing new
    /// opens" are those of a closed DOF `d` (`s_d a_d ≥ 0`, `s_d` its admissible sign):
    /// `ν_d = s_d ((M a)_d − q_d − f_d + (Gᵀμ)_d) ≥ 0`, its contact multiplier; the open DOFs
    /// are free. The relaxed problem (either corner of a closed joint) is convex with a unique
    /// optimum (`M` positive definite on the null space of the closure), so when every
    /// `ν_d > margin × scale` (`scale` the largest of the three terms over the closed DOFs) the
    /// optimum opens nothing and the model keeps the configuration. `false` when any is not
    /// (or the system is singular): the model must be asked.
    pub fn current_holds(
        &mut self,
        statuses: &[Status],
        open: &[usize],
        ag: f64,
        x: &[f64],
        v: &[f64],
        margin: f64,
    ) -> bool {
        let nf = open.len();
        let mut a = std::mem::take(&mut self.screen);
        a.clear();
        a.resize(nf, 0.0);
        let ok = self.accelerations(open, ag, x, v, &mut a);
        if ok {
            self.memo.store(open, ag, x, v, &a);
        }
        let holds = ok && {
            let n = statuses.len();
            let mu = [self.rhs[nf], self.rhs[nf + 1], self.rhs[nf + 2]];
            let pose = &self.pose;
            let (mut worst, mut scale) = (f64::INFINITY, 0.0_f64);
            for k in (0..n).filter(|&k| !statuses[k].is_open()) {
                for (d, sign) in [(k, -1.0), (n + k, 1.0)] {
                    let pd = self.chain.dof_pivot(pose, d);
                    let ma: f64 = self
                        .pivots
                        .iter()
                        .zip(&a)
                        .map(|(&pj, &aj)| self.chain.mass_entry_of(pose, pd, pj) * aj)
                        .sum();
                    let load = self.chain.load_entry(pose, d, ag, self.gravity)
                        + self.chain.velocity_load_entry(pose, &self.scratch, d);
                    let p = self.chain.pivot(pose, d);
                    let gmu = mu[0] + p[1] * mu[1] - p[0] * mu[2];
                    worst = worst.min(sign * (ma - load + gmu));
                    scale = scale.max(ma.abs()).max(load.abs()).max(gmu.abs());
                }
            }
            worst > margin * scale
        };
        self.screen = a;
        holds
    }

    /// [`LoopEquations::accelerations`] through the memo of the last first stage.
    fn first_stage(
        &mut self,
        open: &[usize],
        ag: f64,
        x: &[f64],
        v: &[f64],
        out: &mut [f64],
    ) -> bool {
        if self.memo.matches(open, ag, x, v) {
            out.copy_from_slice(&self.memo.out);
            return true;
        }
        let ok = self.accelerations(open, ag, x, v, out);
        if ok {
            self.memo.store(open, ag, x, v, out);
        }
        ok
    }

    /// One classical RK4 step of length `dt` from `(x, v)` at time `t` under `ag(t)`: the state
    /// at `t + dt` in `(x1, v1)`. Returns `false` if an evaluation failed
    /// ([`LoopEquations::accelerations`]).
    #[allow(clippy::too_many_arguments)]
    pub fn rk4_step(
        &mut self,
        open: &[usize],
        ag: &dyn Fn(f64) -> f64,
        t: f64,
        dt: f64,
        x: &[f64],
        v: &[f64],
        x1: &mut [f64],
        v1: &mut [f64],
    ) -> bool {
        let n = open.len();
        let axpy = |out: &mut Vec<f64>, a: &[f64], b: &[f64], h: f64| {
            out.clear();
            out.extend(a.iter().zip(b).map(|(a, b)| a + h * b));
        };
        let mut st = std::mem::take(&mut self.stages);
        st.resize(9, Vec::new());
        let [k1a, k2a, k3a, k4a, k2x, k3x, k4x, xs, ..] = &mut st[..] else {
            unreachable!()
        };
        for k in [&mut *k1a, &mut *k2a, &mut *k3a, &mut *k4a] {
            k.clear();
            k.resize(n, 0.0);
        }
        let k1x = v;
        let ok1 = self.first_stage(open, ag(t), x, v, k1a);
        axpy(k2x, v, k1a, dt / 2.0);
        axpy(xs, x, k1x, dt / 2.0);
        let ok2 = self.accelerations(open, ag(t + dt / 2.0), xs, k2x, k2a);
        axpy(k3x, v, k2a, dt / 2.0);
        axpy(xs, x, k2x, dt / 2.0);
        let ok3 = self.accelerations(open, ag(t + dt / 2.0), xs, k3x, k3a);
        axpy(k4x, v, k3a, dt);
        axpy(xs, x, k3x, dt);
        let ok4 = self.accelerations(open, ag(t + dt), xs, k4x, k4a);
        for i in 0..n {
            x1[i] = x[i] + dt / 6.0 * (k1x[i] + 2.0 * k2x[i] + 2.0 * k3x[i] + k4x[i]);
            v1[i] = v[i] + dt / 6.0 * (k1a[i] + 2.0 * k2a[i] + 2.0 * k3a[i] + k4a[i]);
        }
        self.stages = st;
        ok1 && ok2 && ok3 && ok4
    }
}

/// Solves the dense `a x = b` in place (`b` becomes `x`, `a` is left as scratch) by Gaussian
/// elimination with partial pivoting; `false` if a pivot is zero or the result is not finite.
///
/// The pivot is the last row of largest `|a_ic|` (`total_cmp`, as `Iterator::max_by`). Only the
/// entries right of the pivot column are swapped and updated: those left of it and below the
/// diagonal are never read again (the multiplier is taken before), so the factors and the
/// solution are those of the full update to the bit.
pub(super) fn solve_in_place(a: &mut [f64], b: &mut [f64]) -> bool {
    // The driver's systems (`|F| + 3` unknowns) in rows of a fixed length: the same operations.
    match b.len() {
        4 => solve_fixed::<4>(a, b),
        5 => solve_fixed::<5>(a, b),
        6 => solve_fixed::<6>(a, b),
        7 => solve_fixed::<7>(a, b),
        8 => solve_fixed::<8>(a, b),
        9 => solve_fixed::<9>(a, b),
        10 => solve_fixed::<10>(a, b),
        11 => solve_fixed::<11>(a, b),
        12 => solve_fixed::<12>(a, b),
        13 => solve_fixed::<13>(a, b),
        14 => solve_fixed::<14>(a, b),
        15 => solve_fixed::<15>(a, b),
        16 => solve_fixed::<16>(a, b),
        _ => solve_any(a, b),
    }
}

/// [`solve_in_place`] for `N` unknowns. Each row below the pivot is updated over its whole
/// length `N` (a loop of known length, without the short loop's overhead): the entries right of
/// the pivot column get the one multiplication and subtraction of [`solve_any`] (the same bits);
/// those at or left of it are never read again (the multiplier is taken before the update; later
/// pivot searches, updates and the back substitution read only columns right of theirs), so
/// what they hold does not matter.
fn solve_fixed<const N: usize>(a: &mut [f64], b: &mut [f64]) -> bool {
    debug_assert!(a.len() == N * N && b.len() == N);
    // The matrix as rows of known length (a copy on the stack; `a` is scratch to the callers).
    let mut rows = [[0.0_f64; N]; N];
    for (row, src) in rows.iter_mut().zip(a.chunks_exact(N)) {
        row.copy_from_slice(src);
    }
    let b = &mut b[..N];
    for col in 0..N {
        let mut piv = col;
        let mut best = rows[col][col].abs();
        for (i, row) in rows.iter().enumerate().skip(col + 1) {
            let v = row[col].abs();
            if v.total_cmp(&best) != std::cmp::Ordering::Less {
                piv = i;
                best = v;
            }
        }
        if rows[piv][col] == 0.0 {
            return false;
        }
        if piv != col {
            rows.swap(col, piv);
            b.swap(col, piv);
        }
        let (top, bottom) = rows.split_at_mut(col + 1);
        let prow = &top[col];
        let d = prow[col];
        let bc = b[col];
        for (row, br) in bottom.iter_mut().zip(&mut b[col + 1..]) {
            let f = row[col] / d;
            for j in 0..N {
                row[j] -= f * prow[j];
            }
            *br -= f * bc;
        }
    }
    for r in (0..N).rev() {
        let s: f64 = (r + 1..N).map(|k| rows[r][k] * b[k]).sum();
        b[r] = (b[r] - s) / rows[r][r];
    }
    b.iter().all(|x| x.is_finite())
}

/// [`solve_in_place`] for any size.
fn solve_any(a: &mut [f64], b: &mut [f64]) -> bool {
    let n = b.len();
    debug_assert_eq!(a.len(), n * n);
    for col in 0..n {
        let mut piv = col;
        let mut best = a[col * n + col].abs();
        for i in col + 1..n {
            let v = a[i * n + col].abs();
            if v.total_cmp(&best) != std::cmp::Ordering::Less {
                piv = i;
                best = v;
            }
        }
        if a[piv * n + col] == 0.0 {
            return false;
        }
        if piv != col {
            let (top, bottom) = a.split_at_mut(piv * n);
            top[col * n + col..(col + 1) * n].swap_with_slice(&mut bottom[col..n]);
            b.swap(col, piv);
        }
        let (top, bottom) = a.split_at_mut((col + 1) * n);
        let len = n - col - 1;
        let d = top[col * n + col];
        let prow = &top[col * n + col + 1..][..len];
        let bc = b[col];
        for (row, br) in bottom.chunks_exact_mut(n).zip(&mut b[col + 1..]) {
            let f = row[col] / d;
            let tail = &mut row[col + 1..][..len];
            for j in 0..len {
                tail[j] -= f * prow[j];
            }
            *br -= f * bc;
        }
    }
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r * n + k] * b[k]).sum();
        b[r] = (b[r] - s) / a[r * n + r];
    }
    b.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fixed-size elimination is the general one bit for bit: random systems of 4–16
    /// unknowns, symmetric KKT-like ones with a zero block, ties in the pivot column and a
    /// singular one.
    #[test]
    fn fixed_sizes_are_the_general_solve_bit_for_bit() {
        let mut uniform = crate::test_support::uniform(0x9e37_79b9_7f4a_7c15_u64);
        let mut next = move || uniform() - 0.5;
        for case in 0..600 {
            let n = 4 + case % 13;
            let mut a: Vec<f64> = (0..n * n).map(|_| next()).collect();
            match case % 4 {
                1 => {
                    // Symmetric with a trailing 3 × 3 zero block (a loop's KKT system).
                    for i in 0..n {
                        for j in 0..i {
                            a[i * n + j] = a[j * n + i];
                        }
                    }
                    for i in n - 3..n {
                        for j in n - 3..n {
                            a[i * n + j] = 0.0;
                        }
                    }
                }
                2 => (0..n).for_each(|i| a[i * n] = if i % 2 == 0 { 0.5 } else { -0.5 }),
                3 if case % 8 == 3 => (0..n).for_each(|i| a[i * n + 1] = 2.0 * a[i * n]),
                _ => {}
            }
            let b: Vec<f64> = (0..n).map(|_| next()).collect();
            let (mut a1, mut b1) = (a.clone(), b.clone());
            let (mut a2, mut b2) = (a, b);
            let ok1 = solve_in_place(&mut a1, &mut b1);
            let ok2 = solve_any(&mut a2, &mut b2);
            assert_eq!(ok1, ok2, "case {case}");
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            if ok1 {
                assert_eq!(bits(&b1), bits(&b2), "case {case}");
            }
        }
    }
}
