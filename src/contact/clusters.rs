//! Opt-in condensed steps ([`super::moreau::SchemeOptions::clusters`]): drums whose joint is
//! closed at both ends, sticking and carrying both corners' impulses move together, so the step's
//! contact problem is solved over the clusters they form and the free joints only, then checked.
//!
//! **Exact in exact arithmetic.** A joint `k` closed at both ends and sticking obeys, in the step's
//! problem, `H_k v⁺ = −s_k` on its three rows (`s_k`: the persistent contacts' shift, the rates of
//! the velocities before on the midpoint rows, [`super::moreau`] step 4; `O(h)`: the turning of
//! the contact with the drums). The velocities that obey this at every condensed joint of a
//! cluster are `v = T u + w`: `T` the rigid motions of the cluster about its centre of mass at
//! the step's midpoint (annihilated by the condensed joints' rows, which are those of the same
//! midpoint), `u = (V_x, V_y, ω)`, and `w` one velocity field with those rates and no momentum
//! (nor angular momentum about the centre), so that `Tᵀ M w = 0`. Then `Tᵀ M T` is
//! `diag(M_c, M_c, I_c)` (mass, and moment of inertia about the centre, of the cluster: one body
//! of the chain's contact problem), the condensed joints' impulses do no work on `T`, and the
//! step's equations projected on `T` are the same contact problem for the clusters, with the
//! free joints' rows mapped to the clusters' centres and `H w` added to their free rates. Its
//! answer, with the condensed joints' impulses (from the cluster's drums top down:
//! `Up_jᵀ P_j = M_j (v⁺_j − v_free_j) − Low_{j+1}ᵀ P_{j+1}`), satisfies every condition of the
//! full problem if those impulses are admissible (both corners pressed, `|T| < μ N`, with a
//! margin): then it is the full step's answer up to rounding. If one is not, or the column comes
//! to rest, the sub-step is redone by the full path.
//!
//! The hook is `Stepper::substep`: the step's sub-steps and those of the located impacts are
//! condensed; the landings' prediction, location and missed-landing check, the impact problems
//! and the projection of the positions after the sub-step ([`super::projection`]) are the full
//! ones. A condensed joint's contact work is not booked: it is zero by construction
//! (`U⁺ = −s = −U⁻`).

use super::drums::ContactRows;
use super::friction::{
    dot3, invert3, ContactProblem, JointContacts, JointStatus, Slip, SolveReport, B3,
};
use super::moreau::Stepper;
use crate::ground::GroundMotion;

/// Counters of the condensed steps (not part of [`super::accounts::StepCounters`]: the default
/// scheme's outputs stay as they were).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClusterCounters {
    /// Sub-steps taken condensed (the step's, and those of the located impacts: the trial, the
    /// sub-step to the impact and the rest of the step; the impact's own problem stays full).
    pub condensed: u64,
    /// Joints condensed, summed over those sub-steps.
    pub condensed_joints: u64,
    /// Clusters (bodies of the condensed problem), summed over those sub-steps.
    pub clusters: u64,
    /// Sub-steps tried condensed and redone in full: a condensed joint's impulse not admissible
    /// (it would slip or open).
    pub broken: u64,
    /// Sub-steps tried and redone in full for another reason (the column coming to rest, a
    /// singular joint, a problem the solvers could not solve).
    pub other: u64,
    /// Sub-steps taken in full without a try (no joint to condense).
    pub full: u64,
}

/// Relative margin of the condensed joints' impulses: each corner's impulse above `MARGIN · N`,
/// the tangential one below `(1 − MARGIN) μ N`.
pub const MARGIN: f64 = 1e-6;

