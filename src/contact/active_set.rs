//! The primal-dual active set method on the joint-wise contact problem of [`super::friction`]:
//! with the statuses fixed, the reduced linear system (block tridiagonal, one block LU from the
//! lowest changed joint), the rates it gives, and the update of the statuses (damped: only
//! violations of at least half the largest; of a run of neighbours calling for the same change
//! only the lowest; after a cycle one joint at a time, Murty's least-index rule), then the
//! fallbacks (Lemke, nonsmooth Gauss–Seidel).

use super::blocks::{back, by_size, by_sizes, coupling, impulses, pivot};
use super::friction::{
    dot3, larger, ContactProblem, JointStatus, Reduction, Slip, SolveFailure, SolveReport,
    MAX_ITERATIONS,
};

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
            // Not short-circuiting: the same answer as `p.iter().all(|x| x.is_finite())`.
            finite &= p[0].is_finite() & p[1].is_finite() & p[2].is_finite();
            ps[k] = p;
        }
        self.update_free_rates();
        finite
    }

    /// `u = W p + b`.
    pub(super) fn update_rates(&mut self) {
        for k in 0..self.n {
            self.u[k] = self.joint_rates(k);
        }
    }

    /// `u = W p + b` of joint `k` (its row of blocks: the same operations in the same order
    /// whichever of the loops below computes it).
    #[inline(always)]
    fn joint_rates(&self, k: usize) -> [f64; 3] {
        let n = self.n;
        let (wd, wo, b, ps) = (&self.wd[..n], &self.wo[..n], &self.b[..n], &self.p[..n]);
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
        u
    }

    /// [`Self::update_rates`] on the joints whose reduction (the last linear solve's) leaves a
    /// row free: the status test reads a joint's rates only on its free rows (an open end's
    /// normal, a slipping joint's tangent), and a joint closed at both ends and sticking has
    /// none. The others' rates are computed by [`Self::complete_rates`] once the statuses hold
    /// (the same numbers: the impulses do not change in between).
    fn update_free_rates(&mut self) {
        for k in 0..self.n {
            if self.red[k].size < 3 {
                self.u[k] = self.joint_rates(k);
            }
        }
    }

    /// The rates [`Self::update_free_rates`] left out.
    fn complete_rates(&mut self) {
        for k in 0..self.n {
            if self.red[k].size == 3 {
                self.u[k] = self.joint_rates(k);
            }
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
    // The holding tests are the negations of the change tests (`!(x < −tol)`, not `x ≥ −tol`):
    // a NaN calls for no change in either.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn update_statuses(
        &mut self,
        statuses: &mut [JointStatus],
        tol_u: f64,
        tol_p: f64,
        single: bool,
    ) -> Option<usize> {
        let (u_ref, p_ref) = (tol_u * 1e10, tol_p * 1e10);
        let mut worst = 0.0_f64;
        let n = self.n;
        // Slices of length `n`: the indices below need no checks.
        let (joints, ps, us) = (&self.joints[..n], &self.p[..n], &self.u[..n]);
        let (nexts, viols) = (&mut self.next[..n], &mut self.viol[..n]);
        let statuses = &mut statuses[..n];
        for k in 0..n {
            let jc = &joints[k];
            let st = statuses[k];
            let p = ps[k];
            let u = us[k];
            // First whether the joint's status holds (most joints, in most iterations): the
            // tests below, without the sizes of the violations, which would leave `next == st`
            // and no violation (and `worst` as it is: it is never below zero).
            let end_holds = |c: usize| {
                if !jc.active[c] {
                    !st.closed[c]
                } else if jc.bilateral[c] {
                    st.closed[c]
                } else if st.closed[c] {
                    !(p[c] < -tol_p)
                } else {
                    !(u[c] < -tol_u)
                }
            };
            if end_holds(0) && end_holds(1) {
                let any_closed = (jc.active[0] && st.closed[0]) || (jc.active[1] && st.closed[1]);
                let slip_holds = if any_closed && jc.slips {
                    match st.slip {
                        Slip::Stick => {
                            let bound = jc.mu * (p[0] + p[1]).max(0.0);
                            !(p[2].abs() > bound + tol_p)
                        }
                        slip => !(slip.sign() * u[2] < -tol_u),
                    }
                } else {
                    true
                };
                if slip_holds && ((any_closed && !jc.sticks) || st.slip == Slip::Stick) {
                    nexts[k] = st;
                    viols[k] = 0.0;
                    continue;
                }
            }
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
            if any_closed && jc.slips {
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
            if !any_next || jc.sticks {
                next.slip = Slip::Stick;
            }
            if next == st {
                viol = 0.0;
            } else {
                // A change with no measured violation (bookkeeping of inactive ends) is taken.
                viol = larger(viol, f64::MIN_POSITIVE);
            }
            nexts[k] = next;
            viols[k] = viol;
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
                None => {
                    self.complete_rates();
                    return true;
                }
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
            // The law classified once for the status tests.
            let mu = self.joints[k].mu;
            self.joints[k].slips = mu > 0.0 && mu.is_finite();
            self.joints[k].sticks = mu == 0.0 || mu.is_infinite();
            let jc = self.joints[k];
            for c in 0..2 {
                if !jc.active[c] {
                    statuses[k].closed[c] = false;
                } else if jc.bilateral[c] {
                    statuses[k].closed[c] = true;
                }
            }
            if jc.sticks {
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
                None => {
                    self.complete_rates();
                    return Ok(report);
                }
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
