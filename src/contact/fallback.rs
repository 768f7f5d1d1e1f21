//! The fallbacks of the contact problem's active set method ([`super::friction`]), both
//! deterministic and bounded: Lemke's algorithm on the standard LCP of 2D Coulomb friction
//! (Stewart & Trinkle 1996; Anitescu & Potra 1997), exact up to round-off; and when round-off
//! breaks Lemke's path (near-degenerate problems, a column almost at rest), the nonsmooth
//! Gauss–Seidel iteration of non-smooth contact dynamics (Jean 1999; Acary & Brogliato 2008,
//! §13.4.5), joint by joint with exact local solves, to a relative change of `1e-12` or at most
//! 20 000 sweeps.

use super::blocks::by_size;
use super::friction::{larger, ContactProblem, JointStatus, Slip, SolveFailure, SolveReport, B3};

/// A variable of the LCP.
#[derive(Clone, Copy, Debug)]
enum Var {
    /// Normal impulse at an end, with a sign (a bilateral end has two parts).
    Normal(usize, usize, f64),
    /// A signed part of the tangential impulse.
    Tangent(usize, f64),
    /// The slip speed `β` of Coulomb's law (multiplier of the cone).
    Beta(usize),
}

impl ContactProblem {
    /// Statuses read off a solution (for the next warm start).
    fn statuses_from_impulses(&self, statuses: &mut [JointStatus]) {
        for k in 0..self.n {
            let jc = self.joints[k];
            let p = self.p[k];
            let mut st = JointStatus::default();
            for c in 0..2 {
                st.closed[c] = jc.active[c] && (jc.bilateral[c] || p[c] > 0.0);
            }
            if jc.mu > 0.0 && jc.mu.is_finite() {
                let normal = p[0] + p[1];
                if normal > 0.0 && p[2].abs() >= jc.mu * normal * (1.0 - 1e-9) {
                    st.slip = if p[2] > 0.0 {
                        Slip::Negative
                    } else {
                        Slip::Positive
                    };
                }
            }
            statuses[k] = st;
        }
    }

    /// Block `(k, l)` of `W` (zero beyond the neighbours).
    fn block(&self, k: usize, l: usize) -> Option<B3> {
        if k == l {
            Some(self.wd[k])
        } else if l == k + 1 {
            Some(self.wo[k])
        } else if k == l + 1 {
            let o = &self.wo[l];
            let mut t = [[0.0; 3]; 3];
            for a in 0..3 {
                for c in 0..3 {
                    t[a][c] = o[c][a];
                }
            }
            Some(t)
        } else {
            None
        }
    }

