//! The primal-dual active set method on the joint-wise contact problem of [`super::friction`]:
//! with the statuses fixed, the reduced linear system (block tridiagonal, one block LU from the
//! lowest changed joint), the rates it gives, and the update of the statuses (damped: only
//! violations of at least half the largest; of a run of neighbours calling for the same change
//! only the lowest; after a cycle one joint at a time, Murty's least-index rule), then the
//! fallbacks (Lemke, nonsmooth Gauss–Seidel).

use super::blocks::{back, by_size, by_sizes, coupling, impulses, pivot};
use super::friction::{
    dot3, ContactProblem, JointStatus, Reduction, Slip, SolveFailure, SolveReport, MAX_ITERATIONS,
};

/// `x` if it is larger than `m`, else `m`: [`f64::max`] for the running maxima below, whose `m`
/// is never NaN and whose values are never negative zeros (absolute values, positive violations,
/// and the Delassus diagonal, only compared with zero), without its NaN handling (a NaN `x` is
/// skipped by both).
#[inline(always)]
fn larger(m: f64, x: f64) -> f64 {
    if x > m {
        x
    } else {
        m
    }
}

impl ContactProblem {
    /// The reduction of joint `k` for status `st`.
    pub(super) fn reduce(&self, k: usize, st: &JointStatus) -> Reduction {
        let jc = &self.joints[k];
        let mut red = Reduction::default();
        let mut r = 0;
        for c in 0..2 {
            if jc.active[c] && st.closed[c] {
                red.rows[r] = c;
                red.cols[r][c] = 1.0;
                r += 1;
            }
        }
        let nclosed = r;
        if nclosed > 0 && jc.mu > 0.0 {
            match st.slip {
                Slip::Stick => {
                    red.rows[r] = 2;
                    red.cols[r][2] = 1.0;
                    r += 1;
                }
                slip => {
                    let f = -slip.sign() * jc.mu;
                    for i in 0..nclosed {
                        red.cols[i][2] = f;
                    }
                }
            }
        }
        red.size = r;
        red
    }

    /// One linear solve for the statuses; fills `p` and `u`. `false` if singular. Joints below
    /// `from` have the statuses of the previous solve: their reductions and eliminated blocks are
    /// kept (the coupling of joint `from − 1` with joint `from` is redone). The block kernels
    /// take the joints' sizes as constants ([`super::blocks`]).
    fn linear_solve(&mut self, statuses: &[JointStatus], from: usize) -> bool {
        let n = self.n;
        if n == 0 {
            return true;
        }
        for k in from..n {
            self.red[k] = self.reduce(k, &statuses[k]);
        }
        // Slices of length `n`: the indices below need no checks.
        let (red, wo, wd, b) = (&self.red[..n], &self.wo[..n], &self.wd[..n], &self.b[..n]);
        let (cp, dp, dinvs) = (&mut self.cp[..n], &mut self.dp[..n], &mut self.dinv[..n]);
        if from > 0 {
            let k = from - 1;
            let (rk, rn) = (&red[k], &red[from]);
            let (wo, dinv) = (&wo[k], &dinvs[k]);
            cp[k] = by_sizes!(coupling, rk.size, rn.size, (rk, rn, wo, dinv));
        }
        // Forward elimination.
        for k in from..n {
            let rk = &red[k];
            let m = rk.size;
            if m == 0 {
                dp[k] = [0.0; 3];
                cp[k] = [[0.0; 3]; 3];
                continue;
            }
            let (rp, wo_prev, cprev, dprev, p) = if k > 0 {
                let rp = &red[k - 1];
                (rp, &wo[k - 1], &cp[k - 1], &dp[k - 1], rp.size)
            } else {
                (rk, &wo[k], &cp[k], &dp[k], 0)
            };
            let (wd, b) = (&wd[k], &b[k]);
            let pivot = by_sizes!(pivot, m, p, (rk, rp, wd, b, wo_prev, cprev, dprev));
            let Some((dinv, y)) = pivot else {
                return false;
            };
            dinvs[k] = dinv;
            dp[k] = y;
            if k + 1 < n {
                let rn = &red[k + 1];
                let wo = &wo[k];
                cp[k] = by_sizes!(coupling, m, rn.size, (rk, rn, wo, &dinv));
            }
        }
        // Back substitution.
        let z = &mut self.z[..n];
        z[n - 1] = dp[n - 1];
        for k in (0..n - 1).rev() {
            let (m, rn) = (red[k].size, red[k + 1].size);
            let (dp, cp, zn) = (&dp[k], &cp[k], &z[k + 1]);
            z[k] = by_sizes!(back, m, rn, (dp, cp, zn));
        }
        let mut finite = true;
        let ps = &mut self.p[..n];
        for k in 0..n {
            let red = &red[k];
            let p = by_size!(impulses, red.size, (red, &z[k]));
            finite &= p.iter().all(|x| x.is_finite());
            ps[k] = p;
        }
        self.update_rates();
        finite
    }

