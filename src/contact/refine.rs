//! Opt-in error control of the Moreau–Jean drum scheme ([`super::moreau`]), on
//! [`super::moreau::SchemeOptions::energy_tolerance`].
//!
//! The scheme's energy identity is exact (`closure()` at round-off); its error is two of its own
//! terms, the normal work at ends that were not approaching (an end caught while leaving its face
//! within a step) and the projections' work ([`super::accounts::EnergyAccounts`]). Both are
//! known at the end of every step. With a tolerance `tol`, a step of length `h` whose error —
//! the change of `persistent_contact + projection` over the step, in absolute value — exceeds
//! `tol × E` is redone from its start as two steps of `h / 2`, each checked the same way, down to
//! `dt / 2^MAX_HALVINGS`. `E` is the run's energy scale at the start of the step
//! ([`super::simulation::DrumEnergy::scale`], the largest energy involved so far: what the
//! residual is measured against), floored at `FLOOR` of the column's weight times the height of
//! its centre of mass (micro-rocking runs: no refinement below that). A step at the shortest
//! length is kept whatever its error (counted in `StepCounters::refine_floor`).
//!
//! With `energy_consistent`, a retry (every sub-step below the grid step) also locates every
//! landing of an open end whatever its speed, and counts an end as touching only within the
//! projection's tolerance instead of the contact tolerance (`Stepper::locate_slow_landings`,
//! below). Without it, a landing slower than the split speed (`0.01 g h`) that came within the contact
//! tolerance (`1e-9` of the drum size) of its face was taken into the index set there and stopped
//! by the velocity law at that gap, then pulled onto the face by the projection: the weight times
//! a gap set by the tolerance, not by the step, so halving did not reduce it (nanoradian rocking:
//! 2e-5 J a landing against runs of 1e-4 J; docs/nanoradian-rocking.md).
//! Moreau–Jean's index set is the predicted one (Acary & Brogliato 2008 §10.1) and the
//! projection (Acary 2013) is there for the `O(h²)` drift of persistent contacts; a landing is
//! an event, located as the fast ones are.
//!
//! The run sees one step of the grid: the impacts located in the accepted sub-steps, in order,
//! are the step's `impacts`; the counters are those of the accepted sub-steps (a rejected attempt
//! is rolled back with the state) plus `refined`, the steps redone; the joints' modes, and with
//! them the events other than impacts, are read at the end of the grid step as without the
//! control.

use super::landing::Saved;
use super::moreau::{LocatedImpact, StepError, Stepper};
use super::simulation::DrumEnergy;
use crate::ground::GroundMotion;

/// Halvings of a grid step at most: the shortest step is `dt / 64`.
pub const MAX_HALVINGS: usize = 6;

/// The energy scale's floor, as a fraction of the column's weight times the height of its centre
/// of mass.
pub const FLOOR: f64 = 1e-6;

/// The error control's snapshots (one per level of halving) and the impacts of the accepted
/// sub-steps.
#[derive(Clone, Debug)]
pub(crate) struct Refiner {
    tolerance: f64,
    floor: f64,
    slots: Vec<Option<Box<Saved>>>,
    impacts: Vec<LocatedImpact>,
}

impl Refiner {
    /// The control for `st` with tolerance `tolerance`.
    pub fn new(st: &Stepper, tolerance: f64) -> Refiner {
        let d = st.drums();
        let g = st.options().gravity;
        let rest = d.rest_positions();
        let weight_height: f64 = (0..d.len()).map(|j| d.mass(j) * g * rest[3 * j + 1]).sum();
        Refiner {
            tolerance,
            floor: FLOOR * weight_height.abs(),
            slots: vec![None; MAX_HALVINGS + 1],
            impacts: Vec::new(),
        }
    }

    /// One grid step of length `h` under the control; `potential0`, `kinetic0`: the run's
    /// energies at its start (for the scale).
    pub fn step(
        &mut self,
        st: &mut Stepper,
        h: f64,
        motion: &dyn GroundMotion,
        potential0: f64,
        kinetic0: f64,
    ) -> Result<(), StepError> {
        let scale = DrumEnergy {
            potential_change: st.potential_energy() - potential0,
            kinetic_change: st.kinetic_energy() - kinetic0,
            accounts: st.energy,
        }
        .scale()
        .max(self.floor);
        self.impacts.clear();
        let result = self.advance(st, h, motion, self.tolerance * scale, 0);
        std::mem::swap(&mut st.impacts, &mut self.impacts);
        result
    }

    /// Advances `st` by `h` within the error `allowed` per step, halving at most
    /// `MAX_HALVINGS − depth` more times.
    fn advance(
        &mut self,
        st: &mut Stepper,
        h: f64,
        motion: &dyn GroundMotion,
        allowed: f64,
        depth: usize,
    ) -> Result<(), StepError> {
        let t_end = st.t + h;
        let error = |st: &Stepper| st.energy.persistent_contact + st.energy.projection;
        let before = error(st);
        let last = depth == MAX_HALVINGS;
        if !last {
            self.save(st, depth);
        }
        // A retry locates every landing (see `Stepper::locate_slow_landings`).
        st.slow_landings = depth > 0 && st.options().energy_consistent;
        let result = st.step(h, motion);
        st.slow_landings = false;
        let step_error = (error(st) - before).abs();
        if result.is_err() || step_error <= allowed || last {
            if result.is_ok() && step_error > allowed {
                st.counters.refine_floor += 1;
            }
            self.impacts.extend_from_slice(&st.impacts);
            return result;
        }
        self.restore(st, depth);
        st.counters.refined += 1;
        self.advance(st, 0.5 * h, motion, allowed, depth + 1)?;
        let rest = t_end - st.t;
        self.advance(st, rest, motion, allowed, depth + 1)?;
        st.t = t_end;
        Ok(())
    }

    /// The stepper's own save and restore, on this level's slot (the stepper uses its slot
    /// inside a step).
    fn save(&mut self, st: &mut Stepper, depth: usize) {
        std::mem::swap(&mut st.saved, &mut self.slots[depth]);
        st.save();
        std::mem::swap(&mut st.saved, &mut self.slots[depth]);
    }

    fn restore(&mut self, st: &mut Stepper, depth: usize) {
        std::mem::swap(&mut st.saved, &mut self.slots[depth]);
        st.restore();
        std::mem::swap(&mut st.saved, &mut self.slots[depth]);
    }
}

impl Stepper {
    /// In a retry of the control (`slow_landings`), from the step's `h`: every landing of an open
    /// end is located, whatever its speed, and an end counts as touching only within the
    /// projection's tolerance. Otherwise the contact tolerance, as without the control.
    pub(super) fn locate_slow_landings(&mut self, h: f64) {
        if !self.slow_landings {
            self.touch_gap = self.contact_gap;
            return;
        }
        self.v_split = 0.0;
        self.touch_gap = self.projection_gap;
        let g = self.options.gravity;
        self.impact_gap = self
            .projection_gap
            .max(super::consistent::IMPACT_GAP * g * h * h);
    }
}