    /// Lemke's algorithm on the LCP of the whole problem: per joint the active ends' normal
    /// impulses (a bilateral end as two signed parts), the tangential impulse as `T⁺ − T⁻` and
    /// the slip speed `β`: `w_{T±} = β ± U_t`, `w_β = μ N − T⁺ − T⁻` (μ = ∞: `U_t = 0`, `T` free).
    pub(super) fn solve_lemke(&mut self, statuses: &mut [JointStatus]) -> Result<(), SolveFailure> {
        let n = self.n;
        let mut vars: Vec<Var> = Vec::new();
        for k in 0..n {
            let jc = self.joints[k];
            for c in 0..2 {
                if jc.active[c] {
                    vars.push(Var::Normal(k, c, 1.0));
                    if jc.bilateral[c] {
                        vars.push(Var::Normal(k, c, -1.0));
                    }
                }
            }
            if (jc.active[0] || jc.active[1]) && jc.mu > 0.0 {
                vars.push(Var::Tangent(k, 1.0));
                vars.push(Var::Tangent(k, -1.0));
                if jc.mu.is_finite() {
                    vars.push(Var::Beta(k));
                }
            }
        }
        let m = vars.len();
        // Impulse (P_R, P_L, T) of a unit of a variable.
        let unit = |v: Var| -> (usize, [f64; 3]) {
            match v {
                Var::Normal(k, c, s) => {
                    let mut p = [0.0; 3];
                    p[c] = s;
                    (k, p)
                }
                Var::Tangent(k, s) => (k, [0.0, 0.0, s]),
                Var::Beta(k) => (k, [0.0; 3]),
            }
        };
        let mut mat = vec![0.0; m * m];
        let mut q = vec![0.0; m];
        for (i, &vi) in vars.iter().enumerate() {
            let (ki, ri) = unit(vi);
            if let Var::Beta(k) = vi {
                let mu = self.joints[k].mu;
                for (j, &vj) in vars.iter().enumerate() {
                    match vj {
                        Var::Normal(kj, _, s) if kj == k => mat[i * m + j] = mu * s,
                        Var::Tangent(kj, _) if kj == k => mat[i * m + j] = -1.0,
                        _ => {}
                    }
                }
                continue;
            }
            for (j, &vj) in vars.iter().enumerate() {
                if let Var::Beta(kb) = vj {
                    if matches!(vi, Var::Tangent(_, _)) && kb == ki {
                        mat[i * m + j] = 1.0;
                    }
                    continue;
                }
                let (kj, rj) = unit(vj);
                if let Some(w) = self.block(ki, kj) {
                    let mut acc = 0.0;
                    for a in 0..3 {
                        if ri[a] != 0.0 {
                            for c in 0..3 {
                                acc += ri[a] * w[a][c] * rj[c];
                            }
                        }
                    }
                    mat[i * m + j] = acc;
                }
            }
            q[i] = (0..3).map(|a| ri[a] * self.b[ki][a]).sum();
        }
        let z = self.lemke.solve(&mat, &q, m).ok_or(SolveFailure)?;
        for p in self.p.iter_mut() {
            *p = [0.0; 3];
        }
        for (i, &vi) in vars.iter().enumerate() {
            let (k, r) = unit(vi);
            for a in 0..3 {
                self.p[k][a] += r[a] * z[i];
            }
        }
        self.update_rates();
        self.statuses_from_impulses(statuses);
        Ok(())
    }

    /// The last impulses of the active set method made admissible (normal impulses of
    /// unilateral ends at least zero, inactive ends' zero, the tangential one within the cone):
    /// the start of [`Self::sweeps_then_active_set`] where it cycled.
    pub(super) fn clip_impulses(&mut self) {
        for k in 0..self.n {
            let jc = self.joints[k];
            let mut p = self.p[k];
            for c in 0..2 {
                if !jc.active[c] {
                    p[c] = 0.0;
                } else if !jc.bilateral[c] {
                    p[c] = p[c].max(0.0);
                }
            }
            if !(jc.active[0] || jc.active[1]) || jc.mu == 0.0 {
                p[2] = 0.0;
            } else if jc.mu.is_finite() {
                let bound = jc.mu * (p[0] + p[1]).max(0.0);
                p[2] = p[2].clamp(-bound, bound);
            }
            if !p.iter().all(|x| x.is_finite()) {
                p = [0.0; 3];
            }
            self.p[k] = p;
        }
    }

    /// The fallback tried first where the active set method cycles (with `sweep_fallback`):
    /// rounds of nonsmooth Gauss–Seidel sweeps from the impulses in `p` (of `rounds[0]`
    /// sweeps, then `rounds[1]` more, ...), each followed by the active set method started from
    /// the statuses of the sweeps' impulses. `true` when one of those ends with statuses that
    /// satisfy the conditions (the active set method's own test, its tolerances): the solution
    /// the other fallbacks would reach, to round-off, where it is unique. Otherwise `p` is left
    /// with the sweeps' impulses.
    pub(super) fn sweeps_then_active_set(
        &mut self,
        statuses: &mut [JointStatus],
        tol_u: f64,
        p_floor: f64,
        report: &mut SolveReport,
        rounds: &[usize],
    ) -> bool {
        let mut sweep = 0;
        for &round in rounds {
            for _ in 0..round {
                let (change, size) = self.gauss_seidel_sweep(sweep, true);
                sweep += 1;
                if change <= 1e-12 * size || size == 0.0 {
                    break;
                }
            }
            let mut saved = std::mem::take(&mut self.gs_saved);
            saved.clear();
            saved.extend_from_slice(&self.p[..self.n]);
            self.statuses_from_impulses(statuses);
            if self.active_set_from(statuses, tol_u, p_floor, 12, report) {
                self.gs_saved = saved;
                return true;
            }
            self.p[..self.n].copy_from_slice(&saved);
            self.gs_saved = saved;
        }
        false
    }

