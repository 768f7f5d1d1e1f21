//! The accounts of the Moreau–Jean scheme ([`super::moreau`]): the energy of every step split into
//! ground work, impact dissipation, friction dissipation and the scheme's own errors (the work at
//! persistent contacts and of the projections), and the counters of the work done.

use super::friction::Slip;
use super::moreau::Stepper;

/// Energy accounts of the scheme (J), accumulated over the steps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnergyAccounts {
    /// Work of the inertial load of the ground motion along the path, `∫ −Σ m a_g dx`.
    pub ground_work: f64,
    /// Energy dissipated by the normal impulses at approaching ends (impacts).
    pub impact: f64,
    /// Energy dissipated by friction (tangential impulses).
    pub friction: f64,
    /// Work of the normal impulses at ends that were not approaching, with the sign of a
    /// dissipation: the scheme's error at persistent contacts (`O(h)` in total).
    pub persistent_contact: f64,
    /// Work of the loads on the projections' displacements (`Σ f·Δq`).
    pub projection: f64,
}

/// Counters of the work done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepCounters {
    /// Sub-steps integrated (accepted).
    pub substeps: u64,
    /// Steps taken by the rest shortcut (column closed, sticking and at rest).
    pub rest_steps: u64,
    /// Contact problems solved.
    pub solves: u64,
    /// Active-set iterations in total.
    pub iterations: u64,
    /// Problems that went to Lemke's algorithm.
    pub fallbacks: u64,
    /// Projections of the positions.
    pub projections: u64,
    /// Impacts located inside steps.
    pub located_impacts: u64,
    /// Active-set iterations of the impact problems.
    pub impact_iterations: u64,
    /// Problems whose last fallback (nonsmooth Gauss–Seidel) stopped at its cap of sweeps.
    pub inexact: u64,
    /// Steps (or sub-steps) of the error control ([`super::refine`]) redone as two halves.
    pub refined: u64,
    /// Steps of the error control kept at its shortest length with their energy error still
    /// above the tolerance.
    pub refine_floor: u64,
}

impl Stepper {
    /// Adds the contact work of the solved problem to the accounts: `−P·U_mid` per row, with
    /// `U_before` the rows' rates of the velocities before. In an impact (`impact`) all of it is
    /// impact dissipation; in a step, the normal work at approaching ends and the tangential work
    /// of a sticking joint with an approaching end is, the tangential work of a slipping joint is
    /// friction, the rest is the scheme's work at persistent contacts. `v_before`: the velocities
    /// before; `None` in a sub-step, whose rates of them are already in `rates_before`.
    pub(super) fn account_contact_work(&mut self, v_before: Option<&[f64]>, impact: bool) {
        let n = self.drums.len();
        for k in 0..n {
            let p = self.problem.impulses(k);
            let (ub, ua) = if p == [0.0; 3] {
                ([0.0; 3], [0.0; 3])
            } else {
                let ua = self.problem.rates(k);
                let sh = self.shifts[k];
                let ua = [ua[0] - sh[0], ua[1] - sh[1], ua[2] - sh[2]];
                let ub = match v_before {
                    Some(v) => self.problem.rows_rates(k, v),
                    None => self.rates_before[k],
                };
                (ub, ua)
            };
            self.book_joint(k, p, ub, ua, impact);
        }
    }

    /// The contact work of joint `k`: its impulses `p` (two normal, one tangential), its rates
    /// `ub` before and `ua` after (the persistent contacts' shifts removed), booked as
    /// [`Stepper::account_contact_work`] says; `joint_impulses` keeps `p`. The full and the
    /// condensed sub-steps (`clusters.rs`) book through it.
    pub(super) fn book_joint(
        &mut self,
        k: usize,
        p: [f64; 3],
        ub: [f64; 3],
        ua: [f64; 3],
        impact: bool,
    ) {
        self.joint_impulses[k] = [p[0] + p[1], p[2]];
        if p == [0.0; 3] {
            return;
        }
        let mut approaching = false;
        for c in 0..2 {
            if p[c] != 0.0 {
                let w = -p[c] * 0.5 * (ub[c] + ua[c]);
                if impact || ub[c] < 0.0 {
                    approaching = true;
                    self.energy.impact += w;
                } else {
                    self.energy.persistent_contact += w;
                }
            }
        }
        if p[2] != 0.0 {
            let w = -p[2] * 0.5 * (ub[2] + ua[2]);
            if self.statuses[k].slip != Slip::Stick
                || (self.options.energy_consistent && !impact && self.slipping_before[k])
            {
                // Slipping, or (energy_consistent) a slip that stopped within the step: the
                // Coulomb impulse's work along the step's mean slip rate is friction.
                self.energy.friction += w;
            } else if approaching {
                self.energy.impact += w;
            } else {
                self.energy.persistent_contact += w;
            }
        }
    }
}