/// Workspace of the condensed steps.
#[derive(Clone, Debug, Default)]
pub(super) struct ClusterWork {
    problem: ContactProblem,
    contacts: Vec<JointContacts>,
    statuses: Vec<JointStatus>,
    /// First drum of each cluster (its bottom joint is free).
    first: Vec<usize>,
    /// Cluster of each drum.
    of: Vec<usize>,
    condensed: Vec<bool>,
    /// Rows of each joint for its upper and lower drum (`[nR, nL, t]`, the problem's).
    up: Vec<B3>,
    low: Vec<B3>,
    mass: Vec<f64>,
    inertia: Vec<f64>,
    centre: Vec<[f64; 2]>,
    /// Velocities `(V_x, V_y, ω)` of the clusters: free, then after the impulses.
    vc: Vec<f64>,
    /// Positions at the step's midpoint.
    qm: Vec<f64>,
    /// The drums' velocity field `w` (see the module documentation), then the new velocities.
    w: Vec<f64>,
    v_new: Vec<f64>,
    /// Impulses `(P_R, P_L, T)` of the condensed joints.
    p: Vec<[f64; 3]>,
    /// Inverse of each condensed joint's rows for its upper drum.
    inv: Vec<B3>,
    /// The drums' free velocities.
    vf: Vec<f64>,
    /// The condensed problem's report, booked with the step.
    report: SolveReport,
}

impl ClusterWork {
    pub(super) fn new(masses: &[f64], inertias: &[f64]) -> ClusterWork {
        let n = masses.len();
        ClusterWork {
            problem: ContactProblem::new(masses, inertias),
            contacts: vec![JointContacts::default(); n],
            statuses: vec![JointStatus::default(); n],
            first: Vec::with_capacity(n),
            of: vec![0; n],
            condensed: vec![false; n],
            up: vec![[[0.0; 3]; 3]; n],
            low: vec![[[0.0; 3]; 3]; n],
            mass: vec![0.0; n],
            inertia: vec![0.0; n],
            centre: vec![[0.0; 2]; n],
            vc: vec![0.0; 3 * n],
            qm: vec![0.0; 3 * n],
            w: vec![0.0; 3 * n],
            v_new: vec![0.0; 3 * n],
            p: vec![[0.0; 3]; n],
            inv: vec![[[0.0; 3]; 3]; n],
            vf: vec![0.0; 3 * n],
            report: SolveReport::default(),
        }
    }
}

/// The problem's rows of a joint (tangent: the active ends' weighted mean).
fn blocks(r: &[ContactRows; 2], w: [f64; 2]) -> (B3, B3) {
    let t = |a: [f64; 3], b: [f64; 3]| {
        [
            w[0] * a[0] + w[1] * b[0],
            w[0] * a[1] + w[1] * b[1],
            w[0] * a[2] + w[1] * b[2],
        ]
    };
    (
        [r[0].n_up, r[1].n_up, t(r[0].t_up, r[1].t_up)],
        [r[0].n_low, r[1].n_low, t(r[0].t_low, r[1].t_low)],
    )
}

/// Rates `(U_R, U_L, U_t)` of joint `k` on its rows for the drums' velocities `v`.
fn rates(up: &B3, low: &B3, v: &[f64], k: usize) -> [f64; 3] {
    let vu = [v[3 * k], v[3 * k + 1], v[3 * k + 2]];
    let mut u = [dot3(&up[0], &vu), dot3(&up[1], &vu), dot3(&up[2], &vu)];
    if k > 0 {
        let vl = [v[3 * k - 3], v[3 * k - 2], v[3 * k - 1]];
        for a in 0..3 {
            u[a] += dot3(&low[a], &vl);
        }
    }
    u
}

/// A row `[a, b, c]` of a drum whose centre is at `d` from its cluster's: the row of the cluster's
/// `(V_x, V_y, ω)` (the drum's velocity is `(V_x − ω d_y, V_y + ω d_x, ω)`).
fn moved(r: [f64; 3], d: [f64; 2]) -> [f64; 3] {
    [r[0], r[1], r[2] - r[0] * d[1] + r[1] * d[0]]
}