    /// One symmetric half sweep (bottom up for even `sweep`, top down for odd) of the
    /// nonsmooth Gauss–Seidel iteration: the largest change of an impulse and the largest
    /// impulse.
    fn gauss_seidel_sweep(&mut self, sweep: usize, warm: bool) -> (f64, f64) {
        let n = self.n;
        let mut change = 0.0_f64;
        let mut size = 0.0_f64;
        for i in 0..n {
            let k = if sweep % 2 == 0 { i } else { n - 1 - i };
            let old = self.p[k];
            let Some(new) = self.local_solve(k, warm) else {
                continue;
            };
            self.p[k] = new;
            for a in 0..3 {
                // Absolute values: `larger` is `max` here (see there).
                change = larger(change, (new[a] - old[a]).abs());
                size = larger(size, new[a].abs());
            }
        }
        (change, size)
    }

    /// The nonsmooth Gauss–Seidel iteration: each joint's local problem (its 3 × 3 block, the
    /// neighbours' impulses fixed) solved exactly by trying its statuses in a fixed order;
    /// symmetric sweeps (bottom up, then top down) until the impulses change by less than `1e-12`
    /// of their size, or 20 000 sweeps: then the last iterate is the answer (`Ok(false)`).
    pub(super) fn solve_gauss_seidel(
        &mut self,
        statuses: &mut [JointStatus],
    ) -> Result<bool, SolveFailure> {
        for p in self.p.iter_mut() {
            *p = [0.0; 3];
        }
        let mut converged = false;
        for sweep in 0..20_000 {
            let (change, size) = self.gauss_seidel_sweep(sweep, self.sweep_fallback);
            if change <= 1e-12 * size || size == 0.0 {
                converged = true;
                break;
            }
        }
        if !converged && !self.p.iter().flatten().all(|x| x.is_finite()) {
            return Err(SolveFailure);
        }
        self.update_rates();
        self.statuses_from_impulses(statuses);
        Ok(converged)
    }

    /// Exact solution of joint `k`'s local problem with its neighbours' impulses fixed: the first
    /// status (in a fixed order) whose solution satisfies the conditions, else the least violating.
    /// With `warm`, the status of the joint's current impulses is tried first (the sweeps of
    /// [`Self::sweeps_then_active_set`], where it rarely changes from one sweep to the next).
    fn local_solve(&self, k: usize, warm: bool) -> Option<[f64; 3]> {
        let n = self.n;
        let jc = self.joints[k];
        if !(jc.active[0] || jc.active[1]) {
            return Some([0.0; 3]);
        }
        let mut r = self.b[k];
        if k + 1 < n {
            let pn = self.p[k + 1];
            for a in 0..3 {
                for c in 0..3 {
                    r[a] += self.wo[k][a][c] * pn[c];
                }
            }
        }
        if k > 0 {
            let pp = self.p[k - 1];
            for a in 0..3 {
                for c in 0..3 {
                    r[a] += self.wo[k - 1][c][a] * pp[c];
                }
            }
        }
        let friction = jc.mu > 0.0;
        let scale_u = r
            .iter()
            .fold(0.0_f64, |m, x| larger(m, x.abs()))
            .max(1e-300);
        if warm {
            let p = self.p[k];
            let pattern = [
                jc.active[0] && (jc.bilateral[0] || p[0] > 0.0),
                jc.active[1] && (jc.bilateral[1] || p[1] > 0.0),
            ];
            let normal = p[0] + p[1];
            let sigma = if !((pattern[0] || pattern[1]) && friction) {
                f64::NAN
            } else if jc.mu.is_finite()
                && normal > 0.0
                && p[2].abs() >= jc.mu * normal * (1.0 - 1e-9)
            {
                if p[2] > 0.0 {
                    -1.0
                } else {
                    1.0
                }
            } else {
                0.0
            };
            if let Some((p, viol)) = self.local_try(k, &r, scale_u, pattern, sigma) {
                if viol <= 1e-12 {
                    return Some(p);
                }
            }
        }
        let mut best: Option<([f64; 3], f64)> = None;
        for pattern in [[true, true], [true, false], [false, true], [false, false]] {
            if (pattern[0] && !jc.active[0]) || (pattern[1] && !jc.active[1]) {
                continue;
            }
            if (jc.bilateral[0] && !pattern[0]) || (jc.bilateral[1] && !pattern[1]) {
                continue;
            }
            let any = pattern[0] || pattern[1];
            let slips: &[f64] = if any && friction {
                if jc.mu.is_finite() {
                    &[0.0, 1.0, -1.0]
                } else {
                    &[0.0]
                }
            } else {
                &[f64::NAN]
            };
            for &sigma in slips {
                let Some((p, viol)) = self.local_try(k, &r, scale_u, pattern, sigma) else {
                    continue;
                };
                if viol <= 1e-12 {
                    return Some(p);
                }
                if best.map_or(true, |(_, v)| viol < v) {
                    best = Some((p, viol));
                }
            }
        }
        best.map(|(p, _)| p)
    }