    /// `u = W p + b`.
    pub(super) fn update_rates(&mut self) {
        let n = self.n;
        let (wd, wo, b, ps) = (&self.wd[..n], &self.wo[..n], &self.b[..n], &self.p[..n]);
        let us = &mut self.u[..n];
        for k in 0..n {
            let mut u = b[k];
            let p = ps[k];
            for a in 0..3 {
                u[a] += dot3(&wd[k][a], &p);
            }
            if k + 1 < n {
                let pn = ps[k + 1];
                for a in 0..3 {
                    u[a] += dot3(&wo[k][a], &pn);
                }
            }
            if k > 0 {
                let pp = ps[k - 1];
                let o = &wo[k - 1];
                for a in 0..3 {
                    u[a] += o[0][a] * pp[0] + o[1][a] * pp[1] + o[2][a] * pp[2];
                }
            }
            us[k] = u;
        }
    }

    /// Status update of the active set method; returns the lowest joint whose status changed.
    /// Each joint's next status and the size of the violation that calls for it (relative to the
    /// problem's velocity or impulse scale) are found first; then the violated joints change
    /// whose violation is at least half the largest, the lowest of each run of neighbours calling
    /// for the same change (a damped primal-dual active set step: in a stack, a wrong status at
    /// one joint puts spurious tension on the joints around it, and opening them all makes the
    /// closures come back one joint per iteration); with `single`, only the lowest violated
    /// joint. On the 20-drum suite columns this takes a third fewer iterations and half the
    /// fallbacks of changing every violated joint at once.
    fn update_statuses(
        &mut self,
        statuses: &mut [JointStatus],
        tol_u: f64,
        tol_p: f64,
        single: bool,
    ) -> Option<usize> {
        let (u_ref, p_ref) = (tol_u * 1e10, tol_p * 1e10);
        let mut worst = 0.0_f64;
        for k in 0..self.n {
            let jc = &self.joints[k];
            let st = statuses[k];
            let p = self.p[k];
            let u = self.u[k];
            let mut next = st;
            let mut viol = 0.0_f64;
            for c in 0..2 {
                if !jc.active[c] {
                    next.closed[c] = false;
                } else if jc.bilateral[c] {
                    next.closed[c] = true;
                } else if st.closed[c] {
                    if p[c] < -tol_p {
                        next.closed[c] = false;
                        viol = larger(viol, -p[c] / p_ref);
                    }
                } else if u[c] < -tol_u {
                    next.closed[c] = true;
                    viol = larger(viol, -u[c] / u_ref);
                }
            }
            let any_closed = (jc.active[0] && st.closed[0]) || (jc.active[1] && st.closed[1]);
            if any_closed && jc.mu > 0.0 && jc.mu.is_finite() {
                let bound = jc.mu * (p[0] + p[1]).max(0.0);
                match st.slip {
                    Slip::Stick => {
                        if p[2].abs() > bound + tol_p {
                            next.slip = if p[2] > 0.0 {
                                Slip::Negative
                            } else {
                                Slip::Positive
                            };
                            viol = larger(viol, (p[2].abs() - bound) / p_ref);
                        }
                    }
                    slip => {
                        let s = slip.sign();
                        if s * u[2] < -tol_u {
                            // Reversed: stick, or slip the other way if it reverses strongly
                            // (Alart–Curnier's augmented test with ρ = 1 / W_tt).
                            let wtt = self.wd[k][2][2];
                            let rho = if wtt > 0.0 { 1.0 / wtt } else { 0.0 };
                            next.slip = if -s * u[2] * rho > 2.0 * bound {
                                if s > 0.0 {
                                    Slip::Negative
                                } else {
                                    Slip::Positive
                                }
                            } else {
                                Slip::Stick
                            };
                            viol = larger(viol, -s * u[2] / u_ref);
                        }
                    }
                }
            }
            let any_next = (jc.active[0] && next.closed[0]) || (jc.active[1] && next.closed[1]);
            if !any_next || jc.mu == 0.0 || jc.mu.is_infinite() {
                next.slip = Slip::Stick;
            }
            if next == st {
                viol = 0.0;
            } else {
                // A change with no measured violation (bookkeeping of inactive ends) is taken.
                viol = larger(viol, f64::MIN_POSITIVE);
            }
            self.next[k] = next;
            self.viol[k] = viol;
            worst = larger(worst, viol);
        }
        if worst == 0.0 {
            return None;
        }
        let mut changed: Option<usize> = None;
        // Of a run of neighbouring joints calling for the same change (same status before and
        // after), only the lowest changes: the others' violations are usually the echo of its
        // wrong status (in a stack, a joint that should open puts tension on its neighbours).
        let mut run: Option<(JointStatus, JointStatus)> = None;
        for k in 0..self.n {
            let v = self.viol[k];
            if v == 0.0 {
                run = None;
                continue;
            }
            let kind = (statuses[k], self.next[k]);
            let echo = run == Some(kind);
            run = Some(kind);
            if !single && (v < 0.5 * worst || echo) {
                continue;
            }
            statuses[k] = self.next[k];
            if changed.is_none() {
                changed = Some(k);
                if single {
                    break;
                }
            }
        }
        if changed.is_none() {
            // Every violation was held back: take the largest.
            let mut k_max = 0;
            for k in 0..self.n {
                if self.viol[k] > self.viol[k_max] {
                    k_max = k;
                }
            }
            statuses[k_max] = self.next[k_max];
            changed = Some(k_max);
        }
        changed
    }

