//! Impacts inside a step (see [`super::moreau`]): landings predicted linearly or found after the
//! sub-step (an end that accelerated onto its face), located by a trial sub-step and the root of
//! the cubic Hermite interpolant of the gap, and the impact law applied at that instant — the
//! kinetic-metric projection with friction, in stages over bumps for the thesis's consecutive
//! impacts.

use super::drums::JointGeometry;
use super::friction::{JointContacts, JointStatus};
use super::moreau::{EnergyAccounts, LocatedImpact, StepCounters, StepError, Stepper};
use crate::ground::GroundMotion;

/// The state a sub-step starts from, for a landing located after it (`save`, `restore`).
#[derive(Clone, Debug)]
pub(super) struct Saved {
    pub(super) t: f64,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) statuses: Vec<JointStatus>,
    pub(super) energy: EnergyAccounts,
    pub(super) counters: StepCounters,
    pub(super) joint_impulses: Vec<[f64; 2]>,
    pub(super) carried: Vec<[bool; 2]>,
    pub(super) geometry: Vec<JointGeometry>,
}

impl Stepper {
    /// Gaps and normal rates of every end at the start of a sub-step (for [`Self::missed_landing`]).
    pub(super) fn record_start_rates(&mut self) {
        for k in 0..self.drums.len() {
            for c in 0..2 {
                let e = &self.geometry[k].ends[c];
                let (un, _) = self.drums.rates(&e.rows, &self.v, k);
                self.start_rates[k][c] = [e.gap, un];
            }
        }
        self.rates_fresh = true;
    }