    /// Joint `k`'s local solution for the closed ends `pattern` and the slip `sigma` (`0`
    /// stick, `±1` slipping with `U_t` of that sign, NaN no tangential unknown), its neighbours'
    /// impulses in `r`: the impulses and their largest relative violation of the conditions;
    /// `None` when the local system is singular.
    #[inline(always)]
    fn local_try(
        &self,
        k: usize,
        r: &[f64; 3],
        scale_u: f64,
        pattern: [bool; 2],
        sigma: f64,
    ) -> Option<([f64; 3], f64)> {
        let jc = self.joints[k];
        let wl = &self.wd[k];
        let friction = jc.mu > 0.0;
        let any = pattern[0] || pattern[1];
        let stick = sigma == 0.0;
        let slide = !stick && !sigma.is_nan();
        let mut idx = [0usize; 3];
        let mut m = 0;
        for c in 0..2 {
            if pattern[c] {
                idx[m] = c;
                m += 1;
            }
        }
        if stick {
            idx[m] = 2;
            m += 1;
        }
        let mut a = [[0.0; 3]; 3];
        let mut rhs = [0.0; 3];
        for (ii, &row) in idx[..m].iter().enumerate() {
            rhs[ii] = -r[row];
            for (jj, &col) in idx[..m].iter().enumerate() {
                a[ii][jj] = wl[row][col];
                if slide && col < 2 {
                    a[ii][jj] += wl[row][2] * (-sigma * jc.mu);
                }
            }
        }
        let x = solve_small(&a, &rhs, m)?;
        let mut p = [0.0; 3];
        for (ii, &col) in idx[..m].iter().enumerate() {
            p[col] = x[ii];
        }
        if slide {
            p[2] = -sigma * jc.mu * (p[0] + p[1]);
        }
        let mut u = *r;
        for i in 0..3 {
            for j in 0..3 {
                u[i] += wl[i][j] * p[j];
            }
        }
        let pscale = p
            .iter()
            .fold(0.0_f64, |m, x| larger(m, x.abs()))
            .max(1e-300);
        let mut viol = 0.0_f64;
        for c in 0..2 {
            if !jc.active[c] || jc.bilateral[c] {
                continue;
            }
            if pattern[c] {
                viol = viol.max(-p[c] / pscale);
            } else {
                viol = viol.max(-u[c] / scale_u);
            }
        }
        if any && friction && jc.mu.is_finite() {
            if stick {
                viol = viol.max((p[2].abs() - jc.mu * (p[0] + p[1])) / pscale);
            } else {
                viol = viol.max(-sigma * u[2] / scale_u);
            }
        }
        Some((p, viol))
    }
}

/// Solves the leading `m × m` system by Gaussian elimination with partial pivoting; `None` when
/// singular (`m = 0` gives the empty solution).
fn solve_small(a: &B3, b: &[f64; 3], m: usize) -> Option<[f64; 3]> {
    by_size!(solve_sized, m, (a, b))
}

