//! Stops of a column that can no longer move or tip, exact verdicts that end a run early:
//! closed after the ground has gone quiet for good ([`StopReason::AtRest`],
//! `stopping.quiet_after`), and the energy bound of `stopping.stop_when_safe` that proves a
//! single block cannot tip in the rest of the motion ([`StopReason::CannotTip`]), and its
//! extension to columns (`stopping.stop_when_safe_column`, or `stop_when_safe` on the columns
//! whose barrier is certified, [`crate::driver::column_is_certified`]); under thesis Eq. 6, the
//! monolith stop of [`super::monolith`] after `quiet_after`.

use super::monolith::Monolith;
use crate::driver::chain::ChainDynamics;
use crate::driver::problem::Problem;
use crate::driver::state::State;
use crate::driver::StopReason;

/// Share of `√E_tip` the energy bound may reach.
const SAFETY_FACTOR: f64 = 0.9;
/// Accepted steps between two evaluations of the bound.
const SAFETY_EVERY: usize = 16;

/// The energy bound of [`crate::driver::StoppingOptions::stop_when_safe`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct CannotTip {
    /// `m R / √(2 I_P)` (one block) or `√(M/2)` (a column).
    growth: f64,
    /// `0.9 √E_tip`.
    limit: f64,
}

impl CannotTip {
    /// The bound when it applies (static tipping; asked for: one block, or a column with the
    /// exact velocity terms).
    pub fn new<C: ChainDynamics>(problem: &Problem<C>, n: usize, e_tip: f64) -> Option<CannotTip> {
        let stopping = &problem.opts.stopping;
        if stopping.continue_until_fallen {
            return None;
        }
        let growth = if n == 1 {
            stopping
                .stop_when_safe
                .then(|| problem.chain.energy_growth_bound())
        } else {
            // Proven where the barrier is certified, forced (unproven) elsewhere.
            let asked = stopping.stop_when_safe_column
                || (stopping.stop_when_safe && problem.chain.barrier_certified());
            (asked && problem.opts.physics.exact_velocity_terms)
                .then(|| problem.chain.column_growth_bound())
        }?;
        Some(CannotTip {
            growth,
            limit: SAFETY_FACTOR * e_tip.sqrt(),
        })
    }

    /// Whether the bound proves, at `state`, that the block can never tip.
    fn proves<C: ChainDynamics>(&self, problem: &mut Problem<C>, state: &State) -> bool {
        let Some(impulse) = problem.motion.remaining_impulse(state.t()) else {
            return false;
        };
        let energy = if state.is_closed() {
            0.0
        } else {
            let (kin, pot) = problem.chain.energy(&state.open, &state.phi, &state.rates);
            kin + pot
        };
        energy.max(0.0).sqrt() + self.growth * impulse <= self.limit
    }
}

/// The monolith stop of [`super::monolith`] when it applies: `stop_when_safe`, static tipping,
/// `quiet_after` given, and a chain that has it (a column of two or more blocks under Eq. 6).
pub(crate) fn monolith<C: ChainDynamics>(problem: &Problem<C>) -> Option<Monolith> {
    let stopping = &problem.opts.stopping;
    if !stopping.stop_when_safe || stopping.continue_until_fallen || stopping.quiet_after.is_none()
    {
        return None;
    }
    problem.chain.monolith()
}

/// The stop before a step from `state` (after `steps` accepted steps), if the column is at rest
/// for good or cannot tip.
pub(crate) fn stop<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    cannot_tip: Option<&CannotTip>,
    monolith: Option<&mut Monolith>,
    steps: usize,
) -> Option<StopReason> {
    let quiet = problem
        .opts
        .stopping
        .quiet_after
        .is_some_and(|q| state.t() >= q);
    if state.is_closed() && quiet {
        return Some(StopReason::AtRest);
    }
    if steps % SAFETY_EVERY != 0 {
        return None;
    }
    if quiet && monolith.is_some_and(|m| m.proves(problem, state)) {
        return Some(StopReason::CannotTip);
    }
    cannot_tip?
        .proves(problem, state)
        .then_some(StopReason::CannotTip)
}