/// `m r` (`transpose` false) or `mᵀ r`.
fn times(m: &B3, r: [f64; 3], transpose: bool) -> [f64; 3] {
    let mut x = [0.0; 3];
    for (i, xi) in x.iter_mut().enumerate() {
        *xi = if transpose {
            m[0][i] * r[0] + m[1][i] * r[1] + m[2][i] * r[2]
        } else {
            m[i][0] * r[0] + m[i][1] * r[1] + m[i][2] * r[2]
        };
    }
    x
}

impl Stepper {
    /// Tries the sub-step of length `h` ([`Stepper::substep`], `excluded` ends kept out of its
    /// index set) condensed; `Ok(true)` if taken, `Ok(false)` if the full sub-step is to take it
    /// (the state is then as it was). A landing the prediction missed is reported as the full
    /// sub-step does (`missed_found`, the state advanced: the caller restores it).
    pub(super) fn condensed_substep(
        &mut self,
        h: f64,
        motion: &dyn GroundMotion,
        excluded: Option<&[[bool; 2]]>,
    ) -> Result<bool, super::moreau::StepError> {
        let o = self.options;
        if o.energy_consistent || !o.persistent_restitution || !o.project || self.skip_projection {
            return Ok(false);
        }
        let Some(mut cw) = self.cluster_work.take() else {
            return Ok(false);
        };
        let taken = self.cluster_substep(&mut cw, h, motion, excluded);
        self.cluster_work = Some(cw);
        taken
    }

    fn cluster_substep(
        &mut self,
        cw: &mut ClusterWork,
        h: f64,
        motion: &dyn GroundMotion,
        excluded: Option<&[[bool; 2]]>,
    ) -> Result<bool, super::moreau::StepError> {
        let n = self.drums.len();
        let theta = self.options.theta;
        let t_end = self.t + h;
        let a = motion.acceleration(self.t + theta * h);
        let a1 = motion.acceleration(t_end);
        for i in 0..3 * n {
            cw.qm[i] = self.q[i] + theta * h * self.v[i];
        }
        self.drums.joints_rows_into(&cw.qm, &mut self.predicted);
        // The index set, the rows, the persistent contacts' shifts (as the full sub-step), and
        // the joints that condense.
        let mut any = false;
        for k in 0..n {
            for c in 0..2 {
                self.flags[k][c] = self.in_index_set(k, c, h, excluded);
            }
            let act = self.flags[k];
            let w = ContactProblem::tangent_weights(act);
            let g = &self.predicted[k];
            let (up, low) = blocks(&[g.ends[0].rows, g.ends[1].rows], w);
            let ub = rates(&up, &low, &self.v, k);
            cw.up[k] = up;
            cw.low[k] = low;
            self.rates_before[k] = ub;
            let mut shift = [0.0; 3];
            let mut held = [false; 2];
            for c in 0..2 {
                if act[c] && self.carried[k][c] && ub[c] >= -self.v_touch {
                    shift[c] = ub[c];
                    held[c] = true;
                }
            }
            let st = self.statuses[k];
            if (shift[0] != 0.0 || shift[1] != 0.0) && st.slip == Slip::Stick {
                shift[2] = ub[2];
            }
            self.shifts[k] = shift;
            cw.condensed[k] = k > 0
                && held == [true, true]
                && st.closed == [true, true]
                && st.slip == Slip::Stick
                && self.mu[k] > 0.0;
            any |= cw.condensed[k];
        }
        if !any {
            self.cluster_counters.full += 1;
            return Ok(false);
        }
        let qm = std::mem::take(&mut cw.qm);
        let solved = self.condensed_solve(cw, &qm, h, a);
        cw.qm = qm;
        if !solved {
            return Ok(false);
        }
        self.rates_fresh = false;
        self.condensed_finish(cw, h, a, t_end);
        self.cluster_counters.condensed += 1;
        if self.watching {
            if let Some(tau) = self.missed_landing(h) {
                self.missed_found = Some(tau);
                return Ok(true);
            }
        }
        self.project(a1, true)?;
        self.counters.substeps += 1;
        let joints = cw.condensed.iter().filter(|&&c| c).count();
        self.cluster_counters.condensed_joints += joints as u64;
        self.cluster_counters.clusters += cw.first.len() as u64;
        Ok(true)
    }