/// [`solve_small`] with the size `M` a constant (the same operations; see [`super::blocks`]).
#[inline(always)]
fn solve_sized<const M: usize>(a: &B3, b: &[f64; 3]) -> Option<[f64; 3]> {
    let m = M;
    let mut a = *a;
    let mut b = *b;
    for c in 0..m {
        let mut p = c;
        for r in c + 1..m {
            if a[r][c].abs() > a[p][c].abs() {
                p = r;
            }
        }
        if a[p][c] == 0.0 || !a[p][c].is_finite() {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..m {
            let f = a[r][c] / a[c][c];
            for j in c..m {
                a[r][j] -= f * a[c][j];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 3];
    for i in (0..m).rev() {
        let mut s = b[i];
        for j in i + 1..m {
            s -= a[i][j] * x[j];
        }
        x[i] = s / a[i][i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::super::friction::{ContactProblem, JointStatus, SolveReport};
    use super::super::moreau::{SchemeOptions, Stepper};
    use crate::ground::excitation::Excitation;
    use crate::ground::records::read_at2;
    use crate::model::column::{Block, Column};

    /// The tolerances `solve` takes for a problem as set.
    fn tolerances(pr: &ContactProblem) -> (f64, f64) {
        let mut scale_u = 0.0_f64;
        let mut wmax = 0.0_f64;
        for k in 0..pr.n {
            for a in 0..3 {
                scale_u = scale_u.max(pr.b[k][a].abs());
                wmax = wmax.max(pr.wd[k][a][a]);
            }
        }
        let p_floor = if wmax > 0.0 { scale_u / wmax } else { 0.0 };
        (1e-10 * scale_u.max(1e-300), p_floor)
    }

    /// The sweeps and the active set method from their statuses (the fallback of
    /// `energy_consistent`) reach Lemke's solution, to round-off, on the problems of a
    /// chattering twenty-drum column (its steps', impacts' and projections' problems), started
    /// from zero impulses.
    #[test]
    fn sweeps_reach_lemkes_solution() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let rec = read_at2(&dir.join("examples/records/synthetic.AT2")).unwrap();
        let motion = Excitation::record(rec.scaled_to_pga(4.0).unwrap()).unwrap();
        let n = 20;
        let column = Column::new(vec![Block::rectangle(1.0, 2.0, 5000.0); n]).unwrap();
        let options = SchemeOptions {
            energy_consistent: true,
            ..SchemeOptions::default()
        };
        let mut st = Stepper::new(&column, vec![0.7; n], options);
        let (mut compared, mut not_reached, mut largest) = (0, 0, 0.0_f64);
        for i in 0..8000 {
            if st.step(1e-3, &motion).is_err() {
                break;
            }
            if i % 4 != 0 {
                continue;
            }
            for base in [&st.problem, &st.projection] {
                let (mut a, mut b) = (base.clone(), base.clone());
                let mut sa = vec![JointStatus::default(); n];
                let mut sb = vec![JointStatus::default(); n];
                if a.solve_lemke(&mut sa).is_err() {
                    continue;
                }
                b.p.iter_mut().for_each(|p| *p = [0.0; 3]);
                let (tol_u, p_floor) = tolerances(&b);
                let mut report = SolveReport::default();
                let rounds = [8, 32, 128, 512, 2048];
                if !b.sweeps_then_active_set(&mut sb, tol_u, p_floor, &mut report, &rounds) {
                    not_reached += 1;
                    continue;
                }
                let scale = a.p.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
                if scale == 0.0 {
                    continue;
                }
                for k in 0..n {
                    for c in 0..3 {
                        let d = (a.p[k][c] - b.p[k][c]).abs() / scale;
                        largest = largest.max(d);
                        assert!(
                            d <= 1e-8,
                            "step {i}, joint {k}: {:?} against {:?}",
                            a.p[k],
                            b.p[k]
                        );
                    }
                }
                compared += 1;
            }
        }
        println!(
            "{compared} problems, largest difference {largest:.1e} of the largest impulse; \
             {not_reached} not reached by the sweeps"
        );
        assert!(compared >= 1000, "{compared} problems compared");
    }
}