    /// Root in `(0, h]` of the cubic Hermite interpolant of a gap going from `g0` (rate `u0`) to
    /// `g1 ≤ 0` (rate `u1`) over `h`.
    pub(super) fn hermite_root(g0: f64, u0: f64, g1: f64, u1: f64, h: f64) -> f64 {
        let p = |s: f64| {
            let x = s / h;
            let (x2, x3) = (x * x, x * x * x);
            (2.0 * x3 - 3.0 * x2 + 1.0) * g0
                + (x3 - 2.0 * x2 + x) * h * u0
                + (-2.0 * x3 + 3.0 * x2) * g1
                + (x3 - x2) * h * u1
        };
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if p(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// Ends open at the start of the last sub-step of length `h` that ended inside their face
    /// (deeper than a tenth of what the split speed covers in the step), arriving faster than the
    /// split speed: their landing instants (Hermite) into `self.missed`, the first one returned.
    pub(super) fn missed_landing(&mut self, h: f64) -> Option<f64> {
        let deep = if self.slow_landings {
            self.projection_gap
        } else {
            0.1 * self.v_split * h
        };
        let mut best: Option<f64> = None;
        for k in 0..self.drums.len() {
            for c in 0..2 {
                let tau = self.missed_time(k, c, h, deep);
                self.missed[k][c] = tau;
                if let Some(tau) = tau {
                    if best.map_or(true, |b| tau < b) {
                        best = Some(tau);
                    }
                }
            }
        }
        best
    }

    pub(super) fn missed_time(&self, k: usize, c: usize, h: f64, deep: f64) -> Option<f64> {
        let [g0, u0] = self.start_rates[k][c];
        // Only ends that the sub-step left free (its index set is still in `flags`).
        if self.flags[k][c] {
            return None;
        }
        let e = &self.geometry[k].ends[c];
        if e.gap >= -deep {
            return None;
        }
        let (u1, _) = self.drums.rates(&e.rows, &self.v, k);
        if u1 >= -self.v_split {
            return None;
        }
        Some(Self::hermite_root(g0, u0, e.gap, u1, h))
    }

    /// The missed landings within `1e-9` of the step of the first (recorded by
    /// [`Self::missed_landing`] before the restore).
    pub(super) fn missed_set(&self, tau: f64, h: f64, out: &mut [[bool; 2]]) {
        for k in 0..self.drums.len() {
            for c in 0..2 {
                out[k][c] = self.missed[k][c].is_some_and(|t| t <= tau + 1e-9 * h);
            }
        }
    }

    /// Linear landing time of end `c` of joint `k` if it approaches its face faster than
    /// `v_split`: `gap / |U|`, or zero for an end already touching (its impact is due now).
    pub(super) fn landing_time(&self, k: usize, c: usize, v_split: f64) -> Option<f64> {
        let e = &self.geometry[k].ends[c];
        let un = if self.rates_fresh {
            self.start_rates[k][c][1]
        } else {
            self.drums.rates(&e.rows, &self.v, k).0
        };
        if e.gap <= self.touch_gap {
            (un < -self.v_touch).then_some(0.0)
        } else {
            (un < -v_split).then(|| e.gap / -un)
        }
    }

    /// The first fast landing within `remaining`: `(τ, (joint, end))` by the linear prediction.
    pub(super) fn next_landing(&self, remaining: f64) -> Option<(f64, (usize, usize))> {
        let mut best: Option<(f64, (usize, usize))> = None;
        for k in 0..self.drums.len() {
            for c in 0..2 {
                if let Some(tau) = self.landing_time(k, c, self.v_split) {
                    if tau < remaining && best.map_or(true, |(b, _)| tau < b) {
                        best = Some((tau, (k, c)));
                    }
                }
            }
        }
        best
    }

    /// Ends landing at (nearly) the time `tau`: all with linear landing time within `1e-9` of
    /// the step of the first.
    pub(super) fn landing_set(&self, tau: f64, remaining: f64, out: &mut [[bool; 2]]) {
        for k in 0..self.drums.len() {
            out[k] = [false; 2];
            for c in 0..2 {
                if let Some(t) = self.landing_time(k, c, self.v_split) {
                    out[k][c] = t <= tau + 1e-9 * remaining;
                }
            }
        }
    }

    pub(super) fn save(&mut self) {
        let saved = self.saved.get_or_insert_with(|| {
            Box::new(Saved {
                t: 0.0,
                q: vec![0.0; self.q.len()],
                v: vec![0.0; self.v.len()],
                statuses: vec![JointStatus::default(); self.statuses.len()],
                energy: EnergyAccounts::default(),
                counters: StepCounters::default(),
                joint_impulses: vec![[0.0; 2]; self.joint_impulses.len()],
                carried: vec![[false; 2]; self.carried.len()],
                geometry: self.geometry.clone(),
            })
        });
        saved.t = self.t;
        saved.q.copy_from_slice(&self.q);
        saved.v.copy_from_slice(&self.v);
        saved.statuses.copy_from_slice(&self.statuses);
        saved.energy = self.energy;
        saved.counters = self.counters;
        saved.joint_impulses.copy_from_slice(&self.joint_impulses);
        saved.carried.copy_from_slice(&self.carried);
        saved.geometry.copy_from_slice(&self.geometry);
    }

    pub(super) fn restore(&mut self) {
        self.rates_fresh = false;
        let s = self.saved.as_ref().expect("saved state");
        self.t = s.t;
        self.q.copy_from_slice(&s.q);
        self.v.copy_from_slice(&s.v);
        self.statuses.copy_from_slice(&s.statuses);
        self.energy = s.energy;
        self.counters = s.counters;
        self.joint_impulses.copy_from_slice(&s.joint_impulses);
        self.carried.copy_from_slice(&s.carried);
        // The geometry at the saved positions, saved with them (the state is saved between
        // sub-steps, where the geometry is that of `q`): the numbers `update_geometry` would
        // compute again (checked bit for bit on every restore of shard 5/16 of the drum suite
        // with `--consistent`).
        self.geometry.copy_from_slice(&s.geometry);
    }

    /// Integrates up to the first landing (trial, Hermite root, redo) and applies the impact.
    pub(super) fn locate_and_impact(
        &mut self,
        tau: f64,
        remaining: f64,
        motion: &dyn GroundMotion,
    ) -> Result<(), StepError> {
        let mut landing = std::mem::take(&mut self.landing);
        self.landing_set(tau, remaining, &mut landing);
        let result = self.locate_and_impact_set(tau, &landing, motion);
        self.landing = landing;
        result
    }

    pub(super) fn locate_and_impact_set(
        &mut self,
        tau: f64,
        landing: &[[bool; 2]],
        motion: &dyn GroundMotion,
    ) -> Result<(), StepError> {
        let n = self.drums.len();
        // The end that decides the instant: the first one.
        let (k0, c0) = (0..n)
            .flat_map(|k| (0..2).map(move |c| (k, c)))
            .find(|&(k, c)| landing[k][c])
            .expect("a landing end");
        if tau <= 0.0 {
            return self.impact(landing, motion.acceleration(self.t));
        }
        let g0 = self.geometry[k0].ends[c0].gap;
        let (u0, _) = self
            .drums
            .rates(&self.geometry[k0].ends[c0].rows, &self.v, k0);
        self.save();
        let t0 = self.t;
        if self.options.energy_consistent {
            return self.locate_consistently(tau, landing, motion, (k0, c0), (g0, u0));
        }
        self.substep(tau, motion, Some(landing))?;
        let g1 = self.geometry[k0].ends[c0].gap;
        let (u1, _) = self
            .drums
            .rates(&self.geometry[k0].ends[c0].rows, &self.v, k0);
        self.t = t0 + tau;
        if g1 > self.contact_gap {
            // Not there yet (it slowed down): keep the sub-step; the next round looks again.
            return Ok(());
        }
        let tau_star = Self::hermite_root(g0, u0, g1, u1, tau);
        // Redo the sub-step to the root unless the trial already ended on the face (to the
        // contact tolerance).
        if g1 < -self.contact_gap && (tau_star - tau).abs() > 1e-12 * tau {
            self.restore();
            self.substep(tau_star, motion, Some(landing))?;
            self.t = t0 + tau_star;
        }
        self.impact(landing, motion.acceleration(self.t))
    }

    /// From the start of a sub-step: integrate to `tau` without the landing ends, then the impact.
    pub(super) fn integrate_and_impact(
        &mut self,
        tau: f64,
        landing: &[[bool; 2]],
        motion: &dyn GroundMotion,
    ) -> Result<(), StepError> {
        if tau > 0.0 {
            let t0 = self.t;
            self.substep(tau, motion, Some(landing))?;
            self.t = t0 + tau;
        }
        self.impact(landing, motion.acceleration(self.t))
    }

    /// The impact law at the current instant: the ends in contact and the `landing` ones (per
    /// joint, right and left), with the bump stages of the thesis's consecutive impacts for
    /// rocking joints; `a_g` is the ground acceleration now (for the work of the loads on the
    /// projection that follows). Used by the steps; public for the models' comparisons.
    pub fn impact(&mut self, landing: &[[bool; 2]], a_g: f64) -> Result<(), StepError> {
        self.rates_fresh = false;
        let n = self.drums.len();
        let kinetic_before = self.kinetic_energy();
        let stages = self.options.n_impacts.max(1);
        self.shifts.iter_mut().for_each(|s| *s = [0.0; 3]);
        // Warm start: the landing ends close.
        for k in 0..n {
            for c in 0..2 {
                if landing[k][c] {
                    self.statuses[k].closed[c] = true;
                }
            }
        }
        let eps = self.contact_gap;
        // The contact tolerance, or with `energy_consistent` the impact's own (see
        // `consistent::IMPACT_GAP`); the model comparisons that call this outside a step have
        // the contact tolerance.
        let impact_gap = if self.options.energy_consistent {
            self.impact_gap.max(self.touch_gap)
        } else {
            eps
        };
        for stage in 1..=stages {
            for k in 0..n {
                let geo = self.geometry[k];
                let mut jc = JointContacts {
                    active: [false; 2],
                    bilateral: [false; 2],
                    rows: [geo.ends[0].rows, geo.ends[1].rows],
                    mu: self.mu[k],
                };
                for c in 0..2 {
                    jc.active[c] = landing[k][c] || geo.ends[c].gap <= impact_gap;
                }
                for c in 0..2 {
                    let p = 1 - c;
                    let rocking = landing[k][c] && !landing[k][p] && geo.ends[p].gap <= eps;
                    if rocking && stage < stages {
                        // A bump at the fraction stage/stages from the pivot towards the corner.
                        let lam = stage as f64 / stages as f64;
                        let (a, b) = (geo.ends[p].point, geo.ends[c].point);
                        let r = [a[0] + lam * (b[0] - a[0]), a[1] + lam * (b[1] - a[1])];
                        jc.rows[c] = self.drums.rows_at(&self.q, k, r, geo.ends[c].normal);
                    }
                }
                self.contacts[k] = jc;
            }
            self.v_free.copy_from_slice(&self.v);
            if stage == 1 {
                self.problem.set(&self.contacts, &self.v_free);
            } else {
                // A later stage differs from the one before only in the bumps' rows: the
                // blocks of the unchanged rows are kept.
                self.problem.set_again(&self.contacts, &self.v_free);
            }
            let report = self.problem.solve(&mut self.statuses)?;
            self.counters.impact_iterations += report.iterations as u64;
            self.counters.inexact += report.inexact as u64;
            self.counters.solves += 1;
            self.counters.iterations += report.iterations as u64;
            self.counters.fallbacks += report.fallback as u64;
            let mut v = std::mem::take(&mut self.v_free);
            self.problem.apply(&mut v);
            let before = std::mem::replace(&mut self.v, v);
            self.account_contact_work(Some(&before), true);
            self.v_free = before;
        }
        // Landed ends that hold an impulse are put back onto their faces.
        if self.options.energy_consistent {
            self.carried_before_impact.copy_from_slice(&self.carried);
        }
        for k in 0..n {
            let p = self.problem.impulses(k);
            self.carried[k] = [p[0] > 0.0, p[1] > 0.0];
        }
        self.project(a_g, true)?;
        if self.options.energy_consistent {
            self.keep_persistent_through_impact();
        }
        self.counters.located_impacts += 1;
        for k in 0..n {
            for c in 0..2 {
                if landing[k][c] {
                    self.impacts.push(LocatedImpact {
                        t: self.t,
                        joint: k,
                        end: c,
                        kinetic_before,
                        kinetic_after: self.kinetic_energy(),
                    });
                }
            }
        }
        Ok(())
    }
}