    /// The drums' free velocity `v + h M⁻¹ f` (the full sub-step's numbers).
    fn free_velocity(&self, j: usize, a: f64, h: f64) -> [f64; 3] {
        let m = self.drums.mass(j);
        let f = [-m * a, -m * self.options.gravity, 0.0];
        let inv = self.problem.inv_mass[j];
        let v = &self.v[3 * j..3 * j + 3];
        [
            v[0] + h * inv[0] * f[0],
            v[1] + h * inv[1] * f[1],
            v[2] + h * inv[2] * f[2],
        ]
    }

    /// The clusters, their problem, solved; the new velocities and the condensed joints' impulses
    /// checked. `Ok(false)`: not admissible (counted).
    fn condensed_solve(&mut self, cw: &mut ClusterWork, qm: &[f64], h: f64, a: f64) -> bool {
        let n = self.drums.len();
        cw.first.clear();
        for j in 0..n {
            if !cw.condensed[j] {
                cw.first.push(j);
            }
            cw.of[j] = cw.first.len() - 1;
        }
        let nc = cw.first.len();
        for j in 0..n {
            let vf = self.free_velocity(j, a, h);
            cw.vf[3 * j..3 * j + 3].copy_from_slice(&vf);
        }
        for c in 0..nc {
            let (s, e) = (cw.first[c], cw.first.get(c + 1).copied().unwrap_or(n));
            if e - s == 1 {
                cw.mass[c] = self.drums.mass(s);
                cw.inertia[c] = self.drums.inertia(s);
                cw.centre[c] = [qm[3 * s], qm[3 * s + 1]];
                cw.problem.inv_mass[c] = self.problem.inv_mass[s];
                cw.vc[3 * c..3 * c + 3].copy_from_slice(&cw.vf[3 * s..3 * s + 3]);
                cw.w[3 * s..3 * s + 3].iter_mut().for_each(|x| *x = 0.0);
                continue;
            }
            let (mut m, mut sx, mut sy) = (0.0, 0.0, 0.0);
            for j in s..e {
                let mj = self.drums.mass(j);
                m += mj;
                sx += mj * qm[3 * j];
                sy += mj * qm[3 * j + 1];
            }
            let r = [sx / m, sy / m];
            let d = |j: usize| [qm[3 * j] - r[0], qm[3 * j + 1] - r[1]];
            let mut inertia = 0.0;
            for j in s..e {
                let dj = d(j);
                inertia +=
                    self.drums.inertia(j) + self.drums.mass(j) * (dj[0] * dj[0] + dj[1] * dj[1]);
            }
            cw.mass[c] = m;
            cw.inertia[c] = inertia;
            cw.centre[c] = r;
            cw.problem.inv_mass[c] = [1.0 / m, 1.0 / m, 1.0 / inertia];
            // Momentum and angular momentum (about the centre) of a velocity field of the drums.
            let momentum = |st: &Stepper, vel: &dyn Fn(usize) -> [f64; 3]| {
                let (mut px, mut py, mut l) = (0.0, 0.0, 0.0);
                for j in s..e {
                    let (mj, v, dj) = (st.drums.mass(j), vel(j), d(j));
                    px += mj * v[0];
                    py += mj * v[1];
                    l += st.drums.inertia(j) * v[2] + mj * (dj[0] * v[1] - dj[1] * v[0]);
                }
                [px / m, py / m, l / inertia]
            };
            let vfs = &cw.vf;
            let vf = momentum(self, &|j| [vfs[3 * j], vfs[3 * j + 1], vfs[3 * j + 2]]);
            cw.vc[3 * c..3 * c + 3].copy_from_slice(&vf);
            // w: the prescribed rates `−s` joint by joint from the bottom drum, then its rigid
            // part removed.
            cw.w[3 * s..3 * s + 3].iter_mut().for_each(|x| *x = 0.0);
            for j in s + 1..e {
                let sh = self.shifts[j];
                let wl = [cw.w[3 * j - 3], cw.w[3 * j - 2], cw.w[3 * j - 1]];
                let low = &cw.low[j];
                let rhs = [
                    -sh[0] - dot3(&low[0], &wl),
                    -sh[1] - dot3(&low[1], &wl),
                    -sh[2] - dot3(&low[2], &wl),
                ];
                let Some(inv) = invert3(&cw.up[j], 3) else {
                    self.cluster_counters.other += 1;
                    return false;
                };
                cw.inv[j] = inv;
                let x = times(&inv, rhs, false);
                cw.w[3 * j..3 * j + 3].copy_from_slice(&x);
            }
            let wv = &cw.w;
            let rig = momentum(self, &|j| [wv[3 * j], wv[3 * j + 1], wv[3 * j + 2]]);
            for j in s..e {
                let dj = d(j);
                cw.w[3 * j] -= rig[0] - rig[2] * dj[1];
                cw.w[3 * j + 1] -= rig[1] + rig[2] * dj[0];
                cw.w[3 * j + 2] -= rig[2];
            }
        }
        // The free joints' rows on the clusters.
        for c in 0..nc {
            let k = cw.first[c];
            let g = &self.predicted[k];
            let mut rows = [g.ends[0].rows, g.ends[1].rows];
            let du = [qm[3 * k] - cw.centre[c][0], qm[3 * k + 1] - cw.centre[c][1]];
            let single_up = cw.first.get(c + 1).copied().unwrap_or(n) - k == 1;
            let single_low = c == 0 || k - cw.first[c - 1] == 1;
            for r in rows.iter_mut() {
                if !single_up {
                    r.n_up = moved(r.n_up, du);
                    r.t_up = moved(r.t_up, du);
                }
                if !single_low {
                    let dl = [
                        qm[3 * k - 3] - cw.centre[c - 1][0],
                        qm[3 * k - 2] - cw.centre[c - 1][1],
                    ];
                    r.n_low = moved(r.n_low, dl);
                    r.t_low = moved(r.t_low, dl);
                }
            }
            cw.contacts[c] = JointContacts {
                active: self.flags[k],
                bilateral: [false; 2],
                rows,
                mu: self.mu[k],
            };
            cw.statuses[c] = self.statuses[k];
        }
        cw.problem.n = nc;
        cw.problem.set(&cw.contacts[..nc], &cw.vc[..3 * nc]);
        for c in 0..nc {
            let k = cw.first[c];
            let b = cw.problem.free_rates(c);
            let hw = rates(&cw.up[k], &cw.low[k], &cw.w, k);
            let sh = self.shifts[k];
            cw.problem.set_offsets(
                c,
                [
                    b[0] + hw[0] + sh[0],
                    b[1] + hw[1] + sh[1],
                    b[2] + hw[2] + sh[2],
                ],
            );
        }
        let Ok(report) = cw.problem.solve(&mut cw.statuses[..nc]) else {
            self.cluster_counters.other += 1;
            return false;
        };
        cw.report = report;
        cw.problem.apply(&mut cw.vc[..3 * nc]);
        // The column coming to rest: the full path (it removes the velocities left).
        let all_stuck = (0..nc).all(|c| {
            cw.contacts[c].active == [true, true]
                && cw.statuses[c].closed == [true, true]
                && cw.statuses[c].slip == Slip::Stick
        });
        if all_stuck {
            self.cluster_counters.other += 1;
            return false;
        }
        // The drums' new velocities.
        for j in 0..n {
            let c = cw.of[j];
            let u = [cw.vc[3 * c], cw.vc[3 * c + 1], cw.vc[3 * c + 2]];
            let single = cw.first.get(c + 1).copied().unwrap_or(n) - cw.first[c] == 1;
            if single {
                cw.v_new[3 * j..3 * j + 3].copy_from_slice(&u);
                continue;
            }
            let d = [qm[3 * j] - cw.centre[c][0], qm[3 * j + 1] - cw.centre[c][1]];
            cw.v_new[3 * j] = u[0] - u[2] * d[1] + cw.w[3 * j];
            cw.v_new[3 * j + 1] = u[1] + u[2] * d[0] + cw.w[3 * j + 1];
            cw.v_new[3 * j + 2] = u[2] + cw.w[3 * j + 2];
        }
        // The condensed joints' impulses, top down.
        for j in (1..n).rev() {
            if !cw.condensed[j] {
                continue;
            }
            let vf = &cw.vf[3 * j..3 * j + 3];
            let (mj, ij) = (self.drums.mass(j), self.drums.inertia(j));
            let vn = &cw.v_new[3 * j..3 * j + 3];
            let mut r = [
                mj * (vn[0] - vf[0]),
                mj * (vn[1] - vf[1]),
                ij * (vn[2] - vf[2]),
            ];
            if j + 1 < n {
                let p = if cw.condensed[j + 1] {
                    cw.p[j + 1]
                } else {
                    cw.problem.impulses(cw.of[j + 1])
                };
                let low = &cw.low[j + 1];
                for (i, ri) in r.iter_mut().enumerate() {
                    *ri -= low[0][i] * p[0] + low[1][i] * p[1] + low[2][i] * p[2];
                }
            }
            let p = times(&cw.inv[j], r, true);
            let nn = p[0] + p[1];
            let mu = self.mu[j];
            if !(p[0] > MARGIN * nn && p[1] > MARGIN * nn && p[2].abs() < (1.0 - MARGIN) * mu * nn)
            {
                self.cluster_counters.broken += 1;
                return false;
            }
            cw.p[j] = p;
        }
        true
    }