    /// One active set solve from `statuses` (no least-index stage): `true` if it ends with
    /// statuses that satisfy the conditions within `max_iterations` solves and without a cycle.
    pub(super) fn active_set_from(
        &mut self,
        statuses: &mut [JointStatus],
        tol_u: f64,
        p_floor: f64,
        max_iterations: usize,
        report: &mut SolveReport,
    ) -> bool {
        self.history.clear();
        let mut from = 0;
        for _ in 0..max_iterations {
            report.iterations += 1;
            if !self.linear_solve(statuses, from) {
                return false;
            }
            let tol_p = self.impulse_tolerance(p_floor);
            match self.update_statuses(statuses, tol_u, tol_p, false) {
                None => return true,
                Some(k) => from = k,
            }
            let sig = Self::signature(statuses);
            if self.history.contains(&sig) {
                return false;
            }
            self.history.push(sig);
        }
        false
    }

    /// The impulse tolerance of the status test: `1e-10` of the largest impulse, or of `p_floor`
    /// when every impulse is below it.
    fn impulse_tolerance(&self, p_floor: f64) -> f64 {
        let mut scale_p = 0.0_f64;
        for p in &self.p {
            for x in p {
                scale_p = larger(scale_p, x.abs());
            }
        }
        1e-10 * scale_p.max(p_floor).max(1e-300)
    }

    fn signature(statuses: &[JointStatus]) -> u64 {
        // FNV-1a over the status codes: deterministic, no allocation.
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for s in statuses {
            let code = (s.closed[0] as u64) | (s.closed[1] as u64) << 1 | (s.slip as u64) << 2;
            h ^= code;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
        h
    }

    /// Solves the problem set by [`ContactProblem::set`], starting from `statuses` (the previous
    /// step's: a warm start) and leaving the solution's statuses there. The impulses are then
    /// read with [`ContactProblem::impulses`], the velocities with [`ContactProblem::apply`].
    pub fn solve(&mut self, statuses: &mut [JointStatus]) -> Result<SolveReport, SolveFailure> {
        let n = self.n;
        // Statuses of inactive ends are open; bilateral ends closed.
        for k in 0..n {
            let jc = self.joints[k];
            for c in 0..2 {
                if !jc.active[c] {
                    statuses[k].closed[c] = false;
                } else if jc.bilateral[c] {
                    statuses[k].closed[c] = true;
                }
            }
            if jc.mu == 0.0 || jc.mu.is_infinite() {
                statuses[k].slip = Slip::Stick;
            }
        }
        let mut scale_u = 0.0_f64;
        for k in 0..n {
            for a in 0..3 {
                scale_u = larger(scale_u, self.b[k][a].abs());
            }
        }
        let tol_u = 1e-10 * scale_u.max(1e-300);
        // The impulse that changes a velocity by `scale_u`: the floor of the impulse tolerance
        // (when every impulse is nearly zero, their own size is round-off).
        let mut wmax = 0.0_f64;
        for k in 0..n {
            for a in 0..3 {
                wmax = larger(wmax, self.wd[k][a][a]);
            }
        }
        let p_floor = if wmax > 0.0 { scale_u / wmax } else { 0.0 };
        self.history.clear();
        let mut report = SolveReport::default();
        let mut from = 0;
        // All violated statuses change at once (primal-dual active set); after a cycle, one joint
        // at a time (the lowest: a least-index rule, Murty 1974); then the fallbacks.
        let mut single = false;
        let mut single_iterations = 0;
        loop {
            report.iterations += 1;
            if single {
                single_iterations += 1;
            }
            if !self.linear_solve(statuses, from) {
                break;
            }
            let tol_p = self.impulse_tolerance(p_floor);
            match self.update_statuses(statuses, tol_u, tol_p, single) {
                None => return Ok(report),
                Some(k) => from = k,
            }
            let sig = Self::signature(statuses);
            let seen = self.history.iter().position(|&h| h == sig);
            if !single {
                if seen.is_some() || report.iterations >= MAX_ITERATIONS {
                    single = true;
                    self.history.clear();
                }
            } else if seen.is_some() || single_iterations >= 4 * n + 8 {
                break;
            }
            self.history.push(sig);
        }
        report.fallback = true;
        if self.sweep_fallback {
            self.clip_impulses();
            if self.sweeps_then_active_set(statuses, tol_u, p_floor, &mut report, &[8, 32, 128]) {
                return Ok(report);
            }
        }
        if self.solve_lemke(statuses).is_ok() {
            return Ok(report);
        }
        report.gauss_seidel = true;
        // Lemke's algorithm leaves the sweeps' impulses: go on with them.
        if self.sweep_fallback
            && self.sweeps_then_active_set(statuses, tol_u, p_floor, &mut report, &[512, 2048])
        {
            return Ok(report);
        }
        report.inexact = !self.solve_gauss_seidel(statuses)?;
        Ok(report)
    }
}
