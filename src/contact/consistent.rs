//! Opt-in removal of the one-signed energy errors of the located impacts
//! ([`super::moreau::SchemeOptions::energy_consistent`], docs/energy-control.md).
//!
//! The scheme's energy identity is exact; its errors are the normal work at ends that were not
//! approaching (`persistent_contact`) and the projections' work. Measured term by term on the
//! worst runs of the drum suite (twenty 1 × 2 m drums chattering at a located impact or more per
//! step), both come from the located impacts and have one sign (the column gains energy):
//!
//! - **Persistent contacts lost at an impact.** After an impact the ends that carry the column are
//!   those that took an impulse in the impact problem, which has no load: a pivot that carried the
//!   column's weight before the impact but no share of the impact is then, for the rest of the
//!   step, a fresh contact under plain Moreau–Jean (restitution zero), which pumps `P U⁻ / 2` (its
//!   `U⁻` the turning of the contact, `O(h)`) into the column — the first-order error the midpoint
//!   rule at persistent contacts removes on the steps without an impact. Here an end that was
//!   persistent before the impact and is still on its face after it stays persistent; and in a
//!   sub-step every end on its face and not approaching gets the midpoint law, whether it carried
//!   an impulse before or not (an end unloaded for a step, or just put back on its face, is the
//!   same contact: under restitution zero it gains `P U⁻ / 2` alike).
//! - **A landing read after its projection.** The trial sub-step to the linearly predicted
//!   instant overshoots an end that accelerates onto its face; the scheme's projection at the end
//!   of the sub-step pushed that end back out (raising the column: the projection's work is a
//!   gain of about `m g δ`), and the gap then read was the projected one, so the root was not
//!   searched and the impact was applied at the late instant. Here the trial is read before it
//!   is projected.
//! - **Other ends landing in the trial.** Ends other than the predicted one that reach their face
//!   within the trial were left to the projection (the same gain): here the earliest of all the
//!   landings in the trial is located (the missed-landing test of the step, on the trial).
//! - **The cap.** After `moreau::MAX_SPLITS` (8) located impacts a step left the next landings to
//!   the projection; here the cap is [`MAX_SPLITS`]. It matters: on the worst column of the suite
//!   the residual is −5.6e-2, −2.8e-2, −1.1e-2, −9.2e-4, −4.2e-4 and −2.6e-4 with a cap of 8, 16,
//!   32, 64, 128 and none, at 4.2, 6.6, 8.3, 8.8, 10.1 and 11.1 s (docs/energy-control.md).
//!
//! - **Cascades.** An impact's impulse sets an end nanometres from its face approaching, and
//!   that landing, 1–100 µs later, was located by itself (most of the cost of a
//!   chattering column): here the ends within [`IMPACT_GAP`]` · g h²` of their face take part in
//!   the located impact (docs/energy-control.md, "Cost").
//!
//! And one misnomer: a joint slipping at the start of a sub-step and sticking at its end does the
//! work of its Coulomb impulse along the step's mean slip rate (the slip stopping: friction),
//! which the accounts booked as the scheme's error; here it is friction. And a column that closes
//! and sticks everywhere in a sub-step is stopped at the end of the sub-step (its kinetic energy
//! removed at fixed positions, booked as impact), not before its positions advance: the
//! velocities the midpoint law keeps through impacts are not round-off, and removing them first
//! would leave the energy identity short.

use super::moreau::{StepError, Stepper};
use crate::ground::GroundMotion;

/// Most impacts located in one step with `energy_consistent`.
pub const MAX_SPLITS: usize = 256;

/// With `energy_consistent`, the ends within `IMPACT_GAP · g h²` of their face (at `h` = 1 ms,
/// 10 nm; a tenth of what an end at the split speed covers in a step) take part in a located
/// impact as the ends touching it do: the impact's index set with a gap tolerance, as the
/// event-driven schemes take the constraints below a tolerance as active (Acary & Brogliato
/// 2008). Left out, an end that close is set approaching by the impact's impulse and lands
/// 1–100 µs later, located by itself: the cascade of a chattering column (measured in
/// docs/energy-control.md). Taking part, it is a contact like the touching ends: it holds an
/// impulse or not, and if it does the projection (Acary 2013) puts it back onto its face. The
/// tolerance is `O(h²)`, as the scheme's own position error.
pub const IMPACT_GAP: f64 = 1e-3;

impl Stepper {
    /// After an impact and its projection: the ends persistent before it and still on their
    /// faces stay persistent (the impact problem has no load: a pivot need not take a share of
    /// it to keep carrying the column).
    pub(super) fn keep_persistent_through_impact(&mut self) {
        let eps = self.contact_gap;
        for ((carried, before), geo) in self
            .carried
            .iter_mut()
            .zip(&self.carried_before_impact)
            .zip(&self.geometry)
        {
            for c in 0..2 {
                if before[c] && geo.ends[c].gap <= eps {
                    carried[c] = true;
                }
            }
        }
    }

    /// [`Self::locate_and_impact_set`] with `energy_consistent`, from the saved start of the
    /// sub-step: the trial to `tau` read before its projection; the earliest landing in it
    /// located (the predicted end `(k0, c0)`, gap and rate `(g0, u0)` at the start, or another).
    pub(super) fn locate_consistently(
        &mut self,
        tau: f64,
        landing: &[[bool; 2]],
        motion: &dyn GroundMotion,
        (k0, c0): (usize, usize),
        (g0, u0): (f64, f64),
    ) -> Result<(), StepError> {
        let t0 = self.t;
        self.skip_projection = true;
        let trial = self.substep(tau, motion, Some(landing));
        self.skip_projection = false;
        trial?;
        self.t = t0 + tau;
        let a1 = motion.acceleration(self.t);
        let end = &self.geometry[k0].ends[c0];
        let g1 = end.gap;
        let (u1, _) = self.drums.rates(&end.rows, &self.v, k0);
        let tau_star = (g1 < -self.touch_gap).then(|| Self::hermite_root(g0, u0, g1, u1, tau));
        // An end that reached its face before the predicted one (or instead of it).
        if let Some(first) = self.missed_landing(tau) {
            if tau_star.map_or(true, |ts| first < ts * (1.0 - 1e-9)) {
                self.restore();
                let mut set = std::mem::take(&mut self.located_first);
                set.resize(self.drums.len(), [false; 2]);
                self.missed_set(first, tau, &mut set);
                let result = self.integrate_and_impact(first, &set, motion);
                self.located_first = set;
                return result;
            }
        }
        match tau_star {
            Some(ts) if (ts - tau).abs() > 1e-12 * tau => {
                self.restore();
                self.substep(ts, motion, Some(landing))?;
                self.t = t0 + ts;
            }
            _ => {
                if self.options.project {
                    self.project(a1, true)?;
                }
                if g1 > self.touch_gap {
                    // Not there yet (it slowed down): keep the sub-step; the next round looks
                    // again.
                    return Ok(());
                }
            }
        }
        self.impact(landing, motion.acceleration(self.t))
    }
}