    /// Positions, the accounts, the statuses and the carried ends of the condensed sub-step; the
    /// geometry at its end.
    fn condensed_finish(&mut self, cw: &mut ClusterWork, h: f64, a: f64, t_end: f64) {
        let n = self.drums.len();
        let theta = self.options.theta;
        let mut work = 0.0;
        for j in 0..n {
            for i in 0..3 {
                let vt = (1.0 - theta) * self.v[3 * j + i] + theta * cw.v_new[3 * j + i];
                self.q_next[3 * j + i] = self.q[3 * j + i] + h * vt;
            }
            let dx = self.q_next[3 * j] - self.q[3 * j];
            work += -self.drums.mass(j) * a * dx;
        }
        std::mem::swap(&mut self.v, &mut cw.v_new);
        std::mem::swap(&mut self.q, &mut self.q_next);
        self.t = t_end;
        self.update_geometry();
        self.energy.ground_work += work;
        let report = cw.report;
        self.counters.solves += 1;
        self.counters.iterations += report.iterations as u64;
        self.counters.fallbacks += report.fallback as u64;
        self.counters.inexact += report.inexact as u64;
        for k in 0..n {
            let p = if cw.condensed[k] {
                // Its work is zero: `U⁺ = −s = −U⁻` on its rows (`H_k (T u + w) = H_k w`).
                let p = cw.p[k];
                self.joint_impulses[k] = [p[0] + p[1], p[2]];
                p
            } else {
                let c = cw.of[k];
                self.statuses[k] = cw.statuses[c];
                let u = cw.problem.rates(c);
                let sh = self.shifts[k];
                let p = cw.problem.impulses(c);
                // The full sub-step's accounts (a condensed step never runs with
                // `energy_consistent`, so its term is off).
                let ub = self.rates_before[k];
                self.book_joint(k, p, ub, [u[0] - sh[0], u[1] - sh[1], u[2] - sh[2]], false);
                p
            };
            let st = self.statuses[k];
            self.carried[k] = [
                self.flags[k][0] && st.closed[0] && p[0] > 0.0,
                self.flags[k][1] && st.closed[1] && p[1] > 0.0,
            ];
        }
    }
}

#[cfg(test)]
#[path = "clusters_tests.rs"]
mod tests;
